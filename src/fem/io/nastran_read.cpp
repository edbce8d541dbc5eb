// Nastran bulk data reader (MSC/NX Nastran Quick Reference Guide, "Bulk Data Entry format":
// small field (8 columns), large field (16 columns, `GRID*` with `*` continuations), free field
// (commas); continuation lines starting with `+`, `*`, a blank first field or a comma; BEGIN BULK
// / ENDDATA; INCLUDE relative to the including file). Cards read: GRID (CP 0 or blank only),
// CTETRA (4/10), CHEXA (8/20), CPENTA (6/15), CPYRAM/CPYRA (5/13), CTRIA3/CTRIA6, CQUAD4/CQUAD8;
// all other cards are skipped. Reals may use Nastran's shorthand exponent (`1.-3` = 1e-3,
// `-2.5+2` = -250, `1.0D+3`). Groups are property ids ("PID <n>"). CHEXA20/CPENTA15 mid-side
// grids are reordered to VTK's order (scan.cpp, nastran_to_vtk).
#include <algorithm>
#include <deque>
#include <map>

#include "scan.h"

namespace interfere::fem_io {
namespace {

/// Parses a Nastran real: standard forms plus the implicit-exponent shorthand.
bool nastran_real(std::string_view f, double& out) {
  if (f.empty()) {
    out = 0;
    return true;
  }
  if (parse_double(f, out)) return true;
  char buf[48];
  if (f.size() + 2 > sizeof buf) return false;
  std::size_t n = 0;
  bool have_exp = false;
  for (std::size_t i = 0; i < f.size(); ++i) {
    char c = f[i];
    if (c == 'D' || c == 'd') c = 'E';
    if (c == 'E' || c == 'e') have_exp = true;
    if (!have_exp && i > 0 && (c == '+' || c == '-') && f[i - 1] != 'E' && f[i - 1] != 'e') {
      buf[n++] = 'E';
      have_exp = true;
    }
    buf[n++] = c;
  }
  return parse_double(std::string_view(buf, n), out);
}

struct Card {
  std::string name;
  std::vector<std::string_view> fields;  // data fields 2.. (field 2 of the entry is fields[0])
  int file = 0;
  std::int64_t line = 0;
};

struct SourceFile {
  std::string name;
  std::string bytes;  // only for included files (the main file's bytes are the caller's)
};

struct Reader {
  std::vector<std::unique_ptr<SourceFile>> files;
  std::deque<std::string> tab_lines;  // tab-expanded copies; a deque keeps them (and their
                                      // short-string buffers) in place for the fields' views
  int depth = 0;
  // Element cards without a surface (beams, rods, springs, masses, rigid elements), by name: skipped
  // and counted for the reader's warning (issue #23, item 10: gmsh writes its lines as CBAR).
  std::map<std::string, std::size_t> skipped_elements;

  Error err(const Card& c, std::string r) const { return line_error(files[static_cast<std::size_t>(c.file)]->name, c.line, std::move(r)); }

  static void append_fixed(Card& c, std::string_view line, bool large) {
    const std::size_t w = large ? 16 : 8, per = large ? 4 : 8;
    for (std::size_t k = 0; k < per; ++k) {
      const std::size_t b = 8 + k * w;
      c.fields.push_back(b < line.size() ? trim(line.substr(b, std::min(w, line.size() - b))) : std::string_view());
    }
  }
  static void append_free(Card& c, std::string_view line, bool large) {
    const std::size_t per = large ? 4 : 8;
    // Fields between commas (empty ones kept); the first is the name or continuation marker.
    std::size_t b = line.find(',');
    std::size_t k = 0;
    while (b != std::string_view::npos && k < per) {
      const std::size_t e = line.find(',', b + 1);
      c.fields.push_back(trim(line.substr(b + 1, e == std::string_view::npos ? std::string_view::npos : e - b - 1)));
      ++k;
      b = e;
    }
    for (; k < per; ++k) c.fields.emplace_back();
  }

