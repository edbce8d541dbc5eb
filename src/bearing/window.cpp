// Eq. (1) of Jia & Zheng 2019, §2.3, "ideal maximum interference range" (issue #27), reconstructed
// from the paper's triangle MCT_b with the law of cosines; derivation and validity range in
// window.h and docs/bearing.md.
#include "interfere/bearing/window.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

namespace interfere::bearing {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

}  // namespace

double max_valid_tilt(const WindowParams& w) {
  return std::atan(2 * std::min(w.roller_radius, w.partner_radius) / w.height);
}

Status validate(const WindowParams& w) {
  char buf[320];
  if (!(std::isfinite(w.roller_radius) && w.roller_radius > 0)) {
    std::snprintf(buf, sizeof buf, "roller radius r must be > 0, got %.17g", w.roller_radius);
    return Error{.reason = buf};
  }
  if (!(std::isfinite(w.partner_radius) && w.partner_radius > 0)) {
    std::snprintf(buf, sizeof buf, "partner radius R must be > 0, got %.17g", w.partner_radius);
    return Error{.reason = buf};
  }
  if (!(std::isfinite(w.height) && w.height > 0)) {
    std::snprintf(buf, sizeof buf, "roller height h_b must be > 0, got %.17g", w.height);
    return Error{.reason = buf};
  }
  const double amax = max_valid_tilt(w);
  if (!(w.max_tilt >= 0 && w.max_tilt < amax)) {
    std::snprintf(buf, sizeof buf,
                  "max_tilt %.15g degrees is outside the range of Eq. (1) (Jia & Zheng 2019, section 2.3): "
                  "it must be in [0, %.15g) degrees = [0, atan(2 min(r, R) / h_b)) for r = %.17g, R = %.17g, "
                  "h_b = %.17g (from there on one top-view circle lies inside the other and the "
                  "interference range does not exist)",
                  w.max_tilt / kDeg, amax / kDeg, w.roller_radius, w.partner_radius, w.height);
    return Error{.reason = buf};
  }
  return {};
}

double ideal_interference_range(const WindowParams& w) {
  const double r = w.roller_radius, R = w.partner_radius;
  const double d = (R + r) - w.height * std::tan(w.max_tilt);  // CT_b
  // law of cosines in triangle MCT_b: R^2 = r^2 + d^2 - 2 r d cos(angle MCT_b); written as
  // ((r - R)(r + R) + d^2) / (2 r d) to keep the cancellation of r^2 - R^2 exact
  if (!(d > 0)) return 2 * std::numbers::pi;  // outside the valid range (validate() rejects it)
  const double c = ((r - R) * (r + R) + d * d) / (2 * r * d);
  return 2 * std::acos(std::clamp(c, -1.0, 1.0));
}

double interference_window(const WindowParams& w) { return 0.5 * ideal_interference_range(w); }

double contact_turn_bound(const WindowParams& w) {
  const double s = w.height * std::sin(w.max_tilt) / (w.roller_radius + w.partner_radius);
  return std::asin(std::clamp(s, 0.0, 1.0));
}

}  // namespace interfere::bearing
