// Helpers shared by the triangle-triangle tests of src/np (exact and Guigue-Devillers).
#pragma once

namespace interfere::np_detail {

/// Index of the corner alone on its side of the other triangle's plane (Guigue & Devillers 2003,
/// step 3: the triangle is permuted so that this corner comes first). h: signs (-1, 0, +1) of the
/// corners' heights, not all zero and not all of one strict sign.
inline int alone_index(const int h[3]) {
  int pos = 0, neg = 0;
  for (int i = 0; i < 3; ++i) pos += h[i] > 0, neg += h[i] < 0;
  const int want = pos == 1 ? 1 : (neg == 1 ? -1 : 0);
  for (int i = 0; i < 3; ++i)
    if (h[i] == want) return i;
  return 0;
}

}  // namespace interfere::np_detail
