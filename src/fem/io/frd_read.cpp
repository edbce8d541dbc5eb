// CalculiX .frd results reader (issue #26, item 1): nodes (block 2C), elements (block 3C) and the
// nodal displacements (result blocks 100C whose dataset is DISP) of every step and increment, as
// one NodalSeries "DISP". Format: CalculiX GraphiX manual, "Result Format" (Model Header 1C, User
// Header 1U, Nodal Point Coordinate Block 2C, Element Definition Block 3C, Parameter Header 1P,
// Nodal Results Block 100C with its -4 dataset and -5 component records, end 9999), checked
// against the files ccx 2.20 writes (src/frd.c, frdheader.c, frdvector.c of CalculiX):
//
// - Text records are fixed-column Fortran records: the data lines `-1`/`-2` hold an id of 5
//   (short format, 0) or 10 (long format, 1) columns after the 3-column key, then reals of 12
//   columns each (`%12.5E` runs into its neighbour when negative, so numbers are cut by column).
// - Binary blocks (ccx writes them for *NODE OUTPUT / *EL OUTPUT instead of *NODE FILE / *EL
//   FILE): the header lines stay text, the data follows without the closing -3 record. Nodes:
//   format 2 (int32 id, 3 float32) or 3 (int32 id, 3 float64: what ccx writes); elements: format
//   2 (int32 id, type, group, material, node ids); results: format 2 (int32 node, one float32 per
//   stored component) or 3 (float64). Stored components are the -5 records whose IEXIST is not 1
//   (DISP announces 4 components, D1 D2 D3 and ALL, but ALL is computed, not stored).
// - Element types: 1 he8, 2 pe6, 3 te4, 4 he20, 5 pe15, 6 te10, 7 tr3, 8 tr6, 9 qu4, 10 qu8,
//   11 be2, 12 be3. ccx writes C3D20 and C3D15 with the mid-side nodes bottom, vertical, top
//   (frd.c: kon 0-11, 16-19, 12-15), which is Nastran's order: converted to VTK's with
//   nastran_to_vtk. Shells and beams are kept or dropped by dimension like every reader.
//
// Groups: the element's material number when the file has more than one (named by the 1UMAT
// header lines, else "material N"); with one material every element is ungrouped, so bodies come
// from connectivity. Each DISP block is one step (time = the 100C value; for ccx the total time of
// the increment); nodes absent from a block get zero displacement (counted in a warning).
//
// Speed (issue #26, item 7: a 10^6-element file with 10 steps in <= 2 s; docs/fem-benchmarks.md):
// the file is mapped (read_frd_file: mmap of a regular file, no copy; other files are read), the
// large arrays are allocated with transparent huge pages advised (on the 2-core VM of the
// benchmarks a fresh 4 KiB page costs several microseconds: a 10-step DISP series is 250 MB),
// numbers are parsed by an exact fast path (Clinger: at most 15 digits and |exponent| <= 22 give a
// correctly rounded double with one multiplication or division, as std::from_chars would; anything
// else goes to from_chars), and ASCII node, element and DISP blocks and binary DISP blocks are
// parsed in parallel chunks (oneTBB) when their records have one layout (what ccx writes). The parallel pass only accepts what the sequential reader accepts:
// on anything unusual it gives up, and the sequential reader reads the block again from its start
// and reports the error with its line, so errors and values do not depend on the path taken.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <map>
#include <set>

#include "scan.h"

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#define INTERFERE_FRD_MMAP 1
#endif

