// The simplifier's parallel sort utilities (src/simplify/radix_sort.h, issue #6 speed): the stable
// LSD radix sort against std::stable_sort, the merge-path parallel merge against std::merge, with
// many equal keys (stability is what makes the batched passes deterministic), for 1 and 4 threads.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "../../../src/simplify/radix_sort.h"

namespace interfere {
namespace {

using Item = std::pair<std::uint32_t, std::uint32_t>;  // (key, original position)

std::vector<Item> random_items(std::size_t n, std::uint32_t key_range, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::uint32_t> key(0, key_range - 1);
  std::vector<Item> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = {key(rng), static_cast<std::uint32_t>(i)};
  return v;
}

TEST(RadixSort, StableLikeStdStableSortForAnyThreadCount) {
  for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{1000}, std::size_t{300000}}) {
    for (const std::uint32_t range : {3u, 1u << 22}) {
      const auto input = random_items(n, range, 11);
      auto expected = input;
      std::stable_sort(expected.begin(), expected.end(), [](const Item& a, const Item& b) { return a.first < b.first; });
      for (int threads : {1, 4}) {
        auto v = input;
        std::vector<Item> tmp;
        tbb::task_arena(threads).execute([&] { radix_sort_u32<22>(v, tmp, [](const Item& x) { return x.first; }); });
        EXPECT_EQ(v, expected) << "n " << n << " range " << range << " threads " << threads;
      }
    }
  }
}

TEST(ParallelMerge, SameAsStdMergeWithTiesFromTheFirstRangeFirst) {
  const auto less = [](const Item& a, const Item& b) { return a.first < b.first; };
  for (const auto& [na, nb] : {std::pair<std::size_t, std::size_t>{0, 50000}, {70000, 0}, {200000, 3}, {90000, 120000},
                               {10, 20}}) {
    for (const std::uint32_t range : {4u, 1000000u}) {
      auto a = random_items(na, range, 3), b = random_items(nb, range, 5);
      for (auto& x : b) x.second += 1u << 30;  // tell the ranges apart
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      std::vector<Item> expected(na + nb), out(na + nb);
      std::merge(a.begin(), a.end(), b.begin(), b.end(), expected.begin(), less);
      for (int threads : {1, 4}) {
        std::fill(out.begin(), out.end(), Item{0, 0});
        tbb::task_arena(threads).execute([&] { parallel_merge(a.data(), na, b.data(), nb, out.data(), less); });
        EXPECT_EQ(out, expected) << na << " + " << nb << " range " << range << " threads " << threads;
      }
    }
  }
}

}  // namespace
}  // namespace interfere
