// Raceway scars (raceway_scar.h; issue #27, deliverable 2): the raceway as a roller grid over its
// whole circumference, scarred by scar.h's generator or scar_import.h's importers (Jia & Zheng 2019,
// §2.2), unchanged; only the sign of the heights (toward the rollers) and the window checks are
// the raceway's own.
#include "interfere/bearing/raceway_scar.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace interfere::bearing {
namespace {

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

Error param_error(const std::string& prefix, const char* name, const std::string& what, double got) {
  return Error{.reason = prefix + "." + name + " must be " + what + ", got " + num(got)};
}

/// +1 when "toward the rollers" is away from the axis (convex raceways), -1 otherwise.
double toward_sign(RacewaySurface s) { return raceway_concave(s) ? -1.0 : 1.0; }

Expected<Roller> make_surface(const RacewayGeometry& g, const RacewayGrid& grid) {
  return make_roller(raceway_roller_params(g, grid));
}

/// Tree, window, raise of a scarred surface.
RacewayScar finish(const RacewayGeometry& g, const RacewayGrid& grid, Roller&& surface, std::string source) {
  RacewayScar out;
  out.geometry = g, out.grid = grid;
  out.surface = std::move(surface);
  out.to_ring = Transform::identity();
  out.to_ring.t = {0, 0, g.z0};
  out.tree = build_quadtree(out.surface);
  if (raceway_concave(g.surface)) {
    // a bore's end caps are no ring material: both cap roots point at one empty node (half_r < 0:
    // its lower bound is +inf, scarred.cpp), so the solvers see the side triangles only
    QuadNode empty;
    empty.half_r = -1;
    out.tree.nodes.push_back(empty);
    out.tree.bottom_root = out.tree.top_root = static_cast<std::int32_t>(out.tree.nodes.size() - 1);
    BoundNode none;  // the same in the exact solvers' bound tree (quadtree.h)
    none.half_r = -1;
    out.tree.bounds.nodes.push_back(none);
    out.tree.bounds.bottom_root = out.tree.bounds.top_root = static_cast<std::int32_t>(out.tree.bounds.nodes.size() - 1);
  }
  VertexHeights h;
  h.n = out.surface.n(), h.m = out.surface.m();
  h.height.resize(out.surface.displacement.size());
  h.covered = out.surface.scar;
  const double sign = toward_sign(g.surface);
  double raise = 0;
  for (std::size_t v = 0; v < h.height.size(); ++v) {
    h.height[v] = -sign * out.surface.displacement[v];  // toward the rollers
    raise = std::max(raise, h.height[v]);
  }
  out.raise = raise;
  out.scar_vertices = h.covered_count();
  out.window = covered_window(h, out.surface.params);
  out.source = std::move(source);
  return out;
}

}  // namespace

const char* raceway_surface_name(RacewaySurface s) {
  switch (s) {
    case RacewaySurface::inner: return "inner";
    case RacewaySurface::outer: return "outer";
    case RacewaySurface::cone: return "cone";
    case RacewaySurface::cup: return "cup";
  }
  return "?";
}

Status validate(const RacewayGeometry& g, const RacewayGrid& grid, const std::string& prefix) {
  if (!std::isfinite(g.z0)) return param_error(prefix, "z0", "finite", g.z0);
  if (!(g.width > 0 && std::isfinite(g.width))) return param_error(prefix, "width", "> 0", g.width);
  if (!(g.radius > 0 && std::isfinite(g.radius))) return param_error(prefix, "radius", "> 0", g.radius);
  if (!(g.top_radius > 0 && std::isfinite(g.top_radius)))
    return param_error(prefix, "top_radius", "> 0", g.top_radius);
  if (grid.radial_segments < 8 || grid.radial_segments > 65536)
    return param_error(prefix, "radial_segments", "in [8, 65536]", grid.radial_segments);
  if (grid.height_segments < 1 || grid.height_segments > 4096)
    return param_error(prefix, "height_segments", "in [1, 4096]", grid.height_segments);
  return {};
}

RollerParams raceway_roller_params(const RacewayGeometry& g, const RacewayGrid& grid) {
  RollerParams p;
  p.radius = g.radius;
  p.top_radius = g.top_radius == g.radius ? -1.0 : g.top_radius;
  p.height = g.width;
  p.radial_segments = grid.radial_segments;
  p.height_segments = grid.height_segments;
  return p;
}

