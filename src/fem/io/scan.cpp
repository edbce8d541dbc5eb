// Shared scanning helpers of the FEM readers/writers (scan.h): file loading, number parsing,
// id maps, node-order tables. Node orders: Gmsh manual, section "Node ordering" (high-order
// elements: edges listed as (0,1) (0,3) (0,4) (1,2) ... for hexahedra); Nastran Quick Reference
// Guide, CHEXA/CPENTA (mid-side grids G9..G12 bottom, G13..G16 vertical, G17..G20 top); VTK file
// formats (VTK_QUADRATIC_* cell node orders).
#include "scan.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <system_error>
#include <array>
#include <string>

#include "../surface_faces.h"

namespace interfere::fem_io {

Expected<std::string> read_file_bytes(const std::filesystem::path& path, bool regular_only) {
  const std::string name = path.string();
  std::error_code ec;
  const auto st = std::filesystem::status(path, ec);
  if (!ec && std::filesystem::is_directory(st)) return file_error(name, "cannot open: is a directory");
  if (!ec && regular_only && std::filesystem::exists(st) && !std::filesystem::is_regular_file(st)) return file_error(name, "cannot open: not a regular file");
  std::FILE* f = std::fopen(name.c_str(), "rb");
  if (!f) return file_error(name, std::string("cannot open: ") + std::strerror(errno));
  std::string data;
  if (std::fseek(f, 0, SEEK_END) == 0) {
    const long size = std::ftell(f);
    if (size > 0 && size < (1L << 42)) data.resize(static_cast<std::size_t>(size));
    std::fseek(f, 0, SEEK_SET);
  }
  std::size_t got = data.empty() ? 0 : std::fread(data.data(), 1, data.size(), f);
  data.resize(got);
  // Whatever follows (pipes, growing files).
  char buf[1 << 16];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) data.append(buf, n);
  const bool err = std::ferror(f) != 0;
  std::fclose(f);
  if (err) return file_error(name, "cannot read");
  if (data.empty()) return file_error(name, "file is empty");
  return data;
}

std::string quote_tok(std::string_view t) {
  constexpr std::size_t kMax = 40;
  std::string s = "'";
  for (std::size_t i = 0; i < t.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(t[i]);
    if (c < 0x20 || c >= 0x7f) {
      char b[8];
      std::snprintf(b, sizeof b, "\\x%02x", c);
      s += b;
    } else {
      s += static_cast<char>(c);
    }
  }
  if (t.size() > kMax) s += "...";
  return s + "'";
}

bool istarts_with(std::string_view s, std::string_view p) { return s.size() >= p.size() && iequals(s.substr(0, p.size()), p); }
std::string to_lower(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = lower(c);
  return r;
}
std::string_view trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && is_space(s[b])) ++b;
  while (e > b && is_space(s[e - 1])) --e;
  return s.substr(b, e - b);
}



std::int64_t line_of(std::string_view s, std::size_t pos) {
  pos = std::min(pos, s.size());
  return 1 + static_cast<std::int64_t>(std::count(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
}

std::int64_t IdMap::build(const std::vector<std::int64_t>& ids) {
  table_.clear();
  hash_.clear();
  const std::size_t n = ids.size();
  if (n == 0) {
    dense_ = true;
    lo_ = 0;
    return -1;
  }
  const auto [mn, mx] = std::minmax_element(ids.begin(), ids.end());
  lo_ = *mn;
  const std::uint64_t span = static_cast<std::uint64_t>(*mx) - static_cast<std::uint64_t>(*mn);
  dense_ = span < 4 * static_cast<std::uint64_t>(n) + 1024;
  if (dense_) {
    table_.assign(span + 1, kNone);
    for (std::size_t i = 0; i < n; ++i) {
      std::uint32_t& slot = table_[static_cast<std::uint64_t>(ids[i]) - static_cast<std::uint64_t>(lo_)];
      if (slot != kNone) return static_cast<std::int64_t>(i);
      slot = static_cast<std::uint32_t>(i);
    }
    return -1;
  }
  hash_.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!hash_.emplace(ids[i], static_cast<std::uint32_t>(i)).second) return static_cast<std::int64_t>(i);
  }
  return -1;
}

std::int64_t find_duplicate(const std::vector<std::int64_t>& ids, std::int64_t* first) {
  IdMap map;
  const std::int64_t dup = map.build(ids);
  if (dup >= 0 && first) {
    *first = std::find(ids.begin(), ids.end(), ids[static_cast<std::size_t>(dup)]) - ids.begin();
  }
  return dup;
}