namespace interfere::fem_io {
namespace {

// ---------------------------------------------------------------- memory

/// Advises transparent huge pages for the 2 MiB-aligned pages inside [p, p + bytes) (Linux;
/// nothing elsewhere, or when THP is off): the pages are not touched yet, so they fault in 2 MiB
/// at a time.
void advise_huge(const void* p, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHuge = std::uintptr_t{1} << 21;
  if (bytes < 2 * kHuge) return;
  const auto a = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t b = (a + kHuge - 1) & ~(kHuge - 1), e = (a + bytes) & ~(kHuge - 1);
  if (e > b) (void)::madvise(reinterpret_cast<void*>(b), e - b, MADV_HUGEPAGE);
#else
  (void)p, (void)bytes;
#endif
}

/// reserve(n) with huge pages advised for the new storage.
template <class T>
void reserve_huge(std::vector<T>& v, std::size_t n) {
  if (n <= v.capacity()) return;
  v.reserve(n);
  advise_huge(v.data() + v.size(), (v.capacity() - v.size()) * sizeof(T));
}

// ---------------------------------------------------------------- numbers

constexpr double kPow10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                               1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

inline bool is_digit(char c) { return c >= '0' && c <= '9'; }

/// Whole token as a double, exactly as parse_double (std::from_chars) gives it: the fast path
/// takes [+-]digits[.digits][(E|e)[+-]digits] with at most 15 significant digits and a decimal
/// exponent within ±22, where m·10^x (or m/10^-x) of two exact doubles is one correctly rounded
/// operation (Clinger 1990); every other spelling goes to parse_double.
inline bool real_token(std::string_view f, double& out) {
  const char* p = f.data();
  const char* const e = p + f.size();
  // ccx's own spelling first, "[-]d.dddddE±dd" (%12.5E): the same arithmetic at fixed places.
  if (const std::size_t n = f.size(); (n == 11 || (n == 12 && *p == '-'))) {
    const char* q = p + (n - 11);
    if (q[1] == '.' && q[7] == 'E' && (q[8] == '+' || q[8] == '-') && is_digit(q[0]) && is_digit(q[2]) && is_digit(q[3]) &&
        is_digit(q[4]) && is_digit(q[5]) && is_digit(q[6]) && is_digit(q[9]) && is_digit(q[10])) {
      const std::uint64_t m = static_cast<std::uint64_t>(q[0] - '0') * 100000 + static_cast<std::uint64_t>(q[2] - '0') * 10000 +
                              static_cast<std::uint64_t>(q[3] - '0') * 1000 + static_cast<std::uint64_t>(q[4] - '0') * 100 +
                              static_cast<std::uint64_t>(q[5] - '0') * 10 + static_cast<std::uint64_t>(q[6] - '0');
      const int ex = (q[9] - '0') * 10 + (q[10] - '0');
      const int x = (q[8] == '-' ? -ex : ex) - 5;
      if (x >= -22 && x <= 22) {
        const double v = m == 0 ? 0.0 : x >= 0 ? static_cast<double>(m) * kPow10[x] : static_cast<double>(m) / kPow10[-x];
        out = n == 12 ? -v : v;
        return true;
      }
    }
  }
  bool neg = false;
  if (p < e && (*p == '-' || *p == '+')) neg = *p++ == '-';
  std::uint64_t m = 0;
  int sig = 0, x = 0;
  bool digits = false;
  for (; p < e && is_digit(*p); ++p) {
    digits = true;
    if (m == 0 && *p == '0') continue;
    m = m * 10 + static_cast<std::uint64_t>(*p - '0');
    ++sig;
  }
  if (p < e && *p == '.') {
    for (++p; p < e && is_digit(*p); ++p) {
      digits = true;
      --x;
      if (m == 0 && *p == '0') continue;
      m = m * 10 + static_cast<std::uint64_t>(*p - '0');
      ++sig;
    }
  }
  if (digits && sig <= 15 && p < e && (*p == 'E' || *p == 'e')) {
    ++p;
    bool eneg = false;
    if (p < e && (*p == '-' || *p == '+')) eneg = *p++ == '-';
    int ex = 0, nd = 0;
    for (; p < e && is_digit(*p) && nd < 6; ++p, ++nd) ex = ex * 10 + (*p - '0');
    if (nd == 0 || nd == 6) return parse_double(f, out);
    x += eneg ? -ex : ex;
  }
  if (!digits || sig > 15 || p != e) return parse_double(f, out);
  double v;
  if (m == 0) {
    v = 0;
  } else if (x >= 0 && x <= 22) {
    v = static_cast<double>(m) * kPow10[x];
  } else if (x < 0 && x >= -22) {
    v = static_cast<double>(m) / kPow10[-x];
  } else {
    return parse_double(f, out);
  }
  out = neg ? -v : v;
  return true;
}

/// Whole token as an integer, as parse_int gives it (fast path: [+-] and up to 18 digits).
inline bool int_token(std::string_view f, std::int64_t& out) {
  const char* p = f.data();
  const char* const e = p + f.size();
  bool neg = false;
  if (p < e && (*p == '-' || *p == '+')) neg = *p++ == '-';
  if (p == e || e - p > 18) return parse_int(f, out);
  std::int64_t v = 0;
  for (; p < e; ++p) {
    if (!is_digit(*p)) return parse_int(f, out);
    v = v * 10 + (*p - '0');
  }
  out = neg ? -v : v;
  return true;
}

bool frd_type(std::int64_t t, ElemType& out) {
  switch (t) {
    case 1: out = ElemType::hex8; return true;
    case 2: out = ElemType::wedge6; return true;
    case 3: out = ElemType::tet4; return true;
    case 4: out = ElemType::hex20; return true;
    case 5: out = ElemType::wedge15; return true;
    case 6: out = ElemType::tet10; return true;
    case 7: out = ElemType::tri3; return true;
    case 8: out = ElemType::tri6; return true;
    case 9: out = ElemType::quad4; return true;
    case 10: out = ElemType::quad8; return true;
    case 11: out = ElemType::line2; return true;
    case 12: out = ElemType::line3; return true;
    default: return false;
  }
}

/// Index of the first '\n' in s[p, n), or n: eight bytes at a time (the lines are short, so a
/// call of memchr per line cost more than the search).
inline std::size_t find_newline(const char* s, std::size_t p, std::size_t n) {
  if constexpr (std::endian::native == std::endian::little) {
    constexpr std::uint64_t kOnes = 0x0101010101010101ull, kHigh = 0x8080808080808080ull, kNl = 0x0A0A0A0A0A0A0A0Aull;
    for (; p + 8 <= n; p += 8) {
      std::uint64_t w;
      std::memcpy(&w, s + p, 8);
      const std::uint64_t x = w ^ kNl;
      // The lowest flagged byte is the first zero byte of x (a borrow only flags bytes above it).
      const std::uint64_t z = (x - kOnes) & ~x & kHigh;
      if (z) return p + static_cast<std::size_t>(std::countr_zero(z) >> 3);
    }
  }
  while (p < n && s[p] != '\n') ++p;
  return p;
}

/// Columns [b, b + w) of a record, trimmed; empty past the end of the line.
inline std::string_view column(std::string_view line, std::size_t b, std::size_t w) {
  if (b >= line.size()) return {};
  const char* p = line.data() + b;
  const char* e = p + std::min(w, line.size() - b);
  while (p < e && is_space(*p)) ++p;
  while (e > p && is_space(e[-1])) --e;
  return {p, static_cast<std::size_t>(e - p)};
}

struct Reader {
  std::string file;
  std::string_view s;
  Text t;
  FemMesh m;
  bool binary_seen = false;  // after binary data, positions are reported as bytes
  std::size_t line_pos = 0;  // byte offset of the current line
  std::int64_t line_no = 0;
  IdMap node_map;
  bool have_nodes = false, have_elements = false;
  std::vector<std::int64_t> where;     // per element: line or byte
  std::size_t elem_count = 0;          // the 3C header's count
  bool where_bytes = false;
  std::map<std::int64_t, std::string> mat_names;  // 1UMAT
  // The 1PSTEP record before a result block: load case counter, increment, step.
  std::int64_t p_counter = -1, p_inc = -1, p_step = -1;
  int result_blocks = 0;
  NodalSeries disp{.name = "DISP"};
  std::size_t missing = 0, missing_blocks = 0;

  Reader(std::string f, std::string_view bytes) : file(std::move(f)), s(bytes), t(bytes) { m.file = file; }

  /// The current line is the file's last and has no end of line: the file ends inside it.
  bool cut_inside_line() const { return t.at_end() && !s.empty() && s.back() != '\n'; }

  Error at(std::string reason) const {
    if (cut_inside_line() && reason.find("truncated") == std::string::npos) reason += " (the file ends inside this line: truncated)";
    return binary_seen ? byte_error(file, static_cast<std::int64_t>(line_pos), std::move(reason))
                       : line_error(file, line_no, std::move(reason));
  }
  Error at_byte(std::size_t b, std::string reason) const { return byte_error(file, static_cast<std::int64_t>(b), std::move(reason)); }

