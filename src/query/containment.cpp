// Exact point-in-closed-mesh by ray parity. Every crossing decision goes through orient3d; a ray that
// meets an edge, a vertex or lies in a triangle's plane is degenerate and is replaced by another
// direction (symbolic perturbation by re-sampling), so the parity is never decided by an epsilon.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "clash_internal.h"
#include "interfere/bvh/traverse.h"
#include "interfere/core/predicates.h"

namespace interfere::detail {
namespace {

enum class Crossing { no, yes, degenerate };

/// Segment pq against triangle t; p is known not to lie on the mesh surface.
Crossing segment_crosses(const Vec3& p, const Vec3& q, const std::array<Vec3, 3>& t) {
  const int sp = orient3d(t[0], t[1], t[2], p);
  const int sq = orient3d(t[0], t[1], t[2], q);
  if (sp == 0) return Crossing::no;  // p in the plane but not on the triangle: touches the plane only at p
  if (sq == 0) return Crossing::degenerate;
  if (sp == sq) return Crossing::no;
  const int e0 = orient3d(p, q, t[0], t[1]);
  const int e1 = orient3d(p, q, t[1], t[2]);
  const int e2 = orient3d(p, q, t[2], t[0]);
  const bool has_pos = e0 > 0 || e1 > 0 || e2 > 0, has_neg = e0 < 0 || e1 < 0 || e2 < 0;
  if (has_pos && has_neg) return Crossing::no;
  if (e0 == 0 || e1 == 0 || e2 == 0) return Crossing::degenerate;  // through an edge or a vertex
  return Crossing::yes;
}

}  // namespace

int point_in_closed_mesh(const Model& model, const Vec3& p) {
  const Bvh& bvh = model.bvh;
  if (bvh.empty()) return 0;
  // The root's box (float, rounded outwards: it holds every triangle), not mesh.bounds(), which
  // reads every vertex (this runs once per probe).
  Aabb bounds;
  for (int k = 0; k < 3; ++k) bounds.lo[k] = bvh.nodes[0].box.lo[k], bounds.hi[k] = bvh.nodes[0].box.hi[k];
  for (int k = 0; k < 3; ++k)
    if (p[k] < bounds.lo[k] || p[k] > bounds.hi[k]) return 0;  // (outside the bounds: outside)
  const double diag = norm(bounds.extent());
  const double reach = 2.0 * (diag + norm(p - bounds.center())) + 1.0;
  const double pad = 1e-9 * reach;
  // The draws of a fixed generator (results are reproducible): every call would draw the same
  // sequence, so it is drawn once (3 numbers per attempt) and read from a table.
  static const std::array<double, 120> table = [] {
    std::mt19937_64 rng(0x1f2e3d4c5b6a7988ULL);
    std::normal_distribution<double> g;
    std::array<double, 120> t{};
    for (double& x : t) x = g(rng);
    return t;
  }();
  std::size_t next = 0;
  const auto gauss = [&] { return table[next++]; };
  // The first rays leave by the nearest side of the bounds (short: few boxes to visit for a point
  // near the surface), tilted at random so that grid-aligned meshes rarely make them degenerate;
  // then random directions across the whole part. Any ray that is not degenerate gives the parity.
  int axis = 0;
  double sign = 1, gap = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k)
    for (const double s : {-1.0, 1.0}) {
      const double g = s > 0 ? bounds.hi[k] - p[k] : p[k] - bounds.lo[k];
      if (g < gap) gap = g, axis = k, sign = s;
    }
  for (int attempt = 0; attempt < 40; ++attempt) {
    Vec3 q;
    if (attempt < 8 && std::isfinite(gap) && gap >= 0) {
      const double x = gauss(), y = gauss(), z = gauss();
      Vec3 dir{0.25 * x, 0.25 * y, 0.25 * z};
      dir[axis] = sign;
      q = p + dir * (gap + 0.01 * diag);  // (the axis component is 1: q lies beyond the bounds)
      if (!is_finite(q)) continue;
    } else {
      const double x = gauss(), y = gauss(), z = gauss();
      Vec3 dir{x, y, z};
      const double len = norm(dir);
      if (!(len > 0)) continue;
      q = p + dir * (reach / len);
    }
    const Vec3 d = q - p;
    bool degenerate = false;
    int parity = 0;
    for_each_on_segment(bvh, p, d, pad, [&](std::uint32_t t) {
      const Crossing c = segment_crosses(p, q, model.mesh.corners(t));
      degenerate = c == Crossing::degenerate;
      parity ^= (c == Crossing::yes);
      return !degenerate;
    });
    if (!degenerate) return parity;
  }
  return -1;
}

}  // namespace interfere::detail
