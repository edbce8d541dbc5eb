// CalculiX .frd reader (issue #26, item 1): files written by the real solver (tests/data/fem/
// ccx_elements*.frd, made by make_frd_files.py with ccx 2.20; and, when `ccx` is on PATH, a fresh
// run) against the .inp they were computed from, read by the Abaqus reader: same node ids and
// coordinates, same elements with the same nodes in the same (VTK) order, materials as groups, the
// prescribed displacements of every increment. Hand-made files written here in ASCII and in binary
// by the test's own writer (the record layouts of the cgx manual, "Result Format") read alike; bad
// input (truncated blocks, wrong counts, unknown nodes in DISP, non-numbers) is an error naming
// the file, the line or byte, and the block and step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>

#include "fem_io_test_util.h"

namespace interfere::fem_test {
namespace {

fs::path data(const std::string& name) { return fs::path(INTERFERE_SOURCE_DIR) / "tests" / "data" / "fem" / name; }

FemMesh must_read(const fs::path& p) {
  Expected<FemMesh> m = read_fem(p);
  EXPECT_TRUE(m) << m.error().message();
  if (!m) return {};
  EXPECT_TRUE(validate_fem_mesh(*m));
  return std::move(*m);
}

std::map<std::int64_t, std::size_t> index_of(const std::vector<std::int64_t>& ids) {
  std::map<std::int64_t, std::size_t> r;
  for (std::size_t i = 0; i < ids.size(); ++i) r[ids[i]] = i;
  return r;
}

/// Same nodes (ids, coordinates) and elements (ids, types, node ids in order) as the input deck.
void expect_same_mesh(const FemMesh& inp, const FemMesh& frd) {
  ASSERT_EQ(frd.num_nodes(), inp.num_nodes());
  const auto fi = index_of(frd.node_ids);
  for (std::size_t i = 0; i < inp.num_nodes(); ++i) {
    ASSERT_TRUE(fi.count(inp.node_ids[i])) << "node " << inp.node_ids[i];
    EXPECT_EQ(frd.nodes[fi.at(inp.node_ids[i])], inp.nodes[i]) << "node " << inp.node_ids[i];
  }
  ASSERT_EQ(frd.elem_ids, inp.elem_ids);
  ASSERT_EQ(frd.elem_types, inp.elem_types);
  for (std::size_t e = 0; e < inp.num_elements(); ++e) {
    ASSERT_EQ(frd.element_size(e), inp.element_size(e));
    for (int q = 0; q < inp.element_size(e); ++q) {
      EXPECT_EQ(frd.node_ids[frd.element_nodes(e)[q]], inp.node_ids[inp.element_nodes(e)[q]])
          << "element " << inp.elem_ids[e] << " node " << q << " (" << elem_info(inp.elem_types[e]).name << ")";
    }
  }
}

/// The model of make_frd_files.py: nodes on z = 0 held, on z = 1 moved by t * (0.01, 0.02, 0).
void expect_ccx_displacements(const FemMesh& m) {
  ASSERT_EQ(m.fields.size(), 1u);
  const NodalSeries& u = m.fields[0];
  EXPECT_EQ(u.name, "DISP");
  ASSERT_EQ(u.num_steps(), 2u);
  EXPECT_EQ(u.times, (std::vector<double>{0.5, 1.0}));
  for (std::size_t s = 0; s < 2; ++s) {
    const double t = u.times[s];
    for (std::size_t i = 0; i < m.num_nodes(); ++i) {
      const double z = m.nodes[i].z;
      if (z == 0) EXPECT_LE(norm(u.values[s][i]), 1e-12) << m.node_ids[i];
      if (z == 1) {
        EXPECT_NEAR(u.values[s][i].x, 0.01 * t, 1e-7) << m.node_ids[i];
        EXPECT_NEAR(u.values[s][i].y, 0.02 * t, 1e-7) << m.node_ids[i];
        EXPECT_NEAR(u.values[s][i].z, 0.0, 1e-7) << m.node_ids[i];
      }
    }
  }
}

TEST(FemIoFrd, CcxAsciiAndBinaryFilesMatchTheirInputDeck) {
  const FemMesh inp = must_read(data("ccx_elements.inp"));
  ASSERT_EQ(inp.num_elements(), 6u);
  for (const char* name : {"ccx_elements.frd", "ccx_elements_bin.frd"}) {
    SCOPED_TRACE(name);
    const FemMesh frd = must_read(data(name));
    expect_same_mesh(inp, frd);
    // Two materials: groups named by the 1UMAT records, ids = the material numbers.
    ASSERT_EQ(frd.groups.size(), 2u);
    EXPECT_EQ(frd.groups[0].name, "STEEL");
    EXPECT_EQ(frd.groups[0].id, 1);
    EXPECT_EQ(frd.groups[1].name, "ALU");
    EXPECT_EQ(frd.groups[1].id, 2);
    EXPECT_EQ(frd.elem_groups, (std::vector<std::int32_t>{0, 0, 0, 1, 1, 1}));
    expect_ccx_displacements(frd);
    EXPECT_TRUE(frd.warnings.empty());
  }
  // The binary file holds float32 displacements, the ASCII one 6 digits: the same to 1e-7.
  const FemMesh a = must_read(data("ccx_elements.frd")), b = must_read(data("ccx_elements_bin.frd"));
  for (std::size_t s = 0; s < 2; ++s) {
    for (std::size_t i = 0; i < a.num_nodes(); ++i) EXPECT_LE(norm(a.fields[0].values[s][i] - b.fields[0].values[s][i]), 1e-7);
  }
}

TEST(FemIoFrd, FreshCcxRunMatchesItsInputDeck) {
  if (std::system("command -v ccx > /dev/null 2>&1") != 0) GTEST_SKIP() << "ccx (calculix-ccx) not on PATH";
  const fs::path dir = temp_dir() / "ccx_run";
  fs::create_directories(dir);
  fs::copy_file(data("ccx_elements.inp"), dir / "job.inp", fs::copy_options::overwrite_existing);
  const std::string cmd = "cd " + dir.string() + " && ccx -i job > job.log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read_text(dir / "job.log");
  const FemMesh inp = must_read(dir / "job.inp");
  const FemMesh frd = must_read(dir / "job.frd");
  expect_same_mesh(inp, frd);
  expect_ccx_displacements(frd);
}

// ---------------------------------------------------------------- the test's own frd writer

struct Model {
  std::vector<std::pair<int, Vec3>> nodes;
  struct Elem {
    int id, type, mat;
    std::vector<int> nodes;  // frd order
  };
  std::vector<Elem> elems;
  std::vector<double> times;
  std::vector<std::vector<std::pair<int, Vec3>>> disp;  // per step
};

std::string fmt(const char* f, ...) {
  char b[256];
  va_list ap;
  va_start(ap, f);
  std::vsnprintf(b, sizeof b, f, ap);
  va_end(ap);
  return b;
}
template <class T>
void raw(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.append(b, sizeof(T));
}

/// ASCII (long format) or binary (nodes float64, elements int32, results float32 or float64).
std::string write_frd(const Model& m, bool binary, bool double_results = false) {
  std::string o = "    1C\n    1UUSER\n";
  o += fmt("%5s%1s%18s%12d%37s%1d\n", "2", "C", "", static_cast<int>(m.nodes.size()), "", binary ? 3 : 1);
  for (const auto& [id, x] : m.nodes) {
    if (binary) {
      raw(o, static_cast<std::int32_t>(id)), raw(o, x.x), raw(o, x.y), raw(o, x.z);
    } else {
      o += fmt(" -1%10d%12.5E%12.5E%12.5E\n", id, x.x, x.y, x.z);
    }
  }
  if (!binary) o += " -3\n";
  o += fmt("%5s%1s%18s%12d%37s%1d\n", "3", "C", "", static_cast<int>(m.elems.size()), "", binary ? 2 : 1);
  for (const Model::Elem& e : m.elems) {
    if (binary) {
      for (int v : {e.id, e.type, 0, e.mat}) raw(o, static_cast<std::int32_t>(v));
      for (int n : e.nodes) raw(o, static_cast<std::int32_t>(n));
    } else {
      o += fmt(" -1%10d%5d%5d%5d\n", e.id, e.type, 0, e.mat);
      for (std::size_t k = 0; k < e.nodes.size(); ++k) {
        if (k % 10 == 0) o += (k ? "\n -2" : " -2");
        o += fmt("%10d", e.nodes[k]);
      }
      o += "\n";
    }
  }
  if (!binary) o += " -3\n";
  for (std::size_t s = 0; s < m.disp.size(); ++s) {
    o += fmt("    1PSTEP%14s%12d%12d%12d\n", "", static_cast<int>(s + 1), static_cast<int>(s + 1), 1);
    std::string h(75, ' ');
    std::memcpy(h.data(), "  100CL", 7);
    std::memcpy(h.data() + 7, fmt("%5d", static_cast<int>(101 + s)).c_str(), 5);
    std::memcpy(h.data() + 12, fmt("%12.5E", m.times[s]).c_str(), 12);
    std::memcpy(h.data() + 24, fmt("%12d", static_cast<int>(m.disp[s].size())).c_str(), 12);
    std::memcpy(h.data() + 56, " 0", 2);
    std::memcpy(h.data() + 58, fmt("%5d", static_cast<int>(s + 1)).c_str(), 5);
    h[74] = binary ? (double_results ? '3' : '2') : '1';
    o += h + "\n";
    o += " -4  DISP        4    1\n -5  D1          1    2    1    0\n -5  D2          1    2    2    0\n"
         " -5  D3          1    2    3    0\n -5  ALL         1    2    0    0    1ALL\n";
    for (const auto& [id, u] : m.disp[s]) {
      if (binary) {
        raw(o, static_cast<std::int32_t>(id));
        for (double c : {u.x, u.y, u.z}) {
          if (double_results) {
            raw(o, c);
          } else {
            raw(o, static_cast<float>(c));
          }
        }
      } else {
        o += fmt(" -1%10d%12.5E%12.5E%12.5E\n", id, u.x, u.y, u.z);
      }
    }
    if (!binary) o += " -3\n";
  }
  o += " 9999\n";
  return o;
}

/// A hex20 (frd order: mid-side nodes bottom, vertical, top) beside a hex8, two steps.
Model two_elements() {
  Model m;
  const Vec3 c[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int frd_edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {1, 5}, {2, 6}, {3, 7}, {4, 5}, {5, 6}, {6, 7}, {7, 4}};
  Model::Elem h20{7, 4, 1, {}}, h8{9, 1, 1, {}};
  for (int i = 0; i < 8; ++i) {
    m.nodes.push_back({10 + i, c[i]});
    h20.nodes.push_back(10 + i);
  }
  for (int k = 0; k < 12; ++k) {
    m.nodes.push_back({30 + k, (c[frd_edges[k][0]] + c[frd_edges[k][1]]) * 0.5});
    h20.nodes.push_back(30 + k);
  }
  for (int i = 0; i < 8; ++i) {
    m.nodes.push_back({50 + i, c[i] + Vec3{3, 0, 0}});
    h8.nodes.push_back(50 + i);
  }
  m.elems = {h20, h8};
  m.times = {0.25, 0.5};
  for (int s = 0; s < 2; ++s) {
    std::vector<std::pair<int, Vec3>> d;
    for (const auto& [id, x] : m.nodes) d.push_back({id, Vec3{-0.125 * (s + 1) * (id >= 50), 0.0625 * x.z, 0}});
    m.disp.push_back(d);
  }
  return m;
}

TEST(FemIoFrd, HandWrittenAsciiAndBinaryReadAlike) {
  const Model mod = two_elements();
  for (int variant = 0; variant < 3; ++variant) {
    SCOPED_TRACE(variant);
    const fs::path p = temp_dir() / ("two_" + std::to_string(variant) + ".frd");
    write_text(p, write_frd(mod, variant > 0, variant == 2));
    const FemMesh m = must_read(p);
    ASSERT_EQ(m.num_nodes(), 28u);
    EXPECT_EQ(m.elem_ids, (std::vector<std::int64_t>{7, 9}));
    ASSERT_EQ(m.elem_types, (std::vector<ElemType>{ElemType::hex20, ElemType::hex8}));
    EXPECT_TRUE(m.groups.empty());  // one material: ungrouped, bodies by connectivity
    EXPECT_EQ(m.elem_groups, (std::vector<std::int32_t>{-1, -1}));
    // VTK hex20: corners, bottom mid-edges 30-33, top 38-41, vertical 34-37.
    std::vector<std::int64_t> ids;
    for (int q = 0; q < 20; ++q) ids.push_back(m.node_ids[m.element_nodes(0)[q]]);
    EXPECT_EQ(ids, (std::vector<std::int64_t>{10, 11, 12, 13, 14, 15, 16, 17, 30, 31, 32, 33, 38, 39, 40, 41, 34, 35, 36, 37}));
    ASSERT_EQ(m.fields.size(), 1u);
    EXPECT_EQ(m.fields[0].times, (std::vector<double>{0.25, 0.5}));
    for (int s = 0; s < 2; ++s) {
      for (const auto& [id, u] : mod.disp[static_cast<std::size_t>(s)]) {
        const auto i = static_cast<std::size_t>(std::find(m.node_ids.begin(), m.node_ids.end(), id) - m.node_ids.begin());
        EXPECT_EQ(m.fields[0].values[static_cast<std::size_t>(s)][i], u) << id;  // exact in every encoding
      }
    }
  }
}

// ---------------------------------------------------------------- bad input

Error read_error(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  write_text(p, text);
  Expected<FemMesh> m = read_fem(p);
  EXPECT_FALSE(m) << name << " was read";
  return m ? Error{} : m.error();
}

/// 1-based line of the first line containing `needle`.
std::int64_t line_with(const std::string& text, const std::string& needle, std::size_t from = 0) {
  return 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(text.find(needle, from)), '\n');
}

TEST(FemIoFrd, BadAsciiInputNamesLineBlockAndStep) {
  const std::string good = write_frd(two_elements(), false);
  ASSERT_TRUE(read_fem([&] { write_text(temp_dir() / "good.frd", good); return temp_dir() / "good.frd"; }()));
  {  // truncated inside the node block
    const std::string t = good.substr(0, good.find(" -1        15"));
    const Error e = read_error("trunc_nodes.frd", t);
    EXPECT_NE(e.reason.find("truncated"), std::string::npos) << e.message();
    EXPECT_NE(e.reason.find("2C"), std::string::npos) << e.message();
  }
  {  // truncated inside the second DISP block
    const std::size_t at = good.rfind(" -1        52");
    const Error e = read_error("trunc_disp.frd", good.substr(0, at));
    EXPECT_NE(e.reason.find("DISP result block 2 (step 1, increment 2)"), std::string::npos) << e.message();
    EXPECT_NE(e.reason.find("truncated"), std::string::npos) << e.message();
  }
  {  // node block header says one node more than there are
    std::string t = good;
    t.replace(t.find("          28"), 12, "          29");
    const Error e = read_error("count_nodes.frd", t);
    EXPECT_NE(e.reason.find("wrong count"), std::string::npos) << e.message();
    EXPECT_EQ(e.line, line_with(t, " -3"));
  }
  {  // DISP header says 28 nodes, one record removed
    std::string t = good;
    const std::size_t at = t.find(" -1        57", t.find("100CL"));
    t.erase(at, t.find('\n', at) + 1 - at);
    const Error e = read_error("count_disp.frd", t);
    EXPECT_NE(e.reason.find("DISP result block 1"), std::string::npos) << e.message();
    EXPECT_NE(e.reason.find("wrong count"), std::string::npos) << e.message();
  }
  {  // a node DISP names that the node block does not have
    std::string t = good;
    const std::size_t at = t.find(" -1        57", t.find("100CL  102"));
    t.replace(at, 13, " -1        99");
    const Error e = read_error("unknown_node.frd", t);
    EXPECT_NE(e.reason.find("DISP result block 2 (step 1, increment 2) (time 0.5): node 99 is not defined"), std::string::npos) << e.message();
    EXPECT_EQ(e.line, line_with(t, " -1        99"));
  }
  {  // non-numbers
    std::string t = good;
    const std::size_t at = t.find(" -1        12");
    t.replace(at + 13, 12, " 1.0000x+00");
    const Error e = read_error("nan_coord.frd", t);
    EXPECT_NE(e.reason.find("node 12: malformed x coordinate"), std::string::npos) << e.message();
    EXPECT_EQ(e.line, line_with(t, "x+00"));
    std::string d = good;
    const std::size_t ad = d.find(" -1        50", d.find("100CL"));
    d.replace(ad + 13 + 12, 12, "     garbage");
    const Error ed = read_error("nan_disp.frd", d);
    EXPECT_NE(ed.reason.find("node 50: malformed value"), std::string::npos) << ed.message();
    EXPECT_NE(ed.reason.find("DISP result block 1"), std::string::npos) << ed.message();
  }
  {  // unknown element type, undefined element node
    std::string t = good;
    t.replace(t.find(" -1         9    1"), 18, " -1         9   13");
    EXPECT_NE(read_error("type.frd", t).reason.find("unknown frd element type 13"), std::string::npos);
    std::string u = good;
    const std::size_t el = u.find("    3C");
    u.replace(u.find("        50", el), 10, "       777");
    EXPECT_NE(read_error("elem_node.frd", u).reason.find("element 9: node 777 is not defined"), std::string::npos);
  }
  {  // no end record: read, with a warning; a node without DISP values: zero, with a warning
    std::string t = good.substr(0, good.find(" 9999"));
    const std::size_t at = t.find(" -1        57", t.find("100CL  102"));
    t.erase(at, t.find('\n', at) + 1 - at);
    t.replace(t.find("          28", t.find("100CL  102")), 12, "          27");
    write_text(temp_dir() / "partial.frd", t);
    const FemMesh m = must_read(temp_dir() / "partial.frd");
    ASSERT_EQ(m.warnings.size(), 2u);
    EXPECT_NE(m.warnings[0].find("9999"), std::string::npos);
    EXPECT_NE(m.warnings[1].find("1 (node, step) values absent in 1 of 2 steps"), std::string::npos) << m.warnings[1];
    const auto i57 = static_cast<std::size_t>(std::find(m.node_ids.begin(), m.node_ids.end(), 57) - m.node_ids.begin());
    EXPECT_EQ(m.fields[0].values[1][i57], (Vec3{0, 0, 0}));
    EXPECT_NE(m.fields[0].values[0][i57], (Vec3{0, 0, 0}));
  }
}

TEST(FemIoFrd, BadBinaryInputNamesByteBlockAndStep) {
  const std::string good = write_frd(two_elements(), true);
  {  // cut inside the binary node data
    const std::size_t data = good.find('\n', good.find("    2C")) + 1;
    const Error e = read_error("bin_nodes.frd", good.substr(0, data + 5 * 28 + 3));
    EXPECT_EQ(e.byte, static_cast<std::int64_t>(data + 5 * 28));
    EXPECT_NE(e.reason.find("after 5 of 28 nodes (truncated)"), std::string::npos) << e.message();
  }
  {  // cut inside the second DISP block
    const std::size_t h = good.find("1ALL", good.find("100CL  102"));
    const std::size_t data = good.find('\n', h) + 1;
    const Error e = read_error("bin_disp.frd", good.substr(0, data + 3 * 16 + 7));
    EXPECT_EQ(e.byte, static_cast<std::int64_t>(data + 3 * 16));
    EXPECT_NE(e.reason.find("DISP result block 2 (step 1, increment 2)"), std::string::npos) << e.message();
    EXPECT_NE(e.reason.find("truncated"), std::string::npos) << e.message();
  }
  {  // an unknown node id in binary DISP data
    std::string t = good;
    const std::size_t data = t.find('\n', t.find("1ALL", t.find("100CL  101"))) + 1;
    const std::int32_t bad = 4242;
    std::memcpy(t.data() + data + 16, &bad, 4);
    const Error e = read_error("bin_unknown.frd", t);
    EXPECT_EQ(e.byte, static_cast<std::int64_t>(data + 16));
    EXPECT_NE(e.reason.find("node 4242 is not defined"), std::string::npos) << e.message();
  }
}

// ---------------------------------------------------------------- truncated anywhere

/// Byte ranges of the blocks of a file written by write_frd: from the end of the block's key in
/// its header record ("2C", "3C", "100C": before it the line could be any record) to the end of
/// its last byte (ASCII: the "-3"; binary: the last datum). A file cut in [begin, end) ends
/// inside that block.
struct BlockSpan {
  std::size_t begin, end;
  std::string name;  // what the error must name
};

std::vector<BlockSpan> block_spans(const std::string& f, const Model& mod, bool binary, bool dbl) {
  std::vector<BlockSpan> r;
  auto after_line = [&](std::size_t p) { return f.find('\n', p) + 1; };
  auto ascii_end = [&](std::size_t p) { return f.find("\n -3", p) + 4; };
  const std::size_t n2 = f.find("    2C"), n3 = f.find("    3C");
  std::size_t elem_bytes = 0;
  for (const Model::Elem& e : mod.elems) elem_bytes += 4 * (4 + e.nodes.size());
  r.push_back({n2 + 6, binary ? after_line(n2) + mod.nodes.size() * 28 : ascii_end(n2), "node block (2C)"});
  r.push_back({n3 + 6, binary ? after_line(n3) + elem_bytes : ascii_end(n3), "element block (3C)"});
  std::size_t p = n3;
  for (std::size_t s = 0; s < mod.disp.size(); ++s) {
    const std::size_t h = f.find("  100CL", p);
    const std::size_t data = after_line(f.find("1ALL", h));
    const std::size_t end = binary ? data + mod.disp[s].size() * (4 + 3 * (dbl ? 8 : 4)) : ascii_end(h);
    r.push_back({h + 6, end, "result block " + std::to_string(s + 1) + " (step 1, increment " + std::to_string(s + 1) + ")"});
    p = end;
  }
  return r;
}

TEST(FemIoFrd, CutAtEveryByteIsAnErrorNamingTheBlockOrAnEarlierEnd) {
  // Every prefix of the file, in ASCII and binary (float32 and float64 results): cut inside a
  // block, an error (never a crash or a hang) naming the file, the line or byte, the block and,
  // for result blocks, the step, and saying "truncated"; cut between blocks, either an error or
  // the complete blocks before the cut (steps = the DISP blocks that ended before it).
  const Model mod = two_elements();
  for (int variant = 0; variant < 3; ++variant) {
    SCOPED_TRACE(variant);
    const bool binary = variant > 0, dbl = variant == 2;
    const std::string good = write_frd(mod, binary, dbl);
    const std::vector<BlockSpan> spans = block_spans(good, mod, binary, dbl);
    ASSERT_EQ(spans.back().end + (binary ? 0 : 1), good.find(" 9999")) << "the spans end where the end record begins";
    const fs::path p = temp_dir() / ("cut_" + std::to_string(variant) + ".frd");
    std::size_t errors = 0, reads = 0;
    for (std::size_t cut = 1; cut < good.size(); ++cut) {
      write_text(p, good.substr(0, cut));
      Expected<FemMesh> m = read_fem(p);
      const BlockSpan* in = nullptr;
      for (const BlockSpan& s : spans) {
        if (cut >= s.begin && cut < s.end) in = &s;
      }
      if (in) {
        ASSERT_FALSE(m) << "cut at byte " << cut << " inside " << in->name << " was read";
        const Error& e = m.error();
        const std::string msg = e.message();
        EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
        EXPECT_NE(e.reason.find(in->name), std::string::npos) << "cut at " << cut << ": " << msg;
        EXPECT_NE(e.reason.find("truncated"), std::string::npos) << "cut at " << cut << ": " << msg;
        EXPECT_TRUE(e.line > 0 || e.byte >= 0) << msg;
        if (!binary) EXPECT_GT(e.line, 0) << msg;
        if (binary && cut > spans[0].begin + 80) EXPECT_GE(e.byte, 0) << msg;  // past the first binary data: bytes
        ++errors;
      } else if (m) {
        std::size_t complete = 0;
        for (std::size_t s = 2; s < spans.size(); ++s) complete += spans[s].end <= cut;
        ASSERT_GE(cut, spans[1].end) << "read without elements at " << cut;
        EXPECT_EQ(m->num_elements(), 2u);
        EXPECT_EQ(m->fields.empty() ? 0u : m->fields[0].num_steps(), complete) << "cut at " << cut;
        ++reads;
      }
    }
    EXPECT_GT(errors, good.size() / 2);
    EXPECT_GT(reads, 0u);
  }
}

// ---------------------------------------------------------------- large files (mapped, parallel)

/// nx × nx × 1 hex8 cells (ids from 1), `steps` DISP steps of values with 6 significant digits.
Model grid_model(int nx, int steps) {
  Model m;
  const int p = nx + 1;
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < p; ++j) {
      for (int i = 0; i < p; ++i) m.nodes.push_back({1 + (k * p + j) * p + i, Vec3{i * 0.1, j * 0.1, k * 0.1}});
    }
  }
  auto id = [&](int i, int j, int k) { return 1 + (k * p + j) * p + i; };
  for (int j = 0; j < nx; ++j) {
    for (int i = 0; i < nx; ++i) {
      m.elems.push_back({1 + j * nx + i, 1, 1, {id(i, j, 0), id(i + 1, j, 0), id(i + 1, j + 1, 0), id(i, j + 1, 0), id(i, j, 1), id(i + 1, j, 1), id(i + 1, j + 1, 1), id(i, j + 1, 1)}});
    }
  }
  for (int s = 0; s < steps; ++s) {
    m.times.push_back(0.125 * (s + 1));
    std::vector<std::pair<int, Vec3>> d;
    for (const auto& [nid, x] : m.nodes) d.push_back({nid, Vec3{std::sin(nid * 0.37 + s) * 1e-3, -x.x * x.y * (s + 1), std::exp(-x.x) * 12.5}});
    m.disp.push_back(d);
  }
  return m;
}

