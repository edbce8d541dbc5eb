// A scene clash run as a viewer document (include/interfere/view/scene_document.h; issue #25, item 1).
#include "interfere/view/scene_document.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <map>
#include <memory>
#include <utility>

#include "interfere/core/error.h"
#include "interfere/query/verdict.h"

namespace interfere::view {
namespace {

using nlohmann::json;
using scene::Body;
using scene::Scene;
using scene::SceneClash;

/// The motion of one body: its pose and local positions in each frame (carried forward from the
/// previous frame where a frame does not list it; initially the scene's).
struct BodyMotion {
  std::vector<Transform> poses;                               ///< per frame; empty: never moves
  std::vector<const std::vector<Vec3>*> shapes;               ///< per frame (null: the mesh's); empty: never deforms
};

std::vector<BodyMotion> body_motions(const Scene& s) {
  std::vector<BodyMotion> m(s.bodies.size());
  const std::size_t nf = s.frames.size();
  std::vector<bool> moves(s.bodies.size(), false), deforms(s.bodies.size(), false);
  for (const scene::Frame& f : s.frames) {
    for (const scene::Frame::Pose& p : f.poses)
      if (p.body < s.bodies.size()) moves[p.body] = true;
    for (const scene::Frame::Shape& sh : f.shapes)
      if (sh.body < s.bodies.size() && sh.positions) deforms[sh.body] = true;
  }
  std::vector<Transform> pose(s.bodies.size());
  std::vector<const std::vector<Vec3>*> shape(s.bodies.size(), nullptr);
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    pose[b] = s.bodies[b].pose;
    if (moves[b]) m[b].poses.resize(nf);
    if (deforms[b]) m[b].shapes.resize(nf);
  }
  for (std::size_t f = 0; f < nf; ++f) {
    for (const scene::Frame::Pose& p : s.frames[f].poses)
      if (p.body < s.bodies.size()) pose[p.body] = p.pose;
    for (const scene::Frame::Shape& sh : s.frames[f].shapes)
      if (sh.body < s.bodies.size() && sh.positions) shape[sh.body] = sh.positions.get();
    for (std::size_t b = 0; b < s.bodies.size(); ++b) {
      if (moves[b]) m[b].poses[f] = pose[b];
      if (deforms[b]) m[b].shapes[f] = shape[b];
    }
  }
  return m;
}

// A fixed palette (muted: greys, greens, teals, violets, browns), none near the highlight colours.
constexpr std::array<Rgb, 10> kPalette{{{0.62f, 0.66f, 0.72f},
                                        {0.55f, 0.68f, 0.56f},
                                        {0.50f, 0.66f, 0.68f},
                                        {0.64f, 0.58f, 0.72f},
                                        {0.68f, 0.60f, 0.50f},
                                        {0.72f, 0.72f, 0.62f},
                                        {0.46f, 0.54f, 0.62f},
                                        {0.60f, 0.70f, 0.64f},
                                        {0.70f, 0.62f, 0.66f},
                                        {0.56f, 0.56f, 0.56f}}};

std::string user_string(const SceneClash& c, const std::string& key) {
  const auto it = c.user_fields.find(key);
  if (it == c.user_fields.end()) return "";
  const json v = json::parse(it->second, nullptr, false);
  if (v.is_discarded()) return "";
  return v.is_string() ? v.get<std::string>() : v.dump();
}

bool read_vec(const json& j, Vec3& out) {
  if (!j.is_array() || j.size() != 3) return false;
  for (std::size_t k = 0; k < 3; ++k) {
    if (!j[k].is_number()) return false;
    out[k] = j[k].get<double>();
  }
  return is_finite(out);
}

std::string body_id_of(const json& clash, const char* key) {
  if (!clash.contains(key) || !clash[key].is_object()) return "";
  const json& b = clash[key];
  return b.contains("id") && b["id"].is_string() ? b["id"].get<std::string>() : "";
}

/// A resolved baseline clash as a row, when both its bodies are in the scene.
bool resolved_row(const Scene& s, const SceneClash& r, ViewClash& out) {
  const json j = json::parse(r.baseline_json, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return false;
  const std::int64_t a = s.find(body_id_of(j, "body_a")), b = s.find(body_id_of(j, "body_b"));
  if (a < 0 || b < 0) return false;
  out.id = r.id;
  out.body_a = static_cast<std::uint32_t>(a), out.body_b = static_cast<std::uint32_t>(b);
  const std::string verdict = j.contains("verdict") && j["verdict"].is_string() ? j["verdict"].get<std::string>() : "";
  out.verdict = verdict == "contact" || verdict == "clearance" || verdict == "undecided" ? verdict : "clash";
  const std::string user = user_string(r, "status");
  out.status = user.empty() ? "resolved" : user;
  out.kind = r.kind;
  const auto num = [&](const char* k) { return j.contains(k) && j[k].is_number() ? j[k].get<double>() : -1.0; };
  out.depth = num("depth"), out.depth_bound = num("depth_bound"), out.distance = num("distance");
  if (out.verdict == "clearance") out.depth = out.depth_bound = -1;
  else out.distance = -1;
  if (j.contains("point")) read_vec(j["point"], out.point);
  out.box_min = out.box_max = out.point;
  if (j.contains("box") && j["box"].is_object() && j["box"].contains("min") && j["box"].contains("max")) {
    Vec3 lo, hi;
    if (read_vec(j["box"]["min"], lo) && read_vec(j["box"]["max"], hi)) out.box_min = lo, out.box_max = hi;
  }
  if (j.contains("curves") && j["curves"].is_array())
    for (const json& curve : j["curves"]) {
      if (!curve.is_object() || !curve.contains("points") || !curve["points"].is_array()) continue;
      std::vector<Vec3> pts;
      for (const json& p : curve["points"]) {
        Vec3 v;
        if (read_vec(p, v)) pts.push_back(v);
      }
      if (pts.size() >= 2) out.curves.push_back(std::move(pts));
    }
  out.note = "resolved: in the baseline, not found now";
  return true;
}

}  // namespace

Rgb body_color(std::size_t index) { return kPalette[index % kPalette.size()]; }

Document scene_document(const Scene& s, const std::vector<scene::ClashTest>& tests, const scene::SceneClashResult& result,
                        const SceneDocumentOptions& options) {
  Document doc;
  doc.units = s.units;
  doc.command = options.command;
  doc.tool_version = options.tool_version;
  doc.verdict = verdict_name(result.verdict);
  doc.title = !options.title.empty() ? options.title
                                     : "interfere clash: " + std::to_string(s.bodies.size()) + " bodies, " +
                                           std::to_string(result.clashes.size()) + " clashes";
  const std::size_t nf = s.frames.size();

  // Meshes: one per distinct local mesh (instances share), one per deformed shape.
  std::map<std::pair<const TriMesh*, const void*>, std::uint32_t> mesh_index;
  const auto add_mesh = [&](ViewMesh m) {
    doc.meshes.push_back(std::move(m));
    return static_cast<std::uint32_t>(doc.meshes.size() - 1);
  };
  const std::vector<BodyMotion> motion = body_motions(s);
  std::vector<std::size_t> users;  // bodies drawing each mesh
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    const Body& body = s.bodies[b];
    ViewBody vb;
    vb.id = body.id, vb.name = body.name, vb.path = body.path, vb.tags = body.tags;
    vb.pose = body.pose;
    vb.color = body_color(b);
    const TriMesh* mesh = body.mesh.get();
    const auto key = std::make_pair(mesh, static_cast<const void*>(body.source_ids.get()));
    auto it = mesh_index.find(key);
    if (it == mesh_index.end()) {
      ViewMesh vm;
      if (mesh) vm.mesh = *mesh;
      else doc.notes.push_back("body '" + body.id + "' has no geometry: nothing to draw");
      vm.source_triangles = vm.mesh.num_triangles();
      if (body.source_ids && body.source_ids->size() == vm.mesh.num_triangles()) vm.source_ids = *body.source_ids;
      it = mesh_index.emplace(key, add_mesh(std::move(vm))).first;
    }
    vb.mesh = it->second;
    vb.frame_poses = motion[b].poses;
    if (!motion[b].shapes.empty() && mesh) {
      vb.frame_meshes.resize(nf);
      for (std::size_t f = 0; f < nf; ++f) {
        const std::vector<Vec3>* shape = motion[b].shapes[f];
        if (!shape) {
          vb.frame_meshes[f] = vb.mesh;
          continue;
        }
        const auto skey = std::make_pair(mesh, static_cast<const void*>(shape));
        auto sit = mesh_index.find(skey);
        if (sit == mesh_index.end()) {
          ViewMesh vm;
          vm.mesh.positions = *shape;
          vm.mesh.triangles = mesh->triangles;
          vm.source_triangles = vm.mesh.num_triangles();
          vm.source_ids = doc.meshes[vb.mesh].source_ids;
          sit = mesh_index.emplace(skey, add_mesh(std::move(vm))).first;
        }
        vb.frame_meshes[f] = sit->second;
      }
    }
    doc.bodies.push_back(std::move(vb));
  }
  const auto count_users = [&] {
    users.assign(doc.meshes.size(), 0);
    for (const ViewBody& vb : doc.bodies) {
      std::vector<std::uint32_t> drawn = vb.frame_meshes;
      drawn.push_back(vb.mesh);
      std::sort(drawn.begin(), drawn.end());
      drawn.erase(std::unique(drawn.begin(), drawn.end()), drawn.end());
      for (const std::uint32_t m : drawn) ++users[m];
    }
  };
  count_users();

