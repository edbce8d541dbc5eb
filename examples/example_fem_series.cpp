// FEM parts through a load-step series: extract the boundary surfaces of two bodies, move one by a
// displacement field per step, refit + clash per step, and name the first clash by element ids.
#include <cstdio>

#include "interfere/fem/deform.h"
#include "interfere/fem/generate.h"
#include "interfere/fem/surface.h"

int main() {
  using namespace interfere;
  // Body A: a hex20 block [0,1]^3; body B: a tet10 ball of radius 0.4 starting at x = 2.
  const FemMesh a = make_fem_box({.type = ElemType::hex20, .nx = 4, .ny = 4, .nz = 4}).mesh;
  const FemMesh b = make_fem_sphere({.type = ElemType::tet10, .nx = 6, .ny = 6, .nz = 6}, 0.4, {2, 0.5, 0.5}).mesh;
  auto sa = extract_surface(a), sb = extract_surface(b);
  if (!sa || !sb) return 1;

  // B moves by -0.11 in x per step: its leftmost point (x = 1.6) passes A's face x = 1 between steps 5
  // (gap 0.05) and 6 (0.06 deep).
  NodalSeries u{.name = "u"};
  for (int s = 0; s < 10; ++s) {
    u.times.push_back(0.1 * s);
    u.values.emplace_back(b.num_nodes(), Vec3{-0.11 * s, 0, 0});
  }
  auto r = clash_series({&a, &sa->parts[0], nullptr}, {&b, &sb->parts[0], &u});
  if (!r) {
    std::fprintf(stderr, "%s\n", r.error().message().c_str());
    return 1;
  }
  for (const StepSummary& s : r->steps) {
    std::printf("step %zu: %zu pairs, %zu regions, max curve %.4f\n", s.step, s.pairs, s.regions, s.max_curve_length);
  }
  std::printf("first clash at step %lld\n", static_cast<long long>(r->first_clash_step));
  if (r->first_clash_step < 0) return 1;
  const RegionIds ids = region_ids(r->first_clash.regions.at(0), sa->parts[0], a, sb->parts[0], b);
  std::printf("elements of A:");
  for (std::int64_t id : ids.elements_a) std::printf(" %lld", static_cast<long long>(id));
  std::printf("\n");
  return r->first_clash_step == 6 ? 0 : 1;
}
