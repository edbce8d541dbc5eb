// The "ideal maximum interference range" (Jia & Zheng 2019, Eq. (1), reconstructed and derived in
// docs/bearing.md): a roller of radius r and length h_b pivots about its bottom end centre by a
// tilt of at most alpha next to a partner of radius R (axes at distance R + r). The top end of its
// axis moves by at most h_b*sin(alpha) in any direction; seen from the partner's axis the contact
// direction turns by at most
//        theta = asin( h_b * sin(alpha) / (R + r) ),                                  (1)
// which is the half-width of the angular window of roller vertices that can hold the maximum
// interference. Eq. (1) holds for 0 <= alpha < pi/2 and h_b*sin(alpha) < R + r.
#pragma once
#include "interfere/core/error.h"

namespace interfere::bearing {

struct WindowParams {
  double roller_radius = 10;   ///< r
  double partner_radius = 30;  ///< R
  double height = 40;          ///< h_b
  double max_tilt = 0.0175;    ///< alpha, radians
};

/// Checks the ranges named above; the error names the parameter.
Status validate(const WindowParams& w);

/// theta of Eq. (1), radians. Call validate(w) first: outside Eq. (1)'s range the asin argument
/// is clamped to [0, 1] (never NaN), which is meaningless there.
double interference_window(const WindowParams& w);

}  // namespace interfere::bearing
