// Abaqus / CalculiX input reader (Abaqus Keywords Reference: *NODE, *ELEMENT, *NSET, *ELSET
// (GENERATE), *INCLUDE (INPUT=), *PART / *END PART, *ASSEMBLY / *END ASSEMBLY, *INSTANCE (PART=,
// translation line, rotation line: points a and b on the axis and the angle in degrees; the
// translation is applied first) / *END INSTANCE). Keywords and parameters are case-insensitive,
// `**` starts a comment, data lines ending with a comma continue on the next line. Element node
// orders of C3D10/C3D15/C3D20 equal VTK's (corners, then mid-edges bottom, top, vertical), so no
// reordering happens.
//
// Ids and groups: without instances, the file's ids, and groups = the ELSET of each *ELEMENT
// block (one group "all" when no block names one). With instances, every instance copies its
// part's nodes and elements, transformed; group = the instance (name, id = 1-based instance
// number); ids of the k-th instance (0-based, file order) are id + k * S where S is the smallest
// power of ten above every node and element id of the parts (so the first instance keeps the
// solver's ids and id mod S is always the solver's id).
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "scan.h"

namespace interfere::fem_io {
namespace {

struct Line {
  int file;
  std::int64_t number;
  std::string_view text;
};

struct PartData {
  std::vector<Vec3> nodes;
  std::vector<std::int64_t> node_ids;
  std::vector<ElemType> types;
  std::vector<std::int64_t> elem_ids;
  std::vector<std::uint64_t> offsets{0};
  std::vector<std::int64_t> elem_node_ids;  // solver ids, resolved when the mesh is built
  std::vector<std::string> elem_block_set;  // ELSET of the *ELEMENT block (per element)
  std::vector<std::int64_t> elem_line;      // index into lines (for errors)
  std::map<std::string, std::vector<std::int64_t>> nsets, elsets;  // ids
  std::vector<std::string> set_order_n, set_order_e;
};

struct Instance {
  std::string name, part;
  Vec3 translate{};
  bool rotate = false;
  Vec3 a{}, b{};
  double angle = 0;
  std::int64_t line = 0;
};

// 1-D and point elements (trusses, beams, pipes, springs, dashpots, connectors, masses): read as
// line2/line3/point1 by their node count (so their node ids are checked), then skipped with a
// warning (drop_lower_dimension). Names as in the Abaqus Elements Guide; suffixes (H, OS, ...) free.
bool abaqus_1d_type(std::string_view name, ElemType& t) {
  const std::string n = to_lower(name);
  struct Family {
    const char* prefix;
    ElemType type;
  };
  static const Family kFamilies[] = {
      {"t2d2", ElemType::line2},  {"t3d2", ElemType::line2},   {"t2d3", ElemType::line3},  {"t3d3", ElemType::line3},
      {"b21", ElemType::line2},   {"b23", ElemType::line2},    {"b31", ElemType::line2},   {"b33", ElemType::line2},
      {"b22", ElemType::line3},   {"b32", ElemType::line3},    {"pipe21", ElemType::line2}, {"pipe31", ElemType::line2},
      {"pipe22", ElemType::line3}, {"pipe32", ElemType::line3}, {"springa", ElemType::line2}, {"spring2", ElemType::line2},
      {"dashpota", ElemType::line2}, {"dashpot2", ElemType::line2}, {"conn3d2", ElemType::line2},
      {"conn2d2", ElemType::line2}, {"gapuni", ElemType::line2}, {"jointc", ElemType::line2},
      {"spring1", ElemType::point1}, {"dashpot1", ElemType::point1}, {"mass", ElemType::point1},
      {"rotaryi", ElemType::point1}};
  for (const Family& f : kFamilies) {
    const std::size_t len = std::char_traits<char>::length(f.prefix);
    if (n.compare(0, len, f.prefix) != 0) continue;
    bool letters = true;  // only letter suffixes (B31H, B31OS, T3D2H)
    for (std::size_t i = len; i < n.size(); ++i) letters &= n[i] >= 'a' && n[i] <= 'z';
    if (!letters) continue;
    t = f.type;
    return true;
  }
  return false;
}

bool abaqus_type(std::string_view name, ElemType& t) {
  if (abaqus_1d_type(name, t)) return true;
  const std::string n = to_lower(name);
  auto num_after = [&](std::string_view prefix, int& v) {
    if (n.size() <= prefix.size() || n.compare(0, prefix.size(), prefix) != 0) return false;
    std::size_t i = prefix.size();
    v = 0;
    std::size_t d = 0;
    while (i < n.size() && n[i] >= '0' && n[i] <= '9') {
      if (v > 100000) return false;  // no such element type (and no overflow)
      v = v * 10 + (n[i] - '0');
      ++i;
      ++d;
    }
    if (d == 0) return false;
    // Allowed suffixes: R (reduced), H (hybrid), I (incompatible), M (modified), T (thermal).
    for (; i < n.size(); ++i) {
      if (n[i] != 'r' && n[i] != 'h' && n[i] != 'i' && n[i] != 'm' && n[i] != 't') return false;
    }
    return true;
  };
  int v = 0;
  if (num_after("c3d", v)) {
    switch (v) {
      case 4: t = ElemType::tet4; return true;
      case 10: t = ElemType::tet10; return true;
      case 5: t = ElemType::pyr5; return true;
      case 6: t = ElemType::wedge6; return true;
      case 15: t = ElemType::wedge15; return true;
      case 8: t = ElemType::hex8; return true;
      case 20: t = ElemType::hex20; return true;
      case 27: t = ElemType::hex27; return true;
      default: return false;
    }
  }
  // Plane stress/strain, axisymmetric, membrane, surface and rigid elements (gmsh writes CPS3 /
  // CPS6 for the boundary of its volumes): 2-D, dropped beside volumes like the shells.
  for (const char* prefix : {"cps", "cpe", "cax", "m3d", "sfm3d", "r3d"}) {
    if (!num_after(prefix, v)) continue;
    switch (v) {
      case 3: t = ElemType::tri3; return true;
      case 4: t = ElemType::quad4; return true;
      case 6: t = ElemType::tri6; return true;
      case 8: t = ElemType::quad8; return true;
      case 9: t = ElemType::quad9; return true;
      default: return false;
    }
  }
  if (num_after("s", v) || num_after("stri", v)) {
    switch (v) {
      case 3: t = ElemType::tri3; return true;
      case 4: t = ElemType::quad4; return true;
      case 6: t = ElemType::tri6; return true;
      case 8: t = ElemType::quad8; return true;
      case 9: t = ElemType::quad9; return true;
      default: return false;
    }
  }
  return false;
}

struct Keyword {
  std::string name;                                      // lower case, without '*'
  std::vector<std::pair<std::string, std::string>> params;  // lower-case key, value as written
  const std::string* get(std::string_view key) const {
    for (const auto& [k, v] : params) {
      if (k == key) return &v;
    }
    return nullptr;
  }
};

Keyword parse_keyword(std::string_view text) {
  Keyword k;
  std::size_t b = 1, comma = text.find(',');
  k.name = to_lower(trim(text.substr(b, comma == std::string_view::npos ? std::string_view::npos : comma - b)));
  while (comma != std::string_view::npos) {
    b = comma + 1;
    comma = text.find(',', b);
    std::string_view p = trim(text.substr(b, comma == std::string_view::npos ? std::string_view::npos : comma - b));
    if (p.empty()) continue;
    const std::size_t eq = p.find('=');
    std::string key = to_lower(trim(p.substr(0, eq)));
    std::string val = eq == std::string_view::npos ? std::string() : std::string(trim(p.substr(eq + 1)));
    if (val.size() >= 2 && val.front() == '"' && val.back() == '"') val = val.substr(1, val.size() - 2);
    k.params.emplace_back(std::move(key), std::move(val));
  }
  return k;
}

struct Reader {
  std::vector<std::string> names;
  std::vector<std::unique_ptr<std::string>> bytes;
  std::vector<Line> lines;
  int depth = 0;

