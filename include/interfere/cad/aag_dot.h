// The attributed adjacency graph as Graphviz DOT (issue #6, item 2; He & Xu 2023 §2.1, after Joshi
// & Chang 1988): a picture of what feature recognition sees, for checking it on one's own parts
// (`interfere features PART.step --dot FILE`; render with `dot -Tsvg FILE`).
//
// One cluster per part. Nodes: "F<face>" with the surface type and, for rotational faces, the radius
// (a bore marked "hole"); filled per recognised feature (the feature's type in the legend of its
// cluster), with a bold red border on the step's assembly-feature faces. Arcs: convex solid, concave
// dashed, smooth dotted; labelled with the curve type; bold where the edge lies on an inner loop of
// either face (where minimal subgraphs are split first, §2.2). Several edges between two faces are
// several arcs.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "interfere/cad/features.h"
#include "interfere/cad/model.h"

namespace interfere::cad {

struct DotPart {
  std::string name;
  const Aag* aag = nullptr;
  std::vector<Feature> features;               ///< recognised on it (may be empty)
  std::vector<std::uint32_t> assembly_faces;   ///< the step's assembly-feature faces (may be empty)
};

/// The graph of every part, one DOT document ("graph aag { ... }"); names and labels quoted.
std::string aag_dot(const std::vector<DotPart>& parts);

}  // namespace interfere::cad
