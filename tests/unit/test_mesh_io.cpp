// Mesh IO: round trips of every format, flavour detection, hand-built files (PLY endianness, extra
// properties and elements, OBJ relative indices, OFF variants), and every bad-input case with its
// file, line or byte offset and reason; atomic writes.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "interfere/mesh/generate.h"
#include "interfere/mesh/io.h"
#include "interfere/mesh/validate.h"

namespace interfere {
namespace {

namespace fs = std::filesystem;

/// A fresh directory per test under the system temp dir, removed afterwards.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string("interfere_io_") + (info ? info->name() : "x") + "_" +
                       std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
                       std::to_string(counter++) + "_" +
                       std::to_string(reinterpret_cast<std::uintptr_t>(this) & 0xffffff);
    for (char& c : name) {
      if (c == '/') c = '_';
    }
    path_ = fs::temp_directory_path() / name;
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  fs::path operator/(const std::string& f) const { return path_ / f; }
  const fs::path& path() const { return path_; }
  std::size_t file_count() const {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(path_)) ++n;
    return n;
  }

 private:
  fs::path path_;
};

void put_file(const fs::path& p, std::string_view bytes) {
  std::ofstream f(p, std::ios::binary);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string get_file(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

/// Little/big-endian byte builder for hand-made binary files.
struct Bytes {
  std::string s;
  bool big = false;
  template <class T>
  Bytes& put(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (big != (std::endian::native == std::endian::big)) std::reverse(b, b + sizeof(T));
    s.append(b, sizeof(T));
    return *this;
  }
  Bytes& text(std::string_view t) {
    s.append(t);
    return *this;
  }
};

std::string stl_binary(const std::vector<std::array<float, 9>>& facets,
                       std::string header = "test") {
  Bytes b;
  header.resize(80, ' ');
  b.text(header).put(static_cast<std::uint32_t>(facets.size()));
  for (const auto& f : facets) {
    b.put(0.0f).put(0.0f).put(1.0f);
    for (float x : f) b.put(x);
    b.put(std::uint16_t{0});
  }
  return b.s;
}

TriMesh test_mesh() {
  // Irregular double coordinates (not float-representable), 2-manifold, ~200 triangles.
  return make_sphere(
      {.target_triangles = 200, .radius = 1.3, .center = {0.1, -0.2, 0.3}, .bump_amplitude = 0.05});
}

double to_float(double x) {
  // Through a volatile: GCC 12.2 at -O2 (SLP vectorizer) drops paired (double)(float)x round trips.
  volatile float f = static_cast<float>(x);
  return f;
}

TriMesh float_rounded(TriMesh m) {
  for (Vec3& p : m.positions) p = {to_float(p.x), to_float(p.y), to_float(p.z)};
  return m;
}

/// Same triangles in the same order with the same corner positions (exactly).
void expect_same_triangles(const TriMesh& expected, const TriMesh& got) {
  ASSERT_EQ(expected.num_triangles(), got.num_triangles());
  for (std::size_t t = 0; t < expected.num_triangles(); ++t) {
    const auto a = expected.corners(t), b = got.corners(t);
    for (std::size_t k = 0; k < 3; ++k)
      ASSERT_EQ(a[k], b[k]) << "triangle " << t << " corner " << k;
  }
}

/// Expects an error about `file` at `line` (text) or `byte` (binary) whose reason contains `what`.
void expect_error(const Expected<TriMesh>& r, const fs::path& file, std::int64_t line,
                  std::int64_t byte, const std::string& what) {
  ASSERT_FALSE(r.has_value()) << "expected an error containing '" << what << "'";
  const Error& e = r.error();
  EXPECT_EQ(e.file, file.string());
  EXPECT_EQ(e.line, line) << e.message();
  EXPECT_EQ(e.byte, byte) << e.message();
  EXPECT_NE(e.reason.find(what), std::string::npos)
      << "reason: " << e.reason << "\nwanted: " << what;
}

Expected<TriMesh> read_text(const TempDir& dir, const std::string& name, std::string_view content,
                            MeshReadInfo* info = nullptr, ReadOptions options = {}) {
  put_file(dir / name, content);
  return read_mesh(dir / name, options, info);
}

// ---------------------------------------------------------------------------------------------
// Round trips

struct RoundTripCase {
  MeshFormat format;
  const char* file;
  bool float_precision;
  bool ply_float = false;
};

class RoundTrip : public ::testing::TestWithParam<RoundTripCase> {};

TEST_P(RoundTrip, SameTrianglesSameOrderSamePositions) {
  const RoundTripCase c = GetParam();
  TempDir dir;
  const TriMesh m = test_mesh();
  ASSERT_TRUE(write_mesh(dir / c.file, m, {.format = c.format, .ply_float = c.ply_float}));
  MeshReadInfo info;
  auto r = read_mesh(dir / c.file, {}, &info);
  ASSERT_TRUE(r) << r.error().message();
  EXPECT_EQ(info.format, c.format);
  expect_same_triangles(c.float_precision ? float_rounded(m) : m, *r);
  EXPECT_EQ(r->num_vertices(), m.num_vertices());
  EXPECT_EQ(dir.file_count(), 1u);  // no temporary file left behind
}

INSTANTIATE_TEST_SUITE_P(
    AllFormats, RoundTrip,
    ::testing::Values(RoundTripCase{MeshFormat::stl_binary, "m.stl", true},
                      RoundTripCase{MeshFormat::stl_ascii, "m.stl", false},
                      RoundTripCase{MeshFormat::obj, "m.obj", false},
                      RoundTripCase{MeshFormat::ply_ascii, "m.ply", false},
                      RoundTripCase{MeshFormat::ply_binary_le, "m.ply", false},
                      RoundTripCase{MeshFormat::ply_binary_be, "m.ply", false},
                      RoundTripCase{MeshFormat::ply_binary_le, "m.ply", true, true},
                      RoundTripCase{MeshFormat::ply_ascii, "m.ply", true, true},
                      RoundTripCase{MeshFormat::off, "m.off", false}),
    [](const auto& info) {
      return std::string(mesh_format_name(info.param.format)).replace(3, 1, "_") +
             (info.param.ply_float ? "_float" : "");
    });

TEST(MeshIo, FormatFromExtensionWhenWriting) {
  TempDir dir;
  const TriMesh m = test_mesh();
  MeshReadInfo info;
  ASSERT_TRUE(write_mesh(dir / "a.STL", m));
  ASSERT_TRUE(read_mesh(dir / "a.STL", {}, &info));
  EXPECT_EQ(info.format, MeshFormat::stl_binary);
  ASSERT_TRUE(write_mesh(dir / "a.ply", m));
  ASSERT_TRUE(read_mesh(dir / "a.ply", {}, &info));
  EXPECT_EQ(info.format, MeshFormat::ply_binary_le);
  const Status s = write_mesh(dir / "a.xyz", m);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().reason.find("extension"), std::string::npos);
}

TEST(MeshIo, FormatDetectedFromContentForUnknownExtension) {
  TempDir dir;
  const TriMesh m = test_mesh();
  for (MeshFormat f : {MeshFormat::stl_binary, MeshFormat::stl_ascii, MeshFormat::obj,
                       MeshFormat::ply_ascii, MeshFormat::ply_binary_be, MeshFormat::off}) {
    ASSERT_TRUE(write_mesh(dir / "mesh.dat", m, {.format = f}));
    MeshReadInfo info;
    auto r = read_mesh(dir / "mesh.dat", {}, &info);
    ASSERT_TRUE(r) << mesh_format_name(f) << ": " << r.error().message();
    EXPECT_EQ(info.format, f);
    EXPECT_EQ(r->num_triangles(), m.num_triangles());
  }
  put_file(dir / "junk.dat", "hello world\n");
  auto r = read_mesh(dir / "junk.dat");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().reason.find("cannot tell the mesh format"), std::string::npos);
  // A forced format wins over the extension.
  ASSERT_TRUE(write_mesh(dir / "really_obj.stl", m, {.format = MeshFormat::obj}));
  EXPECT_TRUE(read_mesh(dir / "really_obj.stl", {.format = MeshFormat::obj}));
}

