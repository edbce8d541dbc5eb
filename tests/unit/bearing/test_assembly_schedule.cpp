// run_assembly's schedule (issue #27, the 1,024-roller frame rate; src/bearing/assembly_schedule.h):
// the order of the work changes no row. On scarred assemblies (cylindrical and tapered, rollers and
// raceways scarred) over more frames than one block, every row equals solve_pair on that frame's
// poses bit for bit (every field), for 1 and 2 threads; the schedule holds every pair once, a
// scarred roller's pairs in one task, each task's pairs in pair order; progress reports whole
// frames in order, the last call the frame count; the summaries equal a row-by-row recount.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <set>
#include <tbb/global_control.h>

#include "../../../src/bearing/assembly_schedule.h"
#include "unit/bearing/assembly_fixture.h"
#include "interfere/bearing/assembly.h"

namespace interfere::bearing {
namespace {

/// Both bearings, scarred rollers with the scar in range (350 degrees), scarred inner and cone
/// raceways.
Assembly scarred() {
  const std::string extra =
      R"("frames": 4, "seed": 3, "clearance": 0.05,
         "motion": {"inner_deg_per_frame": 7, "max_tilt_deg": 0.1, "load": {"direction_deg": 270, "displacement": 0.08},
                    "pocket_play": 1.3, "axial_play": 1.05},
         "scar": {"fraction": 0.4, "angle_width_deg": 350, "depth": 0.05, "seed": 5},)";
  std::string cyl = test::kCylindricalBearing, tap = test::kTaperedBearing;
  cyl.insert(cyl.rfind('}'), R"(, "scars": [{"part": "inner", "angle_center_deg": 60, "angle_width_deg": 120, "depth": 0.04, "seed": 2}])");
  tap.insert(tap.rfind('}'), R"(, "scars": [{"part": "cone", "angle_center_deg": 120, "angle_width_deg": 160, "depth": 0.03, "seed": 4}])");
  Expected<AssemblySpec> s = parse_assembly(test::assembly_json(extra, cyl + "," + tap), "t.json");
  EXPECT_TRUE(s) << s.error().message();
  Expected<Assembly> a = build_assembly(*s);
  EXPECT_TRUE(a) << a.error().message();
  return std::move(*a);
}

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }
bool same_bits(const Vec3& a, const Vec3& b) { return bits(a.x) == bits(b.x) && bits(a.y) == bits(b.y) && bits(a.z) == bits(b.z); }

/// Every field, doubles bit for bit.
bool identical(const AssemblyPairResult& a, const AssemblyPairResult& b) {
  return bits(a.distance) == bits(b.distance) && same_bits(a.point_a, b.point_a) && same_bits(a.point_b, b.point_b) &&
         a.solver == b.solver && a.path == b.path && a.scar == b.scar && a.exact == b.exact &&
         a.two_sided == b.two_sided && a.verdict == b.verdict && a.scar_part == b.scar_part;
}

