// A roller against a scarred raceway (raceway_scar_solver.h; issue #27): the raceway term by
// scarred.h's exact branch and bound over the raceway grid's quadtree (Jia & Zheng 2019, §3.2, with
// the raceway as the scarred part), the roller term by the same solver on the roller (convex
// raceway) or by the exact vertex maximum of the meridian distance (concave raceway).
#include "interfere/bearing/raceway_scar_solver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "interfere/bearing/scarred.h"

namespace interfere::bearing {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool has_scar_vertex(const Roller& r, std::uint32_t triangle) {
  if (triangle >= r.mesh.triangles.size()) return false;
  const auto& t = r.mesh.triangles[triangle];
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t v = t[static_cast<std::size_t>(k)];
    if (v < r.scar.size() && r.scar[v]) return true;
  }
  return false;
}

/// A world point on the raceway under the roller's centre (the hint of the raceway term).
Vec3 raceway_hint(const RacewayPairRoller& roller, const RacewayPairRing& ring, const Transform& surface_pose) {
  const Vec3 c = roller.cylinder.center();
  const Vec3 w = c - surface_pose.t;
  const Transform& p = surface_pose;
  const double x = p.r[0][0] * w.x + p.r[1][0] * w.y + p.r[2][0] * w.z;
  const double y = p.r[0][1] * w.x + p.r[1][1] * w.y + p.r[2][1] * w.z;
  const double z = std::clamp(p.r[0][2] * w.x + p.r[1][2] * w.y + p.r[2][2] * w.z, 0.0, ring.scar->geometry.width);
  const double rho = std::hypot(x, y);
  const double r = ring.scar->geometry.radius_at(z);
  const Vec3 local = rho > 0 ? Vec3{x * r / rho, y * r / rho, z} : Vec3{r, 0, z};
  return p.apply(local);
}

