#include "interfere/query/model.h"

#include <tbb/parallel_invoke.h>

#include <stdexcept>
#include <string>
#include <utility>

namespace interfere {

Model make_model(TriMesh mesh, const BvhBuildOptions& options, bool with_stats) {
  Model m;
  m.mesh = std::move(mesh);
  m.bvh = build_bvh(m.mesh, options);
  if (with_stats) m.stats = mesh_stats(m.mesh);
  return m;
}

std::pair<Model, Model> make_models(TriMesh a, TriMesh b, const BvhBuildOptions& options,
                                    bool with_stats) {
  std::pair<Model, Model> m;
  tbb::parallel_invoke([&] { m.first = make_model(std::move(a), options, with_stats); },
                       [&] { m.second = make_model(std::move(b), options, with_stats); });
  return m;
}

void refit(Model& model, std::vector<Vec3> new_positions) {
  if (new_positions.size() != model.mesh.positions.size()) {
    throw std::invalid_argument("refit: " + std::to_string(new_positions.size()) +
                                " positions given for a mesh of " +
                                std::to_string(model.mesh.positions.size()) + " vertices");
  }
  model.mesh.positions = std::move(new_positions);
  refit_bvh(model.bvh, model.mesh);
}

}  // namespace interfere
