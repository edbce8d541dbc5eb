// Instance-pair interference of an assembly (include/interfere/cad/assembly_clash.h): the clash
// engine of paper 1 (exact triangle tests, regions, containment; query/clash.h) on every pair of
// instances whose world boxes overlap, found by sorting the boxes along x and sweeping.
#include "interfere/cad/assembly_clash.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <numeric>

#include "interfere/mesh/validate.h"
#include "interfere/query/model.h"
#include "interfere/query/distance.h"

namespace interfere::cad {
namespace {

// Where the segment pq meets the surface of m: parameters in (0, 1), sorted (floating point: a
// sampling aid, each interval between them is classified exactly afterwards).
std::vector<double> surface_crossings(const Model& m, const Vec3& p, const Vec3& q) {
  std::vector<double> ts;
  const Vec3 d = q - p;
  std::vector<std::uint32_t> stack{0};
  while (!stack.empty()) {
    const BvhNode& n = m.bvh.nodes[stack.back()];
    stack.pop_back();
    double t0 = 0, t1 = 1;  // slab test
    for (int k = 0; k < 3 && t0 <= t1; ++k) {
      const double lo = double(n.box.lo[k]), hi = double(n.box.hi[k]);
      if (d[k] == 0) {
        if (p[k] < lo || p[k] > hi) t0 = 2;
        continue;
      }
      double a = (lo - p[k]) / d[k], b = (hi - p[k]) / d[k];
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a), t1 = std::min(t1, b);
    }
    if (t0 > t1) continue;
    if (!n.is_leaf()) {
      stack.push_back(n.first);
      stack.push_back(n.first + 1);
      continue;
    }
    for (std::uint32_t k = 0; k < n.count; ++k) {
      const auto t = m.mesh.corners(m.bvh.prims[n.first + k]);
      const Vec3 nrm = cross(t[1] - t[0], t[2] - t[0]);
      const double sp = dot(nrm, p - t[0]), sq = dot(nrm, q - t[0]);
      if ((sp > 0) == (sq > 0) || sp == sq) continue;
      const double s = sp / (sp - sq);
      const Vec3 x = p + d * s;
      const double e0 = dot(cross(t[1] - t[0], x - t[0]), nrm), e1 = dot(cross(t[2] - t[1], x - t[1]), nrm),
                   e2 = dot(cross(t[0] - t[2], x - t[2]), nrm);
      if (e0 >= 0 && e1 >= 0 && e2 >= 0 && s > 0 && s < 1) ts.push_back(s);
    }
  }
  std::sort(ts.begin(), ts.end());
  return ts;
}

// How deep the surface of x reaches into the solid y, sampled: the largest distance to y's surface
// of x's points inside y (exact ray parity) among: the middles of the stretches of the crossing
// triangles' edges between their crossings of y's surface, the vertices of the triangles that cross
// or touch y (`paired`), and the vertices of the connected sets of its other triangles that lie
// inside y (such a set lies wholly inside or outside; one vertex, exactly off y's surface, decides).
double depth_into(const Model& x, const Model& y, const std::vector<char>& paired) {
  const TriMesh& m = x.mesh;
  const auto nt = static_cast<std::uint32_t>(m.num_triangles());
  std::vector<char> free_of(nt);  // the triangles that touch nothing of y
  for (std::uint32_t t = 0; t < nt; ++t) free_of[t] = !paired[t];
  const std::vector<std::uint32_t> set = connected_sets(m, free_of);
  std::vector<char> set_inside(nt, 0);  // per set root
  for (std::uint32_t t = 0; t < nt; ++t)
    if (!paired[t] && set[t] == t) set_inside[t] = point_in_solid(y, m.positions[m.triangles[t][0]]) == 1;
  std::vector<char> state(m.num_vertices(), 0);  // 0 unknown, 1 inside, 2 not
  double depth = 0;
  // Along the edges of the crossing triangles: the middle of each stretch between two crossings of
  // y's surface that lies inside y (a long edge may pass through y with both ends outside).
  std::vector<std::array<std::uint32_t, 2>> crossing_edges;
  for (std::uint32_t t = 0; t < nt; ++t)
    if (paired[t])
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t u = m.triangles[t][k], v = m.triangles[t][(k + 1) % 3];
        crossing_edges.push_back({std::min(u, v), std::max(u, v)});
      }
  std::sort(crossing_edges.begin(), crossing_edges.end());
  crossing_edges.erase(std::unique(crossing_edges.begin(), crossing_edges.end()), crossing_edges.end());
  for (const auto& [u, v] : crossing_edges) {
    const Vec3 p = m.positions[u], q = m.positions[v];
    std::vector<double> ts = surface_crossings(y, p, q);
    ts.insert(ts.begin(), 0.0);
    ts.push_back(1.0);
    for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
      if (!(ts[i + 1] > ts[i])) continue;
      const Vec3 mid = p + (q - p) * (0.5 * (ts[i] + ts[i + 1]));
      if (point_in_solid(y, mid) == 1) depth = std::max(depth, surface_distance(y, mid));
    }
  }
  for (std::uint32_t t = 0; t < nt; ++t) {
    const bool whole = !paired[t] && set_inside[set[t]];
    if (!paired[t] && !whole) continue;
    for (std::uint32_t v : m.triangles[t]) {
      if (state[v] == 0) state[v] = whole || point_in_solid(y, m.positions[v]) == 1 ? 1 : 2;
      if (state[v] == 1) {
        depth = std::max(depth, surface_distance(y, m.positions[v]));
        state[v] = 3;  // (measured)
      }
    }
  }
  return depth;
}