Expected<RacewayScar> make_raceway_scar(const RacewayGeometry& g, const RacewayGrid& grid, const ScarParams& s,
                                        const std::string& prefix) {
  if (Status st = validate(g, grid, prefix + ".raceway"); !st) return st.error();
  // the window must lie on the raceway (named here as the raceway's, before scar.h's own checks)
  if (!(s.z_min >= 0 && s.z_min < g.width))
    return param_error(prefix, "z_min", "in [0, raceway width " + num(g.width) + ") (the scar must lie on the raceway)",
                       s.z_min);
  if (!(s.z_max > s.z_min && s.z_max <= g.width))
    return param_error(prefix, "z_max",
                       "in (z_min, raceway width " + num(g.width) + "] (the scar must lie on the raceway)", s.z_max);
  const double rmin = std::min(g.radius, g.top_radius);
  if (!(s.depth > 0 && s.depth < 0.5 * rmin))
    return param_error(prefix, "depth", "in (0, half the raceway's smallest radius " + num(0.5 * rmin) + ")", s.depth);
  Expected<Roller> surface = make_surface(g, grid);
  if (!surface) return surface.error();
  ScarParams on_grid = s;
  on_grid.raised = raceway_concave(g.surface) ? !s.raised : s.raised;  // toward the rollers
  if (Status st = validate(on_grid, surface->params, prefix); !st) return st.error();
  Expected<int> applied = apply_scar(*surface, on_grid);
  if (!applied) return applied.error();
  if (*applied == 0)
    return Error{.reason = prefix + ": the window covers no vertex of the raceway grid (angle_width_deg " +
                           num(s.angle_width_deg) + " narrower than one of " +
                           std::to_string(grid.radial_segments) + " columns?)"};
  return finish(g, grid, std::move(*surface), "generated (seed " + std::to_string(s.seed) + ")");
}

Expected<RacewayScar> make_raceway_scar(const RacewayGeometry& g, const RacewayGrid& grid, const HeightMap& map,
                                        int border) {
  if (Status st = validate(g, grid, "raceway"); !st) return Error{.file = map.source, .reason = st.error().reason};
  // rows off the raceway: a misplaced map, an error (not silently cut)
  for (int r = 0; r < map.rows(); ++r) {
    const double z = map.z[static_cast<std::size_t>(r)];
    if (z >= 0 && z <= g.width) continue;
    Error e{.file = map.source};
    if (static_cast<std::size_t>(r) < map.row_line.size()) e.line = map.row_line[static_cast<std::size_t>(r)];
    e.reason = (map.from_png ? "pixel row " + std::to_string(map.rows() - 1 - r) + ": " : std::string()) +
               "axial position " + num(z) + " lies outside the " + raceway_surface_name(g.surface) +
               " raceway (0 .. " + num(g.width) + " from its start): the scar must lie on the raceway";
    return e;
  }
  for (std::size_t k = 0; k < map.height.size(); ++k)
    if (!std::isfinite(map.height[k]))
      return Error{.file = map.source, .reason = "height " + std::to_string(k) + " is not finite"};
  HeightMap radial = map;  // toward the rollers -> radial (away from the axis)
  const double sign = toward_sign(g.surface);
  for (double& h : radial.height) h *= sign;
  Expected<Roller> surface = make_surface(g, grid);
  if (!surface) return surface.error();
  Expected<VertexHeights> heights = resample_height_map(radial, surface->params);
  if (!heights) return heights.error();
  Expected<int> applied = apply_vertex_heights(*surface, *heights, border);
  if (!applied) return applied.error();
  return finish(g, grid, std::move(*surface), map.source);
}

Expected<RacewayScar> make_raceway_scar(const RacewayGeometry& g, const RacewayGrid& grid,
                                        const std::vector<Vec3>& points_ring_frame, const PointScarOptions& options,
                                        const std::string& source, int border) {
  if (Status st = validate(g, grid, "raceway"); !st) return Error{.file = source, .reason = st.error().reason};
  Expected<Roller> surface = make_surface(g, grid);
  if (!surface) return surface.error();
  std::vector<Vec3> local(points_ring_frame.size());
  for (std::size_t k = 0; k < local.size(); ++k) {
    const Vec3& p = points_ring_frame[k];
    local[k] = {p.x, p.y, p.z - g.z0};
    if (std::isfinite(p.z) && !(local[k].z >= -1e-9 * g.width && local[k].z <= g.width * (1 + 1e-9)))
      return Error{.file = source,
                   .reason = "point " + std::to_string(k) + ": axial position " + num(local[k].z) +
                             " from the raceway's start lies outside the " + raceway_surface_name(g.surface) +
                             " raceway (0 .. " + num(g.width) + "): the scar must lie on the raceway"};
  }
  Expected<VertexHeights> heights = scar_from_points(local, surface->params, options, source);
  if (!heights) return heights.error();
  Expected<int> applied = apply_vertex_heights(*surface, *heights, border);
  if (!applied) return applied.error();
  return finish(g, grid, std::move(*surface), source);
}

bool raceway_scar_angle_contains(const RacewayScar& s, double phi, double margin) {
  return scar_angle_contains(s.window, phi, margin);
}

}  // namespace interfere::bearing
