// Closed pockets (issue #29, item 3: "slots, pockets and steps as the paper's library defines them").
// He & Xu 2023 §2.2 show the library's through step as two planes meeting at one concave arc (Fig. 4);
// a pocket is the closed form of the same depression feature (ISO 10303-224's closed pocket): a planar
// floor whose boundary is walls all round. Decided on the AAG:
//  - the floor is a plane every arc of which is concave (material rises all round it: no edge where
//    it meets the part's outside, as a through slot's or a step's floor does at its open ends);
//  - its neighbours are walls standing on it: planes perpendicular to it, or cylinders whose axis is
//    its normal (corner rounds, and the convex blends of a profiled outline, as NIST CTC-01's
//    pockets have); at least three (one wall all round is a blind hole, recognised as such before,
//    two are a slot);
//  - the walls close a ring: each meets at least two other walls (a concave corner, a smooth round,
//    or a convex corner where the outline turns inwards).
// Islands (bosses standing on the floor) are further walls of the floor's inner loops and are allowed.
#include "pocket_recognition.h"

#include <algorithm>
#include <cmath>

namespace interfere::cad::detail {

std::vector<PocketFeature> recognize_pockets(const Aag& g, const std::vector<char>& claimed) {
  const std::size_t n = g.nodes.size();
  std::vector<std::vector<std::uint32_t>> arcs_of(n);
  for (std::uint32_t i = 0; i < g.arcs.size(); ++i) arcs_of[g.arcs[i].a].push_back(i), arcs_of[g.arcs[i].b].push_back(i);
  const auto unit = [](const Vec3& v) {
    const double l = norm(v);
    return l > 0 ? v / l : v;
  };
  std::vector<PocketFeature> out;
  for (std::uint32_t f = 0; f < n; ++f) {
    const AagNode& floor = g.nodes[f];
    if (claimed[f] || floor.type != SurfaceType::plane || arcs_of[f].empty()) continue;
    const Vec3 up = unit(floor.normal);
    std::vector<std::uint32_t> walls;
    bool ok = true;
    for (std::uint32_t ai : arcs_of[f]) {
      const AagArc& arc = g.arcs[ai];
      const std::uint32_t w = arc.a == f ? arc.b : arc.a;
      const AagNode& wall = g.nodes[w];
      const bool standing =
          (wall.type == SurfaceType::plane && std::abs(dot(unit(wall.normal), up)) <= 1e-3) ||
          (wall.type == SurfaceType::cylinder && norm(cross(unit(wall.axis), up)) <= 1e-3);
      if (arc.convexity != Convexity::concave || claimed[w] || !standing) {
        ok = false;
        break;
      }
      walls.push_back(w);
    }
    if (!ok) continue;
    std::sort(walls.begin(), walls.end());
    walls.erase(std::unique(walls.begin(), walls.end()), walls.end());
    if (walls.size() < 3) continue;
    for (std::uint32_t w : walls) {
      std::vector<std::uint32_t> others;
      for (std::uint32_t ai : arcs_of[w]) {
        const AagArc& arc = g.arcs[ai];
        const std::uint32_t o = arc.a == w ? arc.b : arc.a;
        if (o != w && std::binary_search(walls.begin(), walls.end(), o) &&
            std::find(others.begin(), others.end(), o) == others.end())
          others.push_back(o);
      }
      ok = ok && others.size() >= 2;
    }
    if (ok) out.push_back({f, std::move(walls)});
  }
  return out;
}

}  // namespace interfere::cad::detail
