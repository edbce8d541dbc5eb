// Scars (Jia & Zheng 2019, §2.2): diamond-square height map (Fournier, Fussell & Carpenter 1982)
// as inward (or, raised, outward) radial displacement over an (angle x height) window, median-filtered border band.
#include "interfere/bearing/scar.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace interfere::bearing {
namespace {
Error scar_error(const std::string& prefix, const char* name, const std::string& what, double got) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", got);
  return Error{.reason = prefix + "." + name + " must be " + what + ", got " + buf};
}
double wrap_angle(double a) {  // to [-pi, pi)
  const double two_pi = 2 * std::numbers::pi;
  a = std::fmod(a + std::numbers::pi, two_pi);
  if (a < 0) a += two_pi;
  return a - std::numbers::pi;
}
}  // namespace

Status validate(const ScarParams& s, const RollerParams& roller, const std::string& prefix) {
  if (!std::isfinite(s.angle_center_deg))
    return scar_error(prefix, "angle_center_deg", "finite", s.angle_center_deg);
  if (!(s.angle_width_deg > 0 && s.angle_width_deg < 360))
    return scar_error(prefix, "angle_width_deg", "in (0, 360)", s.angle_width_deg);
  if (!(s.z_min >= 0 && s.z_min < roller.height))
    return scar_error(prefix, "z_min", "in [0, roller.height) (the window must lie on the side surface)",
                      s.z_min);
  if (!(s.z_max > s.z_min && s.z_max <= roller.height))
    return scar_error(prefix, "z_max", "in (z_min, roller.height] (the window must lie on the side surface)",
                      s.z_max);
  const double rmin = std::min(roller.radius, roller.top());
  if (!(s.depth > 0 && s.depth < rmin)) return scar_error(prefix, "depth", "in (0, smallest radius)", s.depth);
  if (!(s.roughness > 0 && s.roughness <= 1)) return scar_error(prefix, "roughness", "in (0, 1]", s.roughness);
  if (s.border < 0 || s.border > 64) return scar_error(prefix, "border", "in [0, 64]", s.border);
  return {};
}

std::vector<double> diamond_square(int levels, double roughness, std::uint64_t seed) {
  const int size = (1 << levels) + 1;
  std::vector<double> h(static_cast<std::size_t>(size) * size, 0.0);
  SplitMix64 rng{seed};
  const auto at = [&](int x, int y) -> double& { return h[static_cast<std::size_t>(y) * size + x]; };
  at(0, 0) = rng.uniform(), at(size - 1, 0) = rng.uniform();
  at(0, size - 1) = rng.uniform(), at(size - 1, size - 1) = rng.uniform();
  double amp = 1.0;
  for (int step = size - 1; step > 1; step /= 2) {
    const int half = step / 2;
    for (int y = half; y < size; y += step)  // diamond
      for (int x = half; x < size; x += step)
        at(x, y) = 0.25 * (at(x - half, y - half) + at(x + half, y - half) + at(x - half, y + half) +
                           at(x + half, y + half)) + amp * rng.symmetric();
    for (int y = 0; y < size; y += half)  // square
      for (int x = (y / half) % 2 == 0 ? half : 0; x < size; x += step) {
        double sum = 0;
        int count = 0;
        if (x >= half) sum += at(x - half, y), ++count;
        if (x + half < size) sum += at(x + half, y), ++count;
        if (y >= half) sum += at(x, y - half), ++count;
        if (y + half < size) sum += at(x, y + half), ++count;
        at(x, y) = sum / count + amp * rng.symmetric();
      }
    amp *= roughness;
  }
  const auto [lo, hi] = std::minmax_element(h.begin(), h.end());
  const double l = *lo, span = *hi - *lo;
  for (double& v : h) v = span > 0 ? (v - l) / span : 0.0;
  return h;
}

bool scar_angle_contains(const ScarParams& s, double phi, double margin) {
  const double c = s.angle_center_deg * std::numbers::pi / 180.0;
  const double half = 0.5 * s.angle_width_deg * std::numbers::pi / 180.0 + margin;
  if (half >= std::numbers::pi) return true;
  return std::fabs(wrap_angle(phi - c)) <= half;
}