  /// Next line (false at the end of the file); keeps its position for messages.
  bool line(std::string_view& out) {
    line_pos = t.pos();
    if (line_pos >= s.size()) return false;
    std::size_t next = 0;
    out = line_at(line_pos, next);
    line_no = t.cur_line();
    t.set_pos(next, s[next - 1] == '\n' ? line_no + 1 : line_no);
    return true;
  }
  /// Resumes text reading at byte `pos` after binary data.
  void resume(std::size_t pos) {
    binary_seen = true;
    t.set_pos(pos, t.cur_line());
  }

  bool int_field(std::string_view f, std::int64_t& v) const { return !f.empty() && int_token(f, v); }
  bool real_field(std::string_view f, double& v) const { return !f.empty() && real_token(f, v); }

  /// Count and format of a 2C / 3C header: the two integers after the key.
  Status block_header(std::string_view l, const char* what, std::int64_t& count, std::int64_t& format) {
    Text h(l);
    (void)h.token();  // "2C" / "3C"
    const std::string_view c = h.token(), f = h.token();
    if (!int_field(c, count) || count < 0) return at(std::string(what) + " header: malformed count " + quote_tok(c));
    if (static_cast<std::uint64_t>(count) > s.size()) return at(std::string(what) + " header: implausible count " + std::to_string(count));
    format = 0;
    if (!f.empty() && !int_field(f, format)) return at(std::string(what) + " header: malformed format " + quote_tok(f));
    if (format < 0 || format > 3) return at(std::string(what) + " header: unknown format " + std::to_string(format) + " (0 short, 1 long, 2/3 binary)");
    return {};
  }

  /// The end of `count` records of `len` bytes each from the current position when a -3 record
  /// follows them there (the fixed-length records ccx writes), else 0.
  std::size_t fixed_end(std::size_t len, std::int64_t count) const {
    const std::size_t p0 = t.pos(), n = static_cast<std::size_t>(count);
    if (len == 0 || n == 0 || p0 >= s.size() || len > (s.size() - p0) / n) return 0;
    const std::size_t end = p0 + len * n;
    std::size_t nx = 0;
    return end < s.size() && s[end - 1] == '\n' && column(line_at(end, nx), 0, 3) == "-3" ? end : 0;
  }

  /// The line of `len` bytes at `b` (its end of line last, none inside), or false.
  bool fixed_line(std::size_t b, std::size_t len, std::string_view& l) const {
    const std::size_t e = b + len - 1;
    if (s[e] != '\n' || find_newline(s.data(), b, e) != e) return false;
    l = s.substr(b, e - b);
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    return true;
  }

