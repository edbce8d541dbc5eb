// Internal interface between the surface extraction sources (src/fem/surface*.cpp).
#pragma once
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "interfere/fem/surface.h"
#include "interfere/mesh/tri_mesh.h"

namespace interfere::fem_detail {

inline constexpr std::uint32_t kNoPart = std::numeric_limits<std::uint32_t>::max();

struct PartAssignment {
  std::vector<std::uint32_t> part;  ///< per element; kNoPart for points and lines
  std::vector<std::string> names;
  std::vector<std::int32_t> groups;
};

/// Triangles of one part before their vertices are renumbered: node indices, element, local face,
/// and flags (kFlagShell: a shell's triangle, kept as it is).
inline constexpr std::uint8_t kFlagShell = 1;
struct PartTriangles {
  std::vector<Tri> tris;
  std::vector<std::uint32_t> elem;
  std::vector<std::uint8_t> face, flag;
  void reserve(std::size_t n) {
    tris.reserve(n), elem.reserve(n), face.reserve(n), flag.reserve(n);
  }
  /// Appends triangle t with the element, face and flags of `from`'s triangle i.
  void push(const PartTriangles& from, std::size_t i, const Tri& t) {
    tris.push_back(t), elem.push_back(from.elem[i]), face.push_back(from.face[i]), flag.push_back(from.flag[i]);
  }
};

/// Splits every linear face's triangle that has an edge of a quadratic element of the part (in
/// `elements`, with a mid-side node) at that node, so that mixed linear/quadratic bodies are
/// conforming; returns the count of faces split. Only called with subdivided quadratic faces.
std::size_t split_at_mid_nodes(const FemMesh& mesh, const std::vector<std::uint32_t>& elements, PartTriangles& pt);

struct OrientStats {
  std::size_t components = 0;               ///< of volume-face triangles connected by manifold edges
  std::size_t open_components = 0;          ///< with an edge used by one triangle
  std::size_t degenerate_components = 0;    ///< outward side undecidable: volume sum ~0 (rounding)
  std::size_t nonorientable_components = 0;  ///< propagation met a contradiction
  std::size_t reoriented = 0;               ///< triangles turned against their face's vote
  double volume = 0;  ///< enclosed volume of the closed components (cavities count negative)
};
/// Orients the volume-face triangles consistently by propagation across manifold edges, then each
/// component outward by the sign of the summed volumes of the cones from its triangles to their
/// elements' centroids (a cavity's boundary faces into the cavity).
OrientStats orient_part(const FemMesh& mesh, PartTriangles& pt, bool parallel);

/// `split` automatic resolves to by_group when an element with a surface has a group, else
/// connectivity.
PartAssignment assign_parts(const FemMesh& mesh, PartSplit split);

}  // namespace interfere::fem_detail
