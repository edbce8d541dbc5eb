// `interfere simplify`'s JSON report (docs/simplify.md "simplify report"): the result's fields and,
// for STEP input, one entry per simplified part.
#include <algorithm>

#include "interfere/simplify/hausdorff.h"
#include "simplify_cli.h"

namespace interfere::cli {

void add_result_report(nlohmann::json& report, const SimplifyResult& r, const SimplifyOptions& so,
                       const SimplifyCliOptions& o) {
  report["input_triangles"] = r.input_triangles;
  report["target_triangles"] = r.target_triangles;
  report["output_triangles"] = r.mesh.num_triangles();
  report["output_vertices"] = r.mesh.num_vertices();
  report["reached"] = r.reached;
  report["one_below"] = r.one_below;
  report["collapses"] = r.collapses;
  report["rejected"] = {{"link_condition", r.rejected_link}, {"flipped_normal", r.rejected_flip},
                        {"self_intersection", r.rejected_intersection}, {"last_face_triangle", r.rejected_face}};
  report["guard_rerun"] = r.guard_rerun;
  report["guard_reruns"] = r.guard_reruns;
  report["input_contact_pairs"] = r.input_contact_pairs;
  report["inherited_pairs"] = r.inherited_pairs;
  report["degenerate_triangles"] = r.degenerate_triangles;
  report["vertices"] = {{"welded_input", r.input_vertices_welded}, {"seam", r.seam_vertices},
                        {"corner", r.corner_vertices}, {"locked", r.locked_vertices}};
  report["feature_mode"] = feature_mode_name(so.feature_mode);
  report["seams"] = o.seams;
  report["seams_relaxed_at"] = r.seams_relaxed_at;
  report["max_error"] = so.max_error > 0 ? nlohmann::json(so.max_error) : nlohmann::json(nullptr);
  report["max_error_runs"] = r.max_error_runs;
  report["error_limited_budget"] = r.error_limited_budget;
  std::vector<std::uint32_t> ff = so.feature_faces;
  std::sort(ff.begin(), ff.end());
  ff.erase(std::unique(ff.begin(), ff.end()), ff.end());
  report["feature_faces"] = ff;
  report["sharp_angle"] = o.sharp_angle > 0 ? nlohmann::json(o.sharp_angle) : nlohmann::json(nullptr);
  {
    std::vector<std::uint32_t> ids = so.face_ids;
    std::sort(ids.begin(), ids.end());
    report["regions"] = std::unique(ids.begin(), ids.end()) - ids.begin();  // faces or regions of the input (0: none)
  }
  report["feature_triangles"] = {{"input", r.feature_triangles_in}, {"output", r.feature_triangles_out}};
  report["max_unmodified_cost"] = r.max_unmodified_cost;
  report["bbox_diagonal"] = r.bbox_diagonal;
  report["hausdorff"] = r.hausdorff;
  report["hausdorff_features"] = r.hausdorff_features < 0 ? nlohmann::json(nullptr) : nlohmann::json(r.hausdorff_features);
  report["error_bound"] = r.error_bound;
}

#ifdef INTERFERE_HAS_CAD
nlohmann::json parts_report(const cad::Prepared& prep, const cad::AssemblySimplifyResult& a, bool count_self,
                            std::size_t& self_total) {
  nlohmann::json parts = nlohmann::json::array();
  for (std::size_t i = 0; i < prep.parts.size(); ++i) {
    if (a.part_budgets[i] == 0) continue;
    const cad::PreparedPart& p = prep.parts[i];
    const SimplifyResult& d = a.parts[i];
    const auto or_null = [](double x) { return x < 0 ? nlohmann::json(nullptr) : nlohmann::json(x); };
    nlohmann::json j = {{"part", i}, {"model_part", p.model_part}, {"name", p.name}, {"instances", p.instances},
                        {"input_triangles", d.input_triangles}, {"target_triangles", a.part_budgets[i]},
                        {"output_triangles", d.mesh.num_triangles()}, {"one_below", d.one_below},
                        {"feature_triangles", {{"input", d.feature_triangles_in}, {"output", d.feature_triangles_out}}},
                        {"hausdorff", d.hausdorff}, {"error_bound", d.error_bound},
                        {"hausdorff_features", or_null(d.hausdorff_features)}, {"guard_rerun", d.guard_rerun},
                        {"guard_reruns", d.guard_reruns}, {"input_contact_pairs", d.input_contact_pairs},
                        {"inherited_pairs", d.inherited_pairs}, {"seams_relaxed_at", d.seams_relaxed_at},
                        {"max_error_runs", d.max_error_runs}, {"error_limited_budget", d.error_limited_budget},
                        {"tessellation_error", p.tessellation_error}};
    if (count_self) {
      const std::size_t x = count_self_intersections(d.mesh);
      j["self_intersections"] = x;
      self_total += x * p.instances;
    }
    parts.push_back(std::move(j));
  }
  return parts;
}
#endif

}  // namespace interfere::cli
