// A lower bound of the Euclidean distance of a roller and a rib block by supporting planes, for the
// rib rows that are not two-sided (rib_euclid_bound.h; issue #27, docs/bearing.md "Limitations").
#include "rib_euclid_bound.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "assembly_tapered_scars.h"
#include "raceway_detail.h"
#include "interfere/bearing/part_pair.h"

namespace interfere::bearing::detail {
namespace {

/// min over the solid frustum c of w.(x - o), unit w: the lower of its two rims' minima (c is the
/// convex hull of its rims), c_k.w - r_k |w across d| (accurate_across: exactly 0 for w = +-d).
double support_min(const Cylinder& c, const Vec3& o, const Vec3& w) {
  const double across = norm(accurate_across(w, c.axis));
  return std::min(dot(c.base - o, w) - c.radius * across, dot(c.top_center() - o, w) - c.top() * across);
}

/// The rounding margin: 2^-40 of the pair's scale (coordinates relative to the face centre).
double margin_of(const Cylinder& c, const Rib& rib, double thickness) {
  const Vec3 m = c.center() - rib.center;
  return 0x1p-40 * (1 + std::fabs(m.x) + std::fabs(m.y) + std::fabs(m.z) + c.height + c.max_radius() + rib.outer_radius +
                    thickness);
}

}  // namespace

double rib_support_gap(const Cylinder& c, const Rib& rib, double thickness, const Vec3& w) {
  // max over Q = {rho <= r_o, -T <= l <= 0} of w.(x - o): r_o |w across the ring axis| from the
  // disk, plus -T w.n when w points into the rib (its back face)
  const double a = dot(w, rib.normal);
  const double hq = rib.outer_radius * norm(accurate_across(w, rib.axis)) + std::max(0.0, -thickness * a);
  return support_min(c, rib.center, w) - hq;
}

double rib_euclid_lower(const Cylinder& c, const Rib& rib, double thickness, int level) {
  // w = n: the lowest height over the face plane (max over Q of n.(x - o) = 0), raceway_detail.h's
  double best = lowest_height(c, rib.center, rib.normal);
  if (level >= 1)  // w = the roller's axis toward the rib's side: its end face's plane against the top edge
    best = std::max(best, rib_support_gap(c, rib, thickness, dot(c.axis, rib.normal) >= 0 ? c.axis : -c.axis));
  if (level >= 2) {  // any w is sound: the solver's witnesses give a good one (its accuracy is not relied on)
    Cylinder qc;
    qc.base = rib.center - rib.normal * thickness, qc.axis = rib.normal;
    qc.height = thickness, qc.radius = rib.outer_radius, qc.top_radius = -1;
    const PairDistance f = cylinder_pair_distance(c, qc);
    const Vec3 v = f.point_a - f.point_b;
    if (f.distance > 0 && norm(v) > 0) best = std::max(best, rib_support_gap(c, rib, thickness, v / norm(v)));
  }
  const double lower = best - margin_of(c, rib, thickness);
  return lower == lower ? lower : -std::numeric_limits<double>::infinity();  // (NaN would read as clear)
}

namespace {

/// The first of E's lower bounds (the levels in turn, cheapest first: most rows are decided by the
/// lowest height) whose verdict is `want`, for a row whose solid lies in `roller` grown by `raise`.
std::optional<double> lower_giving(Verdict want, const Cylinder& roller, double raise, const Rib& rib, double thickness,
                                   double clearance, double tol) {
  const Cylinder c = raise > 0 ? grown_roller_solid(roller, raise) : roller;  // (holds a scarred roller's A')
  for (int level = 0; level < 3; ++level)
    if (const double lower = rib_euclid_lower(c, rib, thickness, level); distance_verdict(lower, tol, clearance) == want)
      return lower;
  return std::nullopt;
}

}  // namespace

void rib_euclid_decide_clear(AssemblyPairResult& row, const Cylinder& roller, double raise, const Rib& rib,
                             double thickness, double clearance, double tol) {
  const std::optional<double> lower = lower_giving(Verdict::clear, roller, raise, rib, thickness, clearance, tol);
  if (!lower) {
    row.verdict = Verdict::undecided;
    return;
  }
  if (!row.exact) row.distance = std::max(row.distance, *lower);  // (a lower bound either way)
  row.verdict = Verdict::clear;
}

void rib_euclid_verdict(AssemblyPairResult& row, const Cylinder& roller, double raise, const Rib& rib, double thickness,
                        double clearance, double tol, bool apart_bound) {
  if (row.exact && row.two_sided) return;  // S (ring_two_sided.h, scarred_rib_two_sided.h)
  if (apart_bound && row.path == AnalyticPath::apart) return;  // a lower bound of E already
  if (row.verdict != Verdict::clear && row.verdict != Verdict::clearance) return;
  // a bracket [lower, value]: the verdict both ends give (clear: lower >= the clearance; clearance:
  // lower above the touch tolerance, the value (>= E: an attained height over the annulus) below it)
  if (!lower_giving(row.verdict, roller, raise, rib, thickness, clearance, tol)) row.verdict = Verdict::undecided;
}

}  // namespace interfere::bearing::detail
