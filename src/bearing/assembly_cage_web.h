// The cage web rows of a bearing assembly (assembly_pairs.cpp, roller-cage; docs/bearing.md, "Cage
// webs in closed form"): s(web, roller), the minimum over the web's triangles of the roller's signed
// distance, and the two-sided S of a roller and a convex web (ring_two_sided.h). Moved out of
// assembly_pairs.cpp unchanged (issue #27).
#pragma once
#include <limits>

#include "interfere/bearing/analytic.h"
#include "interfere/bearing/assembly.h"
#include "interfere/core/transform.h"

namespace interfere::bearing::detail {

/// s(web, roller): the minimum over the web's triangles of the roller's signed distance (the web
/// is convex and thin; when that minimum is > 0 the web could only lie inside the roller: its centre
/// is tested). point_a on the roller's boundary, point_b on the web.
struct WebValue {
  double distance = std::numeric_limits<double>::infinity();
  Vec3 point_a, point_b;
};

/// web_distance: s(web, roller) for the web mesh posed by cage_pose; `faces`, when given, the web's
/// six face planes and corners (the closed forms separated_web and deepest_web_point are tried first).
WebValue web_distance(const Cylinder& roller, const TriMesh& web, const Transform& cage_pose,
                      const CageWeb* faces = nullptr);

/// Two-sided S of a roller and a cage web (ring_two_sided.h): `rev` = web_distance's value (the
/// web's deepest point in the roller, <= 0 here), fwd = deepest_in_web (the roller's deepest point
/// in the convex web). fwd <= min over the faces j of D_j = d_j - min over the roller of n_j.x (the
/// roller's reach past face j): when -rev already reaches that bound, S = rev with no search.
WebValue two_sided_web(const Cylinder& roller, const CageWeb& web, const Transform& pose, const WebValue& rev);

}  // namespace interfere::bearing::detail
