// Shared inputs of the bearing assembly tests (test_assembly*.cpp; issue #27): small valid
// descriptions (one cylindrical, one tapered bearing) as JSON text.
#pragma once
#include <string>

namespace interfere::bearing::test {

inline const char* kCylindricalBearing = R"({
      "id": "cyl", "type": "cylindrical", "position": [0, 0, 0], "axis": [0, 0, 1],
      "inner_ring": {"bore_radius": 20, "raceway_radius": 30, "width": 30, "rib": {"height": 3, "width": 4}},
      "outer_ring": {"raceway_radius": 50.1, "outer_radius": 58, "width": 30},
      "rollers": {"count": 10, "radius": 10, "length": 20, "pitch_radius": 40.05, "radial_segments": 24, "height_segments": 23},
      "cage": {"pocket_clearance": 0.25, "web_thickness": 6}
    })";

inline const char* kTaperedBearing = R"({
      "id": "tap", "type": "tapered", "position": [300, 10, -5], "axis": [1, 1, 0],
      "contact_angle_deg": 20,
      "cone": {"bore_radius": 25, "clearance": 0.02},
      "cup": {"outer_radius": 75, "clearance": 0.02},
      "rollers": {"count": 12, "radius": 8, "top_radius": 9.5, "length": 30, "radial_segments": 24, "height_segments": 23},
      "cage": {"pocket_clearance": 0.3, "web_thickness": 6}
    })";

/// A whole description: `extra` goes at the top level (e.g. "\"frames\": 3,"), the bearings given.
inline std::string assembly_json(const std::string& extra, const std::string& bearings) {
  return "{" + extra + "\"bearings\": [" + bearings + "]}";
}

inline std::string both_bearings() {
  return std::string(kCylindricalBearing) + "," + kTaperedBearing;
}

/// Motion with load, tilts, play and scars, so that most pair kinds clash in some frames.
inline const char* kLively =
    R"("frames": 4, "seed": 3, "clearance": 0.05,
       "motion": {"inner_deg_per_frame": 7, "max_tilt_deg": 0.1, "load": {"direction_deg": 270, "displacement": 0.08},
                  "pocket_play": 1.3, "axial_play": 1.05},
       "scar": {"fraction": 0.3, "angle_width_deg": 90, "depth": 0.05, "seed": 5},)";

}  // namespace interfere::bearing::test
