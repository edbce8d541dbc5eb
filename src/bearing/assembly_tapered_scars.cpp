// Scarred rollers of tapered bearings (assembly_tapered_scars.h; issue #27, deliverable 2).
#include "assembly_tapered_scars.h"

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

PairDistance mesh_in_conical_bore(const TriMesh& mesh, const Transform& pose, const Vec3& base, const Vec3& axis,
                                  double R0, double k, double width, bool& found) {
  constexpr double kNegInf = -std::numeric_limits<double>::infinity();
  const double nk = std::sqrt(1 + k * k);
  std::vector<Vec3> p(mesh.positions.size());
  std::vector<double> zs(p.size());
  // g of a point at axial position z: (rho - R(z)) / nk (a cylindrical bore: rho - R0)
  const auto g_of = [&](const Vec3& x, double z) {
    const double rho = norm(cross(x - base, axis));
    return k == 0 ? rho - R0 : (rho - (R0 + k * z)) / nk;
  };
  double all = kNegInf, best = kNegInf;  // max over every vertex (G), over the clipped mesh (G_K)
  Vec3 far_all, far;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p[i] = pose.apply(mesh.positions[i]), zs[i] = dot(p[i] - base, axis);
    const double g = g_of(p[i], zs[i]);
    if (g > all) all = g, far_all = p[i];
    if (zs[i] >= 0 && zs[i] <= width && g > best) best = g, far = p[i];
  }
  const double z_all = dot(far_all - base, axis);
  const bool all_in = z_all >= 0 && z_all <= width;
  if (!all_in) {  // the farthest vertex lies beyond a side face: clip
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