  // Clashing instances of shared meshes get their own copy (flag_instances).
  if (options.flag_instances) {
    std::vector<bool> clashing(doc.bodies.size(), false);
    for (const SceneClash& c : result.clashes) {
      if (c.a < clashing.size() && !c.triangles_a.empty()) clashing[c.a] = true;
      if (c.b < clashing.size() && !c.triangles_b.empty()) clashing[c.b] = true;
    }
    for (std::size_t b = 0; b < doc.bodies.size(); ++b)
      if (clashing[b] && users[doc.bodies[b].mesh] > 1) {
        const std::uint32_t shared = doc.bodies[b].mesh;
        ViewMesh copy = doc.meshes[shared];
        doc.bodies[b].mesh = add_mesh(std::move(copy));
        for (std::uint32_t& fm : doc.bodies[b].frame_meshes)
          if (fm == shared) fm = doc.bodies[b].mesh;
        --users[shared];  // (the last clashing user of a mesh keeps it)
        users.push_back(1);
      }
  }

  // Per-triangle clash flags on the meshes one body draws: the static mesh, and a deformed frame
  // mesh where the clash is present in a frame that draws it.
  const auto flag = [&](std::uint32_t body, const std::vector<std::uint32_t>& tris, const std::vector<std::uint32_t>& frames,
                        std::int32_t index) {
    const ViewBody& vb = doc.bodies[body];
    const auto mark = [&](std::uint32_t m) {
      if (users[m] != 1) return;
      ViewMesh& vm = doc.meshes[m];
      vm.clash_flags.resize(vm.mesh.num_triangles(), 0);
      vm.clash_region.resize(vm.mesh.num_triangles(), -1);
      for (const std::uint32_t t : tris)
        if (t < vm.clash_flags.size()) {
          vm.clash_flags[t] = 1;
          if (vm.clash_region[t] < 0) vm.clash_region[t] = index;  // (the first clash listing it)
        }
    };
    mark(vb.mesh);
    if (vb.frame_meshes.empty()) return;
    if (frames.empty()) {
      for (const std::uint32_t m : vb.frame_meshes)
        if (m != vb.mesh) mark(m);
    } else {
      for (const std::uint32_t f : frames)
        if (f < vb.frame_meshes.size() && vb.frame_meshes[f] != vb.mesh) mark(vb.frame_meshes[f]);
    }
  };
  std::int32_t clash_index = 0;  // (the index the clash gets in doc.clashes below)
  for (const SceneClash& c : result.clashes) {
    if (c.a >= doc.bodies.size() || c.b >= doc.bodies.size()) continue;
    flag(c.a, c.triangles_a, c.frames, clash_index);
    flag(c.b, c.triangles_b, c.frames, clash_index);
    ++clash_index;
  }