  /// The `count` records of an ASCII node block in parallel when they have one length and a -3
  /// follows them; then the position is at the -3. False (arrays empty, position unchanged) on
  /// anything else, and the sequential loop reads the block and names the problem.
  bool parallel_nodes(std::size_t w, std::int64_t count, std::vector<std::int64_t>& node_where) {
    const std::size_t p0 = t.pos();
    if (p0 >= s.size()) return false;
    std::size_t next = 0;
    (void)line_at(p0, next);
    const std::size_t len = next - p0, n = static_cast<std::size_t>(count);
    const std::size_t end = fixed_end(len, count);
    if (end == 0) return false;
    const std::int64_t line0 = t.cur_line();
    m.nodes.resize(n), m.node_ids.resize(n), node_where.resize(n);
    std::atomic<bool> bad{false};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t k = r.begin(); k != r.end(); ++k) {
        std::string_view l;
        std::int64_t id = 0;
        double x[3] = {0, 0, 0};
        bool ok = !bad.load(std::memory_order_relaxed) && fixed_line(p0 + k * len, len, l) && column(l, 0, 3) == "-1" &&
                  int_field(column(l, 3, w), id);
        for (std::size_t c = 0; ok && c < 3; ++c) ok = real_field(column(l, 3 + w + 12 * c, 12), x[c]) && std::isfinite(x[c]);
        if (!ok) {
          bad.store(true, std::memory_order_relaxed);
          return;
        }
        m.nodes[k] = Vec3{x[0], x[1], x[2]};
        m.node_ids[k] = id;
        node_where[k] = line0 + static_cast<std::int64_t>(k);
      }
    });
    if (bad.load()) {
      m.nodes.clear(), m.node_ids.clear(), node_where.clear();
      return false;
    }
    t.set_pos(end, line0 + count);
    return true;
  }

  /// The `count` records of an ASCII element block in parallel when they all have the length,
  /// the lines and the element type of the first one and a -3 follows them; then the position is
  /// at the -3. False (element arrays empty, position unchanged) on anything else — another type,
  /// an unknown node, a malformed field —, and the sequential loop reads the block and names it.
  bool parallel_elements(std::size_t w, std::int64_t count) {
    const std::size_t p0 = t.pos();
    if (p0 >= s.size()) return false;
    // The first record: its -1 line, then -2 lines until its type's node count.
    std::size_t p = p0, nx = 0;
    std::string_view l = line_at(p, nx);
    std::int64_t type = 0;
    ElemType et{};
    if (column(l, 0, 3) != "-1" || !int_field(column(l, 3 + w, 5), type) || !frd_type(type, et)) return false;
    const std::size_t nn = static_cast<std::size_t>(elem_info(et).nodes);
    std::size_t got = 0, lines = 1;
    for (p = nx; got < nn; p = nx, ++lines) {
      if (p >= s.size()) return false;
      l = line_at(p, nx);
      if (column(l, 0, 3) != "-2") return false;
      for (std::size_t b = 3; b < l.size(); b += w) got += !column(l, b, w).empty();
    }
    if (got != nn) return false;
    const std::size_t len = p - p0, n = static_cast<std::size_t>(count);
    const std::size_t end = fixed_end(len, count);
    if (end == 0) return false;
    const std::int64_t line0 = t.cur_line();
    reserve_huge(m.elem_nodes, n * nn);
    m.elem_types.resize(n), m.elem_ids.resize(n), m.elem_groups.resize(n), m.elem_offsets.resize(n + 1);
    m.elem_nodes.resize(n * nn), where.resize(n);
    const int* perm = nastran_to_vtk(et);
    std::atomic<bool> bad{false};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t k = r.begin(); k != r.end(); ++k) {
        if (bad.load(std::memory_order_relaxed)) return;
        const std::size_t q0 = p0 + k * len, qe = q0 + len;
        std::size_t q = q0, e = 0;
        std::string_view h = line_at(q, e);
        std::int64_t id = 0, ty = 0, mat = 0;
        const std::string_view fm = column(h, 3 + w + 10, 5);
        bool ok = e <= qe && column(h, 0, 3) == "-1" && int_field(column(h, 3, w), id) && int_field(column(h, 3 + w, 5), ty) &&
                  ty == type && (fm.empty() || int_field(fm, mat)) && mat >= INT32_MIN && mat <= INT32_MAX;
        std::uint32_t v[32];
        std::size_t have = 0, nl = 1;
        for (q = e; ok && have < nn; q = e, ++nl) {
          const std::string_view d = q < qe ? line_at(q, e) : std::string_view();
          ok = q < qe && e <= qe && column(d, 0, 3) == "-2";
          for (std::size_t b = 3; ok && b < d.size(); b += w) {
            const std::string_view f = column(d, b, w);
            if (f.empty()) continue;
            std::int64_t node = 0;
            const std::int64_t idx = have < nn && int_field(f, node) ? node_map.find(node) : -1;
            ok = idx >= 0;
            if (ok) v[have++] = static_cast<std::uint32_t>(idx);
          }
        }
        if (!ok || have != nn || q != qe || nl != lines) {
          bad.store(true, std::memory_order_relaxed);
          return;
        }
        permute(perm, v, static_cast<int>(nn));
        m.elem_types[k] = et;
        m.elem_ids[k] = id;
        m.elem_groups[k] = static_cast<std::int32_t>(mat);
        m.elem_offsets[k + 1] = (k + 1) * nn;
        std::copy(v, v + nn, m.elem_nodes.begin() + static_cast<std::ptrdiff_t>(k * nn));
        where[k] = line0 + static_cast<std::int64_t>(k * lines);
      }
    });
    if (bad.load()) {
      m.elem_types.clear(), m.elem_ids.clear(), m.elem_groups.clear(), m.elem_nodes.clear(), where.clear();
      m.elem_offsets.assign(1, 0);
      return false;
    }
    t.set_pos(end, line0 + count * static_cast<std::int64_t>(lines));
    return true;
  }

  Status read_nodes(std::string_view header) {
    if (have_nodes) return at("a second node block (2C): one mesh per file is supported");
    std::int64_t count = 0, format = 0;
    if (Status st = block_header(header, "node block (2C)", count, format); !st) return st;
    reserve_huge(m.nodes, static_cast<std::size_t>(count));
    reserve_huge(m.node_ids, static_cast<std::size_t>(count));
    std::vector<std::int64_t> node_where;
    reserve_huge(node_where, static_cast<std::size_t>(count));
    if (format <= 1) {
      const std::size_t w = format == 0 ? 5 : 10;
      std::string_view l;
      const bool parallel = count >= kParallelRecords && parallel_nodes(w, count, node_where);
      for (std::int64_t k = 0; !parallel && k < count; ++k) {
        if (!line(l)) return at("node block (2C): the file ends after " + std::to_string(k) + " of " + std::to_string(count) + " nodes (truncated)");
        const std::string_view key = column(l, 0, 3);
        if (key == "-3") return at("node block (2C): -3 after " + std::to_string(k) + " nodes, the header says " + std::to_string(count) + " (wrong count)");
        if (key != "-1") return at("node block (2C): expected a node record (-1), found " + quote_tok(trim(l)));
        std::int64_t id = 0;
        const std::string_view fid = column(l, 3, w);
        if (!int_field(fid, id)) return at("node block (2C): malformed node id " + quote_tok(fid));
        Vec3 x{};
        for (int c = 0; c < 3; ++c) {
          const std::string_view f = column(l, 3 + w + 12 * static_cast<std::size_t>(c), 12);
          double v = 0;
          if (f.empty()) return at("node block (2C): node " + std::to_string(id) + ": the record ends before its " + "xyz"[c] + " coordinate (short or truncated line)");
          if (!real_field(f, v)) return at("node block (2C): node " + std::to_string(id) + ": malformed " + "xyz"[c] + " coordinate " + quote_tok(f));
          if (!std::isfinite(v)) return at("node block (2C): node " + std::to_string(id) + ": non-finite " + "xyz"[c] + " coordinate");
          x[c] = v;
        }
        m.nodes.push_back(x);
        m.node_ids.push_back(id);
        node_where.push_back(line_no);
      }
      if (!line(l)) return at("node block (2C): the file ends before its -3 record (truncated)");
      if (column(l, 0, 3) != "-3") return at("node block (2C): expected -3 after " + std::to_string(count) + " nodes, found " + quote_tok(trim(l)) + " (wrong count)");
    } else {
      const bool dbl = format == 3;
      Bytes in(s, t.pos());
      for (std::int64_t k = 0; k < count; ++k) {
        const std::size_t b = in.pos();
        std::int32_t id = 0;
        Vec3 x{};
        bool ok = in.get(id);
        for (int c = 0; c < 3 && ok; ++c) {
          if (dbl) {
            ok = in.get(x[c]);
          } else {
            float f = 0;
            ok = in.get(f);
            x[c] = f;
          }
        }
        if (!ok) return at_byte(b, "binary node block (2C): the file ends after " + std::to_string(k) + " of " + std::to_string(count) + " nodes (truncated)");
        if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2])) return at_byte(b, "binary node block (2C): node " + std::to_string(id) + ": non-finite coordinate");
        m.nodes.push_back(x);
        m.node_ids.push_back(id);
        node_where.push_back(static_cast<std::int64_t>(b));
      }
      resume(in.pos());
    }
    const std::int64_t dup = node_map.build(m.node_ids);
    if (dup >= 0) {
      const std::int64_t w = node_where[static_cast<std::size_t>(dup)];
      const std::string r = "duplicate node id " + std::to_string(m.node_ids[static_cast<std::size_t>(dup)]);
      return format >= 2 ? at_byte(static_cast<std::size_t>(w), r) : line_error(file, w, r);
    }
    have_nodes = true;
    return {};
  }

  Status add_element(std::int64_t id, std::int64_t type, std::int64_t mat, const std::vector<std::int64_t>& ids, std::int64_t loc) {
    ElemType et{};
    frd_type(type, et);
    std::uint32_t v[32];
    const int nn = elem_info(et).nodes;
    for (int q = 0; q < nn; ++q) {
      const std::int64_t idx = node_map.find(ids[static_cast<std::size_t>(q)]);
      if (idx < 0) return at("element block (3C): element " + std::to_string(id) + ": node " + std::to_string(ids[static_cast<std::size_t>(q)]) + " is not defined");
      v[q] = static_cast<std::uint32_t>(idx);
    }
    permute(nastran_to_vtk(et), v, nn);  // he20 / pe15: bottom, vertical, top -> VTK (see above)
    if (m.elem_nodes.empty()) reserve_huge(m.elem_nodes, elem_count * static_cast<std::size_t>(nn));  // by the first element's type
    if (mat < INT32_MIN || mat > INT32_MAX) return at("element block (3C): element " + std::to_string(id) + ": material number out of range");
    m.add_element(et, id, static_cast<std::int32_t>(mat), v, nn);  // (material, made a group later)
    where.push_back(loc);
    return {};
  }

  Status read_elements(std::string_view header) {
    if (have_elements) return at("a second element block (3C): one mesh per file is supported");
    if (!have_nodes) return at("element block (3C) before the node block (2C)");
    std::int64_t count = 0, format = 0;
    if (Status st = block_header(header, "element block (3C)", count, format); !st) return st;
    where_bytes = format >= 2;
    const auto n = static_cast<std::size_t>(count);
    reserve_huge(m.elem_types, n), reserve_huge(m.elem_ids, n), reserve_huge(m.elem_groups, n);
    reserve_huge(m.elem_offsets, n + 1), reserve_huge(where, n);
    elem_count = n;
    std::vector<std::int64_t> ids;
    if (format <= 1) {
      const std::size_t w = format == 0 ? 5 : 10;
      std::string_view l;
      const bool parallel = count >= kParallelRecords && parallel_elements(w, count);
      for (std::int64_t k = 0; !parallel && k < count; ++k) {
        if (!line(l)) return at("element block (3C): the file ends after " + std::to_string(k) + " of " + std::to_string(count) + " elements (truncated)");
        const std::string_view key = column(l, 0, 3);
        if (key == "-3") return at("element block (3C): -3 after " + std::to_string(k) + " elements, the header says " + std::to_string(count) + " (wrong count)");
        if (key != "-1") return at("element block (3C): expected an element record (-1), found " + quote_tok(trim(l)));
        std::int64_t id = 0, type = 0, mat = 0;
        const std::string_view fid = column(l, 3, w), ft = column(l, 3 + w, 5), fm = column(l, 3 + w + 10, 5);
        if (!int_field(fid, id)) return at("element block (3C): malformed element id " + quote_tok(fid));
        if (!int_field(ft, type)) return at("element block (3C): element " + std::to_string(id) + ": malformed type " + quote_tok(ft));
        if (!fm.empty() && !int_field(fm, mat)) return at("element block (3C): element " + std::to_string(id) + ": malformed material " + quote_tok(fm));
        ElemType et{};
        if (!frd_type(type, et)) return at("element block (3C): element " + std::to_string(id) + ": unknown frd element type " + std::to_string(type) + " (1-12: he8 pe6 te4 he20 pe15 te10 tr3 tr6 qu4 qu8 be2 be3)");
        const std::int64_t loc = line_no;
        const std::size_t nn = static_cast<std::size_t>(elem_info(et).nodes);
        ids.clear();
        while (ids.size() < nn) {
          if (!line(l)) return at("element block (3C): element " + std::to_string(id) + ": the file ends after " + std::to_string(ids.size()) + " of its " + std::to_string(nn) + " nodes (truncated)");
          if (column(l, 0, 3) != "-2") return at("element block (3C): element " + std::to_string(id) + ": expected a node list record (-2) after " + std::to_string(ids.size()) + " of " + std::to_string(nn) + " nodes, found " + quote_tok(trim(l)));
          for (std::size_t b = 3; b < l.size(); b += w) {
            const std::string_view f = column(l, b, w);
            if (f.empty()) continue;
            std::int64_t n = 0;
            if (!int_field(f, n)) return at("element block (3C): element " + std::to_string(id) + ": malformed node id " + quote_tok(f));
            if (ids.size() == nn) return at("element block (3C): element " + std::to_string(id) + ": more than the " + std::to_string(nn) + " nodes of a " + elem_info(et).name);
            ids.push_back(n);
          }
        }
        if (Status st = add_element(id, type, mat, ids, loc); !st) return st;
      }
      if (!line(l)) return at("element block (3C): the file ends before its -3 record (truncated)");
      if (column(l, 0, 3) != "-3") return at("element block (3C): expected -3 after " + std::to_string(count) + " elements, found " + quote_tok(trim(l)) + " (wrong count)");
    } else {
      if (format != 2) return at("element block (3C): binary elements have format 2, not " + std::to_string(format));
      Bytes in(s, t.pos());
      std::int32_t head[4], nodes[32];
      for (std::int64_t k = 0; k < count; ++k) {
        const std::size_t b = in.pos();
        if (!in.get_array(4, head)) return at_byte(b, "binary element block (3C): the file ends after " + std::to_string(k) + " of " + std::to_string(count) + " elements (truncated)");
        ElemType et{};
        if (!frd_type(head[1], et)) return at_byte(b, "binary element block (3C): element " + std::to_string(head[0]) + ": unknown frd element type " + std::to_string(head[1]) + " (binary: the rest of the block cannot be read)");
        const int nn = elem_info(et).nodes;
        if (!in.get_array(static_cast<std::size_t>(nn), nodes)) return at_byte(b, "binary element block (3C): element " + std::to_string(head[0]) + ": the file ends inside its node list (truncated)");
        ids.assign(nodes, nodes + nn);
        line_pos = b;
        binary_seen = true;
        if (Status st = add_element(head[0], head[1], head[3], ids, static_cast<std::int64_t>(b)); !st) return st;
      }
      resume(in.pos());
    }
    have_elements = true;
    return {};
  }

  /// The line starting at byte `p` (without its end of line); `next`: the byte after it.
  std::string_view line_at(std::size_t p, std::size_t& next) const {
    std::size_t e = find_newline(s.data(), p, s.size());
    next = e < s.size() ? e + 1 : e;
    if (e > p && s[e - 1] == '\r') --e;
    return s.substr(p, e - p);
  }

  static constexpr std::int64_t kParallelRecords = 4096;

  /// The `count` node records of an ASCII DISP block (one line each: `stored` <= 6), read in
  /// parallel chunks into u/seen; then the position is at the block's -3 record. False, with u
  /// and seen zero again and the position unchanged, unless exactly `count` well-formed records
  /// of distinct defined nodes with finite values precede a -3 record: the sequential reader then
  /// reads the block and names the problem (or reads what this pass does not take, such as
  /// records continued on -2 lines), so the result never depends on the path.
  bool parallel_disp(std::size_t w, std::int64_t stored, std::int64_t count, std::vector<Vec3>& u, std::vector<char>& seen) {
    const std::size_t p0 = t.pos();
    if (p0 >= s.size()) return false;
    std::size_t next = 0;
    auto is_end = [&](std::size_t p) {
      std::size_t nx = 0;
      return p < s.size() && s[p - 1] == '\n' && column(line_at(p, nx), 0, 3) == "-3";
    };
    // Where the records end: ccx's records have one length, so try that first; else count lines.
    (void)line_at(p0, next);
    const std::size_t len = next - p0, n = static_cast<std::size_t>(count);
    std::size_t end = len <= (s.size() - p0) / n ? p0 + len * n : s.size();
    if (!is_end(end)) {
      end = p0;
      for (std::size_t k = 0; k < n; ++k) {
        if (end >= s.size()) return false;
        (void)line_at(end, next);
        end = next;
      }
      if (!is_end(end)) return false;
    }
    // Chunks of about 1 MiB cut at line starts.
    const std::size_t bytes = end - p0, chunks = std::min<std::size_t>(4096, bytes / (1u << 20) + 1);
    std::vector<std::size_t> cut(chunks + 1, end);
    cut[0] = p0;
    for (std::size_t c = 1; c < chunks; ++c) {
      std::size_t q = std::max(cut[c - 1], p0 + bytes / chunks * c);
      if (q > p0 && q < end && s[q - 1] != '\n') {
        const void* nl = std::memchr(s.data() + q, '\n', end - q);
        q = nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - s.data()) + 1 : end;
      }
      cut[c] = std::min(q, end);
    }
    std::atomic<bool> bad{false};
    std::atomic<std::int64_t> records{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t c = r.begin(); c != r.end(); ++c) {
        std::int64_t here = 0;
        for (std::size_t p = cut[c], nx = 0; p < cut[c + 1]; p = nx) {
          if (bad.load(std::memory_order_relaxed)) return;
          const std::string_view l = line_at(p, nx);
          std::int64_t node = 0;
          double v[6];
          bool ok = column(l, 0, 3) == "-1" && int_field(column(l, 3, w), node);
          for (std::int64_t k = 0; ok && k < stored; ++k) ok = real_field(column(l, 3 + w + 12 * static_cast<std::size_t>(k), 12), v[k]);
          ok = ok && std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
          const std::int64_t idx = ok ? node_map.find(node) : -1;
          if (idx < 0 || std::atomic_ref<char>(seen[static_cast<std::size_t>(idx)]).exchange(1, std::memory_order_relaxed) != 0) {
            bad.store(true, std::memory_order_relaxed);
            return;
          }
          u[static_cast<std::size_t>(idx)] = Vec3{v[0], v[1], v[2]};
          ++here;
        }
        records.fetch_add(here, std::memory_order_relaxed);
      }
    });
    if (bad.load() || records.load() != count) {
      std::fill(u.begin(), u.end(), Vec3{});
      std::fill(seen.begin(), seen.end(), 0);
      return false;
    }
    t.set_pos(end, t.cur_line() + count);
    return true;
  }

  /// The `count` records (int32 node, then D1 D2 D3 and maybe more as float32 or float64) of a
  /// binary DISP block at byte `start`, in parallel chunks; false, with u and seen zero again, on
  /// any node that is unknown, repeated or has a non-finite value (the sequential loop then names it).
  bool parallel_binary_disp(std::size_t start, std::size_t rec, bool dbl, std::int64_t count, std::vector<Vec3>& u, std::vector<char>& seen) {
    std::atomic<bool> bad{false};
    const char* base = s.data() + start;
    tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, count, 16384), [&](const tbb::blocked_range<std::int64_t>& r) {
      for (std::int64_t k = r.begin(); k != r.end(); ++k) {
        const char* q = base + static_cast<std::size_t>(k) * rec;
        std::int32_t node;
        std::memcpy(&node, q, 4);
        double v[3];
        for (int c = 0; c < 3; ++c) {
          if (dbl) {
            std::memcpy(&v[c], q + 4 + 8 * c, 8);
          } else {
            float f;
            std::memcpy(&f, q + 4 + 4 * c, 4);
            v[c] = f;
          }
        }
        const std::int64_t idx = std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]) ? node_map.find(node) : -1;
        if (idx < 0 || std::atomic_ref<char>(seen[static_cast<std::size_t>(idx)]).exchange(1, std::memory_order_relaxed) != 0) {
          bad.store(true, std::memory_order_relaxed);
          return;
        }
        u[static_cast<std::size_t>(idx)] = Vec3{v[0], v[1], v[2]};
      }
    });
    if (!bad.load()) return true;
    std::fill(u.begin(), u.end(), Vec3{});
    std::fill(seen.begin(), seen.end(), 0);
    return false;
  }

  /// A 100C result block; DISP blocks become steps of `disp`, others are read past.
  Status read_results(std::string_view header) {
    ++result_blocks;
    std::string label = "result block " + std::to_string(result_blocks);
    if (p_step >= 0) label += " (step " + std::to_string(p_step) + ", increment " + std::to_string(p_inc) + ")";
    // (1X,' 100','C',6A1,E12.5,I12,20A1,I2,I5,10A1,I2): value cols 12-23, count 24-35, format 73-74.
    double value = 0;
    std::int64_t count = 0, format = 0;
    const std::string_view fv = column(header, 12, 12), fc = column(header, 24, 12), ff = column(header, 73, 2);
    if (!real_field(fv, value) || !std::isfinite(value)) return at(label + ": malformed 100C value (time) " + quote_tok(fv));
    if (!int_field(fc, count) || count < 0) return at(label + ": malformed 100C node count " + quote_tok(fc));
    if (static_cast<std::uint64_t>(count) > s.size()) return at(label + ": implausible node count " + std::to_string(count));
    if (ff.empty()) {
      format = 0;
    } else if (!int_field(ff, format) || format < 0 || format > 3) {
      return at(label + ": malformed 100C format " + quote_tok(ff) + " (0 short, 1 long, 2/3 binary)");
    }
    std::string_view l;
    // -4: (1X,I2,2X,8A1,2I5) name, component count, IRTYPE.
    if (!line(l)) return at(label + ": the file ends before its -4 record (truncated)");
    if (column(l, 0, 3) != "-4") return at(label + ": expected the dataset record (-4), found " + quote_tok(trim(l)));
    const std::string name(column(l, 5, 8));
    std::int64_t ncomps = 0, irtype = 1;
    if (!int_field(column(l, 13, 5), ncomps) || ncomps < 1 || ncomps > 1000) return at(label + ": malformed component count " + quote_tok(column(l, 13, 5)));
    if (const std::string_view fr = column(l, 18, 5); !fr.empty() && !int_field(fr, irtype)) return at(label + ": malformed IRTYPE " + quote_tok(fr));
    label = name + " " + label + " (time " + short_number(value) + ")";
    // -5 records (one per component; -6 records may follow them): stored unless IEXIST = 1.
    std::int64_t stored = 0;
    for (std::int64_t c = 0; c < ncomps;) {
      if (!line(l)) return at(label + ": the file ends in its component records (truncated)");
      const std::string_view key = column(l, 0, 3);
      if (key == "-6") continue;
      if (key != "-5") return at(label + ": expected component record " + std::to_string(c + 1) + " of " + std::to_string(ncomps) + " (-5), found " + quote_tok(trim(l)));
      std::int64_t iexist = 0;
      if (const std::string_view fe = column(l, 33, 5); !fe.empty() && !int_field(fe, iexist)) return at(label + ": malformed IEXIST " + quote_tok(fe));
      if (iexist != 1) ++stored;
      ++c;
    }
    const bool is_disp = name == "DISP";
    if (is_disp && stored < 3) return at(label + ": " + std::to_string(stored) + " stored components, a displacement needs 3");
    if (is_disp && irtype != 1) return at(label + ": material-dependent displacements (IRTYPE " + std::to_string(irtype) + ") are not supported");
    if (is_disp && !have_nodes) return at(label + ": displacements before the node block (2C)");
    std::vector<Vec3> u;
    std::vector<char> seen;
    if (is_disp) {
      reserve_huge(u, m.nodes.size());
      u.resize(m.nodes.size());
      seen.assign(m.nodes.size(), 0);
    }
    auto store = [&](std::int64_t node, const double* v, std::size_t b, bool bytes) -> Status {
      const std::int64_t idx = node_map.find(node);
      auto fail = [&](std::string r) { return bytes ? at_byte(b, std::move(r)) : at(std::move(r)); };
      if (idx < 0) return fail(label + ": node " + std::to_string(node) + " is not defined in the node block");
      if (seen[static_cast<std::size_t>(idx)]) return fail(label + ": node " + std::to_string(node) + " appears twice");
      for (int c = 0; c < 3; ++c) {
        if (!std::isfinite(v[c])) return fail(label + ": node " + std::to_string(node) + ": non-finite D" + std::to_string(c + 1));
      }
      seen[static_cast<std::size_t>(idx)] = 1;
      u[static_cast<std::size_t>(idx)] = Vec3{v[0], v[1], v[2]};
      return {};
    };
    if (format <= 1) {
      const std::size_t w = format == 0 ? 5 : 10;
      std::int64_t found = 0;
      std::vector<double> vals;
      const bool parallel = is_disp && stored <= 6 && count >= kParallelRecords && parallel_disp(w, stored, count, u, seen);
      if (parallel) {
        found = count;
        if (!line(l) || column(l, 0, 3) != "-3") return at(label + ": expected -3 (internal: the parallel pass ended elsewhere)");
      }
      while (!parallel) {
        if (!line(l)) return at(label + ": the file ends before its -3 record after " + std::to_string(found) + " of " + std::to_string(count) + " nodes (truncated)");
        const std::string_view key = column(l, 0, 3);
        if (key == "-3") break;
        if (!is_disp) continue;  // other datasets: read past
        if (key != "-1") return at(label + ": expected a node record (-1), found " + quote_tok(trim(l)));
        std::int64_t node = 0;
        const std::string_view fid = column(l, 3, w);
        if (!int_field(fid, node)) return at(label + ": malformed node id " + quote_tok(fid));
        // Values: 6 per record, continued on -2 records (generalized DISP: D4.. after D1-D3).
        vals.clear();
        std::string_view rec = l;
        while (true) {
          for (std::size_t b = 3 + w; b < rec.size() && static_cast<std::int64_t>(vals.size()) < stored; b += 12) {
            const std::string_view f = column(rec, b, 12);
            if (f.empty()) break;
            double v = 0;
            if (!real_field(f, v)) return at(label + ": node " + std::to_string(node) + ": malformed value " + quote_tok(f));
            vals.push_back(v);
          }
          if (static_cast<std::int64_t>(vals.size()) >= stored) break;
          if (!line(rec)) return at(label + ": node " + std::to_string(node) + ": the file ends inside its values (truncated)");
          if (column(rec, 0, 3) != "-2") return at(label + ": node " + std::to_string(node) + ": " + std::to_string(vals.size()) + " values, expected " + std::to_string(stored));
        }
        if (Status st = store(node, vals.data(), 0, false); !st) return st;
        ++found;
        if (found > count) return at(label + ": more node records than the " + std::to_string(count) + " of its 100C header (wrong count)");
      }
      if (is_disp && found != count) return at(label + ": " + std::to_string(found) + " node records, its 100C header says " + std::to_string(count) + " (wrong count)");
    } else {
      if (irtype != 1) return at(label + ": binary material-dependent data (IRTYPE " + std::to_string(irtype) + ") cannot be read past");
      const std::size_t sz = format == 3 ? 8 : 4;
      const std::size_t rec = 4 + static_cast<std::size_t>(stored) * sz;
      Bytes in(s, t.pos());
      const std::size_t start = in.pos();
      if (!is_disp) {
        if (static_cast<std::uint64_t>(count) > in.remaining() / rec) {
          return at_byte(start, label + ": binary block of " + std::to_string(count) + " nodes needs " + std::to_string(static_cast<std::uint64_t>(count) * rec) + " bytes, the file has " + std::to_string(in.remaining()) + " left (truncated)");
        }
        in.skip(static_cast<std::size_t>(count) * rec);
      } else {
        std::vector<double> vals(static_cast<std::size_t>(stored));
        const bool parallel = count >= kParallelRecords && static_cast<std::uint64_t>(count) <= in.remaining() / rec &&
                              parallel_binary_disp(start, rec, sz == 8, count, u, seen);
        if (parallel) in.skip(static_cast<std::size_t>(count) * rec);
        for (std::int64_t k = 0; !parallel && k < count; ++k) {
          const std::size_t b = in.pos();
          std::int32_t node = 0;
          bool ok = in.get(node);
          for (std::int64_t c = 0; c < stored && ok; ++c) {
            if (sz == 8) {
              ok = in.get(vals[static_cast<std::size_t>(c)]);
            } else {
              float f = 0;
              ok = in.get(f);
              vals[static_cast<std::size_t>(c)] = f;
            }
          }
          if (!ok) return at_byte(b, label + ": the file ends after " + std::to_string(k) + " of " + std::to_string(count) + " nodes (truncated)");
          if (Status st = store(node, vals.data(), b, true); !st) return st;
        }
      }
      resume(in.pos());
    }
    if (is_disp) {
      const auto absent = static_cast<std::size_t>(std::count(seen.begin(), seen.end(), 0));
      if (absent > 0) {
        missing += absent;
        ++missing_blocks;
      }
      disp.times.push_back(value);
      disp.values.push_back(std::move(u));
    }
    p_counter = p_inc = p_step = -1;
    return {};
  }

  Expected<FemMesh> run() {
    std::string_view l;
    bool ended = false;
    while (line(l)) {
      const std::string_view tl = trim(l);
      if (tl.empty()) continue;
      Text h(tl);
      const std::string_view key = h.token();
      if (key == "9999") {
        ended = true;
        break;
      }
      Status st;
      if (key.starts_with("1U")) {
        // 1UMAT: "    1UMAT" + I5 material number + name.
        if (key == "1UMAT") {
          std::int64_t n = 0;
          if (int_field(column(l, 9, 5), n)) mat_names[n] = std::string(column(l, 14, 80));
        }
      } else if (key.starts_with("1P")) {
        if (key == "1PSTEP") {
          std::int64_t a = 0, b = 0, c = 0;
          if (int_field(h.token(), a) && int_field(h.token(), b) && int_field(h.token(), c)) {
            p_counter = a, p_inc = b, p_step = c;
          }
        }
      } else if (key.starts_with("1C")) {
        // model header: nothing to keep
      } else if (key == "2C") {
        st = read_nodes(l);
      } else if (key == "3C") {
        st = read_elements(l);
      } else if (key.starts_with("100C")) {
        st = read_results(l);
      } else {
        st = at("unexpected record " + quote_tok(tl) + " (expected a block: 1C, 1U, 1P, 2C, 3C, 100C or 9999)");
      }
      if (!st) return st.error();
    }
    if (!have_nodes) return file_error(file, "no node block (2C): not a CalculiX .frd file, or an empty one");
    if (!have_elements || m.elem_types.empty()) return file_error(file, "no elements (element block 3C missing or empty)");
    if (!ended) m.warnings.push_back("no end record (9999): the file may be incomplete (a running or stopped job)");
    if (Status st = check_element_ids(m, where, where_bytes); !st) return st.error();
    drop_lower_dimension(m, &where);
    // Materials -> groups when there is more than one.
    // (Runs of one material are the rule: a set insert per run, not per element.)
    std::set<std::int32_t> mats;
    for (std::size_t e = 0; e < m.elem_groups.size(); ++e) {
      if (e == 0 || m.elem_groups[e] != m.elem_groups[e - 1]) mats.insert(m.elem_groups[e]);
    }
    if (mats.size() > 1) {
      std::map<std::int32_t, std::int32_t> index;
      const int dim = elem_info(m.elem_types[0]).dim;
      for (std::int32_t mat : mats) {
        auto it = mat_names.find(mat);
        std::string name = it != mat_names.end() && !it->second.empty() ? it->second : "material " + std::to_string(mat);
        index[mat] = static_cast<std::int32_t>(m.groups.size());
        m.groups.push_back(FemGroup{.name = std::move(name), .id = mat, .dim = dim});
      }
      std::int32_t last_mat = 0, last_group = -1;
      for (std::int32_t& g : m.elem_groups) {
        if (last_group < 0 || g != last_mat) last_mat = g, last_group = index[g];
        g = last_group;
      }
    } else {
      std::fill(m.elem_groups.begin(), m.elem_groups.end(), -1);
    }
    if (!disp.values.empty()) {
      if (missing > 0) {
        m.warnings.push_back("DISP: " + std::to_string(missing) + " (node, step) values absent in " + std::to_string(missing_blocks) + " of " +
                             std::to_string(disp.values.size()) + " steps, set to zero");
      }
      m.fields.push_back(std::move(disp));
    }
    return std::move(m);
  }
};

}  // namespace

