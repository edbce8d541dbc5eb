// Python bindings of the simplification module (issue #6) and, when built with OpenCASCADE, of the
// CAD pipeline (STEP import, AAG, features, assembly semantics). Only argument parsing, requests
// and result conversion here; the GIL is released around the simplification.
#include <tuple>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <stdexcept>

#include "bindings.h"
#include "interfere/simplify/budget.h"
#include "interfere/simplify/hausdorff.h"
#include "interfere/simplify/gltf_io.h"
#include "interfere/simplify/tagged_io.h"
#include "interfere/simplify/qem.h"
#ifdef INTERFERE_HAS_CAD
#include "interfere/cad/aag_dot.h"
#include "interfere/cad/assembly_clash.h"
#include "interfere/cad/assembly_simplify.h"
#include "interfere/cad/features.h"
#include "interfere/cad/model.h"
#include "interfere/cad/pipeline.h"
#include "interfere/cad/semantics.h"
#endif

namespace py = pybind11;

namespace interfere::python {
namespace {

// The modes of simplify() and simplify_step() by name (as the CLI's --feature-mode, --lock, --seams).
FeatureMode feature_mode_of(const std::string& name, bool lock) {
  if (lock) return FeatureMode::lock;
  if (const auto mode = feature_mode_from_name(name)) return *mode;
  throw py::value_error("feature_mode must be weight, last or lock, not '" + name + "'");
}
#ifdef INTERFERE_HAS_CAD
// A prepared model's instances as dicts (name, part, placement, face_offset).
py::list instance_list(const cad::Prepared& prep) {
  py::list out;
  for (const cad::PreparedInstance& i : prep.instances)
    out.append(py::dict(py::arg("name") = i.name, py::arg("part") = i.part, py::arg("placement") = i.placement,
                        py::arg("face_offset") = i.face_offset));
  return out;
}
#endif

SeamMode seam_mode_of(const std::string& name) {
  if (const auto seams = seam_mode_from_name(name)) return *seams;
  throw py::value_error("seams must be all, auto, features or none, not '" + name + "'");
}

// [(T_i, F_i)] from Python, checked (F_i <= T_i).
std::vector<PartBudgetInput> budget_inputs(const std::vector<std::pair<std::size_t, std::size_t>>& parts) {
  std::vector<PartBudgetInput> in;
  for (const auto& [t, f] : parts) {
    if (f > t) throw py::value_error("feature triangles exceed the part's triangles");
    in.push_back({t, f});
  }
  return in;
}

}  // namespace

void bind_simplify(py::module_& m) {
  py::class_<SimplifyResult>(m, "SimplifyResult", "Result of interfere.simplify (see docs/simplify.md).")
      .def_readonly("mesh", &SimplifyResult::mesh)
      .def_readonly("face_ids", &SimplifyResult::face_ids)
      .def_readonly("input_triangles", &SimplifyResult::input_triangles)
      .def_readonly("target_triangles", &SimplifyResult::target_triangles)
      .def_readonly("reached", &SimplifyResult::reached)
      .def_readonly("one_below", &SimplifyResult::one_below)
      .def_readonly("collapses", &SimplifyResult::collapses)
      .def_readonly("rejected_link", &SimplifyResult::rejected_link)
      .def_readonly("rejected_flip", &SimplifyResult::rejected_flip)
      .def_readonly("rejected_intersection", &SimplifyResult::rejected_intersection)
      .def_readonly("rejected_face", &SimplifyResult::rejected_face)
      .def_readonly("guard_rerun", &SimplifyResult::guard_rerun)
      .def_readonly("guard_reruns", &SimplifyResult::guard_reruns)
      .def_readonly("input_contact_pairs", &SimplifyResult::input_contact_pairs)
      .def_readonly("inherited_pairs", &SimplifyResult::inherited_pairs)
      .def_readonly("seams_relaxed_at", &SimplifyResult::seams_relaxed_at)
      .def_readonly("max_error_runs", &SimplifyResult::max_error_runs)
      .def_readonly("error_limited_budget", &SimplifyResult::error_limited_budget)
      .def_readonly("degenerate_triangles", &SimplifyResult::degenerate_triangles)
      .def_readonly("seam_vertices", &SimplifyResult::seam_vertices)
      .def_readonly("corner_vertices", &SimplifyResult::corner_vertices)
      .def_readonly("locked_vertices", &SimplifyResult::locked_vertices)
      .def_readonly("feature_triangles_in", &SimplifyResult::feature_triangles_in)
      .def_readonly("feature_triangles_out", &SimplifyResult::feature_triangles_out)
      .def_readonly("max_unmodified_cost", &SimplifyResult::max_unmodified_cost)
      .def_readonly("bbox_diagonal", &SimplifyResult::bbox_diagonal)
      .def_readonly("hausdorff", &SimplifyResult::hausdorff)
      .def_readonly("hausdorff_features", &SimplifyResult::hausdorff_features)
      .def_readonly("error_bound", &SimplifyResult::error_bound)
      .def_readonly("phases", &SimplifyResult::phases, "[(phase, seconds)] wall time of simplify()'s phases, in order")
      .def_readonly("warnings", &SimplifyResult::warnings);

  m.def(
      "simplify",
      [](const TriMesh& mesh, std::size_t target, double ratio, std::vector<std::uint32_t> face_ids,
         std::vector<std::uint32_t> feature_faces, bool lock, double sharp_angle, bool prevent_self_intersections,
         bool measure_error, const std::string& feature_mode, bool inherit_input_contacts, const std::string& seams,
         double max_error) {
        SimplifyOptions o;
        o.target_triangles = target;
        o.ratio = ratio;
        o.face_ids = std::move(face_ids);
        o.feature_faces = std::move(feature_faces);
        o.feature_mode = feature_mode_of(feature_mode, lock);
        o.seams = seam_mode_of(seams);
        o.sharp_angle_deg = sharp_angle;
        o.prevent_self_intersections = prevent_self_intersections;
        o.inherit_input_contacts = inherit_input_contacts;
        o.measure_error = measure_error;
        o.max_error = max_error;
        Expected<SimplifyResult> r = Error{};
        {
          py::gil_scoped_release release;
          r = simplify(mesh, o);
        }
        if (!r) throw py::value_error(r.error().message());
        return std::move(*r);
      },
      py::arg("mesh"), py::arg("target") = 0, py::arg("ratio") = 0.0, py::arg("face_ids") = std::vector<std::uint32_t>{},
      py::arg("feature_faces") = std::vector<std::uint32_t>{}, py::arg("lock") = false, py::arg("sharp_angle") = 0.0,
      py::arg("prevent_self_intersections") = true, py::arg("measure_error") = true,
      py::arg("feature_mode") = std::string("weight"), py::arg("inherit_input_contacts") = true,
      py::arg("seams") = std::string("auto"), py::arg("max_error") = 0.0,
      "Feature-preserving QEM simplification to `target` triangles (or `ratio` of them). face_ids: per-triangle "
      "face/region ids; feature_faces: ids kept (cost-weighted, or hard-locked with lock=True). "
      "prevent_self_intersections: no intersecting pair the input did not have; inherit_input_contacts=False makes "
      "that strict where the input has contacts of its own (see docs/simplify.md). max_error > 0: where the budget's "
      "error bound would exceed it, the fewest triangles within it (error_limited_budget, max_error_runs). "
      "ValueError on bad input (budget "
      "<= 0 or larger than the mesh, ...).");
  m.def(
      "hausdorff",
      [](const TriMesh& a, const TriMesh& b) {
        py::gil_scoped_release release;
        const HausdorffResult h = hausdorff(a, b, false);
        return std::make_pair(h.a_to_b, h.b_to_a);
      },
      py::arg("a"), py::arg("b"), "Sampled one-sided distances (a->b, b->a); the symmetric Hausdorff is their max.");
  m.def(
      "distance_bound",
      [](const TriMesh& a, const TriMesh& b) {
        py::gil_scoped_release release;
        return one_sided(a, b).bound;
      },
      py::arg("a"), py::arg("b"),
      "Upper bound of the distance from every point of a's surface to b (SimplifyResult.error_bound for a = input, "
      "b = result).");
  m.def(
      "write_tagged_mesh",
      [](const std::filesystem::path& path, const TriMesh& mesh, const std::vector<std::uint32_t>& face_ids,
         const std::vector<std::uint32_t>& feature_faces, double error_bound) {
        if (!face_ids.empty() && face_ids.size() != mesh.num_triangles())
          throw py::value_error("face_ids must have one id per triangle");
        const Status s = write_tagged_mesh(path, mesh, face_ids, feature_faces, MeshFormat::automatic, error_bound);
        if (!s) throw py::value_error(s.error().message());
      },
      py::arg("path"), py::arg("mesh"), py::arg("face_ids") = std::vector<std::uint32_t>{},
      py::arg("feature_faces") = std::vector<std::uint32_t>{}, py::arg("error_bound") = -1.0,
      "Writes a simplified mesh as `interfere simplify` does: PLY/OBJ/STL with per-triangle face ids and feature "
      "tags where the format allows, and the error bound (>= 0) in PLY/OBJ (read by clash --conservative).");
  m.def(
      "write_glb",
      [](const std::filesystem::path& path,
         const std::vector<std::tuple<std::string, TriMesh, std::vector<std::uint32_t>, std::vector<std::uint32_t>, double>>& parts,
         const std::vector<std::tuple<std::string, std::uint32_t, Transform>>& instances, const std::string& units) {
        std::vector<GltfPart> gp;
        for (const auto& [name, mesh, ids, feats, bound] : parts) gp.push_back({name, mesh, ids, feats, bound});
        std::vector<GltfInstance> gi;
        for (const auto& [name, part, placement] : instances) gi.push_back({name, part, placement});
        if (gi.empty())
          for (std::uint32_t i = 0; i < gp.size(); ++i) gi.push_back({gp[i].name, i, Transform{}});
        const Status s = write_glb(path, gp, gi, units);
        if (!s) throw py::value_error(s.error().message());
      },
      py::arg("path"), py::arg("parts"), py::arg("instances") = std::vector<std::tuple<std::string, std::uint32_t, Transform>>{},
      py::arg("units") = std::string("mm"),
      "Binary glTF 2.0: parts [(name, mesh, face_ids, feature_faces, error_bound)], instances [(name, part index, "
      "Transform)] (default: each part once, unplaced); units (mm, cm, m, um, in, ft) scale the scene to metres.");
  m.def(
      "read_error_bound",
      [](const std::filesystem::path& path) {
        const Expected<double> e = read_error_bound(path);
        if (!e) throw py::value_error(e.error().message());
        return *e;
      },
      py::arg("path"), "The error bound a simplified PLY/OBJ file stores, -1 when it has none.");
  m.def(
      "count_self_intersections",
      [](const TriMesh& mesh) {
        py::gil_scoped_release release;
        return count_self_intersections(mesh);
      },
      py::arg("mesh"), "Pairs of non-adjacent intersecting triangles (the engine's exact clash of the mesh with itself).");
  m.def(
      "triangle_budgets",
      [](const std::vector<std::pair<std::size_t, std::size_t>>& parts, std::size_t renderer_max) {
        return triangle_budgets(budget_inputs(parts), renderer_max).budgets;
      },
      py::arg("parts"), py::arg("renderer_max"),
      "Per-part triangle budgets N_i from [(T_i, F_i)] and the renderer's maximum (docs/simplify.md).");
  m.def(
      "rebalanced_budgets",
      [](const std::vector<std::pair<std::size_t, std::size_t>>& parts, std::size_t renderer_max,
         const std::vector<std::optional<std::size_t>>& fixed) {
        if (fixed.size() != parts.size()) throw py::value_error("fixed must have one entry (None or a count) per part");
        return rebalanced_budgets(budget_inputs(parts), renderer_max, fixed).budgets;
      },
      py::arg("parts"), py::arg("renderer_max"), py::arg("fixed"),
      "Budgets once some parts stopped above theirs: fixed[i] (a count, or None) is kept, the others share the "
      "rest of renderer_max by the same formula (docs/simplify.md).");

#ifdef INTERFERE_HAS_CAD
  m.attr("HAVE_CAD") = true;
  m.def(
      "import_step",
      [](const std::filesystem::path& path, double linear_deflection, double angular_deflection, bool aag,
         bool measure_deviation) {
        Expected<cad::CadModel> r = Error{};
        {
          py::gil_scoped_release release;
          r = cad::import_step(path, {.linear_deflection = linear_deflection,
                                      .angular_deflection = angular_deflection,
                                      .measure_deviation = measure_deviation,
                                      .build_aag = aag});
        }
        if (!r) throw py::value_error(r.error().message());
        py::dict out;
        py::list parts;
        for (const cad::Part& p : r->parts) {
          py::dict d;
          d["name"] = p.name;
          d["mesh"] = p.mesh;
          d["face_ids"] = p.face_ids;
          d["faces"] = p.faces;
          d["solids"] = p.solids;
          d["linear_deflection"] = p.linear_deflection;
          d["tessellation_deviation"] = p.tessellation_deviation;
          py::list nodes, arcs;
          for (const cad::AagNode& n : p.aag.nodes)
            nodes.append(py::dict(py::arg("face") = n.face, py::arg("type") = cad::surface_type_name(n.type),
                                  py::arg("radius") = n.radius, py::arg("hole") = n.hole,
                                  py::arg("from_bspline") = n.from_bspline, py::arg("inner_loops") = n.inner_loops));
          for (const cad::AagArc& a : p.aag.arcs)
            arcs.append(py::dict(py::arg("faces") = py::make_tuple(a.a, a.b), py::arg("curve") = cad::curve_type_name(a.curve),
                                 py::arg("convexity") = cad::convexity_name(a.convexity), py::arg("angle") = a.angle));
          d["aag_nodes"] = nodes;
          d["aag_arcs"] = arcs;
          parts.append(d);
        }
        out["parts"] = parts;
        py::list inst;
        for (const cad::Instance& i : r->instances)
          inst.append(py::dict(py::arg("name") = i.name, py::arg("part") = i.part, py::arg("path") = i.path,
                               py::arg("placement") = i.placement));
        out["instances"] = inst;
        out["warnings"] = r->warnings;
        out["units"] = r->units;
        out["file_length_units"] = r->file_length_units;
        return out;
      },
      py::arg("path"), py::arg("linear_deflection") = 0.0, py::arg("angular_deflection") = 0.5, py::arg("aag") = true,
      py::arg("measure_deviation") = false,
      "Reads a STEP file: parts (name, mesh, per-triangle face_ids, linear_deflection, tessellation_deviation (with "
      "measure_deviation=True: how far the triangles measured from their surfaces, else -1), AAG nodes/arcs: empty with "
      "aag=False, for triangles only), instances (name, part, path, placement: Transform, part -> world), warnings, "
      "units (always 'mm') and file_length_units (the units the file declares).");
  m.def(
      "step_features",
      [](const std::filesystem::path& path, const std::string& process_file, const std::string& step,
         const std::string& library_file, const std::string& rules_file) {
        if (process_file.empty() != step.empty()) throw py::value_error("process and step go together");
        auto sem = cad::load_semantics(
            {.library_file = library_file, .rules_file = rules_file, .process_file = process_file, .step = step});
        if (!sem) throw py::value_error(sem.error().message());
        auto model = cad::import_step(path);
        if (!model) throw py::value_error(model.error().message());
        const cad::FeatureLibrary* lib = &sem->library;
        py::list out;
        for (const cad::Part& p : model->parts) {
          const auto feats = cad::recognize_features(p.aag, *lib);
          py::list fl;
          for (const cad::Feature& f : feats)
            fl.append(py::dict(py::arg("type") = f.type, py::arg("faces") = f.faces, py::arg("roles") = f.roles,
                               py::arg("radii") = f.radii));
          py::dict d(py::arg("part") = p.name, py::arg("features") = fl);
          std::vector<std::uint32_t> assembly;
          if (!process_file.empty()) {  // in the step when it names the part or one of its instances
            const auto sel = cad::part_step_selection(*sem->process, step, sem->rules, *model,
                                                      static_cast<std::uint32_t>(&p - model->parts.data()), feats);
            if (!sel) throw py::value_error(sel.error().message());
            d["assembly_feature_faces"] = assembly = sel->faces;
          }
          d["dot"] = cad::aag_dot({{p.name, &p.aag, feats, assembly}});
          out.append(d);
        }
        return out;
      },
      py::arg("path"), py::arg("process") = std::string(), py::arg("step") = std::string(),
      py::arg("library") = std::string(), py::arg("rules") = std::string(),
      "Features of every part of a STEP file (library types, face ids, roles, radii), its AAG as Graphviz DOT "
      "(dot: as `interfere features --dot`) and, with process/step, the assembly-feature faces of that step "
      "(library, rules: JSON files instead of the installed ones).");
  m.def(
      "prepare_step",
      [](const std::filesystem::path& path, const std::string& process_file, const std::string& step,
         double linear_deflection, double angular_deflection, const std::string& library_file,
         const std::string& rules_file, bool mates, const std::string& mesher) {
        if (process_file.empty() != step.empty()) throw py::value_error("process and step go together");
        if (mesher != "default" && mesher != "delabella")
          throw py::value_error("mesher must be 'default' or 'delabella', not '" + mesher + "'");
        Expected<cad::Prepared> r = Error{};
        {
          py::gil_scoped_release release;
          r = cad::prepare_for_simplify(path.string(), {linear_deflection, angular_deflection, library_file,
                                                        rules_file, process_file, step, mates, mesher == "delabella"});
        }
        if (!r) throw py::value_error(r.error().message());
        py::list parts;
        for (const cad::PreparedPart& p : r->parts)
          parts.append(py::dict(py::arg("name") = p.name, py::arg("mesh") = p.mesh, py::arg("face_ids") = p.face_ids,
                                py::arg("feature_faces") = p.feature_faces, py::arg("faces") = p.faces,
                                py::arg("instances") = p.instances, py::arg("model_part") = p.model_part,
                                py::arg("tessellation_error") = p.tessellation_error));
        py::dict out;
        out["parts"] = parts;
        out["instances"] = instance_list(*r);
        out["warnings"] = r->warnings;
        out["report"] = py::module_::import("json").attr("loads")(r->report_json);
        return out;
      },
      py::arg("path"), py::arg("process") = std::string(), py::arg("step") = std::string(),
      py::arg("linear_deflection") = 0.0, py::arg("angular_deflection") = 0.5, py::arg("library") = std::string(),
      py::arg("rules") = std::string(), py::arg("mates") = true, py::arg("mesher") = std::string("default"),
      "The CLI's STEP pipeline up to simplification (mates=True without a process: the assembly features the mates "
      "inferred from the geometry pick, as `interfere simplify --mates auto`; mesher: 'default' or 'delabella', as "
      "--mesher): parts ready for interfere.simplify (name, mesh in part "
      "coordinates, face_ids, feature_faces of the step, faces, instances, model_part, tessellation_error (the larger of "
      "the linear deflection and the measured deviation: relative to the B-Rep, add it to a simplification's error "
      "bound); a part whose instances "
      "differ in taking part in the step comes twice, '<part> [<step>]' with the step's features), instances "
      "(name, part: index into parts, placement: Transform, face_offset), warnings and the CLI report's 'cad' "
      "object (report). Budgets per part: interfere.triangle_budgets.");
  m.def(
      "assembly_clash",
      [](const std::filesystem::path& path, double clearance, double linear_deflection, double angular_deflection,
         bool geometry) {
        if (!(clearance >= 0 && std::isfinite(clearance))) throw py::value_error("clearance must be >= 0");
        Expected<cad::CadModel> model = Error{};
        cad::AssemblyClashResult r;
        {
          py::gil_scoped_release release;
          model = cad::import_step(path, {.linear_deflection = linear_deflection,
                                          .angular_deflection = angular_deflection,
                                          .measure_deviation = true});
          if (model) r = cad::assembly_clash(*model, {.clearance = clearance, .geometry = geometry});
        }
        if (!model) throw py::value_error(model.error().message());
        py::list pairs;
        for (const cad::InstancePairResult& q : r.pairs) {
          py::dict d(py::arg("a") = q.a, py::arg("b") = q.b, py::arg("a_name") = model->instances[q.a].name,
                                py::arg("b_name") = model->instances[q.b].name,
                                py::arg("meeting") = cad::instance_meeting_name(q.meeting),
                                py::arg("cross_pairs") = q.cross_pairs, py::arg("touch_pairs") = q.touch_pairs,
                                py::arg("touching_overlap") = q.touching_overlap,
                                py::arg("containment") = containment_name(q.containment),
                                py::arg("curve_length") = q.curve_length, py::arg("clearance_pairs") = q.clearance_pairs,
                                py::arg("min_clearance") = q.min_clearance, py::arg("depth") = q.depth,
                                py::arg("depth_bound") = q.depth_bound,
                                py::arg("tessellation_error") = q.tessellation_error,
                                py::arg("nominal_fit") = q.nominal_fit,
                                py::arg("verdict") = cad::instance_meeting_name(q.meeting),
                                py::arg("verdict_reasons") = q.verdict_reasons);
          if (geometry) {
            d["curves"] = q.curves;
            d["region_triangles_a"] = q.region_triangles_a;
            d["region_triangles_b"] = q.region_triangles_b;
          }
          pairs.append(d);
        }
        py::dict out;
        out["pairs"] = pairs;
        out["candidate_pairs"] = r.candidate_pairs;
        out["clashes"] = r.clashes;
        out["contacts"] = r.contacts;
        out["within_clearance"] = r.within_clearance;
        out["undecided"] = r.undecided;
        out["verdict"] = verdict_name(r.verdict);
        std::vector<std::string> warnings = model->warnings;
        warnings.insert(warnings.end(), r.warnings.begin(), r.warnings.end());
        out["warnings"] = warnings;
        return out;
      },
      py::arg("path"), py::arg("clearance") = 0.0, py::arg("linear_deflection") = 0.0, py::arg("angular_deflection") = 0.5,
      py::arg("geometry") = false,
      "`interfere assembly-clash` of a STEP file: every pair of instances that meets, as a dict with pairs [{a, b, "
      "a_name, b_name, meeting and verdict ('clash', 'contact', 'clearance', 'undecided'), verdict_reasons, cross_pairs, touch_pairs, touching_overlap, "
      "containment, curve_length, clearance_pairs, min_clearance, depth (sampled), depth_bound (an upper bound, for "
      "clashes; else 0), tessellation_error, nominal_fit; with "
      "geometry=True also curves (Polylines, world coordinates) and region_triangles_a/_b (each instance's clash-region "
      "triangles, indices into its part's mesh; empty unless the pair clashes)}], candidate_pairs, clashes, contacts, "
      "within_clearance, undecided, verdict (the worst pair's), warnings. ValueError on bad input.");
  m.def(
      "simplify_step",
      [](const std::filesystem::path& path, std::size_t target, double ratio, std::size_t renderer_max,
         const std::string& process_file, const std::string& step, bool lock, const std::string& feature_mode,
         const std::string& seams, bool prevent_self_intersections, bool measure_error, double max_error,
         double linear_deflection, double angular_deflection, const std::string& library_file,
         const std::string& rules_file, bool mates, const std::string& mesher) {
        if (process_file.empty() != step.empty()) throw py::value_error("process and step go together");
        if ((target > 0) + (ratio > 0) + (renderer_max > 0) != 1)
          throw py::value_error("give one of target, ratio or renderer_max");
        if (mesher != "default" && mesher != "delabella")
          throw py::value_error("mesher must be 'default' or 'delabella', not '" + mesher + "'");
        SimplifyOptions o;
        o.target_triangles = target;
        o.ratio = ratio;
        o.feature_mode = feature_mode_of(feature_mode, lock);
        o.seams = seam_mode_of(seams);
        o.prevent_self_intersections = prevent_self_intersections;
        o.measure_error = measure_error;
        o.max_error = max_error;
        Expected<cad::Prepared> prep = Error{};
        Expected<cad::AssemblySimplifyResult> r = Error{};
        {
          py::gil_scoped_release release;
          // mates as the CLI's --mates auto|off (issue #29, item 4): on by default; ignored with a process
          // (cad::PipelineOptions::mates), so a process step's features are kept either way.
          prep = cad::prepare_for_simplify(path.string(), {linear_deflection, angular_deflection, library_file,
                                                           rules_file, process_file, step, mates,
                                                           mesher == "delabella"});
          if (prep && renderer_max > 0) {  // the total from the renderer's maximum (docs/simplify.md "Budget")
            const std::size_t f = count_feature_triangles(prep->face_ids, prep->feature_faces);
            o.target_triangles = std::max<std::size_t>(
                1, triangle_budgets({{prep->mesh.num_triangles(), f}}, renderer_max).budgets[0]);
          }
          if (prep) r = cad::simplify_assembly(*prep, o);
        }
        if (!prep) throw py::value_error(prep.error().message());
        if (!r) throw py::value_error(path.string() + ": " + r.error().message());
        py::list parts;
        for (std::size_t i = 0; i < prep->parts.size(); ++i) {
          const cad::PreparedPart& p = prep->parts[i];
          parts.append(py::dict(py::arg("name") = p.name, py::arg("result") = std::move(r->parts[i]),
                                py::arg("budget") = r->part_budgets[i], py::arg("instances") = p.instances,
                                py::arg("feature_faces") = p.feature_faces, py::arg("model_part") = p.model_part,
                                py::arg("tessellation_error") = p.tessellation_error));
        }

        py::dict out;
        out["result"] = std::move(r->merged);
        out["parts"] = parts;
        out["instances"] = instance_list(*prep);
        out["budget_rounds"] = r->budget_rounds;
        out["features_exceed_budget"] = r->features_exceed_budget;
        out["feature_faces"] = prep->feature_faces;
        out["warnings"] = prep->warnings;
        out["report"] = py::module_::import("json").attr("loads")(prep->report_json);
        return out;
      },
      py::arg("path"), py::arg("target") = 0, py::arg("ratio") = 0.0, py::arg("renderer_max") = 0,
      py::arg("process") = std::string(), py::arg("step") = std::string(), py::arg("lock") = false,
      py::arg("feature_mode") = std::string("weight"), py::arg("seams") = std::string("auto"),
      py::arg("prevent_self_intersections") = true, py::arg("measure_error") = true, py::arg("max_error") = 0.0,
      py::arg("linear_deflection") = 0.0, py::arg("angular_deflection") = 0.5, py::arg("library") = std::string(),
      py::arg("rules") = std::string(), py::arg("mates") = true, py::arg("mesher") = std::string("default"),
      "`interfere simplify` of a STEP file: every part simplified on its own to its share of one total budget "
      "(target, ratio of the model's triangles, or from renderer_max), the step's assembly features kept (without a "
      "process: those the mates inferred from the geometry pick unless mates=False, as the CLI's default --mates "
      "auto and --mates off; mates is ignored with a process; mesher: 'default' or 'delabella', as --mesher); parts "
      "that stop early leave the rest to the others. Returns result (SimplifyResult of every instance placed, face "
      "ids as prepare_step's world ids), parts [{name, result (part coordinates), budget (per instance, 0: not "
      "simplified), instances, feature_faces, model_part, tessellation_error}], instances, budget_rounds, features_exceed_budget, "
      "feature_faces (world ids), warnings (the import's; the simplification's are in result.warnings) and report "
      "(the CLI report's 'cad' object). ValueError on bad input.");
#else
  m.attr("HAVE_CAD") = false;
#endif
}

}  // namespace interfere::python
