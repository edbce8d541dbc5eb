// Gmsh MSH reader, versions 2.x and 4.1, ASCII and binary (Gmsh reference manual, section
// "MSH file format": $MeshFormat, $PhysicalNames, $Entities, $Nodes, $Elements, $NodeData).
// Binary files must be little-endian (the endianness marker `1` is checked). Element nodes are
// converted from Gmsh's to VTK's order (scan.cpp, gmsh_to_vtk). Elements of lower dimension
// than the highest present are dropped; their physical groups become node sets. Groups are the
// first physical group of each element (else, when no element of the highest dimension has one,
// its elementary entity). $NodeData views with 3 components become NodalSeries (one step per
// block, time from the first real tag).
#include <algorithm>
#include <map>
#include <unordered_map>

#include "scan.h"

namespace interfere::fem_io {
namespace {

bool gmsh_type(std::int64_t g, ElemType& t) {
  switch (g) {
    case 1: t = ElemType::line2; return true;
    case 2: t = ElemType::tri3; return true;
    case 3: t = ElemType::quad4; return true;
    case 4: t = ElemType::tet4; return true;
    case 5: t = ElemType::hex8; return true;
    case 6: t = ElemType::wedge6; return true;
    case 7: t = ElemType::pyr5; return true;
    case 8: t = ElemType::line3; return true;
    case 9: t = ElemType::tri6; return true;
    case 10: t = ElemType::quad9; return true;
    case 11: t = ElemType::tet10; return true;
    case 12: t = ElemType::hex27; return true;
    case 15: t = ElemType::point1; return true;
    case 16: t = ElemType::quad8; return true;
    case 17: t = ElemType::hex20; return true;
    case 18: t = ElemType::wedge15; return true;
    case 19: t = ElemType::pyr13; return true;
    default: return false;
  }
}

std::string unsupported_type(std::int64_t g) {
  std::string r = "unsupported Gmsh element type " + std::to_string(g);
  if (g == 13 || g == 14) r += " (18-node wedge / 14-node pyramid: mesh with Mesh.SecondOrderIncomplete=1)";
  return r;
}

struct Reader {
  std::string file;
  std::string_view s;
  Text t;
  FemMesh m;
  bool binary = false;
  int major = 0;
  // Per element while reading: entity tag, dimension, physical tag (MSH 2; 0 = none), location.
  std::vector<std::int32_t> entity;
  std::vector<std::int32_t> phys;
  std::vector<std::int64_t> where;
  std::map<std::pair<int, int>, std::string> phys_names;        // (dim, tag) -> name
  std::map<std::pair<int, int>, std::vector<int>> entity_phys;  // (dim, entity) -> physical tags
  IdMap node_map;
  bool have_nodes = false, have_elements = false;
  std::map<std::string, std::size_t> field_of;       // view name -> index in m.fields
  std::map<std::string, std::int64_t> last_step_of;  // view name -> last step index read

  Reader(std::string f, std::string_view bytes) : file(std::move(f)), s(bytes), t(bytes) { m.file = file; }

  Error at_line(std::string r) const { return line_error(file, t.line(), std::move(r)); }
  Error at_byte(std::size_t b, std::string r) const { return byte_error(file, static_cast<std::int64_t>(b), std::move(r)); }

  bool int_token(std::int64_t& v, const char* what, Error& err) {
    const std::string_view tok = t.token();
    if (tok.empty()) {
      err = line_error(file, t.cur_line(), std::string("unexpected end of file, expected ") + what);
      return false;
    }
    if (!parse_int(tok, v)) {
      err = at_line("malformed " + std::string(what) + " " + quote_tok(tok));
      return false;
    }
    return true;
  }
  bool real_token(double& v, const char* what, Error& err) {
    const std::string_view tok = t.token();
    if (tok.empty()) {
      err = line_error(file, t.cur_line(), std::string("unexpected end of file, expected ") + what);
      return false;
    }
    if (!parse_double(tok, v)) {
      err = at_line("malformed " + std::string(what) + " " + quote_tok(tok));
      return false;
    }
    if (!std::isfinite(v)) {
      err = at_line("non-finite " + std::string(what) + " " + quote_tok(tok));
      return false;
    }
    return true;
  }
  bool count_token(std::int64_t& v, const char* what, Error& err) {
    if (!int_token(v, what, err)) return false;
    if (v < 0 || static_cast<std::uint64_t>(v) > s.size()) {
      err = at_line(std::string("implausible ") + what + " " + std::to_string(v));
      return false;
    }
    return true;
  }

