// Hole recognition on the AAG (issue #29, item 1). The pattern matching of He & Xu (SJTU 2023) §2.2
// takes "a concave cylinder between two planes" for a through hole: on real parts (NIST CTC/FTC,
// gmsh) that reports pocket corner rounds and slot ends as holes and misses holes whose floor circle
// is split, or which open onto inclined or curved faces. Here a hole is decided from the wall's
// geometry and its ends:
//  1. wall surfaces: hole-sense cylinder and cone faces grouped by surface (coaxial, same radius or
//     same cone) where their axial extents touch, whatever faces and edges the modeller split them
//     into; a group is a wall when the union of its faces' angular ranges (AagNode::arc_start,
//     arc_span) closes the circle, so fillets and corner rounds (quarter and half arcs) never are;
//  2. a hole: coaxial walls joined by an arc or whose axial extents touch (a counterbore's seat plane
//     has no height; an undercut between them is no wall), ordered along the axis;
//  3. an end is closed (blind) by a plane perpendicular to the axis at the end's height facing into
//     the hole (one or several faces: split floors; together at least half the end's disk), by a coaxial sphere or a floor fillet (a torus
//     whose tube centre lies inside the wall), or by a cone ending at its apex (a drill point);
//     otherwise it is open, whatever face the wall meets there (planar, inclined, curved, another
//     hole): arcs are taken per neighbouring face and by the end their middle lies nearest to;
//  4. type, from an open end inwards: counterdrilled (a larger cylinder, then a cone narrowing to
//     the next cylinder: a drill point's seat), counterbored (a cylinder larger than the next cylinder),
//     countersunk (a cone narrowing inwards: countersinks and entry chamfers), stepped (other
//     diameter changes), blind (one closed end), through. Holes closed at both ends are not holes.
#include "hole_recognition.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace interfere::cad::detail {
namespace {

constexpr double kTwoPi = 2 * M_PI;

Vec3 unit(const Vec3& v) {
  const double l = norm(v);
  return l > 0 ? v / l : v;
}
std::pair<Vec3, Vec3> across(const Vec3& a) {
  const Vec3 e1 = unit(std::abs(a.x) < 0.9 ? cross(a, {1, 0, 0}) : cross(a, {0, 1, 0}));
  return {e1, cross(a, e1)};
}

struct UnionFind {
  std::vector<std::uint32_t> p;
  explicit UnionFind(std::size_t n) : p(n) { std::iota(p.begin(), p.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (p[x] != x) x = p[x] = p[p[x]];
    return x;
  }
  void join(std::uint32_t a, std::uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) p[std::max(a, b)] = std::min(a, b);
  }
};

// Tolerances: analytic surfaces from files agree to ~1e-9; fitted B-spline ones to ~1e-4.
double angle_tol(const AagNode& a, const AagNode& b) { return a.from_bspline || b.from_bspline ? 1e-3 : 1e-5; }
double length_tol(const AagNode& a, const AagNode& b) {
  const double rel = a.from_bspline || b.from_bspline ? 1e-3 : 1e-5;
  return rel * std::max({1.0, a.radius, b.radius});
}

bool parallel(const Vec3& a, const Vec3& b, double tol) { return norm(cross(a, b)) <= tol; }
double line_distance(const Vec3& p, const Vec3& a, const Vec3& q) {
  const Vec3 d = q - p;
  return norm(d - a * dot(d, a));
}
// Height of node's axial position h (its own frame) in the frame (P, A).
double height_in(const AagNode& n, double h, const Vec3& P, const Vec3& A) { return dot(n.axis_point + n.axis * h - P, A); }
// Radius of a cylinder/cone node at the point of its axis at height H of the frame (P, A).
double radius_at(const AagNode& n, const Vec3& P, const Vec3& A, double H) {
  if (n.type == SurfaceType::cylinder) return n.radius;
  const double h = dot(P + A * H - n.axis_point, n.axis);
  return std::abs(n.radius + h * std::tan(n.half_angle));
}

bool same_surface(const AagNode& a, const AagNode& b) {
  if (a.type != b.type) return false;
  const double lt = length_tol(a, b);
  if (!parallel(a.axis, b.axis, angle_tol(a, b)) || line_distance(a.axis_point, a.axis, b.axis_point) > lt) return false;
  if (a.type == SurfaceType::cylinder) {
    if (std::abs(a.radius - b.radius) > lt) return false;
  } else {  // cones: the same apex and opening
    const double ta = std::tan(a.half_angle), tb = std::tan(b.half_angle);
    if (std::abs(std::abs(ta) - std::abs(tb)) > angle_tol(a, b) * (1 + ta * ta)) return false;
    const Vec3 apex_a = a.axis_point - a.axis * (a.radius / ta), apex_b = b.axis_point - b.axis * (b.radius / tb);
    if (norm(apex_a - apex_b) > lt) return false;
    if (dot(a.axis * (ta > 0 ? 1.0 : -1.0), b.axis * (tb > 0 ? 1.0 : -1.0)) < 0) return false;
  }
  // Axial extents touch.
  const double b0 = height_in(b, b.axial_min, a.axis_point, a.axis), b1 = height_in(b, b.axial_max, a.axis_point, a.axis);
  return std::min(b0, b1) <= a.axial_max + lt && std::max(b0, b1) >= a.axial_min - lt;
}

// Does the union of the members' angular ranges close the circle? (About A; a range about -A runs
// backwards.)
bool closes_circle(const Aag& g, const std::vector<std::uint32_t>& members, const Vec3& A) {
  const auto [e1, e2] = across(A);
  std::vector<std::pair<double, double>> iv;
  for (std::uint32_t m : members) {
    const AagNode& n = g.nodes[m];
    if (n.arc_span >= kTwoPi - 1e-9) return true;
    if (!(n.arc_span > 0)) continue;
    double s = std::atan2(dot(n.arc_start, e2), dot(n.arc_start, e1));
    if (dot(n.axis, A) < 0) s -= n.arc_span;
    s = std::fmod(s, kTwoPi);
    if (s < 0) s += kTwoPi;
    const double e = s + n.arc_span;
    if (e <= kTwoPi) iv.push_back({s, e});
    else iv.push_back({s, kTwoPi}), iv.push_back({0, e - kTwoPi});
  }
  std::sort(iv.begin(), iv.end());
  constexpr double gap_tol = 0.02;  // radians: boundary sampling of fitted faces
  double reach = 0;
  for (const auto& [s, e] : iv) {
    if (s > reach + gap_tol) return false;
    reach = std::max(reach, e);
  }
  return reach >= kTwoPi - gap_tol;
}

struct Element {
  std::vector<std::uint32_t> faces;
  bool cone = false;
  double lo = 0, hi = 0, r_lo = 0, r_hi = 0;  // in the hole's frame
};

}  // namespace

