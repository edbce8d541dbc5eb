// run_assembly computes its summaries in its loop (issue #27, speed; assembly_run.cpp): they must be
// summarize_assembly's on the same rows (the row-by-row rule, test_assembly_schedule.cpp), on 1 and
// 2 threads, for scenes with scarred rollers, several frame blocks, and a frame count that leaves a
// partial block.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include "unit/bearing/assembly_fixture.h"
#include "interfere/bearing/assembly.h"

namespace interfere::bearing {
namespace {

void expect_same_summaries(const Assembly& as, int frames, std::uint64_t seed) {
  const AssemblyMotion m = generate_motion(as, frames, seed);
  for (const int threads : {1, 2}) {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    const AssemblyResult run = run_assembly(as, m);
    AssemblyResult again = run;
    summarize_assembly(again, as.pairs.size());
    EXPECT_EQ(run.frames, again.frames) << threads;
    EXPECT_EQ(run.worst_per_frame, again.worst_per_frame) << threads;
    EXPECT_EQ(run.worst, again.worst) << threads;
    EXPECT_EQ(run.verdicts, again.verdicts) << threads;
    EXPECT_EQ(run.verdict, again.verdict) << threads;
    EXPECT_EQ(run.interfering_rows, again.interfering_rows) << threads;
    EXPECT_EQ(run.scar_rows, again.scar_rows) << threads;
    EXPECT_EQ(run.inexact_rows, again.inexact_rows) << threads;
  }
}

TEST(BearingAssemblyRunSummaries, AreSummarizeAssemblysOnTheRows) {
  Expected<AssemblySpec> s = parse_assembly(test::assembly_json(test::kLively, test::both_bearings()), "t.json");
  ASSERT_TRUE(s) << s.error().message();
  Expected<Assembly> as = build_assembly(*s);
  ASSERT_TRUE(as) << as.error().message();
  expect_same_summaries(*as, 1, 3);
  expect_same_summaries(*as, 37, 7);  // (blocks of 16: 16, 16, 5)
  Expected<AssemblySpec> example = read_assembly_file(std::string(INTERFERE_SOURCE_DIR) + "/data/examples/bearing_axle.json");
  ASSERT_TRUE(example) << example.error().message();
  Expected<Assembly> ex = build_assembly(*example);
  ASSERT_TRUE(ex) << ex.error().message();
  expect_same_summaries(*ex, 18, example->seed);
}

}  // namespace
}  // namespace interfere::bearing
