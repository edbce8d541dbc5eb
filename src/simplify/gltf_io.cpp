// glTF 2.0 writer for simplified parts. GLB (Khronos specification §4.4 "GLB File Format"): a
// 12-byte header, a JSON chunk (padded with spaces) and a BIN chunk (padded with zeros); .gltf: the
// JSON alone, its one buffer embedded as a base64 data: URI (§3.6.1.1; one self-contained file,
// written atomically like the GLB). Every buffer view is 4-byte aligned. Meshes are stored once per part and placed by one node per instance
// (glTF node `matrix`, column-major); a root node scales model units to metres (glTF's unit).
#include "interfere/simplify/gltf_io.h"

#include "interfere/core/units.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <utility>

#include "interfere/core/atomic_file.h"
#include "interfere/core/base64.h"
#include "interfere/core/glb.h"
#include "interfere/simplify/qem.h"

namespace interfere {
namespace {

constexpr std::uint32_t kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr std::uint32_t kFloat = 5126, kUnsignedInt = 5125;

// Per-vertex normals (glTF NORMAL, unit length): the area-weighted mean of the normals of the
// vertex's triangles. The vertices are split along faces (or crease regions) first, so the normals
// are smooth within a face (a decimated cylinder still shades round) and sharp across its borders.
// A vertex of degenerate triangles only takes +z (the attribute must be a unit vector).
std::vector<float> vertex_normals(const TriMesh& m) {
  std::vector<Vec3> sum(m.num_vertices(), Vec3{});
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    const auto c = m.corners(t);
    const Vec3 n = cross(c[1] - c[0], c[2] - c[0]);  // length: twice the area
    for (std::uint32_t v : m.triangles[t]) sum[v] = sum[v] + n;
  }
  std::vector<float> out(3 * sum.size());
  for (std::size_t v = 0; v < sum.size(); ++v) {
    const double l = norm(sum[v]);
    const Vec3 n = l > 0 && std::isfinite(l) ? sum[v] / l : Vec3{0, 0, 1};
    for (int k = 0; k < 3; ++k) out[3 * v + k] = static_cast<float>(n[k]);
  }
  return out;
}

double metres_per(const std::string& units) {
  const std::optional<double> mm = millimetres_per_unit(units);
  return mm ? *mm * 1e-3 : 0;  // unknown: no scaling
}

}  // namespace

