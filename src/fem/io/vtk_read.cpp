// Legacy VTK reader (VTK File Formats, "Simple Legacy Formats", versions 2.0 to 5.1):
// DATASET UNSTRUCTURED_GRID, ASCII or BINARY (big-endian), POINTS, CELLS in the old "n size"
// layout or 5.1's OFFSETS/CONNECTIVITY, CELL_TYPES, CELL_DATA/POINT_DATA with SCALARS (+
// LOOKUP_TABLE), VECTORS, NORMALS, FIELD arrays, METADATA blocks skipped.
#include <algorithm>

#include "vtk_common.h"

namespace interfere::fem_io {
namespace {

struct Reader {
  std::string file;
  std::string_view s;
  Text t;
  bool binary = false;
  VtkData d;

  Reader(std::string f, std::string_view bytes) : file(std::move(f)), s(bytes), t(bytes) {}
  Error at_line(std::string r) const { return line_error(file, t.line(), std::move(r)); }
  Error eof(std::string what) const { return line_error(file, t.cur_line(), "unexpected end of file, expected " + what); }

  static int type_size(std::string_view ty, bool& integer, bool& ok) {
    ok = true;
    integer = true;
    if (ty == "bit") { ok = false; return 0; }
    if (ty == "unsigned_char" || ty == "char") return 1;
    if (ty == "short" || ty == "unsigned_short") return 2;
    if (ty == "int" || ty == "unsigned_int") return 4;
    if (ty == "long" || ty == "unsigned_long" || ty == "vtktypeint64" || ty == "vtktypeuint64" || ty == "vtkidtype") return 8;
    integer = false;
    if (ty == "float") return 4;
    if (ty == "double") return 8;
    ok = false;
    return 0;
  }

  /// Reads `n` values of VTK type `ty` (ASCII tokens or big-endian binary after the current line).
  Status values(std::size_t n, std::string_view ty, VtkArray& a) {
    bool integer = false, ok = false;
    const int size = type_size(to_lower(ty), integer, ok);
    if (!ok) return at_line("unsupported data type " + quote_tok(ty));
    a.integer = integer;
    if (n > s.size()) return at_line("implausible count " + std::to_string(n));
    if (integer) a.ints.resize(n); else a.reals.resize(n);
    if (!binary) {
      for (std::size_t i = 0; i < n; ++i) {
        const std::string_view tok = t.token();
        if (tok.empty()) return eof(std::to_string(n) + " values, found " + std::to_string(i));
        if (integer) {
          if (!parse_int(tok, a.ints[i])) return at_line("malformed integer " + quote_tok(tok));
        } else if (!parse_double(tok, a.reals[i])) {
          return at_line("malformed number " + quote_tok(tok));
        }
      }
      return {};
    }
    t.skip_line();
    const std::size_t start = t.pos();
    Bytes in(s, start, true);
    if (n > in.remaining() / static_cast<std::size_t>(size)) return byte_error(file, static_cast<std::int64_t>(start), "truncated binary block (" + std::to_string(n) + " values of " + std::string(ty) + ")");
    const std::string lt = to_lower(ty);
    auto take = [&](auto zero) {
      for (std::size_t i = 0; i < n; ++i) {
        decltype(zero) v = zero;
        in.get(v);
        if (integer) a.ints[i] = static_cast<std::int64_t>(v); else a.reals[i] = static_cast<double>(v);
      }
    };
    if (lt == "float") take(0.0f);
    else if (lt == "double") take(0.0);
    else if (lt == "char") take(std::int8_t{0});
    else if (lt == "unsigned_char") take(std::uint8_t{0});
    else if (lt == "short") take(std::int16_t{0});
    else if (lt == "unsigned_short") take(std::uint16_t{0});
    else if (lt == "int") take(std::int32_t{0});
    else if (lt == "unsigned_int") take(std::uint32_t{0});
    else if (lt == "vtktypeuint64" || lt == "unsigned_long") take(std::uint64_t{0});
    else take(std::int64_t{0});
    const std::int64_t lines = line_of(s.substr(start), in.pos() - start) - 1;
    t.set_pos(in.pos(), t.cur_line() + lines);
    return {};
  }

  Status count(std::int64_t& v, const char* what) {
    const std::string_view tok = t.token();
    if (tok.empty()) return eof(what);
    if (!parse_int(tok, v) || v < 0) return at_line(std::string("malformed ") + what + " " + quote_tok(tok));
    if (static_cast<std::uint64_t>(v) > s.size()) return at_line(std::string("implausible ") + what + " " + std::to_string(v));
    return {};
  }

  /// Skips a METADATA block (up to an empty line).
  void skip_metadata() {
    t.skip_line();
    std::string_view line;
    while (t.next_line(line)) {
      if (trim(line).empty()) break;
    }
  }

