// The library in ten lines: two overlapping spheres, every intersecting pair, the curve length.
#include <cstdio>

#include "interfere/mesh/generate.h"
#include "interfere/query/clash.h"

int main() {
  using namespace interfere;
  SpherePair parts = make_overlapping_spheres(20000);
  const Model a = make_model(std::move(parts.a));
  const Model b = make_model(std::move(parts.b));
  const ClashResult r = clash(a, b, ClashRequest{.clearance = 0.0});
  double length = 0;
  for (const ClashRegion& g : r.regions) length += g.curve_length;
  std::printf("%zu pairs (%zu cross, %zu touch), %zu regions, curve length %.6f\n", r.pairs.size(),
              r.cross_pairs, r.touch_pairs, r.regions.size(), length);
  // Two spheres of radius ~1 at distance 1.96 meet along one closed curve of length ~2π·0.199.
  return r.regions.size() == 1 && r.cross_pairs > 0 && length > 1.0 && length < 1.5 ? 0 : 1;
}
