// Floor features: pockets, through slots, blind slots and steps (issue #29, item 1: "slots, pockets
// and steps as the paper's library defines them").
//
// He & Xu 2023 §2.2 give the library's through step (Fig. 4): two planes meeting at one concave arc.
// The other depression features of the library follow the same AAG reading (Joshi & Chang 1988; ISO
// 10303-224's closed pocket, slot and step): a planar floor, walls standing on it, and open sides
// where the floor meets the part's outside (a convex arc). Decided on the AAG:
//  - a floor: a plane; its outer-loop arcs are concave to walls, smooth to floor fillets, or convex
//    (an open side; so is a smooth arc to a convex round: a boss-sense cylinder or sphere, a torus
//    that is no floor fillet). Any other arc (a concave arc to an inclined face, a smooth arc to a face that is
//    no fillet) means the plane is no floor of these features. Arcs of the floor's inner loops
//    (islands standing on it, holes through it) do not take part;
//  - a wall stands on the floor: a plane perpendicular to it, or a cylinder whose axis is its normal
//    (corner rounds, the round end of a slot, convex blends of a profiled outline);
//  - a floor fillet joins the floor to a wall through smooth arcs: a concave cylinder whose axis lies
//    parallel to the floor one radius above it, a torus about the floor's normal whose tube centre lies
//    one minor radius above it, or a concave sphere (corner blends); its own arcs lead (smoothly or at a
//    concave arc) to walls, to further fillets, or (convex, or smooth to a convex round) to the outside;
//  - the type, from the walls joined into components by their arcs:
//    pocket       no open side; at least three walls closing a ring (each meets two others);
//    blind_slot   open; one component: two opposite planes facing each other (the sides) and an end
//                 closing them (one plane perpendicular to both, and/or rounds) - a slot closed at one end;
//    slot         open; two components, each one plane, opposite and facing each other (a through slot);
//    through_step open; one component of one plane, whose only wall, seen from it as a floor, is this
//                 floor (the paper's Fig. 4: two planes meeting at one concave arc).
//    Other floors (an L-shaped corner of two walls, a floor with one wall all round: a blind hole's)
//    are none of these.
// Fillets are never a floor or wall of their own, so floor fillets and corner rounds are not reported
// as features (and never as holes: hole_recognition.cpp requires walls closing the full circle).
// A floor belongs to one feature and is no other feature's face: candidates are accepted pockets first,
// then blind slots, slots and steps (a slot's side is also "a floor with one wall", a step, and loses to
// the slot); of one rank, larger floors first. Walls and fillets may be shared (the gaps above and below
// one cooling fin), but two features of one type never have the same walls (issue #29, item 2: found by
// rendering the floor truth set, tools/hole_truth/render_labels.py).
#include "pocket_recognition.h"

#include <algorithm>
#include <set>
#include <cmath>
#include <map>
#include <numeric>

