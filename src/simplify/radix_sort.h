// Parallel stable LSD radix sort (issue #6 speed targets: the batched QEM passes sort millions of
// 16-byte candidate entries by a 32-bit key several times per run). Fixed blocks: per-block digit
// histograms, exclusive offsets in (digit, block) order, scatter in parallel; the result is the
// stable order, identical for any thread count. Digits whose histogram has a single bucket are
// skipped. Not installed.
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace interfere {

/// Block length for splitting a list of n entries over threads: 2^16, smaller for short lists so
/// both threads of a small machine take part (at most 16 blocks then; at least 2^12 entries each).
inline std::size_t parallel_block_length(std::size_t n) {
  return std::max<std::size_t>(std::size_t{1} << 12, std::min<std::size_t>(std::size_t{1} << 16, (n + 15) / 16));
}

/// Sorts `v` (a std::vector of any allocator) stably by key(x) (uint32 below 2^KeyBits) ascending;
/// `tmp` is scratch (resized).
template <int KeyBits = 32, class Vector, class Key>
void radix_sort_u32(Vector& v, Vector& tmp, Key key) {
  using T = typename Vector::value_type;
  constexpr int kBits = 11;
  constexpr std::size_t kBuckets = std::size_t{1} << kBits;
  const std::size_t n = v.size();
  if (n < 2) return;
  // Few blocks: the offset sweep stays cheap. Below 2^16 entries one block (serial): splitting
  // made the sort slower there on 2 cores (45,000 entries: 0.32 ms in 11 blocks, 0.23 ms in one).
  const std::size_t kBlock = n < (std::size_t{1} << 16) ? n : parallel_block_length(n);
  tmp.resize(n);
  const std::size_t nb = (n + kBlock - 1) / kBlock;
  std::vector<std::array<std::uint32_t, kBuckets>> hist(nb);
  for (int shift = 0; shift < KeyBits; shift += kBits) {
    auto digit = [&](const T& x) { return (key(x) >> shift) & (kBuckets - 1); };
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nb, 1), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t b = r.begin(); b < r.end(); ++b) {
        auto& h = hist[b];
        h.fill(0);
        const std::size_t e = std::min(n, (b + 1) * kBlock);
        for (std::size_t i = b * kBlock; i < e; ++i) ++h[digit(v[i])];
      }
    });
    // Exclusive offsets, digit-major then block: stable. A digit shared by all keys is skipped.
    std::size_t sum = 0, used = 0;
    for (std::size_t d = 0; d < kBuckets; ++d) {
      std::size_t total = 0;
      for (std::size_t b = 0; b < nb; ++b) {
        const std::uint32_t c = hist[b][d];
        hist[b][d] = static_cast<std::uint32_t>(sum);
        sum += c, total += c;
      }
      used += total > 0;
    }
    if (used == 1) continue;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nb, 1), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t b = r.begin(); b < r.end(); ++b) {
        auto& h = hist[b];
        const std::size_t e = std::min(n, (b + 1) * kBlock);
        for (std::size_t i = b * kBlock; i < e; ++i) tmp[h[digit(v[i])]++] = v[i];
      }
    });
    v.swap(tmp);
  }
}

/// Stable merge of the sorted ranges [a, a + na) and [b, b + nb) into out (entries of a first among
/// equivalent ones): the result of std::merge, computed in parallel over fixed output chunks whose
/// boundaries are found by the merge-path binary search (Odeh, Green, Mwassi, Shmueli & Birk 2012).
template <class T, class Less>
void parallel_merge(const T* a, std::size_t na, const T* b, std::size_t nb, T* out, Less less) {
  const std::size_t n = na + nb;
  constexpr std::size_t kChunks = 16;
  if (n < (std::size_t{1} << 15)) {
    std::merge(a, a + na, b, b + nb, out, less);
    return;
  }
  // Entries of a among the first k of the output: the smallest i with b[k - i - 1] < a[i].
  const auto split = [&](std::size_t k) {
    std::size_t lo = k > nb ? k - nb : 0, hi = std::min(k, na);
    while (lo < hi) {
      const std::size_t i = lo + (hi - lo) / 2;
      if (!less(b[k - i - 1], a[i])) lo = i + 1;
      else hi = i;
    }
    return lo;
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kChunks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t c = r.begin(); c < r.end(); ++c) {
      const std::size_t k0 = n * c / kChunks, k1 = n * (c + 1) / kChunks;
      const std::size_t i0 = split(k0), i1 = split(k1);
      std::merge(a + i0, a + i1, b + (k0 - i0), b + (k1 - i1), out + k0, less);
    }
  });
}

}  // namespace interfere
