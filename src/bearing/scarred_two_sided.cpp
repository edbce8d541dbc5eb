// Two-sided values of scarred rollers' rows (scarred_two_sided.h; issue #27).
#include "scarred_two_sided.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "assembly_tapered_scars.h"
#include "interfere/bearing/scarred.h"
#include "interfere/np/distance.h"
#include "interfere/query/clash.h"
#include "interfere/query/distance.h"
#include "interfere/query/model.h"

namespace interfere::bearing::detail {

bool scarred_ring_two_sided(const PairDistance& d, const Vec3& base, const Vec3& axis, double k, double width,
                            double outer_radius, const TriMesh& mesh, const Transform& pose) {
  if (d.path != AnalyticPath::bore) return false;  // (a bound)
  if (d.distance > 0) {
    // apart (scarred_two_sided.h (1), apart): the Euclidean distance when the witness's foot on the
    // raceway's line lies within the width
    const double zb = dot(d.point_b - base, axis);
    return zb >= 0 && zb <= width;
  }
  if (!(d.distance <= 0)) return false;
  const double reach = -d.distance;  // r_f
  // fwd = r_f: the witness is at least r_f from the side faces' and the outside's lines
  const Vec3 w = d.point_a - base;
  const double z = dot(w, axis);
  const double rho = norm(cross(w, axis));
  if (!(z >= reach && width - z >= reach && outer_radius - rho >= reach)) return false;
  if (k == 0) return true;
  // a cup: rev <= r_f needs the pushed point q + t n (z moved by -k t / sqrt(1 + k^2)) in K, i.e.
  // the whole solid within the width: its z-range is its vertices'
  for (const Vec3& v : mesh.positions) {
    const double zv = dot(pose.apply(v) - base, axis);
    if (!(zv >= 0 && zv <= width)) return false;
  }
  return true;
}

namespace {

/// Body frame of a pose: R^T (x - t) (R a rotation).
Vec3 to_body(const Transform& p, const Vec3& x) {
  const Vec3 w = x - p.t;
  return {p.r[0][0] * w.x + p.r[1][0] * w.y + p.r[2][0] * w.z, p.r[0][1] * w.x + p.r[1][1] * w.y + p.r[2][1] * w.z,
          p.r[0][2] * w.x + p.r[1][2] * w.y + p.r[2][2] * w.z};
}

}  // namespace

namespace {

/// A lower bound of the distance from a triangle (corners in a roller's body frame: axis +z, ends
/// z = 0 and z = h) to that roller's enclosing cylinder (radius R): the distance of a point to the
/// cylinder is at least max(rho - R, -z, z - h), and rho >= n.x for the unit n across the axis
/// toward the triangle's centroid, so over the triangle it is at least
/// max(min over the corners of n.x - R, -max z, min z - h) (linear pieces: their minimum is at a corner).
double triangle_separation(const Vec3& p, const Vec3& q, const Vec3& r, double R, double h) {
  const double cx = p.x + q.x + r.x, cy = p.y + q.y + r.y;
  const double cn = std::sqrt(cx * cx + cy * cy);
  double radial = -R;
  if (cn > 0) {
    const double nx = cx / cn, ny = cy / cn;
    radial = std::min({nx * p.x + ny * p.y, nx * q.x + ny * q.y, nx * r.x + ny * r.y}) - R;
  }
  return std::max({radial, -std::max({p.z, q.z, r.z}), std::min({p.z, q.z, r.z}) - h});
}

/// The triangles of `m` (corners `pos`, in the other roller's body frame) that can lie within
/// `upper` of that roller (enclosing cylinder R, h).
TriMesh near_triangles(const TriMesh& m, std::vector<Vec3> pos, double R, double h, double upper) {
  TriMesh sub;
  for (const Tri& t : m.triangles)
    if (triangle_separation(pos[t[0]], pos[t[1]], pos[t[2]], R, h) <= upper) sub.triangles.push_back(t);
  sub.positions = std::move(pos);
  return sub;
}

}  // namespace

std::optional<MeshesApart> scarred_meshes_apart(const Roller& ra, const Transform& pa,
                                                const Roller& rb, const Model& sb, const Transform& pb,
                                                const Vec3& on_a) {
  // U: the distance from a point of A's surface to B's surface bounds the distance of the solids
  // from above (a small relative margin covers its rounding: U only filters)
  const double scale = norm(pa.t) + norm(pb.t) + ra.params.height + rb.params.height +
                       std::max(ra.params.radius, ra.params.top()) + std::max(rb.params.radius, rb.params.top());
  const double u2 = nearest_triangle_d2(sb.mesh, sb.bvh, to_body(pb, on_a));
  if (!std::isfinite(u2)) return std::nullopt;
  const double upper = std::sqrt(u2) + 0x1p-30 * scale;
  // only triangles that can be within U of the other roller's enclosing cylinder (its largest
  // radius plus the raise; the scarred solid lies in it) can hold the closest pair: A's in A's
  // body frame, B's taken into A's body frame (and compared in B's own)
  const auto enclosing_radius = [](const Roller& r) { return std::max(r.params.radius, r.params.top()) + std::max(r.raise, 0.0); };
  std::vector<Vec3> a_in_b, b_in_a;
  a_in_b.reserve(ra.mesh.positions.size()), b_in_a.reserve(rb.mesh.positions.size());
  for (const Vec3& v : ra.mesh.positions) a_in_b.push_back(to_body(pb, pa.apply(v)));
  for (const Vec3& v : rb.mesh.positions) b_in_a.push_back(to_body(pa, pb.apply(v)));
  TriMesh near_a = near_triangles(ra.mesh, a_in_b, enclosing_radius(rb), rb.params.height, upper);
  TriMesh near_b = near_triangles(rb.mesh, std::move(b_in_a), enclosing_radius(ra), ra.params.height, upper);
  if (near_a.triangles.empty() || near_b.triangles.empty()) return std::nullopt;  // (cannot happen: U is attained)
  // both in A's body frame turned about its axis so that x points toward B's centre: the facing
  // triangles (tangent across x) get thin boxes along the gap, so the engine's box distances are
  // close to the triangles' and prune (a rotation: distances unchanged up to rounding)
  const Vec3 cb = to_body(pa, pb.apply({0, 0, 0.5 * rb.params.height}));
  const double cn = std::sqrt(cb.x * cb.x + cb.y * cb.y);
  const double ux = cn > 0 ? cb.x / cn : 1, uy = cn > 0 ? cb.y / cn : 0;
  const auto turn = [&](const Vec3& v) { return Vec3{ux * v.x + uy * v.y, -uy * v.x + ux * v.y, v.z}; };
  const auto unturn = [&](const Vec3& v) { return Vec3{ux * v.x - uy * v.y, uy * v.x + ux * v.y, v.z}; };
  near_a.positions.resize(ra.mesh.positions.size());
  for (std::size_t i = 0; i < ra.mesh.positions.size(); ++i) near_a.positions[i] = turn(ra.mesh.positions[i]);
  for (Vec3& v : near_b.positions) v = turn(v);
  const std::uint32_t evaluated = static_cast<std::uint32_t>(near_a.triangles.size() + near_b.triangles.size());
  BvhBuildOptions build;
  build.builder = BvhBuilder::median_split;  // (serial: a few hundred triangles)
  const Model ma = make_model(std::move(near_a), build, false), mb = make_model(std::move(near_b), build, false);
  DistanceRequest rq;
  rq.upper_bound = upper;
  const DistanceResult r = distance(ma, mb, rq);
  if (!r.intersecting && !std::isfinite(r.distance)) return std::nullopt;
  MeshesApart out;
  out.distance = r.distance, out.meeting = r.intersecting;
  out.point_a = pa.apply(unturn(r.point_a)), out.point_b = pa.apply(unturn(r.point_b));
  out.evaluated = evaluated;
  return out;
}

namespace {

/// sd of the world point p to a scarred roller's closed mesh (`s`, body frame, posed by `pose`):
/// the nearest triangle's distance, negative inside (exact ray parity); `foot` the nearest point
/// (world). nullopt when every ray direction was degenerate.
struct SolidDistance {
  double value = 0;
  Vec3 foot;
};
std::optional<SolidDistance> solid_signed_distance(const Model& s, const Transform& pose, const Vec3& p) {
  const Vec3 body = to_body(pose, p);
  std::uint32_t tri = kNoTriangle;
  const double d2 = nearest_triangle_d2(s.mesh, s.bvh, body, &tri);
  if (!std::isfinite(d2) || tri == kNoTriangle) return std::nullopt;
  SolidDistance out;
  out.foot = pose.apply(closest_point_on_triangle(body, s.mesh.corners(tri)));
  out.value = std::sqrt(d2);
  if (out.value == 0) return out;  // on the surface
  const int in = point_in_solid(s, body);
  if (in < 0) return std::nullopt;
  if (in == 1) out.value = -out.value;
  return out;
}

/// The intact cylinder inscribed in a roller (a frustum's smaller radius): its centre lies inside
/// the scarred solid (scars are shallower than the radius).
Cylinder inner(const Cylinder& c) {
  Cylinder in = c;
  in.radius = std::min(c.radius, c.top()), in.top_radius = -1;
  return in;
}

}  // namespace

TwoScarredValue two_scarred_value(const ScenePart& a, const ScenePart& b, double tol) {
  // L = min(s(A mesh, B0), s(B mesh, A0)) <= S: B's solid lies in B0, so sd_B >= sd_B0 (part_pair.h)
  const Cylinder a0 = grown_roller_solid(a.cylinder, a.mesh->raise);
  const Cylinder b0 = grown_roller_solid(b.cylinder, b.mesh->raise);
  ScarredSolver sa(a.mesh, a.tree), sb(b.mesh, b.tree);
  const MeshPairResult fa = sa.solve(a.pose, b0), fb = sb.solve(b.pose, a0);
  TwoScarredValue out;
  out.evaluated = fa.evaluated + fb.evaluated;
  if (fa.distance <= fb.distance) {
    out.lower = fa.distance, out.point_a = fa.point_a, out.point_b = fa.point_b;
  } else {
    out.lower = fb.distance, out.point_a = fb.point_b, out.point_b = fb.point_a, out.reverse = true;
  }
  out.upper = out.lower;
  // surfaces that do not meet: one solid inside the other, or apart; the centre of each inscribed
  // cylinder (inside its own solid) in the other's solid decides (part_pair.h, mesh_containment)
  const auto containment = [&] {
    const int in_a = mesh_containment(a, inner(b.cylinder)), in_b = mesh_containment(b, inner(a.cylinder));
    return in_a == 1 || in_b == 1 ? 1 : in_a < 0 || in_b < 0 ? -1 : 0;
  };
  const auto take_distance = [&](const MeshesApart& e) {
    out.lower = out.upper = e.distance;
    out.point_a = e.point_a, out.point_b = e.point_b, out.reverse = false;
    out.exact = out.upper_known = true;
    out.evaluated += e.evaluated;
  };
  if (out.lower > tol) {
    // A's surface misses B0, which holds B's surface (and B's misses A0): the surfaces do not meet
    out.contained = containment();
    if (out.contained != 0) return out;
    // neither solid holds the other: apart, S = s(A, B) = s(B, A) their Euclidean distance (2)
    if (a.solid != nullptr && b.solid != nullptr)
      if (const auto e = scarred_meshes_apart(*a.mesh, a.pose, *b.mesh, *b.solid, b.pose, fa.point_a); e && !e->meeting)
        take_distance(*e);
    return out;
  }
  if (a.solid == nullptr || b.solid == nullptr) return out;
  // (3) U*: S <= s(A, B) <= sd_B(p) for p on A's surface, and the same with the roles exchanged;
  // p the bound's witnesses (each surface's point deepest in the other's grown intact solid)
  double upper = std::numeric_limits<double>::infinity();
  Vec3 ua, ub;
  bool reverse = false;
  if (const auto d = solid_signed_distance(*b.solid, b.pose, fa.point_a); d && d->value < upper)
    upper = d->value, ua = fa.point_a, ub = d->foot, reverse = false;
  if (const auto d = solid_signed_distance(*a.solid, a.pose, fb.point_a); d && d->value < upper)
    upper = d->value, ua = d->foot, ub = fb.point_a, reverse = true;
  if (!(upper < -tol)) {
    // the vertices: a faceted surface's most protruding points (a witness may lie over a pit of the
    // other roller). Those of A inside B's enclosing cylinder, and B's in A's: a vertex is skipped
    // only when it cannot lower U* (sd_B >= max(rho - R, -z, z - h) in that cylinder's frame), so
    // U* is the least over all of them, whatever the roles (to rounding)
    const auto vertices = [&](const ScenePart& p, const ScenePart& q, bool rev) {
      const Cylinder c = grown_roller_solid(q.cylinder, q.mesh->raise);
      const double radius = c.max_radius();
      for (const Vec3& v : p.mesh->mesh.positions) {
        const Vec3 w = p.pose.apply(v);
        const double z = dot(w - c.base, c.axis), rho = norm(cross(w - c.base, c.axis));
        if (!(std::max({rho - radius, -z, z - c.height}) < std::min(upper, 0.0))) continue;
        if (const auto d = solid_signed_distance(*q.solid, q.pose, w); d && d->value < upper) {
          upper = d->value, reverse = rev;
          (rev ? ub : ua) = w, (rev ? ua : ub) = d->foot;
        }
      }
    };
    vertices(a, b, false);
    vertices(b, a, true);
  }
  if (!(upper < -tol)) {
    // not decided by a point: the surfaces meet (S <= 0), or they do not and, neither solid holding
    // the other, the solids are apart at their distance (2)
    if (const auto e = scarred_meshes_apart(*a.mesh, a.pose, *b.mesh, *b.solid, b.pose, fa.point_a)) {
      if (!e->meeting) {
        out.contained = containment();
        if (out.contained == 0) take_distance(*e);
        return out;
      }
      out.evaluated += e->evaluated;
      if (!(upper <= 0)) upper = 0, ua = e->point_a, ub = e->point_b, reverse = false;
    }
  }
  if (!std::isfinite(upper)) return out;  // (every ray degenerate and no engine result: L only)
  out.upper_known = true;
  out.upper = upper, out.lower = std::min(out.lower, upper);  // (L <= S <= U*; min: rounding)
  out.point_a = ua, out.point_b = ub, out.reverse = reverse;
  return out;
}

}  // namespace interfere::bearing::detail
