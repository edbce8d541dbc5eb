// glTF 2.0 scene export of a viewer document (include/interfere/view/gltf.h; issue #25, item 2).
// Khronos glTF 2.0 specification: §3.5 "Geometry" (accessors, min/max of POSITION, modes 1 LINES
// and 4 TRIANGLES), §3.7 "Animations" (STEP samplers; an animated node uses TRS, not `matrix`),
// §3.9 "Materials" (linear baseColorFactor, alphaMode BLEND, doubleSided), KHR_materials_unlit for
// lines; the GLB container of core/glb.h.
#include "interfere/view/gltf.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "export_checks.h"
#include "interfere/core/glb.h"
#include "interfere/core/units.h"
#include "interfere/simplify/qem.h"

namespace interfere::view {
namespace {

using json = nlohmann::ordered_json;

constexpr std::uint32_t kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr std::uint32_t kFloat = 5126, kUnsignedInt = 5125;
constexpr int kLines = 1, kTriangles = 4;

constexpr Rgb rgb8(int r, int g, int b) { return {r / 255.0f, g / 255.0f, b / 255.0f}; }
// The page's colours (docs/viewer.md), sRGB.
constexpr Rgb kClashRed = rgb8(0xe0, 0x20, 0x20), kContactOrange = rgb8(0xf0, 0xa0, 0x20),
              kWitnessBlue = rgb8(0x20, 0x60, 0xe0), kCurveYellow = rgb8(0xff, 0xd4, 0x00),
              kUndecidedMagenta = rgb8(0xe0, 0x20, 0xe0);

Rgb region_colour(const std::string& verdict) {
  if (verdict == "clash") return kClashRed;
  if (verdict == "contact") return kContactOrange;
  if (verdict == "clearance") return kWitnessBlue;
  return kUndecidedMagenta;
}

json number_or_null(double v) { return v < 0 ? json(nullptr) : json(v); }

/// A colour factor as written: rounded to 6 decimals (a float 0.35f would read 0.3499999940395355).
double factor(float x) { return std::round(static_cast<double>(x) * 1e6) / 1e6; }

/// The unit quaternion [x, y, z, w] of a rotation matrix (Shepperd's method: the largest of the
/// four squared components first, so the division is well conditioned).
std::array<double, 4> quaternion(const Transform& t) {
  const auto& r = t.r;
  const double trace = r[0][0] + r[1][1] + r[2][2];
  std::array<double, 4> q{};
  if (trace > 0) {
    const double s = 2 * std::sqrt(1 + trace);
    q = {(r[2][1] - r[1][2]) / s, (r[0][2] - r[2][0]) / s, (r[1][0] - r[0][1]) / s, s / 4};
  } else if (r[0][0] > r[1][1] && r[0][0] > r[2][2]) {
    const double s = 2 * std::sqrt(1 + r[0][0] - r[1][1] - r[2][2]);
    q = {s / 4, (r[0][1] + r[1][0]) / s, (r[0][2] + r[2][0]) / s, (r[2][1] - r[1][2]) / s};
  } else if (r[1][1] > r[2][2]) {
    const double s = 2 * std::sqrt(1 + r[1][1] - r[0][0] - r[2][2]);
    q = {(r[0][1] + r[1][0]) / s, s / 4, (r[1][2] + r[2][1]) / s, (r[0][2] - r[2][0]) / s};
  } else {
    const double s = 2 * std::sqrt(1 + r[2][2] - r[0][0] - r[1][1]);
    q = {(r[0][2] + r[2][0]) / s, (r[1][2] + r[2][1]) / s, s / 4, (r[1][0] - r[0][1]) / s};
  }
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& x : q) x /= n;
  return q;
}

json column_major(const Transform& t) {
  std::array<double, 16> m{};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m[c * 4 + r] = t.r[r][c];
    m[12 + r] = t.t[r];
  }
  m[15] = 1;
  return m;
}

class SceneWriter {
 public:
  SceneWriter(const Document& doc, const GltfOptions& options) : doc_(doc), options_(options) {}

