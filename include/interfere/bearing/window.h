// The "ideal maximum interference range" of Jia & Zheng 2019, §2.3, Eq. (1) (issue #27; the
// derivation and its validity range are in docs/bearing.md, "Eq. (1)").
//
// Figs. 3-4 of the paper: parts A (radius r, the part whose vertices are searched: here the roller)
// and B (radius R) with parallel axes at distance R + r (touching). B tilts towards A by alpha
// about its bottom end centre; the paper takes the interference depth at the top end as
// h_b*tan(alpha) and the tilted top face, seen from above, as a circle again. In the top view the
// circle of A (centre C, radius r) and the circle of B's top face (centre T_b, radius R) then lie
// at distance CT_b = (R + r) - h_b*tan(alpha) and overlap in a lens with corners M and N. The
// maximum interference point pair lies within the cylindrical region bounded by MN; its angular
// extent seen from C is theta = angle MCN. In triangle MCT_b (MC = r, MT_b = R, angle MCT_b =
// theta/2) the law of cosines gives
//        theta = 2 * acos( (r^2 + d^2 - R^2) / (2 r d) ),   d = (R + r) - h_b*tan(alpha).    (1)
// (The printed formula is garbled by the text extraction; this is its reconstruction from the
// paper's definitions: 37.4 degrees for r = 10, R = 30, h_b = 40, alpha = 1 degree.)
//
// Validity: the lens (a non-degenerate triangle MCT_b) exists iff |R - r| < d <= R + r, i.e.
//        0 <= h_b*tan(alpha) < 2*min(r, R)   <=>   0 <= alpha < atan(2*min(r, R) / h_b).
// At alpha = 0 the circles touch (theta = 0). Towards the upper end the smaller circle becomes
// internally tangent to the larger one (r < R: theta -> 360 degrees, every direction; r > R: theta
// -> 0, B's circle inside A's; r = R: the circles coincide, theta -> 180 degrees); from there on one
// circle contains the other, the lens does not exist and Eq. (1) is undefined: validate() rejects
// it. theta grows monotonically with alpha for r <= R; for r > R it peaks at 2 asin(R / r).
// The paper's two simplifications (depth h_b tan(alpha) instead of the top's shift h_b sin(alpha),
// and the tilted top face seen as a circle instead of the cut ellipse of semi-axis R / cos(alpha))
// make theta smaller than the true 3D cut by a relative amount of order R*alpha / (4 h_b) (0.3 % in
// the example above; tests/unit/bearing/test_bearing_window.cpp).
#pragma once
#include "interfere/core/error.h"

namespace interfere::bearing {

struct WindowParams {
  double roller_radius = 10;   ///< r (part A, whose range is computed)
  double partner_radius = 30;  ///< R (part B)
  double height = 40;          ///< h_b, the length of the tilting part
  double max_tilt = 0.0175;    ///< alpha, radians
};

/// The tilt (radians) at which Eq. (1) degenerates, atan(2 min(r, R) / h_b): valid tilts are below it.
/// Radii and height must be valid (validate()).
double max_valid_tilt(const WindowParams& w);

/// Checks r, R, h_b > 0 (finite) and 0 <= alpha < max_valid_tilt(w); the error names the
/// parameter and, for alpha, the range of Eq. (1).
Status validate(const WindowParams& w);

/// theta = angle MCN of Eq. (1), radians, in [0, 2 pi]: the full angular extent of the range,
/// centred on the direction from A's axis towards B's axis. Call validate(w) first (outside the
/// range the acos argument is clamped: never NaN, but meaningless).
double ideal_interference_range(const WindowParams& w);

/// The window half-width used by the searches: theta / 2 = angle MCT_b (radians, in [0, pi]).
double interference_window(const WindowParams& w);

/// The project's former window (kept measurable, not used by default): the largest turn of the
/// contact direction when the top of A's axis moves by h_b sin(alpha), asin(h_b sin(alpha) / (R + r)).
/// A tight bound on how far the exact maximum-interference point moves from the current contact
/// direction (tests: BearingWindow.ContactTurnBound*); not the paper's range. Requires
/// h_b sin(alpha) <= R + r (clamped otherwise).
double contact_turn_bound(const WindowParams& w);

}  // namespace interfere::bearing
