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

namespace {
// Splits `amount` over weights w_i (sum_w > 0) as floor(amount * w_i / sum_w), the rest by largest
// remainder (ties: lower index); adds the shares to out[i].
void share_out(std::size_t amount, const std::vector<std::size_t>& w, std::size_t sum_w, std::vector<std::size_t>& out) {
  std::vector<std::pair<std::size_t, std::size_t>> remainder;  // (remainder numerator, index)
  std::size_t given = 0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    const std::uint64_t num = static_cast<std::uint64_t>(amount) * w[i];  // < 2^64 below 4e9 triangles
    const auto share = static_cast<std::size_t>(num / sum_w);
    out[i] += share;
    given += share;
    remainder.emplace_back(static_cast<std::size_t>(num % sum_w), i);
  }
  std::stable_sort(remainder.begin(), remainder.end(),
                   [](const auto& x, const auto& y) { return x.first != y.first ? x.first > y.first : x.second < y.second; });
  for (std::size_t k = 0; given < amount && k < remainder.size(); ++k, ++given) ++out[remainder[k].second];
}
}  // namespace

std::size_t count_feature_triangles(const std::vector<std::uint32_t>& face_ids, std::vector<std::uint32_t> feature_faces,
                                    const std::vector<std::uint32_t>& feature_triangles) {
  std::sort(feature_faces.begin(), feature_faces.end());
  std::vector<std::uint8_t> mark(face_ids.size(), 0);
  for (std::size_t t = 0; t < face_ids.size(); ++t)
    mark[t] = std::binary_search(feature_faces.begin(), feature_faces.end(), face_ids[t]);
  for (std::uint32_t t : feature_triangles)
    if (t < mark.size()) mark[t] = 1;
  return static_cast<std::size_t>(std::count(mark.begin(), mark.end(), std::uint8_t{1}));
}

// He & Xu (SJTU 2023) §3.3 give a part its proportional share N = N_max * N2 / N1; the step's
// feature triangles are reserved first (issue #6), and, issue #29 item 3, every part keeps at least
// half its proportional share (the floor) and the renderer's maximum is never exceeded: features
// beyond what the floors leave are simplified too, in proportion (formula in budget.h).
BudgetResult triangle_budgets(const std::vector<PartBudgetInput>& parts, std::size_t renderer_max) {
  BudgetResult r;
  const std::size_t n = parts.size();
  std::size_t total = 0;
  for (const PartBudgetInput& p : parts) total += p.triangles;
  r.budgets.assign(n, 0);
  if (total <= renderer_max) {
    for (std::size_t i = 0; i < n; ++i) r.budgets[i] = parts[i].triangles;
    return r;
  }
  std::vector<std::size_t> floor(n), prot(n);
  std::size_t sum_floor = 0, sum_prot = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t t = parts[i].triangles;
    floor[i] = std::min<std::size_t>(t, static_cast<std::size_t>(static_cast<std::uint64_t>(renderer_max) * t / (2 * std::uint64_t{total})));
    prot[i] = std::max(floor[i], std::min(parts[i].feature_triangles, t));
    sum_floor += floor[i], sum_prot += prot[i];
  }
  if (sum_prot <= renderer_max) {
    std::vector<std::size_t> free(n);
    std::size_t sum_free = 0;
    for (std::size_t i = 0; i < n; ++i) free[i] = parts[i].triangles - prot[i], sum_free += free[i];  // > 0: total > renderer_max
    r.budgets = prot;
    share_out(renderer_max - sum_prot, free, sum_free, r.budgets);
    return r;
  }
  // The protected triangles exceed the cap: floors kept, the features above them scaled down.
  r.features_exceed_budget = true;
  std::vector<std::size_t> excess(n);
  for (std::size_t i = 0; i < n; ++i) excess[i] = prot[i] - floor[i];
  r.budgets = floor;
  share_out(renderer_max - sum_floor, excess, sum_prot - sum_floor, r.budgets);
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
