// The scarred solver (Jia & Zheng 2019, §3.2) and the references it is checked against.
//
// The quantity is (*) of analytic.h with A the roller's triangle mesh (the scarred surface itself,
// not its vertices): s = min over the triangles T of A of min over p in T of sd_B(p), B an
// intact cylinder or (issue #27: scarred tapered rollers against a tapered bearing's cone, a
// neighbouring tapered roller) an intact cone frustum. Per triangle the minimum is exact to
// rounding. A frustum B: sd_B = phi(rho, z) is nondecreasing in rho (a convex meridian section
// symmetric about the axis), so the slice search below applies with phi the frustum's closed form;
// (first Newton steps with a convexity certificate, then golden section when that fails);
// the quadtree's node bound uses the plane tangent to B's cone along the box centre's meridian,
// sd_B >= (rho - R(z)) / sqrt(1 + k^2) (raceway_cone.cpp's lateral bound), and the end slab. For a
// cylinder B: rho_B's minimum over T is a
// planar point-to-triangle distance after projecting along B's axis (closest points on the edges,
// or 0 when B's axis pierces T); when sd_B = rho_B - R at that minimiser (certificate, as in
// analytic.h) it is the triangle's value, otherwise a nested golden-section search over T's
// barycentric coordinates (sd_B is convex) gives it. See docs/bearing.md for why the minimum over
// the surface is the minimum over the solid except when B's innermost core lies inside A.
//
//  - surface_reference: every triangle (the exact reference).
//  - ScarredSolver: branch and bound down the roller's quadtree (bounds from quadtree.h), started
//    from the previous frame's minimising triangle (temporal coherence, §3.2) so that the first
//    upper bound is already (nearly) tight. Equal to surface_reference to rounding. It descends the
//    tree of coplanar facet strips (quadtree.h, FacetStrips; issue #27): a planar run of intact
//    cells of one column is minimised as one rectangle (two triangles), the scar's cells as before.
//    First the leaves of the previous triangle, of the hinted cell and of its partner (the cell
//    across the vertex line the best point lies on: an intact facetted roller's nearest point to
//    a part beside it is on a vertex line, where two columns tie); nodes holding an entry of the
//    best value are descended without their bound (issue #27, speed; only the work depends on it).
//  - vertex methods (the paper's and its comparisons, approximate by construction): brute force over
//    all vertices; Barbier–Galin distance over all vertices; the paper's quadtree method
//    (calculation layer, virtual vertices, scar descent) over the window of Eq. (1).
#pragma once
#include <cstdint>
#include <vector>

#include "interfere/bearing/analytic.h"
#include "interfere/bearing/quadtree.h"
#include "interfere/bearing/roller.h"

namespace interfere::bearing {

struct MeshPairResult {
  double distance = 0;        ///< s: > 0 clearance, < 0 interference
  Vec3 point_a, point_b;      ///< world frame
  std::uint32_t triangle = 0; ///< minimising triangle of A (for vertex methods: a vertex id)
  std::uint32_t evaluated = 0;  ///< triangles (or vertices) evaluated exactly
  std::uint32_t nodes_visited = 0;
  std::uint32_t fallbacks = 0;  ///< triangles that needed the nested search
};

/// min over p in triangle t (world frame) of sd_B(p), exact to rounding, with the minimiser.
struct TriangleMin {
  double value = 0;
  Vec3 point;
  bool certified = true;  ///< false: the nested search was used
};
TriangleMin triangle_min_signed_distance(const Cylinder& b, const Vec3& t0, const Vec3& t1, const Vec3& t2);

/// Exact reference: every triangle of the roller posed by `pose`.
MeshPairResult surface_reference(const Roller& roller, const Transform& pose, const Cylinder& b);

/// Temporally coherent exact solver over the quadtree. One object per roller/partner pair: it keeps
/// the previous frame's minimising triangle.
class ScarredSolver {
 public:
  ScarredSolver() = default;
  ScarredSolver(const Roller* roller, const RollerQuadtree* tree) : roller_(roller), tree_(tree) {}
  MeshPairResult solve(const Transform& pose, const Cylinder& b);
  /// Same, with a hint: a world point near the expected minimiser (e.g. the standard solver's
  /// witness on the intact cylinder); the side cell under it is evaluated first, tightening the
  /// first upper bound when the motion since the previous frame is large. The result does not
  /// depend on the hint (only the work does).
  MeshPairResult solve(const Transform& pose, const Cylinder& b, const Vec3& hint);
  void reset() { previous_ = kNone; }
  std::uint32_t previous_triangle() const { return previous_; }

 private:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  const Roller* roller_ = nullptr;
  const RollerQuadtree* tree_ = nullptr;
  std::uint32_t previous_ = kNone;
  MeshPairResult run(const Transform& pose, const Cylinder& b, const Vec3* hint);
};

/// Test-only (issue #27): ScarredSolver descends the tree of coplanar facet strips
/// (RollerQuadtree::strips, quadtree.h) when enabled (the default), else the cell tree
/// (RollerQuadtree::bounds) as before the strips; for comparing the two. Process-wide.
void set_facet_strips_for_testing(bool enabled);

/// Vertex methods: min over (some) vertices of sd_B. `window` = theta of Eq. (1) (radians). B must be
/// an untapered cylinder here (the paper's comparisons; cylinder.h's point distances).
MeshPairResult vertex_brute_force(const Roller& roller, const Transform& pose, const Cylinder& b);
MeshPairResult vertex_barbier_galin(const Roller& roller, const Transform& pose, const Cylinder& b);
MeshPairResult vertex_quadtree_method(const Roller& roller, const RollerQuadtree& tree,
                                      const Transform& pose, const Cylinder& b, double window);

/// Body-frame angle (radians, [0, 2 pi)) of the direction from the roller's axis towards B's axis
/// (the centre of the window of Eq. (1)).
double contact_direction_angle(const Transform& pose, const Cylinder& b, double height);

}  // namespace interfere::bearing
