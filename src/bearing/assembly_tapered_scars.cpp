// Scarred rollers of tapered bearings (assembly_tapered_scars.h; issue #27, deliverable 2).
#include "assembly_tapered_scars.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "interfere/bearing/part_pair.h"
#include "interfere/bearing/raceway.h"
#include "interfere/bearing/scarred.h"

namespace interfere::bearing::detail {

Cylinder grown_roller_solid(const Cylinder& intact, double raise) {
  Cylinder a = intact;
  if (!(raise > 0)) return a;
  if (a.tapered()) {
    a.top_radius = a.top() + raise;
    a.radius += raise;
  } else {
    a.radius += raise;
  }
  return a;
}

ScarredFrustumValue scarred_against_frustum(const Roller& mesh, const RollerQuadtree& tree, const Model* solid,
                                            const Transform& pose, const Cylinder& intact, const Cylinder& b,
                                            double tol) {
  ScarredFrustumValue out;
  // s(A, B): the scarred solver, hinted by the intact frustum's witness (the value does not depend
  // on the hint, only the work)
  const PairDistance hint = cone_pair_distance(intact, b);
  ScarredSolver solver(&mesh, &tree);
  const MeshPairResult fwd = solver.solve(pose, b, hint.point_a);
  out.distance = out.lower = fwd.distance;
  out.point_a = fwd.point_a, out.point_b = fwd.point_b;
  out.evaluated = fwd.evaluated;
  if (fwd.distance > tol) {
    // the surfaces are apart: B wholly inside A's solid or wholly outside it
    ScenePart a;
    a.cylinder = intact, a.mesh = &mesh, a.tree = &tree, a.solid = solid, a.pose = pose;
    Cylinder inner = b;  // B's inscribed cylinder of its smaller radius (same centre, smaller depth)
    inner.radius = std::min(b.radius, b.top()), inner.top_radius = -1;
    const int inside = mesh_containment(a, inner);
    out.contained = inside == 1 ? 1 : inside < 0 ? -1 : 0;
    return out;
  }
  // B's depth into A: bounded below through A's grown intact solid A0 (A lies in A0)
  const PairDistance rev = cone_pair_distance(b, grown_roller_solid(intact, mesh.raise));
  if (rev.distance < out.distance) out.lower = rev.distance, out.exact = false;
  return out;
}

std::optional<PairDistance> roller_in_bore_by_columns(const Roller& roller, const Transform& pose, const Vec3& base,
                                                      const Vec3& axis, double R0, double width, double scar_height) {
  const int n = roller.n(), m = roller.m();
  const TriMesh& mesh = roller.mesh;
  if (n < 3 || m < 1 || mesh.positions.size() != static_cast<std::size_t>(n) * static_cast<std::size_t>(m + 1) + 2)
    return std::nullopt;
  // (the bound needs 0 <= r: every inward displacement below the smallest radius)
  if (!(scar_height < std::min(roller.params.radius, roller.params.top()))) return std::nullopt;
  const double h = roller.params.height;
  const double r_max = std::max(roller.params.radius, roller.params.top()) + std::max(roller.raise, 0.0);
  const Vec3 u = pose.rotate({0, 0, 1});
  const auto across = [&](const Vec3& v) { return v - axis * dot(v, axis); };
  const Vec3 q0 = across(pose.t - base), q1 = across(pose.t + u * h - base);
  const double qq = std::max(dot(q0, q0), dot(q1, q1));
  double all2 = -1, best2 = -1;  // the largest rho^2 over every vertex, over those in the width
  std::uint32_t all_i = 0;
  Vec3 far_all;
  const auto vertex = [&](std::uint32_t idx) {
    const Vec3 x = pose.apply(mesh.positions[idx]);
    const double z = dot(x - base, axis);
    const Vec3 c = cross(x - base, axis);
    const double r2 = dot(c, c);
    if (r2 > all2 || (r2 == all2 && idx < all_i)) all2 = r2, all_i = idx, far_all = x;
    if (z >= 0 && z <= width && r2 > best2) best2 = r2;
  };
  // the column bounds; the largest first (on the stack for the usual segment counts: no allocation)
  std::array<double, 256> bound_small;
  std::vector<double> bound_large;
  double* bound = bound_small.data();
  if (n > static_cast<int>(bound_small.size()))
    bound_large.resize(static_cast<std::size_t>(n)), bound = bound_large.data();
  int first = 0;
  // the column directions by rotating (1, 0) by 2 pi / n step by step (a few ulps off the mesh's
  // cos and sin per step: far below the margin)
  const Vec3 ex = pose.rotate({1, 0, 0}), ey = pose.rotate({0, 1, 0});
  const double cd = std::cos(roller.angle(1)), sd = std::sin(roller.angle(1));
  std::array<Vec3, 256> dir_small;  // (the columns' w, for their vertices' bounds)
  std::vector<Vec3> dir_large;
  Vec3* dir = dir_small.data();
  if (n > static_cast<int>(dir_small.size()))
    dir_large.resize(static_cast<std::size_t>(n)), dir = dir_large.data();
  double ca = 1, sa = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3 w = ex * ca + ey * sa;
    dir[i] = w;
    const double cn = ca * cd - sa * sd;
    sa = sa * cd + ca * sd, ca = cn;
    const Vec3 pw = across(w);
    const double lin = std::max(dot(q0, w), dot(q1, w));
    bound[i] = qq + std::max(0.0, 2 * r_max * lin + r_max * r_max * dot(pw, pw));
    if (bound[i] > bound[first]) first = i;
  }
  // A column's vertex j lies at height z_j = roller.z(j) (update_positions), so the same bound with
  // q(t) = q0 + t (q1 - q0), t = z_j / h, in place of the maximum over z holds for it alone:
  // |q(t)|^2 + max(0, 2 r_max q(t).w + r_max^2 |P w|^2), a quadratic and a linear function of t
  // (issue #27, speed: a side column's vertices are n apart in memory, a cache line each; most of
  // a column is below the best so far, and its vertices are not read). The order of evaluation
  // does not matter: the maxima compared are the same (rho^2, ties to the lowest index), and a
  // vertex is skipped only when its bound is below best2, which only grows.
  const Vec3 dq = q1 - q0;
  const double c0 = dot(q0, q0), c1 = 2 * dot(q0, dq), c2 = dot(dq, dq);
  const auto below = [&](double b) { return b + 0x1p-30 * b < best2; };
  const auto column = [&](int i) {
    const Vec3& w = dir[i];
    const Vec3 pw = across(w);
    const double a0 = 2 * r_max * dot(q0, w), a1 = 2 * r_max * dot(dq, w), a2 = r_max * r_max * dot(pw, pw);
    const auto vertex_bound = [&](int j) {
      const double t = roller.z(j) / h;
      return c0 + t * (c1 + t * c2) + std::max(0.0, a0 + t * a1 + a2);
    };
    // the column's ends first (for a nearly parallel roller one of them is the farthest), then the rest
    if (!below(vertex_bound(0))) vertex(roller.side_vertex(i, 0));
    if (!below(vertex_bound(m))) vertex(roller.side_vertex(i, m));
    for (int j = 1; j < m; ++j)
      if (!below(vertex_bound(j))) vertex(roller.side_vertex(i, j));
  };
  column(first);
  // the end centres (on the axis: r = 0)
  if (!below(dot(q0, q0))) vertex(static_cast<std::uint32_t>(n * (m + 1)));
  if (!below(dot(q1, q1))) vertex(static_cast<std::uint32_t>(n * (m + 1) + 1));
  for (int i = 0; i < n; ++i)
    if (i != first && !below(bound[i])) column(i);
  const double z_all = dot(far_all - base, axis);
  if (!(all2 >= 0) || !(z_all >= 0 && z_all <= width)) return std::nullopt;
  // mesh_in_conical_bore's result when its maximiser lies in the width
  PairDistance d;
  d.path = AnalyticPath::bore;
  d.distance = -(std::sqrt(all2) - R0);
  d.point_a = far_all;
  const double z = dot(far_all - base, axis);
  const Vec3 foot = base + axis * z;
  const Vec3 radial = far_all - foot;
  const double rn = norm(radial);
  d.point_b = rn > 0 ? foot + radial * (R0 / rn) : far_all;
  return d;
}