std::vector<double> median_filter_border(const Roller& roller, const std::vector<double>& raw,
                                         const std::vector<std::uint8_t>& inside, int border) {
  const int n = roller.n(), m = roller.m();
  // Median filter over the border band: window vertices within `border` grid steps of a vertex
  // outside the window take the median of their (2b+1)^2 neighbourhood (outside counts as 0).
  std::vector<double> out = raw;
  const int b = border;
  if (b > 0) {
    std::vector<double> nb;
    for (int j = 0; j <= m; ++j)
      for (int i = 0; i < n; ++i) {
        if (!inside[roller.side_vertex(i, j)]) continue;
        bool near_border = false;
        for (int dj = -b; dj <= b && !near_border; ++dj)
          for (int di = -b; di <= b; ++di) {
            const int jj = j + dj;
            if (jj < 0 || jj > m || !inside[roller.side_vertex(i + di, jj)]) { near_border = true; break; }
          }
        if (!near_border) continue;
        nb.clear();
        for (int dj = -b; dj <= b; ++dj)
          for (int di = -b; di <= b; ++di) {
            const int jj = j + dj;
            nb.push_back(jj < 0 || jj > m ? 0.0 : raw[roller.side_vertex(i + di, jj)]);
          }
        std::nth_element(nb.begin(), nb.begin() + nb.size() / 2, nb.end());
        out[roller.side_vertex(i, j)] = nb[nb.size() / 2];
      }
  }
  return out;
}

Expected<int> apply_scar(Roller& roller, const ScarParams& s) {
  if (Status st = validate(s, roller.params); !st) return st.error();
  const int n = roller.n(), m = roller.m();
  const double c = s.angle_center_deg * std::numbers::pi / 180.0;
  const double half = 0.5 * s.angle_width_deg * std::numbers::pi / 180.0;
  // window membership of each vertex and its (u, v) in [0,1]^2
  std::vector<double> raw(static_cast<std::size_t>(n) * (m + 1), 0.0);
  std::vector<std::uint8_t> inside(raw.size(), 0);
  int cells = 1;
  for (int i = 0; i < n; ++i) cells += std::fabs(wrap_angle(roller.angle(i) - c)) <= half;
  int levels = 1;
  while ((1 << levels) < std::max(cells, m + 1) && levels < 12) ++levels;
  const std::vector<double> map = diamond_square(levels, s.roughness, s.seed);
  const int size = (1 << levels) + 1;
  for (int j = 0; j <= m; ++j) {
    const double z = roller.z(j);
    if (z < s.z_min || z > s.z_max) continue;
    const double v = (z - s.z_min) / (s.z_max - s.z_min);
    for (int i = 0; i < n; ++i) {
      const double d = wrap_angle(roller.angle(i) - c);
      if (std::fabs(d) > half) continue;
      const double u = (d + half) / (2 * half);
      const double fx = u * (size - 1), fy = v * (size - 1);
      const int x0 = std::min(static_cast<int>(fx), size - 2), y0 = std::min(static_cast<int>(fy), size - 2);
      const double ax = fx - x0, ay = fy - y0;
      const auto at = [&](int x, int y) { return map[static_cast<std::size_t>(y) * size + x]; };
      const double hval = (1 - ay) * ((1 - ax) * at(x0, y0) + ax * at(x0 + 1, y0)) +
                          ay * ((1 - ax) * at(x0, y0 + 1) + ax * at(x0 + 1, y0 + 1));
      raw[roller.side_vertex(i, j)] = (s.raised ? -s.depth : s.depth) * hval;
      inside[roller.side_vertex(i, j)] = 1;
    }
  }
  const std::vector<double> out = median_filter_border(roller, raw, inside, s.border);
  int labelled = 0;
  for (std::size_t k = 0; k < out.size(); ++k) {
    roller.displacement[k] = out[k];
    roller.scar[k] = inside[k];
    labelled += inside[k];
  }
  roller.has_scar = labelled > 0;
  roller.update_positions();
  return labelled;
}

}  // namespace interfere::bearing
