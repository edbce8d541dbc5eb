// Eq. (1) of Jia & Zheng 2019, "ideal maximum interference range" (reconstructed; derivation in
// docs/bearing.md): theta = asin(h_b sin(alpha) / (R + r)).
#include "interfere/bearing/window.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

namespace interfere::bearing {

Status validate(const WindowParams& w) {
  char buf[160];
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
  if (!(w.max_tilt >= 0 && w.max_tilt < std::numbers::pi / 2)) {
    std::snprintf(buf, sizeof buf, "max_tilt must be in [0, 90) degrees, got %.17g degrees",
                  w.max_tilt * 180 / std::numbers::pi);
    return Error{.reason = buf};
  }
  if (!(w.height * std::sin(w.max_tilt) < w.roller_radius + w.partner_radius)) {
    std::snprintf(buf, sizeof buf,
                  "max_tilt %.17g degrees is beyond the range of Eq. (1): h_b*sin(alpha) = %.17g must be "
                  "< R + r = %.17g",
                  w.max_tilt * 180 / std::numbers::pi, w.height * std::sin(w.max_tilt),
                  w.roller_radius + w.partner_radius);
    return Error{.reason = buf};
  }
  return {};
}

double interference_window(const WindowParams& w) {
  const double s = w.height * std::sin(w.max_tilt) / (w.roller_radius + w.partner_radius);
  return std::asin(s < 1 ? (s > 0 ? s : 0.0) : 1.0);
}

}  // namespace interfere::bearing
