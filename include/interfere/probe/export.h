// Visual output of a sweep (issue #5, item 5): the probe (and holder) at the colliding poses and
// the workpiece triangles they hit, as OBJ (groups) or legacy VTK POLYDATA (cell data), for
// re-planning in a viewer.
#pragma once
#include <filesystem>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/probe/sweep.h"

namespace interfere::probe {

/// Closed triangulated cylinder (`sides` around, capped), every face outward (a closed, consistently
/// oriented solid for the scene engine: the cell's probe and holder, URDF <cylinder> links). Before
/// 2026-11-29 the sides faced inward, so the engine treated these bodies as open (containment
/// undecided).
TriMesh cylinder_mesh(const Cylinder& c, int sides = 24);

/// The box's 8 corners and its 12 boundary triangles (outward), exactly the solid that is tested.
TriMesh box_mesh(const OrientedBox& b);

/// One tagged mesh: hit triangles of the workpiece (tag kind 0) and the probe/holder (cylinder or
/// box) meshes at the colliding points (kind 1) and at the midpoint of each colliding segment
/// interval (kind 2); `point` is the path point (or segment start) index, -1 for workpiece triangles.
struct CollisionGeometry {
  TriMesh mesh;
  std::vector<int> kind;
  std::vector<long> point;
  std::size_t probe_poses = 0, hit_triangles = 0;
};
CollisionGeometry collision_geometry(const Workpiece& w, const ProbePath& path, const Robot* robot,
                                     const ProbeShape& probe, const SweepResult& result, int sides = 24);

/// Writes atomically: .obj (groups "hits", "probe_<i>", "segment_<i>") or .vtk (POLYDATA, cell data
/// "kind" and "point"). Other extensions are an error.
Status write_collision_geometry(const std::filesystem::path& file, const CollisionGeometry& g);

}  // namespace interfere::probe