  json build() {
    j_["asset"] = {{"version", "2.0"}, {"generator", "interfere" + (doc_.tool_version.empty() ? "" : " " + doc_.tool_version)}};
    for (const char* array : {"nodes", "meshes", "materials", "accessors", "bufferViews"}) j_[array] = json::array();
    setup_frames();
    // Nodes 0, 1 (and 2): the root, the bodies group (and the clashes group).
    const double scale = metres_per_unit();
    json root{{"name", "interfere_root"}, {"children", json::array({1})}};
    if (scale > 0 && scale != 1) root["scale"] = {scale, scale, scale};
    j_["nodes"].push_back(root);
    j_["nodes"].push_back({{"name", "bodies"}, {"children", json::array()}});
    if (!doc_.clashes.empty()) {
      j_["nodes"][0]["children"].push_back(2);
      j_["nodes"].push_back({{"name", "clashes"}, {"children", json::array()}});
    }
    for (std::size_t b = 0; b < doc_.bodies.size(); ++b)
      if (doc_.bodies[b].visible || options_.hidden_bodies) j_["nodes"][1]["children"].push_back(body_node(b));
    for (std::size_t c = 0; c < doc_.clashes.size(); ++c) j_["nodes"][2]["children"].push_back(clash_node(c));
    // glTF: a node's `children`, when present, has at least one item (node.schema.json).
    for (json& node : j_["nodes"])
      if (node.contains("children") && node["children"].empty()) node.erase("children");
    if (!channels_.empty()) {
      json extras{{"labels", doc_.frames.labels}};
      if (!doc_.frames.times.empty()) extras["times"] = doc_.frames.times;
      if (!doc_.frames.verdicts.empty()) extras["verdicts"] = doc_.frames.verdicts;
      j_["animations"] = json::array({{{"name", "frames"}, {"channels", channels_}, {"samplers", samplers_}, {"extras", extras}}});
    }
    json scene{{"name", doc_.title.empty() ? std::string("interfere") : doc_.title}, {"nodes", {0}}, {"extras", scene_extras(scale)}};
    j_["scenes"] = json::array({scene});
    j_["scene"] = 0;
    if (unlit_used_) j_["extensionsUsed"] = json::array({"KHR_materials_unlit"});
    for (const char* array : {"meshes", "materials", "accessors", "bufferViews"})
      if (j_[array].empty()) j_.erase(array);
    if (!bin_.empty()) j_["buffers"] = json::array({{{"byteLength", bin_.size()}}});
    return std::move(j_);
  }

  std::string take_bin() { return std::move(bin_); }

 private:
  // ---- buffers and accessors ----
  std::size_t view(const void* data, std::size_t bytes, std::optional<std::uint32_t> target) {
    json v{{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes}};
    if (target) v["target"] = *target;
    j_["bufferViews"].push_back(v);
    glb_append_aligned(bin_, data, bytes);
    return j_["bufferViews"].size() - 1;
  }

  /// A float accessor of `values.size() / width` elements of `type`; with min/max when asked.
  std::size_t floats(const std::vector<float>& values, int width, const char* type, std::optional<std::uint32_t> target,
                     bool bounds) {
    const std::size_t count = values.size() / width;
    json a{{"bufferView", view(values.data(), values.size() * 4, target)}, {"componentType", kFloat}, {"count", count}, {"type", type}};
    if (bounds) {
      std::vector<float> lo(width, std::numeric_limits<float>::max()), hi(width, -std::numeric_limits<float>::max());
      for (std::size_t i = 0; i < values.size(); ++i) {
        lo[i % width] = std::min(lo[i % width], values[i]);
        hi[i % width] = std::max(hi[i % width], values[i]);
      }
      a["min"] = lo, a["max"] = hi;
    }
    j_["accessors"].push_back(a);
    return j_["accessors"].size() - 1;
  }

  std::size_t indices(const std::vector<std::uint32_t>& idx) {
    json a{{"bufferView", view(idx.data(), idx.size() * 4, kElementArrayBuffer)},
           {"componentType", kUnsignedInt}, {"count", idx.size()}, {"type", "SCALAR"}};
    j_["accessors"].push_back(a);
    return j_["accessors"].size() - 1;
  }