namespace interfere::cad::detail {
namespace {

Vec3 unit(const Vec3& v) {
  const double l = norm(v);
  return l > 0 ? v / l : v;
}

// Angles: 1e-3 rad (fitted B-spline surfaces agree to ~1e-4, analytic ones far better).
double angle_tol(const AagNode&) { return 1e-3; }

struct Graph {
  const Aag& g;
  std::vector<std::vector<std::uint32_t>> arcs_of;
  std::uint32_t other(std::uint32_t ai, std::uint32_t f) const { return g.arcs[ai].a == f ? g.arcs[ai].b : g.arcs[ai].a; }
  bool inner_on(std::uint32_t ai, std::uint32_t f) const {
    const AagArc& a = g.arcs[ai];
    return a.a == f ? a.inner_loop_a : a.inner_loop_b;
  }
};

bool standing(const AagNode& w, const Vec3& up) {
  const double tol = angle_tol(w);
  if (w.type == SurfaceType::plane) return std::abs(dot(unit(w.normal), up)) <= tol;
  if (w.type == SurfaceType::cylinder) return norm(cross(unit(w.axis), up)) <= tol;
  return false;
}

bool fillet(const AagNode& f, const AagNode& floor, const Vec3& up) {
  const double tol = angle_tol(f);
  const double scale = std::max(1.0, f.radius);
  if (f.type == SurfaceType::cylinder) {
    if (!f.hole || std::abs(dot(unit(f.axis), up)) > tol) return false;
    const double h = dot(f.axis_point - floor.axis_point, up);
    return std::abs(h - f.radius) <= (f.from_bspline ? 1e-3 : 1e-5) * scale + 1e-6;
  }
  if (f.type == SurfaceType::torus) {
    // A corner blend: its tube's centre circle one minor radius above the floor (a convex round of the
    // floor's outline lies one minor radius below it).
    const double h = dot(f.axis_point - floor.axis_point, up);
    return norm(cross(unit(f.axis), up)) <= tol &&
           std::abs(h - f.minor_radius) <= (f.from_bspline ? 1e-3 : 1e-5) * std::max(1.0, f.minor_radius) + 1e-6;
  }
  return f.type == SurfaceType::sphere && f.hole;
}

// A convex round (the blend of an outer edge): where the floor, or a floor fillet, meets it smoothly the
// floor meets the outside.
bool convex_round(const AagNode& f, const AagNode& floor, const Vec3& up) {
  if (f.type == SurfaceType::cylinder || f.type == SurfaceType::sphere) return !f.hole;
  return f.type == SurfaceType::torus && !fillet(f, floor, up);
}

struct Candidate {
  FloorFeature f;
  int rank = 0;  // lower first
};

// The floor's walls, fillets and open sides; false when `fl` is no floor.
bool floor_of(const Graph& G, std::uint32_t fl, const std::vector<char>& claimed, std::vector<std::uint32_t>& walls,
              std::vector<std::uint32_t>& fillets, bool& open) {
  const Aag& g = G.g;
  const AagNode& floor = g.nodes[fl];
  const Vec3 up = unit(floor.normal);
  open = false;
  std::vector<std::uint32_t> todo;
  for (std::uint32_t ai : G.arcs_of[fl]) {
    if (G.inner_on(ai, fl)) continue;
    const AagArc& arc = g.arcs[ai];
    const std::uint32_t nb = G.other(ai, fl);
    if (arc.convexity == Convexity::convex) {
      open = true;
      continue;
    }
    if (claimed[nb]) return false;
    const AagNode& w = g.nodes[nb];
    if (arc.convexity == Convexity::concave) {
      if (!standing(w, up)) return false;
      walls.push_back(nb);
    } else if (fillet(w, floor, up)) {
      if (std::find(fillets.begin(), fillets.end(), nb) == fillets.end()) fillets.push_back(nb), todo.push_back(nb);
    } else if (convex_round(w, floor, up)) {
      open = true;
    } else {
      return false;
    }
  }
  // The fillets' other neighbours.
  while (!todo.empty()) {
    const std::uint32_t f = todo.back();
    todo.pop_back();
    for (std::uint32_t ai : G.arcs_of[f]) {
      const AagArc& arc = g.arcs[ai];
      const std::uint32_t nb = G.other(ai, f);
      if (nb == fl || std::find(fillets.begin(), fillets.end(), nb) != fillets.end()) continue;
      if (arc.convexity == Convexity::convex) {
        open = true;
        continue;
      }
      if (claimed[nb]) return false;
      const AagNode& w = g.nodes[nb];
      if (standing(w, up)) walls.push_back(nb);
      else if (fillet(w, floor, up)) fillets.push_back(nb), todo.push_back(nb);  // smooth, or a mitred corner
      else if (arc.convexity == Convexity::smooth && convex_round(w, floor, up)) open = true;
      else return false;
    }
  }
  std::sort(walls.begin(), walls.end());
  walls.erase(std::unique(walls.begin(), walls.end()), walls.end());
  std::sort(fillets.begin(), fillets.end());
  return !walls.empty();
}

bool facing(const AagNode& a, const AagNode& b) {
  // Opposite planes, each normal (into the void) pointing at the other.
  const Vec3 na = unit(a.normal), nb = unit(b.normal);
  if (dot(na, nb) > -1 + angle_tol(a) + angle_tol(b)) return false;
  return dot(b.axis_point - a.axis_point, na) > 0;
}

}  // namespace

const std::set<std::string>& floor_feature_types() {
  static const std::set<std::string> t{"pocket", "slot", "blind_slot", "through_step"};
  return t;
}

std::vector<FloorFeature> recognize_floor_features(const Aag& g, const std::vector<char>& claimed,
                                                   const std::set<std::string>& types) {
  const std::size_t n = g.nodes.size();
  Graph G{g, std::vector<std::vector<std::uint32_t>>(n)};
  for (std::uint32_t i = 0; i < g.arcs.size(); ++i) G.arcs_of[g.arcs[i].a].push_back(i), G.arcs_of[g.arcs[i].b].push_back(i);
  auto adjacent = [&](std::uint32_t a, std::uint32_t b) {
    return std::any_of(G.arcs_of[a].begin(), G.arcs_of[a].end(), [&](std::uint32_t ai) { return G.other(ai, a) == b; });
  };
  std::vector<Candidate> cand;
  for (std::uint32_t fl = 0; fl < n; ++fl) {
    if (claimed[fl] || g.nodes[fl].type != SurfaceType::plane) continue;
    std::vector<std::uint32_t> walls, fillets;
    bool open = false;
    if (!floor_of(G, fl, claimed, walls, fillets, open)) continue;
    Candidate c;
    c.f.floor = fl, c.f.walls = walls, c.f.fillets = fillets;
    if (!open) {
      if (walls.size() < 3) continue;
      bool ring = true;
      for (std::uint32_t w : walls) {
        int others = 0;
        for (std::uint32_t v : walls) others += v != w && adjacent(w, v);
        ring = ring && others >= 2;
      }
      if (!ring) continue;
      c.f.type = "pocket", c.rank = 0;
    } else {
      // Components of the walls.
      std::vector<std::uint32_t> comp(walls.size());
      std::iota(comp.begin(), comp.end(), 0u);
      auto find = [&](std::uint32_t x) {
        while (comp[x] != x) x = comp[x] = comp[comp[x]];
        return x;
      };
      for (std::uint32_t i = 0; i < walls.size(); ++i)
        for (std::uint32_t j = i + 1; j < walls.size(); ++j)
          if (adjacent(walls[i], walls[j])) comp[std::max(find(i), find(j))] = std::min(find(i), find(j));
      std::map<std::uint32_t, std::vector<std::uint32_t>> comps;
      for (std::uint32_t i = 0; i < walls.size(); ++i) comps[find(i)].push_back(walls[i]);
      const auto is_plane = [&](std::uint32_t f) { return g.nodes[f].type == SurfaceType::plane; };
      if (comps.size() == 1 && walls.size() == 1 && is_plane(walls[0])) {
        // The paper's step: two planes whose only concave arc is the one between them, so the wall,
        // taken as a floor, has this floor as its one wall (a face standing on a base plate among
        // others is no step of the base's).
        std::vector<std::uint32_t> w2, f2;
        bool open2 = false;
        if (!floor_of(G, walls[0], claimed, w2, f2, open2) || !open2 || w2 != std::vector<std::uint32_t>{fl}) continue;
        c.f.type = "through_step", c.rank = 3;
      } else if (comps.size() == 2 && walls.size() == 2 && is_plane(walls[0]) && is_plane(walls[1]) &&
                 facing(g.nodes[walls[0]], g.nodes[walls[1]])) {
        c.f.type = "slot", c.rank = 2, c.f.sides = walls;
      } else if (comps.size() == 1 && walls.size() >= 3) {
        // Two facing sides, the rest an end: planes perpendicular to the sides, all the same way, or rounds.
        std::vector<std::uint32_t> sides;
        for (std::uint32_t i = 0; i < walls.size() && sides.empty(); ++i)
          for (std::uint32_t j = i + 1; j < walls.size(); ++j)
            if (is_plane(walls[i]) && is_plane(walls[j]) && facing(g.nodes[walls[i]], g.nodes[walls[j]])) {
              sides = {walls[i], walls[j]};
              break;
            }
        if (sides.empty()) continue;
        const Vec3 across = unit(g.nodes[sides[0]].normal);
        std::vector<std::uint32_t> ends;
        bool ok = true;
        Vec3 end_normal;
        for (std::uint32_t w : walls) {
          if (w == sides[0] || w == sides[1]) continue;
          const AagNode& e = g.nodes[w];
          if (e.type == SurfaceType::plane) {
            const Vec3 en = unit(e.normal);
            ok = ok && std::abs(dot(en, across)) <= angle_tol(e) && (norm(end_normal) == 0 || dot(en, end_normal) >= 1 - angle_tol(e));
            end_normal = en;
          }
          ends.push_back(w);
        }
        if (!ok || ends.empty()) continue;
        c.f.type = "blind_slot", c.rank = 1, c.f.sides = sides, c.f.ends = ends;
      } else {
        continue;
      }
    }
    if (!types.count(c.f.type)) continue;
    cand.push_back(std::move(c));
  }
  // Of two readings of the same faces (a step's floor and wall, a blind slot's floor and end, whose
  // corner rounds are then its "floor fillets"), the larger floor is taken.
  std::stable_sort(cand.begin(), cand.end(), [&](const Candidate& a, const Candidate& b) {
    return a.rank != b.rank ? a.rank < b.rank : g.nodes[a.f.floor].area > g.nodes[b.f.floor].area;
  });
  // Features that only share walls or fillets (the gaps above and below one cooling fin, two slots either
  // side of one rib) are two features; a candidate is another reading of a taken one when its floor is a
  // face of the taken one, the taken one's floor is a face of it, or both are of one type between the same
  // walls (a rectangular window read as a slot from either end face).
  std::vector<char> taken(claimed.size(), 0), floor_taken(claimed.size(), 0);
  std::set<std::pair<std::string, std::vector<std::uint32_t>>> wall_sets;
  std::vector<FloorFeature> out;
  for (Candidate& c : cand) {
    std::vector<std::uint32_t> owned = c.f.walls;
    owned.push_back(c.f.floor);
    owned.insert(owned.end(), c.f.fillets.begin(), c.f.fillets.end());
    std::vector<std::uint32_t> walls = c.f.walls;
    std::sort(walls.begin(), walls.end());
    if (taken[c.f.floor] || wall_sets.count({c.f.type, walls}) ||
        std::any_of(owned.begin(), owned.end(), [&](std::uint32_t f) { return claimed[f] != 0 || floor_taken[f] != 0; }))
      continue;
    for (std::uint32_t f : owned) taken[f] = 1;
    floor_taken[c.f.floor] = 1;
    wall_sets.insert({c.f.type, std::move(walls)});
    out.push_back(std::move(c.f));
  }
  std::sort(out.begin(), out.end(), [](const FloorFeature& a, const FloorFeature& b) {
    return a.type != b.type ? a.type < b.type : a.floor < b.floor;
  });
  return out;
}

}  // namespace interfere::cad::detail
