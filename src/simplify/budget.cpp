// Triangle budgets per part for an assembly step (issue #6, item 5): the renderer's maximum split
// over the parts by their share of the non-feature triangles after the step's assembly-feature
// triangles are reserved (formula in include/interfere/simplify/budget.h and docs/simplify.md).
#include "interfere/simplify/budget.h"

#include <algorithm>
#include <cstdint>
#include <numeric>

namespace interfere {

std::size_t count_feature_triangles(const std::vector<std::uint32_t>& face_ids,
                                    std::vector<std::uint32_t> feature_faces) {
  std::sort(feature_faces.begin(), feature_faces.end());
  std::size_t n = 0;
  for (std::uint32_t f : face_ids) n += std::binary_search(feature_faces.begin(), feature_faces.end(), f);
  return n;
}

BudgetResult triangle_budgets(const std::vector<PartBudgetInput>& parts, std::size_t renderer_max) {
  BudgetResult r;
  std::size_t total = 0, features = 0;
  for (const PartBudgetInput& p : parts) total += p.triangles, features += std::min(p.feature_triangles, p.triangles);
  r.budgets.resize(parts.size());
  if (total <= renderer_max) {
    for (std::size_t i = 0; i < parts.size(); ++i) r.budgets[i] = parts[i].triangles;
    return r;
  }
  if (features >= renderer_max) {
    r.features_exceed_budget = features > renderer_max;
    for (std::size_t i = 0; i < parts.size(); ++i) r.budgets[i] = std::min(parts[i].feature_triangles, parts[i].triangles);
    return r;
  }
  const std::size_t rest = renderer_max - features;
  const std::size_t free_total = total - features;  // > rest since total > renderer_max
  std::vector<std::pair<std::size_t, std::size_t>> remainder;  // (remainder numerator, index)
  std::size_t given = 0;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::size_t f = std::min(parts[i].feature_triangles, parts[i].triangles);
    const std::size_t free_i = parts[i].triangles - f;
    const std::uint64_t num = static_cast<std::uint64_t>(rest) * free_i;  // < 2^64 below 4e9 triangles
    const auto share = static_cast<std::size_t>(num / free_total);
    r.budgets[i] = f + share;
    given += share;
    remainder.emplace_back(static_cast<std::size_t>(num % free_total), i);
  }
  std::stable_sort(remainder.begin(), remainder.end(),
                   [](const auto& x, const auto& y) { return x.first != y.first ? x.first > y.first : x.second < y.second; });
  for (std::size_t k = 0; given < rest && k < remainder.size(); ++k, ++given) ++r.budgets[remainder[k].second];
  return r;
}

BudgetResult rebalanced_budgets(const std::vector<PartBudgetInput>& parts, std::size_t renderer_max,
                                const std::vector<std::optional<std::size_t>>& fixed) {
  std::size_t kept = 0;
  std::vector<PartBudgetInput> free_parts;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (i < fixed.size() && fixed[i]) kept += *fixed[i];
    else free_parts.push_back(parts[i]);
  }
  const BudgetResult shared = triangle_budgets(free_parts, renderer_max > kept ? renderer_max - kept : 0);
  BudgetResult r;
  r.features_exceed_budget = shared.features_exceed_budget;
  r.budgets.resize(parts.size());
  for (std::size_t i = 0, k = 0; i < parts.size(); ++i)
    r.budgets[i] = i < fixed.size() && fixed[i] ? *fixed[i] : shared.budgets[k++];
  return r;
}

}  // namespace interfere
