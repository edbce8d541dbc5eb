// The input's contact zone of the simplifier's self-intersection guard (src/simplify/contact_zone.h):
// which intersecting pairs of a result count as the input's own contact, moved.
#include <gtest/gtest.h>

#include <array>

#include "../../../src/simplify/contact_zone.h"
#include "interfere/np/tri_tri.h"

namespace interfere::qem {
namespace {

using Tri3 = std::array<Vec3, 3>;

// A vertical triangle through a horizontal one at x in [0, 1] near the origin: the input's only
// intersecting pair (plus far away, a lone triangle).
TriMesh crossing_input() {
  TriMesh m;
  m.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0},             // horizontal
                 {0.5, 0, -1}, {0.5, 0.2, 1}, {0.5, -0.3, 1},    // vertical, through it at x = 0.5
                 {50, 50, 50}, {51, 50, 50}, {50, 51, 50}};      // far
  m.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}};
  return m;
}

TEST(ContactZone, MadeFromTheInputsOwnPairsOnly) {
  EXPECT_TRUE(ContactZone(TriMesh{}).empty());
  TriMesh apart = crossing_input();
  apart.triangles.erase(apart.triangles.begin() + 1);  // no crossing left
  EXPECT_TRUE(ContactZone(apart).empty());
  const ContactZone z(crossing_input());
  EXPECT_EQ(z.input_pairs(), 1u);
}

TEST(ContactZone, HoldsACrossingMovedNearTheInputsButNotOneElsewhere) {
  const ContactZone z(crossing_input());
  const Tri3 flat{Vec3{-1, -1, 0}, Vec3{1, -1, 0}, Vec3{0, 1, 0}};
  // The vertical triangle moved a little (a collapse nearby): its crossing stays in the zone.
  const Tri3 moved{Vec3{0.6, 0, -1}, Vec3{0.55, 0.3, 1}, Vec3{0.5, -0.3, 1}};
  ASSERT_TRUE(tri_tri_exact_intersects(moved, flat));
  EXPECT_TRUE(z.holds(moved, flat));
  EXPECT_TRUE(z.holds(flat, moved));
  // The same pair touching at a vertex of the vertical triangle, near the crossing: held.
  const Tri3 touching{Vec3{0.5, 0, 0}, Vec3{0.5, 0.2, 1}, Vec3{0.5, -0.3, 1}};
  ASSERT_EQ(tri_tri_exact(touching, flat).kind, ContactKind::touch);
  EXPECT_TRUE(z.holds(touching, flat));
  // Two triangles crossing far from the input's crossing (a fold elsewhere): not held.
  const Tri3 far_a{Vec3{49, 49, 50}, Vec3{52, 49, 50}, Vec3{50, 52, 50}};
  const Tri3 far_b{Vec3{50.5, 50, 49}, Vec3{50.5, 50.2, 51}, Vec3{50.5, 49.8, 51}};
  ASSERT_TRUE(tri_tri_exact_intersects(far_a, far_b));
  EXPECT_FALSE(z.holds(far_a, far_b));
  // A large triangle whose crossing with the flat one runs far beyond the zone: not held, though
  // it also passes through the zone.
  const Tri3 long_one{Vec3{-20, 0.1, -1}, Vec3{20, 0.1, -1}, Vec3{0, 0.1, 1}};
  const Tri3 big_flat{Vec3{-30, -1, 0}, Vec3{30, -1, 0}, Vec3{0, 5, 0}};
  ASSERT_TRUE(tri_tri_exact_intersects(long_one, big_flat));
  EXPECT_FALSE(z.holds(long_one, big_flat));
}

TEST(ContactZone, EachPairsBoxIsGrownByItsDiagonal) {
  const ContactZone z(crossing_input());
  // The pair's box is [-1, 1] x [-1, 1] x [-1, 1], its diagonal 2 sqrt 3 = 3.46: a crossing
  // segment ending at x = 4.3 is inside, one reaching x = 4.6 is not.
  const auto crossing_to = [](double x) {
    return std::array<Tri3, 2>{Tri3{Vec3{3.9, 0, 0}, Vec3{x, 0.1, 0}, Vec3{x, -0.1, 0}},
                               Tri3{Vec3{3.8, 0, -1}, Vec3{5, 0, -1}, Vec3{4.4, 0, 1}}};
  };
  for (const auto& [x, inside] : {std::pair{4.3, true}, std::pair{4.6, false}}) {
    const auto [a, b] = crossing_to(x);
    ASSERT_TRUE(tri_tri_exact_intersects(a, b)) << x;
    EXPECT_EQ(z.holds(a, b), inside) << x;
  }
}

}  // namespace
}  // namespace interfere::qem