  // Penetration depth per vertex (SceneClashResult::depth_maps; issue #26, item 3) on a mesh of its
  // own for each (body, frame) that has one: a mesh drawn by other bodies or other frames is
  // copied first, so each frame shows its own depths; 0 elsewhere on that mesh.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> depth_mesh;  // (body, frame) -> mesh
  const auto mesh_with_depth = [&](std::uint32_t body, std::uint32_t frame) -> ViewMesh& {
    const auto key = std::make_pair(body, frame);
    if (const auto it = depth_mesh.find(key); it != depth_mesh.end()) return doc.meshes[it->second];
    ViewBody& vb = doc.bodies[body];
    std::uint32_t* slot = &vb.mesh;
    if (nf > 0) {
      if (vb.frame_meshes.empty()) vb.frame_meshes.assign(nf, vb.mesh);
      slot = &vb.frame_meshes[std::min<std::size_t>(frame, nf - 1)];
    }
    const std::uint32_t m = *slot;
    const bool shared = users[m] != 1 || (nf > 0 && (m == vb.mesh || std::count(vb.frame_meshes.begin(), vb.frame_meshes.end(), m) > 1));
    if (shared) {
      ViewMesh copy = doc.meshes[m];
      copy.point_depth.clear();
      *slot = add_mesh(std::move(copy));
      users.push_back(1);
    }
    ViewMesh& vm = doc.meshes[*slot];
    vm.point_depth.assign(vm.mesh.num_vertices(), 0.0);
    depth_mesh.emplace(key, *slot);
    return vm;
  };
  if (!result.depth_maps.empty())  // depth known: 0 outside the other bodies
    for (ViewMesh& vm : doc.meshes)
      if (vm.point_depth.empty()) vm.point_depth.assign(vm.mesh.num_vertices(), 0.0);
  for (const scene::PairDepthMap& pm : result.depth_maps) {
    if (pm.a >= doc.bodies.size() || pm.b >= doc.bodies.size()) continue;
    for (const auto& [body, vd] : {std::pair{pm.a, &pm.a_in_b}, std::pair{pm.b, &pm.b_in_a}}) {
      if (vd->vertices.empty()) continue;
      ViewMesh& vm = mesh_with_depth(body, pm.frame);
      for (std::size_t i = 0; i < vd->vertices.size(); ++i)
        if (vd->vertices[i] < vm.point_depth.size())
          vm.point_depth[vd->vertices[i]] = std::max(vm.point_depth[vd->vertices[i]], vd->depths[i]);
    }
  }