TEST(MeshIo, FormatNames) {
  EXPECT_EQ(mesh_format_from_name("stl"), MeshFormat::stl_binary);
  EXPECT_EQ(mesh_format_from_name("STL_ASCII"), MeshFormat::stl_ascii);
  EXPECT_EQ(mesh_format_from_name("ply"), MeshFormat::ply_binary_le);
  EXPECT_EQ(mesh_format_from_name("ply-be"), MeshFormat::ply_binary_be);
  EXPECT_EQ(mesh_format_from_name("ply-ascii"), MeshFormat::ply_ascii);
  EXPECT_EQ(mesh_format_from_name("off"), MeshFormat::off);
  EXPECT_EQ(mesh_format_from_name("obj"), MeshFormat::obj);
  EXPECT_EQ(mesh_format_from_name("nope"), MeshFormat::automatic);
  for (MeshFormat f :
       {MeshFormat::stl_ascii, MeshFormat::stl_binary, MeshFormat::obj, MeshFormat::ply_ascii,
        MeshFormat::ply_binary_le, MeshFormat::ply_binary_be, MeshFormat::off}) {
    EXPECT_EQ(mesh_format_from_name(mesh_format_name(f)), f);
  }
}

// ---------------------------------------------------------------------------------------------
// STL

TEST(Stl, BinaryAndAsciiGiveTheSameMesh) {
  TempDir dir;
  const TriMesh m = float_rounded(test_mesh());
  ASSERT_TRUE(write_mesh(dir / "b.stl", m, {.format = MeshFormat::stl_binary}));
  ASSERT_TRUE(write_mesh(dir / "a.stl", m, {.format = MeshFormat::stl_ascii}));
  auto a = read_mesh(dir / "a.stl");
  auto b = read_mesh(dir / "b.stl");
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->positions, b->positions);
  EXPECT_EQ(a->triangles, b->triangles);
  expect_same_triangles(m, *a);
}

TEST(Stl, BinaryWithSolidHeaderIsDetectedBySize) {
  TempDir dir;
  MeshReadInfo info;
  auto r =
      read_text(dir, "s.stl",
                stl_binary({{0, 0, 0, 1, 0, 0, 0, 1, 0}}, "solid pretending to be ascii"), &info);
  ASSERT_TRUE(r) << r.error().message();
  EXPECT_EQ(info.format, MeshFormat::stl_binary);
  EXPECT_EQ(r->num_triangles(), 1u);
}

