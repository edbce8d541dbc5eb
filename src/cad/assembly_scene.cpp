// A STEP assembly as a scene (include/interfere/cad/assembly_scene.h): one body per instance, and
// assembly-clash's nominal-fit check (assembly_fit.cpp) as the scene engine's hook.
#include "interfere/cad/assembly_scene.h"

#include <cmath>
#include <map>
#include <memory>

#include "assembly_clash_internal.h"
#include "interfere/cad/assembly_clash.h"
#include "interfere/core/units.h"
#include "interfere/mesh/validate.h"

namespace interfere::cad {

scene::Scene assembly_scene(const CadModel& model) {
  scene::Scene s;
  s.units = model.units;
  s.warnings = model.warnings;
  // Per part, once: the tessellation welded (faces meeting along shared edges: a closed solid is
  // closed; triangles keep their order, so face_ids still apply) and its B-Rep faces, 1-based.
  std::vector<std::shared_ptr<const TriMesh>> meshes(model.parts.size());
  std::vector<std::shared_ptr<const std::vector<std::int64_t>>> faces(model.parts.size());
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    TriMesh m = model.parts[p].mesh;
    weld_exact(m);
    meshes[p] = std::make_shared<const TriMesh>(std::move(m));
    if (model.parts[p].face_ids.size() == model.parts[p].mesh.num_triangles()) {
      auto ids = std::make_shared<std::vector<std::int64_t>>(model.parts[p].face_ids.begin(),
                                                             model.parts[p].face_ids.end());
      for (std::int64_t& f : *ids) ++f;
      faces[p] = std::move(ids);
    }
  }
  s.bodies.reserve(model.instances.size());
  for (const Instance& in : model.instances) {
    const Part& part = model.parts[in.part];
    scene::Body b;
    b.path = in.path.empty() ? "/" + in.name : in.path;
    b.id = scene::make_body_id(b.path);
    b.name = in.name;
    b.source = {.kind = scene::SourceKind::step_instance, .file = model.file, .detail = b.path};
    b.unit = model.units;
    b.mesh = meshes[in.part];
    b.pose = in.placement;
    if (faces[in.part]) {
      b.source_id_kind = scene::SourceIdKind::brep_face;
      b.source_ids = faces[in.part];
    }
    b.tessellation_error = part.tessellation_error();
    s.bodies.push_back(std::move(b));
  }
  scene::make_ids_unique(s);
  return s;
}

namespace {

// Where a body's part lies in the world: two triangles' corners of its mesh (the largest
// triangle, and a vertex farthest from its plane) and their images in the world model, from which
// a rigid placement is recovered.
struct Anchor {
  std::uint32_t tri = 0;                      // the largest triangle
  std::uint32_t far_tri = 0, far_corner = 0;  // the vertex farthest from its plane
  bool ok = false;                            // the four points span space
};

Anchor anchor_of(const TriMesh& m) {
  Anchor a;
  double best = -1;
  for (std::uint32_t t = 0; t < m.num_triangles(); ++t) {
    const auto c = m.corners(t);
    const double area = norm(cross(c[1] - c[0], c[2] - c[0]));
    if (area > best) best = area, a.tri = t;
  }
  if (!(best > 0)) return a;
  const auto c = m.corners(a.tri);
  const Vec3 n = cross(c[1] - c[0], c[2] - c[0]);
  double far = 0;
  for (std::uint32_t t = 0; t < m.num_triangles(); ++t) {
    const auto d = m.corners(t);
    for (std::uint32_t k = 0; k < 3; ++k)
      if (const double h = std::fabs(dot(n, d[k] - c[0])); h > far)
        far = h, a.far_tri = t, a.far_corner = k;
  }
  a.ok = far > 0;
  return a;
}

// The affine map taking the anchor's four points of `local` to those of `world` (same triangles),
// or nothing when they are degenerate there.
bool placement_from(const Anchor& an, const TriMesh& local, const TriMesh& world, Transform& out) {
  if (!an.ok || world.num_triangles() != local.num_triangles()) return false;
  const auto pl = local.corners(an.tri), pw = world.corners(an.tri);
  const Vec3 p[4] = {pl[0], pl[1], pl[2], local.corners(an.far_tri)[an.far_corner]};
  const Vec3 q[4] = {pw[0], pw[1], pw[2], world.corners(an.far_tri)[an.far_corner]};
  // A = Q P^-1 with P = [p1-p0 p2-p0 p3-p0] (columns), Q likewise; P^-1 by its adjugate.
  const Vec3 e1 = p[1] - p[0], e2 = p[2] - p[0], e3 = p[3] - p[0];
  const double det = dot(e1, cross(e2, e3));
  if (!(std::fabs(det) > 0) || !std::isfinite(det)) return false;
  const Vec3 rows[3] = {cross(e2, e3) / det, cross(e3, e1) / det,
                        cross(e1, e2) / det};  // rows of P^-1
  const Vec3 f1 = q[1] - q[0], f2 = q[2] - q[0], f3 = q[3] - q[0];
  const double fq[3][3] = {{f1.x, f2.x, f3.x}, {f1.y, f2.y, f3.y}, {f1.z, f2.z, f3.z}};
  for (int i = 0; i < 3; ++i) {
    const Vec3 ri{fq[i][0], fq[i][1], fq[i][2]};
    out.r[i] = {ri.x * rows[0].x + ri.y * rows[1].x + ri.z * rows[2].x,
                ri.x * rows[0].y + ri.y * rows[1].y + ri.z * rows[2].y,
                ri.x * rows[0].z + ri.y * rows[1].z + ri.z * rows[2].z};
  }
  out.t = q[0] - out.apply(p[0]);
  return true;
}

// Body -> instance of `model` (by the instance path assembly_scene puts in the source; -1: a body
// not from `model`, or whose mesh is not its part's tessellation).
std::vector<std::int64_t> instances_of_bodies(const CadModel& model, const scene::Scene& s) {
  std::map<std::string, std::uint32_t> by_path;
  for (std::uint32_t i = 0; i < model.instances.size(); ++i)
    by_path.emplace(
        model.instances[i].path.empty() ? "/" + model.instances[i].name : model.instances[i].path,
        i);
  std::vector<std::int64_t> instance(s.bodies.size(), -1);
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    const scene::Body& body = s.bodies[b];
    if (body.source.kind != scene::SourceKind::step_instance || body.source.file != model.file ||
        !body.mesh)
      continue;
    const auto it = by_path.find(body.source.detail);
    if (it == by_path.end()) continue;
    if (body.mesh->num_triangles() != model.parts[model.instances[it->second].part].face_ids.size())
      continue;
    instance[b] = it->second;
  }
  return instance;
}

}  // namespace