Status check_element_ids(const FemMesh& m, const std::vector<std::int64_t>& where, bool bytes) {
  std::int64_t first = -1;
  const std::int64_t dup = find_duplicate(m.elem_ids, &first);
  if (dup < 0) return {};
  const std::int64_t at = dup < static_cast<std::int64_t>(where.size()) ? where[static_cast<std::size_t>(dup)] : -1;
  std::string reason = "duplicate element id " + std::to_string(m.elem_ids[static_cast<std::size_t>(dup)]);
  if (first >= 0 && first < static_cast<std::int64_t>(where.size())) {
    reason += std::string(" (first at ") + (bytes ? "byte " : "line ") + std::to_string(where[static_cast<std::size_t>(first)]) + ")";
  }
  return bytes ? byte_error(m.file, at, reason) : line_error(m.file, at, reason);
}

std::int32_t group_index(FemMesh& m, std::unordered_map<std::string, std::int32_t>& by_name, const std::string& name,
                         std::int64_t id, int dim) {
  auto it = by_name.find(name);
  if (it != by_name.end()) return it->second;
  const auto g = static_cast<std::int32_t>(m.groups.size());
  m.groups.push_back(FemGroup{.name = name, .id = id, .dim = dim});
  by_name.emplace(name, g);
  return g;
}

namespace {
// What the dropped lower-dimension elements were (issue #23, item 10), as reader warnings: points
// and lines (masses, springs, trusses, beams: no surface) counted; 2-D elements on a face of a 3-D
// element (the boundary triangles/quads exporters such as gmsh write beside the volumes: neither a
// body nor a second copy of the surface) told apart from 2-D elements elsewhere (shells beside
// the volumes, which are not checked).
void warn_dropped(FemMesh& m, int top) {
  std::size_t points = 0, lines = 0, on_faces = 0, elsewhere = 0;
  std::vector<std::array<std::uint32_t, 4>> faces;  // sorted corner keys of the 3-D elements' faces
  auto key = [](const std::uint32_t* v, const fem_detail::FaceDef& f) {
    std::array<std::uint32_t, 4> k{v[f.c[0]], v[f.c[1]], v[f.c[2]], f.n == 4 ? v[f.c[3]] : ~0u};
    std::sort(k.begin(), k.begin() + f.n);
    return k;
  };
  const std::size_t ne = m.elem_types.size();
  bool any2 = false;
  for (std::size_t e = 0; e < ne; ++e) any2 |= elem_info(m.elem_types[e]).dim == 2;
  if (top == 3 && any2) {
    for (std::size_t e = 0; e < ne; ++e) {
      const fem_detail::ElemFaces ef = fem_detail::volume_faces(m.elem_types[e]);
      const std::uint32_t* v = m.elem_nodes.data() + m.elem_offsets[e];
      for (int f = 0; f < ef.count; ++f) faces.push_back(key(v, ef.faces[f]));
    }
    std::sort(faces.begin(), faces.end());
  }
  for (std::size_t e = 0; e < ne; ++e) {
    const ElemType t = m.elem_types[e];
    const int d = elem_info(t).dim;
    if (d == top) continue;
    if (d == 0) {
      ++points;
    } else if (d == 1) {
      ++lines;
    } else if (d == 2 && top == 3) {
      const fem_detail::FaceDef& f = elem_info(t).corners == 3 ? fem_detail::kTriShell : fem_detail::kQuadShell;
      const auto k = key(m.elem_nodes.data() + m.elem_offsets[e], f);
      (std::binary_search(faces.begin(), faces.end(), k) ? on_faces : elsewhere) += 1;
    }
  }
  std::vector<std::string>& w = m.warnings;
  if (lines + points > 0) {
    w.push_back("skipped " + std::to_string(lines + points) + " elements without a surface (" + std::to_string(lines) +
                " 1-D: trusses, beams, springs, lines; " + std::to_string(points) + " points: masses, 1-node springs)");
  }
  if (elsewhere > 0) {
    w.push_back("skipped " + std::to_string(elsewhere) +
                " 2-D elements that are not faces of the 3-D elements (shells beside volumes are not checked; " +
                std::to_string(on_faces) + " 2-D elements on the volumes' faces are their boundary)");
  }
}
}  // namespace