Expected<FemMesh> read_frd(const std::string& file, std::string_view bytes) {
  Reader r(file, bytes);
  return r.run();
}

Expected<FemMesh> read_frd_file(const std::filesystem::path& path) {
#ifdef INTERFERE_FRD_MMAP
  // A regular file is mapped, not copied: a results file is large (10^6 elements and 10 steps in
  // ASCII: 0.7 GB), and copying it into fresh memory took longer than parsing it. (A file that
  // another process truncates while it is read would end the process with SIGBUS: ccx rewrites
  // its .frd when a new job starts.) Anything else — a pipe, a device, a small file — is read.
  constexpr off_t kMapMin = 1 << 20;
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd >= 0) {
    struct stat st {};
    const bool map = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size >= kMapMin;
    void* p = MAP_FAILED;
    const auto size = static_cast<std::size_t>(st.st_size);
#ifdef MAP_POPULATE
    if (map) p = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
#else
    if (map) p = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
#endif
    ::close(fd);
    if (p != MAP_FAILED) {
      Expected<FemMesh> m = read_frd(path.string(), std::string_view(static_cast<const char*>(p), size));
      ::munmap(p, size);
      return m;
    }
  }
#endif
  Expected<std::string> bytes = read_file_bytes(path);
  if (!bytes) return bytes.error();
  return read_frd(path.string(), *bytes);
}

}  // namespace interfere::fem_io
