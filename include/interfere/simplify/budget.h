// Triangle budgets of the parts of an assembly step (issue #6, item 5; docs/simplify.md "Budget").
//
// Given the renderer's maximum triangle count N_max, the parts j of the scene with T_j triangles of
// which F_j lie on assembly-feature faces of the current step (F_j = 0 for parts not in the step):
//   if sum_j T_j <= N_max:   N_i = T_i                       (nothing to simplify)
//   else:                    R   = N_max - sum_j F_j          (triangles left after the features)
//                            N_i = F_i + R * (T_i - F_i) / sum_j (T_j - F_j)
// rounded down, and the remaining triangles handed out by largest remainder (ties: lower index), so
// that sum_i N_i = N_max exactly. When R < 0 (the features alone exceed the renderer's budget) every
// part keeps only its feature triangles, N_i = F_i (and a warning says so).
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace interfere {

struct PartBudgetInput {
  std::size_t triangles = 0;          ///< T_i
  std::size_t feature_triangles = 0;  ///< F_i (<= T_i)
};

struct BudgetResult {
  std::vector<std::size_t> budgets;  ///< N_i, in input order
  bool features_exceed_budget = false;
};

BudgetResult triangle_budgets(const std::vector<PartBudgetInput>& parts, std::size_t renderer_max);

/// F_i: the triangles whose face id (per triangle) is one of `feature_faces`.
std::size_t count_feature_triangles(const std::vector<std::uint32_t>& face_ids,
                                    std::vector<std::uint32_t> feature_faces);

/// Budgets once some parts stopped above theirs (seams, corners, locks, the self-intersection guard):
/// a part i with fixed[i] keeps that many triangles, N_i = fixed[i]; the others share what is left,
/// N_max - sum of the fixed, by the formula above (nothing left: their feature triangles). The
/// renderer's maximum is a cap, so what one part cannot give up is taken from the others.
/// fixed.size() must equal parts.size().
BudgetResult rebalanced_budgets(const std::vector<PartBudgetInput>& parts, std::size_t renderer_max,
                                const std::vector<std::optional<std::size_t>>& fixed);

}  // namespace interfere
