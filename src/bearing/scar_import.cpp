// Imported scars (issue #27): the CSV height map, bilinear resampling onto the roller's vertex grid
// (periodic in angle when the map wraps), applying heights as the scar, and the covered window.
// The format and the rules are in scar_import.h.
#include "scar_number.h"
#include "interfere/bearing/scar_import.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <sstream>

namespace interfere::bearing {
namespace {

using detail::scar_number;

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r'))
    s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

/// A whole cell as a finite double, or false.
bool parse_number(std::string_view cell, double& out) {
  const std::string c(trim(cell));
  if (c.empty()) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtod(c.c_str(), &end);
  return end == c.c_str() + c.size() && std::isfinite(out) && errno != ERANGE;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> cells;
  std::size_t start = 0;
  for (;;) {
    const std::size_t k = line.find(',', start);
    if (k == std::string_view::npos) {
      cells.push_back(line.substr(start));
      return cells;
    }
    cells.push_back(line.substr(start, k - start));
    start = k + 1;
  }
}

/// Where a map node is, for errors: "line L, field F (angle A deg, z Z)" or "pixel (x, y)".
Error node_error(const HeightMap& map, int row, int col, const std::string& reason) {
  Error e{.file = map.source};
  if (!map.row_line.empty()) {
    e.line = map.row_line[static_cast<std::size_t>(row)];
    e.reason = "field " + std::to_string(col + 2) + " (angle " +
               scar_number(map.angle_deg[static_cast<std::size_t>(col)]) + " deg, z " +
               scar_number(map.z[static_cast<std::size_t>(row)]) + "): " + reason;
  } else if (map.from_png) {
    e.reason = "pixel (" + std::to_string(col) + ", " + std::to_string(map.rows() - 1 - row) +
               "): " + reason;
  } else {
    e.reason =
        "node (row " + std::to_string(row) + ", column " + std::to_string(col) + "): " + reason;
  }
  return e;
}

/// The interpolation interval of x in the increasing knots: k with knots[k] <= x <= knots[k + 1]
/// and the weight of knots[k + 1]; false outside [knots.front(), knots.back()].
bool interval(const std::vector<double>& knots, double x, int& k, double& t) {
  if (!(x >= knots.front() && x <= knots.back())) return false;
  const auto it = std::upper_bound(knots.begin(), knots.end(), x);
  k = static_cast<int>(it - knots.begin()) - 1;
  k = std::clamp(k, 0, static_cast<int>(knots.size()) - 2);
  const double a = knots[static_cast<std::size_t>(k)], b = knots[static_cast<std::size_t>(k) + 1];
  t = (x - a) / (b - a);
  t = std::clamp(t, 0.0, 1.0);
  return true;
}

}  // namespace

bool HeightMap::wraps() const {
  const int c = cols();
  if (c < 2) return false;
  const double step = 360.0 / c;
  for (int k = 0; k < c; ++k)
    if (std::fabs(angle_deg[static_cast<std::size_t>(k)] - (angle_deg[0] + step * k)) > 1e-9 * 360)
      return false;
  return true;
}

int VertexHeights::covered_count() const {
  int count = 0;
  for (const std::uint8_t c : covered) count += c;
  return count;
}

Expected<HeightMap> parse_scar_csv(std::string_view text, const std::string& source) {
  HeightMap map;
  map.source = source;
  const auto fail = [&](std::int64_t line, const std::string& reason) {
    return Error{.file = source, .line = line, .reason = reason};
  };
  std::int64_t line_no = 0;
  std::size_t pos = 0;
  bool header = false;
  std::size_t fields = 0;
  while (pos <= text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = trim(text.substr(pos, end - pos));
    ++line_no;
    pos = end + 1;
    if (line.empty() || line.front() == '#') {
      if (end == text.size()) break;
      continue;
    }
    const std::vector<std::string_view> cells = split(line);
    if (!header) {
      header = true;
      fields = cells.size();
      if (fields < 3)
        return fail(line_no, "the header needs a label cell and at least 2 angles (degrees), got " +
                                 std::to_string(fields) + " field(s)");
      for (std::size_t c = 1; c < fields; ++c) {
        double a;
        if (!parse_number(cells[c], a))
          return fail(line_no, "field " + std::to_string(c + 1) + ": angle '" +
                                   std::string(trim(cells[c])) +
                                   "' is not a finite number (degrees)");
        if (!map.angle_deg.empty() && !(a > map.angle_deg.back()))
          return fail(line_no, "field " + std::to_string(c + 1) +
                                   ": angles must increase strictly, got " + scar_number(a) + " after " +
                                   scar_number(map.angle_deg.back()));
        map.angle_deg.push_back(a);
      }
      if (!(map.angle_deg.back() - map.angle_deg.front() < 360))
        return fail(line_no, "the angles must span less than 360 degrees (last - first = " +
                                 scar_number(map.angle_deg.back() - map.angle_deg.front()) + ")");
    } else {
      if (cells.size() != fields)
        return fail(line_no, "expected " + std::to_string(fields) +
                                 " fields like the header (z and " + std::to_string(fields - 1) +
                                 " heights), got " + std::to_string(cells.size()));
      double z;
      if (!parse_number(cells[0], z))
        return fail(line_no,
                    "field 1: z '" + std::string(trim(cells[0])) + "' is not a finite number (mm)");
      if (!map.z.empty() && !(z > map.z.back()))
        return fail(line_no, "field 1: z must increase strictly down the file, got " + scar_number(z) +
                                 " after " + scar_number(map.z.back()));
      map.z.push_back(z);
      map.row_line.push_back(line_no);
      for (std::size_t c = 1; c < fields; ++c) {
        double h;
        if (!parse_number(cells[c], h))
          return fail(line_no, "field " + std::to_string(c + 1) + ": height '" +
                                   std::string(trim(cells[c])) + "' is not a finite number (mm)");
        map.height.push_back(h);
      }
    }
    if (end == text.size()) break;
  }
  if (!header) return fail(-1, "no header line (a label cell, then the angles in degrees)");
  if (map.rows() < 2)
    return fail(-1, "a height map needs at least 2 rows (z values) and 2 columns, got " +
                        std::to_string(map.rows()) + " row(s) x " + std::to_string(map.cols()) +
                        " column(s)");
  return map;
}

Expected<HeightMap> read_scar_csv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{.file = path, .reason = "cannot open the scar height map"};
  std::stringstream ss;
  ss << in.rdbuf();
  if (in.bad()) return Error{.file = path, .reason = "cannot read the scar height map"};
  return parse_scar_csv(ss.str(), path);
}

