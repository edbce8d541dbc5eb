// A Model pairs a mesh (in world coordinates, pose already applied) with its BVH and its validation
// statistics. Immutable after build; refit() produces the moved state explicitly.
#pragma once
#include "interfere/bvh/bvh.h"
#include "interfere/mesh/tri_mesh.h"
#include "interfere/mesh/validate.h"

#include <utility>

namespace interfere {

struct Model {
  TriMesh mesh;
  Bvh bvh;
  MeshStats stats;
};

/// Builds the BVH and the statistics (the statistics pass is skipped when `with_stats` is false).
Model make_model(TriMesh mesh, const BvhBuildOptions& options = {}, bool with_stats = true);

/// Builds the models of two parts concurrently (one oneTBB task each; their inner parallel loops
/// share the worker threads). The trees are identical to two make_model calls: only the schedule
/// differs. On few cores this beats two consecutive builds, which each scale sub-linearly.
std::pair<Model, Model> make_models(TriMesh a, TriMesh b, const BvhBuildOptions& options = {},
                                    bool with_stats = true);

/// Moves the vertices (same topology) and refits the tree in place.
void refit(Model& model, std::vector<Vec3> new_positions);

}  // namespace interfere
