// Triangle budgets of the parts of an assembly step (issue #6, item 5; docs/simplify.md "Budget").
//
// Given the renderer's maximum triangle count N_max, the parts j of the scene with T_j triangles of
// which F_j lie on assembly-feature faces of the current step (F_j = 0 for parts not in the step):
//   if sum_j T_j <= N_max:   N_i = T_i                       (nothing to simplify)
//   else:                    L_i = min(T_i, floor(N_max * T_i / (2 * sum_j T_j)))   (floor: half the
//                                  part's proportional share, He & Xu's N = N_max * N2 / N1)
//                            P_i = max(F_i, L_i)              (protected: features, at least the floor)
//     if sum_j P_j <= N_max: R   = N_max - sum_j P_j          (triangles left after them)
//                            N_i = P_i + R * (T_i - P_i) / sum_j (T_j - P_j)
//     else (the step's features exceed what the cap leaves; features_exceed_budget, a warning):
//                            S   = N_max - sum_j L_j          (>= N_max / 2)
//                            N_i = L_i + S * (P_i - L_i) / sum_j (P_j - L_j)
//                                  (the features simplified too, in proportion; no part below its floor)
// rounded down, and the remaining triangles handed out by largest remainder (ties: lower index), so
// that sum_i N_i = N_max exactly: the renderer's maximum is never exceeded by the shares, and no part
// is starved (issue #29, item 3: before, features above N_max gave N_i = F_i, above the cap, and
// parts without features 0).
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
/// F_i with feature triangles beside the faces (SimplifyOptions::feature_triangles: the clamped
/// annuli of larger faces): the triangles on `feature_faces` or listed in `feature_triangles`, each once.
std::size_t count_feature_triangles(const std::vector<std::uint32_t>& face_ids,
                                    std::vector<std::uint32_t> feature_faces,
                                    const std::vector<std::uint32_t>& feature_triangles);

/// Budgets once some parts stopped above theirs (seams, corners, locks, the self-intersection guard):
/// a part i with fixed[i] keeps that many triangles, N_i = fixed[i]; the others share what is left,
/// N_max - sum of the fixed, by the formula above (nothing left: 0 each). The
/// renderer's maximum is a cap, so what one part cannot give up is taken from the others.
/// fixed.size() must equal parts.size().
BudgetResult rebalanced_budgets(const std::vector<PartBudgetInput>& parts, std::size_t renderer_max,
                                const std::vector<std::optional<std::size_t>>& fixed);

}  // namespace interfere