  /// After a section's data: the next token must be `$End<name>`.
  bool expect_end(std::string_view name, Error& err) {
    const std::string_view tok = t.token();
    if (tok.size() != name.size() + 4 || tok.substr(0, 4) != "$End" || tok.substr(4) != name) {
      err = tok.empty() ? line_error(file, t.cur_line(), "unexpected end of file, expected $End" + std::string(name))
                        : at_line("expected $End" + std::string(name) + ", found " + quote_tok(tok) + " (wrong count?)");
      return false;
    }
    return true;
  }
  /// Moves the text cursor to byte `pos` (after binary data), keeping line numbers right.
  void resume_text(std::size_t start, std::size_t pos) {
    const std::int64_t lines = line_of(s.substr(start), pos - start) - 1;
    t.set_pos(pos, t.cur_line() + lines);
  }
  /// Start of binary data: the byte after the newline ending the current header line.
  std::size_t binary_start() {
    t.skip_line();
    return t.pos();
  }

  Status run();
  Status mesh_format();
  Status physical_names();
  Status entities();
  Status nodes();
  Status elements();
  Status node_data();
  Status skip_section(std::string_view name);
  Status add_element(std::int64_t gtype, std::int64_t id, const std::int64_t* nodes_in, int entity_tag, int entity_dim,
                     int phys_tag, std::int64_t loc);
  Status finish();
};

Status Reader::run() {
  bool have_format = false;
  for (;;) {
    const std::string_view tok = t.token();
    if (tok.empty()) break;
    if (tok.front() != '$') return at_line("expected a section ($Name), found " + quote_tok(tok));
    if (!have_format && tok != "$MeshFormat") return at_line("not a Gmsh MSH file: first section must be $MeshFormat, found " + quote_tok(tok));
    Status st;
    if (tok == "$MeshFormat") {
      st = mesh_format();
      have_format = true;
    } else if (tok == "$PhysicalNames") {
      st = physical_names();
    } else if (tok == "$Entities") {
      st = entities();
    } else if (tok == "$Nodes" || tok == "$NOD") {
      st = nodes();
    } else if (tok == "$Elements" || tok == "$ELM") {
      st = elements();
    } else if (tok == "$NodeData") {
      st = node_data();
    } else {
      st = skip_section(tok.substr(1));
    }
    if (!st) return st;
  }
  if (!have_format) return file_error(file, "not a Gmsh MSH file (no $MeshFormat)");
  return finish();
}

Status Reader::mesh_format() {
  Error err;
  const std::string_view ver = t.token();
  double v = 0;
  if (!parse_double(ver, v)) return at_line("malformed MSH version " + quote_tok(ver));
  std::int64_t ft = 0, ds = 0;
  if (!int_token(ft, "file type", err) || !int_token(ds, "data size", err)) return err;
  if (v >= 2 && v < 3) {
    major = 2;
  } else if (v == 4.1) {
    major = 4;
  } else if (v >= 4 && v < 4.1) {
    return at_line("MSH 4.0 is not supported (save as 4.1 or 2.2)");
  } else {
    return at_line("unsupported MSH version " + quote_tok(ver) + " (2.x and 4.1 are supported)");
  }
  if (ft != 0 && ft != 1) return at_line("file type must be 0 (ASCII) or 1 (binary), found " + std::to_string(ft));
  binary = ft == 1;
  if (ds != 8) return at_line("data size must be 8, found " + std::to_string(ds));
  if (binary) {
    const std::size_t b = binary_start();
    Bytes in(s, b);
    std::int32_t one = 0;
    if (!in.get(one)) return at_byte(b, "truncated endianness marker");
    if (one != 1) {
      return at_byte(b, Bytes::byteswap(one) == 1 ? "big-endian binary MSH is not supported (endianness marker byte-swapped)"
                                                  : "bad endianness marker " + std::to_string(one));
    }
    resume_text(b, in.pos());
  }
  Error e2;
  if (!expect_end("MeshFormat", e2)) return e2;
  return {};
}

Status Reader::physical_names() {
  Error err;
  std::int64_t n = 0;
  if (!count_token(n, "number of physical names", err)) return err;
  for (std::int64_t i = 0; i < n; ++i) {
    std::int64_t dim = 0, tag = 0;
    if (!int_token(dim, "physical dimension", err) || !int_token(tag, "physical tag", err)) return err;
    // The name: a quoted string to the end of the line.
    std::string_view rest;
    t.next_line(rest);
    rest = trim(rest);
    if (rest.size() >= 2 && rest.front() == '"' && rest.back() == '"') rest = rest.substr(1, rest.size() - 2);
    phys_names[{static_cast<int>(dim), static_cast<int>(tag)}] = std::string(rest);
  }
  if (!expect_end("PhysicalNames", err)) return err;
  return {};
}

Status Reader::entities() {
  if (major != 4) return skip_section("Entities");
  Error err;
  if (!binary) {
    std::int64_t counts[4];
    for (auto& c : counts) {
      if (!count_token(c, "number of entities", err)) return err;
    }
    for (int dim = 0; dim < 4; ++dim) {
      for (std::int64_t i = 0; i < counts[dim]; ++i) {
        std::int64_t tag = 0, np = 0;
        double x = 0;
        if (!int_token(tag, "entity tag", err)) return err;
        for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) {
          if (!real_token(x, "bounding box", err)) return err;
        }
        if (!count_token(np, "number of physical tags", err)) return err;
        std::vector<int>& ph = entity_phys[{dim, static_cast<int>(tag)}];
        for (std::int64_t k = 0; k < np; ++k) {
          std::int64_t p = 0;
          if (!int_token(p, "physical tag", err)) return err;
          ph.push_back(static_cast<int>(p));
        }
        if (dim > 0) {
          std::int64_t nb = 0, b = 0;
          if (!count_token(nb, "number of bounding entities", err)) return err;
          for (std::int64_t k = 0; k < nb; ++k) {
            if (!int_token(b, "bounding entity", err)) return err;
          }
        }
      }
    }
  } else {
    const std::size_t start = binary_start();
    Bytes in(s, start);
    std::uint64_t counts[4];
    for (auto& c : counts) {
      if (!in.get(c)) return at_byte(in.pos(), "truncated $Entities");
    }
    for (int dim = 0; dim < 4; ++dim) {
      for (std::uint64_t i = 0; i < counts[dim]; ++i) {
        std::int32_t tag = 0;
        std::uint64_t np = 0;
        if (!in.get(tag) || !in.skip(8 * (dim == 0 ? 3 : 6)) || !in.get(np)) return at_byte(in.pos(), "truncated $Entities");
        if (np > in.remaining() / 4) return at_byte(in.pos(), "implausible number of physical tags " + std::to_string(np));
        std::vector<int>& ph = entity_phys[{dim, tag}];
        for (std::uint64_t k = 0; k < np; ++k) {
          std::int32_t p = 0;
          if (!in.get(p)) return at_byte(in.pos(), "truncated $Entities");
          ph.push_back(p);
        }
        if (dim > 0) {
          std::uint64_t nb = 0;
          if (!in.get(nb) || nb > in.remaining() / 4 || !in.skip(4 * nb)) return at_byte(in.pos(), "truncated $Entities");
        }
      }
    }
    resume_text(start, in.pos());
  }
  if (!expect_end("Entities", err)) return err;
  return {};
}

Status Reader::nodes() {
  if (major == 0) return at_line("$Nodes before $MeshFormat");
  if (have_nodes) return at_line("second $Nodes section");
  have_nodes = true;
  Error err;
  const std::int64_t section_line = t.line();
  if (major == 2) {
    std::int64_t n = 0;
    if (!count_token(n, "number of nodes", err)) return err;
    m.nodes.resize(static_cast<std::size_t>(n));
    m.node_ids.resize(static_cast<std::size_t>(n));
    if (!binary) {
      for (std::int64_t i = 0; i < n; ++i) {
        std::int64_t id = 0;
        Vec3 p;
        if (!int_token(id, "node tag", err) || !real_token(p.x, "coordinate", err) || !real_token(p.y, "coordinate", err) ||
            !real_token(p.z, "coordinate", err))
          return err;
        m.node_ids[static_cast<std::size_t>(i)] = id;
        m.nodes[static_cast<std::size_t>(i)] = p;
      }
    } else {
      const std::size_t start = binary_start();
      Bytes in(s, start);
      for (std::int64_t i = 0; i < n; ++i) {
        std::int32_t id = 0;
        double c[3];
        const std::size_t at = in.pos();
        if (!in.get(id) || !in.get_array(3, c)) return at_byte(at, "truncated binary node block (node " + std::to_string(i + 1) + " of " + std::to_string(n) + ")");
        const Vec3 p{c[0], c[1], c[2]};
        if (!is_finite(p)) return at_byte(at, "node " + std::to_string(id) + ": non-finite coordinate");
        m.node_ids[static_cast<std::size_t>(i)] = id;
        m.nodes[static_cast<std::size_t>(i)] = p;
      }
      resume_text(start, in.pos());
    }
  } else if (!binary) {
    std::int64_t blocks = 0, n = 0, lo = 0, hi = 0;
    if (!count_token(blocks, "number of node blocks", err) || !count_token(n, "number of nodes", err) ||
        !int_token(lo, "minimum node tag", err) || !int_token(hi, "maximum node tag", err))
      return err;
    m.nodes.reserve(static_cast<std::size_t>(n));
    m.node_ids.reserve(static_cast<std::size_t>(n));
    for (std::int64_t b = 0; b < blocks; ++b) {
      std::int64_t dim = 0, tag = 0, par = 0, k = 0;
      if (!int_token(dim, "entity dimension", err) || !int_token(tag, "entity tag", err) || !int_token(par, "parametric flag", err) ||
          !count_token(k, "number of nodes in block", err))
        return err;
      if (dim < 0 || dim > 3) return at_line("bad entity dimension " + std::to_string(dim));
      if (static_cast<std::int64_t>(m.nodes.size()) + k > n) return at_line("node blocks hold more nodes than the " + std::to_string(n) + " announced");
      const std::size_t first = m.nodes.size();
      for (std::int64_t i = 0; i < k; ++i) {
        std::int64_t id = 0;
        if (!int_token(id, "node tag", err)) return err;
        m.node_ids.push_back(id);
      }
      const int extra = par ? static_cast<int>(dim) : 0;
      m.nodes.resize(first + static_cast<std::size_t>(k));
      for (std::int64_t i = 0; i < k; ++i) {
        Vec3& p = m.nodes[first + static_cast<std::size_t>(i)];
        if (!real_token(p.x, "coordinate", err) || !real_token(p.y, "coordinate", err) || !real_token(p.z, "coordinate", err)) return err;
        double u = 0;
        for (int e = 0; e < extra; ++e) {
          if (!real_token(u, "parametric coordinate", err)) return err;
        }
      }
    }
    if (static_cast<std::int64_t>(m.nodes.size()) != n) {
      return at_line("node blocks hold " + std::to_string(m.nodes.size()) + " nodes, the header announced " + std::to_string(n));
    }
  } else {
    const std::size_t start = binary_start();
    Bytes in(s, start);
    std::uint64_t blocks = 0, n = 0, lo = 0, hi = 0;
    if (!in.get(blocks) || !in.get(n) || !in.get(lo) || !in.get(hi)) return at_byte(start, "truncated $Nodes header");
    if (n > in.remaining() / 32) return at_byte(start, "truncated binary node block: " + std::to_string(n) + " nodes announced, the file is too short");
    m.nodes.resize(static_cast<std::size_t>(n));
    m.node_ids.resize(static_cast<std::size_t>(n));
    std::size_t filled = 0;
    std::vector<double> buf;
    for (std::uint64_t b = 0; b < blocks; ++b) {
      const std::size_t at = in.pos();
      std::int32_t dim = 0, tag = 0, par = 0;
      std::uint64_t k = 0;
      if (!in.get(dim) || !in.get(tag) || !in.get(par) || !in.get(k)) return at_byte(at, "truncated node block header");
      if (dim < 0 || dim > 3) return at_byte(at, "bad entity dimension " + std::to_string(dim));
      if (k > n - filled) return at_byte(at, "node blocks hold more nodes than the " + std::to_string(n) + " announced");
      std::vector<std::uint64_t> tags(static_cast<std::size_t>(k));
      if (!in.get_array(tags.size(), tags.data())) return at_byte(in.pos(), "truncated binary node block (tags)");
      for (std::size_t i = 0; i < tags.size(); ++i) m.node_ids[filled + i] = static_cast<std::int64_t>(tags[i]);
      const std::size_t per = 3 + (par ? static_cast<std::size_t>(dim) : 0);
      const std::size_t cat = in.pos();
      if (per == 3) {
        static_assert(sizeof(Vec3) == 24);
        if (!in.get_array(static_cast<std::size_t>(k) * 3, reinterpret_cast<double*>(m.nodes.data() + filled)))
          return at_byte(cat, "truncated binary node block (coordinates)");
      } else {
        buf.resize(static_cast<std::size_t>(k) * per);
        if (!in.get_array(buf.size(), buf.data())) return at_byte(cat, "truncated binary node block (coordinates)");
        for (std::size_t i = 0; i < k; ++i) m.nodes[filled + i] = {buf[i * per], buf[i * per + 1], buf[i * per + 2]};
      }
      for (std::size_t i = 0; i < k; ++i) {
        if (!is_finite(m.nodes[filled + i])) {
          return at_byte(cat + i * per * 8, "node " + std::to_string(m.node_ids[filled + i]) + ": non-finite coordinate");
        }
      }
      filled += static_cast<std::size_t>(k);
    }
    if (filled != n) return at_byte(in.pos(), "node blocks hold " + std::to_string(filled) + " nodes, the header announced " + std::to_string(n));
    resume_text(start, in.pos());
  }
  if (!expect_end("Nodes", err)) return err;
  const std::int64_t dup = node_map.build(m.node_ids);
  if (dup >= 0) return line_error(file, section_line, "duplicate node id " + std::to_string(m.node_ids[static_cast<std::size_t>(dup)]) + " in $Nodes");
  return {};
}

Status Reader::add_element(std::int64_t gtype, std::int64_t id, const std::int64_t* nodes_in, int entity_tag, int entity_dim,
                           int phys_tag, std::int64_t loc) {
  ElemType type{};
  gmsh_type(gtype, type);  // checked by the caller
  const ElemInfo& info = elem_info(type);
  std::uint32_t v[32];
  for (int k = 0; k < info.nodes; ++k) {
    const std::int64_t idx = node_map.find(nodes_in[k]);
    if (idx < 0) {
      const std::string r = "element " + std::to_string(id) + ": node " + std::to_string(nodes_in[k]) + " is not defined";
      return binary ? byte_error(file, loc, r) : line_error(file, loc, r);
    }
    v[k] = static_cast<std::uint32_t>(idx);
  }
  permute(gmsh_to_vtk(type), v, info.nodes);
  // MSH 2 writes an element once per physical group (renumbered): a copy of the previous element
  // in the same entity is dropped (the element keeps its first group).
  if (major == 2 && !m.elem_types.empty() && m.elem_types.back() == type && entity.back() == entity_tag) {
    const std::size_t last = m.elem_types.size() - 1;
    if (std::equal(v, v + info.nodes, m.element_nodes(last))) return {};
  }
  m.add_element(type, id, -1, v, info.nodes);
  entity.push_back(entity_tag);
  phys.push_back(major == 2 ? phys_tag : entity_dim);  // MSH 4: entity dimension, resolved in finish()
  where.push_back(loc);
  return {};
}

Status Reader::elements() {
  if (!have_nodes) return at_line("$Elements before $Nodes");
  if (have_elements) return at_line("second $Elements section");
  have_elements = true;
  Error err;
  std::int64_t nodes_buf[32];
  if (major == 2 && !binary) {
    std::int64_t n = 0;
    if (!count_token(n, "number of elements", err)) return err;
    for (std::int64_t i = 0; i < n; ++i) {
      std::int64_t id = 0, g = 0, ntags = 0;
      if (!int_token(id, "element tag", err)) return err;
      const std::int64_t line = t.line();
      if (!int_token(g, "element type", err)) return err;
      ElemType type{};
      if (!gmsh_type(g, type)) return at_line(unsupported_type(g));
      if (!count_token(ntags, "number of tags", err)) return err;
      std::int64_t tags[2] = {0, 0};
      for (std::int64_t k = 0; k < ntags; ++k) {
        std::int64_t x = 0;
        if (!int_token(x, "element tag value", err)) return err;
        if (k < 2) tags[k] = x;
      }
      const int nn = elem_info(type).nodes;
      for (int k = 0; k < nn; ++k) {
        if (!int_token(nodes_buf[k], "node tag", err)) return err;
      }
      Status st = add_element(g, id, nodes_buf, static_cast<int>(tags[1]), elem_info(type).dim, static_cast<int>(tags[0]), line);
      if (!st) return st;
    }
  } else if (major == 2) {
    std::int64_t n = 0;
    if (!count_token(n, "number of elements", err)) return err;
    const std::size_t start = binary_start();
    Bytes in(s, start);
    std::int64_t done = 0;
    std::vector<std::int32_t> rec;
    while (done < n) {
      const std::size_t at = in.pos();
      std::int32_t hdr[3];
      if (!in.get_array(3, hdr)) return at_byte(at, "truncated binary element block header");
      ElemType type{};
      if (!gmsh_type(hdr[0], type)) return at_byte(at, unsupported_type(hdr[0]));
      if (hdr[1] <= 0 || hdr[1] > n - done || hdr[2] < 0 || hdr[2] > 1000) return at_byte(at, "bad element block header");
      const int nn = elem_info(type).nodes;
      const std::size_t per = 1 + static_cast<std::size_t>(hdr[2]) + static_cast<std::size_t>(nn);
      rec.resize(per);
      for (std::int32_t i = 0; i < hdr[1]; ++i) {
        const std::size_t eat = in.pos();
        if (!in.get_array(per, rec.data())) return at_byte(eat, "truncated binary element block");
        for (int k = 0; k < nn; ++k) nodes_buf[k] = rec[1 + static_cast<std::size_t>(hdr[2]) + static_cast<std::size_t>(k)];
        const int ph = hdr[2] > 0 ? rec[1] : 0, en = hdr[2] > 1 ? rec[2] : 0;
        Status st = add_element(hdr[0], rec[0], nodes_buf, en, elem_info(type).dim, ph, static_cast<std::int64_t>(eat));
        if (!st) return st;
      }
      done += hdr[1];
    }
    resume_text(start, in.pos());
  } else if (!binary) {
    std::int64_t blocks = 0, n = 0, lo = 0, hi = 0;
    if (!count_token(blocks, "number of element blocks", err) || !count_token(n, "number of elements", err) ||
        !int_token(lo, "minimum element tag", err) || !int_token(hi, "maximum element tag", err))
      return err;
    m.elem_types.reserve(static_cast<std::size_t>(n));
    m.elem_ids.reserve(static_cast<std::size_t>(n));
    std::int64_t total = 0;
    for (std::int64_t b = 0; b < blocks; ++b) {
      std::int64_t dim = 0, tag = 0, g = 0, k = 0;
      if (!int_token(dim, "entity dimension", err) || !int_token(tag, "entity tag", err) || !int_token(g, "element type", err)) return err;
      ElemType type{};
      if (!gmsh_type(g, type)) return at_line(unsupported_type(g));
      if (!count_token(k, "number of elements in block", err)) return err;
      total += k;
      if (total > n) return at_line("element blocks hold more elements than the " + std::to_string(n) + " announced");
      const int nn = elem_info(type).nodes;
      for (std::int64_t i = 0; i < k; ++i) {
        std::int64_t id = 0;
        if (!int_token(id, "element tag", err)) return err;
        const std::int64_t line = t.line();
        for (int q = 0; q < nn; ++q) {
          if (!int_token(nodes_buf[q], "node tag", err)) return err;
        }
        Status st = add_element(g, id, nodes_buf, static_cast<int>(tag), elem_info(type).dim, 0, line);
        if (!st) return st;
      }
    }
    if (total != n) return at_line("element blocks hold " + std::to_string(total) + " elements, the header announced " + std::to_string(n));
  } else {
    const std::size_t start = binary_start();
    Bytes in(s, start);
    std::uint64_t blocks = 0, n = 0, lo = 0, hi = 0;
    if (!in.get(blocks) || !in.get(n) || !in.get(lo) || !in.get(hi)) return at_byte(start, "truncated $Elements header");
    if (n > in.remaining() / 16) return at_byte(start, "truncated binary element block: " + std::to_string(n) + " elements announced, the file is too short");
    m.elem_types.reserve(static_cast<std::size_t>(n));
    m.elem_ids.reserve(static_cast<std::size_t>(n));
    m.elem_groups.reserve(static_cast<std::size_t>(n));
    m.elem_offsets.reserve(static_cast<std::size_t>(n) + 1);
    entity.reserve(static_cast<std::size_t>(n));
    phys.reserve(static_cast<std::size_t>(n));
    where.reserve(static_cast<std::size_t>(n));
    std::uint64_t total = 0;
    std::vector<std::uint64_t> rec;
    for (std::uint64_t b = 0; b < blocks; ++b) {
      const std::size_t at = in.pos();
      std::int32_t dim = 0, tag = 0, g = 0;
      std::uint64_t k = 0;
      if (!in.get(dim) || !in.get(tag) || !in.get(g) || !in.get(k)) return at_byte(at, "truncated element block header");
      ElemType type{};
      if (!gmsh_type(g, type)) return at_byte(at, unsupported_type(g));
      if (k > n - total) return at_byte(at, "element blocks hold more elements than the " + std::to_string(n) + " announced");
      total += k;
      const int nn = elem_info(type).nodes;
      const std::size_t per = 1 + static_cast<std::size_t>(nn);
      if (k > in.remaining() / (8 * per)) return at_byte(in.pos(), "truncated binary element block");
      m.elem_nodes.reserve(m.elem_nodes.size() + k * static_cast<std::size_t>(nn));
      rec.resize(per);
      for (std::uint64_t i = 0; i < k; ++i) {
        const std::size_t eat = in.pos();
        in.get_array(per, rec.data());
        for (int q = 0; q < nn; ++q) nodes_buf[q] = static_cast<std::int64_t>(rec[1 + static_cast<std::size_t>(q)]);
        Status st = add_element(g, static_cast<std::int64_t>(rec[0]), nodes_buf, tag, elem_info(type).dim, 0, static_cast<std::int64_t>(eat));
        if (!st) return st;
      }
    }
    if (total != n) return at_byte(in.pos(), "element blocks hold " + std::to_string(total) + " elements, the header announced " + std::to_string(n));
    resume_text(start, in.pos());
  }
  if (!expect_end("Elements", err)) return err;
  return {};
}

Status Reader::node_data() {
  if (!have_nodes) return at_line("$NodeData before $Nodes");
  Error err;
  std::int64_t ns = 0, nr = 0, ni = 0;
  std::string name = "NodeData";
  if (!count_token(ns, "number of string tags", err)) return err;
  for (std::int64_t i = 0; i < ns; ++i) {
    std::string_view line;
    // String tags are on their own lines: skip to the start of the next line first.
    if (i == 0) t.skip_line();
    if (!t.next_line(line)) return line_error(file, t.cur_line(), "unexpected end of file in $NodeData string tags");
    line = trim(line);
    if (line.size() >= 2 && line.front() == '"' && line.back() == '"') line = line.substr(1, line.size() - 2);
    if (i == 0) name = std::string(line);
  }
  if (!count_token(nr, "number of real tags", err)) return err;
  double time = 0;
  bool have_time = false;
  for (std::int64_t i = 0; i < nr; ++i) {
    double x = 0;
    if (!real_token(x, "real tag", err)) return err;
    if (i == 0) {
      time = x;
      have_time = true;
    }
  }
  if (!count_token(ni, "number of integer tags", err)) return err;
  std::int64_t itag[4] = {0, 1, 0, 0};
  for (std::int64_t i = 0; i < ni; ++i) {
    std::int64_t x = 0;
    if (!int_token(x, "integer tag", err)) return err;
    if (i < 4) itag[i] = x;
  }
  const std::int64_t step = itag[0], comps = itag[1], count = itag[2];
  if (ni < 3) return at_line("$NodeData needs 3 integer tags (step, components, count)");
  if (comps < 1 || comps > 9 || count < 0 || static_cast<std::uint64_t>(count) > s.size()) return at_line("bad $NodeData integer tags");
  if (comps != 3) {  // not a vector field: skip its data
    const std::size_t end = s.find("$EndNodeData", t.pos());
    if (end == std::string_view::npos) return line_error(file, t.cur_line(), "unexpected end of file, expected $EndNodeData");
    resume_text(t.pos(), end);
    if (!expect_end("NodeData", err)) return err;
    return {};
  }
  auto [it, added] = field_of.emplace(name, m.fields.size());
  if (added) {
    m.fields.push_back(NodalSeries{.name = name});
    last_step_of[name] = step - 1;
  }
  NodalSeries& f = m.fields[it->second];
  if (f.values.empty() || last_step_of[name] != step) {
    f.values.emplace_back(m.nodes.size(), Vec3{});
    f.times.push_back(have_time ? time : static_cast<double>(step));
    last_step_of[name] = step;
  }
  std::vector<Vec3>& vals = f.values.back();
  if (!binary) {
    for (std::int64_t i = 0; i < count; ++i) {
      std::int64_t id = 0;
      Vec3 v;
      if (!int_token(id, "node tag", err)) return err;
      const std::int64_t idx = node_map.find(id);
      if (idx < 0) return at_line("$NodeData: node " + std::to_string(id) + " is not defined");
      if (!real_token(v.x, "value", err) || !real_token(v.y, "value", err) || !real_token(v.z, "value", err)) return err;
      vals[static_cast<std::size_t>(idx)] = v;
    }
  } else {
    const std::size_t start = binary_start();
    Bytes in(s, start);
    for (std::int64_t i = 0; i < count; ++i) {
      const std::size_t at = in.pos();
      std::int32_t id = 0;
      double c[3];
      if (!in.get(id) || !in.get_array(3, c)) return at_byte(at, "truncated binary $NodeData");
      const std::int64_t idx = node_map.find(id);
      if (idx < 0) return at_byte(at, "$NodeData: node " + std::to_string(id) + " is not defined");
      const Vec3 v{c[0], c[1], c[2]};
      if (!is_finite(v)) return at_byte(at, "$NodeData: non-finite value for node " + std::to_string(id));
      vals[static_cast<std::size_t>(idx)] = v;
    }
    resume_text(start, in.pos());
  }
  if (!expect_end("NodeData", err)) return err;
  return {};
}

Status Reader::skip_section(std::string_view name) {
  const std::string end = "$End" + std::string(name);
  const std::size_t at = s.find(end, t.pos());
  if (at == std::string_view::npos) return at_line("section $" + std::string(name) + " has no " + end);
  resume_text(t.pos(), at + end.size());
  return {};
}

Status Reader::finish() {
  if (!have_nodes) return file_error(file, "no $Nodes section");
  if (!have_elements || m.elem_types.empty()) return file_error(file, "no elements");
  const std::size_t ne = m.elem_types.size();
  int top = 0;
  for (ElemType t : m.elem_types) top = std::max(top, elem_info(t).dim);
  // Physical tags of each element (MSH 4: of its entity).
  auto phys_of = [&](std::size_t e, std::vector<int>& out) {
    out.clear();
    if (major == 2) {
      if (phys[e] != 0) out.push_back(phys[e]);
      return;
    }
    auto it = entity_phys.find({phys[e], entity[e]});
    if (it != entity_phys.end()) out = it->second;
  };
  std::vector<int> ph;
  bool any_phys = false;
  for (std::size_t e = 0; e < ne; ++e) {
    if (elem_info(m.elem_types[e]).dim != top) continue;
    phys_of(e, ph);
    if (!ph.empty()) {
      any_phys = true;
      break;
    }
  }
  // Groups, in order of tag.
  std::map<int, std::int32_t> group_of_tag;
  {
    std::vector<int> tags;
    for (std::size_t e = 0; e < ne; ++e) {
      if (elem_info(m.elem_types[e]).dim != top) continue;
      if (any_phys) {
        phys_of(e, ph);
        if (!ph.empty()) tags.push_back(ph.front());
      } else {
        tags.push_back(entity[e]);
      }
    }
    std::sort(tags.begin(), tags.end());
    tags.erase(std::unique(tags.begin(), tags.end()), tags.end());
    for (int tag : tags) {
      std::string name;
      if (any_phys) {
        auto it = phys_names.find({top, tag});
        name = it != phys_names.end() && !it->second.empty() ? it->second : "physical " + std::to_string(tag);
      } else {
        name = "entity " + std::to_string(tag);
      }
      group_of_tag[tag] = static_cast<std::int32_t>(m.groups.size());
      m.groups.push_back(FemGroup{.name = name, .id = tag, .dim = top});
    }
  }
  // Node sets of lower-dimension physical groups.
  std::map<std::pair<int, int>, std::vector<std::uint32_t>> sets;
  for (std::size_t e = 0; e < ne; ++e) {
    const int dim = elem_info(m.elem_types[e]).dim;
    if (dim == top) {
      if (any_phys) {
        phys_of(e, ph);
        if (!ph.empty()) m.elem_groups[e] = group_of_tag[ph.front()];
      } else {
        m.elem_groups[e] = group_of_tag[entity[e]];
      }
      continue;
    }
    phys_of(e, ph);
    for (int p : ph) {
      auto& v = sets[{dim, p}];
      v.insert(v.end(), m.element_nodes(e), m.element_nodes(e) + m.element_size(e));
    }
  }
  for (auto& [key, v] : sets) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    auto it = phys_names.find(key);
    std::string name = it != phys_names.end() && !it->second.empty()
                           ? it->second
                           : "physical " + std::to_string(key.second) + " (dim " + std::to_string(key.first) + ")";
    m.node_sets.push_back(FemSet{.name = std::move(name), .members = std::move(v)});
  }
  std::vector<std::int32_t>().swap(entity);
  std::vector<std::int32_t>().swap(phys);
  drop_lower_dimension(m, &where);
  Status st = check_element_ids(m, where, binary);
  if (!st) return st;
  return {};
}

}  // namespace

Expected<FemMesh> read_msh(const std::string& file, std::string_view bytes) {
  Reader r(file, bytes);
  Status st = r.run();
  if (!st) return st.error();
  return std::move(r.m);
}

}  // namespace interfere::fem_io
