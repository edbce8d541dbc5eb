// Every pair of a bearing assembly at every frame (assembly.h, run_assembly). Each (frame, pair)
// is a pure function of the poses (no temporal state), solved in parallel (oneTBB) into its own
// slot: the rows, their order and every summary are identical for any thread count.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "interfere/bearing/assembly.h"

namespace interfere::bearing {

void summarize_assembly(AssemblyResult& out, std::size_t np) {
  const std::size_t frames = np > 0 ? out.rows.size() / np : static_cast<std::size_t>(std::max(out.frames, 0));
  out.frames = static_cast<int>(frames);
  out.worst = 0;
  out.verdicts = {};
  out.verdict = Verdict::clear;
  out.interfering_rows = out.scar_rows = out.inexact_rows = 0;
  out.worst_per_frame.assign(frames, 0);
  for (std::size_t i = 0; i < out.rows.size(); ++i) {
    const AssemblyPairResult& r = out.rows[i].result;
    const std::size_t f = i / np;
    if (i % np == 0 || r.distance < out.rows[out.worst_per_frame[f]].result.distance)
      out.worst_per_frame[f] = static_cast<std::uint32_t>(i);
    if (i == 0 || r.distance < out.rows[out.worst].result.distance) out.worst = static_cast<std::uint32_t>(i);
    ++out.verdicts[static_cast<std::size_t>(r.verdict)];
    out.verdict = worst(out.verdict, r.verdict);
    if (r.distance < 0) ++out.interfering_rows;
    if (r.scar) ++out.scar_rows;
    if (!r.exact) ++out.inexact_rows;
  }
}

AssemblyResult run_assembly(const Assembly& as, const AssemblyMotion& motion,
                            const std::function<void(std::size_t, std::size_t)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  AssemblyResult out;
  out.frames = static_cast<int>(motion.poses.size());
  const std::size_t np = as.pairs.size();
  out.rows.resize(motion.poses.size() * np);
  std::atomic<std::size_t> rows_done{0};  // (progress: whole frames done)
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, out.rows.size(), 4), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      AssemblyRow& row = out.rows[i];
      row.frame = static_cast<std::int32_t>(i / np);
      row.pair = static_cast<std::uint32_t>(i % np);
      row.result = solve_pair(as, as.pairs[row.pair], motion.poses[i / np], as.spec.clearance);
    }
    if (progress && np > 0) {
      const std::size_t after = rows_done.fetch_add(r.size()) + r.size();
      if (after / np != (after - r.size()) / np) progress(after / np, motion.poses.size());
    }
  });
  summarize_assembly(out, np);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace interfere::bearing
