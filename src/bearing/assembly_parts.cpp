// The parts of a bearing assembly as bodies (assembly.h): closed outward meshes of the rings
// (solids of revolution of their profiles), the cage (Z convex webs, one hexahedron each: the side
// rings that would join them lie axially beyond the rollers and are not modelled), the rollers
// (make_roller, scarred by scar.h), and the list of pairs that can touch.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "assembly_internal.h"
#include "assembly_raceway_scars.h"
#include "assembly_roller_scars.h"
#include "interfere/bearing/assembly.h"

namespace interfere::bearing {
namespace {

constexpr double kPi = std::numbers::pi;

/// Signed volume (divergence theorem): > 0 for a closed outward mesh.
double signed_volume(const TriMesh& m) {
  double v = 0;
  for (const Tri& t : m.triangles)
    v += dot(m.positions[t[0]], cross(m.positions[t[1]], m.positions[t[2]]));
  return v / 6;
}

void flip_if_inward(TriMesh& m) {
  if (signed_volume(m) < 0)
    for (Tri& t : m.triangles) std::swap(t[1], t[2]);
}

/// The solid of revolution of a closed polygon in the (r, z) half-plane (r > 0 everywhere) about
/// the z axis, `n` segments: a closed torus-like mesh, outward.
TriMesh revolve(const std::vector<std::array<double, 2>>& profile, int n) {
  TriMesh m;
  const std::size_t p = profile.size();
  for (int j = 0; j < n; ++j) {
    const double a = 2 * kPi * j / n, c = std::cos(a), s = std::sin(a);
    for (const auto& [r, z] : profile) m.positions.push_back({r * c, r * s, z});
  }
  const auto v = [&](std::size_t i, int j) { return static_cast<std::uint32_t>((j % n) * p + (i % p)); };
  for (int j = 0; j < n; ++j)
    for (std::size_t i = 0; i < p; ++i) {
      m.triangles.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
      m.triangles.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
    }
  flip_if_inward(m);
  return m;
}

}  // namespace

const char* part_kind_name(PartKind k) {
  switch (k) {
    case PartKind::inner: return "inner";
    case PartKind::outer: return "outer";
    case PartKind::cage: return "cage";
    case PartKind::roller: return "roller";
  }
  return "?";
}

const char* assembly_pair_kind_name(AssemblyPairKind k) {
  switch (k) {
    case AssemblyPairKind::roller_inner: return "roller-inner";
    case AssemblyPairKind::roller_outer: return "roller-outer";
    case AssemblyPairKind::roller_roller: return "roller-roller";
    case AssemblyPairKind::roller_cage: return "roller-cage";
    case AssemblyPairKind::roller_rib: return "roller-rib";
    case AssemblyPairKind::roller_cone: return "roller-cone";
    case AssemblyPairKind::roller_cup: return "roller-cup";
    case AssemblyPairKind::cage_inner: return "cage-inner";
    case AssemblyPairKind::cage_outer: return "cage-outer";
    case AssemblyPairKind::bearing_bearing: return "bearing-bearing";
  }
  return "?";
}

const char* assembly_solver_name(AssemblySolver s) {
  switch (s) {
    case AssemblySolver::standard: return "standard";
    case AssemblySolver::scarred: return "scarred";
    case AssemblySolver::raceway: return "raceway";
    case AssemblySolver::vertex: return "vertex";
    case AssemblySolver::web: return "web";
    case AssemblySolver::mesh: return "mesh";
    case AssemblySolver::bound: return "bound";
  }
  return "?";
}

namespace {

/// A ring's profile (a closed polygon in the (r, z) half-plane) and its raceway edge: from point
/// `raceway` to the next one (cyclically).
struct RingProfile {
  std::vector<std::array<double, 2>> points;
  std::size_t raceway = 0;
};

RingProfile inner_profile(const BearingSpec& b, const BearingGeometry& g) {
  if (b.type == BearingType::tapered) {
    const double lo = g.ring_lo, hi = g.ring_hi;
    return {{{b.cone_bore, lo}, {g.raceway.radius, lo}, {g.raceway.top(), hi}, {b.cone_bore, hi}}, 1};
  }
  const double h = 0.5 * b.inner_width, w = b.rib_width, ri = b.inner_raceway, rr = ri + b.rib_height;
  return {{{b.inner_bore, -h}, {rr, -h}, {rr, -h + w}, {ri, -h + w}, {ri, h - w}, {rr, h - w}, {rr, h}, {b.inner_bore, h}},
          3};
}

RingProfile outer_profile(const BearingSpec& b, const BearingGeometry& g) {
  if (b.type == BearingType::tapered) {
    const double lo = g.ring_lo, hi = g.ring_hi;
    const auto cup_r = [&](double z) {
      return (z - g.apex_z) * std::tan(g.cup_half_angle) + b.cup_clearance / std::cos(g.cup_half_angle);
    };
    return {{{cup_r(lo), lo}, {b.cup_outer, lo}, {b.cup_outer, hi}, {cup_r(hi), hi}}, 3};
  }
  const double h = 0.5 * b.outer_width;
  return {{{b.outer_raceway, -h}, {b.outer_radius, -h}, {b.outer_radius, h}, {b.outer_raceway, h}}, 3};
}

}  // namespace

TriMesh inner_ring_mesh(const BearingSpec& b, const BearingGeometry& g, int segments) {
  return revolve(inner_profile(b, g).points, segments);
}

TriMesh outer_ring_mesh(const BearingSpec& b, const BearingGeometry& g, int segments) {
  return revolve(outer_profile(b, g).points, segments);
}

TriMesh scarred_ring_mesh(const BearingSpec& b, const BearingGeometry& g, const RacewayScar& scar) {
  const bool inner = scar.geometry.surface == RacewaySurface::inner || scar.geometry.surface == RacewaySurface::cone;
  RingProfile prof = inner ? inner_profile(b, g) : outer_profile(b, g);
  // the raceway edge takes the scar grid's rows strictly between its ends (in the edge's order);
  // the ends stay intact (at the ribs or the ring's faces)
  const Roller& surf = scar.surface;
  const int n = surf.n(), m = surf.m();
  const std::size_t e = prof.raceway, p0 = prof.points.size();
  const double za = prof.points[e][1], zb = prof.points[(e + 1) % p0][1];
  std::vector<int> rows;
  for (int k = 0; k <= m; ++k) {
    const double z = scar.to_ring.t.z + surf.z(k);
    if (z > std::min(za, zb) && z < std::max(za, zb)) rows.push_back(k);
  }
  if (zb < za) std::reverse(rows.begin(), rows.end());
  std::vector<std::array<double, 2>> pts(prof.points.begin(), prof.points.begin() + static_cast<std::ptrdiff_t>(e) + 1);
  for (const int k : rows) pts.push_back({prof.points[e][0], scar.to_ring.t.z + surf.z(k)});  // (radius replaced below)
  pts.insert(pts.end(), prof.points.begin() + static_cast<std::ptrdiff_t>(e) + 1, prof.points.end());
  TriMesh mesh = revolve(pts, n);
  // the inserted vertices: the scar surface's (same angles 2 pi j / n, same rows), in the ring frame
  const std::size_t p = pts.size();
  for (int j = 0; j < n; ++j)
    for (std::size_t r = 0; r < rows.size(); ++r)
      mesh.positions[static_cast<std::size_t>(j) * p + e + 1 + r] =
          scar.to_ring.apply(surf.mesh.positions[surf.side_vertex(j, rows[r])]);
  return mesh;
}

TriMesh web_mesh(const CageWeb& w) {
  TriMesh m;
  m.positions.assign(w.corners.begin(), w.corners.end());
  // corner i: bit 0 the pocket face (0: k, 1: k+1), bit 1 inner/outer, bit 2 low/high; each face is
  // the 4 corners with its bit fixed
  const Vec3 centre = [&] {
    Vec3 c;
    for (const Vec3& p : w.corners) c += p;
    return c / 8.0;
  }();
  for (int bit = 0; bit < 3; ++bit)
    for (int value = 0; value < 2; ++value) {
      std::array<std::uint32_t, 4> q{};
      int n = 0;
      // cyclic order over the other two bits: 00, 01, 11, 10
      const int o1 = (bit + 1) % 3, o2 = (bit + 2) % 3;
      for (const auto& [x, y] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}})
        q[n++] = static_cast<std::uint32_t>((value << bit) | (x << o1) | (y << o2));
      Tri t0{q[0], q[1], q[2]}, t1{q[0], q[2], q[3]};
      const Vec3 nrm = cross(w.corners[q[1]] - w.corners[q[0]], w.corners[q[2]] - w.corners[q[0]]);
      if (dot(nrm, w.corners[q[0]] - centre) < 0) std::swap(t0[1], t0[2]), std::swap(t1[1], t1[2]);
      m.triangles.push_back(t0);
      m.triangles.push_back(t1);
    }
  return m;
}

