// `interfere bearing --scar-map FILE | --scar-points FILE` (issue #27): reads an imported scar
// (bearing/scar_import.h) and resamples it onto the scene's roller grid, in place of the generated
// diamond-square map.
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "interfere/bearing/simulation.h"

namespace interfere::cli {

struct ScarImportOptions {
  std::string map;                      ///< --scar-map: .csv grid or 16-bit .png
  std::string points;                   ///< --scar-points: x y z text, or .stl/.ply/.obj/.off
  std::optional<double> scale, offset;  ///< --scar-map-scale / --scar-map-offset (PNG)
  std::optional<double> window;         ///< --scar-points-window (mm; 0 = automatic)
  bool any() const { return !map.empty() || !points.empty(); }
};

/// Reads the imported scar of `o` (if any) onto p.roller's grid into p.imported_scar; a PNG is
/// placed on p.scar's window (centre +- width / 2 in angle, z_min .. z_max). Throws InputError
/// naming the option or the file. Returns its description for the JSON summary (null when none).
nlohmann::json apply_scar_import(const ScarImportOptions& o, bearing::SceneParams& p);

/// Files the import reads (for the output/input distinctness check).
std::vector<std::string> scar_import_inputs(const ScarImportOptions& o);

}  // namespace interfere::cli
