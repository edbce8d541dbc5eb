// Deformed FEM parts and the clash per load step (fem/deform.h): positions gathered from the nodal
// displacements, trees refitted per step (bottom-up box recomputation of an unchanged topology, as
// in van den Bergen, "Efficient collision detection of complex deformable models using AABB
// trees", J. Graphics Tools 2(4), 1997), then the static clash of issue #2.
#include "interfere/fem/deform.h"

#include "interfere/core/coordinate_range.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "surface_faces.h"

namespace interfere {

using namespace fem_detail;

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The element id of the part's first surface triangle at vertex v (-1 when none uses it).
std::int64_t element_at(const SurfacePart& part, const FemMesh& mesh, std::uint32_t v) {
  const auto& tris = part.mesh.triangles;
  for (std::size_t t = 0; t < tris.size(); ++t)
    if (tris[t][0] == v || tris[t][1] == v || tris[t][2] == v) return mesh.elem_ids[part.tri_element[t]];
  return -1;
}

// SeriesRequest::depth for one checked step (issue #26, item 3): the penetration depth and both
// depth maps of a clashing step of closed parts, the deepest node named by its FE ids. Returns
// whether `maps` were computed.
bool measure_depth(const SeriesPart& a, const SeriesPart& b, const Model& ma, const Model& mb, const ClashResult& r,
                   std::size_t max_splits, StepSummary& sum, DepthMaps& maps) {
  if (sum.verdict != Verdict::clash) return false;
  const bool ca = ma.stats.closed(), cb = mb.stats.closed();
  if (!ca || !cb) {
    sum.depth_note = std::string("depth not measured: ") +
                     (!ca && !cb ? "parts A and B are" : !ca ? "part A is" : "part B is") +
                     " not closed (inside/outside is undefined)";
    return false;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const PenetrationDepth d = penetration_depth(ma, mb, r, max_splits, &maps);
  sum.depth_measured = true;
  if (r.cross_pairs > 0 || r.touching_overlap) {
    sum.depth = d.depth, sum.depth_bound = d.depth_bound, sum.depth_bounded = d.bounded;
  } else {  // one part inside the other without crossing: the deepest node, no bound
    sum.depth = sum.depth_bound = std::max(maps.a.max_depth, maps.b.max_depth);
    sum.depth_note = "one part inside the other: the depth of the deepest surface node, no upper bound";
  }
  const SeriesPart* parts[2] = {&a, &b};
  const DepthMap* side_maps[2] = {&maps.a, &maps.b};
  const Model* models[2] = {&ma, &mb};
  for (int side = 0; side < 2; ++side) {
    const DepthMap& m = *side_maps[side];
    if (m.max_vertex == kNoVertex || !(m.max_depth > 0)) continue;
    if (sum.has_deepest && !(m.max_depth > sum.deepest.depth)) continue;  // ties: part a
    const SeriesPart& p = *parts[side];
    sum.has_deepest = true;
    sum.deepest = {.part = side,
                   .vertex = m.max_vertex,
                   .node = p.mesh->node_ids[p.part->vertex_node[m.max_vertex]],
                   .element = element_at(*p.part, *p.mesh, m.max_vertex),
                   .depth = m.max_depth,
                   .point = models[side]->mesh.positions[m.max_vertex]};
  }
  if (const std::size_t undecided = maps.a.undecided + maps.b.undecided; undecided > 0) {
    if (!sum.depth_note.empty()) sum.depth_note += "; ";
    sum.depth_note += std::to_string(undecided) + " surface nodes undecided (no inside/outside answer; depth 0 in the maps)";
  }
  sum.depth_seconds = seconds_since(t0);
  return true;
}
}  // namespace

void deformed_positions(const SurfacePart& part, const FemMesh& mesh, const NodalSeries* displacement,
                        std::size_t step, double scale, std::vector<Vec3>& out) {
  const std::size_t n = part.vertex_node.size();
  out.resize(n);
  const Vec3* nodes = mesh.nodes.data();
  const std::uint32_t* map = part.vertex_node.data();
  if (displacement == nullptr) {
    for (std::size_t i = 0; i < n; ++i) out[i] = nodes[map[i]];
    return;
  }
  const Vec3* u = displacement->values[step].data();
  auto body = [&](std::size_t lo, std::size_t hi) {
    for (std::size_t i = lo; i < hi; ++i) out[i] = nodes[map[i]] + u[map[i]] * scale;
  };
  if (n < 65536) {
    body(0, n);
  } else {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384),
                      [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
  }
}

Expected<SeriesResult> clash_series(const SeriesPart& a, const SeriesPart& b, const SeriesRequest& request) {
  auto fail = [](const std::string& file, std::string reason) { return Error{.file = file, .reason = std::move(reason)}; };
  if (!a.mesh || !a.part || !b.mesh || !b.part) return fail("", "clash_series: a part or its mesh is missing");
  if (!std::isfinite(request.scale)) return fail("", "scale must be finite");
  for (const SeriesPart* s : {&a, &b}) {
    if (!s->displacement) continue;
    for (std::size_t k = 0; k < s->displacement->values.size(); ++k) {
      if (s->displacement->values[k].size() != s->mesh->num_nodes()) {
        return fail(s->mesh->file, "displacement " + s->displacement->name + " step " + std::to_string(k) + " has " +
                                       std::to_string(s->displacement->values[k].size()) + " values for " +
                                       std::to_string(s->mesh->num_nodes()) + " nodes");
      }
    }
    if (s->displacement->num_steps() == 0) return fail(s->mesh->file, "displacement " + s->displacement->name + " has no step");
  }
  SeriesResult result;
  const std::size_t na = a.displacement ? a.displacement->num_steps() : 0;
  const std::size_t nb = b.displacement ? b.displacement->num_steps() : 0;
  if (na && nb && na != nb) {
    return fail(b.mesh->file, "mismatched step counts: part A's displacements have " + std::to_string(na) +
                                  " steps, part B's " + std::to_string(nb));
  }
  result.num_steps = std::max<std::size_t>({na, nb, 1});
  std::vector<std::size_t> steps = request.steps;
  if (steps.empty()) {
    for (std::size_t s = 0; s < result.num_steps; ++s) steps.push_back(s);
  }
  for (std::size_t i = 0; i < steps.size(); ++i) {
    if (steps[i] >= result.num_steps) {
      return fail("", "step " + std::to_string(steps[i]) + " out of range (the series has " +
                          std::to_string(result.num_steps) + " steps)");
    }
    if (i > 0 && steps[i] <= steps[i - 1]) return fail("", "steps must be increasing");
  }
  const NodalSeries* times = a.displacement ? a.displacement : b.displacement;

  auto t0 = std::chrono::steady_clock::now();
  std::pair<Model, Model> models = make_models(a.part->mesh, b.part->mesh, request.bvh, true);
  result.build_seconds = seconds_since(t0);
  std::vector<Vec3> pa, pb;
  std::size_t deepest_index = 0;  // of result.deepest_step in result.steps
  for (std::size_t s : steps) {
    StepSummary sum;
    sum.step = s;
    sum.time = times && s < times->times.size() ? times->times[s] : static_cast<double>(s);
    t0 = std::chrono::steady_clock::now();
    deformed_positions(*a.part, *a.mesh, a.displacement, s, request.scale, pa);
    deformed_positions(*b.part, *b.mesh, b.displacement, s, request.scale, pb);
    for (int side = 0; side < 2; ++side) {
      const std::vector<Vec3>& p = side == 0 ? pa : pb;
      const SeriesPart& sp = side == 0 ? a : b;
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (!coordinates_in_range(p[i])) {  // non-finite or beyond the exact tests' range (issue #23, item 7)
          return fail(sp.mesh->file, "step " + std::to_string(s) + ": node " +
                                         std::to_string(sp.mesh->node_ids[sp.part->vertex_node[i]]) +
                                         ": deformed position " + coordinate_range_reason(p[i]));
        }
      }
    }
    refit(models.first, std::move(pa));
    refit(models.second, std::move(pb));
    pa = {};
    pb = {};
    sum.refit_seconds = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    ClashResult r = clash(models.first, models.second, request.clash);
    sum.clash_seconds = seconds_since(t0);
    sum.pairs = r.pairs.size();
    sum.cross_pairs = r.cross_pairs;
    sum.touch_pairs = r.touch_pairs;
    sum.regions = r.regions.size();
    for (const ClashRegion& g : r.regions) {
      sum.max_curve_length = std::max(sum.max_curve_length, g.curve_length);
      sum.total_curve_length += g.curve_length;
    }
    sum.containment = r.containment;
    sum.interference = r.interference();
    sum.verdict = r.verdict;
    DepthMaps maps;
    const bool mapped = request.depth && measure_depth(a, b, models.first, models.second, r,
                                                       request.depth_bound_splits, sum, maps);
    if (sum.depth_measured && (result.deepest_step < 0 || sum.depth > result.steps[deepest_index].depth)) {
      result.deepest_step = static_cast<std::int64_t>(s);
      deepest_index = result.steps.size();
    }
    result.steps.push_back(sum);
    if (mapped && request.on_depth_maps) request.on_depth_maps(sum, maps);
    if (request.on_step) request.on_step(sum, r);
    if (sum.interference && result.first_contact_step < 0) result.first_contact_step = static_cast<std::int64_t>(s);
    if (sum.verdict == Verdict::clash && result.first_clash_step < 0) {
      result.first_clash_step = static_cast<std::int64_t>(s);
      if (request.keep_first_clash) result.first_clash = r;
    }
    if (result.worst_step < 0 || sum.verdict > result.verdict) {
      result.verdict = sum.verdict;
      result.worst_step = static_cast<std::int64_t>(s);
      if (request.keep_first_clash) result.worst = r;
    }
    if (request.keep_last && s == steps.back()) result.last = r;
    if (request.keep_all) result.results.push_back(std::move(r));
  }
  return result;
}

