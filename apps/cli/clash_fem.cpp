// `interfere clash` on FEM parts: read_fem + surface extraction per part, displacements per step,
// refit + clash per step (fem/deform.h), results named by the solver's element and node ids.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <cmath>
#include <limits>
#include <filesystem>

#include "clash_options.h"
#include "fem_parts.h"
#include "fem_surfaces.h"
#include "interfere/core/atomic_file.h"
#include "interfere/fem/io.h"
#include "interfere/mesh/io.h"
#include "interfere/mesh/polyline.h"
#include "interfere/view/fem_document.h"
#include "report_json.h"
#include "report_envelope.h"
#include "progress_bar.h"

namespace interfere::cli {
namespace {

// The clash-region triangles of both parts as a tri3 FemMesh (nodes at the step's positions) with
// cell data fem_element_id, fem_face, part (0 = A, 1 = B), region, and point data fem_node_id.
struct RegionMesh {
  FemMesh mesh;
  FemWriteOptions options;
};

// The clash regions of both parts as one surface mesh; `maps` (the step's depth maps, when
// measured) add the point data penetration_depth (issue #26, item 3).
RegionMesh region_mesh(const ClashResult& r, const FemPart* parts[2], const std::vector<Vec3>* positions[2],
                       const DepthMaps* maps) {
  RegionMesh out;
  FemMesh& m = out.mesh;
  m.groups = {{.name = "A", .id = 1, .dim = 2}, {.name = "B", .id = 2, .dim = 2}};
  FemArray elem{.name = "fem_element_id"}, face{.name = "fem_face"}, part{.name = "part"}, region{.name = "region"};
  FemArray node_id{.name = "fem_node_id"}, depth{.name = "penetration_depth"};
  for (int side = 0; side < 2; ++side) {
    const SurfacePart& sp = parts[side]->part();
    const FemMesh& fm = *parts[side]->mesh;
    std::vector<std::uint32_t> local(sp.mesh.num_vertices(), ~0u);
    for (std::size_t g = 0; g < r.regions.size(); ++g) {
      const auto& tris = side == 0 ? r.regions[g].triangles_a : r.regions[g].triangles_b;
      for (std::uint32_t t : tris) {
        std::uint32_t v[3];
        for (int k = 0; k < 3; ++k) {
          std::uint32_t& l = local[sp.mesh.triangles[t][k]];
          if (l == ~0u) {
            l = static_cast<std::uint32_t>(m.nodes.size());
            m.nodes.push_back((*positions[side])[sp.mesh.triangles[t][k]]);
            m.node_ids.push_back(static_cast<std::int64_t>(m.nodes.size()));
            node_id.ints.push_back(fm.node_ids[sp.vertex_node[sp.mesh.triangles[t][k]]]);
            if (maps) {
              const DepthMap& dm = side == 0 ? maps->a : maps->b;
              const std::uint32_t vx = sp.mesh.triangles[t][k];
              depth.reals.push_back(vx < dm.side.size() && dm.side[vx] == -1 ? std::numeric_limits<double>::quiet_NaN()
                                    : vx < dm.depth.size()                 ? dm.depth[vx]
                                                                           : 0.0);
            }
          }
          v[k] = l;
        }
        m.add_element(ElemType::tri3, static_cast<std::int64_t>(m.num_elements() + 1), side, v, 3);
        elem.ints.push_back(fm.elem_ids[sp.tri_element[t]]);
        face.ints.push_back(sp.tri_face[t]);
        part.ints.push_back(side);
        region.ints.push_back(static_cast<std::int64_t>(g));
      }
    }
  }
  out.options.cell_data = {elem, face, part, region};
  out.options.point_data = {node_id};
  if (maps) out.options.point_data.push_back(std::move(depth));
  return out;
}

std::string step_label(const StepSummary& s) { return fmt::format("{} (time {:g})", s.step, s.time); }

// A step's penetration depth (issue #26, item 3): depth, depth_bound (null when not measured or not
// bounded), the deepest node (part "a" or "b", FE node id, an element id at it, depth, point),
// and depth_note (why a clashing step's depth is not measured, or what limits it).
void add_depth_json(nlohmann::json& j, const StepSummary& s) {
  j["depth"] = s.depth_measured ? nlohmann::json(s.depth) : nlohmann::json(nullptr);
  j["depth_bound"] = s.depth_measured && s.depth_bounded ? nlohmann::json(s.depth_bound) : nlohmann::json(nullptr);
  j["deepest"] = s.has_deepest ? nlohmann::json{{"part", s.deepest.part == 0 ? "a" : "b"},
                                                {"node", s.deepest.node},
                                                {"element", s.deepest.element},
                                                {"depth", s.deepest.depth},
                                                {"point", vec_json(s.deepest.point)}}
                               : nlohmann::json(nullptr);
  j["depth_note"] = s.depth_note.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.depth_note);
}

// The text summary's line on a step's depth.
std::string depth_text(const StepSummary& s, const std::string& units) {
  if (!s.depth_measured) return s.depth_note;
  std::string t = fmt::format("depth {:.6g} {} at step {}", s.depth, units, step_label(s));
  if (s.depth_bounded) t += fmt::format(" (at most {:.6g})", s.depth_bound);
  if (s.has_deepest)
    t += fmt::format(": deepest node {} of part {} (element {}), {:.6g} {} inside part {}", s.deepest.node,
                     s.deepest.part == 0 ? "A" : "B", s.deepest.element, s.deepest.depth, units,
                     s.deepest.part == 0 ? "B" : "A");
  if (!s.depth_note.empty()) t += "; " + s.depth_note;
  return t;
}

// --html/--glb/--pvd (issue #25): the two surfaces at every checked step, a row per step that is
// not clear (view/fem_document.h). `steps`: what on_step kept of each checked step.
view::Document series_view(const FemPart& a, const FemPart& b, double scale, std::vector<view::FemSeriesStep> steps,
                           const SeriesResult& sres, const std::string& units) {
  view::FemSeriesInput in;
  in.num_steps = sres.num_steps;
  in.verdict = sres.verdict;
  in.units = units;
  const FemPart* parts[2] = {&a, &b};
  for (std::size_t side = 0; side < 2; ++side) {
    const FemPart& p = *parts[side];
    const SurfacePart& sp = p.part();
    view::FemSeriesBody& body = in.bodies[side];
    body.id = side == 0 ? "A" : "B";
    body.name = sp.name;
    body.path = "/" + std::filesystem::path(p.file).stem().string() + "/" + sp.name;  // as fem/bodies.cpp names scene bodies
    body.role = "part " + body.id;
    body.surface = &sp.mesh;
    body.source_ids.reserve(sp.tri_element.size());
    for (const std::uint32_t e : sp.tri_element) body.source_ids.push_back(p.mesh->elem_ids[e]);
  }
  for (view::FemSeriesStep& s : steps) {
    deformed_positions(a.part(), *a.mesh, a.displacement, s.step, scale, s.positions[0]);
    deformed_positions(b.part(), *b.mesh, b.displacement, s.step, scale, s.positions[1]);
  }
  in.steps = std::move(steps);
  return view::fem_series_document(std::move(in));
}

}  // namespace