  /// POSITION of `points` less `offset`, as float.
  std::size_t positions(const std::vector<Vec3>& points, const Vec3& offset) {
    std::vector<float> pos(3 * points.size());
    for (std::size_t v = 0; v < points.size(); ++v)
      for (int k = 0; k < 3; ++k) pos[3 * v + k] = static_cast<float>(points[v][k] - offset[k]);
    return floats(pos, 3, "VEC3", kArrayBuffer, true);
  }

  // ---- materials ----
  std::size_t material(const std::string& name, const Rgb& srgb, float alpha, bool unlit) {
    const std::string key = name + "|" + std::to_string(srgb[0]) + "," + std::to_string(srgb[1]) + "," +
                            std::to_string(srgb[2]) + "," + std::to_string(alpha) + (unlit ? "|u" : "");
    if (const auto it = materials_.find(key); it != materials_.end()) return it->second;
    json pbr{{"baseColorFactor", {factor(detail::srgb_to_linear(srgb[0])), factor(detail::srgb_to_linear(srgb[1])),
                                  factor(detail::srgb_to_linear(srgb[2])), factor(alpha)}},
             {"metallicFactor", 0.0},
             {"roughnessFactor", unlit ? 1.0 : 0.6}};
    json m{{"name", name}, {"pbrMetallicRoughness", pbr}, {"doubleSided", true}};
    if (alpha < 1) m["alphaMode"] = "BLEND";
    if (unlit) m["extensions"] = {{"KHR_materials_unlit", json::object()}}, unlit_used_ = true;
    j_["materials"].push_back(m);
    return materials_[key] = j_["materials"].size() - 1;
  }

  static std::string hex(const Rgb& c) {
    char s[8];
    const auto byte = [](float x) { return static_cast<int>(std::lround(std::clamp(x, 0.0f, 1.0f) * 255)); };
    std::snprintf(s, sizeof s, "#%02x%02x%02x", byte(c[0]), byte(c[1]), byte(c[2]));
    return s;
  }

  // ---- bodies ----
  struct Geometry {
    std::size_t position = 0, indices = 0;
    std::optional<std::size_t> color;
  };

  /// The accessors of a mesh in local coordinates, written once however many bodies draw it. A
  /// mesh with face colours is split between colours and carries them as COLOR_0 (linear).
  const Geometry& body_geometry(std::uint32_t m) {
    if (const auto it = geometry_.find(m); it != geometry_.end()) return it->second;
    const ViewMesh& vm = doc_.meshes[m];
    Geometry g;
    const bool coloured = !vm.face_colors.empty();
    const TriMesh split = coloured ? split_by_face(vm.mesh, vm.face_colors) : TriMesh{};
    const TriMesh& mesh = coloured ? split : vm.mesh;
    g.position = positions(mesh.positions, Vec3{});
    std::vector<std::uint32_t> idx;
    idx.reserve(3 * mesh.num_triangles());
    for (const Tri& t : mesh.triangles) idx.insert(idx.end(), t.begin(), t.end());
    g.indices = indices(idx);
    if (coloured) {
      std::vector<float> colour(3 * mesh.num_vertices(), 1.0f);
      for (std::size_t t = 0; t < mesh.num_triangles(); ++t)
        for (std::uint32_t v : mesh.triangles[t])
          for (int k = 0; k < 3; ++k) colour[3 * v + k] = detail::srgb_to_linear(doc_.legend[vm.face_colors[t]].color[k]);
      g.color = floats(colour, 3, "VEC3", kArrayBuffer, false);
    }
    return geometry_[m] = g;
  }