TEST(Stl, BinaryHeaderNormalsAndAttributeBytes) {
  TempDir dir;
  TriMesh m;
  m.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {5, 5, 5}};
  m.triangles = {{0, 1, 2}, {0, 0, 3}};  // the second is degenerate: zero normal
  ASSERT_TRUE(write_mesh(dir / "n.stl", m));
  const std::string bytes = get_file(dir / "n.stl");
  ASSERT_EQ(bytes.size(), 84u + 2 * 50u);
  EXPECT_NE(bytes.substr(0, 5), "solid");
  std::uint32_t n;
  std::memcpy(&n, bytes.data() + 80, 4);
  EXPECT_EQ(n, 2u);
  float f[12];
  std::memcpy(f, bytes.data() + 84, sizeof f);
  EXPECT_EQ(f[0], 0.0f);
  EXPECT_EQ(f[1], 0.0f);
  EXPECT_EQ(f[2], 1.0f);
  EXPECT_EQ(f[6], 2.0f);
  EXPECT_EQ(bytes[84 + 48], 0);
  EXPECT_EQ(bytes[84 + 49], 0);
  std::memcpy(f, bytes.data() + 134, sizeof f);
  EXPECT_EQ(f[0], 0.0f);
  EXPECT_EQ(f[1], 0.0f);
  EXPECT_EQ(f[2], 0.0f);
}

TEST(Stl, SoupIsWeldedKeepingTriangleOrder) {
  TempDir dir;
  // Two triangles sharing an edge, the shared corners spelled +0 and -0.
  const std::string file =
      stl_binary({{0, 0, 0, 1, 0, 0, 0, 1, 0}, {1, 0, 0, 1, 1, 0, -0.0f, 1, 0}});
  put_file(dir / "w.stl", file);
  MeshReadInfo info;
  auto r = read_mesh(dir / "w.stl", {}, &info);
  ASSERT_TRUE(r);
  EXPECT_EQ(info.vertices_before_weld, 6u);
  EXPECT_EQ(r->num_vertices(), 4u);
  EXPECT_EQ(r->triangles, (std::vector<Tri>{{0, 1, 2}, {1, 3, 2}}));
  EXPECT_EQ(r->positions[3], (Vec3{1, 1, 0}));
  auto raw = read_mesh(dir / "w.stl", {.weld = false});
  ASSERT_TRUE(raw);
  EXPECT_EQ(raw->num_vertices(), 6u);
  EXPECT_EQ(raw->triangles, (std::vector<Tri>{{0, 1, 2}, {3, 4, 5}}));
}

TEST(Stl, WeldedBinaryReadEqualsWeldExactOnTheSoup) {
  // ~100k corners in shuffled facet order (no locality: most duplicates are found by the global
  // pass), with signed zeros, across several chunks and hash partitions.
  TempDir dir;
  const TriMesh m = float_rounded(make_sphere({.target_triangles = 34000, .radius = 2.0}));
  std::vector<std::size_t> order(m.num_triangles());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::mt19937_64 rng(3);
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<std::array<float, 9>> facets;
  for (std::size_t t : order) {
    std::array<float, 9> f;
    const auto c = m.corners(t);
    for (std::size_t k = 0; k < 9; ++k) f[k] = static_cast<float>(c[k / 3][k % 3]);
    for (float& x : f) {
      if (x == 0 && rng() % 2) x = -0.0f;
    }
    facets.push_back(f);
  }
  put_file(dir / "s.stl", stl_binary(facets));
  MeshReadInfo info;
  auto welded = read_mesh(dir / "s.stl", {}, &info);
  auto soup = read_mesh(dir / "s.stl", {.weld = false});
  ASSERT_TRUE(welded && soup);
  EXPECT_EQ(info.vertices_before_weld, 3 * m.num_triangles());
  TriMesh reference = *soup;
  weld_exact(reference);
  EXPECT_EQ(welded->triangles, reference.triangles);
  EXPECT_EQ(welded->positions, reference.positions);
  EXPECT_EQ(welded->num_vertices(), m.num_vertices());
}

TEST(Stl, AsciiVariants) {
  TempDir dir;
  MeshReadInfo info;
  // Upper case keywords, '+' signs, exponent, NaN normal, a quad loop, two solids, CRLF.
  auto r = read_text(
      dir, "v.stl",
      "SOLID part one\r\n"
      "  FACET NORMAL nan nan nan\r\n    OUTER LOOP\r\n"
      "      VERTEX +0 0 0\r\n      VERTEX 1e0 0 0\r\n      VERTEX 0 1.0 -0\r\n"
      "    ENDLOOP\r\n  ENDFACET\r\nENDSOLID part one\r\n"
      "solid two\nfacet normal 0 0 1\nouter loop\nvertex 0 0 1\nvertex 1 0 1\nvertex 1 1 1\n"
      "vertex 0 1 1\nendloop\nendfacet\nendsolid\n",
      &info);
  ASSERT_TRUE(r) << r.error().message();
  EXPECT_EQ(info.format, MeshFormat::stl_ascii);
  EXPECT_EQ(info.polygons_split, 1u);
  ASSERT_EQ(r->num_triangles(), 3u);
  EXPECT_EQ(r->corners(2)[2], (Vec3{0, 1, 1}));
}

