// A prepared STEP model simplified part by part to one total budget (issue #6, item 5: "the
// triangle budget N_i of each part from the renderer's maximum triangle count, the step's total and
// the part's share"), as `interfere simplify` does for STEP input.
#pragma once
#include <cstddef>
#include <vector>

#include "interfere/cad/pipeline.h"
#include "interfere/simplify/qem.h"

namespace interfere::cad {

struct AssemblySimplifyResult {
  /// Every instance placed in the world (Prepared::instances order), face ids offset per instance
  /// (Prepared::face_ids' numbering); counters, phases and warnings summed or collected over the
  /// parts (counts of placed triangles and contact pairs times the instances; warnings prefixed
  /// with "part '<name>': "); hausdorff, hausdorff_features and error_bound: the largest part's
  /// (rigid placements keep distances); target_triangles: the total.
  SimplifyResult merged;
  /// Per Prepared::parts: the part's own result, in part coordinates (empty for a part without
  /// instances or triangles).
  std::vector<SimplifyResult> parts;
  /// Per Prepared::parts: the budget of the run kept, per instance (0: not simplified).
  std::vector<std::size_t> part_budgets;
  /// Rounds of budgets made (1: the formula's shares; more when parts stopped above theirs and
  /// the others took up the rest).
  int budget_rounds = 0;
  bool features_exceed_budget = false;  ///< the step's feature triangles alone exceed the total
};

/// Simplifies every part of `prepared` with `options` (its face ids and feature faces are the
/// part's own; target_triangles, or ratio of the world mesh's triangles, is the total over all
/// instances). Each part gets its share by triangle_budgets (instances counted, the step's
/// feature triangles reserved). Parts that stop above their share (seams, corners, locks, the
/// self-intersection guard) keep what they reached and the others share the rest
/// (rebalanced_budgets), in up to 4 rounds kept only if they meet the total; what is left then
/// (odd budgets of closed parts, shares rounded down per instance) goes to the parts that met
/// theirs, two triangles each, while the total allows. Errors: a total outside [1, triangles], a
/// part's simplify() error (naming the part).
Expected<AssemblySimplifyResult> simplify_assembly(const Prepared& prepared, const SimplifyOptions& options);

}  // namespace interfere::cad
