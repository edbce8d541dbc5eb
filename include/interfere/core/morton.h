// 30-bit Morton codes (Morton 1966; as in Karras 2012 for LBVH construction): 10 bits per axis
// interleaved, x in the highest position. Used by the LBVH builder (bvh/build_lbvh.cpp).
#pragma once
#include <cstdint>

namespace interfere {

/// Bits ...ba of the low 10 bits of v spread to ..b00a.
inline std::uint32_t morton_spread10(std::uint32_t v) {
  v &= 0x3ffu;
  v = (v | (v << 16)) & 0x030000FFu;
  v = (v | (v << 8)) & 0x0300F00Fu;
  v = (v | (v << 4)) & 0x030C30C3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}

/// Code of grid cell (x, y, z), each in [0, 1024).
inline std::uint32_t morton30(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  return (morton_spread10(x) << 2) | (morton_spread10(y) << 1) | morton_spread10(z);
}

}  // namespace interfere
