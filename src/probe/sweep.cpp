// Probe path checking (issue #5, items 3-5; Li, Zhou & Zheng 2008, §3.2-3.4): candidates from the
// chosen hierarchy, box rejection, the exact cylinder-triangle test at every path point, the
// clearance by best-first search over the BVH, and the conservative continuous check between
// consecutive points (motion bound + grown bodies + bisection). See sweep.h. The holder box
// (probe/box.h) is one more body: exact box-triangle test, culled as its bounding cylinder.
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <optional>
#include <queue>
#include <stdexcept>
#include <tuple>

#include <tbb/parallel_for.h>

#include "interfere/bvh/traverse.h"
#include "interfere/mesh/validate.h"
#include "interfere/probe/sweep.h"
#include "interfere/query/clash.h"

namespace interfere::probe {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// Conservative cylinder-vs-box culling for BVH nodes and triangle boxes (double, with a margin of
/// 1e-9 x the coordinate scale, far above the rounding of these few operations): the box is
/// rejected when its projection on the axis misses [0, len], or when its bounding sphere is
/// farther than r from the axis line. A tilted probe's AABB overlaps many boxes that lie beside
/// the probe; this keeps them away from the exact test.
struct CylinderCull {
  Vec3 c0, u;
  double len = 0, r = 0, margin = 0;
  explicit CylinderCull(const Cylinder& c) : c0(c.c0), r(c.radius) {
    const Vec3 d = c.c1 - c.c0;
    len = norm(d);
    u = len > 0 ? d / len : Vec3{0, 0, 1};
    const double scale = std::max({std::fabs(c.c0.x), std::fabs(c.c0.y), std::fabs(c.c0.z), std::fabs(c.c1.x),
                                   std::fabs(c.c1.y), std::fabs(c.c1.z), len, r});
    margin = 1e-9 * scale;
  }
  bool rejects(const AabbF& b) const {
    const Vec3 h{0.5 * (double(b.hi[0]) - b.lo[0]), 0.5 * (double(b.hi[1]) - b.lo[1]), 0.5 * (double(b.hi[2]) - b.lo[2])};
    const Vec3 c{0.5 * (double(b.hi[0]) + b.lo[0]), 0.5 * (double(b.hi[1]) + b.lo[1]), 0.5 * (double(b.hi[2]) + b.lo[2])};
    const Vec3 w = c - c0;
    const double t = dot(w, u);
    const double ext = h.x * std::fabs(u.x) + h.y * std::fabs(u.y) + h.z * std::fabs(u.z);
    if (t + ext < -margin || t - ext > len + margin) return true;
    const double line = norm(w - u * t);
    return line - norm(h) > r + margin;
  }
};

/// Calls f(triangle) for every triangle whose box overlaps `box` in the BVH and is not culled by
/// the cylinder; stops when f returns true (then returns true).
template <class F>
bool bvh_visit(const Bvh& bvh, const AabbF& box, const CylinderCull& cull, F&& f) {
  auto keep = [&](const AabbF& b) { return boxes_overlap(box, b, 0.0f) && !cull.rejects(b); };
  if (bvh.empty() || !keep(bvh.nodes[0].box)) return false;
  detail::SmallStack<std::uint32_t> stack;
  stack.push(0);
  while (!stack.empty()) {
    const BvhNode& n = bvh.nodes[stack.pop()];
    if (n.is_leaf()) {
      for (std::uint32_t j = n.first; j < n.first + n.count; ++j) {
        if (keep(bvh.prim_boxes[j]) && f(bvh.prims[j])) return true;
      }
    } else {
      if (keep(bvh.nodes[n.first + 1].box)) stack.push(n.first + 1);
      if (keep(bvh.nodes[n.first].box)) stack.push(n.first);
    }
  }
  return false;
}

bool box_overlap(const Aabb& a, const Aabb& b) { return a.overlaps(b); }

/// Grid candidates (sorted, unique) for `box`.
void grid_candidates(const UniformGrid& g, const Aabb& box, std::vector<std::uint32_t>& out) {
  out.clear();
  if (!box_overlap(box, g.bounds)) return;
  const int n[3] = {g.nx, g.ny, g.nz};
  int lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::clamp(static_cast<int>(std::floor((box.lo[k] - g.bounds.lo[k]) / g.cell)), 0, n[k] - 1);
    hi[k] = std::clamp(static_cast<int>(std::floor((box.hi[k] - g.bounds.lo[k]) / g.cell)), 0, n[k] - 1);
  }
  for (int z = lo[2]; z <= hi[2]; ++z) {
    for (int y = lo[1]; y <= hi[1]; ++y) {
      for (int x = lo[0]; x <= hi[0]; ++x) {
        const std::size_t c = (static_cast<std::size_t>(z) * g.ny + y) * g.nx + x;
        out.insert(out.end(), g.items.begin() + g.start[c], g.items.begin() + g.start[c + 1]);
      }
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

/// Distance field: true when the samples along the axis prove the cylinder clear of the surface.
bool field_clears(const DistanceField& f, const Cylinder& c) {
  const Vec3 d = c.c1 - c.c0;
  const double len = norm(d);
  const int n = std::max(2, static_cast<int>(std::ceil(len / f.spacing)) + 1);
  const double h = len / (n - 1);
  const double cover = std::sqrt(c.radius * c.radius + 0.25 * h * h) * (1 + 1e-9);
  for (int i = 0; i < n; ++i) {
    const Vec3 s = c.c0 + d * (double(i) / (n - 1));
    const double fx = (s.x - f.bounds.lo.x) / f.spacing, fy = (s.y - f.bounds.lo.y) / f.spacing,
                 fz = (s.z - f.bounds.lo.z) / f.spacing;
    const long ix = std::lround(fx), iy = std::lround(fy), iz = std::lround(fz);
    if (ix < 0 || iy < 0 || iz < 0 || ix >= f.nx || iy >= f.ny || iz >= f.nz) return false;
    const Vec3 node = f.bounds.lo + Vec3{ix * f.spacing, iy * f.spacing, iz * f.spacing};
    const double lower = f.values[(static_cast<std::size_t>(iz) * f.ny + iy) * f.nx + ix] - distance(s, node);
    if (!(lower > cover)) return false;
  }
  return true;
}

/// Calls f(triangle) for the candidates of `box` under the workpiece's hierarchy (box-filtered);
/// stops at the first f returning true.
template <class F>
bool for_each_candidate(const Workpiece& w, const Cylinder& cyl, const Aabb& box, F&& f) {
  switch (w.hierarchy) {
    case Hierarchy::bvh:
      return bvh_visit(w.bvh, to_float_outward(box), CylinderCull(cyl), f);
    case Hierarchy::patches:
      for (std::size_t p = 0; p < w.patches.size(); ++p) {
        if (!box_overlap(w.patches.boxes[p], box)) continue;
        for (std::uint32_t t : w.patches.tris[p]) {
          if (box_overlap(w.mesh.triangle_box(t), box) && f(t)) return true;
        }
      }
      return false;
    case Hierarchy::distance_field:
      if (field_clears(w.field, cyl)) return false;
      [[fallthrough]];
    case Hierarchy::grid: {
      thread_local std::vector<std::uint32_t> cand;
      grid_candidates(w.hierarchy == Hierarchy::grid ? w.grid : w.field.grid, box, cand);
      const std::vector<std::uint32_t> local = cand;  // f may recurse into another query
      for (std::uint32_t t : local) {
        if (box_overlap(w.mesh.triangle_box(t), box) && f(t)) return true;
      }
      return false;
    }
    case Hierarchy::brute_force:
      for (std::uint32_t t = 0; t < w.mesh.num_triangles(); ++t) {
        if (box_overlap(w.mesh.triangle_box(t), box) && f(t)) return true;
      }
      return false;
  }
  return false;
}

/// The solid bodies at one pose: the probe cylinder, the optional holder cylinder (index 1) and the
/// optional holder box.
struct Bodies {
  std::vector<Cylinder> cylinders;
  std::optional<OrientedBox> box;
};

Bodies bodies_at(const ProbeShape& s, const ProbePose& pose) {
  Bodies b{probe_cylinders(s, pose), std::nullopt};
  if (s.has_holder_box()) b.box = probe_holder_box(s, pose);
  return b;
}


/// Per-body motion bounds: the probe cylinder, the holder cylinder, the holder box (issue #28:
/// each body grown by its own bound; the probe, nearest the surface, moves least when the axis
/// turns about the tip).
struct BodyDeltas {
  std::array<double, 3> d{};
  double max() const { return std::max({d[0], d[1], d[2]}); }
};

/// Every body grown by its own bound plus `extra`.
Bodies grown_bodies(Bodies b, const BodyDeltas& delta, double extra) {
  for (std::size_t k = 0; k < b.cylinders.size(); ++k) b.cylinders[k] = grown(b.cylinders[k], delta.d[k] + extra);
  if (b.box) b.box = grown(*b.box, delta.d[2] + extra);
  return b;
}

/// Exact test of the bodies against the triangles; collects hits (or stops at the first when hits
/// is null).
bool bodies_touch(const Workpiece& w, const Bodies& bodies, std::vector<std::uint32_t>* hits, std::size_t* tests,
                  bool* holder_hit) {
  bool any = false;
  // Candidates of one body (`cull`: a cylinder containing it), tested by `touches`.
  auto body = [&](const Cylinder& cull, const Aabb& box, bool holder, auto&& touches) {
    return for_each_candidate(w, cull, box, [&](std::uint32_t t) {
      if (tests) ++*tests;
      if (!touches(w.mesh.corners(t))) return false;
      any = true;
      if (holder && holder_hit) *holder_hit = true;
      if (!hits) return true;
      hits->push_back(t);
      return false;
    });
  };
  for (std::size_t k = 0; k < bodies.cylinders.size(); ++k) {
    const Cylinder& c = bodies.cylinders[k];
    if (body(c, cylinder_box(c), k == 1, [&](const std::array<Vec3, 3>& t) { return cylinder_triangle_intersect(c, t); })) {
      return true;
    }
  }
  if (bodies.box) {
    const OrientedBox& b = *bodies.box;
    if (body(bounding_cylinder(b), box_aabb(b), true, [&](const std::array<Vec3, 3>& t) { return box_triangle_intersect(b, t); })) {
      return true;
    }
  }
  if (hits) {
    std::sort(hits->begin(), hits->end());
    hits->erase(std::unique(hits->begin(), hits->end()), hits->end());
  }
  return any;
}

/// Where bodies that touch no triangle lie: 1 in the workpiece's material, 0 outside it, -1
/// undecided (every ray direction degenerate). The bodies are connected and miss every surface, so
/// one of their points (the tip, on the probe's end circle) decides for all of them (issue #23,
/// item 3; exact ray parity per closed component, query/clash.h point_in_solid, summed with the
/// components' orientations: Workpiece::solid_sign).
int bodies_inside(const Workpiece& w, const Bodies& bodies) {
  const Vec3 p = bodies.cylinders.front().c0;
  int winding = 0;
  for (std::size_t k = 0; k < w.solids.size(); ++k) {
    const int in = point_in_solid(w.solids[k], p);
    if (in < 0) return -1;
    winding += in * w.solid_sign[k];
  }
  return winding > 0 ? 1 : 0;
}

/// A pose's state: touches the surface or lies inside a solid (collides), outside (clear), or
/// inside/outside undecided.
enum class PoseState { clear, touches, inside, undecided };

PoseState pose_state(const Workpiece& w, const Bodies& bodies, std::vector<std::uint32_t>* hits, std::size_t* tests,
                     bool* holder_hit) {
  if (bodies_touch(w, bodies, hits, tests, holder_hit)) return PoseState::touches;
  const int in = bodies_inside(w, bodies);
  return in == 1 ? PoseState::inside : in == 0 ? PoseState::clear : PoseState::undecided;
}

/// Best-first search over the BVH for the triangle nearest one body (bounded by `body_box`), with
/// `dist(t, best)` returning {distance, point on the body, point on the triangle}; improves best.
template <class Dist>
void nearest_triangle(const Workpiece& w, const Aabb& body_box, Dist&& dist, double& best, std::uint32_t& tri,
                      Vec3& on_probe, Vec3& on_work) {
  const Bvh& bvh = w.bvh;
  const AabbF cb = to_float_outward(body_box);
  using Item = std::pair<double, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  q.push({box_distance_squared(cb, bvh.nodes[0].box), 0});
  while (!q.empty()) {
    const auto [d2, ni] = q.top();
    q.pop();
    if (!(d2 < best * best) && std::isfinite(best)) break;
    const BvhNode& n = bvh.nodes[ni];
    if (n.is_leaf()) {
      for (std::uint32_t j = n.first; j < n.first + n.count; ++j) {
        const double pd2 = box_distance_squared(cb, bvh.prim_boxes[j]);
        if (std::isfinite(best) && !(pd2 < best * best)) continue;
        const std::uint32_t t = bvh.prims[j];
        const auto [d, p, q2] = dist(w.mesh.corners(t), best);
        if (d < best || (d == best && t < tri)) best = d, tri = t, on_probe = p, on_work = q2;
      }
    } else {
      for (std::uint32_t ch = n.first; ch < n.first + 2; ++ch) {
        const double cd2 = box_distance_squared(cb, bvh.nodes[ch].box);
        if (!std::isfinite(best) || cd2 < best * best) q.push({cd2, ch});
      }
    }
  }
}

/// Minimum distance from the bodies to the workpiece by best-first search over the BVH.
double clearance_of(const Workpiece& w, const Bodies& bodies, double max_clearance, std::uint32_t& tri,
                    Vec3& on_probe, Vec3& on_work) {
  double best = max_clearance;
  tri = kNone;
  if (w.bvh.empty()) return std::numeric_limits<double>::infinity();
  for (const Cylinder& c : bodies.cylinders) {
    nearest_triangle(
        w, cylinder_box(c),
        [&](const std::array<Vec3, 3>& t, double ub) {
          const CylinderTriangleDistance r = cylinder_triangle_distance(c, t, ub);
          return std::tuple{r.distance, r.on_cylinder, r.on_triangle};
        },
        best, tri, on_probe, on_work);
  }
  if (bodies.box) {
    const OrientedBox& b = *bodies.box;
    nearest_triangle(
        w, box_aabb(b),
        [&](const std::array<Vec3, 3>& t, double ub) {
          const BoxTriangleDistance r = box_triangle_distance(b, t, ub);
          return std::tuple{r.distance, r.on_box, r.on_triangle};
        },
        best, tri, on_probe, on_work);
  }
  return tri == kNone ? std::numeric_limits<double>::infinity() : best;
}

double line_distance(const Vec3& p, const Vec3& o, const Vec3& dir) {
  const Vec3 w = p - o;
  return norm(w - dir * dot(w, dir));
}

/// The closed connected components of the workpiece become solids (Model: mesh + BVH + stats, as
/// point_in_solid needs); open ones are counted and warned about.
void find_solids(Workpiece& w) {
  const TriMesh& m = w.mesh;
  if (m.triangles.empty()) return;
  std::size_t open_triangles = 0, components = 0;
  std::vector<double> volume;  // signed volume of each solid (6x, double: only its sign is used)
  // One component: its stats decide, `model` builds the solid only when it is closed.
  auto consider = [&](const TriMesh& part, auto&& model) {
    ++components;
    const MeshStats stats = mesh_stats(part);
    if (!stats.closed()) {
      ++w.open_components;
      open_triangles += part.num_triangles();
      return;
    }
    double v = 0;
    for (std::size_t t = 0; t < part.num_triangles(); ++t) {
      const auto c = part.corners(t);
      v += dot(c[0], cross(c[1], c[2]));
    }
    volume.push_back(v);
    w.solids.push_back(model(stats));
  };
  const std::vector<std::uint32_t> set = connected_sets(m, std::vector<char>(m.num_triangles(), 1));
  std::vector<std::uint32_t> roots;
  for (std::uint32_t t = 0; t < m.num_triangles(); ++t) {
    if (set[t] == t) roots.push_back(t);
  }
  if (roots.size() == 1) {  // the usual case: the workpiece's own mesh and BVH, no split
    consider(m, [&](const MeshStats& stats) { return Model{m, w.bvh, stats}; });
  } else {
    std::vector<std::uint32_t> slot(m.num_triangles());
    for (std::size_t k = 0; k < roots.size(); ++k) slot[roots[k]] = static_cast<std::uint32_t>(k);
    std::vector<TriMesh> parts(roots.size());
    std::vector<std::uint32_t> map(m.num_vertices(), kNone);  // a vertex belongs to one component
    for (std::uint32_t t = 0; t < m.num_triangles(); ++t) {
      TriMesh& part = parts[slot[set[t]]];
      Tri tri;
      for (int c = 0; c < 3; ++c) {
        const std::uint32_t v = m.triangles[t][c];
        if (map[v] == kNone) map[v] = static_cast<std::uint32_t>(part.positions.size()), part.positions.push_back(m.positions[v]);
        tri[c] = map[v];
      }
      part.triangles.push_back(tri);
    }
    for (TriMesh& part : parts) {
      consider(part, [&](const MeshStats&) { return make_model(std::move(part)); });
    }
  }
  // Orientation: outward shells bound material (+1). An inward shell is a cavity (-1) when it lies
  // inside an outward one (one of its vertices decides: the shells do not meet), otherwise an
  // inside-out solid, taken as material with a warning.
  std::size_t inside_out = 0;
  w.solid_sign.assign(w.solids.size(), 1);
  for (std::size_t k = 0; k < w.solids.size(); ++k) {
    if (!(volume[k] < 0)) continue;
    const Vec3 v = w.solids[k].mesh.positions[w.solids[k].mesh.triangles[0][0]];
    bool enclosed = false;
    for (std::size_t j = 0; j < w.solids.size() && !enclosed; ++j) {
      enclosed = j != k && volume[j] > 0 && point_in_solid(w.solids[j], v) == 1;
    }
    if (enclosed) {
      w.solid_sign[k] = -1;
    } else {
      ++inside_out;
    }
  }
  if (inside_out > 0) {
    w.warnings.push_back("workpiece: " + std::to_string(inside_out) +
                         " closed components are inside out (inward normals, enclosed by nothing): taken as "
                         "solids");
  }
  if (w.open_components > 0) {
    w.warnings.push_back("workpiece: " + std::to_string(w.open_components) + " of " + std::to_string(components) +
                         " connected components are not closed (" + std::to_string(open_triangles) +
                         " triangles): they bound no solid, so a probe inside or behind them is not checked "
                         "(only contact with their surface)");
  }
}

}  // namespace

const char* segment_state_name(SegmentState s) {
  switch (s) {
    case SegmentState::clear: return "clear";
    case SegmentState::unresolved: return "unresolved";
    case SegmentState::collides: return "collides";
  }
  return "?";
}

double ProbeShape::volume() const { return M_PI * radius * radius * length; }

double ProbeShape::reach() const {
  double r = std::hypot(length + holder_length, std::max(radius, holder_radius));
  if (has_holder_box()) {
    r = std::max(r, std::hypot(length + holder_box_length, std::hypot(0.5 * holder_box_width, 0.5 * holder_box_depth)));
  }
  return r;
}

double ProbeShape::axis_reach() const {
  double r = std::max(radius, has_holder() ? holder_radius : 0.0);
  if (has_holder_box()) r = std::max(r, std::hypot(0.5 * holder_box_width, 0.5 * holder_box_depth));
  return r;
}

std::vector<Cylinder> probe_cylinders(const ProbeShape& s, const ProbePose& pose) {
  std::vector<Cylinder> out;
  out.push_back(cylinder_from_tip(pose.tip, pose.axis, s.length, s.radius));
  if (s.has_holder()) out.push_back(cylinder_from_tip(out[0].c1, pose.axis, s.holder_length, s.holder_radius));
  return out;
}

OrientedBox probe_holder_box(const ProbeShape& s, const ProbePose& pose) {
  const Vec3 back = cylinder_from_tip(pose.tip, pose.axis, s.length, s.radius).c1;
  return holder_box(back, pose.axis, pose.ref, s.holder_box_width, s.holder_box_depth, s.holder_box_length);
}

const char* hierarchy_name(Hierarchy h) {
  switch (h) {
    case Hierarchy::bvh: return "bvh";
    case Hierarchy::patches: return "patches";
    case Hierarchy::grid: return "grid";
    case Hierarchy::distance_field: return "distance_field";
    case Hierarchy::brute_force: return "brute_force";
  }
  return "?";
}

Workpiece prepare_workpiece(TriMesh mesh, const ProbeShape& probe, const WorkpieceOptions& o) {
  const auto start = Clock::now();
  Workpiece w;
  w.mesh = std::move(mesh);
  w.hierarchy = o.hierarchy;
  w.bvh = build_bvh(w.mesh);
  find_solids(w);
  const double target = o.patch_volume > 0 ? o.patch_volume : o.patch_volume_ratio * probe.volume();
  w.patches = make_patches(w.mesh, {.target_volume = target,
                                    .min_extent = 2 * probe.radius,
                                    .max_normal_angle = o.patch_max_normal_angle});
  if (o.hierarchy == Hierarchy::grid) {
    w.grid = make_uniform_grid(w.mesh, o.grid_cell > 0 ? o.grid_cell : 4 * probe.radius);
  }
  if (o.hierarchy == Hierarchy::distance_field) {
    const double spacing = o.field_spacing > 0 ? o.field_spacing : probe.radius;
    w.field = make_distance_field(w.mesh, w.bvh, spacing, probe.reach() + 2 * spacing);
  }
  w.build_seconds = seconds_since(start);
  return w;
}

bool pose_collides(const Workpiece& w, const ProbeShape& probe, const ProbePose& pose,
                   std::vector<std::uint32_t>* hits, std::size_t* tests, bool* inside, bool* undecided) {
  const PoseState st = pose_state(w, bodies_at(probe, pose), hits, tests, nullptr);
  if (inside) *inside = st == PoseState::inside;
  if (undecided) *undecided = st == PoseState::undecided;
  return st == PoseState::touches || st == PoseState::inside;
}

Vec3 rotate_about(const Vec3& v, const Vec3& n, double phi) {
  const double c = std::cos(phi), s = std::sin(phi);
  return v * c + cross(n, v) * s + n * (dot(n, v) * (1 - c));
}

namespace {

/// The motion of a pose-path segment a -> b: the frame at t is R(t) applied to a's, with
/// R(t) = Rot(n, theta t) Rot(a.axis, psi t): the axis turns by the smallest rotation (theta about
/// n = a.axis x b.axis), the reference direction also twists by psi about the axis, so that R(1)
/// carries a.ref to b.ref (psi = 0 without reference directions).
struct SegmentRotation {
  Vec3 n{0, 0, 1};
  double theta = 0, psi = 0;
  bool turns = false;  ///< theta >= 1e-12 (otherwise the axis is kept)
};

SegmentRotation segment_rotation(const ProbePose& a, const ProbePose& b) {
  SegmentRotation r;
  r.theta = std::acos(std::clamp(dot(a.axis, b.axis), -1.0, 1.0));
  r.turns = r.theta >= 1e-12;
  if (r.turns) {
    Vec3 n = cross(a.axis, b.axis);
    if (norm(n) < 1e-12) {  // opposite: any perpendicular
      n = cross(a.axis, std::fabs(a.axis.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0});
    }
    r.n = n / norm(n);
  }
  if (a.has_ref() && b.has_ref()) {
    const Vec3 r1 = r.turns ? rotate_about(a.ref, r.n, r.theta) : a.ref;
    r.psi = std::atan2(dot(cross(r1, b.ref), b.axis), dot(r1, b.ref));
  }
  return r;
}

}  // namespace

ProbePose pose_at(const ProbePath& path, const Robot* robot, std::uint32_t from, double t) {
  if (path.joint_space && robot) {
    const auto& a = path.joints[from];
    const auto& b = path.joints[from + 1];
    std::vector<double> q(a.size());
    for (std::size_t j = 0; j < q.size(); ++j) q[j] = (1 - t) * a[j] + t * b[j];
    return forward_kinematics(*robot, q);
  }
  const ProbePose& a = path.poses[from];
  const ProbePose& b = path.poses[from + 1];
  const SegmentRotation rot = segment_rotation(a, b);
  ProbePose p;
  p.tip = a.tip * (1 - t) + b.tip * t;
  if (!rot.turns) {
    p.axis = a.axis;
  } else {
    const double phi = rot.theta * t;
    // Rodrigues: rotate a.axis about n by phi (n is perpendicular to a.axis).
    p.axis = a.axis * std::cos(phi) + cross(rot.n, a.axis) * std::sin(phi);
  }
  p.axis = p.axis / norm(p.axis);
  if (a.has_ref() && b.has_ref()) {
    const double psi = rot.psi * t;
    Vec3 r = a.ref * std::cos(psi) + cross(a.axis, a.ref) * std::sin(psi);  // twist about a.axis
    if (rot.turns) r = rotate_about(r, rot.n, rot.theta * t);
    p.ref = perpendicular_reference(r, p.axis);
  }
  return p;
}

namespace {

/// The midpoint pose of [t0, t1] on segment `from` and the motion bound around it (one forward
/// kinematics evaluation for both).
BodyDeltas midpoint_and_bound(const ProbePath& path, const Robot* robot, const ProbeShape& probe, std::uint32_t from,
                              double t0, double t1, ProbePose& mid) {
  const double h = 0.5 * (t1 - t0);
  const double tm = 0.5 * (t0 + t1);
  BodyDeltas bound;
  double scale = 1;
  if (path.joint_space && robot) {
    const auto& a = path.joints[from];
    const auto& b = path.joints[from + 1];
    std::vector<double> q(a.size());
    for (std::size_t j = 0; j < q.size(); ++j) q[j] = (1 - tm) * a[j] + tm * b[j];
    const std::vector<Transform> frames = forward_frames(*robot, q);
    mid = tool_pose(*robot, frames.back());
    const Bodies bodies = bodies_at(probe, mid);
    for (const Cylinder& c : bodies.cylinders) scale = std::max({scale, norm(c.c0), norm(c.c1)});
    if (bodies.box) {
      for (const Vec3& v : bodies.box->corners) scale = std::max(scale, norm(v));
    }
    // Distal to proximal, per body: D_j = D_{j+1} + (prismatic: h |dq|; revolute: h |dq| rho_j),
    // rho_j the largest distance of the body to joint j's axis (z of frame j-1, or of frame j in
    // the modified DH convention: joint_axis_frame) at the midpoint pose.
    for (std::size_t j = robot->joints.size(); j-- > 0;) {
      const double dq = std::fabs(b[j] - a[j]) * h;
      if (dq == 0) continue;
      if (robot->joints[j].type == JointType::prismatic) {
        for (double& d : bound.d) d += dq;
      } else {
        const Transform& f = frames[joint_axis_frame(*robot, j)];
        const Vec3 o = f.t, z{f.r[0][2], f.r[1][2], f.r[2][2]};
        for (std::size_t k = 0; k < bodies.cylinders.size(); ++k) {
          const Cylinder& c = bodies.cylinders[k];
          const double rho = std::max(line_distance(c.c0, o, z), line_distance(c.c1, o, z)) + c.radius;
          bound.d[k] += dq * (M_PI / 180.0) * rho;
        }
        if (bodies.box) {  // convex: the farthest point from a line is a corner
          double rho = 0;
          for (const Vec3& v : bodies.box->corners) rho = std::max(rho, line_distance(v, o, z));
          bound.d[2] += dq * (M_PI / 180.0) * rho;
        }
      }
    }
  } else {
    mid = pose_at(path, robot, from, tm);
    const ProbePose& a = path.poses[from];
    const ProbePose& b = path.poses[from + 1];
    // R(t) = Rot(n, theta t) Rot(a.axis, psi t) (segment_rotation): a body point p (from the tip)
    // moves by at most |t - tm| (theta |p| + |psi| dist(p, axis)), plus the tip's motion. Per
    // body, |p| is at most its reach from the tip; the twist about the axis leaves the cylinders
    // (symmetric about it) in place and moves the box by at most |psi| times its reach from the axis.
    const SegmentRotation rot = segment_rotation(a, b);
    const double tip = distance(a.tip, b.tip);
    bound.d[0] = h * (tip + rot.theta * std::hypot(probe.length, probe.radius));
    if (probe.has_holder())
      bound.d[1] = h * (tip + rot.theta * std::hypot(probe.length + probe.holder_length, probe.holder_radius));
    if (probe.has_holder_box()) {
      const double across = std::hypot(0.5 * probe.holder_box_width, 0.5 * probe.holder_box_depth);
      bound.d[2] = h * (tip + rot.theta * std::hypot(probe.length + probe.holder_box_length, across) +
                        std::fabs(rot.psi) * across);
    }
    scale = std::max({1.0, norm(a.tip), norm(b.tip), probe.reach()});
  }
  // Rounding of the midpoint pose and of the bound itself.
  for (double& d : bound.d) d = d * (1 + 1e-9) + 1e-12 * scale;
  return bound;
}

}  // namespace

double motion_bound(const ProbePath& path, const Robot* robot, const ProbeShape& probe, std::uint32_t from,
                    double t0, double t1) {
  ProbePose mid;
  return midpoint_and_bound(path, robot, probe, from, t0, t1, mid).max();
}

namespace {

/// Outcome of one refinement pass over a segment (see sweep.h and docs/probe.md, "Between path
/// points").
struct Refined {
  std::vector<std::array<double, 2>> hit, unresolved;  ///< merged, sorted
  std::vector<std::uint32_t> triangles;                ///< hit at tested interior poses, sorted
  std::uint32_t poses = 0;
  double smallest_gap = std::numeric_limits<double>::infinity();
  double motion = 0;
  SegmentState state = SegmentState::clear;
};

void merge(std::vector<std::array<double, 2>>& iv) {
  std::sort(iv.begin(), iv.end());
  std::vector<std::array<double, 2>> out;
  for (const auto& x : iv) {
    if (!out.empty() && x[0] <= out.back()[1]) {
      out.back()[1] = std::max(out.back()[1], x[1]);
    } else {
      out.push_back(x);
    }
  }
  iv = std::move(out);
}

/// Level-order bisection of segment `from`. Li, Zhou & Zheng 2008 (§2, Fig. 1) check the path
/// points only; this check of the motion between them is ours (docs/probe.md, "Between path
/// points"), conservative by the motion bound: an interval is cleared when the bodies at its midpoint,
/// grown by the motion bound plus `extra`, touch no triangle; otherwise `hit` decides the midpoint
/// (1 proved, 0 not, -1 undecided) and the halves go to the next level, down to depth max_depth or
/// until max_poses midpoints were tested. Leaves left over hold a proved end (part of `hit`
/// intervals) or are unresolved. `gap` (may be empty) measures the gap at unresolved leaves.
/// Pose paths: the motion over a node's interval, for the plane filter below (issue #28, speed).
/// The cylinders move by the tip's translation and the turn Rot(n, theta t) about the tip (the
/// twist about the axis leaves a cylinder in place).
struct PlaneMotion {
  bool on = false;
  Vec3 dtip, tip;  ///< the segment's tip change; the tip at the node's midpoint
  double theta = 0, h = 0, extra = 0;
};

/// Whether cylinder c (at the node's midpoint), swept over the node's interval and grown by
/// m.extra, stays strictly on one side of the plane of T, so that it cannot touch T: a directional
/// form of the motion bound. A point p of c moves along the plane's unit normal n by at most
/// h (|n.dtip| + theta |p - tip|); c is cut into 8 axial slices, each with its support along n (the
/// lower or upper of its end disks: n.e -+ r sqrt(1 - (n.a)^2)) and its reach from the tip (its end
/// centres' largest distance + r). Double precision with a margin of 1e-9 x the coordinates' scale,
/// far above the rounding of these few operations; a degenerate T is never separated.
bool plane_separates(const Cylinder& c, const std::array<Vec3, 3>& t, const PlaneMotion& m) {
  Vec3 n = cross(t[1] - t[0], t[2] - t[0]);
  const double nl = norm(n);
  const Vec3 d = c.c1 - c.c0;
  const double len = norm(d);
  if (!(nl > 0) || !(len > 0)) return false;
  n = n / nl;
  const Vec3 a = d / len;
  const double na = dot(n, a);
  const double sr = c.radius * std::sqrt(std::max(0.0, 1 - na * na));
  const double drift = m.h * std::fabs(dot(n, m.dtip));
  double scale = len + c.radius + m.extra;
  for (const Vec3& v : {t[0], t[1], t[2], c.c0, c.c1}) scale = std::max({scale, std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  const double margin = 1e-9 * scale;
  double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
  constexpr int kSlices = 8;
  for (int j = 0; j < kSlices; ++j) {
    const Vec3 e0 = c.c0 + d * (double(j) / kSlices), e1 = c.c0 + d * (double(j + 1) / kSlices);
    const double s0 = dot(n, e0 - t[0]), s1 = dot(n, e1 - t[0]);
    const double reach = std::max(norm(e0 - m.tip), norm(e1 - m.tip)) + c.radius;
    const double move = drift + m.h * m.theta * reach + m.extra;
    lowest = std::min(lowest, std::min(s0, s1) - sr - move);
    highest = std::max(highest, std::max(s0, s1) + sr + move);
  }
  return lowest > margin || highest < -margin;
}

/// Whether the grown bodies touch a triangle, the cylinders' candidates that touch passed through
/// the plane filter first (pose paths): a triangle whose plane the swept cylinder stays clear of
/// cannot touch it. Sound either way; the filter only clears more intervals at once.
bool swept_touches(const Workpiece& w, const Bodies& mid, const Bodies& grown, const PlaneMotion& m) {
  if (!m.on) return bodies_touch(w, grown, nullptr, nullptr, nullptr);
  for (std::size_t k = 0; k < grown.cylinders.size(); ++k) {
    const Cylinder& g = grown.cylinders[k];
    const bool touch = for_each_candidate(w, g, cylinder_box(g), [&](std::uint32_t t) {
      const auto tri = w.mesh.corners(t);
      return cylinder_triangle_intersect(g, tri) && !plane_separates(mid.cylinders[k], tri, m);
    });
    if (touch) return true;
  }
  if (grown.box) {
    const Bodies box_only{{}, grown.box};
    return bodies_touch(w, box_only, nullptr, nullptr, nullptr);
  }
  return false;
}

template <class Hit, class Gap>
Refined refine(const Workpiece& w, const ProbePath& path, const Robot* robot, const SweepRequest& req,
               std::uint32_t from, bool c0, bool c1, double extra, Hit&& hit, Gap&& gap) {
  struct Node {
    double t0, t1;
    bool c0, c1;
    int depth;
  };
  Refined out;
  auto leaf = [&](const Node& nd) {
    if (nd.c0 || nd.c1) {
      out.hit.push_back({nd.t0, nd.t1});
      return;
    }
    out.unresolved.push_back({nd.t0, nd.t1});
    ProbePose pm;
    const double delta = midpoint_and_bound(path, robot, req.probe, from, nd.t0, nd.t1, pm).max();
    out.motion = std::max(out.motion, delta);
    out.smallest_gap = std::min(out.smallest_gap, gap(bodies_at(req.probe, pm)));
  };
  PlaneMotion motion;
  if (req.plane_filter && !(path.joint_space && robot)) {
    const ProbePose& a = path.poses[from];
    const ProbePose& b = path.poses[from + 1];
    motion.on = true;
    motion.dtip = b.tip - a.tip;
    motion.theta = segment_rotation(a, b).theta;
    motion.extra = extra;
  }
  std::vector<Node> level{{0.0, 1.0, c0, c1, 0}}, next;
  while (!level.empty()) {
    next.clear();
    for (const Node& nd : level) {
      if (nd.c0 && nd.c1) {
        out.hit.push_back({nd.t0, nd.t1});
        continue;
      }
      if (out.poses >= req.max_poses) {
        leaf(nd);
        continue;
      }
      ++out.poses;
      ProbePose pm;
      const BodyDeltas delta = midpoint_and_bound(path, robot, req.probe, from, nd.t0, nd.t1, pm);
      const Bodies at_mid = bodies_at(req.probe, pm);
      if (motion.on) motion.h = 0.5 * (nd.t1 - nd.t0), motion.tip = pm.tip;
      if (!swept_touches(w, at_mid, grown_bodies(at_mid, delta, extra), motion)) {
        // The swept bodies miss every surface: every pose of the interval is on the same side of
        // each closed component as its ends (one collides only by lying inside: then all do).
        if (nd.c0 || nd.c1) out.hit.push_back({nd.t0, nd.t1});
        continue;
      }
      const double tm = 0.5 * (nd.t0 + nd.t1);
      const int cm = hit(at_mid, out.triangles);
      if (cm == 1) out.hit.push_back({tm, tm});
      if (cm < 0) out.unresolved.push_back({tm, tm});
      const Node a{nd.t0, tm, nd.c0, cm == 1, nd.depth + 1}, b{tm, nd.t1, cm == 1, nd.c1, nd.depth + 1};
      if (nd.depth >= req.max_depth) {
        for (const Node& child : {a, b}) (child.c0 && child.c1) ? out.hit.push_back({child.t0, child.t1}) : leaf(child);
      } else {
        next.push_back(a);
        next.push_back(b);
      }
    }
    std::swap(level, next);
  }
  merge(out.hit);
  merge(out.unresolved);
  std::sort(out.triangles.begin(), out.triangles.end());
  out.triangles.erase(std::unique(out.triangles.begin(), out.triangles.end()), out.triangles.end());
  out.state = !out.hit.empty() ? SegmentState::collides
              : !out.unresolved.empty() ? SegmentState::unresolved
                                        : SegmentState::clear;
  return out;
}

}  // namespace

SweepResult sweep(const Workpiece& w, const ProbePath& path, const Robot* robot, const SweepRequest& req) {
  SweepResult res;
  const std::size_t n = path.poses.size();
  if (req.probe.has_holder_box()) {
    for (const ProbePose& p : path.poses) {
      if (!p.has_ref()) throw std::invalid_argument("sweep: a box holder needs a reference direction at every pose");
    }
  }
  const double limit = req.clearance_limit > 0 ? req.clearance_limit : 0.0;
  const double max_clearance = std::max(req.max_clearance, limit);
  res.points.resize(n);
  std::vector<std::size_t> tests(n, 0);
  // (progress: the points, their clearances, the segments)
  const std::size_t work = n + ((req.clearance || limit > 0) ? n : 0) + ((req.continuous && n > 1) ? n - 1 : 0);
  std::atomic<std::size_t> work_done{0};
  auto loop = [&](std::size_t count, auto&& body) {
    auto step = [&](std::size_t i) {
      body(i);
      if (req.progress) req.progress(++work_done, work);
    };
    if (req.parallel) {
      tbb::parallel_for(std::size_t(0), count, step);
    } else {
      for (std::size_t i = 0; i < count; ++i) step(i);
    }
  };
  // Discrete points: surface contact, then containment in a closed component.
  auto start = Clock::now();
  loop(n, [&](std::size_t i) {
    PointResult& r = res.points[i];
    const PoseState st = pose_state(w, bodies_at(req.probe, path.poses[i]), &r.hits, &tests[i], &r.holder);
    r.collides = st == PoseState::touches || st == PoseState::inside;
    r.inside = st == PoseState::inside;
    r.undecided = st == PoseState::undecided;
    if (r.collides) {
      r.clearance = 0;
      if (!r.hits.empty()) {
        r.triangle = r.hits.front();
        r.patch = w.patches.patch_of[r.triangle];
      }
    }
  });
  res.discrete_seconds = seconds_since(start);
  for (std::size_t i = 0; i < n; ++i) {
    res.candidate_tests += tests[i];
    res.colliding_points += res.points[i].collides;
    res.inside_points += res.points[i].inside;
    res.undecided_points += res.points[i].undecided;
  }
  // Clearance.
  start = Clock::now();
  if (req.clearance || limit > 0) {
    loop(n, [&](std::size_t i) {
      PointResult& r = res.points[i];
      if (r.collides) return;
      r.clearance = clearance_of(w, bodies_at(req.probe, path.poses[i]), max_clearance, r.triangle, r.point_probe,
                                 r.point_workpiece);
      if (r.triangle != kNone) r.patch = w.patches.patch_of[r.triangle];
    });
  } else {
    for (PointResult& r : res.points) {
      if (!r.collides) r.clearance = std::numeric_limits<double>::quiet_NaN();
    }
  }
  for (PointResult& r : res.points) {
    r.verdict = r.collides ? Verdict::clash
                : r.undecided ? Verdict::undecided
                : (limit > 0 && r.clearance < limit) ? Verdict::clearance
                                                     : Verdict::clear;
    res.verdict = worst(res.verdict, r.verdict);
  }
  res.clearance_seconds = seconds_since(start);
  // Continuous check between consecutive points.
  start = Clock::now();
  if (req.continuous && n > 1) {
    std::vector<SegmentResult> segs(n - 1);
    loop(n - 1, [&](std::size_t s) {
      SegmentResult& seg = segs[s];
      seg.from = static_cast<std::uint32_t>(s);
      const PointResult &pa = res.points[s], &pb = res.points[s + 1];
      auto gap = [&](const Bodies& b) {
        std::uint32_t tri;
        Vec3 p, q;
        return clearance_of(w, b, max_clearance, tri, p, q);
      };
      const Refined hit = refine(
          w, path, robot, req, seg.from, pa.collides, pb.collides, 0.0,
          [&](const Bodies& b, std::vector<std::uint32_t>& tris) {
            std::vector<std::uint32_t> hits;
            const PoseState st = pose_state(w, b, &hits, nullptr, nullptr);
            tris.insert(tris.end(), hits.begin(), hits.end());
            return st == PoseState::undecided ? -1 : st == PoseState::clear ? 0 : 1;
          },
          gap);
      seg.state = hit.state;
      seg.intervals = hit.hit;
      seg.unresolved = hit.unresolved;
      seg.triangles = hit.triangles;
      seg.poses_tested = hit.poses;
      seg.smallest_gap = hit.smallest_gap;
      seg.unresolved_motion = hit.motion;
      seg.between_samples = !pa.collides && !pb.collides && seg.state == SegmentState::collides;
      if (seg.state == SegmentState::clear && (pa.undecided || pb.undecided)) seg.state = SegmentState::unresolved;
      seg.verdict = seg.state == SegmentState::collides     ? Verdict::clash
                    : seg.state == SegmentState::unresolved ? Verdict::undecided
                                                            : Verdict::clear;
      if (seg.verdict == Verdict::clear && limit > 0) {
        // Clearance pass: the same refinement with the bodies grown by the requested clearance; a
        // midpoint is "hit" when its exact clearance is below it.
        const Refined near = refine(
            w, path, robot, req, seg.from, pa.clearance < limit, pb.clearance < limit, limit,
            [&](const Bodies& b, std::vector<std::uint32_t>&) { return gap(b) < limit ? 1 : 0; },
            [](const Bodies&) { return std::numeric_limits<double>::infinity(); });
        seg.clearance_state = near.state;
        seg.clearance_intervals = near.hit;
        seg.clearance_unresolved = near.unresolved;
        seg.poses_tested += near.poses;
        seg.verdict = near.state == SegmentState::collides     ? Verdict::clearance
                      : near.state == SegmentState::unresolved ? Verdict::undecided
                                                               : Verdict::clear;
      }
    });
    for (SegmentResult& s : segs) {
      res.verdict = worst(res.verdict, s.verdict);
      if (s.verdict == Verdict::clear) continue;
      res.colliding_segments += s.state == SegmentState::collides;
      res.unresolved_segments += s.state == SegmentState::unresolved;
      res.between_samples_segments += s.between_samples;
      res.segments.push_back(std::move(s));
    }
  }
  res.continuous_seconds = seconds_since(start);
  return res;
}

}  // namespace interfere::probe
