// `interfere bearing --scar-map / --scar-points` (issue #27): imported scars onto the roller grid.
#include "bearing_scar_import.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "common.h"
#include "interfere/bearing/scar_import.h"

namespace interfere::cli {

using namespace interfere::bearing;

std::vector<std::string> scar_import_inputs(const ScarImportOptions& o) {
  std::vector<std::string> out;
  if (!o.map.empty()) out.push_back(o.map);
  if (!o.points.empty()) out.push_back(o.points);
  return out;
}

nlohmann::json apply_scar_import(const ScarImportOptions& o, SceneParams& p) {
  if (!o.map.empty() && !o.points.empty())
    throw InputError("--scar-map and --scar-points exclude each other");
  if (!o.any()) {
    if (o.scale || o.offset)
      throw InputError("--scar-map-scale / --scar-map-offset need --scar-map (a PNG)");
    if (o.window) throw InputError("--scar-points-window needs --scar-points");
    return nullptr;
  }
  if (!(p.scar_fraction > 0))
    throw InputError(std::string(o.map.empty() ? "--scar-points" : "--scar-map") +
                     " needs scarred rollers (--scar-fraction > 0, no --no-scar)");
  // the roller grid first: its errors name the roller parameter, not the scar file
  if (Status s = validate(p.roller, "roller"); !s) throw InputError(s.error());
  nlohmann::json j;
  Expected<VertexHeights> heights = Error{.reason = "not read"};
  if (!o.map.empty()) {
    std::string ext = std::filesystem::path(o.map).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    Expected<HeightMap> map = Error{.reason = "not read"};
    if (ext == ".csv") {
      if (o.scale || o.offset)
        throw InputError("--scar-map-scale / --scar-map-offset apply to a PNG map only");
      map = read_scar_csv(o.map);
      j["kind"] = "csv";
    } else if (ext == ".png") {
      if (!o.scale)
        throw InputError("--scar-map " + o.map +
                         ": a PNG map needs --scar-map-scale (mm per pixel unit)");
      const MapPlacement where{
          .angle_min_deg = p.scar.angle_center_deg - 0.5 * p.scar.angle_width_deg,
          .angle_max_deg = p.scar.angle_center_deg + 0.5 * p.scar.angle_width_deg,
          .z_min = p.scar.z_min,
          .z_max = p.scar.z_max};
      map = read_scar_png(o.map, *o.scale, o.offset.value_or(0.0), where);
      j["kind"] = "png";
      j["scale"] = *o.scale;
      j["offset"] = o.offset.value_or(0.0);
      j["placement"] = {{"angle_min_deg", where.angle_min_deg},
                        {"angle_max_deg", where.angle_max_deg},
                        {"z_min", where.z_min},
                        {"z_max", where.z_max}};
    } else {
      throw InputError("--scar-map " + o.map + ": unknown extension '" + ext + "' (.csv or .png)");
    }
    if (!map) throw InputError(map.error());
    j["rows"] = map->rows(), j["columns"] = map->cols();
    heights = resample_height_map(*map, p.roller);
    j["file"] = o.map;
  } else {
    if (o.window && !(std::isfinite(*o.window) && *o.window >= 0))
      throw InputError("--scar-points-window must be >= 0 (0 = automatic), got " +
                       short_number(*o.window));
    Expected<std::vector<Vec3>> pts = read_scar_points(o.points);
    if (!pts) throw InputError(pts.error());
    heights = scar_from_points(*pts, p.roller, {.window = o.window.value_or(0.0)}, o.points);
    j["kind"] = "points";
    j["file"] = o.points;
    j["points"] = pts->size();
    j["point_window"] = o.window.value_or(0.0);
  }
  if (!heights) throw InputError(heights.error());
  p.imported_scar = std::move(*heights);
  const ScarParams w = covered_window(p.imported_scar, p.roller);
  double lo = 0, hi = 0;
  for (std::size_t k = 0; k < p.imported_scar.height.size(); ++k)
    if (p.imported_scar.covered[k])
      lo = std::min(lo, p.imported_scar.height[k]), hi = std::max(hi, p.imported_scar.height[k]);
  j["covered_vertices"] = p.imported_scar.covered_count();
  j["min_height"] = lo;
  j["max_height"] = hi;
  j["covered_window"] = {{"angle_center_deg", w.angle_center_deg},
                         {"angle_width_deg", w.angle_width_deg},
                         {"z_min", w.z_min},
                         {"z_max", w.z_max}};
  return j;
}

}  // namespace interfere::cli
