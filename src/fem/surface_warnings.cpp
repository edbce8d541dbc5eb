// The surface's and a body's warnings for the user (include/interfere/fem/bodies.h), shared by the
// CLI's FEM parts (apps/cli/fem_parts.cpp) and fem_scene. Own file: the CLI links it without the
// scene source.
#include "interfere/fem/bodies.h"

namespace interfere {

std::vector<std::string> surface_warnings(const SurfaceResult& s) {
  std::vector<std::string> w;
  if (s.degenerate_faces > 0)
    w.push_back(std::to_string(s.degenerate_faces) +
                " boundary faces have a triangle of zero area (degenerate)");
  if (s.nonmanifold_faces > 0)
    w.push_back(std::to_string(s.nonmanifold_faces) +
                " faces shared by more than two elements (left out of the surface)");
  if (s.inverted_faces > 0)
    w.push_back(
        std::to_string(s.inverted_faces) +
        " boundary faces of inverted (negative-Jacobian) elements (oriented outward by geometry)");
  return w;
}

std::vector<std::string> surface_part_warnings(const SurfacePart& sp) {
  std::vector<std::string> w;
  if (sp.open_components > 0)
    w.push_back(
        std::to_string(sp.open_components) + " of " + std::to_string(sp.components) +
        " surface components are open (edges used by one boundary face): not a closed solid");
  if (sp.degenerate_components > 0)
    w.push_back(
        std::to_string(sp.degenerate_components) +
        " closed surface components enclose no volume (degenerate; oriented by the faces' votes)");
  if (sp.nonorientable_components > 0)
    w.push_back(
        std::to_string(sp.nonorientable_components) +
        " surface components cannot be oriented consistently (non-orientable or mis-assembled)");
  return w;
}

}  // namespace interfere
