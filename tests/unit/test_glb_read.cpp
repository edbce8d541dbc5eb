// GLB reading (mesh/io.h, src/mesh/io/glb.cpp): write_glb's files read back placed and scaled; a
// hand-built GLB for the node transforms, primitive modes, index types and strides write_glb does
// not use; malformed files are errors naming the byte or the glTF object, never a crash.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "interfere/mesh/generate.h"
#include "interfere/mesh/io.h"
#include "interfere/simplify/gltf_io.h"
#include "interfere/simplify/tagged_io.h"

namespace interfere {
namespace {

std::filesystem::path tmp(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("interfere_glb_read_" + std::to_string(::getpid()) + name);
}

// A GLB of `doc` and `bin` (padded as the specification asks).
std::string glb(const nlohmann::json& doc, std::string bin) {
  std::string text = doc.dump();
  while (text.size() % 4) text += ' ';
  while (bin.size() % 4) bin += '\0';
  const auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  std::string out = "glTF" + u32(2) + u32(0) + u32(text.size()) + "JSON" + text;
  if (!bin.empty()) out += u32(bin.size()) + std::string("BIN\0", 4) + bin;
  const std::uint32_t n = out.size();
  std::memcpy(out.data() + 8, &n, 4);
  return out;
}

Expected<TriMesh> read_bytes(const std::string& name, const std::string& bytes, ReadOptions o = {}) {
  const auto f = tmp(name);
  std::ofstream(f, std::ios::binary) << bytes;
  return read_mesh(f, o);
}

template <class T>
std::string raw(const std::vector<T>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

// A unit square as two triangles (4 float corners), placed by `node`, with `indices` of
// `component` type (5121, 5123, 5125; empty: none) and primitive `mode`.
nlohmann::json square_doc(const nlohmann::json& node, std::size_t index_bytes, std::size_t index_count,
                          int component, int mode) {
  nlohmann::json doc;
  doc["asset"] = {{"version", "2.0"}};
  doc["buffers"] = {{{"byteLength", 48 + index_bytes}}};
  doc["bufferViews"] = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}}};
  doc["accessors"] = {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}}};
  nlohmann::json prim{{"attributes", {{"POSITION", 0}}}, {"mode", mode}};
  if (index_count > 0) {
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 48}, {"byteLength", index_bytes}});
    doc["accessors"].push_back({{"bufferView", 1}, {"componentType", component}, {"count", index_count}, {"type", "SCALAR"}});
    prim["indices"] = 1;
  }
  doc["meshes"] = {{{"primitives", {prim}}}};
  doc["nodes"] = {node};
  doc["scenes"] = {{{"nodes", {0}}}};
  doc["scene"] = 0;
  return doc;
}
const std::vector<float> kSquare = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};

TEST(GlbRead, WriteGlbFilesReadBackPlacedAndScaledWithTheirBound) {
  const TriMesh ball = make_sphere({.target_triangles = 200});
  Transform moved;  // 90 degrees about z, then (10, 0, 5)
  moved.r = {{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}};
  moved.t = {10, 0, 5};
  const auto file = tmp("ball.glb");
  ASSERT_TRUE(write_glb(file, {{"ball", ball, {}, {}, 0.25}}, {{"a", 0, Transform{}}, {"b", 0, moved}}, "mm").ok());
  MeshReadInfo info;
  auto m = read_mesh(file, {.weld = false}, &info);
  ASSERT_TRUE(m.has_value()) << m.error().message();
  EXPECT_EQ(info.format, MeshFormat::glb);
  ASSERT_EQ(m->num_triangles(), 2 * ball.num_triangles());
  // write_glb splits vertices by region; each output triangle's corners are the input's, as floats,
  // placed and scaled to metres.
  for (std::size_t t = 0; t < ball.num_triangles(); ++t) {
    const auto in = ball.corners(t), a = m->corners(t), b = m->corners(ball.num_triangles() + t);
    for (int k = 0; k < 3; ++k) {
      const Vec3 f{double(float(in[k].x)), double(float(in[k].y)), double(float(in[k].z))};
      const Vec3 pa = f * 1e-3, pb = moved.apply(f) * 1e-3;
      EXPECT_LT(norm(a[k] - pa), 1e-15) << t;
      EXPECT_LT(norm(b[k] - pb), 1e-15) << t;
    }
  }
  auto bound = read_error_bound(file);
  ASSERT_TRUE(bound.has_value());
  EXPECT_DOUBLE_EQ(*bound, 0.25e-3);  // metres, as the coordinates
  // Without units nothing is scaled; a mesh without a bound has none.
  const auto plain = tmp("plain.glb");
  ASSERT_TRUE(write_glb(plain, {{"ball", ball, {}, {}, -1}}, {{"a", 0, Transform{}}}, "").ok());
  auto p = read_mesh(plain, {.weld = false});
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->corners(0)[0], (Vec3{double(float(ball.corners(0)[0].x)), double(float(ball.corners(0)[0].y)),
                                    double(float(ball.corners(0)[0].z))}));
  EXPECT_EQ(*read_error_bound(plain), -1.0);
  // Welded (the default), the sphere is closed again.
  auto w = read_mesh(plain);
  ASSERT_TRUE(w.has_value());
  EXPECT_EQ(w->num_vertices(), ball.num_vertices());
}

