// Stable clash ids (issue #24, item 4): deterministic from the test, the two bodies' ids and the
// clash's location quantised at the test's grid, in the local frames of both bodies, so that the id
// survives reordered inputs, moving an unrelated body and moving the pair together, and changes
// when the clash moves on either body.
#include <cmath>
#include <cstdio>

#include "engine_internal.h"

namespace interfere::scene::detail {

std::uint64_t fnv1a(std::uint64_t h, std::string_view bytes) {
  for (const char ch : bytes) {
    h ^= static_cast<unsigned char>(ch);
    h *= 0x100000001b3ull;
  }
  return h;
}

std::string clash_id(const std::string& test, const std::string& id_a, const std::string& id_b,
                     const std::array<Vec3, 2>& locals, double grid) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  h = fnv1a(h, test), h = fnv1a(h, std::string_view("\0", 1));
  h = fnv1a(h, id_a), h = fnv1a(h, std::string_view("\0", 1));
  h = fnv1a(h, id_b), h = fnv1a(h, std::string_view("\0", 1));
  for (int k = 0; k < 6; ++k) {
    // floor(x / grid + 1/pi), clamped to 64 bits (a far point still hashes deterministically).
    // The offset keeps cell boundaries off round numbers: a clash at x = 0 or 1 mm, common in
    // designed parts, would otherwise flip cells on the last bit of a rounded transform.
    const double q = std::floor(locals[k / 3][k % 3] / grid + 0.31830988618379067);
    const long long cell = q > 9e18 ? 9000000000000000000ll : q < -9e18 ? -9000000000000000000ll : static_cast<long long>(q);
    char buf[32];
    const int n = std::snprintf(buf, sizeof buf, "%lld;", cell);
    h = fnv1a(h, std::string_view(buf, static_cast<std::size_t>(n)));
  }
  char out[24];
  std::snprintf(out, sizeof out, "C%016llx", static_cast<unsigned long long>(h));
  return out;
}

}  // namespace interfere::scene::detail
