// Stanford PLY 1.0 (Turk, "The PLY Polygon File Format", 1994): a text header declaring elements
// and their scalar / list properties, then the body in ascii, binary_little_endian or
// binary_big_endian. We read element `vertex` (scalar x, y, z of any numeric type, other properties
// in any order) and element `face` (list `vertex_indices` or `vertex_index` with integer count and
// index types); every other element and property is parsed and skipped. Element counts are checked
// against the body size before anything is reserved.
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "formats.h"
#include "text_reader.h"

namespace interfere::io_detail {
namespace {

enum class PlyType : std::uint8_t { invalid, i8, u8, i16, u16, i32, u32, f32, f64 };

PlyType ply_type(std::string_view s) {
  if (s == "char" || s == "int8") return PlyType::i8;
  if (s == "uchar" || s == "uint8") return PlyType::u8;
  if (s == "short" || s == "int16") return PlyType::i16;
  if (s == "ushort" || s == "uint16") return PlyType::u16;
  if (s == "int" || s == "int32") return PlyType::i32;
  if (s == "uint" || s == "uint32") return PlyType::u32;
  if (s == "float" || s == "float32") return PlyType::f32;
  if (s == "double" || s == "float64") return PlyType::f64;
  return PlyType::invalid;
}

const char* type_name(PlyType t) {
  switch (t) {
    case PlyType::i8:
      return "char";
    case PlyType::u8:
      return "uchar";
    case PlyType::i16:
      return "short";
    case PlyType::u16:
      return "ushort";
    case PlyType::i32:
      return "int";
    case PlyType::u32:
      return "uint";
    case PlyType::f32:
      return "float";
    case PlyType::f64:
      return "double";
    default:
      return "invalid";
  }
}

std::size_t size_of(PlyType t) {
  switch (t) {
    case PlyType::i8:
    case PlyType::u8:
      return 1;
    case PlyType::i16:
    case PlyType::u16:
      return 2;
    case PlyType::i32:
    case PlyType::u32:
    case PlyType::f32:
      return 4;
    case PlyType::f64:
      return 8;
    default:
      return 0;
  }
}

bool is_integer(PlyType t) {
  return t != PlyType::f32 && t != PlyType::f64 && t != PlyType::invalid;
}

struct Property {
  std::string name;
  bool list = false;
  PlyType count_type = PlyType::invalid;
  PlyType type = PlyType::invalid;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::int64_t line = 0;
  std::vector<Property> props;
};

template <class T>
T load(const char* p, bool swap) {
  T v;
  std::memcpy(&v, p, sizeof v);
  if constexpr (sizeof(T) > 1) {
    if (swap) {
      using U =
          std::conditional_t<sizeof(T) == 2, std::uint16_t,
                             std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>;
      v = std::bit_cast<T>(bswap(std::bit_cast<U>(v)));
    }
  }
  return v;
}

// A scalar of PLY type t at p as R (double for coordinates, int64 for counts and indices: callers
// check that index types are integers, so the float cases are never taken for R = int64).
template <class R>
R load_as(const char* p, PlyType t, bool swap) {
  switch (t) {
    case PlyType::i8:
      return static_cast<R>(load<std::int8_t>(p, swap));
    case PlyType::u8:
      return static_cast<R>(load<std::uint8_t>(p, swap));
    case PlyType::i16:
      return static_cast<R>(load<std::int16_t>(p, swap));
    case PlyType::u16:
      return static_cast<R>(load<std::uint16_t>(p, swap));
    case PlyType::i32:
      return static_cast<R>(load<std::int32_t>(p, swap));
    case PlyType::u32:
      return static_cast<R>(load<std::uint32_t>(p, swap));
    case PlyType::f32:
      if constexpr (std::is_floating_point_v<R>) return static_cast<R>(load<float>(p, swap));
      break;
    case PlyType::f64:
      if constexpr (std::is_floating_point_v<R>) return static_cast<R>(load<double>(p, swap));
      break;
    default:
      break;
  }
  return 0;
}

bool int_in_range(std::int64_t v, PlyType t) {
  switch (t) {
    case PlyType::i8:
      return v >= -128 && v <= 127;
    case PlyType::u8:
      return v >= 0 && v <= 255;
    case PlyType::i16:
      return v >= -32768 && v <= 32767;
    case PlyType::u16:
      return v >= 0 && v <= 65535;
    case PlyType::i32:
      return v >= std::numeric_limits<std::int32_t>::min() &&
             v <= std::numeric_limits<std::int32_t>::max();
    case PlyType::u32:
      return v >= 0 && v <= std::numeric_limits<std::uint32_t>::max();
    default:
      return false;
  }
}

/// One ASCII value of type t; sets dv (always) and iv (integer types).
bool ascii_value(std::string_view tok, PlyType t, double& dv, std::int64_t& iv, std::string& why) {
  if (is_integer(t)) {
    if (!parse_int(tok, iv)) {
      why = "malformed " + std::string(type_name(t)) + " value " + quoted(tok);
      return false;
    }
    if (!int_in_range(iv, t)) {
      why = "value " + quoted(tok) + " out of range for type " + type_name(t);
      return false;
    }
    dv = static_cast<double>(iv);
    return true;
  }
  if (!parse_double(tok, dv)) {
    why = "malformed " + std::string(type_name(t)) + " value " + quoted(tok);
    return false;
  }
  // A value declared float is a float: "0.1" means 0.1f, as in a binary file (and overflows to
  // Inf).
  if (t == PlyType::f32) dv = static_cast<double>(static_cast<float>(dv));
  return true;
}

enum class Role : std::uint8_t { skip, x, y, z, indices };

}  // namespace

Expected<TriMesh> read_ply(const std::string& path, std::string_view d, MeshReadInfo& info) {
  TextReader r(d);
  std::string_view line;
  if (!r.next_line(line) || line != "ply") {
    return text_error(path, 1, "not a PLY file: the first line must be 'ply'");
  }
  PlyEncoding enc = PlyEncoding::ascii;
  bool have_format = false, have_end = false;
  std::vector<Element> elements;
  while (r.next_line(line)) {
    LineTokens tk(line);
    const std::string_view kw = tk.next();
    if (kw.empty() || kw == "comment" || kw == "obj_info") continue;
    if (kw == "format") {
      const std::string_view f = tk.next();
      if (f == "ascii") {
        enc = PlyEncoding::ascii;
      } else if (f == "binary_little_endian") {
        enc = PlyEncoding::binary_le;
      } else if (f == "binary_big_endian") {
        enc = PlyEncoding::binary_be;
      } else {
        return text_error(path, r.line(), "unknown PLY format " + quoted(f));
      }
      const std::string_view version = tk.next();
      if (version != "1.0" && version != "1") {
        return text_error(path, r.line(),
                          "unsupported PLY version " + quoted(version) + " (expected 1.0)");
      }
      have_format = true;
    } else if (kw == "element") {
      Element e;
      e.name = std::string(tk.next());
      const std::string_view c = tk.next();
      std::int64_t n;
      if (e.name.empty() || !parse_int(c, n) || n < 0) {
        return text_error(path, r.line(),
                          "malformed element declaration (expected 'element <name> <count>')");
      }
      e.count = static_cast<std::uint64_t>(n);
      e.line = r.line();
      elements.push_back(std::move(e));
    } else if (kw == "property") {
      if (elements.empty())
        return text_error(path, r.line(), "property declared before any element");
      Property p;
      std::string_view t = tk.next();
      if (t == "list") {
        p.list = true;
        const std::string_view ct = tk.next(), it = tk.next();
        p.count_type = ply_type(ct);
        p.type = ply_type(it);
        if (p.count_type == PlyType::invalid)
          return text_error(path, r.line(), "unknown PLY property type " + quoted(ct));
        if (p.type == PlyType::invalid)
          return text_error(path, r.line(), "unknown PLY property type " + quoted(it));
        if (!is_integer(p.count_type)) {
          return text_error(path, r.line(),
                            "list count type must be an integer type, found " + quoted(ct));
        }
      } else {
        p.type = ply_type(t);
        if (p.type == PlyType::invalid)
          return text_error(path, r.line(), "unknown PLY property type " + quoted(t));
      }
      p.name = std::string(tk.next());
      if (p.name.empty()) return text_error(path, r.line(), "property has no name");
      elements.back().props.push_back(std::move(p));
    } else if (kw == "end_header") {
      have_end = true;
      break;
    } else {
      return text_error(path, r.line(), "unknown PLY header keyword " + quoted(kw));
    }
  }
  if (!have_end)
    return text_error(path, r.end_line(), "PLY header has no 'end_header' line (file truncated?)");
  if (!have_format) return text_error(path, r.line(), "PLY header has no 'format' line");
  info.format = enc == PlyEncoding::ascii       ? MeshFormat::ply_ascii
                : enc == PlyEncoding::binary_le ? MeshFormat::ply_binary_le
                                                : MeshFormat::ply_binary_be;
  const std::int64_t header_end_line = r.line();

  // Roles of the properties we read.
  const Element* vertex = nullptr;
  const Element* face = nullptr;
  std::vector<std::vector<Role>> roles(elements.size());
  for (std::size_t ei = 0; ei < elements.size(); ++ei) {
    const Element& e = elements[ei];
    roles[ei].assign(e.props.size(), Role::skip);
    if (e.name == "vertex" && !vertex) {
      vertex = &e;
      int found[3] = {0, 0, 0};
      for (std::size_t k = 0; k < e.props.size(); ++k) {
        const Property& p = e.props[k];
        const int axis = p.name == "x" ? 0 : p.name == "y" ? 1 : p.name == "z" ? 2 : -1;
        if (axis < 0 || found[axis]) continue;
        if (p.list)
          return text_error(path, e.line,
                            "vertex property '" + p.name + "' is a list; a scalar is needed");
        found[axis] = 1;
        roles[ei][k] = static_cast<Role>(static_cast<int>(Role::x) + axis);
      }
      for (int a = 0; a < 3; ++a) {
        if (!found[a])
          return text_error(path, e.line,
                            std::string("element 'vertex' has no property '") + "xyz"[a] + "'");
      }
    } else if (e.name == "face" && !face) {
      face = &e;
      for (std::size_t k = 0; k < e.props.size(); ++k) {
        const Property& p = e.props[k];
        if (p.name != "vertex_indices" && p.name != "vertex_index") continue;
        if (!p.list)
          return text_error(path, e.line, "face property '" + p.name + "' must be a list");
        if (!is_integer(p.type)) {
          return text_error(path, e.line,
                            "face index type must be an integer type, found '" +
                                std::string(type_name(p.type)) + "'");
        }
        roles[ei][k] = Role::indices;
        break;
      }
      bool has = false;
      for (Role role : roles[ei]) has |= role == Role::indices;
      if (!has)
        return text_error(path, e.line,
                          "element 'face' has no list property 'vertex_indices' or 'vertex_index'");
    }
  }
  if (!vertex) return text_error(path, header_end_line, "PLY header declares no element 'vertex'");
  if (!face || face->count == 0) {
    return text_error(path, header_end_line, "no triangles: the PLY header declares no faces");
  }
  if (vertex->count > std::numeric_limits<std::uint32_t>::max()) {
    return text_error(path, vertex->line,
                      "vertex count " + std::to_string(vertex->count) + " exceeds 32-bit indices");
  }
  const auto nv = static_cast<std::int64_t>(vertex->count);

  // Counts against the body size, before reserving anything: binary instances take at least the sum
  // of their scalar and list-count sizes; ASCII values take at least 2 bytes (digit + separator).
  const std::size_t body_begin = r.position();
  const std::uint64_t body = d.size() - body_begin;
  {
    std::uint64_t need = 0;
    for (const Element& e : elements) {
      std::uint64_t min_size = 0;
      for (const Property& p : e.props) {
        min_size += enc == PlyEncoding::ascii ? 2 : size_of(p.list ? p.count_type : p.type);
      }
      if (min_size == 0) continue;
      // The last ASCII value needs no separator.
      const std::uint64_t slack = enc == PlyEncoding::ascii ? 1 : 0;
      const std::uint64_t room = (body + slack - std::min(need, body + slack)) / min_size;
      if (e.count > room) {
        std::string why = "element '" + e.name + "' (header line " + std::to_string(e.line) +
                          ") declares " + std::to_string(e.count) + " instances, but the " +
                          std::to_string(body) + "-byte body can hold at most " +
                          std::to_string(room);
        if (enc == PlyEncoding::ascii) return text_error(path, e.line, std::move(why));
        return byte_error(path, static_cast<std::int64_t>(d.size()), "file ends early: " + why);
      }
      need += e.count * min_size;
    }
  }

  TriMesh m;
  m.positions.resize(vertex->count);
  m.triangles.reserve(face->count);
  std::vector<std::uint32_t> corners;
  std::string why;

  // Shared per-face logic: corners collected, then fan-triangulated.
  auto finish_face = [&]() {
    if (corners.size() > 3) ++info.polygons_split;
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)
      m.triangles.push_back({corners[0], corners[k], corners[k + 1]});
  };