  // The world geometry of body b's triangles `tris` at frame f (the clash's first frame).
  const auto world_triangles = [&](std::uint32_t b, std::int64_t f, const std::vector<std::uint32_t>& tris, TriMesh& out) {
    const Body& body = s.bodies[b];
    if (!body.mesh) return;
    const TriMesh& mesh = *body.mesh;
    Transform pose = body.pose;
    const std::vector<Vec3>* positions = &mesh.positions;
    if (f >= 0 && static_cast<std::size_t>(f) < nf) {
      if (!motion[b].poses.empty()) pose = motion[b].poses[static_cast<std::size_t>(f)];
      if (!motion[b].shapes.empty() && motion[b].shapes[static_cast<std::size_t>(f)])
        positions = motion[b].shapes[static_cast<std::size_t>(f)];
    }
    std::map<std::uint32_t, std::uint32_t> vertex;  // local -> region mesh
    for (const std::uint32_t t : tris) {
      if (t >= mesh.num_triangles()) continue;
      Tri tri{};
      for (std::size_t k = 0; k < 3; ++k) {
        const std::uint32_t v = mesh.triangles[t][k];
        auto [it, fresh] = vertex.emplace(v, static_cast<std::uint32_t>(out.positions.size()));
        if (fresh) out.positions.push_back(pose.apply(v < positions->size() ? (*positions)[v] : Vec3{}));
        tri[k] = it->second;
      }
      out.triangles.push_back(tri);
    }
  };

