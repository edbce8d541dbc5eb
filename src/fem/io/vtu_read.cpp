// VTK XML UnstructuredGrid (.vtu) reader (VTK File Formats, "XML File Formats": VTKFile,
// UnstructuredGrid, Piece, Points, Cells, PointData, CellData, DataArray, AppendedData).
// DataArray formats: ascii, binary (base64; header UInt32 or UInt64) and appended (raw or
// base64), uncompressed or zlib-compressed (vtkZLibDataCompressor: header [#blocks, block size,
// last block size, compressed sizes...] then the deflate blocks); types Int8..UInt64,
// Float32/64; little- and big-endian. Several pieces are concatenated.
#include <zlib.h>

#include <algorithm>
#include <map>

#include "vtk_common.h"
#include "xml.h"

namespace interfere::fem_io {
namespace {

enum class Scalar { i8, u8, i16, u16, i32, u32, i64, u64, f32, f64, bad };

Scalar scalar_of(const std::string& t) {
  static const std::pair<const char*, Scalar> kTypes[] = {
      {"Int8", Scalar::i8},   {"UInt8", Scalar::u8},   {"Int16", Scalar::i16},   {"UInt16", Scalar::u16},  {"Int32", Scalar::i32},
      {"UInt32", Scalar::u32}, {"Int64", Scalar::i64}, {"UInt64", Scalar::u64}, {"Float32", Scalar::f32}, {"Float64", Scalar::f64},
      {"Char", Scalar::i8},   {"Int", Scalar::i32},    {"Float", Scalar::f32},   {"Double", Scalar::f64}, {"vtkIdType", Scalar::i64}};
  for (auto [n, s] : kTypes) {
    if (t == n) return s;
  }
  return Scalar::bad;
}
std::size_t scalar_size(Scalar s) {
  switch (s) {
    case Scalar::i8: case Scalar::u8: return 1;
    case Scalar::i16: case Scalar::u16: return 2;
    case Scalar::i32: case Scalar::u32: case Scalar::f32: return 4;
    default: return 8;
  }
}
bool scalar_integer(Scalar s) { return s != Scalar::f32 && s != Scalar::f64; }

int b64_value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

/// Decodes base64 (whitespace ignored, stops after padding). Returns the index of the first bad
/// character, or -1. `used` = characters consumed (including padding).
std::int64_t b64_decode(std::string_view s, std::string& out, std::size_t* used = nullptr) {
  out.clear();
  out.reserve(s.size() / 4 * 3);
  std::uint32_t acc = 0;
  int bits = 0;
  std::size_t i = 0;
  for (; i < s.size(); ++i) {
    const char c = s[i];
    if (is_space(c)) continue;
    if (c == '=') {
      while (i < s.size() && (s[i] == '=' || is_space(s[i]))) ++i;
      break;
    }
    const int v = b64_value(c);
    if (v < 0) return static_cast<std::int64_t>(i);
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += static_cast<char>((acc >> bits) & 0xff);
    }
  }
  if (used) *used = i;
  return -1;
}

/// Position after `chars` non-space characters of s.
std::size_t skip_chars(std::string_view s, std::size_t chars) {
  std::size_t i = 0, k = 0;
  while (i < s.size() && k < chars) {
    if (!is_space(s[i])) ++k;
    ++i;
  }
  return i;
}

struct Ctx {
  std::string file;
  std::string_view s;
  const XmlDocument* doc;
  bool big = false;
  bool u64_header = false;
  bool zlib = false;
  Error err(std::size_t at, std::string r) const { return byte_error(file, static_cast<std::int64_t>(at), std::move(r)); }
};

/// Header values in the file's byte order.
bool header_values(const Ctx& c, std::string_view bytes, std::size_t count, std::vector<std::uint64_t>& out) {
  const std::size_t hs = c.u64_header ? 8 : 4;
  if (bytes.size() < hs * count) return false;
  out.resize(count);
  Bytes in(bytes, 0, c.big);
  for (std::size_t k = 0; k < count; ++k) {
    if (c.u64_header) {
      in.get(out[k]);
    } else {
      std::uint32_t v = 0;
      in.get(v);
      out[k] = v;
    }
  }
  return true;
}

/// Inflates the blocks described by `header` from `data` into `out`.
bool inflate_blocks(const std::vector<std::uint64_t>& h, std::string_view data, std::string& out, std::string& why) {
  const std::uint64_t nb = h[0], bs = h[1], last = h[2];
  std::uint64_t pos = 0;
  out.clear();
  // zlib cannot expand more than ~1032:1: refuse headers announcing more (corrupt or hostile).
  {
    std::uint64_t in_total = 0, out_total = 0;
    for (std::uint64_t b = 0; b < nb; ++b) {
      in_total += h[3 + b];
      out_total += (b + 1 == nb && last != 0) ? last : bs;
    }
    if (out_total > 1100 * in_total + 4096) {
      why = "zlib header announces " + std::to_string(out_total) + " bytes from " + std::to_string(in_total) + " compressed bytes";
      return false;
    }
  }
  for (std::uint64_t b = 0; b < nb; ++b) {
    const std::uint64_t cs = h[3 + b];
    const std::uint64_t us = (b + 1 == nb && last != 0) ? last : bs;
    if (cs > data.size() - pos || pos > data.size()) {
      why = "zlib block " + std::to_string(b) + " is truncated";
      return false;
    }
    if (us > (1ull << 32)) {
      why = "implausible zlib block size";
      return false;
    }
    const std::size_t at = out.size();
    out.resize(at + us);
    uLongf got = static_cast<uLongf>(us);
    const int r = uncompress(reinterpret_cast<Bytef*>(out.data() + at), &got, reinterpret_cast<const Bytef*>(data.data() + pos), static_cast<uLong>(cs));
    if (r != Z_OK || got != us) {
      why = "zlib block " + std::to_string(b) + ": " + (r == Z_OK ? "wrong size" : "corrupt data (zlib error " + std::to_string(r) + ")");
      return false;
    }
    pos += cs;
  }
  return true;
}

/// The raw bytes of a binary (base64) or appended DataArray.
Status array_bytes(const Ctx& c, const XmlNode& da, std::string& out) {
  const std::string* fmt = da.attr("format");
  const std::size_t hs = c.u64_header ? 8 : 4;
  std::vector<std::uint64_t> h;
  std::string why;
  const bool appended = fmt && *fmt == "appended";
  const bool base64 = !appended || c.doc->appended_encoding == "base64";
  std::string_view src;
  std::size_t src_at = 0;
  if (appended) {
    if (c.doc->appended == std::string_view::npos) return c.err(da.offset, "appended DataArray but no <AppendedData>");
    const std::string* off = da.attr("offset");
    std::int64_t o = 0;
    if (!off || !parse_int(*off, o) || o < 0) return c.err(da.offset, "appended DataArray without a valid offset");
    src_at = c.doc->appended + static_cast<std::size_t>(o);
    if (src_at > c.s.size()) return c.err(da.offset, "truncated appended data: offset " + std::to_string(o) + " is past the end of the file");
    src = c.s.substr(src_at);
  } else {
    src = da.text;
    src_at = da.text_offset;
  }
  if (!base64) {  // appended raw
    if (!c.zlib) {
      if (!header_values(c, src, 1, h)) return c.err(src_at, "truncated appended data header");
      if (h[0] > src.size() - hs) return c.err(src_at, "truncated appended data (" + std::to_string(h[0]) + " bytes announced)");
      out.assign(src.substr(hs, h[0]));
      return {};
    }
    if (!header_values(c, src, 1, h)) return c.err(src_at, "truncated compression header");
    if (h[0] > src.size() / hs) return c.err(src_at, "truncated compression header");
    if (!header_values(c, src, 3 + h[0], h)) return c.err(src_at, "truncated compression header");
    std::uint64_t total = 0;
    for (std::size_t b = 0; b < h[0]; ++b) total += h[3 + b];
    if (total > src.size()) return c.err(src_at, "truncated compressed appended data");
    if (!inflate_blocks(h, src.substr(hs * (3 + h[0])), out, why)) return c.err(src_at, why);
    return {};
  }
  // base64
  std::string head;
  const std::size_t head_chars = (hs + 2) / 3 * 4;
  const std::size_t cut = skip_chars(src, head_chars);
  std::int64_t bad = b64_decode(src.substr(0, cut), head);
  if (bad >= 0) return c.err(src_at + static_cast<std::size_t>(bad), "bad base64 character " + quote_tok(src.substr(static_cast<std::size_t>(bad), 1)));
  if (!c.zlib) {
    // Header and data encoded together (one stream) or separately (header padded).
    std::string all;
    std::string_view trimmed = trim(src.substr(0, cut));
    const bool separate = !trimmed.empty() && trimmed.back() == '=';
    if (!header_values(c, head, 1, h)) return c.err(src_at, "truncated base64 header");
    if (separate) {
      std::string_view rest = src.substr(cut);
      if (appended) rest = rest.substr(0, std::min(rest.size(), ((h[0] + 2) / 3 * 4) * 2 + 64));
      bad = b64_decode(rest, all);
      if (bad >= 0) return c.err(src_at + cut + static_cast<std::size_t>(bad), "bad base64 character");
      if (all.size() < h[0]) return c.err(src_at, "truncated base64 data (" + std::to_string(h[0]) + " bytes announced, " + std::to_string(all.size()) + " present)");
      out.assign(all, 0, h[0]);
    } else {
      std::string_view whole = src;
      if (appended) whole = whole.substr(0, std::min(whole.size(), skip_chars(whole, (h[0] + hs + 2) / 3 * 4)));
      bad = b64_decode(whole, all);
      if (bad >= 0) return c.err(src_at + static_cast<std::size_t>(bad), "bad base64 character " + quote_tok(whole.substr(static_cast<std::size_t>(bad), 1)));
      if (all.size() < hs + h[0]) return c.err(src_at, "truncated base64 data (" + std::to_string(h[0]) + " bytes announced)");
      out.assign(all, hs, h[0]);
    }
    return {};
  }
  if (!header_values(c, head, 1, h)) return c.err(src_at, "truncated compression header");
  const std::uint64_t nb = h[0];
  if (nb > src.size()) return c.err(src_at, "implausible number of zlib blocks " + std::to_string(nb));
  const std::size_t hchars = (hs * (3 + nb) + 2) / 3 * 4;
  const std::size_t hcut = skip_chars(src, hchars);
  bad = b64_decode(src.substr(0, hcut), head);
  if (bad >= 0) return c.err(src_at + static_cast<std::size_t>(bad), "bad base64 character");
  if (!header_values(c, head, 3 + nb, h)) return c.err(src_at, "truncated compression header");
  std::uint64_t total = 0;
  for (std::size_t b = 0; b < nb; ++b) total += h[3 + b];
  std::string_view rest = src.substr(hcut);
  if (appended) rest = rest.substr(0, std::min(rest.size(), skip_chars(rest, (total + 2) / 3 * 4)));
  std::string data;
  bad = b64_decode(rest, data);
  if (bad >= 0) return c.err(src_at + hcut + static_cast<std::size_t>(bad), "bad base64 character " + quote_tok(rest.substr(static_cast<std::size_t>(bad), 1)));
  if (!inflate_blocks(h, data, out, why)) return c.err(src_at, why);
  return {};
}

template <class T>
void convert(std::string_view b, bool big, std::size_t n, bool integer, VtkArray& a) {
  Bytes in(b, 0, big);
  if (integer) {
    a.ints.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      T v{};
      in.get(v);
      a.ints[i] = static_cast<std::int64_t>(v);
    }
  } else {
    a.reals.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      T v{};
      in.get(v);
      a.reals[i] = static_cast<double>(v);
    }
  }
}

