// read_mesh / write_mesh: whole-file reads (one fread), format detection, dispatch to the
// per-format files, welding, mesh checks before writing, and atomic writes (temporary file +
// rename).
#include "interfere/mesh/io.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>
#include <system_error>

#include "../weld_internal.h"
#include "formats.h"
#include "glb.h"
#include "interfere/core/atomic_file.h"
#include "interfere/core/coordinate_range.h"
#include "interfere/mesh/validate.h"
#include "text_reader.h"


namespace interfere {
namespace io_detail {

void OutputBuffer::put(const char* p, std::size_t n) {
  if (!ok_ || n == 0) return;
  if (std::fwrite(p, 1, n, f_) != n) {
    ok_ = false;
    errno_ = errno != 0 ? errno : EIO;
  }
}

void OutputBuffer::write_double(double v) {
  char b[32];
  const auto r = std::to_chars(b, b + sizeof b, v);
  write(std::string_view(b, static_cast<std::size_t>(r.ptr - b)));
}

void OutputBuffer::write_float(float v) {
  char b[32];
  const auto r = std::to_chars(b, b + sizeof b, v);
  write(std::string_view(b, static_cast<std::size_t>(r.ptr - b)));
}

void OutputBuffer::write_uint(std::uint64_t v) {
  char b[24];
  const auto r = std::to_chars(b, b + sizeof b, v);
  write(std::string_view(b, static_cast<std::size_t>(r.ptr - b)));
}

Vec3 facet_normal(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = cross(b - a, c - a);
  const double len = norm(n);
  if (!(len > 0) || !std::isfinite(len)) return {};
  return n / len;
}

}  // namespace io_detail

namespace {

using namespace io_detail;

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

struct FileBytes {
  weld_detail::ScratchBuffer<char> data;
  std::string_view view() const { return {data.data(), data.size()}; }
};

Expected<FileBytes> read_file(const std::filesystem::path& path, const std::string& name) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    return Error{name, -1, -1, "cannot read: is a directory"};
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return Error{name, -1, -1, std::string("cannot open: ") + std::strerror(errno)};
  FileBytes out;
  const auto known = std::filesystem::file_size(path, ec);
  if (!ec && std::filesystem::is_regular_file(path, ec)) {
    // One uninitialised allocation and one fread for the whole file.
    out.data = weld_detail::ScratchBuffer<char>(known);
    const std::size_t got = std::fread(out.data.data(), 1, known, f);
    if (got != known && std::ferror(f)) {
      const int err = errno;
      std::fclose(f);
      return Error{name, -1, static_cast<std::int64_t>(got),
                   std::string("read error: ") + std::strerror(err)};
    }
    out.data.shrink(got);  // the file shrank meanwhile: parse what is there
  } else {
    // Pipes and other special files: read in chunks.
    std::string buf;
    char chunk[1 << 16];
    std::size_t n;
    while ((n = std::fread(chunk, 1, sizeof chunk, f)) > 0) buf.append(chunk, n);
    if (std::ferror(f)) {
      const int err = errno;
      std::fclose(f);
      return Error{name, -1, static_cast<std::int64_t>(buf.size()),
                   std::string("read error: ") + std::strerror(err)};
    }
    out.data = weld_detail::ScratchBuffer<char>(buf.size());
    std::memcpy(out.data.data(), buf.data(), buf.size());
  }
  std::fclose(f);
  return out;
}

using Family = MeshFamily;

Family family_from_extension(const std::filesystem::path& path) {
  const std::string ext = lower(path.extension().string());
  if (ext == ".stl") return Family::stl;
  if (ext == ".obj") return Family::obj;
  if (ext == ".ply") return Family::ply;
  if (ext == ".off") return Family::off;
  if (ext == ".glb") return Family::glb;
  if (ext == ".gltf") return Family::gltf;
  return Family::unknown;
}

Family family_from_content(std::string_view d) {
  if (d.substr(0, 4) == "ply\n" || d.substr(0, 5) == "ply\r\n") return Family::ply;
  if (is_glb(d)) return Family::glb;
  // A JSON object: glTF (no other format read here starts with '{').
  if (const std::size_t first = d.find_first_not_of(" \t\r\n"); first != std::string_view::npos && d[first] == '{')
    return Family::gltf;
  if (d.size() >= 84) {
    std::uint32_t n;
    std::memcpy(&n, d.data() + 80, 4);
    if constexpr (std::endian::native == std::endian::big) n = bswap(n);
    if (84 + 50 * std::uint64_t{n} == d.size()) return Family::stl;
  }
  TextReader r(d.substr(0, 1 << 16));
  std::string_view line;
  bool first = true;
  while (r.next_line(line)) {
    const std::string_view s = strip_comment(line);
    if (s.empty()) continue;
    LineTokens tk(s);
    const std::string_view kw = tk.next();
    if (first && iequals(kw, "solid")) return Family::stl;
    if (first && kw.size() >= 3 && iequals(kw.substr(kw.size() - 3), "off")) return Family::off;
    first = false;
    if (kw == "v" || kw == "f" || kw == "vn" || kw == "vt" || kw == "o" || kw == "g" ||
        kw == "mtllib") {
      return Family::obj;
    }
  }
  return Family::unknown;
}

Status check_writable(const std::string& name, const TriMesh& m, MeshFormat f, bool float_coords) {
  auto fail = [&](std::string why) { return Status(Error{name, -1, -1, "cannot write: " + why}); };
  if (m.triangles.empty()) return fail("the mesh has no triangles");
  const std::size_t nv = m.positions.size();
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    for (std::uint32_t v : m.triangles[t]) {
      if (v >= nv) {
        return fail("triangle " + std::to_string(t) + " references vertex " + std::to_string(v) +
                    ", but the mesh has " + std::to_string(nv) + " vertices");
      }
    }
  }
  const bool stl = mesh_family(f) == Family::stl;
  const bool to_float = stl || float_coords;
  if (stl && m.triangles.size() > std::numeric_limits<std::uint32_t>::max()) {
    return fail("binary STL holds at most 2^32-1 triangles");
  }
  for (std::size_t i = 0; i < nv; ++i) {
    const Vec3& p = m.positions[i];
    for (std::size_t a = 0; a < 3; ++a) {
      if (!std::isfinite(p[a])) {
        return fail("vertex " + std::to_string(i) + " has a non-finite coordinate (" +
                    (std::isnan(p[a]) ? "NaN" : "Inf") + ")");
      }
      if (to_float && !std::isfinite(static_cast<float>(p[a]))) {
        char num[32];
        const auto end = std::to_chars(num, num + sizeof num, p[a]).ptr;
        return fail("vertex " + std::to_string(i) + " coordinate " + std::string(num, end) +
                    " overflows float, which this format stores");
      }
    }
  }
  return {};
}

}  // namespace

