// Checks of a viewer document before a file export (src/view/export_checks.h; issue #25).
#include "export_checks.h"

#include <cmath>
#include <limits>
#include <string_view>
#include <utility>

namespace interfere::view::detail {
namespace {

struct Bad {
  std::string where, why;
};

std::string at(std::string_view array, std::size_t i) { return std::string(array) + "[" + std::to_string(i) + "]"; }

void finite(const Vec3& p, const std::string& where) {
  if (!is_finite(p)) throw Bad{where, "not finite"};
}

void finite_float(const Vec3& p, const std::string& where) {
  finite(p, where);
  for (int k = 0; k < 3; ++k)
    if (std::fabs(p[k]) > std::numeric_limits<float>::max())
      throw Bad{where, "beyond the range of float32 (" + short_number(p[k]) + ")"};
}

void finite_pose(const Transform& t, const std::string& where) {
  for (const auto& row : t.r)
    for (double x : row)
      if (!std::isfinite(x)) throw Bad{where, "not finite"};
  finite(t.t, where);
}

void check_mesh(const Document& doc, std::size_t m) {
  const ViewMesh& vm = doc.meshes[m];
  const std::string where = at("meshes", m);
  const std::size_t nv = vm.mesh.num_vertices(), nt = vm.mesh.num_triangles();
  if (nv > std::numeric_limits<std::uint32_t>::max())
    throw Bad{where, std::to_string(nv) + " vertices: more than uint32 indices can address"};
  for (std::size_t v = 0; v < nv; ++v) finite_float(vm.mesh.positions[v], at(where + ".positions", v));
  for (std::size_t t = 0; t < nt; ++t)
    for (std::uint32_t i : vm.mesh.triangles[t])
      if (i >= nv)
        throw Bad{at(where + ".triangles", t), "vertex " + std::to_string(i) + " out of range (" + std::to_string(nv) + " vertices)"};
  const auto per_triangle = [&](std::size_t size, const char* field) {
    if (size != 0 && size != nt)
      throw Bad{where + "." + field, std::to_string(size) + " values for " + std::to_string(nt) + " triangles"};
  };
  per_triangle(vm.face_colors.size(), "face_colors");
  per_triangle(vm.clash_flags.size(), "clash_flags");
  per_triangle(vm.clash_region.size(), "clash_region");
  per_triangle(vm.source_ids.size(), "source_ids");
  for (std::size_t t = 0; t < vm.face_colors.size(); ++t)
    if (vm.face_colors[t] >= doc.legend.size())
      throw Bad{at(where + ".face_colors", t), "legend entry " + std::to_string(vm.face_colors[t]) + " out of range (" +
                                                    std::to_string(doc.legend.size()) + " entries)"};
  if (!vm.point_depth.empty() && vm.point_depth.size() != nv)
    throw Bad{where + ".point_depth", std::to_string(vm.point_depth.size()) + " values for " + std::to_string(nv) + " vertices"};
}

void check(const Document& doc) {
  const std::size_t frames = frame_count(doc);
  if (!doc.frames.times.empty() && doc.frames.times.size() != frames)
    throw Bad{"frames.times", std::to_string(doc.frames.times.size()) + " times for " + std::to_string(frames) + " frames"};
  for (std::size_t k = 0; k < doc.frames.times.size(); ++k)
    if (!std::isfinite(doc.frames.times[k])) throw Bad{at("frames.times", k), "not finite"};
  for (std::size_t m = 0; m < doc.meshes.size(); ++m) check_mesh(doc, m);
  const auto mesh_index = [&](std::uint64_t m, const std::string& where) {
    if (m >= doc.meshes.size())
      throw Bad{where, "mesh " + std::to_string(m) + " out of range (" + std::to_string(doc.meshes.size()) + " meshes)"};
  };
  for (std::size_t b = 0; b < doc.bodies.size(); ++b) {
    const ViewBody& body = doc.bodies[b];
    const std::string where = at("bodies", b);
    mesh_index(body.mesh, where + ".mesh");
    finite_pose(body.pose, where + ".pose");
    if (!body.frame_poses.empty() && body.frame_poses.size() != frames)
      throw Bad{where + ".frame_poses", std::to_string(body.frame_poses.size()) + " poses for " + std::to_string(frames) + " frames"};
    for (std::size_t k = 0; k < body.frame_poses.size(); ++k) finite_pose(body.frame_poses[k], at(where + ".frame_poses", k));
    if (!body.frame_meshes.empty() && body.frame_meshes.size() != frames)
      throw Bad{where + ".frame_meshes", std::to_string(body.frame_meshes.size()) + " meshes for " + std::to_string(frames) + " frames"};
    for (std::size_t k = 0; k < body.frame_meshes.size(); ++k) mesh_index(body.frame_meshes[k], at(where + ".frame_meshes", k));
  }
  for (std::size_t c = 0; c < doc.clashes.size(); ++c) {
    const ViewClash& clash = doc.clashes[c];
    const std::string where = at("clashes", c);
    if (clash.verdict != "clash" && clash.verdict != "contact" && clash.verdict != "clearance" && clash.verdict != "undecided")
      throw Bad{where + ".verdict", "\"" + clash.verdict + "\" (expected clash, contact, clearance or undecided)"};
    for (std::uint32_t b : {clash.body_a, clash.body_b})
      if (b >= doc.bodies.size())
        throw Bad{where + ".bodies", "body " + std::to_string(b) + " out of range (" + std::to_string(doc.bodies.size()) + " bodies)"};
    finite_float(clash.point, where + ".point");
    if (clash.region_mesh >= 0) mesh_index(static_cast<std::uint64_t>(clash.region_mesh), where + ".region_mesh");
    else if (clash.region_mesh != -1) throw Bad{where + ".region_mesh", std::to_string(clash.region_mesh) + " (expected -1 or a mesh)"};
    for (std::size_t i = 0; i < clash.curves.size(); ++i)
      for (std::size_t p = 0; p < clash.curves[i].size(); ++p) finite_float(clash.curves[i][p], at(at(where + ".curves", i), p));
    if (clash.has_witness) finite_float(clash.witness_a, where + ".witness"), finite_float(clash.witness_b, where + ".witness");
    for (std::size_t k = 0; k < clash.frames.size(); ++k)
      if (clash.frames[k] >= frames)
        throw Bad{at(where + ".frames", k), "frame " + std::to_string(clash.frames[k]) + " out of range (" + std::to_string(frames) + " frames)"};
    const std::pair<const char*, double> values[] = {{"depth", clash.depth}, {"depth_bound", clash.depth_bound}, {"distance", clash.distance}};
    for (const auto& [name, v] : values)
      if (!std::isfinite(v)) throw Bad{where + "." + name, "not finite (a value not known is negative)"};
  }
}

}  // namespace

std::string check_for_export(const Document& doc) {
  if (!doc.error.empty()) return "the report could not be shown: " + doc.error;
  try {
    check(doc);
  } catch (const Bad& bad) {
    return "viewer document: " + bad.where + ": " + bad.why;
  }
  return {};
}

float srgb_to_linear(float c) {
  if (!(c > 0)) return 0;
  if (c >= 1) return 1;
  return c <= 0.04045f ? c / 12.92f : static_cast<float>(std::pow((c + 0.055) / 1.055, 2.4));
}

}  // namespace interfere::view::detail