// The face node of a part, placed in the world.
struct PlacedFace {
  SurfaceType type = SurfaceType::other;
  Vec3 normal, axis_point, axis;
  double radius = 0, offset = 0;  // plane: normal . p
  bool hole = false;
};

PlacedFace placed(const AagNode& n, const Transform& t) {
  PlacedFace f;
  f.type = n.type, f.radius = n.radius, f.hole = n.hole;
  const auto rotate = [&](const Vec3& v) {
    return Vec3{t.r[0][0] * v.x + t.r[0][1] * v.y + t.r[0][2] * v.z, t.r[1][0] * v.x + t.r[1][1] * v.y + t.r[1][2] * v.z,
                t.r[2][0] * v.x + t.r[2][1] * v.y + t.r[2][2] * v.z};
  };
  f.normal = rotate(n.normal);
  f.axis = rotate(n.axis);
  f.axis_point = t.apply(n.axis_point);
  return f;  // (a plane's offset is set by the caller, through a placed triangle of the face)
}

// Whether faces fa (of one instance) and fb (of the other) are one surface (within tol: lengths;
// angles in radians): planes back to back (material on opposite sides), a sphere in a seat, and
// coaxial cylinders of one radius, back to back (a bolt in its hole) or on the same side (two
// bores in line, as a nut's on a plate's: their walls meet at the rim).
bool coincide(const PlacedFace& fa, const PlacedFace& fb, double tol, double angle) {
  if (fa.type != fb.type) return false;
  const auto unit = [](const Vec3& v) { return v / norm(v); };
  switch (fa.type) {
    case SurfaceType::plane:
      return norm(unit(fa.normal) + unit(fb.normal)) <= angle && std::fabs(fa.offset + fb.offset) <= tol;
    case SurfaceType::cylinder: {
      if (std::fabs(fa.radius - fb.radius) > tol) return false;
      const Vec3 a = unit(fa.axis), b = unit(fb.axis);
      if (norm(cross(a, b)) > angle) return false;
      const Vec3 d = fb.axis_point - fa.axis_point;
      return norm(d - a * dot(d, a)) <= tol;  // b's axis point on a's axis
    }
    case SurfaceType::sphere:
      return fa.hole != fb.hole && std::fabs(fa.radius - fb.radius) <= tol && norm(fa.axis_point - fb.axis_point) <= tol;
    default:
      return false;
  }
}

}  // namespace

const char* instance_meeting_name(InstanceMeeting m) {
  switch (m) {
    case InstanceMeeting::clash:
      return "clash";
    case InstanceMeeting::contact:
      return "contact";
    case InstanceMeeting::clearance:
      return "clearance";
  }
  return "?";
}