MeshFamily mesh_family(MeshFormat f) {
  switch (f) {
    case MeshFormat::stl_ascii:
    case MeshFormat::stl_binary:
      return MeshFamily::stl;
    case MeshFormat::obj:
      return MeshFamily::obj;
    case MeshFormat::ply_ascii:
    case MeshFormat::ply_binary_le:
    case MeshFormat::ply_binary_be:
      return MeshFamily::ply;
    case MeshFormat::off:
      return MeshFamily::off;
    case MeshFormat::glb:
      return MeshFamily::glb;
    case MeshFormat::gltf:
      return MeshFamily::gltf;
    case MeshFormat::automatic:
      break;
  }
  return MeshFamily::unknown;
}

MeshFormat mesh_format_from_name(const std::string& raw) {
  std::string n = lower(raw);
  std::replace(n.begin(), n.end(), '_', '-');
  if (!n.empty() && n[0] == '.') n.erase(0, 1);
  if (n == "stl" || n == "stl-binary" || n == "stlb" || n == "stl-bin")
    return MeshFormat::stl_binary;
  if (n == "stl-ascii" || n == "stla") return MeshFormat::stl_ascii;
  if (n == "obj") return MeshFormat::obj;
  if (n == "ply" || n == "ply-le" || n == "ply-binary" || n == "ply-binary-le" ||
      n == "ply-binary-little-endian") {
    return MeshFormat::ply_binary_le;
  }
  if (n == "ply-ascii") return MeshFormat::ply_ascii;
  if (n == "ply-be" || n == "ply-binary-be" || n == "ply-binary-big-endian")
    return MeshFormat::ply_binary_be;
  if (n == "off") return MeshFormat::off;
  if (n == "glb") return MeshFormat::glb;
  if (n == "gltf") return MeshFormat::gltf;
  return MeshFormat::automatic;
}

const char* mesh_format_name(MeshFormat f) {
  switch (f) {
    case MeshFormat::stl_ascii:
      return "stl-ascii";
    case MeshFormat::stl_binary:
      return "stl-binary";
    case MeshFormat::obj:
      return "obj";
    case MeshFormat::ply_ascii:
      return "ply-ascii";
    case MeshFormat::ply_binary_le:
      return "ply-le";
    case MeshFormat::ply_binary_be:
      return "ply-be";
    case MeshFormat::off:
      return "off";
    case MeshFormat::glb:
      return "glb";
    case MeshFormat::gltf:
      return "gltf";
    default:
      return "auto";
  }
}