/// T_a for a concave raceway: minus the largest meridian distance beyond the grown surface over the
/// roller's mesh clipped to the width (vertices in the width, edges' crossings of the side faces).
void concave_roller_term(const RacewayPairRoller& roller, const RacewayPairRing& ring, RacewayScarPairResult& out) {
  const RacewayScar& s = *ring.scar;
  const RacewayGeometry& g = s.geometry;
  const Transform sp = raceway_surface_pose(ring);
  const Vec3 base = sp.t, ax = sp.rotate({0, 0, 1});
  const double k = (g.top_radius - g.radius) / g.width, nk = std::sqrt(1 + k * k);
  const Roller& m = *roller.mesh;
  // T_a = -best at the roller's vertex `far`; its witness on the ring is the foot of `far` on the
  // grown cone line in its meridian half-plane
  const auto finish = [&](double best, const Vec3& far, std::uint32_t far_vertex) {
    out.roller_term = -best;
    const double z = dot(far - base, ax);
    const Vec3 radial = far - base - ax * z;
    const double rho = norm(radial);
    const Vec3 nrm = rho > 0 ? (radial / rho - ax * k) / nk : Vec3{};
    out.point_roller = far;
    out.point_raceway = far - nrm * best;
    out.carrier = far_vertex < m.scar.size() && m.scar[far_vertex] ? ScarCarrier::roller : ScarCarrier::none;
  };
  // the whole roller (grown by its raise) within the width: no edge crosses a side face, so the
  // maximum is at a vertex; a branch and bound down the roller's bound tree (quadtree.h) finds it.
  // The upper bound over a node's oriented box (centre c, unit axes E_i, half extents h_i): with
  // nn the unit direction from the ring's axis to c and tt = ax x nn, a box point x has
  // nn.P(x) <= rho(c) + sum h_i |nn.E_i| =: A and |tt.P(x)| <= sum h_i |tt.E_i| =: T (P the
  // projection off the ring's axis), so rho(x) <= sqrt(A^2 + T^2); its axial position moves by at
  // most Z = sum h_i |ax.E_i|, so R(z) >= R(z(c)) - |k| Z. Anisotropic: the roller's axis is nearly
  // parallel to the ring's, so a node's long axial extent adds only its tilt to A, T and Z, where
  // the former Lipschitz bound (rho(c) + h - R(z(c)) + |k| h, h the box's half-diagonal) added all
  // of it and could not prune along the contact generator (issue #27; docs/bearing.md).
  {
    const Cylinder& c = roller.cylinder;
    const double ca = std::fabs(dot(c.axis, ax)), sa = std::sqrt(std::max(0.0, 1 - ca * ca));
    const double reach = (c.max_radius() + m.raise) * sa;
    const double z0 = dot(c.base - base, ax), z1 = dot(c.top_center() - base, ax);
    if (roller.tree != nullptr && std::min(z0, z1) - reach > 0 && std::max(z0, z1) + reach < g.width) {
      double best = -kInf;
      Vec3 far;
      std::uint32_t far_vertex = 0xffffffffu;
      const auto value_at = [&](const Vec3& x) {
        const double z = dot(x - base, ax);
        return (norm(cross(x - base, ax)) - (g.radius_at(z) - s.raise)) / nk;
      };
      const Vec3 rx = roller.pose.rotate({1, 0, 0}), ry = roller.pose.rotate({0, 1, 0}), rz = roller.pose.rotate({0, 0, 1});
      // rounding: the vertices' values and the bounds are each within a few ulps of the coordinates
      const double eps = std::numeric_limits<double>::epsilon(), coords = norm(roller.pose.t) + norm(base);
      const auto node_ub = [&](const auto& n) {
        if (n.half_r < 0) return -kInf;  // no triangles
        const Vec3 er = rx * n.cos_mid + ry * n.sin_mid, et = ry * n.cos_mid - rx * n.sin_mid;
        const Vec3 d = roller.pose.apply(n.box_center) - base;
        const double zc = dot(d, ax);
        const Vec3 pd = d - ax * zc;
        const double rho = norm(pd);
        double A = rho, T = 0;
        if (rho > 0) {
          const Vec3 nn = pd / rho, tt = cross(ax, nn);
          A += n.half_r * std::fabs(dot(nn, er)) + n.half_t * std::fabs(dot(nn, et)) + n.half_z * std::fabs(dot(nn, rz));
          T = n.half_r * std::fabs(dot(tt, er)) + n.half_t * std::fabs(dot(tt, et)) + n.half_z * std::fabs(dot(tt, rz));
        } else {
          A = n.half_r + n.half_t + n.half_z;
        }
        const double Z = n.half_r * std::fabs(dot(ax, er)) + n.half_t * std::fabs(dot(ax, et)) + n.half_z * std::fabs(dot(ax, rz));
        const double rz_lo = g.radius_at(zc) - std::fabs(k) * Z;
        return (std::sqrt(A * A + T * T) - (rz_lo - s.raise)) / nk + 64 * eps * (A + T + std::fabs(rz_lo) + s.raise + coords);
      };
      const auto search = [&](const auto& nodes, std::array<std::int32_t, 3> roots) {
        struct Item {
          std::int32_t node;
          double ub;
        };
        Item stack[512];
        int top = 0;
        for (const std::int32_t r : roots)
          if (r >= 0) stack[top++] = {r, node_ub(nodes[static_cast<std::size_t>(r)])};
        while (top > 0) {
          const Item it = stack[--top];
          if (it.ub < best) continue;  // (not <=: a tie with a smaller vertex id is kept, as the full scan)
          const auto& n = nodes[static_cast<std::size_t>(it.node)];
          if (n.child_count == 0) {
            for (std::uint32_t t = 0; t < n.tri_count; ++t)
              for (const std::uint32_t v : m.mesh.triangles[n.tri_first + t]) {
                const Vec3 x = roller.pose.apply(m.mesh.positions[v]);
                const double val = value_at(x);
                if (val > best || (val == best && v < far_vertex)) best = val, far = x, far_vertex = v;
              }
            continue;
          }
          Item kids[4];
          int count = 0;
          for (std::int32_t q = 0; q < n.child_count && q < 4; ++q) {
            const std::int32_t id = n.first_child + q;
            const double ub = node_ub(nodes[static_cast<std::size_t>(id)]);
            if (!(ub < best)) kids[count++] = {id, ub};
          }
          for (int i = 1; i < count; ++i)  // ascending upper bound: the largest is popped first
            for (int j = i; j > 0 && kids[j - 1].ub > kids[j].ub; --j) std::swap(kids[j - 1], kids[j]);
          for (int q = 0; q < count && top < 512; ++q) stack[top++] = kids[q];
        }
      };
      const RollerQuadtree& tr = *roller.tree;
      if (!tr.bounds.empty())
        search(tr.bounds.nodes, {tr.bounds.side_root, tr.bounds.bottom_root, tr.bounds.top_root});
      else
        search(tr.nodes, {tr.side_root, tr.bottom_root, tr.top_root});
      if (best > -kInf) {
        finish(best, far, far_vertex);
        return;
      }
    }
  }
  std::vector<Vec3> p(m.mesh.positions.size());
  std::vector<double> zs(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = roller.pose.apply(m.mesh.positions[i]), zs[i] = dot(p[i] - base, ax);
  double best = -kInf;
  Vec3 far;
  std::uint32_t far_vertex = 0xffffffffu;
  const auto consider = [&](const Vec3& x, double z, std::uint32_t vertex) {
    const double rho = norm(cross(x - base, ax));
    const double v = (rho - (g.radius_at(z) - s.raise)) / nk;
    if (v > best) best = v, far = x, far_vertex = vertex;
  };
  for (std::size_t i = 0; i < p.size(); ++i)
    if (zs[i] >= 0 && zs[i] <= g.width) consider(p[i], zs[i], static_cast<std::uint32_t>(i));
  for (const auto& t : m.mesh.triangles)
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = t[static_cast<std::size_t>(e)], b = t[static_cast<std::size_t>((e + 1) % 3)];
      if (a > b) continue;  // each edge of the closed mesh once (its other triangle has it reversed)
      for (const double level : {0.0, g.width}) {
        const double za = zs[a] - level, zb = zs[b] - level;
        if (!((za < 0 && zb > 0) || (za > 0 && zb < 0))) continue;
        const double t01 = za / (za - zb);
        consider(p[a] + (p[b] - p[a]) * t01, level, 0xffffffffu);
      }
    }
  if (!(best > -kInf)) return;  // no part of the roller in the ring's width: no roller term
  finish(best, far, far_vertex);
}

}  // namespace