TEST(GlbRead, NodeTransformsModesIndexTypesAndStrides) {
  // TRS: scale 2, 90 degrees about z, translation (5, 0, 0), under a parent moved by (0, 0, 1).
  const double s = std::sqrt(0.5);
  nlohmann::json child{{"mesh", 0}, {"scale", {2, 2, 2}}, {"rotation", {0, 0, s, s}}, {"translation", {5, 0, 0}}};
  for (int component : {5121, 5123, 5125}) {
    const std::size_t w = component == 5121 ? 1 : component == 5123 ? 2 : 4;
    std::string idx;
    for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) idx += std::string(reinterpret_cast<const char*>(&i), w);
    auto doc = square_doc({{"children", {1}}, {"translation", {0, 0, 1}}}, idx.size(), 6, component, 4);
    doc["nodes"].push_back(child);
    auto m = read_bytes("trs.glb", glb(doc, raw(kSquare) + idx), {.weld = false});
    ASSERT_TRUE(m.has_value()) << m.error().message();
    ASSERT_EQ(m->num_triangles(), 2u);
    // (1, 0, 0) -> scale (2, 0, 0) -> rotate (0, 2, 0) -> + (5, 0, 0) + (0, 0, 1).
    EXPECT_NEAR(m->positions[m->triangles[0][1]].x, 5, 1e-12);
    EXPECT_NEAR(m->positions[m->triangles[0][1]].y, 2, 1e-12);
    EXPECT_NEAR(m->positions[m->triangles[0][1]].z, 1, 1e-12);
  }
  // A strip and a fan of the four corners without indices: two triangles each, wound alike.
  for (int mode : {5, 6}) {
    const std::vector<float> corners = mode == 5 ? std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0} : kSquare;
    auto m = read_bytes("strip.glb", glb(square_doc({{"mesh", 0}}, 0, 0, 0, mode), raw(corners)), {.weld = false});
    ASSERT_TRUE(m.has_value()) << m.error().message();
    ASSERT_EQ(m->num_triangles(), 2u) << mode;
    for (std::size_t t = 0; t < 2; ++t) {
      const auto c = m->corners(t);
      EXPECT_GT(cross(c[1] - c[0], c[2] - c[0]).z, 0) << mode << " " << t;  // counter-clockwise, +z
    }
  }
  // Interleaved positions (stride 24: position + 12 bytes of something else); lines are skipped.
  std::vector<float> inter;
  for (int v = 0; v < 4; ++v) inter.insert(inter.end(), {kSquare[3 * v], kSquare[3 * v + 1], kSquare[3 * v + 2], 9, 9, 9});
  auto doc = square_doc({{"mesh", 0}}, 0, 0, 0, 6);
  doc["bufferViews"][0]["byteLength"] = 96;
  doc["bufferViews"][0]["byteStride"] = 24;
  doc["buffers"][0]["byteLength"] = 96;
  doc["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", 0}}}, {"mode", 1}});
  auto m = read_bytes("stride.glb", glb(doc, raw(inter)), {.weld = false});
  ASSERT_TRUE(m.has_value()) << m.error().message();
  ASSERT_EQ(m->num_triangles(), 2u);
  EXPECT_EQ(m->positions[2], (Vec3{1, 1, 0}));
  // No scenes: the root nodes are drawn.
  auto noscene = square_doc({{"mesh", 0}}, 0, 0, 0, 6);
  noscene.erase("scenes");
  noscene.erase("scene");
  EXPECT_TRUE(read_bytes("noscene.glb", glb(noscene, raw(kSquare))).has_value());
}

