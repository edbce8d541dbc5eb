// The simplifier's scratch map from vertex numbers to values (src/simplify/vertex_map.h): against
// std::unordered_map over many generations, with growth inside a generation, clustered and strided
// vertex numbers, and lookups of absent keys.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <unordered_map>

#include "../../../src/simplify/vertex_map.h"

namespace interfere::qem {
namespace {

TEST(VertexMap, MatchesAReferenceMapAcrossGenerationsAndGrowth) {
  std::mt19937 rng(7);
  VertexMap map;
  for (int gen = 0; gen < 2000; ++gen) {
    map.clear();
    std::unordered_map<std::uint32_t, std::uint32_t> ref;
    // Mostly fans of a few vertices; now and then thousands (the table grows mid-generation).
    const int n = gen % 97 == 0 ? 5000 : int(rng() % 40);
    const std::uint32_t base = rng(), stride = gen % 3 == 0 ? 1u << (rng() % 20) : 1u + rng() % 7;
    for (int i = 0; i < n; ++i) {
      const std::uint32_t w = base + stride * (rng() % (2 * n + 1));
      const std::uint32_t v = rng();
      if (rng() % 2) {
        map.at(w) = v;
        ref[w] = v;
      } else {
        map.at(w, v) |= 1;  // inserted with v when absent
        auto [it, fresh] = ref.emplace(w, v);
        it->second |= 1;
      }
    }
    for (const auto& [w, v] : ref) {
      const std::uint32_t* got = map.find(w);
      ASSERT_NE(got, nullptr) << "generation " << gen << ": vertex " << w << " lost";
      EXPECT_EQ(*got, v);
    }
    for (int i = 0; i < 50; ++i) {  // absent keys (also those of earlier generations)
      const std::uint32_t w = rng();
      EXPECT_EQ(map.find(w) != nullptr, ref.count(w) == 1);
    }
  }
}

}  // namespace
}  // namespace interfere::qem