  if (enc == PlyEncoding::ascii) {
    TextReader tr(d.substr(body_begin), header_end_line + 1);
    for (std::size_t ei = 0; ei < elements.size(); ++ei) {
      const Element& e = elements[ei];
      if (e.props.empty()) continue;
      for (std::uint64_t i = 0; i < e.count; ++i) {
        auto eof = [&]() {
          return text_error(path, tr.end_line(),
                            "file ends inside element '" + e.name + "' (instance " +
                                std::to_string(i) + " of " + std::to_string(e.count) + ")");
        };
        for (std::size_t k = 0; k < e.props.size(); ++k) {
          const Property& p = e.props[k];
          const Role role = roles[ei][k];
          double dv;
          std::int64_t iv;
          if (!p.list) {
            const std::string_view t = tr.token();
            if (t.empty()) return eof();
            if (!ascii_value(t, p.type, dv, iv, why))
              return text_error(path, tr.line(), why + " (property '" + p.name + "')");
            if (role >= Role::x && role <= Role::z) {
              if (!std::isfinite(dv)) {
                return text_error(path, tr.line(),
                                  "non-finite coordinate " + quoted(t) + " (vertex " +
                                      std::to_string(i) + ", property '" + p.name + "')");
              }
              m.positions[i][static_cast<std::size_t>(role) - static_cast<std::size_t>(Role::x)] =
                  dv;
            }
            continue;
          }
          const std::string_view ct = tr.token();
          if (ct.empty()) return eof();
          if (!ascii_value(ct, p.count_type, dv, iv, why)) {
            return text_error(path, tr.line(), why + " (list count of '" + p.name + "')");
          }
          if (iv < 0)
            return text_error(path, tr.line(),
                              "negative list count " + quoted(ct) + " ('" + p.name + "')");
          const std::int64_t n = iv;
          if (role == Role::indices) {
            if (n < 3) {
              return text_error(path, tr.line(),
                                "face " + std::to_string(i) + " has " + std::to_string(n) +
                                    " corners; at least 3 are needed");
            }
            corners.clear();
          }
          for (std::int64_t j = 0; j < n; ++j) {
            const std::string_view t = tr.token();
            if (t.empty()) return eof();
            if (!ascii_value(t, p.type, dv, iv, why))
              return text_error(path, tr.line(), why + " (property '" + p.name + "')");
            if (role == Role::indices) {
              if (iv < 0 || iv >= nv) {
                return text_error(path, tr.line(),
                                  "vertex index " + std::to_string(iv) + " out of range [0, " +
                                      std::to_string(nv) + ") in face " + std::to_string(i));
              }
              corners.push_back(static_cast<std::uint32_t>(iv));
            }
          }
          if (role == Role::indices) finish_face();
        }
      }
    }
    if (const std::string_view extra = tr.token(); !extra.empty()) {
      return text_error(path, tr.line(),
                        "unexpected data " + quoted(extra) +
                            " after the last element (element counts do not match)");
    }
  } else {
    const bool swap = (enc == PlyEncoding::binary_be) != (std::endian::native == std::endian::big);
    std::size_t pos = body_begin;
    const char* base = d.data();
    for (std::size_t ei = 0; ei < elements.size(); ++ei) {
      const Element& e = elements[ei];
      if (e.props.empty()) continue;
      bool fixed = true;
      std::size_t stride = 0;
      for (const Property& p : e.props) {
        fixed &= !p.list;
        stride += size_of(p.type);
      }
      if (fixed) {
        if (e.count > (d.size() - pos) / stride) {
          return byte_error(
              path, static_cast<std::int64_t>(pos + (d.size() - pos) / stride * stride),
              "file ends early: element '" + e.name + "' declares " + std::to_string(e.count) +
                  " instances of " + std::to_string(stride) + " bytes, only " +
                  std::to_string((d.size() - pos) / stride) + " fit in the remaining " +
                  std::to_string(d.size() - pos) + " bytes");
        }
        if (&e == vertex) {
          std::size_t off[3] = {0, 0, 0};
          PlyType type[3] = {PlyType::invalid, PlyType::invalid, PlyType::invalid};
          std::size_t o = 0;
          for (std::size_t k = 0; k < e.props.size(); ++k) {
            const Role role = roles[ei][k];
            if (role >= Role::x && role <= Role::z) {
              const auto a = static_cast<std::size_t>(role) - static_cast<std::size_t>(Role::x);
              off[a] = o;
              type[a] = e.props[k].type;
            }
            o += size_of(e.props[k].type);
          }
          for (std::uint64_t i = 0; i < e.count; ++i, pos += stride) {
            Vec3& v = m.positions[i];
            for (std::size_t a = 0; a < 3; ++a) {
              v[a] = load_as<double>(base + pos + off[a], type[a], swap);
              if (!std::isfinite(v[a])) {
                return byte_error(path, static_cast<std::int64_t>(pos + off[a]),
                                  std::string("non-finite coordinate (") +
                                      (std::isnan(v[a]) ? "NaN" : "Inf") + ") in vertex " +
                                      std::to_string(i) + ", property '" + "xyz"[a] + "'");
              }
            }
          }
        } else {
          pos += e.count * stride;
        }
        continue;
      }
      for (std::uint64_t i = 0; i < e.count; ++i) {
        auto eof = [&](std::size_t needed) {
          return byte_error(path, static_cast<std::int64_t>(pos),
                            "file ends early: element '" + e.name + "' instance " +
                                std::to_string(i) + " of " + std::to_string(e.count) + " needs " +
                                std::to_string(needed) + " more bytes, " +
                                std::to_string(d.size() - pos) + " remain");
        };
        for (std::size_t k = 0; k < e.props.size(); ++k) {
          const Property& p = e.props[k];
          const Role role = roles[ei][k];
          if (!p.list) {
            const std::size_t s = size_of(p.type);
            if (d.size() - pos < s) return eof(s);
            if (role >= Role::x && role <= Role::z) {
              const auto a = static_cast<std::size_t>(role) - static_cast<std::size_t>(Role::x);
              const double v = load_as<double>(base + pos, p.type, swap);
              if (!std::isfinite(v)) {
                return byte_error(path, static_cast<std::int64_t>(pos),
                                  std::string("non-finite coordinate (") +
                                      (std::isnan(v) ? "NaN" : "Inf") + ") in vertex " +
                                      std::to_string(i) + ", property '" + p.name + "'");
              }
              m.positions[i][a] = v;
            }
            pos += s;
            continue;
          }
          const std::size_t cs = size_of(p.count_type);
          if (d.size() - pos < cs) return eof(cs);
          const std::int64_t n = load_as<std::int64_t>(base + pos, p.count_type, swap);
          if (n < 0)
            return byte_error(path, static_cast<std::int64_t>(pos),
                              "negative list count " + std::to_string(n));
          if (role == Role::indices && n < 3) {
            return byte_error(path, static_cast<std::int64_t>(pos),
                              "face " + std::to_string(i) + " has " + std::to_string(n) +
                                  " corners; at least 3 are needed");
          }
          const std::size_t is = size_of(p.type);
          if (static_cast<std::uint64_t>(n) > (d.size() - pos - cs) / is) {
            return eof(cs + static_cast<std::size_t>(n) * is);
          }
          pos += cs;
          if (role != Role::indices) {
            pos += static_cast<std::size_t>(n) * is;
            continue;
          }
          corners.clear();
          for (std::int64_t j = 0; j < n; ++j, pos += is) {
            const std::int64_t v = load_as<std::int64_t>(base + pos, p.type, swap);
            if (v < 0 || v >= nv) {
              return byte_error(path, static_cast<std::int64_t>(pos),
                                "vertex index " + std::to_string(v) + " out of range [0, " +
                                    std::to_string(nv) + ") in face " + std::to_string(i));
            }
            corners.push_back(static_cast<std::uint32_t>(v));
          }
          finish_face();
        }
      }
    }
    if (pos != d.size()) {
      return byte_error(
          path, static_cast<std::int64_t>(pos),
          std::to_string(d.size() - pos) +
              " unexpected bytes after the last element (element counts do not match)");
    }
  }
  if (m.triangles.empty())
    return text_error(path, header_end_line, "no triangles: the PLY file has no faces");
  return m;
}

