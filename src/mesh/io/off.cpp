// Object File Format (Geomview OFF): `[ST][C][N]OFF` keyword, `nv nf ne` counts (on the keyword
// line or the next one; the keyword itself may be missing), then one vertex per line (x y z, extra
// values such as colours ignored), then one face per line (n i0 .. in-1, 0-based, extra values
// ignored).
// `#` starts a comment anywhere. 4OFF, nOFF and binary OFF are rejected.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "formats.h"
#include "text_reader.h"

namespace interfere::io_detail {

Expected<TriMesh> read_off(const std::string& path, std::string_view d, MeshReadInfo& info) {
  info.format = MeshFormat::off;
  TextReader r(strip_bom(d));
  std::string_view line;
  auto next_content = [&]() {
    while (r.next_line(line)) {
      line = strip_comment(line);
      if (!line.empty()) return true;
    }
    return false;
  };

  if (!next_content())
    return text_error(path, r.end_line(), "no triangles: the OFF file has no header");
  LineTokens head(line);
  std::string_view counts_line;
  std::int64_t counts_line_no = r.line();
  std::int64_t probe;
  const std::string_view kw = head.next();
  if (kw.size() >= 3 && iequals(kw.substr(kw.size() - 3), "off")) {
    const std::string_view prefix = kw.substr(0, kw.size() - 3);
    for (char c : prefix) {
      if (c == '4' || c == 'n') {
        return text_error(
            path, r.line(),
            "unsupported OFF variant " + quoted(kw) + " (only 3D vertices are supported)");
      }
      if (c != 'S' && c != 'T' && c != 'C' && c != 'N') {
        return text_error(path, r.line(), "unknown OFF keyword " + quoted(kw));
      }
    }
    LineTokens rest(line);
    rest.next();
    const std::string_view after = rest.next();
    if (iequals(after, "binary")) return text_error(path, r.line(), "binary OFF is not supported");
    if (!after.empty()) {
      counts_line = line.substr(static_cast<std::size_t>(after.data() - line.data()));
    } else {
      if (!next_content())
        return text_error(path, r.end_line(), "file ends before the OFF counts line");
      counts_line = line;
      counts_line_no = r.line();
    }
  } else if (parse_int(kw, probe)) {
    counts_line = line;  // keyword-less OFF: the first line holds the counts
  } else {
    return text_error(path, r.line(), "expected the 'OFF' keyword, found " + quoted(kw));
  }

  std::int64_t nv = 0, nf = 0;
  {
    LineTokens tk(counts_line);
    const std::string_view a = tk.next(), b = tk.next(), c = tk.next();
    if (a.empty() || b.empty()) {
      return text_error(path, counts_line_no, "OFF header needs vertex and face counts");
    }
    std::int64_t ne;
    if (!parse_int(a, nv) || nv < 0)
      return text_error(path, counts_line_no, "malformed vertex count " + quoted(a));
    if (!parse_int(b, nf) || nf < 0)
      return text_error(path, counts_line_no, "malformed face count " + quoted(b));
    if (!c.empty() && (!parse_int(c, ne) || ne < 0)) {
      return text_error(path, counts_line_no, "malformed edge count " + quoted(c));
    }
  }
  if (nf == 0 || nv == 0) {
    return text_error(path, counts_line_no,
                      "no triangles: the OFF header declares " + std::to_string(nv) +
                          " vertices and " + std::to_string(nf) + " faces");
  }
  if (nv > std::numeric_limits<std::uint32_t>::max()) {
    return text_error(path, counts_line_no,
                      "vertex count " + std::to_string(nv) + " exceeds 32-bit indices");
  }
  // Before reserving: a vertex line takes at least 6 bytes ("0 0 0\n"), a face at least 8.
  const auto remaining = static_cast<std::int64_t>(d.size() - r.position());
  if (nv > remaining / 6 + 1 || nf > remaining / 8 + 1 || 6 * nv + 8 * nf - 1 > remaining) {
    return text_error(path, counts_line_no,
                      "OFF header declares " + std::to_string(nv) + " vertices and " +
                          std::to_string(nf) + " faces, but only " + std::to_string(remaining) +
                          " bytes follow");
  }

  TriMesh m;
  m.positions.reserve(static_cast<std::size_t>(nv));
  m.triangles.reserve(static_cast<std::size_t>(nf));
  for (std::int64_t i = 0; i < nv; ++i) {
    if (!next_content()) {
      return text_error(path, r.end_line(),
                        "file ends after " + std::to_string(i) + " of the " + std::to_string(nv) +
                            " vertices declared in the header");
    }
    LineTokens tk(line);
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
      const std::string_view w = tk.next();
      double v;
      if (w.empty())
        return text_error(path, r.line(),
                          "vertex has " + std::to_string(k) + " coordinates; 3 are needed");
      if (Status st = parse_coordinate(path, r.line(), w, k, v, static_cast<std::int64_t>(i)); !st) return st.error();
      p[static_cast<std::size_t>(k)] = v;
    }
    m.positions.push_back(p);
  }
  std::vector<std::uint32_t> corners;
  for (std::int64_t f = 0; f < nf; ++f) {
    if (!next_content()) {
      return text_error(path, r.end_line(),
                        "file ends after " + std::to_string(f) + " of the " + std::to_string(nf) +
                            " faces declared in the header");
    }
    LineTokens tk(line);
    const std::string_view cw = tk.next();
    std::int64_t n;
    if (!parse_int(cw, n))
      return text_error(path, r.line(), "malformed face corner count " + quoted(cw));
    if (n < 3) {
      return text_error(path, r.line(),
                        "face has " + std::to_string(n) + " corners; at least 3 are needed");
    }
    corners.clear();
    for (std::int64_t k = 0; k < n; ++k) {
      const std::string_view w = tk.next();
      std::int64_t v;
      if (w.empty()) {
        return text_error(
            path, r.line(),
            "face declares " + std::to_string(n) + " corners but lists " + std::to_string(k));
      }
      if (!parse_int(w, v))
        return text_error(path, r.line(), "malformed vertex index " + quoted(w));
      if (v < 0 || v >= nv) {
        return text_error(
            path, r.line(),
            "vertex index " + std::to_string(v) + " out of range [0, " + std::to_string(nv) + ")");
      }
      corners.push_back(static_cast<std::uint32_t>(v));
    }
    if (n > 3) ++info.polygons_split;
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)
      m.triangles.push_back({corners[0], corners[k], corners[k + 1]});
  }
  if (next_content()) {
    return text_error(path, r.line(),
                      "unexpected data after the " + std::to_string(nf) +
                          " faces declared in the header (counts do not match)");
  }
  return m;
}

void write_off(OutputBuffer& out, const TriMesh& mesh) {
  out.write("OFF\n");
  out.write_uint(mesh.positions.size());
  out.write_char(' ');
  out.write_uint(mesh.triangles.size());
  out.write(" 0\n");
  for (const Vec3& p : mesh.positions) out.write_xyz_line(p);
  for (const Tri& t : mesh.triangles) out.write_tri_line("3 ", t);
}

}  // namespace interfere::io_detail