  /// The glTF mesh of ViewMesh `m` drawn in `body`'s material (one per mesh and material).
  std::optional<std::size_t> body_mesh(std::uint32_t m, const ViewBody& body) {
    const ViewMesh& vm = doc_.meshes[m];
    if (vm.mesh.num_triangles() == 0) return std::nullopt;  // no geometry: the node stays empty
    const bool coloured = !vm.face_colors.empty();
    const std::size_t mat = coloured ? material("body (face colours)", {1, 1, 1}, options_.body_opacity, false)
                                     : material("body " + hex(body.color), body.color, options_.body_opacity, false);
    const auto key = std::make_pair(m, mat);
    if (const auto it = meshes_.find(key); it != meshes_.end()) return it->second;
    const Geometry& g = body_geometry(m);
    json attributes{{"POSITION", g.position}};
    if (g.color) attributes["COLOR_0"] = *g.color;
    json mesh{{"name", "mesh " + std::to_string(m)},
              {"primitives", json::array({{{"attributes", attributes}, {"indices", g.indices}, {"mode", kTriangles}, {"material", mat}}})},
              {"extras", {{"source_triangles", vm.source_triangles}, {"decimation_error", vm.decimation_error}}}};
    j_["meshes"].push_back(mesh);
    return meshes_[key] = j_["meshes"].size() - 1;
  }

  std::size_t add_node(json node) {
    j_["nodes"].push_back(std::move(node));
    return j_["nodes"].size() - 1;
  }

  static std::string body_name(const ViewBody& b, std::size_t i) {
    return !b.name.empty() ? b.name : !b.id.empty() ? b.id : "body " + std::to_string(i);
  }

  std::size_t body_node(std::size_t b) {
    const ViewBody& body = doc_.bodies[b];
    const std::string name = body_name(body, b);
    json node{{"name", name}};
    node["extras"] = {{"id", body.id}, {"path", body.path}, {"role", body.role}, {"tags", body.tags}, {"visible", body.visible}};
    const bool rigid_motion = animate_ && !body.frame_poses.empty() && body.pose.is_rigid() &&
                              std::all_of(body.frame_poses.begin(), body.frame_poses.end(), [](const Transform& t) { return t.is_rigid(); });
    if (animate_ && !body.frame_poses.empty()) node["extras"]["animated"] = rigid_motion;
    if (rigid_motion) {
      node["translation"] = {body.pose.t.x, body.pose.t.y, body.pose.t.z};
      node["rotation"] = quaternion(body.pose);
    } else if (!body.pose.is_identity()) {
      node["matrix"] = column_major(body.pose);
    }
    // A deforming body: one child per mesh it draws, shown (scale 1) in the frames that draw it.
    const bool deforming = animate_ && std::any_of(body.frame_meshes.begin(), body.frame_meshes.end(),
                                                   [&](std::uint32_t m) { return m != body.mesh; });
    std::vector<std::uint32_t> drawn{body.mesh};
    if (deforming)
      for (std::uint32_t m : body.frame_meshes)
        if (std::find(drawn.begin(), drawn.end(), m) == drawn.end()) drawn.push_back(m);
    if (!deforming) {
      if (const auto mesh = body_mesh(body.mesh, body)) node["mesh"] = *mesh;
      else node["extras"]["geometry"] = "none";
    }
    const std::size_t index = add_node(node);
    if (rigid_motion) {
      std::vector<float> t, r;
      for (const Transform& pose : body.frame_poses) {
        t.insert(t.end(), {static_cast<float>(pose.t.x), static_cast<float>(pose.t.y), static_cast<float>(pose.t.z)});
        for (double x : quaternion(pose)) r.push_back(static_cast<float>(x));
      }
      channel(index, "translation", t, 3, "VEC3");
      channel(index, "rotation", r, 4, "VEC4");
    }
    if (deforming) {
      j_["nodes"][index]["children"] = json::array();
      for (std::uint32_t m : drawn) {
        json child{{"name", name + " mesh " + std::to_string(m)}, {"extras", {{"id", body.id}, {"mesh", m}}}};
        if (const auto mesh = body_mesh(m, body)) child["mesh"] = *mesh;
        if (m != body.mesh) child["scale"] = {0.0, 0.0, 0.0};
        const std::size_t c = add_node(child);
        j_["nodes"][index]["children"].push_back(c);
        std::vector<float> s;
        for (std::uint32_t fm : body.frame_meshes) s.insert(s.end(), 3, fm == m ? 1.0f : 0.0f);
        channel(c, "scale", s, 3, "VEC3");
      }
    }
    return index;
  }