TEST(GlbRead, QuantizedPositionsAreDequantized) {
  // KHR_mesh_quantization (as gltfpack writes): SHORT normalized corners of the unit square
  // (32767 = 1) placed by a node scale of 4, padded to a 8-byte stride; UNSIGNED_BYTE corners
  // (not normalized) with a 4-byte stride; BYTE normalized, where -128 and -127 both give -1.
  struct Case {
    int component;
    bool normalized;
    std::size_t stride;
    std::vector<std::array<int, 3>> corners;
    double scale;
    std::vector<Vec3> expected;
  };
  const std::vector<Case> cases = {
      {5122, true, 8, {{0, 0, 0}, {32767, 0, 0}, {32767, 32767, 0}, {0, 32767, -32768}}, 4,
       {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, -4}}},
      {5121, false, 4, {{0, 0, 0}, {200, 0, 0}, {200, 100, 0}, {0, 100, 7}}, 0.5,
       {{0, 0, 0}, {100, 0, 0}, {100, 50, 0}, {0, 50, 3.5}}},
      {5120, true, 4, {{0, 0, 0}, {127, 0, 0}, {127, -127, 0}, {0, -128, 0}}, 1, {{0, 0, 0}, {1, 0, 0}, {1, -1, 0}, {0, -1, 0}}},
  };
  for (const Case& c : cases) {
    std::string bin;
    for (const auto& v : c.corners) {
      std::string e;
      for (int x : v) {
        if (c.component == 5122) {
          const auto q = static_cast<std::int16_t>(x);
          e += std::string(reinterpret_cast<const char*>(&q), 2);
        } else {
          e += static_cast<char>(x);
        }
      }
      e.resize(c.stride, '\0');
      bin += e;
    }
    nlohmann::json node{{"mesh", 0}, {"scale", {c.scale, c.scale, c.scale}}};
    auto doc = square_doc(node, 0, 0, 0, 6);
    doc["extensionsUsed"] = {"KHR_mesh_quantization"};
    doc["extensionsRequired"] = {"KHR_mesh_quantization"};
    doc["buffers"][0]["byteLength"] = bin.size();
    doc["bufferViews"][0]["byteLength"] = bin.size();
    doc["bufferViews"][0]["byteStride"] = c.stride;
    doc["accessors"][0]["componentType"] = c.component;
    if (c.normalized) doc["accessors"][0]["normalized"] = true;
    auto m = read_bytes("quantized_" + std::to_string(c.component) + ".glb", glb(doc, bin), {.weld = false});
    ASSERT_TRUE(m.has_value()) << m.error().message();
    ASSERT_EQ(m->num_vertices(), 4u);
    for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(m->positions[i], c.expected[i]) << c.component << " " << i;
  }
}