/// Decodes a DataArray into `a` (integer types -> ints, float types -> reals). `want` = the
/// number of values expected (0 = any).
Status decode(const Ctx& c, const XmlNode& da, std::size_t want, VtkArray& a) {
  const std::string* type = da.attr("type");
  const std::string* name = da.attr("Name");
  const std::string* comps = da.attr("NumberOfComponents");
  a.name = name ? *name : "";
  a.where = static_cast<std::int64_t>(da.offset);
  std::int64_t nc = 1;
  if (comps && (!parse_int(*comps, nc) || nc < 1 || nc > 1000)) return c.err(da.offset, "DataArray " + a.name + ": bad NumberOfComponents");
  a.components = static_cast<int>(nc);
  const Scalar sc = type ? scalar_of(*type) : Scalar::bad;
  if (sc == Scalar::bad) return c.err(da.offset, "DataArray " + a.name + ": unsupported type " + (type ? quote_tok(*type) : std::string("(none)")));
  a.integer = scalar_integer(sc);
  const std::string* fmt = da.attr("format");
  if (!fmt || *fmt == "ascii") {
    Text t(da.text);
    std::size_t count = 0;
    for (;;) {
      const std::string_view tok = t.token();
      if (tok.empty()) break;
      if (a.integer) {
        std::int64_t v = 0;
        if (!parse_int(tok, v)) return c.err(da.text_offset + (tok.data() - da.text.data()), "DataArray " + a.name + ": malformed integer " + quote_tok(tok));
        a.ints.push_back(v);
      } else {
        double v = 0;
        if (!parse_double(tok, v)) return c.err(da.text_offset + (tok.data() - da.text.data()), "DataArray " + a.name + ": malformed number " + quote_tok(tok));
        a.reals.push_back(v);
      }
      ++count;
    }
  } else if (*fmt == "binary" || *fmt == "appended") {
    std::string raw;
    Status st = array_bytes(c, da, raw);
    if (!st) {
      Error e = st.error();
      e.reason = "DataArray " + a.name + ": " + e.reason;
      return e;
    }
    const std::size_t sz = scalar_size(sc);
    if (raw.size() % sz != 0) return c.err(da.offset, "DataArray " + a.name + ": " + std::to_string(raw.size()) + " bytes is not a whole number of " + *type);
    const std::size_t n = raw.size() / sz;
    switch (sc) {
      case Scalar::i8: convert<std::int8_t>(raw, c.big, n, true, a); break;
      case Scalar::u8: convert<std::uint8_t>(raw, c.big, n, true, a); break;
      case Scalar::i16: convert<std::int16_t>(raw, c.big, n, true, a); break;
      case Scalar::u16: convert<std::uint16_t>(raw, c.big, n, true, a); break;
      case Scalar::i32: convert<std::int32_t>(raw, c.big, n, true, a); break;
      case Scalar::u32: convert<std::uint32_t>(raw, c.big, n, true, a); break;
      case Scalar::i64: convert<std::int64_t>(raw, c.big, n, true, a); break;
      case Scalar::u64: convert<std::uint64_t>(raw, c.big, n, true, a); break;
      case Scalar::f32: convert<float>(raw, c.big, n, false, a); break;
      case Scalar::f64: convert<double>(raw, c.big, n, false, a); break;
      default: break;
    }
  } else {
    return c.err(da.offset, "DataArray " + a.name + ": unknown format " + quote_tok(*fmt));
  }
  if (want && a.size() != want) {
    return c.err(da.offset, "DataArray " + a.name + ": " + std::to_string(a.size()) + " values, expected " + std::to_string(want));
  }
  return {};
}

}  // namespace