  Status field(std::size_t n_expected, std::vector<VtkArray>* out) {
    std::string_view name = t.token();
    std::int64_t k = 0;
    Status st = count(k, "number of FIELD arrays");
    if (!st) return st;
    (void)name;
    for (std::int64_t i = 0; i < k; ++i) {
      std::string_view an = t.token();
      if (an == "METADATA") {
        skip_metadata();
        an = t.token();
      }
      if (an.empty()) return eof("a FIELD array");
      const std::int64_t line = t.line();
      std::int64_t nc = 0, nt = 0;
      if (!(st = count(nc, "number of components")) || !(st = count(nt, "number of tuples"))) return st;
      const std::string_view ty = t.token();
      VtkArray a{.name = std::string(an), .components = static_cast<int>(nc), .where = line};
      if (nc < 1) return at_line("FIELD array with 0 components");
      if (!(st = values(static_cast<std::size_t>(nc * nt), ty, a))) return st;
      if (out && static_cast<std::size_t>(nt) == n_expected) out->push_back(std::move(a));
    }
    return {};
  }

  Status run() {
    std::string_view line;
    t.next_line(line);
    if (!istarts_with(trim(line), "# vtk DataFile")) return line_error(file, 1, "not a legacy VTK file (no '# vtk DataFile' header)");
    if (!t.next_line(line)) return eof("a title line");
    if (!t.next_line(line)) return eof("ASCII or BINARY");
    const std::string_view mode = trim(line);
    if (iequals(mode, "BINARY")) binary = true;
    else if (!iequals(mode, "ASCII")) return at_line("expected ASCII or BINARY, found " + quote_tok(mode));
    std::string_view tok = t.token();
    if (!iequals(tok, "DATASET")) return tok.empty() ? eof("DATASET") : at_line("expected DATASET, found " + quote_tok(tok));
    tok = t.token();
    if (!iequals(tok, "UNSTRUCTURED_GRID")) return at_line("only DATASET UNSTRUCTURED_GRID is supported, found " + quote_tok(tok));
    std::int64_t np = -1, nc = -1;
    std::vector<VtkArray>* data = nullptr;
    std::size_t data_n = 0;
    Status st;
    for (;;) {
      tok = t.token();
      if (tok.empty()) break;
      const std::string key = to_lower(tok);
      if (key == "points") {
        if (!(st = count(np, "number of points"))) return st;
        const std::string_view ty = t.token();
        VtkArray a;
        if (!(st = values(3 * static_cast<std::size_t>(np), ty, a))) return st;
        if (a.integer) {
          d.points.assign(a.ints.begin(), a.ints.end());
        } else {
          d.points = std::move(a.reals);
        }
      } else if (key == "cells") {
        d.cells_where = t.line();
        std::int64_t n = 0, size = 0;
        if (!(st = count(n, "number of cells")) || !(st = count(size, "cells size"))) return st;
        // 5.1 layout when the next token is OFFSETS (peeked without consuming binary data).
        const std::size_t after = t.pos();
        std::size_t q = after;
        while (q < s.size() && is_space(s[q])) ++q;
        if (istarts_with(s.substr(q, 7), "OFFSETS")) {
          tok = t.token();  // 5.1: n = cells + 1 offsets, size = connectivity length
          if (n < 1) return at_line("OFFSETS needs at least one value");
          const std::string_view ty = t.token();
          VtkArray off, conn;
          if (!(st = values(static_cast<std::size_t>(n), ty, off))) return st;
          tok = t.token();
          if (!iequals(tok, "CONNECTIVITY")) return at_line("expected CONNECTIVITY, found " + quote_tok(tok));
          const std::string_view ty2 = t.token();
          if (!(st = values(static_cast<std::size_t>(size), ty2, conn))) return st;
          if (!off.integer || !conn.integer) return at_line("OFFSETS/CONNECTIVITY must be integers");
          if (off.ints.front() != 0) return line_error(file, d.cells_where, "OFFSETS must start at 0");
          d.offsets.assign(off.ints.begin() + 1, off.ints.end());
          d.connectivity = std::move(conn.ints);
          nc = n - 1;
        } else {
          // Old layout: n records "count i0 i1 ...", size values in all.
          VtkArray all;
          if (binary) {
            if (!(st = values(static_cast<std::size_t>(size), "int", all))) return st;
          } else {
            if (!(st = values(static_cast<std::size_t>(size), "vtkIdType", all))) return st;
          }
          std::size_t p = 0;
          if (size < n) return line_error(file, d.cells_where, "CELLS: size " + std::to_string(size) + " is smaller than the " + std::to_string(n) + " cell counts it must hold");
          d.connectivity.reserve(static_cast<std::size_t>(size - n));
          for (std::int64_t c = 0; c < n; ++c) {
            if (p >= all.ints.size()) return line_error(file, d.cells_where, "CELLS: size " + std::to_string(size) + " is too small for " + std::to_string(n) + " cells");
            const std::int64_t k = all.ints[p++];
            if (k < 0 || static_cast<std::uint64_t>(k) > all.ints.size() - p) return line_error(file, d.cells_where, "cell " + std::to_string(c) + ": bad point count " + std::to_string(k));
            d.connectivity.insert(d.connectivity.end(), all.ints.begin() + static_cast<std::ptrdiff_t>(p), all.ints.begin() + static_cast<std::ptrdiff_t>(p + static_cast<std::size_t>(k)));
            p += static_cast<std::size_t>(k);
            d.offsets.push_back(static_cast<std::int64_t>(d.connectivity.size()));
          }
          if (p != all.ints.size()) return line_error(file, d.cells_where, "CELLS: size " + std::to_string(size) + " does not match the cells (" + std::to_string(p) + " values used)");
          nc = n;
        }
      } else if (key == "cell_types") {
        d.types_where = t.line();
        std::int64_t n = 0;
        if (!(st = count(n, "number of cell types"))) return st;
        VtkArray a;
        if (!(st = values(static_cast<std::size_t>(n), "int", a))) return st;
        d.types = std::move(a.ints);
      } else if (key == "cell_data" || key == "point_data") {
        std::int64_t n = 0;
        if (!(st = count(n, "number of values"))) return st;
        const bool cell = key == "cell_data";
        if (cell ? n != nc : n != np) return at_line(std::string(cell ? "CELL_DATA " : "POINT_DATA ") + std::to_string(n) + " does not match the " + std::to_string(cell ? nc : np) + (cell ? " cells" : " points"));
        data = cell ? &d.cell_arrays : &d.point_arrays;
        data_n = static_cast<std::size_t>(n);
      } else if (key == "scalars" || key == "vectors" || key == "normals") {
        if (!data) return at_line(std::string(tok) + " outside CELL_DATA/POINT_DATA");
        const std::int64_t line = t.line();
        const std::string_view name = t.token();
        const std::string_view ty = t.token();
        std::int64_t comps = key == "scalars" ? 1 : 3;
        if (key == "scalars") {
          // Optional component count on the same line.
          const std::size_t save = t.pos();
          const std::int64_t save_line = t.cur_line();
          const std::string_view maybe = t.token();
          std::int64_t c = 0;
          if (t.line() == line && parse_int(maybe, c) && c >= 1 && c <= 4) comps = c;
          else t.set_pos(save, save_line);
          const std::size_t save2 = t.pos();
          const std::int64_t save2_line = t.cur_line();
          const std::string_view lt = t.token();
          if (iequals(lt, "LOOKUP_TABLE")) {
            t.token();
          } else {
            t.set_pos(save2, save2_line);
          }
        }
        VtkArray a{.name = std::string(name), .components = static_cast<int>(comps), .where = line};
        if (!(st = values(data_n * static_cast<std::size_t>(comps), ty, a))) return st;
        data->push_back(std::move(a));
      } else if (key == "tensors" || key == "texture_coordinates" || key == "color_scalars") {
        // Read past (not used): 9 values per tuple, `dim` per tuple, or `n` per tuple.
        if (!data) return at_line(std::string(tok) + " outside CELL_DATA/POINT_DATA");
        t.token();  // name
        std::int64_t per = 9;
        std::string ty = "float";
        if (key == "tensors") {
          ty = std::string(t.token());
        } else {
          if (!(st = count(per, key == "color_scalars" ? "number of color values" : "texture dimension"))) return st;
          if (per < 1 || per > 16) return at_line("bad component count " + std::to_string(per));
          if (key == "texture_coordinates") ty = std::string(t.token());
          else if (binary) ty = "unsigned_char";
        }
        VtkArray skip;
        if (!(st = values(data_n * static_cast<std::size_t>(per), ty, skip))) return st;
      } else if (key == "field") {
        if (!(st = field(data ? data_n : static_cast<std::size_t>(-1), data))) return st;
      } else if (key == "metadata") {
        skip_metadata();
      } else if (key == "lookup_table") {
        t.token();
        std::int64_t n = 0;
        if (!(st = count(n, "lookup table size"))) return st;
        VtkArray a;
        if (binary) {
          t.skip_line();
          Bytes in(s, t.pos());
          if (!in.skip(4 * static_cast<std::size_t>(n))) return byte_error(file, static_cast<std::int64_t>(t.pos()), "truncated LOOKUP_TABLE");
          t.set_pos(in.pos(), t.cur_line());
        } else if (!(st = values(4 * static_cast<std::size_t>(n), "float", a))) {
          return st;
        }
      } else {
        return at_line("unsupported legacy VTK keyword " + quote_tok(tok));
      }
    }
    if (np < 0) return file_error(file, "no POINTS");
    if (nc < 0) return file_error(file, "no CELLS");
    if (d.types.size() != static_cast<std::size_t>(nc)) return line_error(file, d.types_where >= 0 ? d.types_where : d.cells_where, "CELL_TYPES has " + std::to_string(d.types.size()) + " entries for " + std::to_string(nc) + " cells");
    return {};
  }
};

}  // namespace

Expected<FemMesh> read_vtk_legacy(const std::string& file, std::string_view bytes) {
  Reader r(file, bytes);
  Status st = r.run();
  if (!st) return st.error();
  return build_vtk_mesh(file, std::move(r.d), false);
}

}  // namespace interfere::fem_io