  /// Reads the cards of one file into `cards`.
  Status scan(int fi, std::string_view text, bool bulk_only, std::vector<Card>& cards, bool& ended) {
    const std::string& fname = files[static_cast<std::size_t>(fi)]->name;
    Text t(text);
    std::string_view line;
    bool in_bulk = !bulk_only;
    bool have = false;
    bool large = false;
    Card cur;
    auto flush = [&]() {
      if (have) cards.push_back(std::move(cur));
      cur = Card{};
      have = false;
    };
    while (t.next_line(line)) {
      const std::size_t dollar = line.find('$');
      if (dollar != std::string_view::npos) line = line.substr(0, dollar);
      if (line.find('\t') != std::string_view::npos) {
        std::string x;
        for (char c : line) {
          if (c == '\t') {
            do x += ' ';
            while (x.size() % 8 != 0);
          } else {
            x += c;
          }
        }
        tab_lines.push_back(std::move(x));
        line = tab_lines.back();
      }
      if (trim(line).empty()) continue;
      if (!in_bulk) {
        if (istarts_with(trim(line), "BEGIN BULK") || istarts_with(trim(line), "BEGIN SUPER")) in_bulk = true;
        continue;
      }
      const std::string_view tl = trim(line);
      if (istarts_with(tl, "ENDDATA")) {
        ended = true;
        break;
      }
      if (istarts_with(tl, "BEGIN")) continue;
      if (istarts_with(tl, "INCLUDE")) {
        flush();
        std::string_view rest = trim(tl.substr(7));
        if (!rest.empty() && (rest.front() == '\'' || rest.front() == '"')) {
          const char q = rest.front();
          std::string name(rest.substr(1));
          // The quoted name may continue on following lines.
          while (name.find(q) == std::string::npos) {
            std::string_view more;
            if (!t.next_line(more)) return line_error(fname, t.line(), "INCLUDE: unterminated file name");
            name += std::string(trim(more));
          }
          rest = std::string_view();
          name = name.substr(0, name.find(q));
          Status st = include(fi, name, t.line(), cards, ended);
          if (!st) return st;
        } else {
          Status st = include(fi, std::string(rest), t.line(), cards, ended);
          if (!st) return st;
        }
        if (ended) break;
        continue;
      }
      const bool free = line.find(',') != std::string_view::npos;
      const char c0 = line[0];
      const bool cont = c0 == '+' || c0 == '*' || (free && c0 == ',') || (!free && c0 == ' ' && trim(line.substr(0, std::min<std::size_t>(8, line.size()))).empty());
      if (cont) {
        if (!have) continue;  // continuation of a skipped card
        const bool lg = c0 == '*' || large;
        if (free) append_free(cur, line, c0 == '*' ? true : large); else append_fixed(cur, line, lg && c0 == '*');
        continue;
      }
      flush();
      std::string_view name = free ? trim(line.substr(0, line.find(','))) : trim(line.substr(0, std::min<std::size_t>(8, line.size())));
      large = !name.empty() && name.back() == '*';
      if (large) name.remove_suffix(1);
      std::string up;
      for (char ch : name) up += (ch >= 'a' && ch <= 'z') ? static_cast<char>(ch - 32) : ch;
      static const char* const kWanted[] = {"GRID", "CTETRA", "CHEXA", "CPENTA", "CPYRAM", "CPYRA", "CTRIA3", "CTRIA6", "CQUAD4", "CQUAD8"};
      if (std::find_if(std::begin(kWanted), std::end(kWanted), [&](const char* w) { return up == w; }) == std::end(kWanted)) {
        static const char* const kNoSurface[] = {
            "CBAR",   "CBEAM",  "CBEAM3", "CBEND",  "CROD",   "CONROD", "CTUBE",  "CBUSH",  "CBUSH1D", "CBUSH2D",
            "CELAS1", "CELAS2", "CELAS3", "CELAS4", "CDAMP1", "CDAMP2", "CDAMP3", "CDAMP4", "CDAMP5",  "CONM1",
            "CONM2",  "CMASS1", "CMASS2", "CMASS3", "CMASS4", "CGAP",   "CVISC",  "CWELD",  "CFAST",   "CSPR",
            "RBAR",   "RBAR1",  "RBE1",   "RBE2",   "RBE3",   "RROD",   "RSPLINE", "RTRPLT", "PLOTEL"};
        if (std::find_if(std::begin(kNoSurface), std::end(kNoSurface), [&](const char* w) { return up == w; }) !=
            std::end(kNoSurface)) {
          ++skipped_elements[up];
        }
        have = false;  // skipped card (its continuations too)
        continue;
      }
      have = true;
      cur.fields.reserve(16);
      cur.name = std::move(up);
      cur.file = fi;
      cur.line = t.line();
      if (free) append_free(cur, line, large); else append_fixed(cur, line, large);
    }
    flush();
    return {};
  }