Expected<FemMesh> read_vtu(const std::string& file, std::string_view bytes) {
  Expected<XmlDocument> doc = parse_xml(file, bytes);
  if (!doc) return doc.error();
  const XmlNode& root = *doc->root;
  Ctx c{.file = file, .s = bytes, .doc = &*doc};
  if (root.name != "VTKFile") return c.err(root.offset, "not a VTK XML file (root element <" + root.name + ">)");
  const std::string* type = root.attr("type");
  if (!type || *type != "UnstructuredGrid") return c.err(root.offset, "VTK XML type " + (type ? quote_tok(*type) : std::string("(none)")) + " is not UnstructuredGrid");
  if (const std::string* bo = root.attr("byte_order")) c.big = *bo == "BigEndian";
  if (const std::string* ht = root.attr("header_type")) {
    if (*ht == "UInt64") c.u64_header = true;
    else if (*ht != "UInt32") return c.err(root.offset, "unsupported header_type " + quote_tok(*ht));
  }
  if (const std::string* comp = root.attr("compressor")) {
    if (*comp == "vtkZLibDataCompressor") c.zlib = true;
    else if (!comp->empty()) return c.err(root.offset, "unsupported compressor " + quote_tok(*comp) + " (only vtkZLibDataCompressor)");
  }
  const XmlNode* grid = root.child("UnstructuredGrid");
  if (!grid) return c.err(root.offset, "no <UnstructuredGrid>");
  VtkData d;
  if (const XmlNode* fd = grid->child("FieldData")) {
    for (const auto& da : fd->children) {
      const std::string* n = da->attr("Name");
      const std::string* t = da->attr("type");
      const std::string* f = da->attr("format");
      if (!n || *n != "group_names" || !t || *t != "String" || !f || *f != "ascii") continue;
      Text tx(da->text);
      std::string cur;
      for (std::string_view tok = tx.token(); !tok.empty(); tok = tx.token()) {
        std::int64_t code = 0;
        if (!parse_int(tok, code) || code < 0 || code > 255) return Error{.file = file, .byte = static_cast<std::int64_t>(da->offset), .reason = "group_names: malformed character code"};
        if (code == 0) {
          d.group_names.push_back(cur);
          cur.clear();
        } else {
          cur += static_cast<char>(code);
        }
      }
    }
  }
  std::size_t pieces = 0;
  std::map<std::string, std::size_t> parr_count, carr_count;
  for (const auto& piece : grid->children) {
    if (piece->name != "Piece") continue;
    ++pieces;
    std::int64_t np = 0, nc = 0;
    const std::string* a = piece->attr("NumberOfPoints");
    const std::string* b = piece->attr("NumberOfCells");
    if (!a || !b || !parse_int(*a, np) || !parse_int(*b, nc) || np < 0 || nc < 0) return c.err(piece->offset, "Piece without valid NumberOfPoints/NumberOfCells");
    const std::size_t p0 = d.points.size() / 3;
    const std::size_t conn0 = d.connectivity.size();
    const XmlNode* pts = piece->child("Points");
    if (np > 0) {
      if (!pts || !pts->child("DataArray")) return c.err(piece->offset, "Piece without <Points>");
      VtkArray pa;
      Status st = decode(c, *pts->child("DataArray"), 3 * static_cast<std::size_t>(np), pa);
      if (!st) return st.error();
      if (pa.integer) {
        for (std::int64_t v : pa.ints) d.points.push_back(static_cast<double>(v));
      } else {
        d.points.insert(d.points.end(), pa.reals.begin(), pa.reals.end());
      }
    }
    const XmlNode* cells = piece->child("Cells");
    if (nc > 0) {
      if (!cells) return c.err(piece->offset, "Piece without <Cells>");
      const XmlNode *conn = nullptr, *offs = nullptr, *types = nullptr;
      for (const auto& da : cells->children) {
        const std::string* n = da->attr("Name");
        if (!n) continue;
        if (*n == "connectivity") conn = da.get();
        if (*n == "offsets") offs = da.get();
        if (*n == "types") types = da.get();
      }
      if (!conn || !offs || !types) return c.err(cells->offset, "<Cells> needs connectivity, offsets and types");
      VtkArray ca, oa, ta;
      Status st = decode(c, *conn, 0, ca);
      if (st) st = decode(c, *offs, static_cast<std::size_t>(nc), oa);
      if (st) st = decode(c, *types, static_cast<std::size_t>(nc), ta);
      if (!st) return st.error();
      if (!ca.integer || !oa.integer || !ta.integer) return c.err(cells->offset, "cell arrays must have integer types");
      d.cells_where = static_cast<std::int64_t>(conn->offset);
      d.types_where = static_cast<std::int64_t>(types->offset);
      // Shifted by the previous pieces (wrapping arithmetic: out-of-range values stay invalid).
      for (std::int64_t v : ca.ints) d.connectivity.push_back(v < 0 ? v : static_cast<std::int64_t>(static_cast<std::uint64_t>(v) + p0));
      for (std::int64_t v : oa.ints) d.offsets.push_back(v < 0 ? v : static_cast<std::int64_t>(static_cast<std::uint64_t>(v) + conn0));
      d.types.insert(d.types.end(), ta.ints.begin(), ta.ints.end());
    }
    for (int which = 0; which < 2; ++which) {
      const XmlNode* data = piece->child(which == 0 ? "PointData" : "CellData");
      if (!data) continue;
      std::vector<VtkArray>& out = which == 0 ? d.point_arrays : d.cell_arrays;
      auto& counts = which == 0 ? parr_count : carr_count;
      const std::size_t n = static_cast<std::size_t>(which == 0 ? np : nc);
      for (const auto& da : data->children) {
        if (da->name != "DataArray") continue;
        const std::string* t = da->attr("type");
        if (!t || scalar_of(*t) == Scalar::bad) continue;  // e.g. String arrays: not ours
        VtkArray arr;
        Status st = decode(c, *da, 0, arr);
        if (!st) return st.error();
        if (arr.size() != n * static_cast<std::size_t>(arr.components)) {
          return c.err(da->offset, "DataArray " + arr.name + ": " + std::to_string(arr.size()) + " values for " + std::to_string(n) + (which == 0 ? " points" : " cells") + " x " + std::to_string(arr.components));
        }
        ++counts[arr.name];
        auto it = std::find_if(out.begin(), out.end(), [&](const VtkArray& x) { return x.name == arr.name; });
        if (it == out.end()) {
          if (pieces == 1) out.push_back(std::move(arr));
        } else if (it->integer == arr.integer && it->components == arr.components) {
          it->ints.insert(it->ints.end(), arr.ints.begin(), arr.ints.end());
          it->reals.insert(it->reals.end(), arr.reals.begin(), arr.reals.end());
        }
      }
    }
  }
  if (pieces == 0) return c.err(grid->offset, "no <Piece>");
  // Arrays missing from some piece are dropped.
  auto prune = [&](std::vector<VtkArray>& v, std::map<std::string, std::size_t>& cnt) {
    v.erase(std::remove_if(v.begin(), v.end(), [&](const VtkArray& a) { return cnt[a.name] != pieces; }), v.end());
  };
  prune(d.point_arrays, parr_count);
  prune(d.cell_arrays, carr_count);
  return build_vtk_mesh(file, std::move(d), true);
}

}  // namespace interfere::fem_io