/// The value the file holds for v: its %12.5E text read by strtod (the oracle, not our parser).
double as_written(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%12.5E", v);
  return std::strtod(b, nullptr);
}

TEST(FemIoFrd, LargeFilesReadExactlyAndNameTheirErrors) {
  // 4,900 cells, 10,082 nodes, 8 steps: over 1 MB (the reader maps it) and DISP blocks of more
  // than 4,096 records (read in parallel chunks). Every value is what strtod makes of its text.
  const Model mod = grid_model(70, 8);
  const std::string good = write_frd(mod, false);
  ASSERT_GT(good.size(), 2u << 20);
  const fs::path p = temp_dir() / "large.frd";
  write_text(p, good);
  const FemMesh m = must_read(p);
  ASSERT_EQ(m.num_nodes(), mod.nodes.size());
  ASSERT_EQ(m.num_elements(), mod.elems.size());
  ASSERT_EQ(m.fields.size(), 1u);
  ASSERT_EQ(m.fields[0].num_steps(), 8u);
  EXPECT_TRUE(m.warnings.empty());
  for (std::size_t i = 0; i < mod.nodes.size(); ++i) {
    ASSERT_EQ(m.node_ids[i], mod.nodes[i].first);
    ASSERT_EQ(m.nodes[i], (Vec3{as_written(mod.nodes[i].second.x), as_written(mod.nodes[i].second.y), as_written(mod.nodes[i].second.z)}));
  }
  for (std::size_t e = 0; e < mod.elems.size(); ++e) {
    ASSERT_EQ(m.elem_ids[e], mod.elems[e].id);
    ASSERT_EQ(m.elem_types[e], ElemType::hex8);
    ASSERT_EQ(m.element_size(e), 8);
    for (int q = 0; q < 8; ++q) ASSERT_EQ(m.node_ids[m.element_nodes(e)[q]], mod.elems[e].nodes[static_cast<std::size_t>(q)]) << "element " << mod.elems[e].id;
  }
  for (std::size_t s = 0; s < 8; ++s) {
    for (std::size_t i = 0; i < mod.nodes.size(); ++i) {
      ASSERT_EQ(m.node_ids[i], mod.disp[s][i].first);
      const Vec3& u = mod.disp[s][i].second;
      ASSERT_EQ(m.fields[0].values[s][i], (Vec3{as_written(u.x), as_written(u.y), as_written(u.z)})) << "step " << s << " node " << m.node_ids[i];
    }
  }
  // Records of other lengths (trailing blanks on some, CR LF on others): the same values.
  {
    std::string t;
    std::size_t k = 0;
    for (std::size_t b = 0, e; b < good.size(); b = e + 1) {
      e = good.find('\n', b);
      std::string line = good.substr(b, e - b);
      if (line.starts_with(" -1") && ++k % 7 == 0) line += k % 2 ? "   " : "\r";
      t += line + "\n";
    }
    write_text(temp_dir() / "large_ragged.frd", t);
    const FemMesh r = must_read(temp_dir() / "large_ragged.frd");
    ASSERT_EQ(r.fields.size(), 1u);
    EXPECT_EQ(r.fields[0].values, m.fields[0].values);
  }
  {  // a tet4 among the hex8 elements (records of another length): read alike
    Model mixed = mod;
    mixed.elems[2000] = {mod.elems[2000].id, 3, 1, {mod.elems[2000].nodes[0], mod.elems[2000].nodes[1], mod.elems[2000].nodes[3], mod.elems[2000].nodes[4]}};
    write_text(temp_dir() / "large_mixed.frd", write_frd(mixed, false));
    const FemMesh r = must_read(temp_dir() / "large_mixed.frd");
    ASSERT_EQ(r.num_elements(), mod.elems.size());
    EXPECT_EQ(r.elem_types[2000], ElemType::tet4);
    EXPECT_EQ(r.elem_types[2001], ElemType::hex8);
    EXPECT_EQ(r.node_ids[r.element_nodes(2000)[3]], mod.elems[2000].nodes[4]);
    EXPECT_EQ(r.node_ids[r.element_nodes(4899)[7]], mod.elems[4899].nodes[7]);
  }
  const std::size_t elems = good.find("    3C");
  {  // an element naming an undefined node, deep in the element block: its line
    std::string t = good;
    const std::size_t at = t.find(" -1      3000", elems);
    const std::size_t nodes_line = t.find('\n', at) + 1;
    t.replace(nodes_line + 3, 10, "     99999");
    const Error e = read_error("large_elem_node.frd", t);
    EXPECT_NE(e.reason.find("element block (3C): element 3000: node 99999 is not defined"), std::string::npos) << e.message();
    EXPECT_EQ(e.line, line_with(t, "     99999"));
  }
  {  // a malformed coordinate and a repeated node id deep in the node block: their lines
    std::string t = good;
    const std::size_t at = t.find(" -1      7000");
    t.replace(at + 13 + 12, 12, " 1.00000Q+00");
    const Error e = read_error("large_coord.frd", t);
    EXPECT_NE(e.reason.find("node block (2C): node 7000: malformed y coordinate"), std::string::npos) << e.message();
    EXPECT_EQ(e.line, line_with(t, "Q+00"));
    std::string d = good;
    const std::size_t ad = d.find(" -1      7001");
    d.replace(ad, 13, " -1      6999");
    const Error ed = read_error("large_dup.frd", d);
    EXPECT_NE(ed.reason.find("duplicate node id 6999"), std::string::npos) << ed.message();
    EXPECT_EQ(ed.line, 1 + std::count(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(ad), '\n'));
  }
  const std::size_t last = good.find("  100CL  108");
  {  // an unknown node deep in the last DISP block: its line, the block and the step
    std::string t = good;
    const std::size_t at = t.find(" -1      9000", last);
    t.replace(at, 13, " -1     99999");
    const Error e = read_error("large_unknown.frd", t);
    EXPECT_NE(e.reason.find("DISP result block 8 (step 1, increment 8) (time 1): node 99999 is not defined"), std::string::npos) << e.message();
    EXPECT_EQ(e.line, line_with(t, " -1     99999"));
  }
  {  // a node twice: the line of the second record
    std::string t = good;
    const std::size_t at = t.find(" -1      9000", last);
    t.replace(at, 13, " -1      8999");
    const Error e = read_error("large_twice.frd", t);
    EXPECT_NE(e.reason.find("node 8999 appears twice"), std::string::npos) << e.message();
    EXPECT_EQ(e.line, 1 + std::count(t.begin(), t.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
    EXPECT_GT(at, t.find(" -1      8999", last));  // after the first
  }
  {  // a malformed value and a NaN
    std::string t = good;
    const std::size_t at = t.find(" -1      5000", last);
    t.replace(at + 13 + 12, 12, " 1.23456X-01");
    const Error e = read_error("large_malformed.frd", t);
    EXPECT_NE(e.reason.find("node 5000: malformed value '1.23456X-01'"), std::string::npos) << e.message();
    EXPECT_EQ(e.line, line_with(t, "X-01"));
    std::string n = good;
    n.replace(at + 13, 12, "         NaN");
    EXPECT_NE(read_error("large_nan.frd", n).reason.find("node 5000: non-finite D1"), std::string::npos);
  }
  {  // cut inside the last DISP block, at a line end and inside a line
    const std::size_t at = good.find(" -1      7000", last);
    for (const std::size_t cut : {at, at + 30}) {
      const Error e = read_error("large_cut.frd", good.substr(0, cut));
      EXPECT_NE(e.reason.find("DISP result block 8 (step 1, increment 8)"), std::string::npos) << e.message();
      EXPECT_NE(e.reason.find("truncated"), std::string::npos) << e.message();
      EXPECT_EQ(e.line, line_with(good, " -1      7000", last) - (cut == at ? 1 : 0)) << e.message();
    }
  }
}

}  // namespace
}  // namespace interfere::fem_test