  const bool several_tests = tests.size() > 1;
  for (const SceneClash& c : result.clashes) {
    if (c.a >= doc.bodies.size() || c.b >= doc.bodies.size()) continue;
    ViewClash v;
    v.id = c.id;
    v.verdict = verdict_name(c.verdict);
    const std::string user = user_string(c, "status");
    v.status = user.empty() ? scene::clash_status_name(c.status) : user;
    v.kind = c.kind;
    v.body_a = c.a, v.body_b = c.b;
    if (c.verdict == Verdict::clearance) {
      v.distance = c.distance;
      v.has_witness = true;
      v.witness_a = c.witness_a, v.witness_b = c.witness_b;
    } else if (c.depth_bound > 0) {  // measured (crossings of closed bodies)
      v.depth = c.depth, v.depth_bound = c.depth_bound;
    } else if (c.kind == "touch") {
      v.distance = 0;
    }
    v.point = c.point;
    if (c.box.empty()) v.box_min = v.box_max = c.point;
    else v.box_min = c.box.lo, v.box_max = c.box.hi;
    for (const Polyline& l : c.curves) {
      std::vector<Vec3> pts = l.points;
      if (l.closed && !pts.empty()) pts.push_back(pts.front());
      if (!pts.empty()) v.curves.push_back(std::move(pts));
    }
    // Regions of crossing and touching triangles; an inner body or a duplicate (all its triangles)
    // is shown by the body itself.
    if (options.regions && c.kind != "inside" && c.kind != "duplicate" && (!c.triangles_a.empty() || !c.triangles_b.empty())) {
      ViewMesh region;
      const std::int64_t f = c.frames.empty() ? -1 : static_cast<std::int64_t>(c.frames.front());
      world_triangles(c.a, f, c.triangles_a, region.mesh);
      world_triangles(c.b, f, c.triangles_b, region.mesh);
      region.source_triangles = region.mesh.num_triangles();
      if (region.mesh.num_triangles() > 0) v.region_mesh = add_mesh(std::move(region));
    }
    v.frames = c.frames;
    std::string note;
    if (several_tests) note = "test " + c.test;
    for (const std::string& r : c.reasons) note += (note.empty() ? "" : "; ") + r;
    const std::string comment = user_string(c, "comment"), assignee = user_string(c, "assignee");
    if (!assignee.empty()) note += (note.empty() ? "" : "; ") + std::string("assignee: ") + assignee;
    if (!comment.empty()) note += (note.empty() ? "" : "; ") + std::string("comment: ") + comment;
    v.note = std::move(note);
    doc.clashes.push_back(std::move(v));
  }
  if (options.resolved) {
    std::size_t missing = 0;
    for (const SceneClash& r : result.resolved) {
      ViewClash v;
      if (resolved_row(s, r, v)) doc.clashes.push_back(std::move(v));
      else ++missing;
    }
    if (missing > 0)
      doc.notes.push_back(std::to_string(missing) + " resolved clash(es) of the baseline not drawn: their bodies are not in this scene");
  }

  // Frames: labels and times from the scene's motion, verdicts from the frames table.
  if (nf > 0) {
    doc.frames.labels.resize(nf);
    doc.frames.times.resize(nf);
    doc.frames.verdicts.assign(nf, verdict_name(Verdict::clear));
    for (std::size_t f = 0; f < nf; ++f) {
      doc.frames.labels[f] = s.frames[f].label.empty() ? "frame " + std::to_string(f) : s.frames[f].label;
      doc.frames.times[f] = s.frames[f].time;
    }
    for (const scene::FrameRow& row : result.frames)
      if (row.frame < nf) doc.frames.verdicts[row.frame] = verdict_name(row.verdict);
  }
  for (const std::string& w : result.warnings) doc.notes.push_back(w);
  return doc;
}

}  // namespace interfere::view
