// Imported scars (issue #27, deliverable 2): a measured height map of a worn roller side — a CSV
// grid over angle x axial position, a 16-bit grayscale PNG, or a point cloud (an x y z text file or
// a mesh, e.g. a scanned STL of the worn region) in the roller's body frame — resampled onto the
// roller's regular (angle x height) vertex grid (roller.h) and applied as the scar, in place of the
// generated diamond-square map of scar.h (Jia & Zheng 2019, §2.2: a scar is a radial disturbance of
// the surface points; this brings in a measured one).
//
// Sign: a height is the radial deviation from the intact surface, POSITIVE OUTWARD (a raised scar,
// material above the nominal surface), negative inward (a pit). Roller::displacement is inward, so
// displacement = -height. A height at or below -r(z) (through the axis) is an error.
//
// CSV grid (read_scar_csv). Lines starting with '#' and blank lines are skipped. The first other
// line is the header: a label cell (any text, e.g. "z\angle"), then the column angles in degrees
// (body frame, about +z from +x, any start, strictly increasing, last - first < 360). Each
// following line: z in mm (body frame, from the bottom end, strictly increasing down the file),
// then one height in mm per column. Cells are separated by commas; spaces around them are ignored.
// At least 2 columns and 2 rows; every row has the header's cell count; every number finite.
//
//     z\angle_deg, -20, -10, 0, 10, 20
//     10, 0, 0, 0, 0, 0
//     20, 0, 0.02, 0.05, 0.02, 0
//     30, 0, 0, 0, 0, 0
//
// Resampling (resample_height_map): bilinear in (angle, z) at every side vertex. Angles are taken
// modulo 360 from the first column; a vertex past the last column lies outside the map unless the
// map wraps the whole circumference — evenly spaced columns with last - first + step = 360 (to
// 1e-9 relative): then it is interpolated between the last and the first column. Vertices outside
// the map's angle or z range keep height 0 and are not scar vertices; the others are (labels as
// apply_scar gives its window).
//
// PNG (read_scar_png): 16-bit grayscale (bit depth 16, colour type gray; no palette, no alpha),
// pixel value v in [0, 65535] -> height = scale * v + offset (mm). Pixel column x (left to right)
// is the angle angle_min + (angle_max - angle_min) * x / (W - 1), pixel row y (top to bottom) is
// the height z_max - (z_max - z_min) * y / (H - 1): the image seen from outside the roller, +z up.
//
// Point cloud (scar_from_points): each point (x, y, z) of the worn surface gives angle atan2(y, x),
// height z and deviation rho - r(z) (rho = hypot(x, y), r(z) the nominal radius). Every side vertex
// takes the inverse-distance-weighted mean (Shepard, weights 1/d^2) of the deviations of the points
// within `window` of it, d measured on the unrolled nominal surface (arc r(z_v) * angle difference,
// axial difference); a point closer than 1e-12 of the roller's size gives its own value. A vertex
// with no point within the window keeps 0 and is not a scar vertex. The result is a convex
// combination of measured deviations within the window, so for a surface whose deviation is
// L-Lipschitz on the unrolled surface the vertex height is within L * window of the true one.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "interfere/bearing/roller.h"
#include "interfere/bearing/scar.h"
#include "interfere/core/error.h"
#include "interfere/core/vec.h"

namespace interfere::bearing {

/// A rectangular grid of radial heights over (angle, z).
struct HeightMap {
  std::vector<double> angle_deg;  ///< columns, strictly increasing, span < 360
  std::vector<double> z;          ///< rows, strictly increasing
  std::vector<double> height;     ///< row-major: height[row * cols() + col], mm, positive outward
  std::string source;             ///< the file, for errors
  std::vector<std::int64_t> row_line;  ///< CSV: each row's 1-based line in the file; else empty
  bool from_png = false;               ///< rows are pixel rows from the top (errors name pixels)

