// run_assembly's tasks (assembly_schedule.h; issue #27, the 1,024-roller frame rate).
#include "assembly_schedule.h"

#include <vector>

namespace interfere::bearing::detail {
namespace {

/// An intact row's cost in quarters of a microsecond, roughly (BM_Assembly1024ByKind's thread CPU
/// time per pair, 2026-11-30). Only the chunks' sizes depend on it, never a row.
std::uint32_t weight(AssemblyPairKind k) {
  switch (k) {
    case AssemblyPairKind::roller_inner:
    case AssemblyPairKind::roller_cone: return 6;
    case AssemblyPairKind::roller_cup: return 4;
    case AssemblyPairKind::cage_inner:
    case AssemblyPairKind::cage_outer: return 32;
    case AssemblyPairKind::roller_roller:
    case AssemblyPairKind::roller_cage:
    case AssemblyPairKind::bearing_bearing: return 3;
    default: return 2;  // roller_outer, roller_rib
  }
}

bool scarred_roller(const AssemblyPart& p) { return p.kind == PartKind::roller && p.scarred; }

}  // namespace

AssemblySchedule assembly_schedule(const Assembly& as) {
  constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  const std::size_t np = as.pairs.size();
  // the scarred roller whose task a pair joins (its first scarred roller), else kNone
  std::vector<std::size_t> owner(np, kNone);
  std::vector<std::uint32_t> owned(as.parts.size(), 0);  // pairs per scarred roller
  for (std::size_t i = 0; i < np; ++i) {
    const AssemblyPair& p = as.pairs[i];
    if (scarred_roller(as.parts[p.a])) owner[i] = p.a;
    else if (scarred_roller(as.parts[p.b])) owner[i] = p.b;
    if (owner[i] != kNone) ++owned[owner[i]];
  }
  AssemblySchedule s;
  s.pairs.reserve(np);
  // scarred rollers, in part order: each's pairs in pair order (a counting sort by owner)
  std::vector<std::uint32_t> start(as.parts.size() + 1, 0);
  for (std::size_t r = 0; r < as.parts.size(); ++r) start[r + 1] = start[r] + owned[r];
  s.pairs.resize(start.back());
  std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < np; ++i)
    if (owner[i] != kNone) s.pairs[next[owner[i]]++] = static_cast<std::uint32_t>(i);
  for (std::size_t r = 0; r < as.parts.size(); ++r)
    if (owned[r] > 0) s.task_end.push_back(start[r + 1]);
  // intact pairs in pair order, in chunks of about kChunkWeight
  std::uint32_t load = 0;
  for (std::size_t i = 0; i < np; ++i) {
    if (owner[i] != kNone) continue;
    s.pairs.push_back(static_cast<std::uint32_t>(i));
    load += weight(as.pairs[i].kind);
    if (load >= kChunkWeight) s.task_end.push_back(static_cast<std::uint32_t>(s.pairs.size())), load = 0;
  }
  if (load > 0) s.task_end.push_back(static_cast<std::uint32_t>(s.pairs.size()));
  return s;
}

}  // namespace interfere::bearing::detail