  Error err(std::size_t li, std::string r) const {
    const Line& l = lines[li];
    return line_error(names[static_cast<std::size_t>(l.file)], l.number, std::move(r));
  }

  /// Collects the lines of a file (recursively through *INCLUDE), comments and blanks removed.
  Status collect(int fi, std::string_view text) {
    Text t(text);
    std::string_view line;
    while (t.next_line(line)) {
      const std::string_view tl = trim(line);
      if (tl.empty() || tl.substr(0, 2) == "**") continue;
      if (tl[0] == '*' && istarts_with(tl, "*include")) {
        const Keyword k = parse_keyword(tl);
        const std::string* in = k.get("input");
        if (!in || in->empty()) return line_error(names[static_cast<std::size_t>(fi)], t.line(), "*INCLUDE without INPUT=");
        if (depth > 20) return line_error(names[static_cast<std::size_t>(fi)], t.line(), "*INCLUDE nested too deeply");
        std::filesystem::path p = *in;
        if (p.is_relative()) p = std::filesystem::path(names[static_cast<std::size_t>(fi)]).parent_path() / p;
        Expected<std::string> b = read_file_bytes(p, true);
        if (!b) return line_error(names[static_cast<std::size_t>(fi)], t.line(), "*INCLUDE " + quote_tok(*in) + ": " + b.error().reason);
        names.push_back(p.string());
        bytes.push_back(std::make_unique<std::string>(std::move(*b)));
        ++depth;
        Status st = collect(static_cast<int>(names.size() - 1), *bytes.back());
        --depth;
        if (!st) return st;
        continue;
      }
      lines.push_back(Line{fi, t.line(), tl});
    }
    return {};
  }
};

void rotate_point(Vec3& p, const Vec3& a, const Vec3& b, double degrees) {
  Vec3 axis = b - a;
  const double len = norm(axis);
  if (!(len > 0)) return;
  axis = axis / len;
  const double th = degrees * std::numbers::pi / 180.0;
  const double c = std::cos(th), s = std::sin(th);
  const Vec3 v = p - a;
  // Rodrigues' rotation formula.
  const Vec3 r = v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1 - c));
  p = a + r;
}

}  // namespace