  // ---- clashes ----
  std::size_t line_mesh(const std::string& name, const std::vector<std::vector<Vec3>>& lines, const Vec3& offset,
                        std::size_t mat) {
    std::vector<Vec3> points;
    std::vector<std::uint32_t> idx;
    for (const auto& line : lines) {
      if (line.size() < 2) continue;
      const auto first = static_cast<std::uint32_t>(points.size());
      points.insert(points.end(), line.begin(), line.end());
      for (std::uint32_t i = 0; i + 1 < line.size(); ++i) idx.insert(idx.end(), {first + i, first + i + 1});
    }
    const std::size_t pos = positions(points, offset);
    json mesh{{"name", name},
              {"primitives", json::array({{{"attributes", {{"POSITION", pos}}}, {"indices", indices(idx)}, {"mode", kLines}, {"material", mat}}})}};
    j_["meshes"].push_back(mesh);
    return j_["meshes"].size() - 1;
  }

  std::size_t clash_node(std::size_t c) {
    const ViewClash& clash = doc_.clashes[c];
    const std::string id = clash.id.empty() ? "clash " + std::to_string(c) : clash.id;
    const ViewBody &a = doc_.bodies[clash.body_a], &b = doc_.bodies[clash.body_b];
    json extras{{"clash_id", id},
                {"verdict", clash.verdict},
                {"status", clash.status},
                {"kind", clash.kind},
                {"depth", number_or_null(clash.depth)},
                {"depth_bound", number_or_null(clash.depth_bound)},
                {"distance", number_or_null(clash.distance)},
                {"bodies", json::array({a.id, b.id})},
                {"body_names", json::array({body_name(a, clash.body_a), body_name(b, clash.body_b)})},
                {"point", {clash.point.x, clash.point.y, clash.point.z}},
                {"note", clash.note},
                {"frames", clash.frames}};
    // Geometry relative to the clash point (the node's translation), so float32 keeps its precision.
    const Vec3 at = clash.point;
    json node{{"name", id}, {"extras", extras}, {"children", json::array()}};
    if (at != Vec3{}) node["translation"] = {at.x, at.y, at.z};
    std::vector<json> children;
    const json child_extras{{"clash_id", id}, {"verdict", clash.verdict}};
    if (clash.region_mesh >= 0 && doc_.meshes[static_cast<std::size_t>(clash.region_mesh)].mesh.num_triangles() > 0) {
      const TriMesh& region = doc_.meshes[static_cast<std::size_t>(clash.region_mesh)].mesh;
      std::vector<std::uint32_t> idx;
      for (const Tri& t : region.triangles) idx.insert(idx.end(), t.begin(), t.end());
      const std::string what = clash.verdict == "contact" ? "contact region" : clash.verdict == "clash" ? "clash region" : clash.verdict + " region";
      const std::size_t mat = material(what, region_colour(clash.verdict), 1, false);
      const std::size_t pos = positions(region.positions, at);
      j_["meshes"].push_back({{"name", id + " region"},
                              {"primitives", json::array({{{"attributes", {{"POSITION", pos}}}, {"indices", indices(idx)}, {"mode", kTriangles}, {"material", mat}}})}});
      children.push_back({{"name", id + " region"}, {"mesh", j_["meshes"].size() - 1}, {"extras", child_extras}});
    }
    if (std::any_of(clash.curves.begin(), clash.curves.end(), [](const auto& l) { return l.size() >= 2; }))
      children.push_back({{"name", id + " curves"},
                          {"mesh", line_mesh(id + " curves", clash.curves, at, material("intersection curve", kCurveYellow, 1, true))},
                          {"extras", child_extras}});
    if (clash.has_witness)
      children.push_back({{"name", id + " witness"},
                          {"mesh", line_mesh(id + " witness", {{clash.witness_a, clash.witness_b}}, at,
                                             material("clearance witness", kWitnessBlue, 1, true))},
                          {"extras", child_extras}});
    if (children.empty()) node.erase("children");
    const std::size_t index = add_node(node);
    for (json& child : children) j_["nodes"][index]["children"].push_back(add_node(std::move(child)));
    if (animate_ && !clash.frames.empty()) {
      std::vector<float> s;
      for (std::size_t k = 0; k < detail::frame_count(doc_); ++k) {
        const bool present = std::find(clash.frames.begin(), clash.frames.end(), k) != clash.frames.end();
        s.insert(s.end(), 3, present ? 1.0f : 0.0f);
      }
      channel(index, "scale", s, 3, "VEC3");
    }
    return index;
  }