TEST(Stl, Utf8ByteOrderMarkBeforeText) {
  TempDir dir;
  auto r = read_text(dir, "bom.stl",
                     "\xEF\xBB\xBFsolid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 "
                     "0 0\nvertex 0 1 0\n"
                     "endloop\nendfacet\nendsolid x\n");
  ASSERT_TRUE(r) << r.error().message();
  auto o = read_text(dir, "bom.obj", "\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  ASSERT_TRUE(o) << o.error().message();
}

TEST(StlErrors, TruncatedBinary) {
  TempDir dir;
  std::string b = stl_binary({{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 0, 1, 0, 0, 0, 1, 0}});
  b.resize(84 + 50 + 20);
  expect_error(read_text(dir, "t.stl", b), dir / "t.stl", -1, 154, "truncated binary STL");
  // Even when the header starts with "solid".
  std::string s = stl_binary({{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 0, 1, 0, 0, 0, 1, 0}}, "solid x");
  s.resize(120);
  expect_error(read_text(dir, "s.stl", s), dir / "s.stl", -1, 120, "it ends inside triangle 0");
  // Shorter than the header.
  expect_error(read_text(dir, "h.stl", std::string(40, '\x01')), dir / "h.stl", -1, 40, "header");
}

TEST(StlErrors, BinaryCountMismatchAndNoTriangles) {
  TempDir dir;
  std::string b = stl_binary({{0, 0, 0, 1, 0, 0, 0, 1, 0}});
  b += std::string(7, '\0');
  expect_error(read_text(dir, "x.stl", b), dir / "x.stl", -1, 134, "7 bytes after the 1 triangle");
  expect_error(read_text(dir, "z.stl", stl_binary({})), dir / "z.stl", -1, 80, "no triangles");
}

TEST(StlErrors, AbsurdBinaryCountDoesNotAllocate) {
  TempDir dir;
  Bytes b;
  b.text(std::string(80, 'x')).put(std::uint32_t{0xffffffffu});
  b.text(std::string(50, '\0'));
  expect_error(read_text(dir, "big.stl", b.s), dir / "big.stl", -1, 134, "4294967295 triangles");
}

TEST(StlErrors, NonFiniteBinaryCoordinate) {
  TempDir dir;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  expect_error(read_text(dir, "n.stl",
                         stl_binary({{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 0, 1, nan, 0, 0, 1, 0}})),
               dir / "n.stl", -1, 84 + 50 + 12 + 4 * 4,
               "non-finite coordinate (NaN) in vertex 1 of triangle 1");
  expect_error(read_text(dir, "i.stl", stl_binary({{0, 0, 0, 1, 0, 0, 0, 1, inf}})), dir / "i.stl",
               -1, 84 + 12 + 8 * 4, "(Inf)");
  put_file(dir / "n2.stl", stl_binary({{0, 0, 0, 1, 0, 0, 0, 1, 0},
                                       {0, 0, 0, 1, 0, 0, 0, 1, 0},
                                       {0, 0, -inf, 1, 0, 0, 0, 1, 0}}));
  expect_error(read_mesh(dir / "n2.stl", {.weld = false}), dir / "n2.stl", -1, 84 + 100 + 12 + 8,
               "in vertex 0 of triangle 2");
}

TEST(StlErrors, AsciiProblemsHaveLines) {
  TempDir dir;
  const std::string head = "solid t\nfacet normal 0 0 1\n outer loop\n";
  expect_error(read_text(dir, "a.stl", head + "  vertex 0 0 0\n  vertex 1 0"), dir / "a.stl", 5, -1,
               "unexpected end of file inside the facet that starts at line 2");
  expect_error(
      read_text(dir, "b.stl", head + "  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\n"),
      dir / "b.stl", 7, -1, "expected 'endfacet'");
  expect_error(read_text(dir, "c.stl", head + "  vertex 0 0 0\n  vertex 1 0x 0\n"), dir / "c.stl",
               5, -1, "malformed number '0x' (vertex y)");
  expect_error(read_text(dir, "d.stl", head + "  vertex 0 0 0\n  vertex 1 inf 0\n"), dir / "d.stl",
               5, -1, "non-finite coordinate 'inf'");
  expect_error(read_text(dir, "e.stl",
                         head + "  vertex 0 0 0\n  vertex 1 0 0\n endloop\nendfacet\nendsolid\n"),
               dir / "e.stl", 6, -1, "has 2 vertices; at least 3");
  expect_error(read_text(dir, "f.stl",
                         head + "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"),
               dir / "f.stl", 8, -1, "missing 'endsolid'");
  expect_error(read_text(dir, "g.stl", "solid empty\nendsolid empty\n"), dir / "g.stl", 2, -1,
               "no triangles");
  expect_error(read_text(dir, "h.stl", "solid t\nfacet normal 0 0 1\n outer lop\n"), dir / "h.stl",
               3, -1, "expected 'loop', found 'lop'");
  expect_error(read_text(dir, "i.stl", "solid t\nfacet normal 0 zero 1\n"), dir / "i.stl", 2, -1,
               "malformed number 'zero' (normal component)");
}

TEST(IoErrors, MissingEmptyAndDirectory) {
  TempDir dir;
  auto r = read_mesh(dir / "missing.stl");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().file, (dir / "missing.stl").string());
  EXPECT_NE(r.error().reason.find("cannot open"), std::string::npos);
  EXPECT_NE(r.error().message().find("missing.stl"), std::string::npos);
  expect_error(read_text(dir, "empty.obj", ""), dir / "empty.obj", -1, 0, "file is empty");
  fs::create_directory(dir / "d.stl");
  auto d = read_mesh(dir / "d.stl");
  ASSERT_FALSE(d);
  EXPECT_NE(d.error().reason.find("directory"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// OBJ

TEST(Obj, NegativeIndicesPolygonsAndCornerForms) {
  TempDir dir;
  MeshReadInfo info;
  auto r = read_text(
      dir, "p.obj",
      "# comment\nmtllib x.mtl\no square\nv 0 0 0\nv 1 0 0\nv 1 1 0 1.0\nv 0 1 0 0.5 0.5 0.5\n"
      "vt 0 0\nvn 0 0 1\ng g1\nusemtl m\ns off\n"
      "f -4/1/1 -3/1/1 -2/1/1 -1/1/1\n"  // quad, relative
      "f 1//1 3//1 4//1 # trailing comment\n"
      "l 1 2\nv 0 0 1\nf 1/1 2/1 -1/1\n",
      &info);
  ASSERT_TRUE(r) << r.error().message();
  EXPECT_EQ(info.polygons_split, 1u);
  ASSERT_EQ(r->num_triangles(), 4u);
  EXPECT_EQ(r->corners(0)[1], (Vec3{1, 0, 0}));
  EXPECT_EQ(r->corners(1)[1], (Vec3{1, 1, 0}));  // fan: (v0, v2, v3)
  EXPECT_EQ(r->corners(1)[2], (Vec3{0, 1, 0}));
  EXPECT_EQ(r->corners(3)[2], (Vec3{0, 0, 1}));  // -1 after the fifth v = the fifth vertex
  // Forward references are allowed.
  auto f = read_text(dir, "fwd.obj", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
  ASSERT_TRUE(f) << f.error().message();
}

TEST(ObjErrors, EveryProblemHasItsLine) {
  TempDir dir;
  const std::string v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expect_error(read_text(dir, "a.obj", v3 + "f 1 2 4\n"), dir / "a.obj", 4, -1,
               "vertex index 4 out of range");
  expect_error(read_text(dir, "b.obj", v3 + "f 1 2 -4\n"), dir / "b.obj", 4, -1,
               "relative vertex index -4 refers before the first vertex");
  expect_error(read_text(dir, "c.obj", v3 + "f 1 2 0\n"), dir / "c.obj", 4, -1,
               "index 0 is invalid");
  expect_error(read_text(dir, "d.obj", v3 + "f 1 2\n"), dir / "d.obj", 4, -1, "face has 2 corners");
  expect_error(read_text(dir, "e.obj", "v 0 0 0\nv 1 0.0.0 0\n"), dir / "e.obj", 2, -1,
               "malformed number '0.0.0'");
  expect_error(read_text(dir, "f.obj", "v 0 0 0\n\nv 1 nan 0\n"), dir / "f.obj", 3, -1,
               "non-finite coordinate 'nan'");
  expect_error(read_text(dir, "g.obj", "v 0 0\n"), dir / "g.obj", 1, -1,
               "vertex has 2 coordinates");
  expect_error(read_text(dir, "h.obj", v3 + "f 1 2x 3\n"), dir / "h.obj", 4, -1,
               "malformed vertex index '2x'");
  expect_error(read_text(dir, "i.obj", v3 + "f 1 /2 3\n"), dir / "i.obj", 4, -1,
               "has no vertex index");
  expect_error(read_text(dir, "j.obj", v3 + "# no faces\n"), dir / "j.obj", 4, -1, "no triangles");
  expect_error(read_text(dir, "k.obj", v3 + "f 1 2 3\nf 1 2 99999999999\n"), dir / "k.obj", 5, -1,
               "out of range");
}

// ---------------------------------------------------------------------------------------------
// PLY

/// A PLY whose vertices have extra properties in a scrambled order (double z, float x, uchar red,
/// float y), an `edge` element with a list before the faces, uchar/int face lists with a quad, and
/// a trailing `material` element; in the requested encoding.
std::string tricky_ply(const std::string& format) {
  std::string h = "ply\nformat " + format +
                  " 1.0\ncomment made by hand\nobj_info x\n"
                  "element vertex 4\nproperty double z\nproperty float x\nproperty uchar "
                  "red\nproperty float y\n"
                  "element edge 1\nproperty list uchar int vertex_pair\nproperty short crease\n"
                  "element face 2\nproperty uchar flags\nproperty list uchar int vertex_indices\n"
                  "property list int float texcoord\n"
                  "element material 1\nproperty ushort id\nend_header\n";
  const double z[4] = {0.5, 0.25, -1, 3};
  const float x[4] = {0, 1, 1, 0}, y[4] = {0, 0, 1, 1};
  if (format == "ascii") {
    return h +
           "0.5 0 255 0\n0.25 1 0 0\n-1 1 7 1\n3 0 1 1\n2 0 1 -3\n1 4 0 1 2 3 2 0.5 0.5\n0 3 3 2 1 "
           "0\n65535\n";
  }
  Bytes b;
  b.big = format == "binary_big_endian";
  b.text(h);
  for (int i = 0; i < 4; ++i) b.put(z[i]).put(x[i]).put(std::uint8_t{9}).put(y[i]);
  b.put(std::uint8_t{2}).put(std::int32_t{0}).put(std::int32_t{1}).put(std::int16_t{-3});
  b.put(std::uint8_t{1}).put(std::uint8_t{4});
  for (std::int32_t v : {0, 1, 2, 3}) b.put(v);
  b.put(std::int32_t{2}).put(0.5f).put(0.5f);
  b.put(std::uint8_t{0}).put(std::uint8_t{3});
  for (std::int32_t v : {3, 2, 1}) b.put(v);
  b.put(std::int32_t{0});
  b.put(std::uint16_t{65535});
  return b.s;
}

TEST(Ply, AsciiLittleAndBigEndianReadTheSame) {
  TempDir dir;
  std::vector<TriMesh> got;
  for (const std::string f : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    MeshReadInfo info;
    auto r = read_text(dir, f + ".ply", tricky_ply(f), &info, {.weld = false});
    ASSERT_TRUE(r) << f << ": " << r.error().message();
    EXPECT_EQ(info.polygons_split, 1u);
    EXPECT_EQ(info.format, f == "ascii"                  ? MeshFormat::ply_ascii
                           : f == "binary_little_endian" ? MeshFormat::ply_binary_le
                                                         : MeshFormat::ply_binary_be);
    got.push_back(*r);
  }
  const std::vector<Vec3> expected_positions = {{0, 0, 0.5}, {1, 0, 0.25}, {1, 1, -1}, {0, 1, 3}};
  const std::vector<Tri> expected_triangles = {{0, 1, 2}, {0, 2, 3}, {3, 2, 1}};
  for (const TriMesh& m : got) {
    EXPECT_EQ(m.positions, expected_positions);
    EXPECT_EQ(m.triangles, expected_triangles);
  }
}

TEST(Ply, VertexIndexNameAndUintTypes) {
  TempDir dir;
  Bytes b;
  b.text(
      "ply\r\nformat binary_little_endian 1.0\r\nelement vertex 3\r\nproperty float32 "
      "x\r\nproperty float32 y\r\n"
      "property float32 z\r\nelement face 1\r\nproperty list uint uint "
      "vertex_index\r\nend_header\r\n");
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) b.put(v);
  b.put(std::uint32_t{3}).put(std::uint32_t{0}).put(std::uint32_t{1}).put(std::uint32_t{2});
  auto r = read_text(dir, "u.ply", b.s);
  ASSERT_TRUE(r) << r.error().message();
  EXPECT_EQ(r->num_triangles(), 1u);
}

std::string ply_ascii_header(int nv, int nf, const std::string& extra = "") {
  return "ply\nformat ascii 1.0\nelement vertex " + std::to_string(nv) +
         "\nproperty float x\nproperty float y\nproperty float z\n" + extra + "element face " +
         std::to_string(nf) + "\nproperty list uchar int vertex_indices\nend_header\n";
}

TEST(PlyErrors, Header) {
  TempDir dir;
  expect_error(read_text(dir, "a.ply", "plyx\n"), dir / "a.ply", 1, -1, "first line must be 'ply'");
  expect_error(read_text(dir, "b.ply", "ply\nformat binary_middle_endian 1.0\n"), dir / "b.ply", 2,
               -1, "unknown PLY format 'binary_middle_endian'");
  expect_error(
      read_text(dir, "c.ply",
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n"),
      dir / "c.ply", 4, -1, "unknown PLY property type 'float128'");
  expect_error(
      read_text(dir, "d.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"),
      dir / "d.ply", 4, -1, "no 'end_header'");
  expect_error(
      read_text(
          dir, "e.ply",
          "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
          "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0\n3 0 0 0\n"),
      dir / "e.ply", 3, -1, "no property 'z'");
  expect_error(
      read_text(dir, "f.ply",
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                "property float z\nelement face 1\nproperty list uchar int corners\nend_header\n"),
      dir / "f.ply", 7, -1, "no list property 'vertex_indices'");
  expect_error(
      read_text(dir, "g.ply",
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                "property float z\nelement face 1\nproperty list uchar float "
                "vertex_indices\nend_header\n"),
      dir / "g.ply", 7, -1, "face index type must be an integer type");
  expect_error(read_text(dir, "h.ply", ply_ascii_header(3, 0) + "0 0 0\n1 0 0\n0 1 0\n"),
               dir / "h.ply", 9, -1, "no triangles");
  expect_error(read_text(dir, "i.ply", "ply\nformat ascii 1.0\nbogus line\n"), dir / "i.ply", 3, -1,
               "unknown PLY header keyword 'bogus'");
}

TEST(PlyErrors, AsciiBody) {
  TempDir dir;
  const std::string h = ply_ascii_header(3, 1);  // 9 header lines
  const std::string v = "0 0 0\n1 0 0\n0 1 0\n";
  expect_error(read_text(dir, "a.ply", h + v + "3 0 1 3\n"), dir / "a.ply", 13, -1,
               "vertex index 3 out of range [0, 3)");
  expect_error(read_text(dir, "b.ply", h + v + "3 0 -1 2\n"), dir / "b.ply", 13, -1,
               "vertex index -1 out of range");
  expect_error(read_text(dir, "c.ply", h + v + "2 0 1\n"), dir / "c.ply", 13, -1,
               "face 0 has 2 corners");
  expect_error(read_text(dir, "d.ply", h + "0 0 0\n1 0 0\n0 nan 0\n3 0 1 2\n"), dir / "d.ply", 12,
               -1, "non-finite coordinate 'nan'");
  expect_error(read_text(dir, "e.ply", h + "0 0 0\n1 0 0\n0 1e 0\n3 0 1 2\n"), dir / "e.ply", 12,
               -1, "malformed float value '1e'");
  expect_error(read_text(dir, "f.ply", h + v + "3 0 1"), dir / "f.ply", 13, -1,
               "file ends inside element 'face' (instance 0 of 1)");
  expect_error(read_text(dir, "g.ply", h + v + "3 0 1 2\n3 0 1 2\n"), dir / "g.ply", 14, -1,
               "after the last element (element counts do not match)");
  expect_error(read_text(dir, "h.ply", h + v + "300 0 1 2\n"), dir / "h.ply", 13, -1,
               "out of range for type uchar");
  // Absurd count: rejected against the file size before anything is allocated.
  expect_error(read_text(dir, "i.ply", ply_ascii_header(2000000000, 1) + v + "3 0 1 2\n"),
               dir / "i.ply", 3, -1, "declares 2000000000 instances");
}

std::string ply_binary(int nv, int nf, const std::vector<float>& xyz,
                       const std::vector<std::int32_t>& faces) {
  Bytes b;
  b.text("ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(nv) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
         std::to_string(nf) + "\nproperty list uchar int vertex_indices\nend_header\n");
  for (float v : xyz) b.put(v);
  for (std::size_t i = 0; i < faces.size();) {
    const auto n = static_cast<std::uint8_t>(faces[i++]);
    b.put(n);
    for (int k = 0; k < n && i < faces.size(); ++k) b.put(faces[i++]);
  }
  return b.s;
}

TEST(PlyErrors, BinaryBody) {
  TempDir dir;
  const std::vector<float> v = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::string ok = ply_binary(3, 1, v, {3, 0, 1, 2});
  const std::size_t header = ok.size() - 36 - 13;
  ASSERT_TRUE(read_text(dir, "ok.ply", ok));
  // Ends early inside the face list.
  std::string t = ok;
  t.resize(t.size() - 2);
  expect_error(read_text(dir, "a.ply", t), dir / "a.ply", -1,
               static_cast<std::int64_t>(header + 36),
               "file ends early: element 'face' instance 0 of 1 needs 13 more bytes, 11 remain");
  // Ends inside the vertices.
  std::string tv = ok.substr(0, header + 20);
  expect_error(read_text(dir, "b.ply", tv), dir / "b.ply", -1, static_cast<std::int64_t>(tv.size()),
               "file ends early");
  // Index out of range: byte offset of the bad index.
  expect_error(read_text(dir, "c.ply", ply_binary(3, 1, v, {3, 0, 7, 2})), dir / "c.ply", -1,
               static_cast<std::int64_t>(header + 36 + 1 + 4),
               "vertex index 7 out of range [0, 3) in face 0");
  expect_error(read_text(dir, "d.ply", ply_binary(3, 1, v, {3, 0, -2, 2})), dir / "d.ply", -1,
               static_cast<std::int64_t>(header + 36 + 1 + 4), "vertex index -2 out of range");
  expect_error(read_text(dir, "e.ply", ply_binary(3, 1, v, {2, 0, 1})), dir / "e.ply", -1,
               static_cast<std::int64_t>(header + 36), "face 0 has 2 corners");
  std::vector<float> bad = v;
  bad[4] = std::numeric_limits<float>::infinity();
  expect_error(read_text(dir, "f.ply", ply_binary(3, 1, bad, {3, 0, 1, 2})), dir / "f.ply", -1,
               static_cast<std::int64_t>(header + 16),
               "non-finite coordinate (Inf) in vertex 1, property 'y'");
  // Trailing bytes = counts that do not match.
  expect_error(read_text(dir, "g.ply", ok + "xyz"), dir / "g.ply", -1,
               static_cast<std::int64_t>(ok.size()), "3 unexpected bytes after the last element");
  // Absurd counts are rejected before allocating.
  expect_error(read_text(dir, "h.ply", ply_binary(1000000000, 1, v, {3, 0, 1, 2})), dir / "h.ply",
               -1, static_cast<std::int64_t>(ok.size() + 9), "declares 1000000000 instances");
}

// ---------------------------------------------------------------------------------------------
// OFF

TEST(Off, CommentsPolygonsAndVariants) {
  TempDir dir;
  MeshReadInfo info;
  auto r = read_text(
      dir, "a.off",
      "# leading comment\nCOFF # colours follow\n\n4 2 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n"
      "# inside\n1 1 0 0 0 255 255\n0 1 0 1 1 1 1\n4 0 1 2 3 0.5 0.5 0.5\n3 0 2 1\n",
      &info);
  ASSERT_TRUE(r) << r.error().message();
  EXPECT_EQ(info.polygons_split, 1u);
  EXPECT_EQ(r->num_triangles(), 3u);
  EXPECT_EQ(r->corners(1)[2], (Vec3{0, 1, 0}));
  // Counts on the keyword line, and a keyword-less file.
  EXPECT_TRUE(read_text(dir, "b.off", "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_TRUE(read_text(dir, "c.off", "3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
}

TEST(OffErrors, EveryProblemHasItsLine) {
  TempDir dir;
  const std::string v = "0 0 0\n1 0 0\n0 1 0\n";
  expect_error(read_text(dir, "a.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n"), dir / "a.off", 2, -1,
               "only 12 bytes follow");
  expect_error(
      read_text(dir, "b.off", "OFF\n3 2 0\n" + v + "3 0 1 2\n# padding to pass the size check\n"),
      dir / "b.off", 7, -1, "file ends after 1 of the 2 faces");
  expect_error(read_text(dir, "c.off", "OFF\n3 1 0\n" + v + "3 0 1 2\n3 0 1 2\n"), dir / "c.off", 7,
               -1, "unexpected data after the 1 faces");
  expect_error(read_text(dir, "d.off", "OFF\n3 1 0\n" + v + "3 0 1 3\n"), dir / "d.off", 6, -1,
               "vertex index 3 out of range [0, 3)");
  expect_error(read_text(dir, "e.off", "OFF\n3 1 0\n" + v + "2 0 1    \n"), dir / "e.off", 6, -1,
               "face has 2 corners");
  expect_error(read_text(dir, "f.off", "OFF\n3 1 0\n0 0 0\n1 -inf 0\n0 1 0\n3 0 1 2\n"),
               dir / "f.off", 4, -1, "non-finite coordinate '-inf'");
  expect_error(read_text(dir, "g.off", "OFF\n3 1 0\n0 0 0\n1 0,5 0\n0 1 0\n3 0 1 2\n"),
               dir / "g.off", 4, -1, "malformed number '0,5'");
  expect_error(read_text(dir, "h.off", "OFF\n3 1 0\n" + v + "4 0 1 2\n"), dir / "h.off", 6, -1,
               "face declares 4 corners but lists 3");
  expect_error(read_text(dir, "i.off", "4OFF\n1 1 0\n0 0 0 0\n3 0 0 0\n"), dir / "i.off", 1, -1,
               "unsupported OFF variant");
  expect_error(read_text(dir, "j.off", "OFF BINARY\n"), dir / "j.off", 1, -1,
               "binary OFF is not supported");
  expect_error(read_text(dir, "k.off", "OFF\n3 0 0\n" + v), dir / "k.off", 2, -1, "no triangles");
  expect_error(read_text(dir, "l.off", "OFF\n3 x 0\n" + v), dir / "l.off", 2, -1,
               "malformed face count 'x'");
  expect_error(read_text(dir, "m.off", "OFF\n99999999999 1 0\n" + v + "3 0 1 2\n"), dir / "m.off",
               2, -1, "exceeds 32-bit indices");
  expect_error(read_text(dir, "n.off", "OFF\n1000000 1000000 0\n" + v + "3 0 1 2\n"), dir / "n.off",
               2, -1, "bytes follow");
}

// ---------------------------------------------------------------------------------------------
// Writing

TEST(Write, InvalidMeshIsRejectedAndTheExistingFileIsUntouched) {
  TempDir dir;
  const TriMesh good = test_mesh();
  for (const char* name : {"keep.stl", "keep.obj", "keep.ply", "keep.off"}) {
    ASSERT_TRUE(write_mesh(dir / name, good));
    const std::string before = get_file(dir / name);

    TriMesh bad_index = good;
    bad_index.triangles[5][1] = static_cast<std::uint32_t>(good.num_vertices());
    TriMesh bad_nan = good;
    bad_nan.positions[3].y = std::numeric_limits<double>::quiet_NaN();
    TriMesh empty;
    empty.positions = good.positions;

    const std::pair<const TriMesh*, const char*> cases[] = {
        {&bad_index, "triangle 5 references vertex"},
        {&bad_nan, "vertex 3 has a non-finite coordinate (NaN)"},
        {&empty, "no triangles"}};
    for (const auto& [mesh, why] : cases) {
      const Status s = write_mesh(dir / name, *mesh);
      ASSERT_FALSE(s) << name << " " << why;
      EXPECT_EQ(s.error().file, (dir / name).string());
      EXPECT_NE(s.error().reason.find(why), std::string::npos) << s.error().reason;
      EXPECT_EQ(get_file(dir / name), before);
    }
  }
  EXPECT_EQ(dir.file_count(), 4u);  // no temporary files left
}

TEST(Write, FloatOverflowIsRejectedForStl) {
  TempDir dir;
  TriMesh m = test_mesh();
  m.positions[0].x = 1e300;
  const Status s = write_mesh(dir / "o.stl", m);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().reason.find("overflows float"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "o.stl"));
  EXPECT_TRUE(write_mesh(dir / "o.ply", m));  // double PLY holds it exactly
  // ... but reading it back is refused: 1e300 is beyond the coordinate range of the exact
  // predicates (issue #23, item 7; docs/robustness.md).
  auto r = read_mesh(dir / "o.ply");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().reason.find("vertex 0 (0-based, in file order): x = 1e+300 is outside the supported"),
            std::string::npos)
      << r.error().reason;
}

TEST(Write, MissingDirectoryFailsCleanly) {
  TempDir dir;
  const Status s = write_mesh(dir / "no" / "such" / "dir.stl", test_mesh());
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().reason.find("cannot create temporary file"), std::string::npos);
}

TEST(Write, TargetIsADirectory) {
  TempDir dir;
  fs::create_directory(dir / "d.stl");
  const Status s = write_mesh(dir / "d.stl", test_mesh());
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().file, (dir / "d.stl").string());
  EXPECT_NE(s.error().reason.find("cannot replace the target"), std::string::npos)
      << s.error().reason;
  EXPECT_EQ(dir.file_count(), 1u);  // the temporary file was removed
}

TEST(Write, ReplacesAnExistingFile) {
  TempDir dir;
  put_file(dir / "r.obj", "old content");
  ASSERT_TRUE(write_mesh(dir / "r.obj", test_mesh()));
  auto r = read_mesh(dir / "r.obj");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->num_triangles(), test_mesh().num_triangles());
  EXPECT_EQ(dir.file_count(), 1u);
}

}  // namespace
}  // namespace interfere