Expected<VertexHeights> resample_height_map(const HeightMap& map, const RollerParams& roller) {
  if (Status s = validate(roller); !s) return s.error();
  if (map.cols() < 2 || map.rows() < 2 ||
      map.height.size() !=
          static_cast<std::size_t>(map.cols()) * static_cast<std::size_t>(map.rows()))
    return Error{.file = map.source,
                 .reason = "a height map needs at least 2 x 2 values on its grid, got " +
                           std::to_string(map.rows()) + " row(s) x " + std::to_string(map.cols()) +
                           " column(s)"};
  // nodes: finite, and not through the axis where the roller is (r(z) + h > 0)
  for (int r = 0; r < map.rows(); ++r)
    for (int c = 0; c < map.cols(); ++c) {
      const double h = map.at(r, c), z = map.z[static_cast<std::size_t>(r)];
      if (!std::isfinite(h)) return node_error(map, r, c, "the height is not finite");
      if (z >= 0 && z <= roller.height && !(roller.radius_at(z) + h > 0))
        return node_error(map, r, c,
                          "height " + scar_number(h) +
                              " would take the surface to or through the axis (radius " +
                              scar_number(roller.radius_at(z)) + " at z " + scar_number(z) + ")");
    }
  VertexHeights out;
  out.n = roller.radial_segments, out.m = roller.height_segments, out.source = map.source;
  const std::size_t nv = static_cast<std::size_t>(out.n) * (out.m + 1);
  out.height.assign(nv, 0.0);
  out.covered.assign(nv, 0);
  const bool wrap = map.wraps();
  const double a0 = map.angle_deg.front(), span = map.angle_deg.back() - a0;
  const double step = wrap ? 360.0 / map.cols() : 0.0;
  for (int j = 0; j <= out.m; ++j) {
    const double z = j == out.m ? roller.height : roller.height * j / out.m;
    int kr;
    double tr;
    if (!interval(map.z, z, kr, tr)) continue;
    for (int i = 0; i < out.n; ++i) {
      const double phi = 360.0 * i / out.n;
      double u = std::fmod(phi - a0, 360.0);
      if (u < 0) u += 360.0;
      if (u >= 360.0) u = 0;
      int c0, c1;
      double tc;
      if (u <= span) {
        const double a = a0 + u;
        int k;
        if (!interval(map.angle_deg, std::min(a, map.angle_deg.back()), k, tc)) continue;
        c0 = k, c1 = k + 1;
      } else if (wrap) {  // between the last column and the first one + 360
        c0 = map.cols() - 1, c1 = 0;
        tc = std::clamp((u - span) / step, 0.0, 1.0);
      } else {
        continue;
      }
      const double h0 = (1 - tc) * map.at(kr, c0) + tc * map.at(kr, c1);
      const double h1 = (1 - tc) * map.at(kr + 1, c0) + tc * map.at(kr + 1, c1);
      const std::size_t v = static_cast<std::size_t>(j) * out.n + i;
      out.height[v] = (1 - tr) * h0 + tr * h1;
      out.covered[v] = 1;
    }
  }
  if (out.covered_count() == 0)
    return Error{.file = map.source,
                 .reason = "the height map (angles " + scar_number(map.angle_deg.front()) + ".." +
                           scar_number(map.angle_deg.back()) + " deg, z " + scar_number(map.z.front()) + ".." +
                           scar_number(map.z.back()) + " mm) covers no vertex of the roller (height " +
                           scar_number(roller.height) + ")"};
  return out;
}