TEST(GlbRead, MalformedFilesAreErrorsNamingWhere) {
  const std::string good = glb(square_doc({{"mesh", 0}}, 0, 0, 0, 6), raw(kSquare));
  ASSERT_TRUE(read_bytes("good.glb", good).has_value());
  const auto expect_error = [&](const std::string& bytes, const std::string& what, const std::string& tag) {
    auto m = read_bytes("bad_" + tag + ".glb", bytes);
    ASSERT_FALSE(m.has_value()) << tag;
    EXPECT_NE(m.error().message().find(what), std::string::npos) << tag << ": " << m.error().message();
    EXPECT_NE(m.error().file.find("bad_" + tag), std::string::npos) << tag;
  };
  expect_error(good.substr(0, good.size() - 8), "truncated", "truncated");
  expect_error(good.substr(0, 10), "not a GLB", "short");
  std::string v1 = good;
  v1[4] = 1;
  expect_error(v1, "byte 4: GLB version 1", "version");
  std::string badjson = good;
  badjson[20] = '!';
  expect_error(badjson, "not valid JSON", "json");
  const auto with = [&](const std::function<void(nlohmann::json&)>& edit, std::string bin = {}) {
    auto doc = square_doc({{"mesh", 0}}, 0, 0, 0, 6);
    edit(doc);
    return glb(doc, bin.empty() ? raw(kSquare) : bin);
  };
  expect_error(with([](auto& d) { d["accessors"][0]["count"] = 5; }), "do not fit bufferViews[0]", "count");
  expect_error(with([](auto& d) { d["bufferViews"][0]["byteLength"] = 4096; }), "beyond buffers[0] (48 bytes)", "view");
  expect_error(with([](auto& d) { d["buffers"][0]["uri"] = "no_such_square.bin"; }), "buffers[0].uri: cannot open", "uri");
  expect_error(with([](auto& d) { d["buffers"].push_back({{"byteLength", 4}}); }), "buffers[1]: no uri", "bin1");
  expect_error(with([](auto& d) { d["buffers"][0]["byteLength"] = 52; }), "52 bytes, but the BIN chunk has 48", "len");
  expect_error(with([](auto& d) { d["accessors"][0]["sparse"] = nlohmann::json::object(); }), "sparse", "sparse");
  expect_error(with([](auto& d) { d["accessors"][0]["componentType"] = 5125; }), "positions must be FLOAT", "uint");
  expect_error(with([](auto& d) { d["accessors"][0]["normalized"] = true; }), "only integer positions", "normfloat");
  expect_error(with([](auto& d) { d["extensionsRequired"] = {"EXT_meshopt_compression"}; }),
               "EXT_meshopt_compression is not supported", "meshopt");
  expect_error(with([](auto& d) { d["nodes"][0]["children"] = {0}; }), "nodes[0]: reached twice", "cycle");
  expect_error(with([](auto& d) { d["nodes"][0]["mesh"] = 3; }), "nodes[0].mesh: not an index", "mesh");
  expect_error(with([](auto& d) { d["nodes"][0]["rotation"] = {0, 0, 0, 0}; }), "zero quaternion", "quat");
  expect_error(with([](auto& d) { d["nodes"][0]["matrix"] = {1, 2, 3}; }), "must hold 16 numbers", "matrix");
  expect_error(with([](auto& d) { d["meshes"][0]["primitives"][0]["mode"] = 1; }), "no triangles", "lines");
  expect_error(with([](auto& d) { d["extensionsRequired"] = {"KHR_draco_mesh_compression"}; }),
               "KHR_draco_mesh_compression is not supported", "draco");
  std::vector<float> nan = kSquare;
  nan[4] = std::nanf("");
  expect_error(with([](auto&) {}, raw(nan)), "vertex 1 is not finite", "nan");
  std::string idx;
  for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 7u}) idx += std::string(reinterpret_cast<const char*>(&i), 4);
  expect_error(glb(square_doc({{"mesh", 0}}, 24, 6, 5125, 4), raw(kSquare) + idx), "index 5 is 7, beyond the 4 vertices",
               "index");
  expect_error(glb(square_doc({{"mesh", 0}}, 20, 5, 5125, 4), raw(kSquare) + idx.substr(0, 20)), "not a multiple of 3",
               "triples");
  // read_error_bound reads the header and the JSON chunk only, checked alike; a bad bound is an error.
  const auto bound_of = [&](const std::string& name, const std::string& bytes) {
    const auto f = tmp(name);
    std::ofstream(f, std::ios::binary) << bytes;
    return read_error_bound(f);
  };
  EXPECT_EQ(*bound_of("nb.glb", good), -1.0);
  auto cut = bound_of("cut.glb", good.substr(0, good.size() - 8));
  ASSERT_FALSE(cut.has_value());
  EXPECT_NE(cut.error().reason.find("truncated"), std::string::npos);
  for (const char* bad : {"-1", "\"x\""}) {
    auto doc = square_doc({{"mesh", 0}}, 0, 0, 0, 6);
    doc["scenes"][0]["extras"]["error_bound"] = nlohmann::json::parse(bad);
    auto b = bound_of("eb.glb", glb(doc, raw(kSquare)));
    ASSERT_FALSE(b.has_value()) << bad;
    EXPECT_NE(b.error().message().find("byte 20: glTF scene extras: error_bound"), std::string::npos) << b.error().message();
  }
  // write_mesh does not write glTF (write_glb does).
  const Status s = write_mesh(tmp("out.glb"), make_box({0, 0, 0}, {1, 1, 1}));
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().reason.find("write_glb"), std::string::npos);
}

}  // namespace
}  // namespace interfere