std::function<bool(std::uint32_t, std::uint32_t, const Model&, const Model&, const ClashResult&,
                   double)>
nominal_fit_check(const CadModel& model, const scene::Scene& s) {
  auto instance = std::make_shared<std::vector<std::int64_t>>(instances_of_bodies(model, s));
  auto anchors = std::make_shared<std::map<const TriMesh*, Anchor>>();
  for (std::size_t b = 0; b < s.bodies.size(); ++b)
    if ((*instance)[b] >= 0 && !anchors->count(s.bodies[b].mesh.get()))
      (*anchors)[s.bodies[b].mesh.get()] = anchor_of(*s.bodies[b].mesh);
  return [&model, &s, instance, anchors](std::uint32_t a, std::uint32_t b, const Model& wa,
                                         const Model& wb, const ClashResult& r, double depth) {
    if (a >= instance->size() || b >= instance->size() || (*instance)[a] < 0 || (*instance)[b] < 0)
      return false;
    // Where each body is: its pose when the world model is its image (no frame moved it), else
    // the placement recovered from its mesh and world model; rigid only (the AAG's radii and
    // angles are the part's).
    const auto place = [&](std::uint32_t body, const Model& w, Transform& t) {
      const scene::Body& bd = s.bodies[body];
      const Anchor& an = anchors->at(bd.mesh.get());
      if (!an.ok || w.mesh.num_triangles() != bd.mesh->num_triangles()) return false;
      const auto pl = bd.mesh->corners(an.tri), pw = w.mesh.corners(an.tri);
      const Vec3 fl = bd.mesh->corners(an.far_tri)[an.far_corner],
                 fw = w.mesh.corners(an.far_tri)[an.far_corner];
      if (bd.pose.apply(pl[0]) == pw[0] && bd.pose.apply(pl[1]) == pw[1] &&
          bd.pose.apply(pl[2]) == pw[2] && bd.pose.apply(fl) == fw)
        t = bd.pose;
      else if (!placement_from(an, *bd.mesh, w.mesh, t))
        return false;
      return t.is_rigid();
    };
    Transform ta, tb;
    if (!place(a, wa, ta) || !place(b, wb, tb)) return false;
    const Part& pa = model.parts[model.instances[(*instance)[a]].part];
    const Part& pb = model.parts[model.instances[(*instance)[b]].part];
    return detail::nominal_fit(pa, ta, pb, tb, wa, wb, r, depth,
                               pa.tessellation_error() + pb.tessellation_error());
  };
}

scene::SceneClashOptions::ZeroClearanceFits zero_clearance_fit_check(const CadModel& model, const scene::Scene& s) {
  const auto instance = std::make_shared<std::vector<std::int64_t>>(instances_of_bodies(model, s));
  // The bodies' poses in mm (STEP geometry is; a scene in other units scales its bodies' meshes
  // and translations by 1 / mm per unit: scene_load), rigid only.
  const double mm = millimetres_per_unit(s.units).value_or(1.0);
  auto place = std::make_shared<std::vector<Transform>>(s.bodies.size());
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    if ((*instance)[b] < 0) continue;
    Transform t = s.bodies[b].pose;
    t.t = t.t * mm;
    if (!t.is_rigid()) (*instance)[b] = -1;
    (*place)[b] = t;
  }
  scene::SceneClashOptions::ZeroClearanceFits z;
  z.reach = [&model, instance, mm](std::uint32_t b) {
    if (b >= instance->size() || (*instance)[b] < 0) return 0.0;
    return kFitTolerance * norm(model.parts[model.instances[(*instance)[b]].part].mesh.bounds().extent()) / mm;
  };
  // As assembly-clash decided them until the scene engine asked (issue #29): faces within, and
  // triangles reaching, kFitTolerance of the two parts' diagonals.
  z.check = [&model, instance, place, mm](std::uint32_t a, std::uint32_t b, double* gap) {
    if (a >= instance->size() || b >= instance->size() || (*instance)[a] < 0 || (*instance)[b] < 0) return false;
    const Part& pa = model.parts[model.instances[(*instance)[a]].part];
    const Part& pb = model.parts[model.instances[(*instance)[b]].part];
    const double tol = kFitTolerance * (norm(pa.mesh.bounds().extent()) + norm(pb.mesh.bounds().extent()));
    double g = 0;
    if (!detail::zero_clearance_fit(pa, (*place)[a], pb, (*place)[b], tol, tol, &g)) return false;
    if (gap) *gap = g / mm;
    return true;
  };
  return z;
}

}  // namespace interfere::cad