void write_ply(OutputBuffer& out, const TriMesh& mesh, PlyEncoding enc, bool float_coordinates) {
  out.write("ply\nformat ");
  out.write(enc == PlyEncoding::ascii       ? "ascii"
            : enc == PlyEncoding::binary_le ? "binary_little_endian"
                                            : "binary_big_endian");
  out.write(" 1.0\ncomment written by interfere\nelement vertex ");
  out.write_uint(mesh.positions.size());
  const char* t = float_coordinates ? "float" : "double";
  for (const char* axis : {"x", "y", "z"}) {
    out.write("\nproperty ");
    out.write(t);
    out.write(" ");
    out.write(axis);
  }
  out.write("\nelement face ");
  out.write_uint(mesh.triangles.size());
  out.write("\nproperty list uchar uint vertex_indices\nend_header\n");

  if (enc == PlyEncoding::ascii) {
    for (const Vec3& p : mesh.positions) {
      for (std::size_t a = 0; a < 3; ++a) {
        if (a) out.write_char(' ');
        if (float_coordinates) {
          out.write_float(static_cast<float>(p[a]));
        } else {
          out.write_double(p[a]);
        }
      }
      out.write_char('\n');
    }
    for (const Tri& f : mesh.triangles) out.write_tri_line("3 ", f);
    return;
  }
  const bool swap = (enc == PlyEncoding::binary_be) != (std::endian::native == std::endian::big);
  char buf[24];
  for (const Vec3& p : mesh.positions) {
    for (std::size_t a = 0; a < 3; ++a) {
      if (float_coordinates) {
        auto bits = std::bit_cast<std::uint32_t>(static_cast<float>(p[a]));
        if (swap) bits = bswap(bits);
        std::memcpy(buf + 4 * a, &bits, 4);
      } else {
        auto bits = std::bit_cast<std::uint64_t>(p[a]);
        if (swap) bits = bswap(bits);
        std::memcpy(buf + 8 * a, &bits, 8);
      }
    }
    out.write_bytes(buf, float_coordinates ? 12 : 24);
  }
  for (const Tri& f : mesh.triangles) {
    buf[0] = 3;
    for (std::size_t k = 0; k < 3; ++k) {
      std::uint32_t v = f[k];
      if (swap) v = bswap(v);
      std::memcpy(buf + 1 + 4 * k, &v, 4);
    }
    out.write_bytes(buf, 13);
  }
}

}  // namespace interfere::io_detail