Expected<int> apply_vertex_heights(Roller& roller, const VertexHeights& heights, int border) {
  if (heights.n != roller.n() || heights.m != roller.m() ||
      heights.height.size() != roller.displacement.size() ||
      heights.covered.size() != roller.displacement.size())
    return Error{.file = heights.source,
                 .reason = "the scar heights are on a " + std::to_string(heights.n) + " x " +
                           std::to_string(heights.m + 1) + " grid, the roller's is " +
                           std::to_string(roller.n()) + " x " + std::to_string(roller.m() + 1)};
  if (border < 0 || border > 64)
    return Error{.reason = "scar border must be in [0, 64], got " + std::to_string(border)};
  std::vector<double> raw(heights.height.size(), 0.0);
  for (int j = 0; j <= roller.m(); ++j)
    for (int i = 0; i < roller.n(); ++i) {
      const std::uint32_t v = roller.side_vertex(i, j);
      if (!heights.covered[v]) continue;
      const double h = heights.height[v];
      const double r = roller.params.radius_at(roller.z(j));
      if (!std::isfinite(h) || !(r + h > 0))
        return Error{
            .file = heights.source,
            .reason =
                "vertex (" + std::to_string(i) + ", " + std::to_string(j) + ") at angle " +
                scar_number(360.0 * i / roller.n()) + " deg, z " + scar_number(roller.z(j)) + ": height " + scar_number(h) +
                (std::isfinite(h)
                     ? " would take the surface to or through the axis (radius " + scar_number(r) + ")"
                     : " is not finite")};
      raw[v] = -h;
    }
  // the median of values that each keep r + h > 0 at their own ring may not at another ring of a
  // tapered roller: checked again below
  const std::vector<double> out = median_filter_border(roller, raw, heights.covered, border);
  for (int j = 0; j <= roller.m(); ++j)
    for (int i = 0; i < roller.n(); ++i) {
      const std::uint32_t v = roller.side_vertex(i, j);
      if (!(roller.params.radius_at(roller.z(j)) - out[v] > 0))
        return Error{.file = heights.source,
                     .reason = "vertex (" + std::to_string(i) + ", " + std::to_string(j) +
                               "): the border filter's height " + scar_number(-out[v]) +
                               " would take the surface through the axis"};
    }
  int labelled = 0;
  for (std::size_t k = 0; k < out.size(); ++k) {
    roller.displacement[k] = out[k];
    roller.scar[k] = heights.covered[k];
    labelled += heights.covered[k];
  }
  roller.has_scar = labelled > 0;
  roller.update_positions();
  return labelled;
}

Expected<int> apply_height_map(Roller& roller, const HeightMap& map, int border) {
  Expected<VertexHeights> h = resample_height_map(map, roller.params);
  if (!h) return h.error();
  return apply_vertex_heights(roller, *h, border);
}

ScarParams covered_window(const VertexHeights& heights, const RollerParams& roller) {
  ScarParams w;
  const int n = heights.n, m = heights.m;
  std::vector<std::uint8_t> column(static_cast<std::size_t>(n), 0);
  double zlo = roller.height, zhi = 0, most = 0;
  bool raised = false;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i < n; ++i) {
      const std::size_t v = static_cast<std::size_t>(j) * n + i;
      if (!heights.covered[v]) continue;
      column[static_cast<std::size_t>(i)] = 1;
      const double z = j == m ? roller.height : roller.height * j / m;
      zlo = std::min(zlo, z), zhi = std::max(zhi, z);
      most = std::max(most, std::fabs(heights.height[v]));
      raised |= heights.height[v] > 0;
    }
  // the largest run of uncovered columns (cyclic) is the gap; the window is its complement
  int best_gap = 0, best_start = 0;
  for (int s = 0; s < n; ++s) {
    if (column[static_cast<std::size_t>(s)] ||
        column[static_cast<std::size_t>((s + n - 1) % n)] == 0)
      continue;
    int len = 0;
    while (len < n && !column[static_cast<std::size_t>((s + len) % n)]) ++len;
    if (len > best_gap) best_gap = len, best_start = s;
  }
  const double col = 360.0 / n;
  if (best_gap == 0) {
    w.angle_center_deg = 0, w.angle_width_deg = 360;
  } else {
    // covered columns from best_start + best_gap to best_start - 1 (cyclic)
    const double first = (best_start + best_gap) * col;
    const double width = (n - best_gap - 1) * col;
    w.angle_center_deg = std::fmod(first + 0.5 * width, 360.0);
    w.angle_width_deg = width;
  }
  w.z_min = zlo, w.z_max = zhi;
  w.depth = most;
  w.raised = raised;
  w.border = 0;
  return w;
}

}  // namespace interfere::bearing