void add_fem_clash_options(CLI::App& c, ClashOptions& o) {
  c.add_option("--part", o.part, "FEM: body of both parts (group name, or 'body N' by connectivity)");
  c.add_option("--part-a", o.part_a, "FEM: body of part A (overrides --part)");
  c.add_option("--part-b", o.part_b, "FEM: body of part B (overrides --part)");
  c.add_option("--disp", o.disp, "FEM: nodal displacement CSV for both parts");
  c.add_option("--disp-a", o.disp_a, "FEM: displacement CSV of part A (overrides --disp/--field)");
  c.add_option("--disp-b", o.disp_b, "FEM: displacement CSV of part B (overrides --disp/--field)");
  c.add_option("--field", o.field, "FEM: nodal vector field of the mesh file(s) used as displacement");
  c.add_option("--field-a", o.field_a, "FEM: field of part A (overrides --disp/--field)");
  c.add_option("--field-b", o.field_b, "FEM: field of part B (overrides --disp/--field)");
  c.add_option("--scale", o.scale, "FEM: displacement scale, position = node + scale * u (default 1)");
  c.add_option("--step", o.step, "FEM: check only this step (0-based); default every step");
  c.add_flag("--linear-faces", o.linear_faces, "FEM: quadratic faces by their corners only");
  c.add_option("--split", o.split, "FEM: bodies by auto (default), group, connectivity, single");
  c.add_option("--regions-vtu", o.regions_vtu,
               "FEM: write the clash regions (.vtu; cell data fem_element_id, fem_face, part, region; point data "
               "fem_node_id and, at a clashing step, penetration_depth)");
}

