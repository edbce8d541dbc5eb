// Writing simplified meshes with their per-triangle face ids and feature tags (issue #6, item 7):
// PLY 1.0 (Turk 1994) extra face properties, OBJ groups, the binary STL attribute word.
#include "interfere/simplify/tagged_io.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "../mesh/io/glb.h"
#include "interfere/core/atomic_file.h"

namespace interfere {
namespace {

std::string lower_ext(const std::filesystem::path& p) {
  std::string e = p.extension().string();
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

}  // namespace

Status write_tagged_mesh(const std::filesystem::path& path, const TriMesh& mesh,
                         const std::vector<std::uint32_t>& face_ids,
                         const std::vector<std::uint32_t>& feature_faces, MeshFormat format, double error_bound) {
  const bool untagged = face_ids.empty();
  if (!untagged && face_ids.size() != mesh.num_triangles())
    return Error{.file = path.string(), .reason = "face id count differs from the triangle count"};
  if (mesh.num_triangles() == 0) return Error{.file = path.string(), .reason = "no triangles to write"};
  for (const Vec3& p : mesh.positions)
    if (!is_finite(p)) return Error{.file = path.string(), .reason = "non-finite vertex position"};
  for (const Tri& t : mesh.triangles)
    for (std::uint32_t v : t)
      if (v >= mesh.num_vertices()) return Error{.file = path.string(), .reason = "vertex index out of range"};
  MeshFamily family = mesh_family(format);
  const std::string ext = lower_ext(path);
  if (format == MeshFormat::automatic) {
    family = ext == ".ply" ? MeshFamily::ply : ext == ".obj" ? MeshFamily::obj : ext == ".stl" ? MeshFamily::stl : MeshFamily::unknown;
  }
  if (untagged && (error_bound < 0 || (family != MeshFamily::ply && family != MeshFamily::obj)))
    return write_mesh(path, mesh, {.format = format});
  std::vector<std::uint32_t> feat = feature_faces;
  std::sort(feat.begin(), feat.end());
  auto is_feature = [&](std::uint32_t f) { return std::binary_search(feat.begin(), feat.end(), f); };
  if (family == MeshFamily::ply) {
    const bool ascii = format == MeshFormat::ply_ascii;
    return write_file_atomic(path, [&](std::FILE* f) -> int {
      std::fprintf(f, "ply\nformat %s 1.0\n", ascii ? "ascii" : "binary_little_endian");
      if (!untagged) std::fprintf(f, "comment interfere simplify: face_id = B-Rep face / region, feature = 1 on assembly-feature faces\n");
      if (error_bound >= 0) std::fprintf(f, "comment error_bound %.17g\n", error_bound);
      std::fprintf(f, "element vertex %zu\nproperty double x\nproperty double y\nproperty double z\n", mesh.num_vertices());
      std::fprintf(f, "element face %zu\nproperty list uchar uint vertex_indices\n%send_header\n", mesh.num_triangles(),
                   untagged ? "" : "property uint face_id\nproperty uchar feature\n");
      if (ascii) {
        for (const Vec3& p : mesh.positions) std::fprintf(f, "%.17g %.17g %.17g\n", p.x, p.y, p.z);
        for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
          const Tri& tr = mesh.triangles[t];
          if (untagged) std::fprintf(f, "3 %u %u %u\n", tr[0], tr[1], tr[2]);
          else std::fprintf(f, "3 %u %u %u %u %d\n", tr[0], tr[1], tr[2], face_ids[t], is_feature(face_ids[t]) ? 1 : 0);
        }
      } else {
        for (const Vec3& p : mesh.positions) {
          const double xyz[3] = {p.x, p.y, p.z};
          std::fwrite(xyz, sizeof(double), 3, f);
        }
        for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
          unsigned char rec[18];
          rec[0] = 3;
          std::memcpy(rec + 1, mesh.triangles[t].data(), 12);
          if (!untagged) {
            std::memcpy(rec + 13, &face_ids[t], 4);
            rec[17] = is_feature(face_ids[t]) ? 1 : 0;
          }
          std::fwrite(rec, 1, untagged ? 13 : sizeof rec, f);
        }
      }
      return std::ferror(f) ? EIO : 0;
    });
  }
  if (family == MeshFamily::obj) {
    return write_file_atomic(path, [&](std::FILE* f) -> int {
      if (!untagged) std::fprintf(f, "# interfere simplify: one group per face id (feature_face_<id> for assembly features)\n");
      if (error_bound >= 0) std::fprintf(f, "# error_bound %.17g\n", error_bound);
      for (const Vec3& p : mesh.positions) std::fprintf(f, "v %.17g %.17g %.17g\n", p.x, p.y, p.z);
      std::int64_t current = -1;
      for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
        if (!untagged && static_cast<std::int64_t>(face_ids[t]) != current) {
          current = face_ids[t];
          std::fprintf(f, "g %sface_%u\n", is_feature(face_ids[t]) ? "feature_" : "", face_ids[t]);
        }
        const Tri& tr = mesh.triangles[t];
        std::fprintf(f, "f %u %u %u\n", tr[0] + 1, tr[1] + 1, tr[2] + 1);
      }
      return std::ferror(f) ? EIO : 0;
    });
  }
  const bool fits = std::all_of(face_ids.begin(), face_ids.end(), [](std::uint32_t v) { return v < 65535; });
  if (family == MeshFamily::stl && format != MeshFormat::stl_ascii && fits) {
    for (const Vec3& p : mesh.positions)
      for (int k = 0; k < 3; ++k)
        if (std::abs(p[k]) > 3.4e38) return Error{.file = path.string(), .reason = "coordinate overflows float"};
    return write_file_atomic(path, [&](std::FILE* f) -> int {
      char header[80] = {};
      std::snprintf(header, sizeof header, "interfere simplify: attribute word = face id");
      std::fwrite(header, 1, 80, f);
      const auto n = static_cast<std::uint32_t>(mesh.num_triangles());
      std::fwrite(&n, 4, 1, f);
      for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
        const auto c = mesh.corners(t);
        Vec3 nn = cross(c[1] - c[0], c[2] - c[0]);
        const double l = norm(nn);
        if (l > 0) nn = nn / l;
        float rec[12] = {float(nn.x), float(nn.y), float(nn.z)};
        for (int k = 0; k < 3; ++k) rec[3 + 3 * k] = float(c[k].x), rec[4 + 3 * k] = float(c[k].y), rec[5 + 3 * k] = float(c[k].z);
        std::fwrite(rec, 4, 12, f);
        const auto attr = static_cast<std::uint16_t>(face_ids[t]);
        std::fwrite(&attr, 2, 1, f);
      }
      return std::ferror(f) ? EIO : 0;
    });
  }
  return write_mesh(path, mesh, {.format = format});
}

