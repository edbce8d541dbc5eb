// The standard solver (Jia & Zheng 2019, §3.1, "no scar in range"): the maximum interference
// distance between two finite solid cylinders A (the roller) and B (the partner),
//
//     s(A, B) = min over points p of solid A of sd_B(p)                                  (*)
//
// with sd_B the signed distance to solid B (cylinder.h). s > 0 is the clearance (the Euclidean
// distance between the solids); s < 0 means interference and -s is the depth of A's deepest point
// inside B measured to B's boundary: the "maximum interference distance". Witnesses: p on A where
// the minimum is reached, q the point of B's boundary nearest p.
//
// Method (docs/bearing.md §"Standard solver"): sd_B >= rho_B - R everywhere (rho_B = distance to
// B's axis line), and min over A of rho_B is a planar problem: A projects along B's axis onto the
// Minkowski sum of a segment (the projected axis of A) and an ellipse (the projected end disk,
// semi-axes r and r|cos gamma|, the segment along the minor axis). The point-to-"elliptic stadium"
// distance is the axis-segment closest points (side contact: rho = d - r) or a point-to-ellipse
// distance (end-circle contact; Eberly, "Distance from a point to an ellipse", robust bisection),
// which is Eberly's circle-to-line case of "Distance to Circles in 3D". When sd_B(p*) = rho_B(p*) -
// R at that minimiser p* (B's side is the nearest part of B: a certificate checked explicitly), the
// value is exact to rounding in O(1). A tapered A projects onto the convex hull of ellipses of
// linearly varying size: the distance is a convex function of the axis parameter, minimised by a
// golden-section search with a point-to-ellipse distance per step (then the same certificate).
// Otherwise (B's end face or rim involved, deep overlap where B's axis crosses A): when an
// untapered A contains a point of B's core — the points of B at its greatest depth min(R, h/2),
// the axis segment |z| <= h/2 - R or the mid-plane disk rho <= R - h/2 — s is exactly -min(R, h/2)
// (the `core` path: a 1-D or 2-D convex search of sd_A over the core finds such a point); else a
// general exact-to-rounding fallback minimises the convex sd_B over the convex A by nested
// golden-section searches (partial minimisation keeps convexity). Before that fallback, for axes
// within 60 degrees (A possibly tapered), the `slice` path: sd_B(p) = phi(rho_B, z_B) with phi
// nondecreasing in rho, so s = min over z of phi(F(z), z), F(z) the distance from B's axis point at
// height z to A's cross-section by the plane across B's axis there (an ellipse clipped by A's end
// planes: point-to-ellipse distance or a chord's, closed form); the function is convex (partial
// minimisation), so one golden-section search over z is exact (clear or overlapping). The same
// path serves cone_pair_distance (raceway.h) for a tapered B.
#pragma once
#include <cstdint>

#include "interfere/bearing/cylinder.h"

namespace interfere::bearing {

enum class AnalyticPath : std::uint8_t {
  side,      ///< axis-segment closest points, side of A against side of B (closed form)
  end,       ///< end circle of A against side of B (point-to-ellipse)
  parallel,  ///< parallel axes (the projected segment is a point), closed form
  tapered,   ///< tapered roller: 1-D convex search over the axis, point-to-ellipse per disk
  general,   ///< nested convex minimisation (end faces of B, deep overlap)
  core,      ///< A (untapered) contains a point of B's core (its deepest points): s = -min(R, h/2)
  // raceway.h (issue #27): the bearing's ring pairs
  bore,      ///< roller in a cylindrical bore: farthest point of an end-circle ellipse (closed form)
  cup,       ///< roller in a conical cup: 1-D maximisation over an end circle
  rib,       ///< roller end against a rib face (end circle or annulus-edge curve)
  cone,      ///< A against a cone frustum B: certified lateral (dual) solution
  apart,     ///< a lower bound of the distance (the roller misses or overhangs the ring's width, misses the annulus)
  slice,     ///< overlapping untapered pair, by B's cross-sections: a convex 1-D search (analytic.cpp)
};
const char* analytic_path_name(AnalyticPath p);

struct PairDistance {
  double distance = 0;  ///< s(A, B) of (*): > 0 clearance, < 0 interference depth (negated)
  Vec3 point_a;         ///< on A, where the minimum is reached
  Vec3 point_b;         ///< on B's boundary, nearest point_a
  AnalyticPath path = AnalyticPath::side;
};

/// s(A, B) for a (possibly tapered) A and an untapered B. Never NaN for finite valid input.
PairDistance cylinder_pair_distance(const Cylinder& a, const Cylinder& b);

/// The general path only (the fallback), exposed for tests: nested golden-section minimisation.
PairDistance cylinder_pair_distance_general(const Cylinder& a, const Cylinder& b);

/// min over A of rho_B and its minimiser (the radial lower bound), for tests and the window check.
struct RadialMin {
  double rho = 0;
  Vec3 point;
  AnalyticPath path = AnalyticPath::side;
};
RadialMin min_axis_distance(const Cylinder& a, const Vec3& line_point, const Vec3& line_dir);

/// Distance from (y0, y1) (any signs) to the solid ellipse x0^2/e0^2 + x1^2/e1^2 <= 1 with
/// e0 >= e1 >= 0, and the nearest point (Eberly's robust bisection; e1 == 0 is a segment).
struct EllipsePoint {
  double distance = 0, x0 = 0, x1 = 0;
};
EllipsePoint point_ellipse_distance(double e0, double e1, double y0, double y1);

/// The witness on B's boundary nearest p (p outside or inside).
Vec3 nearest_on_cylinder_boundary(const Cylinder& b, const Vec3& p);

}  // namespace interfere::bearing
