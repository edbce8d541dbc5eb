// The cage-web rows of scarred rollers, two-sided where certified (scarred_web_two_sided.h; issue #27).
#include "scarred_web_two_sided.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "assembly_cage_web.h"

namespace interfere::bearing::detail {

bool scarred_web_two_sided(double v, const Cylinder& roller, double raise, std::span<const Cylinder> ends,
                           const TriMesh& web_mesh, const CageWeb& web, const Transform& cage_pose) {
  if (!(v <= 0)) return false;
  const Vec3 m = roller.center();
  const double scale = std::max({std::fabs(m.x), std::fabs(m.y), std::fabs(m.z)}) + roller.height + roller.max_radius() + raise;
  // a cheap refusal first (issue #27, speed): fwd(A') >= F(x) = min_j (d_j - n_j.x) at any point x of
  // an end piece; at the rim points lowest along each face normal (where the roller's deepest point
  // in the web usually is) F above -v proves S(A') < v: not S, no need for S(C)
  std::array<Vec3, 6> n;
  std::array<double, 6> d{};
  for (int j = 0; j < 6; ++j) n[j] = cage_pose.rotate(web.normals[j]), d[j] = web.offsets[j] + dot(n[j], cage_pose.t);
  for (const Cylinder& e : ends)
    for (int j = 0; j < 6; ++j) {
      const double cu = std::clamp(dot(n[j], e.axis), -1.0, 1.0);
      const bool at_base = cu >= 0;  // the end whose rim reaches lowest along n_j (a cylinder or frustum
                                     // piece: either rim is a point of the piece, which is all F needs)
      Vec3 x = at_base ? e.base : e.top_center();
      const Vec3 w = n[j] - e.axis * cu;
      if (const double wn = norm(w); wn > 0) x = x - w * ((at_base ? e.radius : e.top()) / wn);
      double f = d[0] - dot(n[0], x);
      for (int k = 1; k < 6; ++k) f = std::min(f, d[k] - dot(n[k], x));
      if (f > -v + 0x1p-44 * scale) return false;
    }
  Cylinder c = roller;  // C: the whole roller grown radially by the raise (holds A')
  if (raise > 0) {
    c.radius += raise;
    if (c.top_radius >= 0) c.top_radius += raise;
  }
  // S(C, W) as the intact rows compute it (assembly_pairs.cpp, roller-cage of an intact roller)
  const WebValue rev = web_distance(c, web_mesh, cage_pose, &web);
  const WebValue s = rev.distance > 0 ? rev : two_sided_web(c, web, cage_pose, rev);
  return s.distance >= v - 0x1p-44 * scale;
}

}  // namespace interfere::bearing::detail