const char* scar_carrier_name(ScarCarrier c) {
  switch (c) {
    case ScarCarrier::none: return "none";
    case ScarCarrier::roller: return "roller";
    case ScarCarrier::raceway: return "raceway";
  }
  return "?";
}

Transform raceway_surface_pose(const RacewayPairRing& ring) {
  Transform t = ring.pose;
  t.t = ring.pose.apply({0, 0, ring.scar->geometry.z0});
  return t;
}

Cylinder raceway_term_roller_solid(const RacewayPairRoller& roller, bool* exact) {
  // the roller's intact solid (a frustum when tapered: scarred.h takes it exactly, issue #27), grown
  // radially by a raised roller scar's raise
  Cylinder a = roller.cylinder;
  if (roller.mesh != nullptr && roller.mesh->raise > 0) {
    if (a.tapered()) a.top_radius = a.top() + roller.mesh->raise;
    a.radius += roller.mesh->raise;
  }
  if (exact != nullptr) *exact = true;
  return a;
}

RacewayScarPairResult raceway_scar_pair(const RacewayPairRoller& roller, const RacewayPairRing& ring) {
  RacewayScarPairResult out;
  const RacewayScar& s = *ring.scar;
  const Transform sp = raceway_surface_pose(ring);
  // raceway term: the scarred raceway surface against the roller's enclosing intact cylinder
  bool exact = true;
  const Cylinder a = raceway_term_roller_solid(roller, &exact);
  ScarredSolver race_solver(&s.surface, &s.tree);
  const MeshPairResult tr = race_solver.solve(sp, a, raceway_hint(roller, ring, sp));
  out.raceway_term = tr.distance;
  out.evaluated = tr.evaluated;
  out.nodes_visited = tr.nodes_visited, out.fallbacks = tr.fallbacks;
  out.distance = tr.distance;
  out.point_raceway = tr.point_a, out.point_roller = tr.point_b;
  out.carrier = has_scar_vertex(s.surface, tr.triangle) ? ScarCarrier::raceway : ScarCarrier::none;
  out.exact = exact;
  bool grown = roller.mesh != nullptr && roller.mesh->raise > 0;  // A^ grown by the roller scar's raise
  // roller term: the scarred roller against the ring's enclosing intact material
  if (roller.mesh != nullptr && roller.tree != nullptr) {
    RacewayScarPairResult r = out;
    const RacewayGeometry& g = s.geometry;
    if (raceway_concave(g.surface)) {
      concave_roller_term(roller, ring, r);
    } else {
      Cylinder b;
      b.base = sp.t, b.axis = sp.rotate({0, 0, 1}), b.height = g.width;
      b.radius = g.radius + s.raise;  // a cone: the frustum (scarred.h takes it exactly, issue #27)
      if (g.top_radius != g.radius) b.top_radius = g.top_radius + s.raise;
      ScarredSolver roller_solver(roller.mesh, roller.tree);
      const MeshPairResult ta = roller_solver.solve(roller.pose, b);
      r.roller_term = ta.distance;
      r.evaluated += ta.evaluated;
      r.nodes_visited += ta.nodes_visited, r.fallbacks += ta.fallbacks;
      r.point_roller = ta.point_a, r.point_raceway = ta.point_b;
      r.carrier = has_scar_vertex(*roller.mesh, ta.triangle) ? ScarCarrier::roller : ScarCarrier::none;
    }
    out.roller_term = r.roller_term;
    out.evaluated = r.evaluated;
    out.nodes_visited = r.nodes_visited, out.fallbacks = r.fallbacks;
    out.exact = r.exact;
    if (r.roller_term < out.distance) {  // ties: the raceway term (a fixed rule, either order)
      out.distance = r.roller_term;
      out.point_roller = r.point_roller, out.point_raceway = r.point_raceway;
      out.carrier = r.carrier;
      grown = s.raise > 0;  // B^ grown by the raceway scar's raise
    }
  }
  out.scar = out.carrier != ScarCarrier::none || grown;
  return out;
}

RacewayScarPairResult raceway_scar_pair(const RacewayPairRing& ring, const RacewayPairRoller& roller) {
  return raceway_scar_pair(roller, ring);
}

bool raceway_scar_in_range(const RacewayPairRoller& roller, const RacewayPairRing& ring, double margin) {
  const RacewayScar& s = *ring.scar;
  if (s.window.angle_width_deg >= 360) return true;
  const Transform& p = ring.pose;
  const Vec3 w = roller.cylinder.center() - p.t;
  const double x = p.r[0][0] * w.x + p.r[1][0] * w.y + p.r[2][0] * w.z;
  const double y = p.r[0][1] * w.x + p.r[1][1] * w.y + p.r[2][1] * w.z;
  const double rho = std::hypot(x, y);
  const double half_h = 0.5 * roller.cylinder.height;
  const double grown = roller.cylinder.max_radius() + (roller.mesh != nullptr ? roller.mesh->raise : 0.0);
  const double sphere = std::sqrt(half_h * half_h + grown * grown);
  if (!(rho > sphere)) return true;  // the sphere holds the ring axis: every angle
  const double half_span = std::asin(sphere / rho);
  return scar_angle_contains(s.window, std::atan2(y, x), half_span + margin);
}

}  // namespace interfere::bearing