const std::set<std::string>& hole_types() {
  static const std::set<std::string> t{"through_hole",     "blind_hole",   "counterbored_hole", "counterdrilled_hole",
                                       "countersunk_hole", "stepped_hole"};
  return t;
}

std::vector<HoleFeature> recognize_holes(const Aag& g, const std::set<std::string>& types) {
  const std::size_t n = g.nodes.size();
  std::vector<std::vector<std::uint32_t>> adj(n);
  std::vector<std::vector<std::uint32_t>> arcs_of(n);
  for (std::uint32_t i = 0; i < g.arcs.size(); ++i) {
    const AagArc& a = g.arcs[i];
    adj[a.a].push_back(a.b), adj[a.b].push_back(a.a);
    arcs_of[a.a].push_back(i), arcs_of[a.b].push_back(i);
  }
  // 1. Wall surfaces.
  std::vector<std::uint32_t> cand;
  for (std::uint32_t i = 0; i < n; ++i) {
    const AagNode& a = g.nodes[i];
    if ((a.type == SurfaceType::cylinder || a.type == SurfaceType::cone) && a.hole && a.arc_span > 0) cand.push_back(i);
  }
  UnionFind surf(n);
  for (std::size_t i = 0; i < cand.size(); ++i)
    for (std::size_t j = i + 1; j < cand.size(); ++j)
      if (surf.find(cand[i]) != surf.find(cand[j]) && same_surface(g.nodes[cand[i]], g.nodes[cand[j]])) surf.join(cand[i], cand[j]);
  std::map<std::uint32_t, std::vector<std::uint32_t>> groups;
  for (std::uint32_t c : cand) groups[surf.find(c)].push_back(c);
  std::vector<std::vector<std::uint32_t>> walls;
  std::vector<int> wall_of(n, -1);
  for (auto& [root, members] : groups)
    if (closes_circle(g, members, g.nodes[root].axis)) {
      for (std::uint32_t m : members) wall_of[m] = int(walls.size());
      walls.push_back(members);
    }
  // 2. Holes: coaxial walls joined by an arc or whose axial extents touch (a seat plane has no height).
  UnionFind chain(walls.size());
  auto coaxial = [&](std::size_t w, std::size_t v) {
    const AagNode &a = g.nodes[walls[w][0]], &b = g.nodes[walls[v][0]];
    return parallel(a.axis, b.axis, angle_tol(a, b)) && line_distance(a.axis_point, a.axis, b.axis_point) <= length_tol(a, b);
  };
  // Coaxial walls whose axial extents touch are one hole too (joined through faces that are no walls,
  // e.g. an undercut between a bore and a cone).
  std::vector<std::pair<double, double>> extent(walls.size());
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const AagNode& r = g.nodes[walls[w][0]];
    double lo = 1e300, hi = -1e300;
    for (std::uint32_t f : walls[w]) {
      const AagNode& nd = g.nodes[f];
      for (double h : {nd.axial_min, nd.axial_max}) lo = std::min(lo, height_in(nd, h, r.axis_point, r.axis)), hi = std::max(hi, height_in(nd, h, r.axis_point, r.axis));
    }
    extent[w] = {lo, hi};
  }
  for (std::size_t w = 0; w < walls.size(); ++w)
    for (std::size_t v = w + 1; v < walls.size(); ++v) {
      if (!coaxial(w, v)) continue;
      const AagNode &a = g.nodes[walls[w][0]], &b = g.nodes[walls[v][0]];
      // v's extent in w's frame.
      const double s = dot(b.axis, a.axis) > 0 ? 1.0 : -1.0, off = dot(b.axis_point - a.axis_point, a.axis);
      const double v0 = off + s * extent[v].first, v1 = off + s * extent[v].second;
      const double tol = 1e-4 * std::max({1.0, a.radius, b.radius});
      if (std::min(v0, v1) <= extent[w].second + tol && std::max(v0, v1) >= extent[w].first - tol) chain.join(std::uint32_t(w), std::uint32_t(v));
    }
  for (std::size_t w = 0; w < walls.size(); ++w) {
    for (std::uint32_t f : walls[w])
      for (std::uint32_t nb : adj[f]) {
        if (wall_of[nb] >= 0 && std::size_t(wall_of[nb]) != w && coaxial(w, std::size_t(wall_of[nb])))
          chain.join(std::uint32_t(w), std::uint32_t(wall_of[nb]));
      }
  }
  std::map<std::uint32_t, std::vector<std::size_t>> holes;
  for (std::size_t w = 0; w < walls.size(); ++w) holes[chain.find(std::uint32_t(w))].push_back(w);

  std::vector<HoleFeature> out;
  for (const auto& [root, ws] : holes) {
    const AagNode& ref = g.nodes[walls[ws[0]][0]];
    const Vec3 A = ref.axis, P = ref.axis_point;
    std::vector<Element> el;
    double rmax = 0;
    for (std::size_t w : ws) {
      Element e;
      e.faces = walls[w];
      std::sort(e.faces.begin(), e.faces.end());
      e.cone = g.nodes[e.faces[0]].type == SurfaceType::cone;
      e.lo = 1e300, e.hi = -1e300;
      for (std::uint32_t f : e.faces) {
        const AagNode& nd = g.nodes[f];
        const double h0 = height_in(nd, nd.axial_min, P, A), h1 = height_in(nd, nd.axial_max, P, A);
        e.lo = std::min({e.lo, h0, h1}), e.hi = std::max({e.hi, h0, h1});
      }
      e.r_lo = radius_at(g.nodes[e.faces[0]], P, A, e.lo), e.r_hi = radius_at(g.nodes[e.faces[0]], P, A, e.hi);
      rmax = std::max({rmax, e.r_lo, e.r_hi});
      el.push_back(std::move(e));
    }
    std::sort(el.begin(), el.end(), [](const Element& a, const Element& b) { return a.lo + a.hi < b.lo + b.hi; });
    const double lo = el.front().lo, hi = el.back().hi;
    const double end_tol = std::max(1e-3 * std::max(1.0, rmax), 1e-3 * (hi - lo));
    std::vector<char> in_hole(n, 0);
    for (const Element& e : el)
      for (std::uint32_t f : e.faces) in_hole[f] = 1;
    // 3. Ends: neighbours per face (each neighbouring face once, at the end its arcs' middles are
    // nearest to), floors.
    std::vector<std::uint32_t> floor_lo, floor_hi, entry_lo, entry_hi;
    bool apex_lo = false, apex_hi = false;
    std::vector<char> seen(n, 0);
    for (const Element& e : el) {
      if (e.cone && e.r_lo < 0.02 * rmax && e.lo <= lo + end_tol) apex_lo = true;
      if (e.cone && e.r_hi < 0.02 * rmax && e.hi >= hi - end_tol) apex_hi = true;
      for (std::uint32_t f : e.faces)
        for (std::uint32_t ai : arcs_of[f]) {
          const AagArc& arc = g.arcs[ai];
          const std::uint32_t nb = arc.a == f ? arc.b : arc.a;
          if (in_hole[nb] || seen[nb]) continue;
          const AagNode& p = g.nodes[nb];
          const double hm = dot(arc.midpoint - P, A);
          const bool at_lo = hm - lo < hi - hm;
          if (p.type == SurfaceType::plane && std::abs(std::abs(dot(p.normal, A)) - 1) <= 1e-4) {
            const double hp = dot(p.axis_point - P, A);
            if (std::abs(hp - lo) <= end_tol && dot(p.normal, A) > 0) {
              seen[nb] = 1, floor_lo.push_back(nb);
              continue;
            }
            if (std::abs(hp - hi) <= end_tol && dot(p.normal, A) < 0) {
              seen[nb] = 1, floor_hi.push_back(nb);
              continue;
            }
            // A seat between two walls of the hole is a role, not an end: found below.
            if (hp > lo + end_tol && hp < hi - end_tol) continue;
          }
          const bool on_axis = parallel(p.axis, A, 1e-3) && line_distance(P, A, p.axis_point) <= 1e-3 * std::max(1.0, rmax);
          const bool sphere_floor = p.type == SurfaceType::sphere && line_distance(P, A, p.axis_point) <= 1e-3 * std::max(1.0, rmax);
          const double r_end = at_lo ? el.front().r_lo : el.back().r_hi;
          const bool torus_floor = p.type == SurfaceType::torus && on_axis && p.radius < r_end - 1e-6 * std::max(1.0, rmax) &&
                                   arc.convexity != Convexity::convex;
          seen[nb] = 1;
          if (sphere_floor || torus_floor) (at_lo ? floor_lo : floor_hi).push_back(nb);
          else (at_lo ? entry_lo : entry_hi).push_back(nb);
        }
    }
    // A floor closes its end when it covers the axis; without a point test on the face, planar floors
    // must cover half the end's disk (a flat floor ring around a wider opening does not: gmsh_Block).
    auto covers = [&](const std::vector<std::uint32_t>& fl, double r) {
      double area = 0;
      for (std::uint32_t f : fl) {
        if (g.nodes[f].type != SurfaceType::plane) return true;  // sphere or floor fillet
        area += g.nodes[f].area;
      }
      return area >= 0.5 * M_PI * r * r;
    };
    if (!covers(floor_lo, el.front().r_lo)) entry_lo.insert(entry_lo.end(), floor_lo.begin(), floor_lo.end()), floor_lo.clear();
    if (!covers(floor_hi, el.back().r_hi)) entry_hi.insert(entry_hi.end(), floor_hi.begin(), floor_hi.end()), floor_hi.clear();
    const bool closed_lo = apex_lo || !floor_lo.empty(), closed_hi = apex_hi || !floor_hi.empty();
    if (closed_lo && closed_hi) continue;
    // 4. Type, from an open end inwards.
    bool from_hi = closed_lo;
    if (!closed_lo && !closed_hi) from_hi = el.back().r_hi > el.front().r_lo;
    std::vector<const Element*> seq;
    for (const Element& e : el) seq.push_back(&e);
    if (from_hi) std::reverse(seq.begin(), seq.end());
    auto counterbored = [](const std::vector<const Element*>& s) {
      std::vector<double> cyl;
      for (const Element* e : s)
        if (!e->cone) cyl.push_back(e->r_lo);
      return !s[0]->cone && cyl.size() >= 2 && cyl[0] > cyl[1] * (1 + 1e-6);
    };
    auto countersunk = [](const std::vector<const Element*>& s, bool outer_hi) {
      if (s.size() < 2 || !s[0]->cone) return false;
      return (outer_hi ? s[0]->r_hi : s[0]->r_lo) > (outer_hi ? s[0]->r_lo : s[0]->r_hi);
    };
    std::vector<const Element*> rev(seq.rbegin(), seq.rend());
    const bool both_open = !closed_lo && !closed_hi;
    if (both_open && !counterbored(seq) && counterbored(rev)) seq.swap(rev), from_hi = !from_hi;
    else if (both_open && !counterbored(seq) && !countersunk(seq, from_hi) && countersunk(rev, !from_hi))
      seq.swap(rev), from_hi = !from_hi;
    std::vector<double> radii;
    for (const Element* e : seq)
      if (!e->cone && std::none_of(radii.begin(), radii.end(), [&](double r) { return std::abs(r - e->r_lo) <= 1e-6 * std::max(1.0, r); }))
        radii.push_back(e->r_lo);
    // Counterdrilled (ISO 10303-224's counterdrilled hole): a counterbore whose seat is a drill
    // point's cone, narrowing inwards from the counterdrill to the bore, not a flat seat; the bore
    // is the rest of the hole (one radius, no further seat: a chamfered step between two counterbore
    // diameters, as in gmsh_Block, stays a counterbore).
    bool counterdrilled = counterbored(seq) && seq.size() >= 3 && seq[1]->cone && !seq[2]->cone &&
                          countersunk({seq[1], seq[2]}, from_hi);
    for (std::size_t i = 3; counterdrilled && i < seq.size(); ++i)
      counterdrilled = !seq[i]->cone && std::abs(seq[i]->r_lo - seq[2]->r_lo) <= 1e-6 * std::max(1.0, seq[2]->r_lo);
    std::string type;
    if (counterdrilled && types.count("counterdrilled_hole")) type = "counterdrilled_hole";
    else if (counterbored(seq)) type = "counterbored_hole";
    else if (countersunk(seq, from_hi)) type = "countersunk_hole";
    else if (radii.size() >= 2) type = "stepped_hole";
    else type = (closed_lo || closed_hi) ? "blind_hole" : "through_hole";
    if (!types.count(type)) type = (closed_lo || closed_hi) ? "blind_hole" : "through_hole";
    if (!types.count(type)) continue;
    // Roles.
    HoleFeature hf;
    Feature& f = hf.feature;
    f.type = type;
    auto add = [&](const std::string& role, const std::vector<std::uint32_t>& faces) {
      if (faces.empty()) return;
      auto& v = f.role_faces[role];
      v.insert(v.end(), faces.begin(), faces.end());
    };
    const auto& entry = from_hi ? entry_hi : entry_lo;
    const auto& exit = from_hi ? entry_lo : entry_hi;
    const auto& floor = from_hi ? floor_lo : floor_hi;
    std::vector<std::uint32_t> seat;
    if (type == "counterdrilled_hole") {
      add("counterdrill", seq[0]->faces);
      add("cone", seq[1]->faces);
      for (std::size_t i = 2; i < seq.size(); ++i) add("bore", seq[i]->faces);
      add("bottom", floor);
    } else if (type == "counterbored_hole" || type == "countersunk_hole") {
      add(type == "counterbored_hole" ? "counterbore" : "countersink", seq[0]->faces);
      for (std::size_t i = 1; i < seq.size(); ++i) add("bore", seq[i]->faces);
      if (type == "counterbored_hole") {
        // Seat: perpendicular planes adjacent to the counterbore and to another wall of the hole.
        for (std::uint32_t fc : seq[0]->faces)
          for (std::uint32_t nb : adj[fc]) {
            if (in_hole[nb] || g.nodes[nb].type != SurfaceType::plane) continue;
            bool other = false;
            for (std::uint32_t q : adj[nb])
              other = other || (in_hole[q] && std::find(seq[0]->faces.begin(), seq[0]->faces.end(), q) == seq[0]->faces.end());
            if (other && std::find(seat.begin(), seat.end(), nb) == seat.end()) seat.push_back(nb);
          }
        add("seat", seat);
      }
      add("bottom", floor);
    } else if (type == "blind_hole") {
      for (const Element* e : seq) {
        const bool apex = e->cone && std::min(e->r_lo, e->r_hi) < 0.02 * rmax;
        add(apex ? "bottom" : "wall", e->faces);
      }
      add("bottom", floor);
    } else {
      for (const Element* e : seq) add("wall", e->faces);
    }
    add("top", entry);
    if (type != "blind_hole") add("bottom", exit);
    for (auto& [role, faces] : f.role_faces) {
      std::sort(faces.begin(), faces.end());
      faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
      f.roles[role] = faces.front();
      f.faces.insert(f.faces.end(), faces.begin(), faces.end());
    }
    std::sort(f.faces.begin(), f.faces.end());
    f.faces.erase(std::unique(f.faces.begin(), f.faces.end()), f.faces.end());
    for (const Element* e : seq) hf.owned.insert(hf.owned.end(), e->faces.begin(), e->faces.end());
    hf.owned.insert(hf.owned.end(), floor.begin(), floor.end());
    hf.owned.insert(hf.owned.end(), seat.begin(), seat.end());
    std::sort(hf.owned.begin(), hf.owned.end());
    hf.owned.erase(std::unique(hf.owned.begin(), hf.owned.end()), hf.owned.end());
    f.axis = from_hi ? -A : A;
    f.axis_point = P + A * (from_hi ? hi : lo);
    f.radii = radii;
    for (const Element* e : seq)
      if (e->cone) f.radii.push_back(std::max(e->r_lo, e->r_hi));
    out.push_back(std::move(hf));
  }
  std::sort(out.begin(), out.end(), [](const HoleFeature& a, const HoleFeature& b) { return a.feature.faces < b.feature.faces; });
  return out;
}

}  // namespace interfere::cad::detail
