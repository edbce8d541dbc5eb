// Bearing assembly frames in blocks (issue #31, item 3: interfere-mpi bearing): run_assembly on
// blocks of a motion's frames, the rows renumbered and concatenated, then summarize_assembly, give
// bitwise the rows of one run over all frames, and summaries equal to a recount done here from the
// rows (first minimum by index, verdict tallies), for blocks of 1, 2, 3 and 5 frames of 5.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "unit/bearing/assembly_fixture.h"
#include "interfere/bearing/assembly.h"

namespace interfere::bearing {
namespace {

TEST(BearingAssemblyFrameBlocks, BlocksMergedEqualOneRun) {
  Expected<AssemblySpec> s = parse_assembly(test::assembly_json(test::kLively, test::both_bearings()), "t.json");
  ASSERT_TRUE(s) << s.error().message();
  Expected<Assembly> built = build_assembly(*s);
  ASSERT_TRUE(built) << built.error().message();
  const Assembly& as = *built;
  const std::size_t nf = 5, np = as.pairs.size();
  const AssemblyMotion m = generate_motion(as, static_cast<int>(nf), 11);
  const AssemblyResult whole = run_assembly(as, m);
  ASSERT_EQ(whole.rows.size(), nf * np);
  for (const std::size_t k : {1u, 2u, 3u, 5u, 7u}) {  // (k ranks: frames [r nf / k, (r + 1) nf / k))
    AssemblyResult merged;
    for (std::size_t r = 0; r < k; ++r) {
      AssemblyMotion block;
      block.poses.assign(m.poses.begin() + static_cast<std::ptrdiff_t>(r * nf / k),
                         m.poses.begin() + static_cast<std::ptrdiff_t>((r + 1) * nf / k));
      if (block.poses.empty()) continue;  // (an idle rank)
      AssemblyResult part = run_assembly(as, block);
      for (AssemblyRow& row : part.rows) row.frame += static_cast<std::int32_t>(r * nf / k);
      merged.rows.insert(merged.rows.end(), part.rows.begin(), part.rows.end());
    }
    summarize_assembly(merged, np);
    ASSERT_EQ(merged.rows.size(), whole.rows.size()) << k;
    for (std::size_t i = 0; i < whole.rows.size(); ++i) {
      ASSERT_EQ(merged.rows[i].frame, whole.rows[i].frame);
      ASSERT_EQ(merged.rows[i].pair, whole.rows[i].pair);
      ASSERT_EQ(std::memcmp(&merged.rows[i].result.distance, &whole.rows[i].result.distance, sizeof(double)), 0);
      ASSERT_EQ(merged.rows[i].result.verdict, whole.rows[i].result.verdict);
    }
    // The summaries, recounted from the rows.
    EXPECT_EQ(merged.frames, static_cast<int>(nf));
    std::array<std::uint64_t, 5> verdicts{};
    std::uint64_t interfering = 0, scar = 0, inexact = 0;
    Verdict v = Verdict::clear;
    for (const AssemblyRow& row : whole.rows) {
      ++verdicts[static_cast<std::size_t>(row.result.verdict)];
      interfering += row.result.distance < 0, scar += row.result.scar, inexact += !row.result.exact;
      v = worst(v, row.result.verdict);
    }
    const auto less = [](const AssemblyRow& a, const AssemblyRow& b) { return a.result.distance < b.result.distance; };
    EXPECT_EQ(merged.worst, std::min_element(whole.rows.begin(), whole.rows.end(), less) - whole.rows.begin());
    ASSERT_EQ(merged.worst_per_frame.size(), nf);
    for (std::size_t f = 0; f < nf; ++f) {
      const auto first = whole.rows.begin() + static_cast<std::ptrdiff_t>(f * np);
      EXPECT_EQ(merged.worst_per_frame[f], std::min_element(first, first + static_cast<std::ptrdiff_t>(np), less) - whole.rows.begin());
    }
    EXPECT_EQ(merged.verdicts, verdicts);
    EXPECT_EQ(merged.verdict, v);
    EXPECT_EQ(merged.interfering_rows, interfering);
    EXPECT_EQ(merged.scar_rows, scar);
    EXPECT_EQ(merged.inexact_rows, inexact);
  }
}

}  // namespace
}  // namespace interfere::bearing
