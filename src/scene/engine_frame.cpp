// Decision frames of the scene engine (engine_internal.h, PairFrame; issue #24, item 9): a body
// pair is decided in the local frame of its first body, so that pairs in the same relative pose
// (a product's repeated joints: 14,385 candidate pairs of the 10,000-body assembly are 34 distinct
// configurations, docs/scene-benchmarks.md) are one problem bit for bit, decided once; each member
// then gets the result mapped to the world by its own pose.
#include <algorithm>
#include <utility>

#include "engine_internal.h"

namespace interfere::scene::detail {

Model moved_model(const Model& local_b, const Transform& t) {
  Model m;
  m.mesh.triangles = local_b.mesh.triangles;
  if (t.determinant_sign() < 0)  // outward stays outward (as transformed() does)
    for (Tri& f : m.mesh.triangles) std::swap(f[1], f[2]);
  m.mesh.positions.resize(local_b.mesh.positions.size());
  for (std::size_t v = 0; v < m.mesh.positions.size(); ++v) m.mesh.positions[v] = t.apply(local_b.mesh.positions[v]);
  m.bvh = local_b.bvh;  // the same topology: refitted (the boxes are the moved triangles')
  refit_bvh(m.bvh, m.mesh);
  return m;
}

namespace {

Aabb moved_box(const Aabb& box, const Transform& t) {
  Aabb w;
  if (box.empty()) return w;
  for (int c = 0; c < 8; ++c)
    w.expand(t.apply({c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y, c & 4 ? box.hi.z : box.lo.z}));
  return w;
}

}  // namespace

void place_clashes(std::vector<SceneClash>& list, const Transform& pose_a, bool keep_curves) {
  for (SceneClash& s : list) {
    s.point = pose_a.apply(s.point);
    Aabb tight;
    for (Polyline& l : s.curves)
      for (Vec3& p : l.points) p = pose_a.apply(p), tight.expand(p);
    if (s.verdict == Verdict::clearance) {
      s.witness_a = pose_a.apply(s.witness_a), s.witness_b = pose_a.apply(s.witness_b);
      tight.expand(s.witness_a), tight.expand(s.witness_b);
    }
    // (derive_pair: a crossing's box is its curves', a clearance's its witnesses'; the others'
    // come from triangle boxes or whole bodies, boxes in the frame)
    s.box = tight.empty() ? moved_box(s.box, pose_a) : tight;
    if (!keep_curves) s.curves.clear();
  }
}

void rehome(std::vector<SceneClash>& list, const Scene& scene, std::uint32_t rep_a, std::uint32_t rep_b,
            std::uint32_t a, std::uint32_t b) {
  if (rep_a == a && rep_b == b) return;
  const Body& ra = scene.bodies[rep_a];
  const Body& rb = scene.bodies[rep_b];
  const Body& ba = scene.bodies[a];
  const Body& bb = scene.bodies[b];
  // The source ids are the representative's where both bodies read them from the same tables.
  const bool same_sources = ra.source_ids == ba.source_ids && rb.source_ids == bb.source_ids;
  for (SceneClash& s : list) {
    s.a = a, s.b = b;
    if (s.kind == "inside") {
      const bool a_in = s.reasons.front() == inside_reason(ra, rb);
      s.reasons.front() = a_in ? inside_reason(ba, bb) : inside_reason(bb, ba);
    }
    if (!same_sources && !(s.triangles_a.empty() && s.triangles_b.empty())) {
      s.source_ids_a.clear(), s.source_ids_b.clear();
      set_sources(s, ba, bb);
    }
  }
}

}  // namespace interfere::scene::detail
