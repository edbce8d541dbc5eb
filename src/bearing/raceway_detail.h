// Shared pieces of the raceway solvers (raceway.cpp, raceway_rib.cpp, raceway_cone.cpp).
#pragma once
#include <algorithm>
#include <array>
#include <functional>
#include <cmath>
#include <numbers>
#include <utility>

#include "golden.h"
#include "interfere/bearing/analytic.h"
#include "interfere/bearing/cylinder.h"

namespace interfere::bearing::detail {

inline Vec3 perpendicular_unit(const Vec3& u) {
  const Vec3 t = std::fabs(u.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  const Vec3 p = cross(u, t);
  return p / norm(p);
}

/// An end circle of a roller: centre, radius; the roller's unit axis is its normal.
struct Rim {
  Vec3 c;
  double r = 0;
};

/// The radius of frustum c at axis parameter t in [0, height].
/// d x u for unit axes, also when they are nearly (anti)parallel: there cross(d, u) is rounding
/// noise and its direction arbitrary, so it is taken as the same vector (d -+ u) x u, whose d -+ u
/// is exact (Sterbenz). Review, issue #27 (test_review_parallel_axes.cpp, test_review_bore_rim.cpp).
inline Vec3 accurate_cross(const Vec3& d, const Vec3& u) {
  const Vec3 cr = cross(d, u);
  return norm(cr) < 0x1p-10 ? cross(dot(d, u) >= 0 ? d - u : d + u, u) : cr;
}

/// v - n (n . v), v's part across the unit n, for unit v, also when v and n are nearly
/// (anti)parallel: then as del - n (del . n), del = v -+ n exact (Sterbenz), the same vector.
inline Vec3 accurate_across(const Vec3& v, const Vec3& n) {
  const Vec3 m = v - n * dot(n, v);
  if (!(norm(m) < 0x1p-10)) return m;
  const Vec3 del = dot(n, v) >= 0 ? v - n : v + n;
  return del - n * dot(del, n);
}

/// The lowest height over the plane through `center` with unit normal `n` of a cylinder or frustum
/// c: the lower of its two rims' lowest points (closed form; the rib rows' rule, intact and scarred:
/// ring_two_sided.cpp, assembly_pairs.cpp, scarred_rib_two_sided.cpp).
inline double lowest_height(const Cylinder& c, const Vec3& center, const Vec3& n) {
  const double nu = std::clamp(dot(n, c.axis), -1.0, 1.0), s = std::sqrt(std::max(0.0, 1 - nu * nu));
  return std::min(dot(c.base - center, n) - c.radius * s, dot(c.top_center() - center, n) - c.top() * s);
}

inline double radius_at(const Cylinder& c, double t) { return c.radius + (c.top() - c.radius) * (t / c.height); }

/// The point of the roller's rim at axis parameter t and angle phi in the frame (f1, f2).
inline Vec3 rim_point(const Rim& rim, const Vec3& f1, const Vec3& f2, double phi) {
  return rim.c + f1 * (rim.r * std::cos(phi)) + f2 * (rim.r * std::sin(phi));
}

/// max over one end circle (axis d) of the distance to the line base + z u, and the circle's point
/// where it is reached (raceway.cpp: farthest point of the projected ellipse, closed form to rounding).
std::pair<double, Vec3> max_axis_distance_on_rim(const Rim& rim, const Vec3& d, const Vec3& base, const Vec3& u);

/// Maximises a smooth 2*pi-periodic h over the angle: 32 samples, then every sampled local maximum
/// among the three largest is refined by golden-section search on its bracket [phi_i - step,
/// phi_i + step] (where h is unimodal unless two maxima lie within one step of each other; then their
/// values agree to the variation of h over a step's neighbourhood of a near-flat top).
template <class H>
std::pair<double, double> max_over_angle(H&& h) {
  constexpr int kN = 32;
  constexpr double kStep = 2 * std::numbers::pi / kN;
  std::array<double, kN> v{};
  for (int i = 0; i < kN; ++i) v[i] = h(i * kStep);
  std::array<int, kN> peaks{};
  int np = 0;
  for (int i = 0; i < kN; ++i) {
    const double l = v[(i + kN - 1) % kN], r = v[(i + 1) % kN];
    if (v[i] >= l && v[i] >= r) peaks[np++] = i;
  }
  std::sort(peaks.begin(), peaks.begin() + np, [&](int a, int b) { return v[a] > v[b]; });
  double best_phi = 0, best = v[0];
  for (int i = 0; i < kN; ++i)
    if (v[i] > best) best = v[i], best_phi = i * kStep;
  for (int k = 0; k < std::min(np, 3); ++k) {
    const double c = peaks[k] * kStep;
    const auto [phi, neg] = golden_min([&](double x) { return -h(x); }, c - kStep, c + kStep, 80);
    if (-neg > best) best = -neg, best_phi = phi;
  }
  return {best_phi, best};
}

}  // namespace interfere::bearing::detail

namespace interfere::bearing::detail {

/// The axial extent [zmin, zmax] (along unit u, from base) of a roller's solid and its extreme
/// points: the end circles' points farthest down and up along u (raceway_slab.cpp).
struct AxialExtent {
  double zmin = 0, zmax = 0;
  Vec3 low, high;
};
AxialExtent axial_extent(const Cylinder& roller, const Vec3& base, const Vec3& u);

/// max over K = roller /\ {zlo <= z <= zhi} (z along u from base; K non-empty) of a convex f, and
/// the point where it is reached (raceway_slab.cpp). The maximum of a convex function over the
/// convex K is at an extreme point of K: on an end circle's arc within the slab, or on one of the
/// two curves where the roller's lateral surface crosses the planes z = zlo, z = zhi. Each curve is
/// parametrised by the roller's own angle; the angles where an end circle crosses a plane (closed
/// form) split the circle into intervals on which every curve is either wholly inside the slab or
/// wholly outside it; on each, f is sampled and every sampled local maximum refined by golden-
/// section search, the intervals' ends (the curves' meeting points) included.
/// The `slice` path of the standard solver and of cone_pair_distance (analytic.cpp, analytic.h):
/// s(A, B) for frustums A and B whose axes are within 60 degrees (and A's cone not too open for its
/// tilt); false when it does not apply.
bool slice_distance(const Cylinder& a, const Cylinder& b, PairDistance& out);

struct SlabMax {
  double value = 0;
  Vec3 point;
};
SlabMax max_convex_over_slab(const Cylinder& roller, const Vec3& base, const Vec3& u, double zlo, double zhi,
                             const std::function<double(const Vec3&)>& f);

}  // namespace interfere::bearing::detail