PairDistance mesh_in_conical_bore(const TriMesh& mesh, const Transform& pose, const Vec3& base, const Vec3& axis,
                                  double R0, double k, double width, bool& found) {
  constexpr double kNegInf = -std::numeric_limits<double>::infinity();
  const double nk = std::sqrt(1 + k * k);
  // g of a point at axial position z: (rho - R(z)) / nk (a cylindrical bore: rho - R0)
  const auto g_of = [&](const Vec3& x, double z) {
    const double rho = norm(cross(x - base, axis));
    return k == 0 ? rho - R0 : (rho - (R0 + k * z)) / nk;
  };
  double all = kNegInf, best = kNegInf;  // max over every vertex (G), over the clipped mesh (G_K)
  Vec3 far_all, far;
  if (k == 0) {
    // a cylindrical bore (issue #27, speed): g = sqrt(rho^2) - R0 is non-decreasing in rho^2 (so
    // are the rounded square root and subtraction), so the largest g is sqrt(largest rho^2) - R0,
    // the same double as the largest of the g: one square root per call instead of per vertex, and
    // the posed positions are not stored (recomputed below in the rare clipped case)
    double all2 = -1, best2 = -1;
    for (const Vec3& v : mesh.positions) {
      const Vec3 x = pose.apply(v);
      const double z = dot(x - base, axis);
      const Vec3 c = cross(x - base, axis);
      const double r2 = dot(c, c);
      if (r2 > all2) all2 = r2, far_all = x;
      if (z >= 0 && z <= width && r2 > best2) best2 = r2, far = x;
    }
    if (all2 >= 0) all = std::sqrt(all2) - R0;
    if (best2 >= 0) best = std::sqrt(best2) - R0;
  } else {
    for (const Vec3& v : mesh.positions) {
      const Vec3 x = pose.apply(v);
      const double z = dot(x - base, axis);
      const double g = g_of(x, z);
      if (g > all) all = g, far_all = x;
      if (z >= 0 && z <= width && g > best) best = g, far = x;
    }
  }
  const double z_all = dot(far_all - base, axis);
  const bool all_in = z_all >= 0 && z_all <= width;
  if (!all_in) {  // the farthest vertex lies beyond a side face: clip
    std::vector<Vec3> p(mesh.positions.size());
    std::vector<double> zs(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = pose.apply(mesh.positions[i]), zs[i] = dot(p[i] - base, axis);
    for (const Tri& t : mesh.triangles)
      for (int e = 0; e < 3; ++e) {
        const auto i = t[e], j = t[(e + 1) % 3];
        for (const double level : {0.0, width}) {
          if (!((zs[i] < level && zs[j] > level) || (zs[i] > level && zs[j] < level))) continue;
          const Vec3 x = p[i] + (p[j] - p[i]) * ((level - zs[i]) / (zs[j] - zs[i]));
          if (const double g = g_of(x, level); g > best) best = g, far = x;
        }
      }
  }
  PairDistance d;
  found = best > kNegInf;
  if (!found) return d;
  d.path = AnalyticPath::bore;
  if (all_in) {
    d.distance = -all, far = far_all;
  } else if (best >= 0) {
    d.distance = -best;  // the clipped mesh reaches the raceway: the depth
  } else {  // apart within the width: -G is a lower bound of the distance (raceway.h)
    d.distance = std::max(-all, 0.0), far = far_all, d.path = AnalyticPath::apart;
  }
  d.point_a = far;
  const double z = dot(far - base, axis);
  const Vec3 foot = base + axis * z;
  const Vec3 radial = far - foot;
  const double rn = norm(radial);
  if (k == 0) {
    d.point_b = rn > 0 ? foot + radial * (R0 / rn) : far;
  } else {  // the foot of `far` on the cone line in its meridian half-plane
    const Vec3 n = rn > 0 ? (radial / rn - axis * k) / nk : Vec3{};
    d.point_b = far - n * g_of(far, z);
  }
  return d;
}

}  // namespace interfere::bearing::detail