AssemblyClashResult assembly_clash(const CadModel& model, const AssemblyClashOptions& options) {
  AssemblyClashResult out;
  const std::size_t n = model.instances.size();
  // Each instance in the world, welded (faces meeting along shared edges: a closed solid is closed).
  std::vector<Model> world(n);
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
    const Instance& in = model.instances[i];
    TriMesh m = transformed(model.parts[in.part].mesh, in.placement);
    weld_exact(m);
    world[i] = make_model(std::move(m));
  });
  // Candidates: boxes within the clearance of each other on every axis (sweep along x; growing the
  // low corners alone by it is the same test).
  const double grow = std::max(0.0, options.clearance);
  std::vector<Aabb> box(n);
  for (std::size_t i = 0; i < n; ++i) {
    box[i] = world[i].mesh.bounds();
    box[i].lo = box[i].lo - Vec3{grow, grow, grow};
  }
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
    return box[x].lo.x < box[y].lo.x || (box[x].lo.x == box[y].lo.x && x < y);
  });
  std::vector<std::pair<std::uint32_t, std::uint32_t>> candidates;
  for (std::size_t k = 0; k < n; ++k) {
    const Aabb& a = box[order[k]];
    for (std::size_t l = k + 1; l < n && box[order[l]].lo.x <= a.hi.x; ++l) {
      const Aabb& b = box[order[l]];
      if (a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z && b.lo.z <= a.hi.z)
        candidates.emplace_back(std::min(order[k], order[l]), std::max(order[k], order[l]));
    }
  }
  std::sort(candidates.begin(), candidates.end());
  out.candidate_pairs = candidates.size();
  // The exact clash of each candidate (in parallel; each result is the same on any thread count).
  std::vector<InstancePairResult> result(candidates.size());
  std::vector<char> meets(candidates.size(), 0);
  tbb::parallel_for(std::size_t{0}, candidates.size(), [&](std::size_t c) {
    const auto [a, b] = candidates[c];
    const ClashResult r = clash(world[a], world[b], {.clearance = options.clearance});
    InstancePairResult& p = result[c];
    p.tessellation_error = model.parts[model.instances[a].part].linear_deflection +
                           model.parts[model.instances[b].part].linear_deflection;
    p.a = a, p.b = b;
    p.cross_pairs = r.cross_pairs, p.touch_pairs = r.touch_pairs;
    p.clearance_pairs = r.clearance.size();
    if (!r.clearance.empty())
      p.min_clearance = std::min_element(r.clearance.begin(), r.clearance.end(), [](const auto& x, const auto& y) {
                          return x.distance < y.distance;
                        })->distance;
    p.containment = r.containment;
    p.regions = r.regions.size();
    for (const ClashRegion& g : r.regions) p.curve_length += g.curve_length;
    p.touching_overlap = r.touching_overlap;
    const bool inside = r.containment == Containment::a_inside_b || r.containment == Containment::b_inside_a;
    if (r.cross_pairs > 0) {
      std::vector<char> pa(world[a].mesh.num_triangles(), 0), pb(world[b].mesh.num_triangles(), 0);
      for (const TrianglePair& q : r.pairs) pa[q.a] = 1, pb[q.b] = 1;
      p.depth = std::max(depth_into(world[a], world[b], pa), depth_into(world[b], world[a], pb));
    }
    // A nominal fit: every crossing pair on two coincident B-Rep faces, back to back.
    const Part& part_a = model.parts[model.instances[a].part];
    const Part& part_b = model.parts[model.instances[b].part];
    if (r.cross_pairs > 0 && !inside && !r.touching_overlap && !part_a.face_ids.empty() && !part_b.face_ids.empty()) {
      const double size = norm(world[a].mesh.bounds().extent()) + norm(world[b].mesh.bounds().extent());
      const double tol = kFitTolerance * size, angle = kFitTolerance;
      const auto face_of = [&](const Part& part, const Instance& in, std::uint32_t t, const TriMesh& w) {
        PlacedFace f = placed(part.aag.nodes[part.face_ids[t]], in.placement);
        if (f.type == SurfaceType::plane) {  // the plane through the placed triangle
          const auto c = w.corners(t);
          f.offset = dot(f.normal / norm(f.normal), (c[0] + c[1] + c[2]) / 3.0);
        }
        return f;
      };
      // The faces of A and of B that coincide back to back with a face of the other, among the
      // pairs (crossing or touching); a crossing pair is explained when one of its faces is one.
      std::map<std::pair<std::uint32_t, std::uint32_t>, bool> coincident;  // (face of A, face of B)
      std::set<std::uint32_t> fit_a, fit_b;
      for (const TrianglePair& q : r.pairs) {
        if (q.a >= part_a.face_ids.size() || q.b >= part_b.face_ids.size()) continue;
        const auto key = std::make_pair(part_a.face_ids[q.a], part_b.face_ids[q.b]);
        auto it = coincident.find(key);
        if (it == coincident.end())
          it = coincident.emplace(key, coincide(face_of(part_a, model.instances[a], q.a, world[a].mesh),
                                                             face_of(part_b, model.instances[b], q.b, world[b].mesh),
                                                             tol, angle)).first;
        if (it->second) fit_a.insert(key.first), fit_b.insert(key.second);
      }
      // A face crossing the other part may coincide with one of its faces that it does not meet
      // (a nut's seat a hair inside the plate's top face: parallel, so no pair): each face of the
      // crossing pairs, not yet explained, against every face of the other part (a triangle of
      // each face places it).
      const auto first_triangles = [](const Part& part) {
        std::vector<std::uint32_t> first(part.aag.nodes.size(), 0xffffffffu);
        for (std::uint32_t t = static_cast<std::uint32_t>(part.face_ids.size()); t-- > 0;)
          if (part.face_ids[t] < first.size()) first[part.face_ids[t]] = t;
        return first;
      };
      const std::vector<std::uint32_t> first_a = first_triangles(part_a), first_b = first_triangles(part_b);
      std::set<std::uint32_t> crossing_a, crossing_b;
      for (const TrianglePair& q : r.pairs)
        if (q.kind == ContactKind::cross && q.a < part_a.face_ids.size() && q.b < part_b.face_ids.size())
          crossing_a.insert(part_a.face_ids[q.a]), crossing_b.insert(part_b.face_ids[q.b]);
      const auto explain = [&](const std::set<std::uint32_t>& crossing, bool of_a) {
        for (const std::uint32_t f : crossing) {
          if ((of_a ? fit_a : fit_b).count(f)) continue;
          const std::vector<std::uint32_t>& others = of_a ? first_b : first_a;
          for (std::uint32_t g = 0; g < others.size(); ++g) {
            const std::uint32_t fa = of_a ? f : g, fb = of_a ? g : f;
            if (others[g] != 0xffffffffu &&
                coincide(face_of(part_a, model.instances[a], first_a[fa], world[a].mesh),
                         face_of(part_b, model.instances[b], first_b[fb], world[b].mesh), tol, angle)) {
              fit_a.insert(fa), fit_b.insert(fb);
              break;
            }
          }
        }
      };
      explain(crossing_a, true);
      explain(crossing_b, false);
      bool fit = !fit_a.empty() && p.depth <= p.tessellation_error;
      for (const TrianglePair& q : r.pairs) {
        if (!fit) break;
        if (q.kind != ContactKind::cross) continue;
        fit = (q.a < part_a.face_ids.size() && fit_a.count(part_a.face_ids[q.a])) ||
              (q.b < part_b.face_ids.size() && fit_b.count(part_b.face_ids[q.b]));
      }
      p.nominal_fit = fit;
    }
    if ((r.cross_pairs > 0 && !p.nominal_fit) || inside || r.touching_overlap) p.meeting = InstanceMeeting::clash;
    else if (r.touch_pairs > 0) p.meeting = InstanceMeeting::contact;
    else if (!r.clearance.empty()) p.meeting = InstanceMeeting::clearance;
    else return;
    meets[c] = 1;
  });
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    if (!meets[c]) continue;
    const InstancePairResult& p = result[c];
    out.clashes += p.meeting == InstanceMeeting::clash;
    out.contacts += p.meeting == InstanceMeeting::contact;
    out.within_clearance += p.meeting == InstanceMeeting::clearance;
    out.pairs.push_back(p);
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!world[i].stats.closed())
      out.warnings.push_back("instance '" + model.instances[i].name + "' is not closed: containment in it is not checked");
  return out;
}

}  // namespace interfere::cad
