// How run_assembly (assembly_run.cpp) orders the work of its frames (issue #27, the 1,024-roller
// frame rate): which rows one task solves, one after the other, so that caches serve them. The
// order changes no row: each (frame, pair) is a pure function of the poses, solved once into its own
// slot (frame * pairs + pair), so the rows are identical for any schedule and thread count.
//
//  * A scarred roller's task: every pair that names it (inner raceway, outer bore, ribs, cage webs,
//    both neighbours; a pair of two scarred rollers goes with its first roller, `a`). Its rows read
//    the roller's mesh, facet-strip tree and solid (~230 KB; 60 MB for the 256 scarred rollers of
//    the scene, more than the caches hold), which a frame-by-frame order evicts between two
//    frames: the same scarred row solved again at once costs about half of a cold one.
//  * Intact pairs: in pair order (roller by roller: a roller's pose, posed cylinder and rows together),
//    in contiguous chunks of about kChunkWeight (an estimate of their cost, so that chunks are alike
//    and balance the threads). Grouping them by kind instead (the same code and branches one after
//    the other) measured about 5 % slower over the whole frame (1,024 rollers, 1 and 2 threads).
//
// A task solves its pairs pair by pair, and each pair over every frame of a block of kFrameBlock
// frames before the next pair (run_assembly reports progress after each block).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "interfere/bearing/assembly.h"

namespace interfere::bearing::detail {

/// Frames solved by one round of tasks (run_assembly: progress after each round).
inline constexpr std::size_t kFrameBlock = 16;
/// The estimated cost of an intact chunk (assembly_schedule.cpp's kind weights, about a quarter of a
/// microsecond each).
inline constexpr std::uint32_t kChunkWeight = 64;

struct AssemblySchedule {
  std::vector<std::uint32_t> pairs;     ///< every pair index of the assembly exactly once, task by task
  std::vector<std::uint32_t> task_end;  ///< task t: pairs[t ? task_end[t - 1] : 0, task_end[t])
  std::size_t tasks() const { return task_end.size(); }
  std::size_t task_begin(std::size_t t) const { return t ? task_end[t - 1] : 0; }
};

/// The tasks of `as`'s pair list: the scarred rollers' (in part order, each's pairs in pair order),
/// then the intact pairs' chunks in pair order. A function of the pair list.
AssemblySchedule assembly_schedule(const Assembly& as);

}  // namespace interfere::bearing::detail