Expected<FemMesh> read_abaqus(const std::filesystem::path& path, std::string_view text) {
  Reader r;
  r.names.push_back(path.string());
  Status st = r.collect(0, text);
  if (!st) return st.error();
  const std::string file = path.string();
  std::map<std::string, PartData> parts;  // "" = the model outside any *PART
  std::vector<std::string> part_order;
  std::vector<Instance> instances;
  PartData* cur = &parts[""];
  part_order.push_back("");
  std::string cur_instance;  // inside *INSTANCE ... *END INSTANCE
  bool in_assembly = false;
  std::vector<std::int64_t> vals;
  std::size_t i = 0;
  const std::size_t n = r.lines.size();
  auto is_kw = [&](std::size_t k) { return r.lines[k].text[0] == '*'; };
  // Data fields of one logical record starting at line k (joined while a line ends with ',';
  // `need` > 0: joined until that many fields).
  auto record = [&](std::size_t& k, std::vector<std::string_view>& f, std::size_t need) {
    f.clear();
    for (;;) {
      std::string_view l = r.lines[k].text;
      const bool more = !l.empty() && l.back() == ',';
      std::size_t b = 0;
      for (;;) {
        const std::size_t c = l.find(',', b);
        std::string_view x = trim(l.substr(b, c == std::string_view::npos ? std::string_view::npos : c - b));
        if (!(c == std::string_view::npos && x.empty() && more)) f.push_back(x);
        if (c == std::string_view::npos) break;
        b = c + 1;
      }
      if (more && !f.empty() && f.back().empty()) f.pop_back();
      const bool want_more = need ? f.size() < need : more;
      if (!want_more || k + 1 >= n || is_kw(k + 1)) break;
      ++k;
    }
  };
  std::vector<std::string_view> f;
  while (i < n) {
    if (!is_kw(i)) return r.err(i, "data line outside a keyword: " + quote_tok(r.lines[i].text));
    const Keyword kw = parse_keyword(r.lines[i].text);
    const std::size_t kw_line = i;
    ++i;
    if (kw.name == "part") {
      const std::string* nm = kw.get("name");
      if (!nm) return r.err(kw_line, "*PART without NAME=");
      const std::string key = to_lower(*nm);
      if (parts.count(key)) return r.err(kw_line, "part " + *nm + " defined twice");
      cur = &parts[key];
      part_order.push_back(key);
    } else if (kw.name == "end part") {
      cur = &parts[""];
    } else if (kw.name == "assembly") {
      in_assembly = true;
    } else if (kw.name == "end assembly") {
      in_assembly = false;
    } else if (kw.name == "instance") {
      Instance in;
      const std::string* nm = kw.get("name");
      const std::string* pt = kw.get("part");
      if (!nm || !pt) return r.err(kw_line, "*INSTANCE needs NAME= and PART=");
      in.name = *nm;
      in.part = to_lower(*pt);
      in.line = static_cast<std::int64_t>(kw_line);
      for (int row = 0; row < 2 && i < n && !is_kw(i); ++row, ++i) {
        record(i, f, 0);
        double x[7] = {0, 0, 0, 0, 0, 0, 0};
        const std::size_t want = row == 0 ? 3 : 7;
        for (std::size_t q = 0; q < want && q < f.size(); ++q) {
          if (!f[q].empty() && !parse_double(f[q], x[q])) return r.err(i, "*INSTANCE: malformed number " + quote_tok(f[q]));
          if (!std::isfinite(x[q])) return r.err(i, "*INSTANCE: non-finite number");
        }
        if (row == 0) {
          in.translate = {x[0], x[1], x[2]};
        } else {
          if (f.size() < 7) return r.err(i, "*INSTANCE rotation needs 7 values (a, b, angle)");
          in.rotate = true;
          in.a = {x[0], x[1], x[2]};
          in.b = {x[3], x[4], x[5]};
          in.angle = x[6];
        }
      }
      instances.push_back(std::move(in));
      cur_instance = instances.back().name;
      // Skip anything else up to *END INSTANCE.
      while (i < n && !(is_kw(i) && parse_keyword(r.lines[i].text).name == "end instance")) ++i;
      if (i < n) ++i;
      cur_instance.clear();
    } else if (kw.name == "node") {
      const std::string* ns = kw.get("nset");
      if (const std::string* sys = kw.get("system"); sys && !iequals(*sys, "R")) {
        return r.err(kw_line, "*NODE, SYSTEM=" + *sys + " is not supported (only rectangular coordinates)");
      }
      for (; i < n && !is_kw(i); ++i) {
        record(i, f, 0);
        std::int64_t id = 0;
        if (f.empty() || !parse_int(f[0], id)) return r.err(i, "*NODE: malformed node id " + quote_tok(f.empty() ? "" : f[0]));
        Vec3 p;
        for (std::size_t q = 0; q < 3; ++q) {
          const std::string_view x = q + 1 < f.size() ? f[q + 1] : std::string_view();
          if (x.empty()) continue;
          if (!parse_double(x, p[q])) return r.err(i, "*NODE " + std::to_string(id) + ": malformed coordinate " + quote_tok(x));
        }
        if (!is_finite(p)) return r.err(i, "*NODE " + std::to_string(id) + ": non-finite coordinate");
        cur->nodes.push_back(p);
        cur->node_ids.push_back(id);
        if (ns) {
          auto& s = cur->nsets[to_lower(*ns)];
          if (s.empty()) cur->set_order_n.push_back(to_lower(*ns));
          s.push_back(id);
        }
      }
    } else if (kw.name == "element") {
      const std::string* ty = kw.get("type");
      if (!ty) return r.err(kw_line, "*ELEMENT without TYPE=");
      ElemType t{};
      if (!abaqus_type(*ty, t)) return r.err(kw_line, "unsupported element type " + quote_tok(*ty));
      const std::string* es = kw.get("elset");
      const std::string set = es ? to_lower(*es) : std::string();
      const int nn = elem_info(t).nodes;
      for (; i < n && !is_kw(i); ++i) {
        const std::size_t first = i;
        record(i, f, 1 + static_cast<std::size_t>(nn));
        std::int64_t id = 0;
        if (f.empty() || !parse_int(f[0], id)) return r.err(first, "*ELEMENT: malformed element id " + quote_tok(f.empty() ? "" : f[0]));
        if (f.size() < 1 + static_cast<std::size_t>(nn)) {
          return r.err(first, "element " + std::to_string(id) + ": " + *ty + " needs " + std::to_string(nn) + " nodes, found " + std::to_string(f.size() - 1));
        }
        for (int q = 0; q < nn; ++q) {
          std::int64_t v = 0;
          if (!parse_int(f[1 + static_cast<std::size_t>(q)], v)) return r.err(first, "element " + std::to_string(id) + ": malformed node id " + quote_tok(f[1 + static_cast<std::size_t>(q)]));
          cur->elem_node_ids.push_back(v);
        }
        cur->types.push_back(t);
        cur->elem_ids.push_back(id);
        cur->offsets.push_back(cur->elem_node_ids.size());
        cur->elem_block_set.push_back(set);
        cur->elem_line.push_back(static_cast<std::int64_t>(first));
        if (!set.empty()) {
          auto& s = cur->elsets[set];
          if (s.empty()) cur->set_order_e.push_back(set);
          s.push_back(id);
        }
      }
    } else if (kw.name == "nset" || kw.name == "elset") {
      const bool nodes = kw.name == "nset";
      const std::string* nm = kw.get(nodes ? "nset" : "elset");
      if (!nm) return r.err(kw_line, "*" + std::string(nodes ? "NSET" : "ELSET") + " without a name");
      const std::string* inst = kw.get("instance");
      PartData* target = cur;
      std::string set = to_lower(*nm);
      if (inst) {  // assembly-level set on an instance: stored in its part, named per instance
        const auto it = std::find_if(instances.begin(), instances.end(), [&](const Instance& x) { return iequals(x.name, *inst); });
        if (it == instances.end()) return r.err(kw_line, "unknown instance " + quote_tok(*inst));
        target = &parts[it->part];
        set = "@" + to_lower(it->name) + "." + set;
      }
      const bool gen = kw.get("generate") != nullptr;
      auto& members = nodes ? target->nsets[set] : target->elsets[set];
      auto& order = nodes ? target->set_order_n : target->set_order_e;
      if (std::find(order.begin(), order.end(), set) == order.end()) order.push_back(set);
      for (; i < n && !is_kw(i); ++i) {
        record(i, f, 0);
        if (gen) {
          std::int64_t a = 0, b = 0, s = 1;
          if (f.size() < 2 || !parse_int(f[0], a) || !parse_int(f[1], b) || (f.size() > 2 && !f[2].empty() && !parse_int(f[2], s)) || s <= 0 || b < a)
            return r.err(i, "GENERATE needs first, last[, step] with first <= last and step > 0");
          std::size_t input_bytes = text.size();
          for (const auto& b2 : r.bytes) input_bytes += b2->size();
          const std::uint64_t steps = (static_cast<std::uint64_t>(b) - static_cast<std::uint64_t>(a)) / static_cast<std::uint64_t>(s);
          if (steps > std::max<std::uint64_t>(1000000, 4 * static_cast<std::uint64_t>(input_bytes)))
            return r.err(i, "GENERATE range too large for the model (" + std::to_string(steps + 1) + " ids)");
          for (std::uint64_t k = 0; k <= steps; ++k) members.push_back(a + static_cast<std::int64_t>(k) * s);
          continue;
        }
        for (std::string_view x : f) {
          if (x.empty()) continue;
          std::int64_t v = 0;
          if (parse_int(x, v)) {
            members.push_back(v);
          } else {  // a set name: its members
            const auto& others = nodes ? target->nsets : target->elsets;
            auto it = others.find(to_lower(x));
            if (it == others.end()) return r.err(i, "unknown set " + quote_tok(x));
            const std::vector<std::int64_t> copy = it->second;
            members.insert(members.end(), copy.begin(), copy.end());
          }
        }
      }
    } else {
      // *HEADING, materials, steps, ...: skip the data lines.
      while (i < n && !is_kw(i)) ++i;
    }
  }
  (void)in_assembly;

  FemMesh m;
  m.file = file;
  // Builds one part (or instance) into m: node ids offset by `off`, transformed, group `g`.
  auto emit = [&](const PartData& p, std::int64_t off, const Instance* inst, std::int32_t g, const std::string& prefix) -> Status {
    const std::size_t base = m.nodes.size();
    IdMap map;
    const std::int64_t dup = map.build(p.node_ids);
    if (dup >= 0) {
      return Error{.file = file, .reason = "duplicate node id " + std::to_string(p.node_ids[static_cast<std::size_t>(dup)]) + (prefix.empty() ? std::string() : " in " + prefix)};
    }
    for (std::size_t k = 0; k < p.nodes.size(); ++k) {
      Vec3 x = p.nodes[k];
      if (inst) {
        x += inst->translate;
        if (inst->rotate) rotate_point(x, inst->a, inst->b, inst->angle);
      }
      m.nodes.push_back(x);
      m.node_ids.push_back(p.node_ids[k] + off);
    }
    const std::size_t ebase = m.elem_types.size();
    std::uint32_t v[32];
    std::unordered_map<std::string, std::int32_t> by_name;
    for (std::size_t e = 0; e < p.types.size(); ++e) {
      const int nn = elem_info(p.types[e]).nodes;
      for (int q = 0; q < nn; ++q) {
        const std::int64_t id = p.elem_node_ids[p.offsets[e] + static_cast<std::size_t>(q)];
        const std::int64_t idx = map.find(id);
        if (idx < 0) return r.err(static_cast<std::size_t>(p.elem_line[e]), "element " + std::to_string(p.elem_ids[e]) + ": node " + std::to_string(id) + " is not defined");
        v[q] = static_cast<std::uint32_t>(base + static_cast<std::size_t>(idx));
      }
      std::int32_t grp = g;
      if (g == -2) grp = p.elem_block_set[e].empty() ? -1 : group_index(m, by_name, p.elem_block_set[e], 0, elem_info(p.types[e]).dim);
      m.add_element(p.types[e], p.elem_ids[e] + off, grp, v, nn);
    }
    // Sets (ids -> indices); unknown ids are errors.
    IdMap emap;
    emap.build(p.elem_ids);
    for (const std::string& s : p.set_order_n) {
      FemSet set{.name = prefix.empty() ? s : prefix + "." + s};
      if (s[0] == '@') set.name = s.substr(1);
      if (s[0] == '@' && !prefix.empty() && s.compare(1, prefix.size() + 1, prefix + ".") != 0) continue;  // another instance's
      for (std::int64_t id : p.nsets.at(s)) {
        const std::int64_t idx = map.find(id);
        if (idx < 0) return Error{.file = file, .reason = "node set " + set.name + ": node " + std::to_string(id) + " is not defined"};
        set.members.push_back(static_cast<std::uint32_t>(base + static_cast<std::size_t>(idx)));
      }
      std::sort(set.members.begin(), set.members.end());
      set.members.erase(std::unique(set.members.begin(), set.members.end()), set.members.end());
      m.node_sets.push_back(std::move(set));
    }
    for (const std::string& s : p.set_order_e) {
      FemSet set{.name = prefix.empty() ? s : prefix + "." + s};
      if (s[0] == '@') set.name = s.substr(1);
      if (s[0] == '@' && !prefix.empty() && s.compare(1, prefix.size() + 1, prefix + ".") != 0) continue;
      for (std::int64_t id : p.elsets.at(s)) {
        const std::int64_t idx = emap.find(id);
        if (idx < 0) return Error{.file = file, .reason = "element set " + set.name + ": element " + std::to_string(id) + " is not defined"};
        set.members.push_back(static_cast<std::uint32_t>(ebase + static_cast<std::size_t>(idx)));
      }
      std::sort(set.members.begin(), set.members.end());
      set.members.erase(std::unique(set.members.begin(), set.members.end()), set.members.end());
      m.elem_sets.push_back(std::move(set));
    }
    return {};
  };
  if (instances.empty()) {
    const PartData& p = parts[""];
    if (p.types.empty()) {
      for (const std::string& name : part_order) {
        if (!parts[name].types.empty()) return Error{.file = file, .reason = "parts but no *INSTANCE in an *ASSEMBLY: nothing to place"};
      }
      return file_error(file, "no elements");
    }
    bool any_set = false;
    for (const std::string& s : p.elem_block_set) any_set |= !s.empty();
    if (!any_set) m.groups.push_back(FemGroup{.name = "all", .id = 0, .dim = 3});
    st = emit(p, 0, nullptr, any_set ? -2 : 0, "");
    if (!st) return st.error();
  } else {
    std::int64_t maxid = 0;
    constexpr std::int64_t kMaxId = 100000000000000000;  // 1e17: S and the offsets stay in range
    for (const auto& [name, p] : parts) {
      for (const std::vector<std::int64_t>* ids : {&p.node_ids, &p.elem_ids}) {
        for (std::int64_t id : *ids) {
          if (id <= -kMaxId || id >= kMaxId) return file_error(file, "id " + std::to_string(id) + " too large for instance numbering (|id| < 1e17)");
          maxid = std::max(maxid, id < 0 ? -id : id);
        }
      }
    }
    std::int64_t S = 1;
    while (S <= maxid) S *= 10;
    if (static_cast<double>(instances.size() + 1) * static_cast<double>(S) >= 9e18) return file_error(file, "too many instances for the id offset rule");
    for (std::size_t k = 0; k < instances.size(); ++k) {
      const Instance& in = instances[k];
      auto it = parts.find(in.part);
      if (it == parts.end() || in.part.empty()) return r.err(static_cast<std::size_t>(in.line), "*INSTANCE " + in.name + ": unknown part " + quote_tok(in.part));
      m.groups.push_back(FemGroup{.name = in.name, .id = static_cast<std::int64_t>(k + 1), .dim = 3});
      st = emit(it->second, static_cast<std::int64_t>(k) * S, &in, static_cast<std::int32_t>(k), to_lower(in.name));
      if (!st) return st.error();
    }
    // Nodes/elements outside parts in an assembly file (rare): one more group.
    const PartData& loose = parts[""];
    if (!loose.types.empty()) {
      m.groups.push_back(FemGroup{.name = "model", .id = static_cast<std::int64_t>(instances.size() + 1), .dim = 3});
      st = emit(loose, static_cast<std::int64_t>(instances.size()) * S, nullptr, static_cast<std::int32_t>(m.groups.size() - 1), "");
      if (!st) return st.error();
    }
  }
  if (m.elem_types.empty()) return file_error(file, "no elements (the instantiated parts have none)");
  // Duplicate ids (across *ELEMENT blocks).
  {
    std::int64_t first = -1;
    const std::int64_t d = find_duplicate(m.elem_ids, &first);
    if (d >= 0) return Error{.file = file, .reason = "duplicate element id " + std::to_string(m.elem_ids[static_cast<std::size_t>(d)])};
    const std::int64_t dn = find_duplicate(m.node_ids, &first);
    if (dn >= 0) return Error{.file = file, .reason = "duplicate node id " + std::to_string(m.node_ids[static_cast<std::size_t>(dn)])};
  }
  // Mixed shells and solids: keep the solids (like the other readers); sets keep indices valid.
  int top = 0;
  for (ElemType t : m.elem_types) top = std::max(top, elem_info(t).dim);
  bool mixed = false;
  for (ElemType t : m.elem_types) mixed |= elem_info(t).dim != top;
  if (mixed) {
    std::vector<std::int64_t> remap(m.num_elements(), -1);
    std::int64_t k = 0;
    for (std::size_t e = 0; e < m.num_elements(); ++e) {
      if (elem_info(m.elem_types[e]).dim == top) remap[e] = k++;
    }
    drop_lower_dimension(m, nullptr);
    for (FemSet& s : m.elem_sets) {
      std::vector<std::uint32_t> kept;
      for (std::uint32_t x : s.members) {
        if (remap[x] >= 0) kept.push_back(static_cast<std::uint32_t>(remap[x]));
      }
      s.members = std::move(kept);
    }
  }
  for (FemGroup& g : m.groups) g.dim = top;
  return m;
}

}  // namespace interfere::fem_io