std::vector<std::uint32_t> element_face_nodes(const FemMesh& mesh, std::size_t e, int face) {
  const ElemType t = mesh.elem_types[e];
  const std::uint32_t* v = mesh.element_nodes(e);
  const FaceNodes kinds = face_nodes(t);
  const FaceDef* f = nullptr;
  if (is_shell(t)) {
    f = elem_info(t).corners == 3 ? &kTriShell : &kQuadShell;
  } else {
    const ElemFaces ef = volume_faces(t);
    if (face < 1 || face > ef.count) return {};
    f = &ef.faces[face - 1];
  }
  std::vector<std::uint32_t> out;
  for (int i = 0; i < f->n; ++i) out.push_back(v[f->c[i]]);
  if (kinds.mids) {
    for (int i = 0; i < f->n; ++i) out.push_back(v[f->m[i]]);
  }
  if (kinds.centre && f->centre != kNo) out.push_back(v[f->centre]);
  return out;
}

RegionIds region_ids(const ClashRegion& region, const SurfacePart& a, const FemMesh& mesh_a, const SurfacePart& b,
                     const FemMesh& mesh_b) {
  RegionIds r;
  auto side = [](const std::vector<std::uint32_t>& tris, const SurfacePart& p, const FemMesh& m,
                 std::vector<std::int64_t>& elements, std::vector<std::int64_t>& nodes,
                 std::vector<std::pair<std::int64_t, int>>& faces) {
    std::vector<std::pair<std::uint32_t, int>> ef;
    ef.reserve(tris.size());
    for (std::uint32_t t : tris) ef.emplace_back(p.tri_element[t], p.tri_face[t]);
    std::sort(ef.begin(), ef.end());
    ef.erase(std::unique(ef.begin(), ef.end()), ef.end());
    for (const auto& [e, f] : ef) {
      elements.push_back(m.elem_ids[e]);
      faces.emplace_back(m.elem_ids[e], f);
      for (std::uint32_t n : element_face_nodes(m, e, f)) nodes.push_back(m.node_ids[n]);
    }
    for (auto* v : {&elements, &nodes}) {
      std::sort(v->begin(), v->end());
      v->erase(std::unique(v->begin(), v->end()), v->end());
    }
    std::sort(faces.begin(), faces.end());
  };
  side(region.triangles_a, a, mesh_a, r.elements_a, r.nodes_a, r.faces_a);
  side(region.triangles_b, b, mesh_b, r.elements_b, r.nodes_b, r.faces_b);
  return r;
}

}  // namespace interfere