void drop_lower_dimension(FemMesh& m, std::vector<std::int64_t>* where) {
  int top = -1;
  for (ElemType t : m.elem_types) top = std::max(top, elem_info(t).dim);
  std::size_t k = 0;
  std::uint64_t w = 0;
  const std::size_t ne = m.elem_types.size();
  bool all = true;
  for (ElemType t : m.elem_types) all &= elem_info(t).dim == top;
  if (all) return;
  warn_dropped(m, top);
  for (std::size_t e = 0; e < ne; ++e) {
    if (elem_info(m.elem_types[e]).dim != top) continue;
    const std::uint64_t b = m.elem_offsets[e], n = m.elem_offsets[e + 1] - b;
    std::memmove(m.elem_nodes.data() + w, m.elem_nodes.data() + b, n * sizeof(std::uint32_t));
    m.elem_types[k] = m.elem_types[e];
    m.elem_ids[k] = m.elem_ids[e];
    m.elem_groups[k] = m.elem_groups[e];
    if (where && e < where->size()) (*where)[k] = (*where)[e];
    w += n;
    ++k;
    m.elem_offsets[k] = w;
  }
  m.elem_types.resize(k);
  m.elem_ids.resize(k);
  m.elem_groups.resize(k);
  m.elem_offsets.resize(k + 1);
  m.elem_nodes.resize(w);
  if (where && where->size() > k) where->resize(k);
}

namespace {
// Gmsh -> VTK (vtk[i] = gmsh[perm[i]]), from the edge lists of the Gmsh manual ("Node ordering"):
// tet10 edges (0,1)(1,2)(2,0)(3,0)(3,2)(3,1); hex20 (0,1)(0,3)(0,4)(1,2)(1,5)(2,3)(2,6)(3,7)(4,5)
// (4,7)(5,6)(6,7), faces (0,3,2,1)(0,1,5,4)(0,4,7,3)(1,2,6,5)(2,3,7,6)(4,5,6,7); wedge15
// (0,1)(0,2)(0,3)(1,2)(1,4)(2,5)(3,4)(3,5)(4,5); pyr13 (0,1)(0,3)(0,4)(1,2)(1,4)(2,3)(2,4)(3,4).
constexpr int kGmshTet10[10] = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};
constexpr int kGmshHex20[20] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15};
constexpr int kGmshHex27[27] = {0,  1,  2,  3,  4,  5,  6,  7,  8,  11, 13, 9,  16, 18,
                                19, 17, 10, 12, 14, 15, 22, 23, 21, 24, 20, 25, 26};
constexpr int kGmshWedge15[15] = {0, 1, 2, 3, 4, 5, 6, 9, 7, 12, 14, 13, 8, 10, 11};
constexpr int kGmshPyr13[13] = {0, 1, 2, 3, 4, 5, 8, 10, 6, 7, 9, 11, 12};
// Nastran: CHEXA G9-G12 bottom edges, G13-G16 vertical, G17-G20 top; CPENTA G7-G9 bottom,
// G10-G12 vertical, G13-G15 top. VTK: bottom, top, vertical.
constexpr int kNasHex20[20] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 16, 17, 18, 19, 12, 13, 14, 15};
constexpr int kNasWedge15[15] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 13, 14, 9, 10, 11};
}  // namespace

const int* gmsh_to_vtk(ElemType t) {
  switch (t) {
    case ElemType::tet10: return kGmshTet10;
    case ElemType::hex20: return kGmshHex20;
    case ElemType::hex27: return kGmshHex27;
    case ElemType::wedge15: return kGmshWedge15;
    case ElemType::pyr13: return kGmshPyr13;
    default: return nullptr;
  }
}

const int* nastran_to_vtk(ElemType t) {
  switch (t) {
    case ElemType::hex20: return kNasHex20;
    case ElemType::wedge15: return kNasWedge15;
    default: return nullptr;
  }
}

bool elem_type_from_vtk(int vtk, ElemType& out) {
  for (int i = 0; i < kNumElemTypes; ++i) {
    if (elem_info(static_cast<ElemType>(i)).vtk_cell_type == vtk) {
      out = static_cast<ElemType>(i);
      return true;
    }
  }
  return false;
}

void put_double(std::string& out, double v) {
  char b[32];
  const auto r = std::to_chars(b, b + sizeof b, v);
  out.append(b, static_cast<std::size_t>(r.ptr - b));
}

void put_int(std::string& out, std::int64_t v) {
  char b[24];
  const auto r = std::to_chars(b, b + sizeof b, v);
  out.append(b, static_cast<std::size_t>(r.ptr - b));
}

}  // namespace interfere::fem_io