  // ---- frames ----
  void setup_frames() {
    const std::size_t frames = detail::frame_count(doc_);
    animate_ = options_.animation && frames > 0;
    if (!animate_) return;
    // glTF key times are seconds, >= 0 and strictly increasing (§3.11): frames.times when they are,
    // the frame index otherwise.
    const auto& t = doc_.frames.times;
    bool usable = t.size() == frames && t[0] >= 0;
    for (std::size_t k = 1; usable && k < t.size(); ++k) usable = static_cast<float>(t[k]) > static_cast<float>(t[k - 1]);
    std::vector<float> times(frames);
    for (std::size_t k = 0; k < frames; ++k) times[k] = usable ? static_cast<float>(t[k]) : static_cast<float>(k);
    times_ = floats(times, 1, "SCALAR", std::nullopt, true);
  }

  void channel(std::size_t node, const char* path, const std::vector<float>& values, int width, const char* type) {
    const std::size_t output = floats(values, width, type, std::nullopt, false);
    samplers_.push_back({{"input", times_}, {"output", output}, {"interpolation", "STEP"}});
    channels_.push_back({{"sampler", samplers_.size() - 1}, {"target", {{"node", node}, {"path", path}}}});
  }

  double metres_per_unit() const {
    const std::optional<double> mm = millimetres_per_unit(doc_.units);
    return mm ? *mm * 1e-3 : 0;  // unknown: no scaling
  }

  json scene_extras(double scale) const {
    json e{{"schema", kViewerSchema}, {"schema_version", kViewerSchemaVersion}, {"title", doc_.title}, {"command", doc_.command},
           {"tool_version", doc_.tool_version}, {"units", doc_.units}};
    if (scale > 0) e["metres_per_unit"] = scale;
    e["verdict"] = doc_.verdict;
    e["notes"] = doc_.notes;
    if (detail::frame_count(doc_) > 0) {
      e["frames"] = {{"labels", doc_.frames.labels}, {"times", doc_.frames.times}, {"verdicts", doc_.frames.verdicts}};
    }
    json legend = json::array();
    for (const LegendEntry& l : doc_.legend) legend.push_back({{"label", l.label}, {"color", json::array({factor(l.color[0]), factor(l.color[1]), factor(l.color[2])})}});
    e["legend"] = legend;
    return e;
  }

  const Document& doc_;
  const GltfOptions& options_;
  json j_;
  std::string bin_;
  std::map<std::string, std::size_t> materials_;
  std::map<std::uint32_t, Geometry> geometry_;
  std::map<std::pair<std::uint32_t, std::size_t>, std::size_t> meshes_;
  bool unlit_used_ = false;
  bool animate_ = false;
  std::size_t times_ = 0;
  json channels_ = json::array(), samplers_ = json::array();
};

}  // namespace

Status write_glb(const std::filesystem::path& path, const Document& doc, const GltfOptions& options) {
  const std::string file = path.string();
  if (!(options.body_opacity >= 0 && options.body_opacity <= 1))
    return Error{.file = file, .reason = "glTF: body opacity " + short_number(options.body_opacity) + " is not in [0, 1]"};
  if (const std::string bad = detail::check_for_export(doc); !bad.empty()) return Error{.file = file, .reason = "glTF: " + bad};
  SceneWriter writer(doc, options);
  const json j = writer.build();
  // Text that is not valid UTF-8 (a file name, a product path) is written with U+FFFD in its place.
  return write_glb_container(path, j.dump(-1, ' ', false, json::error_handler_t::replace), writer.take_bin());
}

}  // namespace interfere::view