Status write_glb(const std::filesystem::path& path, const std::vector<GltfPart>& parts,
                 const std::vector<GltfInstance>& instances, const std::string& units, GltfContainer container) {
  const std::string file = path.string();
  if (parts.empty()) return Error{.file = file, .reason = "glTF: no part to write"};
  nlohmann::json j;
  j["asset"] = {{"version", "2.0"}, {"generator", "interfere simplify"}};
  j["meshes"] = nlohmann::json::array();
  j["accessors"] = nlohmann::json::array();
  j["bufferViews"] = nlohmann::json::array();
  std::string bin;
  const auto view = [&](const void* data, std::size_t bytes, std::uint32_t target) {
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}, {"target", target}});
    glb_append_aligned(bin, data, bytes);
    return j["bufferViews"].size() - 1;
  };
  const auto accessor = [&](std::size_t buffer_view, std::uint32_t component, std::size_t count, const char* type) {
    j["accessors"].push_back({{"bufferView", buffer_view}, {"componentType", component}, {"count", count}, {"type", type}});
    return j["accessors"].size() - 1;
  };
  double largest_bound = -1;
  std::map<std::array<float, 3>, std::size_t> colour_material;  // a STEP colour -> its material (from 2)
  std::vector<nlohmann::json> coloured;
  // Every part's mesh, then the coarser levels' meshes (lod_mesh[pi][k]: the mesh of level k + 1).
  std::vector<const GltfPart*> written;
  std::vector<std::vector<std::size_t>> lod_mesh(parts.size());
  for (std::size_t pi = 0; pi < parts.size(); ++pi) written.push_back(&parts[pi]);
  for (std::size_t pi = 0; pi < parts.size(); ++pi)
    for (const GltfPart& l : parts[pi].lods) lod_mesh[pi].push_back(written.size()), written.push_back(&l);
  for (std::size_t wi = 0; wi < written.size(); ++wi) {
    const GltfPart& part = *written[wi];
    const std::size_t pi = wi;
    const std::string what = "glTF: part " + std::to_string(pi) + " ('" + part.name + "')";
    if (part.mesh.num_triangles() == 0) return Error{.file = file, .reason = what + " has no triangles"};
    const bool ids = !part.face_ids.empty();
    if (ids && part.face_ids.size() != part.mesh.num_triangles())
      return Error{.file = file, .reason = what + ": face ids do not match the triangles"};
    // Every vertex on one face, so that per-vertex ids are the triangles' ids and the normals are
    // smooth within a face; without faces, within the regions between crease edges.
    const TriMesh m = split_by_face(part.mesh, ids ? part.face_ids : sharp_edge_regions(part.mesh, part.crease_deg));
    const std::size_t nv = m.num_vertices();
    std::vector<float> pos(3 * nv);
    std::array<float, 3> lo{}, hi{};
    lo.fill(std::numeric_limits<float>::max()), hi.fill(-std::numeric_limits<float>::max());
    for (std::size_t v = 0; v < nv; ++v)
      for (int k = 0; k < 3; ++k) {
        const double x = m.positions[v][k];
        if (!std::isfinite(x) || std::fabs(x) > std::numeric_limits<float>::max())
          return Error{.file = file, .reason = what + ": vertex " + std::to_string(v) + " does not fit a float"};
        pos[3 * v + k] = static_cast<float>(x);
        lo[k] = std::min(lo[k], pos[3 * v + k]), hi[k] = std::max(hi[k], pos[3 * v + k]);
      }
    nlohmann::json attributes;
    const std::size_t a_pos = accessor(view(pos.data(), pos.size() * 4, kArrayBuffer), kFloat, nv, "VEC3");
    j["accessors"][a_pos]["min"] = lo, j["accessors"][a_pos]["max"] = hi;
    attributes["POSITION"] = a_pos;
    const std::vector<float> normals = vertex_normals(m);
    attributes["NORMAL"] = accessor(view(normals.data(), normals.size() * 4, kArrayBuffer), kFloat, nv, "VEC3");
    // Per triangle: an assembly feature (the flags, else the feature faces).
    const bool flagged = !part.feature_flags.empty();
    if (flagged && part.feature_flags.size() != part.mesh.num_triangles())
      return Error{.file = file, .reason = what + ": feature flags do not match the triangles"};
    std::vector<std::uint8_t> tri_feature(m.num_triangles(), 0);
    if (flagged) {
      for (std::size_t t = 0; t < m.num_triangles(); ++t) tri_feature[t] = part.feature_flags[t] != 0;
    } else if (ids) {
      std::vector<std::uint32_t> feat = part.feature_faces;
      std::sort(feat.begin(), feat.end());
      for (std::size_t t = 0; t < m.num_triangles(); ++t)
        tri_feature[t] = std::binary_search(feat.begin(), feat.end(), part.face_ids[t]);
    }
    if (ids) {
      std::vector<float> face(nv, 0.0f), feature(nv, 0.0f);
      for (std::size_t t = 0; t < m.num_triangles(); ++t) {
        const std::uint32_t f = part.face_ids[t];
        if (f >= (1u << 24)) return Error{.file = file, .reason = what + ": face id " + std::to_string(f) + " >= 2^24"};
        for (std::uint32_t v : m.triangles[t]) face[v] = static_cast<float>(f);
      }
      // A vertex is a feature vertex when a feature triangle uses it (faces are split apart, so
      // on whole feature faces this is the face's flag).
      for (std::size_t t = 0; t < m.num_triangles(); ++t)
        if (tri_feature[t])
          for (std::uint32_t v : m.triangles[t]) feature[v] = 1.0f;
      attributes["_FACE_ID"] = accessor(view(face.data(), face.size() * 4, kArrayBuffer), kFloat, nv, "SCALAR");
      attributes["_FEATURE"] = accessor(view(feature.data(), feature.size() * 4, kArrayBuffer), kFloat, nv, "SCALAR");
    }
    // Two primitives on the same vertices: the part's triangles (material 0) and its assembly
    // features (material 1), in triangle order each; an empty one is left out.
    nlohmann::json primitives = nlohmann::json::array();
    for (std::uint8_t want : {std::uint8_t{0}, std::uint8_t{1}}) {
      std::vector<std::uint32_t> idx;
      idx.reserve(3 * m.num_triangles());
      for (std::size_t t = 0; t < m.num_triangles(); ++t)
        if (tri_feature[t] == want) idx.insert(idx.end(), m.triangles[t].begin(), m.triangles[t].end());
      if (idx.empty()) continue;
      const std::size_t a_idx = accessor(view(idx.data(), idx.size() * 4, kElementArrayBuffer), kUnsignedInt, idx.size(), "SCALAR");
      std::size_t material = want;
      if (want == 0 && part.has_color) {  // the part's own colour: a material of its own (by colour)
        const std::array<float, 3> c{part.color[0], part.color[1], part.color[2]};
        auto it = colour_material.find(c);
        if (it == colour_material.end())
          it = colour_material.emplace(c, 2 + colour_material.size()).first,
          coloured.push_back({{"name", part.name},
                              {"pbrMetallicRoughness", {{"baseColorFactor", {c[0], c[1], c[2], 1.0}}, {"metallicFactor", 0.3},
                                                        {"roughnessFactor", 0.6}}}});
        material = it->second;
      }
      primitives.push_back({{"attributes", attributes}, {"indices", a_idx}, {"mode", 4}, {"material", material}});
    }
    nlohmann::json mesh{{"name", part.name}, {"primitives", primitives}};
    if (part.error_bound >= 0) mesh["extras"]["error_bound"] = part.error_bound;
    j["meshes"].push_back(mesh);
    if (wi < parts.size()) largest_bound = std::max(largest_bound, part.error_bound);  // (the finest level's)
  }
  // Nodes: a root scaling model units to metres, one child per instance.
  const double scale = metres_per(units);
  nlohmann::json root{{"name", "interfere_root"}, {"children", nlohmann::json::array()}};
  if (scale > 0 && scale != 1) root["scale"] = {scale, scale, scale};
  j["nodes"] = nlohmann::json::array({root});
  std::map<std::string, std::size_t> groups;  // path prefix -> its group node
  bool lods_used = false;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const GltfInstance& in = instances[i];
    if (in.part >= parts.size())
      return Error{.file = file, .reason = "glTF: instance " + std::to_string(i) + " refers to a missing part"};
    std::array<double, 16> mat{};  // column-major 4x4
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) mat[c * 4 + r] = in.placement.r[r][c];
      mat[12 + r] = in.placement.t[r];
    }
    mat[15] = 1;
    for (double x : mat)
      if (!std::isfinite(x)) return Error{.file = file, .reason = "glTF: instance " + std::to_string(i) + " placement is not finite"};
    // The product hierarchy: a group node per level of the instance's path (created once per
    // prefix), the instance's node under the last one, named by the path's last level.
    std::size_t parent = 0;
    std::string leaf = in.name;
    if (!in.path.empty()) {
      std::vector<std::string> levels;
      for (std::size_t a = 0; a <= in.path.size();) {
        const std::size_t b = std::min(in.path.find('/', a), in.path.size());
        if (b > a) levels.push_back(in.path.substr(a, b - a));
        a = b + 1;
      }
      if (!levels.empty()) leaf = levels.back(), levels.pop_back();
      std::string prefix;
      for (const std::string& level : levels) {
        prefix += "/" + level;
        auto it = groups.find(prefix);
        if (it == groups.end()) {
          it = groups.emplace(prefix, j["nodes"].size()).first;
          j["nodes"][parent]["children"].push_back(j["nodes"].size());
          j["nodes"].push_back({{"name", level}, {"children", nlohmann::json::array()}, {"extras", {{"path", prefix}}}});
        }
        parent = it->second;
      }
    }
    nlohmann::json node{{"name", leaf}, {"mesh", in.part}};
    if (!in.path.empty()) node["extras"]["path"] = in.path;
    if (!in.placement.is_identity()) node["matrix"] = mat;
    const std::size_t at = j["nodes"].size();
    j["nodes"][parent]["children"].push_back(at);
    j["nodes"].push_back(node);
    // MSFT_lod: one node per coarser level, outside the tree, listed finest first.
    if (!lod_mesh[in.part].empty()) {
      nlohmann::json ids = nlohmann::json::array(), coverage = nlohmann::json::array({0.5});
      for (std::size_t k = 0; k < lod_mesh[in.part].size(); ++k) {
        nlohmann::json lod{{"name", leaf + " LOD" + std::to_string(k + 1)}, {"mesh", lod_mesh[in.part][k]}};
        if (!in.placement.is_identity()) lod["matrix"] = mat;
        ids.push_back(j["nodes"].size());
        j["nodes"].push_back(lod);
        coverage.push_back(k + 1 == lod_mesh[in.part].size() ? 0.0 : 0.5 / double(2u << k));
      }
      j["nodes"][at]["extensions"]["MSFT_lod"] = {{"ids", ids}};
      j["nodes"][at]["extras"]["MSFT_screencoverage"] = coverage;
      lods_used = true;
    }
  }
  // Materials: the part (light grey) and its assembly features (orange), PBR metallic-roughness.
  j["materials"] = nlohmann::json::array(
      {{{"name", "part"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.72, 0.74, 0.78, 1.0}}, {"metallicFactor", 0.3}, {"roughnessFactor", 0.6}}}},
       {{"name", "assembly feature"},
        {"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 0.45, 0.05, 1.0}}, {"metallicFactor", 0.1}, {"roughnessFactor", 0.5}}},
        {"emissiveFactor", {0.25, 0.1, 0.0}}}});
  for (const nlohmann::json& m : coloured) j["materials"].push_back(m);
  nlohmann::json scene{{"nodes", {0}}, {"extras", nlohmann::json::object()}};
  if (scale > 0) scene["extras"]["units"] = units, scene["extras"]["metres_per_unit"] = scale;
  if (largest_bound >= 0) scene["extras"]["error_bound"] = largest_bound;
  j["scenes"] = nlohmann::json::array({scene});
  if (lods_used) j["extensionsUsed"] = {"MSFT_lod"};
  j["scene"] = 0;
  j["buffers"] = nlohmann::json::array({{{"byteLength", bin.size()}}});
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (container == GltfContainer::gltf || (container == GltfContainer::by_extension && ext == ".gltf")) {
    j["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64_encode(bin);
    const std::string json = j.dump() + "\n";
    return write_file_atomic(path, [&](std::FILE* f) -> int {
      std::fwrite(json.data(), 1, json.size(), f);
      return std::ferror(f) ? EIO : 0;
    });
  }
  return write_glb_container(path, j.dump(), std::move(bin));
}

}  // namespace interfere