TriMesh cage_mesh(const BearingGeometry& g) {
  TriMesh m;
  for (const CageWeb& w : g.webs) {
    const TriMesh wm = web_mesh(w);
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), wm.positions.begin(), wm.positions.end());
    for (const Tri& t : wm.triangles) m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  return m;
}

std::int64_t Assembly::find(const std::string& id) const {
  for (std::size_t i = 0; i < parts.size(); ++i)
    if (parts[i].id == id) return static_cast<std::int64_t>(i);
  return -1;
}

Expected<Assembly> build_assembly(const AssemblySpec& spec) {
  if (Status st = validate_assembly(spec); !st) {
    Error e = st.error();
    if (e.file.empty()) e.file = spec.file;
    return e;
  }
  Assembly as;
  as.spec = spec;
  std::uint64_t roller_serial = 0;
  for (std::size_t bi = 0; bi < spec.bearings.size(); ++bi) {
    const BearingSpec& b = spec.bearings[bi];
    Expected<BearingGeometry> g = bearing_geometry(b);
    if (!g) return g.error();
    as.geometry.push_back(*g);
    const int bearing = static_cast<int>(bi);
    const auto add = [&](PartKind kind, std::string id, TriMesh mesh, const Transform& rest, int index) {
      AssemblyPart p;
      p.id = std::move(id), p.kind = kind, p.bearing = bearing, p.index = index;
      p.mesh = std::make_shared<const TriMesh>(std::move(mesh));
      p.rest = rest;
      as.parts.push_back(std::move(p));
      return static_cast<std::uint32_t>(as.parts.size() - 1);
    };
    const std::uint32_t inner = add(PartKind::inner, b.id + "/inner", inner_ring_mesh(b, *g, spec.ring_segments), g->frame, 0);
    const std::uint32_t outer = add(PartKind::outer, b.id + "/outer", outer_ring_mesh(b, *g, spec.ring_segments), g->frame, 0);
    const std::uint32_t cage = add(PartKind::cage, b.id + "/cage", cage_mesh(*g), g->frame, 0);
    for (const RacewayScarSpec& sc : b.scars) {  // raceway scars (issue #27; raceway_scar.h)
      const bool on_inner = sc.part == RacewaySurface::inner || sc.part == RacewaySurface::cone;
      AssemblyPart& ring = as.parts[on_inner ? inner : outer];
      if (ring.raceway_scar)
        return Error{.file = spec.file, .reason = sc.where + ".part: the " + raceway_surface_name(sc.part) +
                                                  " raceway has a scar already (one per raceway)"};
      Expected<std::shared_ptr<const RacewayScar>> rs = detail::build_raceway_scar(spec, b, *g, sc);
      if (!rs) return rs.error();
      ring.raceway_scar = std::move(*rs);
      // the ring's mesh (views, .pvd) shows the scarred raceway (issue #27); no solver uses ring meshes
      ring.mesh = std::make_shared<const TriMesh>(scarred_ring_mesh(b, *g, *ring.raceway_scar));
    }
    as.web_offset.push_back(static_cast<std::uint32_t>(as.webs.size()));
    for (const CageWeb& w : g->webs) as.webs.push_back(make_model(web_mesh(w)));
    // rollers, scarred ones spread evenly: roller k is scarred when floor((k+1) f) > floor(k f)
    RollerParams rp;
    rp.radius = b.rollers.radius, rp.top_radius = b.rollers.top_radius, rp.height = b.rollers.length;
    rp.radial_segments = b.rollers.radial_segments, rp.height_segments = b.rollers.height_segments;
    Expected<Roller> plain = make_roller(rp);
    if (!plain) return plain.error();
    const auto shared_plain = std::make_shared<const Roller>(*plain);
    const auto shared_mesh = std::make_shared<const TriMesh>(plain->mesh);
    // an imported roller scar (issue #27): resampled once onto this bearing's roller grid
    std::optional<VertexHeights> imported;
    if (spec.scar_import.any() && spec.scar_fraction > 0) {
      Expected<VertexHeights> h = detail::roller_scar_heights(spec, b, rp);
      if (!h) return h.error();
      imported = std::move(*h);
    }
    const int z = b.rollers.count;
    std::vector<std::uint32_t> rollers;
    for (int k = 0; k < z; ++k, ++roller_serial) {
      AssemblyPart p;
      p.id = b.id + "/roller" + std::to_string(k);
      p.kind = PartKind::roller, p.bearing = bearing, p.index = k;
      p.rest = detail::compose(g->frame, roller_local_pose(b, *g, 2 * kPi * k / z, 0, 0, 0));
      const double f = spec.scar_fraction;
      // (cylindrical and tapered rollers alike, issue #27: the scarred solver takes a frustum B)
      const bool scarred = f > 0 && std::floor((k + 1) * f + 1e-12) > std::floor(k * f + 1e-12);
      if (scarred) {
        Roller r = *plain;
        ScarParams sc = spec.scar;
        if (sc.z_min < 0) sc.z_min = 0.25 * rp.height;
        if (sc.z_max < 0) sc.z_max = 0.75 * rp.height;
        sc.seed = spec.scar.seed + roller_serial;
        Expected<int> applied = imported ? apply_vertex_heights(r, *imported, spec.scar_import.border) : apply_scar(r, sc);
        if (!applied) return applied.error();
        p.scarred = true;
        p.scar_height = r.raise;  // max(raise, largest |displacement|): the raceway-scar rows' check
        for (const double d : r.displacement) p.scar_height = std::max(p.scar_height, std::fabs(d));
        p.tree = std::make_shared<const RollerQuadtree>(build_quadtree(r));
        p.solid = std::make_shared<const Model>(make_model(r.mesh));
        p.mesh = std::make_shared<const TriMesh>(r.mesh);
        p.roller = std::make_shared<const Roller>(std::move(r));
      } else {
        p.roller = shared_plain;
        p.mesh = shared_mesh;
      }
      as.parts.push_back(std::move(p));
      rollers.push_back(static_cast<std::uint32_t>(as.parts.size() - 1));
    }
    // the pairs that can touch
    const bool cyl = b.type == BearingType::cylindrical;
    for (int k = 0; k < z; ++k) {
      const std::uint32_t r = rollers[k];
      as.pairs.push_back({cyl ? AssemblyPairKind::roller_inner : AssemblyPairKind::roller_cone, r, inner, 0});
      as.pairs.push_back({cyl ? AssemblyPairKind::roller_outer : AssemblyPairKind::roller_cup, r, outer, 0});
      if (cyl) {
        as.pairs.push_back({AssemblyPairKind::roller_rib, r, inner, 0});
        as.pairs.push_back({AssemblyPairKind::roller_rib, r, inner, 1});
      }
      as.pairs.push_back({AssemblyPairKind::roller_cage, r, cage, (k + z - 1) % z});  // the web behind it
      as.pairs.push_back({AssemblyPairKind::roller_cage, r, cage, k});                // the web ahead
      as.pairs.push_back({AssemblyPairKind::roller_roller, r, rollers[(k + 1) % z], 0});
    }
    // the cage against the rings (issue #27, item 2): apart by the webs' radial band at rest, but a
    // loaded or file-driven inner ring, or a displaced cage, can reach them
    as.pairs.push_back({AssemblyPairKind::cage_inner, cage, inner, 0});
    as.pairs.push_back({AssemblyPairKind::cage_outer, cage, outer, 0});
  }
  // every part's bounding sphere: the mesh's, grown by the facets' sagitta about the part's axis
  // (rings: the largest radius of a ring_segments polygon; rollers: radial_segments) and a raise
  for (AssemblyPart& p : as.parts) {
    Vec3 lo = p.mesh->positions.front(), hi = lo;
    double rmax = 0;
    for (const Vec3& v : p.mesh->positions) {
      lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
      hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
      rmax = std::max(rmax, std::hypot(v.x, v.y));
    }
    p.sphere.centre = (lo + hi) * 0.5;
    for (const Vec3& v : p.mesh->positions) p.sphere.radius = std::max(p.sphere.radius, norm(v - p.sphere.centre));
    const BearingSpec& b = spec.bearings[p.bearing];
    const int n = p.kind == PartKind::roller ? b.rollers.radial_segments : p.kind == PartKind::cage ? 0 : spec.ring_segments;
    const double sagitta = n > 0 ? rmax * (1 - std::cos(kPi / n)) : 0.0;
    const double grow = sagitta + (p.roller ? p.roller->raise : 0.0) + (p.raceway_scar ? p.raceway_scar->raise : 0.0) +
                        1e-9 * (rmax + norm(p.sphere.centre));
    p.sphere.radius += grow;
    p.sphere.cylinder_radius = rmax + grow, p.sphere.z_lo = lo.z - grow, p.sphere.z_hi = hi.z + grow;
  }
  // every two bearings (issue #27, item 2): their enclosing cylinders are apart at rest (validated),
  // but a motion (file) may bring them together
  std::vector<std::uint32_t> outer_of;
  for (std::size_t i = 0; i < as.parts.size(); ++i)
    if (as.parts[i].kind == PartKind::outer) outer_of.push_back(static_cast<std::uint32_t>(i));
  for (std::size_t i = 0; i < outer_of.size(); ++i)
    for (std::size_t j = i + 1; j < outer_of.size(); ++j)
      as.pairs.push_back({AssemblyPairKind::bearing_bearing, outer_of[i], outer_of[j], 0});
  return as;
}

}  // namespace interfere::bearing