namespace {

Expected<TriMesh> read_mesh_impl(const std::filesystem::path& path, const std::string& name,
                                 const ReadOptions& options, MeshReadInfo* info_out) {
  MeshReadInfo info;
  Expected<TriMesh> result = Error{};
  bool welded = false;
  {
    auto bytes = read_file(path, name);
    if (!bytes) return bytes.error();
    const std::string_view d = bytes->view();
    if (d.empty()) return Error{name, -1, 0, "file is empty"};

    Family fam = mesh_family(options.format);
    if (fam == Family::unknown) fam = family_from_extension(path);
    if (fam == Family::unknown) fam = family_from_content(d);
    switch (fam) {
      case Family::stl:
        if (stl_is_binary(d)) {
          result = read_stl_binary(name, d, info, options.weld);
          welded = options.weld;
        } else {
          result = read_stl_ascii(name, d, info);
        }
        break;
      case Family::obj:
        result = read_obj(name, d, info);
        break;
      case Family::ply:
        result = read_ply(name, d, info);
        break;
      case Family::off:
        result = read_off(name, d, info);
        break;
      case Family::glb:
        result = read_glb(name, d, info, path.parent_path());
        break;
      case Family::gltf:
        result = read_gltf(name, d, info, path.parent_path());
        break;
      default:
        return Error{name, -1, -1,
                     "cannot tell the mesh format from the extension '" +
                         path.extension().string() + "' or the content (STL, OBJ, PLY, OFF, GLB and glTF are read)"};
    }
  }  // the file bytes are released before welding
  if (!result) return result;
  TriMesh& m = *result;
  // The coordinate range of the exact predicates (issue #23, item 7), once for every format; text
  // readers already named the line, binary STL the byte. Before welding: the index is the file's.
  if (const std::size_t i = first_out_of_range(m.positions); i < m.positions.size()) {
    return Error{name, -1, -1,
                 "vertex " + std::to_string(i) + (welded ? "" : " (0-based, in file order)") + ": " +
                     coordinate_range_reason(m.positions[i])};
  }
  if (!welded) {
    info.vertices_before_weld = m.positions.size();
    if (options.weld) weld_exact(m);
  }
  if (info_out) *info_out = info;
  return result;
}

}  // namespace

// The API boundary: allocation failure (a valid but huge file) becomes an error value.
Expected<TriMesh> read_mesh(const std::filesystem::path& path, const ReadOptions& options,
                            MeshReadInfo* info_out) {
  const std::string name = path.string();
  try {
    return read_mesh_impl(path, name, options, info_out);
  } catch (const std::bad_alloc&) {
    return Error{name, -1, -1, "out of memory while reading the mesh"};
  } catch (const std::length_error&) {
    return Error{name, -1, -1, "out of memory while reading the mesh"};
  }
}

namespace {

Status write_mesh_impl(const std::filesystem::path& path, const std::string& name,
                       const TriMesh& mesh, const WriteOptions& options) {
  MeshFormat f = options.format;
  if (f == MeshFormat::automatic) {
    switch (family_from_extension(path)) {
      case Family::stl:
        f = MeshFormat::stl_binary;
        break;
      case Family::obj:
        f = MeshFormat::obj;
        break;
      case Family::ply:
        f = MeshFormat::ply_binary_le;
        break;
      case Family::off:
        f = MeshFormat::off;
        break;
      case Family::glb:
        f = MeshFormat::glb;
        break;
      case Family::gltf:
        f = MeshFormat::gltf;
        break;
      default:
        return Error{name, -1, -1,
                     "cannot tell the mesh format from the extension '" +
                         path.extension().string() + "' (.stl, .obj, .ply and .off are written)"};
    }
  }
  if (f == MeshFormat::glb || f == MeshFormat::gltf)
    return Error{name, -1, -1, "write_mesh does not write glTF: use write_glb (interfere/simplify/gltf_io.h)"};
  const bool ply_float = options.ply_float && mesh_family(f) == Family::ply;
  if (Status s = check_writable(name, mesh, f, ply_float); !s) return s;

  return write_file_atomic(path, [&](std::FILE* file) {
    OutputBuffer out(file);
    switch (f) {
      case MeshFormat::stl_binary:
        write_stl_binary(out, mesh);
        break;
      case MeshFormat::stl_ascii:
        write_stl_ascii(out, mesh);
        break;
      case MeshFormat::obj:
        write_obj(out, mesh);
        break;
      case MeshFormat::ply_ascii:
        write_ply(out, mesh, PlyEncoding::ascii, ply_float);
        break;
      case MeshFormat::ply_binary_le:
        write_ply(out, mesh, PlyEncoding::binary_le, ply_float);
        break;
      case MeshFormat::ply_binary_be:
        write_ply(out, mesh, PlyEncoding::binary_be, ply_float);
        break;
      case MeshFormat::off:
        write_off(out, mesh);
        break;
      default:
        break;
    }
    return out.flush() ? 0 : out.error_number();
  });
}

}  // namespace

Status write_mesh(const std::filesystem::path& path, const TriMesh& mesh,
                  const WriteOptions& options) {
  const std::string name = path.string();
  try {
    return write_mesh_impl(path, name, mesh, options);
  } catch (const std::bad_alloc&) {
    return Error{name, -1, -1, "out of memory while writing the mesh"};
  }
}

}  // namespace interfere