Expected<std::vector<std::uint32_t>> read_region_file(const std::filesystem::path& path, std::size_t triangles) {
  std::ifstream in(path);
  if (!in) return Error{.file = path.string(), .reason = "cannot open the region file"};
  std::vector<std::uint32_t> out;
  out.reserve(triangles);
  std::string line;
  std::int64_t lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream ss(line);
    std::string tok;
    while (ss >> tok) {
      std::uint32_t v = 0;
      const auto [p, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
      if (ec != std::errc{} || p != tok.data() + tok.size())
        return Error{.file = path.string(), .line = lineno, .reason = "not an unsigned integer region id: '" + tok + "'"};
      out.push_back(v);
    }
  }
  if (out.size() != triangles)
    return Error{.file = path.string(), .line = lineno,
                 .reason = std::to_string(out.size()) + " region ids for " + std::to_string(triangles) + " triangles"};
  return out;
}

// The comment lines write_tagged_mesh puts before the data: PLY header comments (up to
// end_header), OBJ comment lines before the first statement.
namespace {

// The glTF document's scene extras.error_bound (write_glb: the largest part's, in model units), in
// the units read_mesh gives (metres where extras.metres_per_unit says the root node scales to them);
// -1 when it has none. `byte`: where the JSON starts in the file (for errors).
Expected<double> scene_error_bound(const nlohmann::json& doc, const std::string& file, std::int64_t byte) {
  const Error bad{.file = file, .byte = byte,
                  .reason = "glTF scene extras: error_bound must be a finite number >= 0 (metres_per_unit > 0)"};
  std::size_t scene = 0;
  if (doc.contains("scene") && doc["scene"].is_number_unsigned()) scene = doc["scene"].get<std::size_t>();
  if (!doc.contains("scenes") || !doc["scenes"].is_array() || scene >= doc["scenes"].size()) return -1.0;
  const auto& extras = doc["scenes"][scene].value("extras", nlohmann::json::object());
  if (!extras.is_object() || !extras.contains("error_bound")) return -1.0;
  const auto& b = extras["error_bound"];
  if (!b.is_number() || !std::isfinite(b.get<double>()) || b.get<double>() < 0) return bad;
  double scale = 1;
  if (extras.contains("metres_per_unit")) {
    const auto& m = extras["metres_per_unit"];
    if (!m.is_number() || !(m.get<double>() > 0) || !std::isfinite(m.get<double>())) return bad;
    scale = m.get<double>();
  }
  return b.get<double>() * scale;
}

// A GLB's bound: scene_error_bound of its JSON chunk.
Expected<double> glb_error_bound(const std::filesystem::path& path, std::ifstream& in) {
  // The header and the JSON chunk only (the BIN chunk, the bulk of the file, is not needed).
  const std::string file = path.string();
  std::string head(20, '\0');
  in.read(head.data(), 20);
  head.resize(static_cast<std::size_t>(in.gcount()));
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  auto length = io_detail::glb_json_length(file, head, ec ? 0 : size);
  if (!length) return length.error();
  std::string json(*length, '\0');
  if (!in.read(json.data(), *length)) return Error{.file = file, .byte = 20, .reason = "truncated JSON chunk"};
  const auto doc = nlohmann::json::parse(json, nullptr, false);
  if (doc.is_discarded()) return Error{.file = file, .byte = 20, .reason = "the JSON chunk is not valid JSON"};
  return scene_error_bound(doc, file, 20);
}

// A .gltf file's bound: as a GLB's, from the whole JSON file.
Expected<double> gltf_error_bound(const std::filesystem::path& path, std::ifstream& in) {
  const std::string file = path.string();
  const auto doc = nlohmann::json::parse(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>(), nullptr, false);
  if (doc.is_discarded()) return Error{.file = file, .byte = 0, .reason = "not valid JSON (glTF)"};
  return scene_error_bound(doc, file, 0);
}

}  // namespace


Expected<double> read_error_bound(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{.file = path.string(), .reason = "cannot open the mesh file"};
  const std::string ext = lower_ext(path);
  if (ext == ".glb") return glb_error_bound(path, in);
  if (ext == ".gltf") return gltf_error_bound(path, in);
  const bool ply = ext == ".ply", obj = ext == ".obj";
  if (!ply && !obj) return -1.0;
  const std::string key = ply ? "comment error_bound" : "# error_bound";
  std::string line;
  for (std::int64_t lineno = 1; lineno <= 4096 && std::getline(in, line); ++lineno) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (ply ? line == "end_header" : (!line.empty() && line[0] != '#')) break;
    if (line.compare(0, key.size(), key) != 0 || line.size() == key.size() || line[key.size()] != ' ') continue;
    std::string tok = line.substr(key.size() + 1);
    while (!tok.empty() && tok.back() == ' ') tok.pop_back();
    double v = 0;
    const auto [p, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    if (ec != std::errc{} || p != tok.data() + tok.size() || !std::isfinite(v) || v < 0)
      return Error{.file = path.string(), .line = lineno,
                   .reason = "error_bound must be a finite number >= 0, not '" + tok + "'"};
    return v;
  }
  return -1.0;
}

}  // namespace interfere