TEST(BearingAssemblySchedule, HoldsEveryPairOnceScarredRollersTogether) {
  const Assembly as = scarred();
  const detail::AssemblySchedule s = detail::assembly_schedule(as);
  ASSERT_EQ(s.pairs.size(), as.pairs.size());
  ASSERT_FALSE(s.task_end.empty());
  EXPECT_EQ(s.task_end.back(), as.pairs.size());
  std::set<std::uint32_t> seen;
  std::size_t scarred_tasks = 0, scarred_rollers = 0;
  for (const AssemblyPart& p : as.parts) scarred_rollers += p.kind == PartKind::roller && p.scarred;
  const auto scarred_roller = [&](std::uint32_t i) { return as.parts[i].kind == PartKind::roller && as.parts[i].scarred; };
  for (std::size_t t = 0; t < s.tasks(); ++t) {
    ASSERT_LT(s.task_begin(t), s.task_end[t]);  // (no empty task)
    const AssemblyPair& first = as.pairs[s.pairs[s.task_begin(t)]];
    // a scarred roller's task: the pairs naming it (a pair of two scarred rollers: with its first)
    const std::uint32_t roller = scarred_roller(first.a) ? first.a : first.b;
    const bool scarred_task = scarred_roller(roller);
    scarred_tasks += scarred_task;
    for (std::size_t k = s.task_begin(t); k < s.task_end[t]; ++k) {
      EXPECT_TRUE(seen.insert(s.pairs[k]).second) << s.pairs[k];
      const AssemblyPair& p = as.pairs[s.pairs[k]];
      if (scarred_task) EXPECT_TRUE(p.a == roller || (p.b == roller && !scarred_roller(p.a))) << t << " " << k;
      else EXPECT_TRUE(!scarred_roller(p.a) && !scarred_roller(p.b)) << t << " " << k;
      if (k > s.task_begin(t)) EXPECT_LT(s.pairs[k - 1], s.pairs[k]) << t << " " << k;  // (pair order)
    }
  }
  EXPECT_EQ(seen.size(), as.pairs.size());
  EXPECT_EQ(scarred_tasks, scarred_rollers);
  EXPECT_GT(scarred_rollers, 4u);
}

TEST(BearingAssemblySchedule, RowsAreSolvePairBitForBit) {
  const Assembly as = scarred();
  const std::size_t nf = detail::kFrameBlock + 3, np = as.pairs.size();  // (two blocks, the second partial)
  const AssemblyMotion m = generate_motion(as, static_cast<int>(nf), 7);
  std::size_t scar_rows = 0, scar_b = 0;
  std::vector<AssemblyPairResult> expected;
  for (std::size_t f = 0; f < nf; ++f)
    for (std::size_t p = 0; p < np; ++p) {
      expected.push_back(solve_pair(as, as.pairs[p], m.poses[f], as.spec.clearance));
      scar_rows += expected.back().scar, scar_b += expected.back().scar_part == 2;
    }
  EXPECT_GT(scar_rows, nf * 10);  // (scarred rows of rollers and raceways)
  EXPECT_GT(scar_b, 0u);
  for (const int threads : {1, 2}) {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    const AssemblyResult r = run_assembly(as, m);
    ASSERT_EQ(r.rows.size(), nf * np);
    EXPECT_EQ(r.frames, static_cast<int>(nf));
    for (std::size_t i = 0; i < r.rows.size(); ++i) {
      ASSERT_EQ(r.rows[i].frame, static_cast<std::int32_t>(i / np)) << i;
      ASSERT_EQ(r.rows[i].pair, i % np) << i;
      ASSERT_TRUE(identical(r.rows[i].result, expected[i])) << threads << " threads, row " << i;
    }
  }
}

TEST(BearingAssemblySchedule, ProgressReportsWholeFramesInOrder) {
  const Assembly as = scarred();
  for (const std::size_t nf : {std::size_t{1}, detail::kFrameBlock, 2 * detail::kFrameBlock + 1}) {
    const AssemblyMotion m = generate_motion(as, static_cast<int>(nf), 2);
    std::mutex mutex;
    std::vector<std::size_t> done;
    const AssemblyResult r = run_assembly(as, m, [&](std::size_t d, std::size_t n) {
      EXPECT_EQ(n, nf);
      const std::lock_guard<std::mutex> lock(mutex);
      done.push_back(d);
    });
    ASSERT_FALSE(done.empty()) << nf;
    for (std::size_t k = 1; k < done.size(); ++k) EXPECT_LT(done[k - 1], done[k]) << nf;
    EXPECT_GE(done.front(), 1u);
    EXPECT_EQ(done.back(), nf);
    EXPECT_EQ(r.rows.size(), nf * as.pairs.size());
  }
  // no frames: no rows, no call
  std::size_t calls = 0;
  const AssemblyResult none = run_assembly(as, AssemblyMotion{}, [&](std::size_t, std::size_t) { ++calls; });
  EXPECT_TRUE(none.rows.empty());
  EXPECT_EQ(calls, 0u);
  EXPECT_EQ(none.frames, 0);
}

