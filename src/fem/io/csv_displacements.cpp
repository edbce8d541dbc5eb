// Nodal displacements from CSV (io.h read_displacements_csv; docs/fem.md): a header row naming
// the columns, then one row per node (and step). Columns, case-insensitive, any order:
// node id ("node_id", "node", "id", "nid"), "ux" "uy" "uz" (also "dx"/"u1"/"x"...), and optionally
// "step" or "time". Separators: comma, semicolon or tab; '#' starts a comment line.
#include <algorithm>
#include <map>

#include "scan.h"

namespace interfere {

Expected<NodalSeries> read_displacements_csv(const std::filesystem::path& path, const FemMesh& mesh, CsvDisplacementInfo* info) {
  using namespace fem_io;
  const std::string file = path.string();
  Expected<std::string> bytes = read_file_bytes(path);
  if (!bytes) return bytes.error();
  std::string_view text = *bytes;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text = text.substr(3);
  Text t(text);
  std::string_view line;
  // Header.
  std::int64_t header_line = 0;
  while (t.next_line(line)) {
    if (!trim(line).empty() && trim(line)[0] != '#') {
      header_line = t.line();
      break;
    }
  }
  if (header_line == 0) return file_error(file, "no header row");
  char sep = ',';
  if (line.find(',') == std::string_view::npos) sep = line.find(';') != std::string_view::npos ? ';' : '\t';
  auto split = [&](std::string_view l, std::vector<std::string_view>& out) {
    out.clear();
    std::size_t b = 0;
    for (;;) {
      const std::size_t c = l.find(sep, b);
      out.push_back(trim(l.substr(b, c == std::string_view::npos ? std::string_view::npos : c - b)));
      if (c == std::string_view::npos) break;
      b = c + 1;
    }
  };
  std::vector<std::string_view> cols;
  split(line, cols);
  int c_id = -1, c_step = -1, c_u[3] = {-1, -1, -1};
  bool by_time = false;
  for (int k = 0; k < static_cast<int>(cols.size()); ++k) {
    std::string n = to_lower(cols[static_cast<std::size_t>(k)]);
    if (n.size() >= 2 && n.front() == '"' && n.back() == '"') n = n.substr(1, n.size() - 2);
    if (n == "node_id" || n == "node" || n == "id" || n == "nid" || n == "node id" || n == "nodeid") c_id = k;
    else if (n == "step" || n == "increment") c_step = k;
    else if (n == "time" || n == "t") { c_step = k; by_time = true; }
    else if (n == "ux" || n == "dx" || n == "u1" || n == "u_x" || n == "x" || n == "u") c_u[0] = k;
    else if (n == "uy" || n == "dy" || n == "u2" || n == "u_y" || n == "y" || n == "v") c_u[1] = k;
    else if (n == "uz" || n == "dz" || n == "u3" || n == "u_z" || n == "z" || n == "w") c_u[2] = k;
    else return line_error(file, header_line, "unknown column " + quote_tok(cols[static_cast<std::size_t>(k)]) + " (expected node_id, ux, uy, uz and optionally step or time)");
  }
  if (c_id < 0 || c_u[0] < 0 || c_u[1] < 0 || c_u[2] < 0) return line_error(file, header_line, "header must name node_id, ux, uy and uz");
  IdMap map;
  if (map.build(mesh.node_ids) >= 0) return file_error(file, "the mesh has duplicate node ids");
  struct Row {
    double step;
    std::uint32_t node;
    Vec3 u;
    std::int64_t line;
  };
  std::vector<Row> rows;
  std::size_t ncols = cols.size();
  while (t.next_line(line)) {
    const std::string_view tl = trim(line);
    if (tl.empty() || tl[0] == '#') continue;
    split(line, cols);
    if (cols.size() != ncols) return line_error(file, t.line(), std::to_string(cols.size()) + " columns, the header has " + std::to_string(ncols));
    Row r{0, 0, {}, t.line()};
    std::int64_t id = 0;
    if (!parse_int(cols[static_cast<std::size_t>(c_id)], id)) return line_error(file, t.line(), "malformed node id " + quote_tok(cols[static_cast<std::size_t>(c_id)]));
    const std::int64_t idx = map.find(id);
    if (idx < 0) {
      // Names the row's step (issue #26, "Bad input") and the mesh the ids are looked up in.
      const std::string at = c_step < 0 ? std::string()
                                        : std::string(by_time ? "time " : "step ") +
                                              std::string(trim(cols[static_cast<std::size_t>(c_step)])) + ", ";
      return line_error(file, t.line(), at + "node " + std::to_string(id) + " is not in the mesh" +
                                            (mesh.file.empty() ? std::string() : " (" + mesh.file + ")"));
    }
    r.node = static_cast<std::uint32_t>(idx);
    for (int k = 0; k < 3; ++k) {
      const std::string_view x = cols[static_cast<std::size_t>(c_u[k])];
      if (!parse_double(x, r.u[static_cast<std::size_t>(k)])) return line_error(file, t.line(), "malformed number " + quote_tok(x));
    }
    if (!is_finite(r.u)) return line_error(file, t.line(), "non-finite displacement for node " + std::to_string(id));
    if (c_step >= 0) {
      const std::string_view x = cols[static_cast<std::size_t>(c_step)];
      if (!parse_double(x, r.step) || !std::isfinite(r.step)) return line_error(file, t.line(), std::string("malformed ") + (by_time ? "time " : "step ") + quote_tok(x));
    }
    rows.push_back(r);
  }
  if (rows.empty()) return line_error(file, header_line, "no data rows");
  std::vector<double> steps;
  for (const Row& r : rows) steps.push_back(r.step);
  std::sort(steps.begin(), steps.end());
  steps.erase(std::unique(steps.begin(), steps.end()), steps.end());
  if (static_cast<double>(steps.size()) * static_cast<double>(mesh.num_nodes()) > 2e9) {
    return file_error(file, std::to_string(steps.size()) + " distinct steps for " + std::to_string(mesh.num_nodes()) + " nodes: more than 2e9 displacement values");
  }
  NodalSeries s;
  s.name = path.stem().string();
  s.times = steps;
  s.values.assign(steps.size(), std::vector<Vec3>(mesh.num_nodes(), Vec3{}));
  std::vector<std::pair<std::uint64_t, std::size_t>> key(rows.size());  // (step index, node) -> row
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    const std::size_t k = static_cast<std::size_t>(std::lower_bound(steps.begin(), steps.end(), r.step) - steps.begin());
    key[i] = {static_cast<std::uint64_t>(k) * mesh.num_nodes() + r.node, i};
    s.values[k][r.node] = r.u;
  }
  std::sort(key.begin(), key.end());
  for (std::size_t i = 1; i < key.size(); ++i) {
    if (key[i].first != key[i - 1].first) continue;
    const Row& a = rows[std::min(key[i].second, key[i - 1].second)];
    const Row& b = rows[std::max(key[i].second, key[i - 1].second)];
    return line_error(file, b.line, "duplicate row for node " + std::to_string(mesh.node_ids[b.node]) +
                                         (c_step >= 0 ? std::string(by_time ? " at time " : " at step ") + std::string(trim(std::to_string(b.step))) : std::string()) +
                                         " (first at line " + std::to_string(a.line) + ")");
  }
  if (info) {
    info->rows = rows.size();
    info->missing_nodes = steps.size() * mesh.num_nodes() - rows.size();
  }
  return s;
}

}  // namespace interfere
