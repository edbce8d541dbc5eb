// Deterministic uniform numbers for the bearing tests' random poses (splitmix64, Steele, Lea &
// Flood 2014): the same sequence on every platform and standard library, unlike std::uniform_*.
#pragma once
#include <cstdint>

namespace interfere::bearing::test {

struct SplitMix {
  std::uint64_t s;
  double uniform() {  ///< in [0, 1)
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1p-53;
  }
  double in(double a, double b) { return a + (b - a) * uniform(); }
};

}  // namespace interfere::bearing::test