/// summarize_assembly against the rule written row by row: each frame's first smallest distance
/// (the frame's first row, then any row below the one kept), the same over all rows, the tallies;
/// ties, NaN rows (a frame opening with one, a frame of them, the very first row), 1 and 2 threads.
TEST(BearingAssemblySchedule, SummariesAreTheRowByRowRule) {
  const std::size_t np = 4;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const std::vector<std::vector<double>> cases{
      {0.5, 0.2, 0.2, 0.7, nan, 0.9, -0.1, -0.1, 0.3, nan, 0.3, 0.1, 1.0, 2.0, 3.0, 4.0},
      {nan, 1.0, 0.5, 0.5, nan, nan, nan, nan, -1.0, nan, -2.0, -2.0},
      {0.5, nan, 0.5, 0.4, nan, nan, nan, nan, 0.4, 0.4, inf, -inf, inf, inf, inf, inf},
      {inf, inf, inf, inf, 0.0, -0.0, 0.0, -0.0}};
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const std::vector<double>& d = cases[c];
    AssemblyResult out;
    for (std::size_t i = 0; i < d.size(); ++i) {
      AssemblyRow row;
      row.frame = static_cast<std::int32_t>(i / np), row.pair = static_cast<std::uint32_t>(i % np);
      row.result.distance = d[i];
      row.result.verdict = static_cast<Verdict>((i + c) % 5);
      row.result.scar = i % 3 == 0, row.result.exact = i % 4 != 1;
      out.rows.push_back(row);
    }
    const std::size_t frames = d.size() / np;
    std::vector<std::uint32_t> per_frame(frames, 0);
    std::uint32_t worst = 0;
    std::array<std::uint64_t, 5> verdicts{};
    std::uint64_t interfering = 0, scar = 0, inexact = 0;
    Verdict v = Verdict::clear;
    for (std::size_t i = 0; i < d.size(); ++i) {
      if (i % np == 0 || d[i] < d[per_frame[i / np]]) per_frame[i / np] = static_cast<std::uint32_t>(i);
      if (d[i] < d[worst]) worst = static_cast<std::uint32_t>(i);
      ++verdicts[(i + c) % 5];
      v = interfere::worst(v, static_cast<Verdict>((i + c) % 5));
      interfering += d[i] < 0, scar += i % 3 == 0, inexact += i % 4 == 1;
    }
    for (const int threads : {1, 2}) {
      tbb::global_control control(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
      summarize_assembly(out, np);
      ASSERT_EQ(out.frames, static_cast<int>(frames));
      EXPECT_EQ(out.worst_per_frame, per_frame) << c;
      EXPECT_EQ(out.worst, worst) << c;
      EXPECT_EQ(out.verdicts, verdicts) << c;
      EXPECT_EQ(out.verdict, v) << c;
      EXPECT_EQ(out.interfering_rows, interfering) << c;
      EXPECT_EQ(out.scar_rows, scar) << c;
      EXPECT_EQ(out.inexact_rows, inexact) << c;
    }
  }
  // (the cases' expected indices, by hand)
  AssemblyResult a;
  for (const double x : cases[0]) a.rows.push_back({0, 0, {.distance = x}});
  summarize_assembly(a, np);
  EXPECT_EQ(a.worst, 6u);
  EXPECT_EQ(a.worst_per_frame, (std::vector<std::uint32_t>{1, 4, 11, 12}));
  AssemblyResult b;
  for (const double x : cases[1]) b.rows.push_back({0, 0, {.distance = x}});
  summarize_assembly(b, np);
  EXPECT_EQ(b.worst, 0u);  // (nothing is below a NaN)
  EXPECT_EQ(b.worst_per_frame, (std::vector<std::uint32_t>{0, 4, 10}));
}

}  // namespace
}  // namespace interfere::bearing
