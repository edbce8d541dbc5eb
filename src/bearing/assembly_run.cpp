// Every pair of a bearing assembly at every frame (assembly.h, run_assembly). Each (frame, pair)
// is a pure function of the poses (no temporal state), solved in parallel (oneTBB) into its own
// slot: the rows, their order and every summary are identical for any thread count and schedule.
// The schedule (assembly_schedule.h; issue #27, speed): blocks of frames, and in each block tasks
// of pairs (a scarred roller's pairs together, intact pairs in pair order), each pair over the
// block's frames before the next, so that a scarred roller's trees stay in cache between its rows.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "assembly_frame.h"
#include "assembly_schedule.h"
#include "interfere/bearing/assembly.h"

namespace interfere::bearing {

// One pass, frame by frame (no division per row; the current minima kept in locals): the same
// indices as comparing each row with the row indexed so far (first minimum on ties).
void summarize_assembly(AssemblyResult& out, std::size_t np) {
  const std::size_t frames = np > 0 ? out.rows.size() / np : static_cast<std::size_t>(std::max(out.frames, 0));
  out.frames = static_cast<int>(frames);
  out.worst = 0;
  out.verdicts = {};
  out.verdict = Verdict::clear;
  out.interfering_rows = out.scar_rows = out.inexact_rows = 0;
  out.worst_per_frame.assign(frames, 0);
  if (np == 0 || out.rows.empty()) return;
  double least = out.rows[0].result.distance;
  std::uint64_t interfering = 0, scar = 0, inexact = 0;
  for (std::size_t f = 0, i = 0; f < frames; ++f) {
    std::uint32_t frame_worst = static_cast<std::uint32_t>(i);
    double frame_distance = out.rows[i].result.distance;
    for (const std::size_t end = i + np; i < end; ++i) {
      const AssemblyPairResult& r = out.rows[i].result;
      if (r.distance < frame_distance) frame_worst = static_cast<std::uint32_t>(i), frame_distance = r.distance;
      if (r.distance < least) out.worst = static_cast<std::uint32_t>(i), least = r.distance;
      ++out.verdicts[static_cast<std::size_t>(r.verdict)];
      out.verdict = interfere::worst(out.verdict, r.verdict);
      interfering += r.distance < 0;
      scar += r.scar;
      inexact += !r.exact;
    }
    out.worst_per_frame[f] = frame_worst;
  }
  out.interfering_rows = interfering, out.scar_rows = scar, out.inexact_rows = inexact;
}

namespace {

/// summarize_assembly fused into run_assembly's loop (issue #27, speed: its pass over the rows read
/// them back from memory, ~0.06 ms a frame of the 1,024-roller scene). Each task keeps, per frame of
/// the block, its least distance and the lowest row index reaching it, and its rows' counts; the
/// tasks' shares are merged frame by frame in task order. summarize_assembly takes the first row of
/// the least distance by strict comparisons in row order from the first row on: the least (distance,
/// row) pair over the rows whose distance is not NaN (a NaN never compares below), unless the first
/// row's own distance is NaN (then nothing ever compares below it: that first row). Counts are sums
/// and the verdict a maximum: any order. The same summaries for any schedule and thread count.
constexpr std::uint32_t kNoRow = std::numeric_limits<std::uint32_t>::max();
struct Least {
  double distance = 0;
  std::uint32_t row = kNoRow;  ///< kNoRow: no row (whose distance is not NaN) yet
  /// takes (d, i) when it is the lesser pair
  void take(double d, std::uint32_t i) {
    if (row == kNoRow ? !std::isnan(d) : d < distance || (d == distance && i < row)) distance = d, row = i;
  }
  void take(const Least& o) {
    if (o.row != kNoRow) take(o.distance, o.row);
  }
};
struct Counts {
  std::array<std::uint64_t, 5> verdicts{};
  Verdict verdict = Verdict::clear;
  std::uint64_t interfering = 0, scar = 0, inexact = 0;
  void add(const AssemblyPairResult& r) {
    ++verdicts[static_cast<std::size_t>(r.verdict)];
    verdict = interfere::worst(verdict, r.verdict);
    interfering += r.distance < 0;
    scar += r.scar;
    inexact += !r.exact;
  }
};

}  // namespace

AssemblyResult run_assembly(const Assembly& as, const AssemblyMotion& motion,
                            const std::function<void(std::size_t, std::size_t)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  AssemblyResult out;
  const std::size_t nf = motion.poses.size(), np = as.pairs.size();
  out.frames = static_cast<int>(nf);
  out.rows.resize(nf * np);
  const detail::AssemblySchedule s = detail::assembly_schedule(as);
  // the bearings' spheres, once per frame (assembly_frame.h; issue #27, speed: each bearing-bearing
  // row computed both of its bearings' from every part's pose), for the bearings that have such rows
  const std::size_t nb = as.spec.bearings.size();
  std::vector<std::uint32_t> outer_of(nb, 0);
  std::vector<char> has_sphere(nb, 0);
  for (const AssemblyPair& p : as.pairs)
    if (p.kind == AssemblyPairKind::bearing_bearing)
      for (const std::uint32_t q : {p.a, p.b}) outer_of[as.parts[q].bearing] = q, has_sphere[as.parts[q].bearing] = 1;
  std::vector<detail::BearingSphere> spheres(std::min(nf, detail::kFrameBlock) * nb);
  // the summaries' shares, per task (and per frame of the block)
  std::vector<Least> least(s.tasks() * detail::kFrameBlock);
  std::vector<Counts> counts(s.tasks());
  Least overall;
  out.worst_per_frame.assign(nf, 0);
  for (std::size_t f0 = 0; np > 0 && f0 < nf; f0 += detail::kFrameBlock) {
    const std::size_t f1 = std::min(nf, f0 + detail::kFrameBlock);
    for (std::size_t f = f0; f != f1; ++f)
      for (std::size_t b = 0; b < nb; ++b)
        if (has_sphere[b]) spheres[(f - f0) * nb + b] = detail::bearing_sphere(as, outer_of[b], motion.poses[f]);
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, s.tasks(), 1),
        [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t t = r.begin(); t != r.end(); ++t) {
            std::array<Least, detail::kFrameBlock> mine{};
            Counts c = counts[t];
            for (std::size_t k = s.task_begin(t); k != s.task_end[t]; ++k) {
              const std::uint32_t p = s.pairs[k];
              for (std::size_t f = f0; f != f1; ++f) {
                AssemblyRow& row = out.rows[f * np + p];
                row.frame = static_cast<std::int32_t>(f);
                row.pair = p;
                row.result = detail::solve_pair_in_frame(as, as.pairs[p], motion.poses[f], as.spec.clearance,
                                                         spheres.data() + (f - f0) * nb);
                mine[f - f0].take(row.result.distance, static_cast<std::uint32_t>(f * np + p));
                c.add(row.result);
              }
            }
            std::copy(mine.begin(), mine.end(), least.begin() + static_cast<std::ptrdiff_t>(t * detail::kFrameBlock));
            counts[t] = c;
          }
        },
        tbb::simple_partitioner());
    for (std::size_t f = f0; f != f1; ++f) {  // (the calling thread, frames and tasks in order)
      Least frame;
      for (std::size_t t = 0; t < s.tasks(); ++t) frame.take(least[t * detail::kFrameBlock + (f - f0)]);
      const std::size_t first = f * np;
      out.worst_per_frame[f] = static_cast<std::uint32_t>(
          std::isnan(out.rows[first].result.distance) || frame.row == kNoRow ? first : frame.row);
      overall.take(frame);
    }
    if (progress) progress(f1, nf);  // (the calling thread: whole frames, in order)
  }
  if (np == 0 || nf == 0) {
    summarize_assembly(out, np);
  } else {
    out.worst = std::isnan(out.rows[0].result.distance) || overall.row == kNoRow ? 0 : overall.row;
    Counts total;
    for (const Counts& c : counts) {
      for (std::size_t v = 0; v < total.verdicts.size(); ++v) total.verdicts[v] += c.verdicts[v];
      total.verdict = interfere::worst(total.verdict, c.verdict);
      total.interfering += c.interfering, total.scar += c.scar, total.inexact += c.inexact;
    }
    out.verdicts = total.verdicts;
    out.verdict = total.verdict;
    out.interfering_rows = total.interfering, out.scar_rows = total.scar, out.inexact_rows = total.inexact;
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace interfere::bearing