  Status include(int from, const std::string& name, std::int64_t line, std::vector<Card>& cards, bool& ended) {
    const std::string& parent = files[static_cast<std::size_t>(from)]->name;
    if (depth > 20) return line_error(parent, line, "INCLUDE nested too deeply");
    std::filesystem::path p = name;
    if (p.is_relative()) p = std::filesystem::path(parent).parent_path() / p;
    Expected<std::string> bytes = read_file_bytes(p, true);
    if (!bytes) return line_error(parent, line, "INCLUDE " + quote_tok(name) + ": " + bytes.error().reason);
    auto sf = std::make_unique<SourceFile>();
    sf->name = p.string();
    sf->bytes = std::move(*bytes);
    files.push_back(std::move(sf));
    const int fi = static_cast<int>(files.size() - 1);
    ++depth;
    Status st = scan(fi, files.back()->bytes, false, cards, ended);
    --depth;
    return st;
  }
};

bool element_kind(const std::string& n, ElemType& lin, ElemType& quad, int& nlin, int& nquad, int& maxf) {
  if (n == "CTETRA") { lin = ElemType::tet4; quad = ElemType::tet10; nlin = 4; nquad = 10; maxf = 10; return true; }
  if (n == "CHEXA") { lin = ElemType::hex8; quad = ElemType::hex20; nlin = 8; nquad = 20; maxf = 20; return true; }
  if (n == "CPENTA") { lin = ElemType::wedge6; quad = ElemType::wedge15; nlin = 6; nquad = 15; maxf = 15; return true; }
  if (n == "CPYRAM" || n == "CPYRA") { lin = ElemType::pyr5; quad = ElemType::pyr13; nlin = 5; nquad = 13; maxf = 13; return true; }
  if (n == "CTRIA3") { lin = quad = ElemType::tri3; nlin = nquad = 3; maxf = 3; return true; }
  if (n == "CTRIA6") { lin = quad = ElemType::tri6; nlin = nquad = 6; maxf = 6; return true; }
  if (n == "CQUAD4") { lin = quad = ElemType::quad4; nlin = nquad = 4; maxf = 4; return true; }
  if (n == "CQUAD8") { lin = quad = ElemType::quad8; nlin = nquad = 8; maxf = 8; return true; }
  return false;
}

}  // namespace

Expected<FemMesh> read_nastran(const std::filesystem::path& path, std::string_view bytes) {
  Reader r;
  auto main = std::make_unique<SourceFile>();
  main->name = path.string();
  r.files.push_back(std::move(main));
  std::vector<Card> cards;
  bool ended = false;
  // Executive/case control before BEGIN BULK is skipped when the file has BEGIN BULK.
  bool has_begin = false;
  {
    Text t(bytes);
    std::string_view line;
    while (t.next_line(line)) {
      if (istarts_with(trim(line), "BEGIN BULK") || istarts_with(trim(line), "BEGIN SUPER")) {
        has_begin = true;
        break;
      }
    }
  }
  Status st = r.scan(0, bytes, has_begin, cards, ended);
  if (!st) return st.error();
  FemMesh m;
  m.file = path.string();
  std::vector<const Card*> elems;
  std::vector<std::int64_t> grid_line;
  for (const Card& c : cards) {
    if (c.name != "GRID") {
      elems.push_back(&c);
      continue;
    }
    auto f = [&](std::size_t k) { return k < c.fields.size() ? c.fields[k] : std::string_view(); };
    std::int64_t id = 0, cp = 0;
    if (!parse_int(f(0), id) || id <= 0) return r.err(c, "GRID: bad id " + quote_tok(f(0)));
    if (!f(1).empty() && (!parse_int(f(1), cp) || cp != 0)) {
      return r.err(c, "GRID " + std::to_string(id) + ": coordinate system CP=" + std::string(f(1)) + " is not supported (only CP 0 or blank)");
    }
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
      if (!nastran_real(f(2 + static_cast<std::size_t>(k)), p[static_cast<std::size_t>(k)])) {
        return r.err(c, "GRID " + std::to_string(id) + ": malformed coordinate " + quote_tok(f(2 + static_cast<std::size_t>(k))));
      }
    }
    if (!is_finite(p)) return r.err(c, "GRID " + std::to_string(id) + ": non-finite coordinate");
    m.nodes.push_back(p);
    m.node_ids.push_back(id);
    grid_line.push_back(static_cast<std::int64_t>(&c - cards.data()));
  }
  IdMap map;
  const std::int64_t dup = map.build(m.node_ids);
  if (dup >= 0) return r.err(cards[static_cast<std::size_t>(grid_line[static_cast<std::size_t>(dup)])], "duplicate GRID id " + std::to_string(m.node_ids[static_cast<std::size_t>(dup)]));
  std::map<std::int64_t, std::int32_t> pid_group;
  std::vector<std::int64_t> pids;
  std::vector<std::int64_t> where;
  std::uint32_t v[32];
  for (const Card* c : elems) {
    ElemType lin{}, quad{};
    int nlin = 0, nquad = 0, maxf = 0;
    element_kind(c->name, lin, quad, nlin, nquad, maxf);
    auto f = [&](std::size_t k) { return k < c->fields.size() ? c->fields[k] : std::string_view(); };
    std::int64_t eid = 0, pid = 0;
    if (!parse_int(f(0), eid) || eid <= 0) return r.err(*c, c->name + ": bad element id " + quote_tok(f(0)));
    if (f(1).empty()) {
      pid = eid;  // Nastran: a blank PID defaults to the element id
    } else if (!parse_int(f(1), pid)) {
      return r.err(*c, c->name + " " + std::to_string(eid) + ": bad property id " + quote_tok(f(1)));
    }
    int n = 0, given = 0;
    for (int k = 0; k < maxf; ++k) {
      const std::string_view g = f(2 + static_cast<std::size_t>(k));
      if (g.empty()) {
        if (k < nlin) return r.err(*c, c->name + " " + std::to_string(eid) + ": corner grid G" + std::to_string(k + 1) + " is blank");
        continue;
      }
      std::int64_t gid = 0;
      if (!parse_int(g, gid)) return r.err(*c, c->name + " " + std::to_string(eid) + ": bad grid id " + quote_tok(g));
      const std::int64_t idx = map.find(gid);
      if (idx < 0) return r.err(*c, c->name + " " + std::to_string(eid) + ": grid " + std::to_string(gid) + " is not defined");
      ++given;
      if (k != n) continue;  // after a blank mid-side grid: partial quadratic element
      v[n++] = static_cast<std::uint32_t>(idx);
    }
    ElemType t{};
    if (n == nquad && given == nquad) {
      t = quad;
    } else if (n >= nlin && given <= nquad) {
      // Linear, or quadratic with some mid-side grids blank (straight edges): read by its corners.
      t = lin;
      n = nlin;
    } else {
      return r.err(*c, c->name + " " + std::to_string(eid) + ": " + std::to_string(given) + " grids (expected " + std::to_string(nlin) + (nquad != nlin ? " to " + std::to_string(nquad) : std::string()) + ")");
    }
    permute(nastran_to_vtk(t), v, n);
    m.add_element(t, eid, -1, v, n);
    pids.push_back(pid);
    where.push_back(static_cast<std::int64_t>(c - cards.data()));
  }
  if (m.elem_types.empty()) return file_error(m.file, "no elements (CTETRA, CHEXA, CPENTA, CPYRAM, CTRIA3, CQUAD4, ...)");
  {
    std::int64_t first = -1;
    const std::int64_t d = find_duplicate(m.elem_ids, &first);
    if (d >= 0) return r.err(cards[static_cast<std::size_t>(where[static_cast<std::size_t>(d)])], "duplicate element id " + std::to_string(m.elem_ids[static_cast<std::size_t>(d)]));
  }
  // Groups by PID of the kept (highest-dimension) elements, in increasing PID order.
  for (std::size_t e = 0; e < m.elem_groups.size(); ++e) m.elem_groups[e] = static_cast<std::int32_t>(e);  // temporary: original index
  drop_lower_dimension(m, nullptr);
  if (!r.skipped_elements.empty()) {
    std::size_t total = 0;
    std::string names;
    for (const auto& [name, count] : r.skipped_elements) {
      total += count;
      names += (names.empty() ? "" : ", ") + name + " " + std::to_string(count);
    }
    m.warnings.insert(m.warnings.begin(), "skipped " + std::to_string(total) +
                                              " element cards without a surface (beams, rods, springs, masses, "
                                              "rigid elements: " + names + ")");
  }
  std::vector<std::int64_t> kept_pid(m.num_elements());
  for (std::size_t e = 0; e < m.num_elements(); ++e) kept_pid[e] = pids[static_cast<std::size_t>(m.elem_groups[e])];
  std::vector<std::int64_t> distinct = kept_pid;
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  const int top = elem_info(m.elem_types.front()).dim;
  for (std::int64_t p : distinct) {
    pid_group[p] = static_cast<std::int32_t>(m.groups.size());
    m.groups.push_back(FemGroup{.name = "PID " + std::to_string(p), .id = p, .dim = top});
  }
  for (std::size_t e = 0; e < m.num_elements(); ++e) m.elem_groups[e] = pid_group[kept_pid[e]];
  return m;
}

}  // namespace interfere::fem_io
