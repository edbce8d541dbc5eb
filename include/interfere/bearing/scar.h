// Scars on the side of a roller (Jia & Zheng 2019, §2.2): a radial height map made by the
// diamond-square algorithm (Fournier, Fussell & Carpenter, "Computer rendering of stochastic
// models", CACM 25(6), 1982), applied as an inward radial displacement (or, with `raised`, an
// outward one: the paper's §2.2 says the disturbance is inward "in most cases", not always; issue
// #27) over an (angle x height) window of the side surface; a median filter over the window's border band joins the scar to the
// intact surface. Seeded and reproducible (SplitMix64; no std:: distributions, whose output is
// implementation-defined).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "interfere/bearing/roller.h"
#include "interfere/core/error.h"

namespace interfere::bearing {

struct ScarParams {
  double angle_center_deg = 0.0;  ///< centre of the window, degrees, body frame (any value, mod 360)
  double angle_width_deg = 40.0;  ///< angular width (0, 360)
  double z_min = 10.0;            ///< window bottom, body-frame height, in [0, height)
  double z_max = 30.0;            ///< window top, in (z_min, height]
  double depth = 0.05;            ///< largest displacement (> 0, < the smallest radius)
  double roughness = 0.6;         ///< diamond-square amplitude factor per level, in (0, 1]
  int border = 2;                 ///< median-filter band, in grid cells (>= 0)
  std::uint64_t seed = 1;
  /// false: inward (a pit, the default); true: outward (a raised scar, issue #27). Last, so that
  /// positional initialisers of the fields above keep their meaning.
  bool raised = false;
};

Status validate(const ScarParams& s, const RollerParams& roller, const std::string& prefix = "scar");

/// Deterministic 64-bit generator (SplitMix64, Steele, Lea & Flood 2014).
struct SplitMix64 {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1p-53; }  ///< [0, 1)
  double symmetric() { return 2.0 * uniform() - 1.0; }                     ///< [-1, 1)
};

/// Diamond-square height map of (2^levels + 1)^2 values, row-major, normalised to [0, 1].
std::vector<double> diamond_square(int levels, double roughness, std::uint64_t seed);

/// Applies the scar to the roller's side: displacement = depth * height map (bilinear over the
/// window; negated when `raised`), then the median filter over the border band, then labels and positions. Returns the
/// number of side vertices labelled as scar.
Expected<int> apply_scar(Roller& roller, const ScarParams& s);

/// The median filter of apply_scar: every vertex with inside = 1 within `border` grid steps (in the
/// (2 border + 1)^2 neighbourhood, columns wrapping) of a vertex with inside = 0 or of the grid's end
/// rings takes the median of that neighbourhood of `raw` (beyond the end rings: 0); the others
/// keep their value. `raw` and `inside` are per side vertex.
std::vector<double> median_filter_border(const Roller& roller, const std::vector<double>& raw,
                                         const std::vector<std::uint8_t>& inside, int border);

/// True when body-frame angle `phi` (radians) lies in the scar window's angular range, widened by
/// `margin` radians on each side.
bool scar_angle_contains(const ScarParams& s, double phi, double margin);

}  // namespace interfere::bearing