  int cols() const { return static_cast<int>(angle_deg.size()); }
  int rows() const { return static_cast<int>(z.size()); }
  double at(int row, int col) const {
    return height[static_cast<std::size_t>(row) * angle_deg.size() + col];
  }
  /// The columns wrap the whole circumference (see above).
  bool wraps() const;
};

/// Per side vertex of a roller grid (Roller::side_vertex order): the height and whether the source
/// covers it.
struct VertexHeights {
  int n = 0, m = 0;                   ///< the grid: RollerParams radial_segments, height_segments
  std::vector<double> height;         ///< n * (m + 1), positive outward
  std::vector<std::uint8_t> covered;  ///< 1: a scar vertex
  std::string source;
  int covered_count() const;
};

/// Where a PNG lies on the roller (body frame, degrees and mm): see above.
struct MapPlacement {
  double angle_min_deg = -20, angle_max_deg = 20;
  double z_min = 10, z_max = 30;
};

/// The CSV grid (format above). Errors name the file, the line and the field (1-based cell).
Expected<HeightMap> read_scar_csv(const std::string& path);
/// The same from text (`source` names it in errors).
Expected<HeightMap> parse_scar_csv(std::string_view text, const std::string& source);

/// A 16-bit grayscale PNG, placed by `where`. Errors: not a PNG, not 16-bit gray, smaller than
/// 2 x 2, non-finite scale/offset, a bad placement (angle_max > angle_min, span < 360; z_max >
/// z_min). Builds without libpng answer that they have no PNG reader.
Expected<HeightMap> read_scar_png(const std::string& path, double scale, double offset,
                                  const MapPlacement& where);
/// Whether this build reads PNG (libpng found at configure time).
bool scar_png_supported();

/// Bilinear resampling onto the roller's grid (above). Errors: a map node inside the roller's
/// height range, or a resampled vertex, whose height would take the surface to or through the axis
/// (height <= -r(z)), naming the file, the CSV line and field (or the PNG pixel) or the vertex;
/// a map that covers no vertex.
Expected<VertexHeights> resample_height_map(const HeightMap& map, const RollerParams& roller);

struct PointScarOptions {
  /// Search radius on the unrolled surface (mm); 0 = automatic: the diagonal of one grid cell at
  /// the larger end radius, hypot(2 pi r_max / n, height / m).
  double window = 0;
};

/// Points of the worn surface in the roller's body frame (above). Errors: no point, a non-finite
/// coordinate, a point on the axis or whose deviation takes the surface through it (naming the
/// point index, 0-based), a bad window, no vertex with a point within the window.
Expected<VertexHeights> scar_from_points(const std::vector<Vec3>& points,
                                         const RollerParams& roller,
                                         const PointScarOptions& options = {},
                                         const std::string& source = "points");

/// Reads a point cloud: .stl .ply .obj .off (any case): the mesh's vertices (welded: a scanned
/// STL's facet corners once each; read by mesh/io.h); any other extension: a text file of "x y z"
/// per line (separated by spaces, tabs or commas; '#' comments and blank lines skipped; exactly
/// three finite numbers per line, errors name the line).
Expected<std::vector<Vec3>> read_scar_points(const std::string& path);

/// Applies the heights as the roller's scar: displacement = -height on covered vertices (0
/// elsewhere), scar labels = covered; then, when border > 0, apply_scar's median filter over the
/// covered region's border band (median_filter_border); then positions. The grid must be the
/// roller's. Errors: a grid mismatch, a non-finite height, a vertex pushed to or through the axis.
/// Returns the number of scar vertices.
Expected<int> apply_vertex_heights(Roller& roller, const VertexHeights& heights, int border = 0);

/// resample_height_map, then apply_vertex_heights.
Expected<int> apply_height_map(Roller& roller, const HeightMap& map, int border = 0);

/// The smallest scar window (angle arc and z range, as ScarParams: centre, width, z_min, z_max;
/// depth = the largest |height|, raised = any height > 0) containing every covered vertex: what the
/// simulation's range test of Eq. (1) uses for an imported scar. Width 360 (any angle) when every
/// column has a covered vertex.
ScarParams covered_window(const VertexHeights& heights, const RollerParams& roller);

}  // namespace interfere::bearing
