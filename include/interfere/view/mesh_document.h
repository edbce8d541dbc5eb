// Meshes with per-triangle labels as a viewer document (issue #25, item 1: "for features/simplify:
// faces coloured by feature type, assembly-feature faces highlighted, the simplified mesh beside or
// over the original"). Each layer is one body; its labels index the legend.
#pragma once
#include <string>
#include <vector>

#include "interfere/view/document.h"

namespace interfere::view {

inline constexpr std::uint32_t kNoLabel = 0xffffffffu;

struct MeshLayer {
  std::string id, name, path, role;
  TriMesh mesh;   ///< local coordinates
  Transform pose;  ///< local -> world
  /// Per triangle: an index into the legend, or kNoLabel (drawn in the body colour); empty: none.
  std::vector<std::uint32_t> labels;
  bool visible = true;
  Rgb color{0.62f, 0.66f, 0.72f};
};

/// One mesh and one body per layer, labels as face colours (unlabelled triangles take the
/// layer's colour through an extra legend entry "other").
Document meshes_document(std::string title, std::vector<MeshLayer> layers, std::vector<LegendEntry> legend);

/// A fixed, distinguishable colour for label i (the same everywhere: the viewer's legend, glTF).
Rgb label_color(std::size_t i);

}  // namespace interfere::view
