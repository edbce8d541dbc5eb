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
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "scan.h"

namespace interfere::fem_io {
namespace {

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

/// Columns [b, b + w) of a record, trimmed; empty past the end of the line.
std::string_view column(std::string_view line, std::size_t b, std::size_t w) {
  if (b >= line.size()) return {};
  return trim(line.substr(b, w));
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
  bool where_bytes = false;
  std::map<std::int64_t, std::string> mat_names;  // 1UMAT
  // The 1PSTEP record before a result block: load case counter, increment, step.
  std::int64_t p_counter = -1, p_inc = -1, p_step = -1;
  int result_blocks = 0;
  NodalSeries disp{.name = "DISP"};
  std::size_t missing = 0, missing_blocks = 0;

  Reader(std::string f, std::string_view bytes) : file(std::move(f)), s(bytes), t(bytes) { m.file = file; }

  Error at(std::string reason) const {
    return binary_seen ? byte_error(file, static_cast<std::int64_t>(line_pos), std::move(reason))
                       : line_error(file, line_no, std::move(reason));
  }
  Error at_byte(std::size_t b, std::string reason) const { return byte_error(file, static_cast<std::int64_t>(b), std::move(reason)); }

  /// Next line (false at the end of the file); keeps its position for messages.
  bool line(std::string_view& out) {
    line_pos = t.pos();
    if (!t.next_line(out)) return false;
    line_no = t.line();
    return true;
  }
  /// Resumes text reading at byte `pos` after binary data.
  void resume(std::size_t pos) {
    binary_seen = true;
    t.set_pos(pos, t.cur_line());
  }

  bool int_field(std::string_view f, std::int64_t& v) const { return !f.empty() && parse_int(f, v); }
  bool real_field(std::string_view f, double& v) const { return !f.empty() && parse_double(f, v); }

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

  Status read_nodes(std::string_view header) {
    if (have_nodes) return at("a second node block (2C): one mesh per file is supported");
    std::int64_t count = 0, format = 0;
    if (Status st = block_header(header, "node block (2C)", count, format); !st) return st;
    m.nodes.reserve(static_cast<std::size_t>(count));
    m.node_ids.reserve(static_cast<std::size_t>(count));
    std::vector<std::int64_t> node_where;
    node_where.reserve(static_cast<std::size_t>(count));
    if (format <= 1) {
      const std::size_t w = format == 0 ? 5 : 10;
      std::string_view l;
      for (std::int64_t k = 0; k < count; ++k) {
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
          if (f.empty()) return at("node " + std::to_string(id) + ": the record ends before its " + "xyz"[c] + " coordinate (short or truncated line)");
          if (!real_field(f, v)) return at("node " + std::to_string(id) + ": malformed " + "xyz"[c] + " coordinate " + quote_tok(f));
          if (!std::isfinite(v)) return at("node " + std::to_string(id) + ": non-finite " + "xyz"[c] + " coordinate");
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
        if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2])) return at_byte(b, "node " + std::to_string(id) + ": non-finite coordinate");
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
      if (idx < 0) return at("element " + std::to_string(id) + ": node " + std::to_string(ids[static_cast<std::size_t>(q)]) + " is not defined");
      v[q] = static_cast<std::uint32_t>(idx);
    }
    permute(nastran_to_vtk(et), v, nn);  // he20 / pe15: bottom, vertical, top -> VTK (see above)
    if (mat < INT32_MIN || mat > INT32_MAX) return at("element " + std::to_string(id) + ": material number out of range");
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
    std::vector<std::int64_t> ids;
    if (format <= 1) {
      const std::size_t w = format == 0 ? 5 : 10;
      std::string_view l;
      for (std::int64_t k = 0; k < count; ++k) {
        if (!line(l)) return at("element block (3C): the file ends after " + std::to_string(k) + " of " + std::to_string(count) + " elements (truncated)");
        const std::string_view key = column(l, 0, 3);
        if (key == "-3") return at("element block (3C): -3 after " + std::to_string(k) + " elements, the header says " + std::to_string(count) + " (wrong count)");
        if (key != "-1") return at("element block (3C): expected an element record (-1), found " + quote_tok(trim(l)));
        std::int64_t id = 0, type = 0, mat = 0;
        const std::string_view fid = column(l, 3, w), ft = column(l, 3 + w, 5), fm = column(l, 3 + w + 10, 5);
        if (!int_field(fid, id)) return at("element block (3C): malformed element id " + quote_tok(fid));
        if (!int_field(ft, type)) return at("element " + std::to_string(id) + ": malformed type " + quote_tok(ft));
        if (!fm.empty() && !int_field(fm, mat)) return at("element " + std::to_string(id) + ": malformed material " + quote_tok(fm));
        ElemType et{};
        if (!frd_type(type, et)) return at("element " + std::to_string(id) + ": unknown frd element type " + std::to_string(type) + " (1-12: he8 pe6 te4 he20 pe15 te10 tr3 tr6 qu4 qu8 be2 be3)");
        const std::int64_t loc = line_no;
        const std::size_t nn = static_cast<std::size_t>(elem_info(et).nodes);
        ids.clear();
        while (ids.size() < nn) {
          if (!line(l)) return at("element " + std::to_string(id) + ": the file ends after " + std::to_string(ids.size()) + " of its " + std::to_string(nn) + " nodes (truncated)");
          if (column(l, 0, 3) != "-2") return at("element " + std::to_string(id) + ": expected a node list record (-2) after " + std::to_string(ids.size()) + " of " + std::to_string(nn) + " nodes, found " + quote_tok(trim(l)));
          for (std::size_t b = 3; b < l.size(); b += w) {
            const std::string_view f = column(l, b, w);
            if (f.empty()) continue;
            std::int64_t n = 0;
            if (!int_field(f, n)) return at("element " + std::to_string(id) + ": malformed node id " + quote_tok(f));
            if (ids.size() == nn) return at("element " + std::to_string(id) + ": more than the " + std::to_string(nn) + " nodes of a " + elem_info(et).name);
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
        if (!frd_type(head[1], et)) return at_byte(b, "element " + std::to_string(head[0]) + ": unknown frd element type " + std::to_string(head[1]) + " (binary: the rest of the block cannot be read)");
        const int nn = elem_info(et).nodes;
        if (!in.get_array(static_cast<std::size_t>(nn), nodes)) return at_byte(b, "element " + std::to_string(head[0]) + ": the file ends inside its node list (truncated)");
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
      u.assign(m.nodes.size(), Vec3{});
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
      while (true) {
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
        for (std::int64_t k = 0; k < count; ++k) {
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
    std::set<std::int32_t> mats(m.elem_groups.begin(), m.elem_groups.end());
    if (mats.size() > 1) {
      std::map<std::int32_t, std::int32_t> index;
      const int dim = elem_info(m.elem_types[0]).dim;
      for (std::int32_t mat : mats) {
        auto it = mat_names.find(mat);
        std::string name = it != mat_names.end() && !it->second.empty() ? it->second : "material " + std::to_string(mat);
        index[mat] = static_cast<std::int32_t>(m.groups.size());
        m.groups.push_back(FemGroup{.name = std::move(name), .id = mat, .dim = dim});
      }
      for (std::int32_t& g : m.elem_groups) g = index[g];
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

}  // namespace interfere::fem_io
