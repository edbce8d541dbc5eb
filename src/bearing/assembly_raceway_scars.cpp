// Raceway scars in bearing assemblies (assembly_raceway_scars.h; issue #27, deliverable 2).
#include "assembly_raceway_scars.h"

#include <cmath>
#include <filesystem>
#include <limits>

#include "interfere/bearing/part_pair.h"
#include "interfere/bearing/raceway_scar_solver.h"
#include "interfere/bearing/scar_import.h"

namespace interfere::bearing::detail {

std::string resolve(const AssemblySpec& spec, const std::string& path) {
  const std::filesystem::path p(path);
  if (p.is_absolute() || spec.file.empty()) return path;
  return (std::filesystem::path(spec.file).parent_path() / p).string();
}

RacewayGeometry raceway_geometry(const BearingSpec& b, const BearingGeometry& g, RacewaySurface part) {
  RacewayGeometry r;
  r.surface = part;
  switch (part) {
    case RacewaySurface::inner:
      r.z0 = -0.5 * b.inner_width, r.width = b.inner_width, r.radius = r.top_radius = b.inner_raceway;
      break;
    case RacewaySurface::outer:
      r.z0 = -0.5 * b.outer_width, r.width = b.outer_width, r.radius = r.top_radius = b.outer_raceway;
      break;
    case RacewaySurface::cone:
      r.z0 = g.raceway.base.z, r.width = g.raceway.height, r.radius = g.raceway.radius, r.top_radius = g.raceway.top();
      break;
    case RacewaySurface::cup: {  // as the roller-cup rows' Cup (assembly_pairs.cpp)
      const auto cup_r = [&](double zz) {
        return (zz - g.apex_z) * std::tan(g.cup_half_angle) + b.cup_clearance / std::cos(g.cup_half_angle);
      };
      r.z0 = g.ring_lo, r.width = g.ring_hi - g.ring_lo, r.radius = cup_r(g.ring_lo), r.top_radius = cup_r(g.ring_hi);
      break;
    }
  }
  return r;
}

Expected<std::shared_ptr<const RacewayScar>> build_raceway_scar(const AssemblySpec& spec, const BearingSpec& b,
                                                                const BearingGeometry& g, const RacewayScarSpec& s) {
  const RacewayGeometry geom = raceway_geometry(b, g, s.part);
  Expected<RacewayScar> made = Error{};
  if (!s.map.empty()) {
    Expected<HeightMap> map = read_scar_csv(resolve(spec, s.map));
    if (!map) return map.error();
    made = make_raceway_scar(geom, s.grid, *map, s.border);
  } else if (!s.png.empty()) {
    MapPlacement where;
    where.angle_min_deg = s.scar.angle_center_deg - 0.5 * s.scar.angle_width_deg;
    where.angle_max_deg = s.scar.angle_center_deg + 0.5 * s.scar.angle_width_deg;
    where.z_min = s.scar.z_min < 0 ? 0.25 * geom.width : s.scar.z_min;
    where.z_max = s.scar.z_max < 0 ? 0.75 * geom.width : s.scar.z_max;
    Expected<HeightMap> map = read_scar_png(resolve(spec, s.png), s.png_scale, s.png_offset, where);
    if (!map) return map.error();
    made = make_raceway_scar(geom, s.grid, *map, s.border);
  } else if (!s.points.empty()) {
    const std::string path = resolve(spec, s.points);
    Expected<std::vector<Vec3>> pts = read_scar_points(path);
    if (!pts) return pts.error();
    PointScarOptions o;
    o.window = s.points_window;
    made = make_raceway_scar(geom, s.grid, *pts, o, path, s.border);
  } else {
    ScarParams sc = s.scar;  // window defaults: the middle half of the raceway's width
    if (sc.z_min < 0) sc.z_min = 0.25 * geom.width;
    if (sc.z_max < 0) sc.z_max = 0.75 * geom.width;
    made = make_raceway_scar(geom, s.grid, sc, s.where);
  }
  if (!made) {
    Error e = made.error();
    if (e.file.empty()) {
      if (e.reason.rfind(s.where, 0) != 0) e.reason = s.where + ": " + e.reason;
      e.file = spec.file;
    }
    return e;
  }
  return std::make_shared<const RacewayScar>(std::move(*made));
}

std::optional<AssemblyPairResult> solve_raceway_scar_row(const Assembly& as, const AssemblyPair& pair,
                                                         const std::vector<Transform>& poses, double clearance) {
  switch (pair.kind) {
    case AssemblyPairKind::roller_inner:
    case AssemblyPairKind::roller_outer:
    case AssemblyPairKind::roller_cone:
    case AssemblyPairKind::roller_cup: break;
    default: return std::nullopt;
  }
  const AssemblyPart& ra = as.parts[pair.a];
  const AssemblyPart& pb = as.parts[pair.b];
  if (!pb.raceway_scar) return std::nullopt;
  const BearingSpec& b = as.spec.bearings[static_cast<std::size_t>(ra.bearing)];
  RacewayPairRoller roller;
  roller.cylinder = posed_cylinder(b.rollers.radius, b.rollers.top_radius, b.rollers.length, poses[pair.a]);
  if (ra.scarred) roller.mesh = ra.roller.get(), roller.tree = ra.tree.get();
  roller.pose = poses[pair.a];
  const RacewayPairRing ring{pb.raceway_scar.get(), poses[pair.b]};
  if (!raceway_scar_in_range(roller, ring)) return std::nullopt;
  const RacewayScarPairResult r = raceway_scar_pair(roller, ring);
  AssemblyPairResult out;
  out.distance = r.distance;
  out.point_a = r.point_roller, out.point_b = r.point_raceway;
  out.solver = AssemblySolver::scarred;
  out.scar = r.scar;
  out.exact = r.exact;
  // both directions are measured when the roller is scarred too (raceway_scar_solver.h); an intact
  // roller's row is S = T_r when the surfaces are apart (the Euclidean distance, symmetric: the row
  // is clear, as the assembly takes apart surfaces), one-sided when they overlap (docs/bearing.md)
  out.two_sided = r.roller_term < std::numeric_limits<double>::infinity() || r.distance > 0;
  if (r.carrier == ScarCarrier::roller) out.scar_part = 1;
  else if (r.carrier == ScarCarrier::raceway) out.scar_part = 2;
  else if (r.scar) out.scar_part = r.distance == r.raceway_term ? 1 : 2;  // the solid grown by the other's raise
  // tolerance: 2^-36 of the pair's coordinate scale (part_pair.h)
  const RacewayGeometry& geom = pb.raceway_scar->geometry;
  Cylinder race;
  race.base = poses[pair.b].apply({0, 0, geom.z0});
  race.axis = poses[pair.b].rotate({0, 0, 1});
  race.height = geom.width, race.radius = std::max(geom.radius, geom.top_radius);
  out.verdict = distance_verdict(r.distance, touch_tolerance(roller.cylinder, race), clearance);
  if (!r.exact && out.verdict != Verdict::clear) out.verdict = Verdict::undecided;  // a lower bound
  return out;
}

}  // namespace interfere::bearing::detail
