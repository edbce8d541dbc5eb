// Imported roller scars in bearing assemblies (assembly_roller_scars.h; issue #27, deliverable 2).
#include "assembly_roller_scars.h"

#include "assembly_raceway_scars.h"

namespace interfere::bearing::detail {

Expected<VertexHeights> roller_scar_heights(const AssemblySpec& spec, const BearingSpec& b, const RollerParams& rp) {
  const RollerScarImport& im = spec.scar_import;
  Expected<VertexHeights> heights = Error{.reason = "no imported scar"};
  if (!im.map.empty() || !im.png.empty()) {
    Expected<HeightMap> map = Error{};
    if (!im.map.empty()) {
      map = read_scar_csv(resolve(spec, im.map));
    } else {
      MapPlacement where;
      where.angle_min_deg = spec.scar.angle_center_deg - 0.5 * spec.scar.angle_width_deg;
      where.angle_max_deg = spec.scar.angle_center_deg + 0.5 * spec.scar.angle_width_deg;
      where.z_min = spec.scar.z_min < 0 ? 0.25 * rp.height : spec.scar.z_min;
      where.z_max = spec.scar.z_max < 0 ? 0.75 * rp.height : spec.scar.z_max;
      map = read_scar_png(resolve(spec, im.png), im.png_scale, im.png_offset, where);
    }
    if (!map) return map.error();
    heights = resample_height_map(*map, rp);
  } else {
    const std::string path = resolve(spec, im.points);
    Expected<std::vector<Vec3>> pts = read_scar_points(path);
    if (!pts) return pts.error();
    PointScarOptions o;
    o.window = im.points_window;
    heights = scar_from_points(*pts, rp, o, path);
  }
  if (!heights) {
    Error e = heights.error();
    const std::string key = !im.map.empty() ? "scar.map" : !im.png.empty() ? "scar.png" : "scar.points";
    if (e.file.empty()) e.file = spec.file, e.reason = key + ": " + e.reason;
    e.reason += " (on the rollers of " + b.where + ", id '" + b.id + "')";
    return e;
  }
  return heights;
}

}  // namespace interfere::bearing::detail
