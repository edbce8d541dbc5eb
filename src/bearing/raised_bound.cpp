// Conservative spheres around the outward-displaced triangles of a raised scar (issue #27).
#include "interfere/bearing/raised_bound.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace interfere::bearing {

RaisedBound build_raised_bound(const Roller& roller, int triangles_per_sphere) {
  RaisedBound out;
  const std::size_t side = roller.displacement.size();
  const auto raised = [&](std::uint32_t v) { return v < side && roller.displacement[v] < 0; };
  std::vector<std::uint32_t> run;
  const auto flush = [&] {
    if (run.empty()) return;
    Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
            std::numeric_limits<double>::infinity()};
    Vec3 hi = lo * -1.0;
    for (const std::uint32_t t : run)
      for (const std::uint32_t v : roller.mesh.triangles[t]) {
        const Vec3& p = roller.mesh.positions[v];
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
      }
    RaisedBound::Sphere s;
    s.center = (lo + hi) * 0.5;
    double r2 = 0, scale = 0;
    for (const std::uint32_t t : run)
      for (const std::uint32_t v : roller.mesh.triangles[t]) {
        const Vec3 d = roller.mesh.positions[v] - s.center;
        r2 = std::max(r2, dot(d, d));
        scale = std::max({scale, std::fabs(roller.mesh.positions[v].x),
                          std::fabs(roller.mesh.positions[v].y),
                          std::fabs(roller.mesh.positions[v].z)});
      }
    // the margin covers the rounding of the centre, the square root and the pose (a few ulps of the
    // coordinates)
    s.radius = std::sqrt(r2) + 64 * std::numeric_limits<double>::epsilon() * scale;
    out.spheres.push_back(s);
    run.clear();
  };
  const auto per = static_cast<std::size_t>(std::max(1, triangles_per_sphere));
  std::uint32_t last = 0;
  for (std::uint32_t t = 0; t < roller.mesh.triangles.size(); ++t) {
    const Tri& tri = roller.mesh.triangles[t];
    if (!(raised(tri[0]) || raised(tri[1]) || raised(tri[2]))) continue;
    if (!run.empty() && (run.size() >= per || t != last + 1)) flush();
    run.push_back(t);
    last = t;
  }
  flush();
  return out;
}

double raised_lower_bound(const RaisedBound& bound, const Transform& pose, const Cylinder& b) {
  double lb = std::numeric_limits<double>::infinity();
  for (const RaisedBound::Sphere& s : bound.spheres)
    lb = std::min(lb, point_signed_distance(b, pose.apply(s.center)) - s.radius);
  return lb;
}

}  // namespace interfere::bearing
