// Wavefront OBJ, geometry subset: `v` positions and `f` faces (corners `i`, `i/t`, `i//n`, `i/t/n`,
// 1-based, negative = relative to the vertices defined so far). Polygons are fan-triangulated; all
// other statements are ignored. A positive index may refer to a vertex defined later in the file
// (checked at the end, reported at the line of the largest offending index).
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "formats.h"
#include "text_reader.h"

namespace interfere::io_detail {

Expected<TriMesh> read_obj(const std::string& path, std::string_view d, MeshReadInfo& info) {
  info.format = MeshFormat::obj;
  TextReader r(strip_bom(d));
  TriMesh m;
  std::vector<std::uint32_t> corners;
  // Largest index that referred past the vertices defined at its line, and that line.
  std::int64_t pending_index = -1;
  std::int64_t pending_line = 0;
  constexpr std::int64_t kMaxVertices = std::numeric_limits<std::uint32_t>::max();

  std::string_view line;
  while (r.next_line(line)) {
    LineTokens tk(line);
    const std::string_view kw = tk.next();
    if (kw.empty() || kw[0] == '#') continue;
    if (kw == "v") {
      Vec3 p;
      for (int k = 0; k < 3; ++k) {
        const std::string_view w = tk.next();
        if (w.empty() || w[0] == '#') {
          return text_error(path, r.line(),
                            "vertex has " + std::to_string(k) + " coordinate" +
                                (k == 1 ? "" : "s") + "; 3 are needed");
        }
        double v;
        if (Status st = parse_coordinate(path, r.line(), w, k, v,
                                       static_cast<std::int64_t>(m.positions.size()) + 1);
            !st) return st.error();
        p[static_cast<std::size_t>(k)] = v;
      }
      if (static_cast<std::int64_t>(m.positions.size()) >= kMaxVertices) {
        return text_error(path, r.line(), "too many vertices for 32-bit indices");
      }
      m.positions.push_back(p);
    } else if (kw == "f") {
      corners.clear();
      const auto defined = static_cast<std::int64_t>(m.positions.size());
      for (std::string_view w = tk.next(); !w.empty() && w[0] != '#'; w = tk.next()) {
        const std::string_view num = w.substr(0, w.find('/'));
        std::int64_t v;
        if (num.empty())
          return text_error(path, r.line(), "face corner " + quoted(w) + " has no vertex index");
        if (!parse_int(num, v))
          return text_error(path, r.line(), "malformed vertex index " + quoted(w));
        std::int64_t resolved;
        if (v == 0) {
          return text_error(path, r.line(), "vertex index 0 is invalid (OBJ indices start at 1)");
        } else if (v < 0) {
          resolved = defined + v;
          if (resolved < 0) {
            return text_error(path, r.line(),
                              "relative vertex index " + std::to_string(v) +
                                  " refers before the first vertex (" + std::to_string(defined) +
                                  " defined so far)");
          }
        } else {
          resolved = v - 1;
          if (resolved >= kMaxVertices) {
            return text_error(path, r.line(),
                              "vertex index " + std::to_string(v) + " out of range");
          }
          if (resolved >= defined && resolved > pending_index)
            pending_index = resolved, pending_line = r.line();
        }
        corners.push_back(static_cast<std::uint32_t>(resolved));
      }
      if (corners.size() < 3) {
        return text_error(path, r.line(),
                          "face has " + std::to_string(corners.size()) + " corner" +
                              (corners.size() == 1 ? "" : "s") + "; at least 3 are needed");
      }
      if (corners.size() > 3) ++info.polygons_split;
      for (std::size_t k = 1; k + 1 < corners.size(); ++k)
        m.triangles.push_back({corners[0], corners[k], corners[k + 1]});
    }
    // Every other statement (vt, vn, vp, g, o, s, usemtl, mtllib, l, p, curv, ...) is ignored.
  }
  if (pending_index >= static_cast<std::int64_t>(m.positions.size())) {
    return text_error(path, pending_line,
                      "vertex index " + std::to_string(pending_index + 1) +
                          " out of range: the file defines " + std::to_string(m.positions.size()) +
                          " vertices");
  }
  if (m.triangles.empty())
    return text_error(path, r.end_line(), "no triangles: the OBJ file has no faces");
  return m;
}

void write_obj(OutputBuffer& out, const TriMesh& mesh) {
  out.write("# written by interfere\n");
  for (const Vec3& p : mesh.positions) {
    out.write("v ");
    out.write_xyz_line(p);
  }
  for (const Tri& t : mesh.triangles) out.write_tri_line("f ", t, 1);
}

}  // namespace interfere::io_detail
