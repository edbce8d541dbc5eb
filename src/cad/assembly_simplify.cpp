// Assembly simplification part by part to one total budget (issue #6, item 5; docs/simplify.md
// "STEP input" and "Budget"): each part's N_i from the renderer's maximum, the step's total and the
// part's share (triangle_budgets), rebalanced when parts stop early.
#include "interfere/cad/assembly_simplify.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <tuple>

#include "interfere/simplify/budget.h"

namespace interfere::cad {

// STEP input: every part is simplified on its own (an assembly's touching parts are not
// self-intersections of one mesh) to its share of the total budget (triangle_budgets: instances
// counted, the step's feature triangles reserved), then the instances are placed in the world mesh.
Expected<AssemblySimplifyResult> simplify_assembly(const Prepared& prep, const SimplifyOptions& so) {
  const std::size_t n_all = prep.mesh.num_triangles();
  std::size_t total = so.target_triangles;
  if (total == 0 && so.ratio > 0) total = static_cast<std::size_t>(std::llround(so.ratio * double(n_all)));
  if (total == 0 || total > n_all)
    return Error{.reason = "triangle budget " + std::to_string(total) + " must lie in [1, " + std::to_string(n_all) + "]"};
  AssemblySimplifyResult out;
  std::vector<SimplifyResult>& done = out.parts;
  std::vector<std::size_t>& target = out.part_budgets;
  int& rounds = out.budget_rounds;
  std::vector<PartBudgetInput> in;
  for (const PreparedPart& p : prep.parts)
    in.push_back({p.instances * p.mesh.num_triangles(),
                  p.instances * count_feature_triangles(p.face_ids, p.feature_faces, p.feature_triangles)});
  // Parts that stop above their share (seams, corners, locks, the guard) keep what they reached and
  // the others share the rest (rebalanced_budgets; the renderer's maximum is a cap), re-simplified
  // from their input when their budget drops; a few rounds, each fixing at least one more part, and
  // kept only if they meet the budget.
  constexpr int kMaxRounds = 4;
  BudgetResult budgets = triangle_budgets(in, total);
  std::vector<std::optional<std::size_t>> fixed(prep.parts.size());
  target.assign(prep.parts.size(), 0);
  done.assign(prep.parts.size(), SimplifyResult{});
  rounds = 0;
  bool features_exceed = budgets.features_exceed_budget;
  std::tuple<std::vector<SimplifyResult>, std::vector<std::size_t>, bool> first;  // round 1
  // The triangles of every instance of every part, as simplified so far.
  const auto placed = [&] {
    std::size_t sum = 0;
    for (std::size_t i = 0; i < prep.parts.size(); ++i) sum += prep.parts[i].instances * done[i].mesh.num_triangles();
    return sum;
  };
  // Part i to n triangles.
  const auto run_part = [&](std::size_t i, std::size_t n) -> Expected<SimplifyResult> {
    const PreparedPart& p = prep.parts[i];
    SimplifyOptions po = so;
    po.target_triangles = n;
    po.ratio = 0;
    po.face_ids = p.face_ids;
    po.feature_faces = p.feature_faces;
    po.feature_triangles = p.feature_triangles;
    auto r = simplify(p.mesh, po);
    if (!r) {
      Error e = r.error();
      e.reason = "part '" + p.name + "': " + e.reason;
      return e;
    }
    return r;
  };
  for (;;) {
    ++rounds;
    for (std::size_t i = 0; i < prep.parts.size(); ++i) {
      const PreparedPart& p = prep.parts[i];
      if (p.instances == 0 || p.mesh.num_triangles() == 0 || fixed[i]) continue;
      const std::size_t n = std::clamp<std::size_t>(budgets.budgets[i] / p.instances, 1, p.mesh.num_triangles());
      if (target[i] == n) continue;  // same budget: same result
      auto r = run_part(i, n);
      if (!r) return r.error();
      done[i] = std::move(*r);
      target[i] = n;
    }
    bool stalled = false;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < prep.parts.size(); ++i) {
      if (target[i] > 0 && !fixed[i] && done[i].mesh.num_triangles() > target[i]) {
        fixed[i] = prep.parts[i].instances * done[i].mesh.num_triangles();
        stalled = true;
      }
      if (fixed[i]) kept += *fixed[i];
    }
    // When the stopped parts alone fill the budget it cannot be met: the others keep their share
    // instead of being cut to nothing for it.
    if (!stalled || rounds == kMaxRounds || kept >= total) break;
    if (rounds == 1) first = {done, target, budgets.features_exceed_budget};
    budgets = rebalanced_budgets(in, total, fixed);
    features_exceed = budgets.features_exceed_budget;
  }
  // Rebalanced parts are kept only if the budget is met: otherwise the formula's shares (the others
  // would lose their shape for a cap missed anyway).
  if (rounds > 1 && placed() > total) {
    std::tie(done, target, features_exceed) = std::move(first);
    rounds = 1;
  }
  // What the budget has left (odd budgets of closed parts, which lose triangles in pairs; shares
  // rounded down per instance) goes to the parts that met theirs, two triangles each (once, in part
  // order) while the total allows: the renderer's budget is met exactly more often.
  std::size_t sum = placed();
  for (std::size_t i = 0; i < prep.parts.size() && sum < total; ++i) {
    const PreparedPart& p = prep.parts[i];
    const std::size_t out = done[i].mesh.num_triangles();
    if (target[i] == 0 || fixed[i] || out > target[i] || out + 2 > p.mesh.num_triangles() ||
        sum + 2 * p.instances > total)
      continue;
    auto r = run_part(i, out + 2);
    if (!r) return r.error();
    if (r->mesh.num_triangles() != out + 2) continue;
    sum += 2 * p.instances;
    done[i] = std::move(*r);
    target[i] = out + 2;
  }
  SimplifyResult& all = out.merged;
  std::size_t parts_one_below = 0;
  for (std::size_t i = 0; i < prep.parts.size(); ++i) {
    const PreparedPart& p = prep.parts[i];
    if (target[i] == 0) continue;
    const SimplifyResult& d = done[i];
    all.collapses += d.collapses, all.rejected_link += d.rejected_link, all.rejected_flip += d.rejected_flip;
    all.rejected_intersection += d.rejected_intersection, all.rejected_face += d.rejected_face;
    all.max_error_runs += d.max_error_runs;
    all.guard_rerun = all.guard_rerun || d.guard_rerun;
    all.guard_reruns = std::max(all.guard_reruns, d.guard_reruns);
    all.input_contact_pairs += d.input_contact_pairs * p.instances, all.inherited_pairs += d.inherited_pairs * p.instances;
    all.seams_relaxed_at += d.seams_relaxed_at * p.instances;
    all.seam_vertices += d.seam_vertices, all.corner_vertices += d.corner_vertices, all.locked_vertices += d.locked_vertices;
    all.input_vertices_welded += d.input_vertices_welded, all.degenerate_triangles += d.degenerate_triangles;
    for (const auto& [name, sec] : d.phases) {  // summed over the parts
      auto it = std::find_if(all.phases.begin(), all.phases.end(), [&](const auto& x) { return x.first == name; });
      if (it == all.phases.end()) all.phases.emplace_back(name, sec);
      else it->second += sec;
    }
    all.max_unmodified_cost = std::max(all.max_unmodified_cost, d.max_unmodified_cost);
    all.hausdorff = std::max(all.hausdorff, d.hausdorff);
    all.hausdorff_features = std::max(all.hausdorff_features, d.hausdorff_features);
    all.error_bound = std::max(all.error_bound, d.error_bound);
    // A closed part with an odd budget ends one below it: counted once for all parts below.
    if (d.one_below) ++parts_one_below;
    const std::string one_below = d.one_below ? one_below_warning(d.target_triangles) : std::string();
    for (const auto& w : d.warnings)
      if (w != one_below) all.warnings.push_back("part '" + p.name + "': " + w);
  }
  for (const PreparedInstance& inst : prep.instances) {
    const SimplifyResult& d = done[inst.part];
    const auto base = static_cast<std::uint32_t>(all.mesh.positions.size());
    for (const Vec3& v : d.mesh.positions) all.mesh.positions.push_back(inst.placement.apply(v));
    for (const Tri& t : d.mesh.triangles) all.mesh.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    for (auto f : d.face_ids) all.face_ids.push_back(f + inst.face_offset);
    all.feature_triangles_in += d.feature_triangles_in, all.feature_triangles_out += d.feature_triangles_out;
    all.input_triangles += d.input_triangles;
  }
  all.target_triangles = total;
  all.reached = all.mesh.num_triangles() == total;
  if (!all.reached)
    all.warnings.push_back("total budget " + std::to_string(total) + ": " + std::to_string(all.mesh.num_triangles()) +
                           " triangles (per-part budgets are rounded down per instance, parts may stop early)");
  if (parts_one_below > 0 && !all.reached)
    all.warnings.push_back(std::to_string(parts_one_below) + (parts_one_below == 1 ? " part" : " parts") +
                           " ended one triangle below an odd budget (closed meshes lose triangles in pairs)");
  if (features_exceed) {
    // Name the parts whose feature triangles are simplified too (issue #29: the cap holds).
    std::string names;
    std::size_t f_all = 0;
    for (std::size_t i = 0; i < prep.parts.size(); ++i) {
      if (in[i].feature_triangles == 0) continue;
      f_all += in[i].feature_triangles;
      names += (names.empty() ? "'" : ", '") + prep.parts[i].name + "' (" + std::to_string(in[i].feature_triangles) + ")";
    }
    all.warnings.push_back("the step's " + std::to_string(f_all) + " feature triangles (" + names +
                           ") exceed the total budget " + std::to_string(total) +
                           " less every part's floor (half its proportional share): the cap holds, so the features "
                           "are simplified too, in proportion");
  }
  all.bbox_diagonal = norm(prep.mesh.bounds().extent());
  out.features_exceed_budget = features_exceed;
  // all.error_bound: the largest part's (rigid placements keep distances).
  return out;
}

}  // namespace interfere::cad