int run_fem_clash(const ClashOptions& o, const ResolvedParts& parts, const ClashRequest& request) {
  if (!std::isfinite(o.scale)) throw InputError("--scale must be a finite number");
  check_output(o.regions_vtu, {".vtu", ".vtk", ".msh"}, "--regions-vtu");
  if (o.step < -1) throw InputError("--step must be >= 0");
  const FailOn fail = fail_on(o.fail_on);
  set_threads(o.threads);
  Progress total("clash");

  // The parts' bodies and displacements as distance takes them (fem_surfaces.h): a part's own
  // displacement flag (--disp-a or --field-a) replaces both shared ones.
  const FemFlags flags{.part = o.part, .part_a = o.part_a, .part_b = o.part_b, .disp = o.disp, .disp_a = o.disp_a,
                       .disp_b = o.disp_b, .field = o.field, .field_a = o.field_a, .field_b = o.field_b,
                       .split = o.split, .linear_faces = o.linear_faces};
  FemPartOptions oa = fem_part_options(flags, 'a'), ob = fem_part_options(flags, 'b');
  oa.transform = parts.a.transform;
  ob.transform = parts.b.transform;
  // Each input's own unit, converted to the working unit (issue #23, item 6).
  for (auto [spec, opt] : {std::pair{&parts.a, &oa}, std::pair{&parts.b, &ob}}) {
    opt->unit = part_unit(*spec);
    opt->unit_scale = unit_in_mm(opt->unit.unit, opt->unit.source) / unit_in_mm(parts.units, "--units");
  }
  const FemPart a = load_fem_part(parts.a.file, oa, "A", false);
  // Two bodies of one file with the same displacement, pose and options: read and extract once.
  const bool same = parts.a.file == parts.b.file && oa.disp == ob.disp && oa.field == ob.field &&
                    oa.transform == ob.transform && oa.unit_scale == ob.unit_scale;
  const FemPart b = same ? other_part(a, ob.part, "B") : load_fem_part(parts.b.file, ob, "B", false);
  for (const FemPart* p : {&a, &b}) {
    for (const std::string& w : p->warnings) {
      warning(w);
    }
  }
  check_step_counts(a, b);
  const std::size_t na = a.num_steps(), nb = b.num_steps();
  const std::size_t num_steps = std::max<std::size_t>({na, nb, 1});
  SeriesRequest sr{.clash = request, .bvh = parts.bvh, .scale = o.scale, .keep_first_clash = true, .keep_last = true,
                   .depth = true};  // penetration depth of every clashing step (issue #26, item 3)
  const bool series = o.step < 0 && num_steps > 1;
  if (o.step >= 0) {
    const std::string whose = na   ? "the displacements of A (" + displacement_source_text(a) + ")"
                              : nb ? "the displacements of B (" + displacement_source_text(b) + ")"
                                   : std::string();
    sr.steps = {check_step(o.step, num_steps, whose)};
  }
  std::vector<view::FemSeriesStep> view_steps;  // --html/--glb/--pvd: the regions of every checked step
  DepthMaps step_maps;  // --pvd etc.: the depth maps of the step on_step is about to hand over
  bool step_mapped = false;
  DepthMaps first_clash_maps;  // --regions-vtu: the depth maps of the first clashing step (the one shown)
  bool first_clash_mapped = false;
  if (!o.regions_vtu.empty() && !o.views.any())
    sr.on_depth_maps = [&](const StepSummary& s, const DepthMaps& m) {
      if (!first_clash_mapped && s.verdict == Verdict::clash) first_clash_maps = m, first_clash_mapped = true;
    };
  if (o.views.any()) {
    sr.on_depth_maps = [&](const StepSummary& s, const DepthMaps& m) {
      if (!o.regions_vtu.empty() && !first_clash_mapped && s.verdict == Verdict::clash)
        first_clash_maps = m, first_clash_mapped = true;
      step_maps = m, step_mapped = true;
    };
    sr.on_step = [&](const StepSummary& s, const ClashResult& r) {
      view_steps.push_back(view::fem_series_step(s.step, s.time, r));
      if (step_mapped) view_steps.back().depth = {std::move(step_maps.a.depth), std::move(step_maps.b.depth)};
      step_mapped = false;
    };
  }

  // Steps: a progress bar with rate and ETA on a terminal, a line per tenth otherwise (progress_bar.h).
  std::unique_ptr<ProgressBar> step_bar;
  std::size_t steps_done = 0;
  if (series) {
    step_bar = std::make_unique<ProgressBar>("steps", num_steps, "steps");
    sr.on_step = [&, inner = std::move(sr.on_step)](const StepSummary& s, const ClashResult& r) {
      if (inner) inner(s, r);
      step_bar->update(++steps_done);
    };
  }
  Expected<SeriesResult> run = Error{};
  {
    Progress progress(series ? "clash per step (" + std::to_string(num_steps) + " steps)" : std::string("clash query"));
    run = clash_series(a.series(), b.series(), sr);
    step_bar.reset();  // (ends the bar's line before the timing line)
  }
  if (!run) throw InputError(run.error());
  const SeriesResult& sres = *run;
  const bool clashed = sres.first_clash_step >= 0;
  // The verdict model (query/verdict.h, issue #23 item 13): the series' verdict is the worst of its
  // steps'; bodies bonded through shared nodes or faces touch without overlapping: a contact.
  // The step whose full result is reported: the first step with the series' verdict when that is
  // not clear (the first clashing step when one clashes), else the last checked one.
  const bool show_worst = sres.verdict != Verdict::clear && sres.worst_step >= 0;
  const ClashResult& result = show_worst ? sres.worst : sres.last;
  const std::int64_t shown_step = show_worst ? sres.worst_step : static_cast<std::int64_t>(sres.steps.back().step);
  const StepSummary& shown = *std::find_if(sres.steps.begin(), sres.steps.end(), [&](const StepSummary& s) {
    return static_cast<std::int64_t>(s.step) == shown_step;
  });
  for (const std::string& w : result.warnings) {
    warning(w);
  }

  // Outputs (inputs fully validated above).
  std::vector<Vec3> pos_a, pos_b;
  deformed_positions(a.part(), *a.mesh, a.displacement, shown.step, o.scale, pos_a);
  deformed_positions(b.part(), *b.mesh, b.displacement, shown.step, o.scale, pos_b);
  if (!o.pairs.empty()) {
    std::string s;
    for (const TrianglePair& p : result.pairs) s += fmt::format("{} {} {}\n", p.a, p.b, kind_name(p.kind));
    write_or_throw(write_output(o.pairs, s));
  }
  auto write_region = [&](const std::string& path, const FemPart& p, const std::vector<Vec3>& pos, bool part_a) {
    if (path.empty()) return;
    std::vector<std::uint32_t> tris;
    for (const ClashRegion& g : result.regions) {
      const auto& v = part_a ? g.triangles_a : g.triangles_b;
      tris.insert(tris.end(), v.begin(), v.end());
    }
    std::sort(tris.begin(), tris.end());
    if (tris.empty()) {
      std::fprintf(stderr, "[interfere] note: part %s has no clash region; %s not written\n", part_a ? "A" : "B",
                   path.c_str());
      return;
    }
    TriMesh m = p.part().mesh;
    m.positions = pos;
    write_or_throw(write_mesh(path, submesh(m, tris)));
  };
  write_region(o.region_a, a, pos_a, true);
  write_region(o.region_b, b, pos_b, false);
  if (!o.curves.empty()) {
    std::vector<Polyline> all;
    for (const ClashRegion& g : result.regions) all.insert(all.end(), g.curves.begin(), g.curves.end());
    for (const std::string& c : o.curves) write_or_throw(write_polylines(c, all));
  }
  if (!o.regions_vtu.empty()) {
    if (result.regions.empty()) {
      std::fprintf(stderr, "[interfere] note: no clash region; %s not written\n", o.regions_vtu.c_str());
    } else {
      const FemPart* ps[2] = {&a, &b};
      const std::vector<Vec3>* pp[2] = {&pos_a, &pos_b};
      const bool maps_shown = first_clash_mapped && sres.verdict == Verdict::clash;  // (shown = first clashing step)
      RegionMesh rm = region_mesh(result, ps, pp, maps_shown ? &first_clash_maps : nullptr);
      write_or_throw(write_fem(rm.mesh, o.regions_vtu, rm.options));
    }
  }

  const int status = verdict_exit_status(sres.verdict, fail);
  auto summary_json = [](const StepSummary& s) {
    return nlohmann::json{{"step", s.step},
                          {"time", s.time},
                          {"interference", s.interference},
                          {"verdict", verdict_name(s.verdict)},
                          {"pairs", s.pairs},
                          {"cross_pairs", s.cross_pairs},
                          {"touch_pairs", s.touch_pairs},
                          {"regions", s.regions},
                          {"max_curve_length", s.max_curve_length},
                          {"curve_length", s.total_curve_length},
                          {"containment", containment_name(s.containment)},
                          {"refit_seconds", s.refit_seconds},
                          {"clash_seconds", s.clash_seconds}};
  };
  auto step_json = [&](const StepSummary& s) {
    nlohmann::json j = summary_json(s);
    add_depth_json(j, s);
    j["depth_seconds"] = s.depth_seconds;
    return j;
  };
  const StepSummary* deepest = nullptr;
  for (const StepSummary& s : sres.steps)
    if (static_cast<std::int64_t>(s.step) == sres.deepest_step) deepest = &s;
  if (!o.json.empty()) {
    nlohmann::json steps = nlohmann::json::array();
    double query = 0;
    for (const StepSummary& s : sres.steps) {
      steps.push_back(step_json(s));
      query += s.refit_seconds + s.clash_seconds + s.depth_seconds;
    }
    nlohmann::json res = clash_result_json(result, o.max_clearance_pairs);
    for (std::size_t i = 0; i < result.regions.size(); ++i) {
      res["regions"][i]["fem"] = region_ids_json(region_ids(result.regions[i], a.part(), *a.mesh, b.part(), *b.mesh));
    }
    add_depth_json(res, shown);
    std::vector<std::string> input_warnings = a.warnings;
    input_warnings.insert(input_warnings.end(), b.warnings.begin(), b.warnings.end());
    nlohmann::json j = {
        {"interfere_version", INTERFERE_VERSION},
        {"command", "clash"},
        {"units", parts.units},
        {"inputs", {{"a", fem_part_json(a)}, {"b", fem_part_json(b)}}},
        {"input_warnings", input_warnings},
        {"options",
         {{"test", o.test}, {"broadphase", o.broadphase}, {"builder", o.builder}, {"threads", active_threads()},
          {"clearance", o.clearance}, {"containment", !o.no_containment}, {"scale", o.scale},
          {"step", o.step >= 0 ? nlohmann::json(o.step) : nlohmann::json(nullptr)},
          {"linear_faces", o.linear_faces}, {"split", o.split}}},
        {"series",
         {{"steps_total", num_steps},
          {"steps_checked", sres.steps.size()},
          {"verdict", verdict_name(sres.verdict)},
          {"first_clash_step", clashed ? nlohmann::json(sres.first_clash_step) : nlohmann::json(nullptr)},
          {"first_clash_time", clashed ? nlohmann::json(shown.time) : nlohmann::json(nullptr)},
          {"first_contact_step",
           sres.first_contact_step >= 0 ? nlohmann::json(sres.first_contact_step) : nlohmann::json(nullptr)},
          {"deepest_step", deepest ? nlohmann::json(deepest->step) : nlohmann::json(nullptr)},
          {"max_depth", deepest ? nlohmann::json(deepest->depth) : nlohmann::json(nullptr)},
          {"steps", steps}}},
        {"verdict", verdict_name(sres.verdict)},
        {"verdict_reasons", result.verdict_reasons},
        {"result_step", shown.step},
        {"result_time", shown.time},
        {"result", res},
        {"warnings", result.warnings},
        {"exit_status", status},
        {"timings_s",
         {{"read", a.read_seconds + (same ? 0.0 : b.read_seconds)},
          {"extract", a.extract_seconds + (same ? 0.0 : b.extract_seconds)},
          {"build", sres.build_seconds},
          {"query", query},
          {"total", total.seconds()}}}};
    write_or_throw(write_output(o.json, report_text(j)));
  }
  if (o.views.any()) {
    view::Document doc = series_view(a, b, o.scale, std::move(view_steps), sres, parts.units);
    for (const std::string& w : result.warnings) doc.notes.push_back(w);
    write_views(o.views, std::move(doc));
  }

  if (series) {
    std::printf("%6s %12s %8s %8s %8s %8s %12s %-11s %s\n", "step", "time", "pairs", "cross", "touch", "regions",
                "max_curve", "containment", "verdict");
    for (const StepSummary& s : sres.steps) {
      std::printf("%6zu %12.6g %8zu %8zu %8zu %8zu %12.6g %-11s %s\n", s.step, s.time, s.pairs, s.cross_pairs,
                  s.touch_pairs, s.regions, s.max_curve_length, containment_name(s.containment),
                  verdict_name(s.verdict));
    }
    if (clashed) {
      std::printf("CLASH: first clash at step %s of %zu\n", step_label(shown).c_str(), num_steps);
      if (deepest) std::printf("max %s\n", depth_text(*deepest, parts.units).c_str());
      if (!shown.depth_measured && !shown.depth_note.empty()) std::printf("%s\n", shown.depth_note.c_str());
    } else if (sres.verdict == Verdict::undecided) {
      std::printf("UNDECIDED: first at step %s of %zu", step_label(shown).c_str(), num_steps);
      for (const std::string& why : result.verdict_reasons) std::printf("; %s", why.c_str());
      std::printf("\n");
    } else if (sres.verdict == Verdict::contact || sres.verdict == Verdict::clearance) {
      std::printf("%s: no clash in %zu steps, first %s at step %s\n", verdict_name(sres.verdict), num_steps,
                  verdict_name(sres.verdict), step_label(shown).c_str());
    } else {
      std::printf("clear: no clash in %zu steps\n", num_steps);
    }
  } else {
    print_clash_summary(result, parts.units);
    if (num_steps > 1) std::printf(", step %s", step_label(shown).c_str());
    std::printf("\n");
    if (shown.verdict == Verdict::clash && (shown.depth_measured || !shown.depth_note.empty()))
      std::printf("%s\n", depth_text(shown, parts.units).c_str());
  }
  return status;
}

}  // namespace interfere::cli
