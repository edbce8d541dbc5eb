// A local frame for the simplifier (issue #6, item 5; "bad input ... never a silently wrong
// answer"): QEM costs grow as the fourth power of the size (area-weighted plane quadrics) and are
// ranked as floats, which overflow above about 1e9 and underflow below 1e-9 (every cost inf or 0:
// collapses in arbitrary order, 15 times the error); a part far from the origin loses its
// quadrics' precision to cancellation (offset 1e6 x size: twice the error, 1e8: garbage). Such
// meshes are simplified in a local frame: translated by a coarse centre c and scaled by a power of
// two, p' = (p - c) * 2^k, used only where both steps are exact for every coordinate (checked), so
// the vertices a simplification keeps map back to their input positions bit for bit.
#pragma once
#include <optional>

#include "interfere/mesh/tri_mesh.h"

namespace interfere::qem {

struct LocalFrame {
  Vec3 centre;  ///< c, zero when not translated
  int exponent = 0;  ///< k
  bool translated = false;
  Vec3 to_local(const Vec3& p) const;
  Vec3 to_world(const Vec3& p) const;  ///< (p * 2^-k) + c, rounded
  double length_to_world(double d) const;  ///< d * 2^-k, exact
};

/// The frame for `mesh` (finite positions, bounds `box`), or nullopt where the mesh is already in a comfortable
/// frame (size within [2^-20, 2^20], centre within 2^8 sizes of the origin) or the exact frame
/// cannot be found (then it is simplified as it is).
std::optional<LocalFrame> local_frame(const TriMesh& mesh, const Aabb& box);

/// mesh with every position in the frame (topology unchanged).
TriMesh to_local(const TriMesh& mesh, const LocalFrame& frame);

}  // namespace interfere::qem
