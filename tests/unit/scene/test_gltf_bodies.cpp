// scene::read_gltf_bodies (include/interfere/scene/io.h, src/scene/gltf_bodies.cpp): one body per
// glTF node with a mesh, posed by the node's world transform. Oracles: the placements the file was
// written with (write_glb), and for a hand-written hierarchy (parent TRS x child matrix, a mirror,
// a non-uniform scale) world matrices multiplied out in the test; the flattening mesh reader,
// which shares the node walk, must give the same triangles in the same order.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "interfere/core/base64.h"
#include "interfere/mesh/generate.h"
#include "interfere/mesh/io.h"
#include "interfere/scene/io.h"
#include "interfere/simplify/gltf_io.h"

namespace interfere::scene {
namespace {

std::filesystem::path tmp(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("interfere_gltf_bodies_" + std::to_string(::getpid()) + "_" + name);
}

Vec3 world_of(const Body& b, std::size_t v) {
  return b.pose.apply(b.mesh->positions[v]);
}

Transform rotation(const Vec3& axis, double angle, const Vec3& t) {  // Rodrigues
  const Vec3 k = axis / norm(axis);
  const double c = std::cos(angle), s = std::sin(angle);
  Transform r;
  const double kk[3] = {k.x, k.y, k.z};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.r[i][j] = (i == j ? c : 0) + (1 - c) * kk[i] * kk[j];
  r.r[0][1] -= s * k.z, r.r[0][2] += s * k.y, r.r[1][0] += s * k.z;
  r.r[1][2] -= s * k.x, r.r[2][0] -= s * k.y, r.r[2][1] += s * k.x;
  r.t = t;
  return r;
}

TEST(GltfBodies, WriteGlbInstancesReadBackAsPosedBodies) {
  GltfPart tet{.name = "tet"}, box{.name = "box"};
  tet.mesh.positions = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}};
  tet.mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  box.mesh = make_box({-5, -5, -5}, {5, 5, 5});
  const std::vector<GltfInstance> instances = {
      {.name = "tet_a", .part = 0, .placement = Transform{}},
      {.name = "tet_b",
       .part = 0,
       .placement = rotation({1, 0, 0}, std::acos(-1.0) / 2, {10, 20, 30})},
      {.name = "tet_c", .part = 0, .placement = rotation({1, 2, 3}, 0.7, {-40, 5, 12.5})},
      {.name = "box", .part = 1, .placement = rotation({0, 0, 1}, 0.3, {100, 0, 0})}};
  const std::vector<GltfPart> parts = {tet, box};
  for (const char* ext : {".glb", ".gltf"}) {
    const auto file = tmp(std::string("parts") + ext);
    const Status w = write_glb(file, parts, instances, "mm");
    ASSERT_TRUE(w.ok()) << w.error().message();
    auto bodies = read_gltf_bodies(file.string(), 1000.0);  // metres -> mm
    ASSERT_TRUE(bodies.has_value()) << bodies.error().message();
    ASSERT_EQ(bodies->size(), instances.size());
    std::set<const TriMesh*> meshes;
    for (std::size_t i = 0; i < instances.size(); ++i) {
      const Body& b = (*bodies)[i];
      const GltfInstance& in = instances[i];
      const TriMesh& part = parts[in.part].mesh;
      EXPECT_EQ(b.name, in.name);
      EXPECT_EQ(b.path, "/interfere_root/" + in.name);
      EXPECT_EQ(b.id, b.path);
      EXPECT_EQ(b.source.kind, SourceKind::gltf_node);
      EXPECT_EQ(b.source.file, file.string());
      EXPECT_EQ(b.source.detail, b.path);
      EXPECT_EQ(b.unit, "m");
      EXPECT_TRUE(b.pose.is_rigid()) << in.name;  // the root's uniform scale went into the mesh
      meshes.insert(b.mesh.get());
      ASSERT_EQ(b.mesh->num_triangles(), part.num_triangles());
      for (std::uint32_t t = 0; t < part.num_triangles(); ++t) {
        const auto want = part.corners(t);
        for (int k = 0; k < 3; ++k) {
          const Vec3 got = b.pose.apply(b.mesh->corners(t)[k]),
                     expect = in.placement.apply(want[k]);
          EXPECT_LE(norm(got - expect), 1e-5) << in.name << " triangle " << t << " corner " << k;
        }
        EXPECT_EQ(b.source_id(t), t);
      }
    }
    EXPECT_EQ(meshes.size(), 2u) << "the three tetrahedra share one mesh";
  }
}

// Column-major 4x4 as glTF stores it; M·p.
using Mat4 = std::array<double, 16>;
Mat4 mul(const Mat4& a, const Mat4& b) {
  Mat4 c{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) c[j * 4 + i] += a[k * 4 + i] * b[j * 4 + k];
  return c;
}
Vec3 apply(const Mat4& m, const Vec3& p) {
  return {m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12],
          m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13],
          m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14]};
}
Mat4 translate(double x, double y, double z) {
  return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, x, y, z, 1};
}
Mat4 scaling(double x, double y, double z) {
  return {x, 0, 0, 0, 0, y, 0, 0, 0, 0, z, 0, 0, 0, 0, 1};
}
const Mat4 kRotZ90 = {0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // (1,0,0) -> (0,1,0)

TEST(GltfBodies, HierarchyOfTrsAndMatricesMirrorsAndNonUniformScales) {
  // Mesh 0: a unit square, indexed (uint16); mesh 1: the same square, not indexed (6 corners).
  const std::vector<float> square = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::vector<std::uint16_t> idx = {0, 1, 2, 0, 2, 3};
  const std::vector<float> soup = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0};
  std::string bin(reinterpret_cast<const char*>(square.data()), 48);
  bin.append(reinterpret_cast<const char*>(idx.data()), 12);
  bin.append(reinterpret_cast<const char*>(soup.data()), 72);
  nlohmann::json doc;
  doc["asset"] = {{"version", "2.0"}};
  doc["buffers"] = {{{"byteLength", bin.size()},
                     {"uri", "data:application/octet-stream;base64," + base64_encode(bin)}}};
  doc["bufferViews"] = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                        {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 12}},
                        {{"buffer", 0}, {"byteOffset", 60}, {"byteLength", 72}}};
  doc["accessors"] = {
      {{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
      {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}},
      {{"bufferView", 2}, {"componentType", 5126}, {"count", 6}, {"type", "VEC3"}}};
  doc["meshes"] = {
      {{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"mode", 4}}}}},
      {{"primitives", {{{"attributes", {{"POSITION", 2}}}}}}}};
  const double h = std::sqrt(0.5);
  // The child's matrix: 90 degrees about x, then (0, 0, 5); column-major.
  const Mat4 arm = {1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 5, 1};
  doc["nodes"] = {
      {{"name", "asm"},
       {"translation", {1, 2, 3}},
       {"rotation", {0, 0, h, h}},
       {"scale", {2, 2, 2}},
       {"children", {1, 3}}},
      {{"name", "arm"}, {"matrix", arm}, {"children", {2}}},
      {{"mesh", 0}, {"translation", {0.5, 0, 0}}},
      {{"name", "mirror"}, {"scale", {-1, 1, 1}}, {"mesh", 1}},
      {{"name", "lonely"}, {"scale", {1, 3, 1}}, {"translation", {0, 0, -7}}, {"mesh", 0}}};
  doc["scenes"] = {{{"nodes", {0, 4}}}};
  doc["scene"] = 0;
  const auto file = tmp("hierarchy.gltf");
  std::ofstream(file) << doc.dump();

  auto bodies = read_gltf_bodies(file.string(), 1000.0);
  ASSERT_TRUE(bodies.has_value()) << bodies.error().message();
  ASSERT_EQ(bodies->size(), 3u);
  const Mat4 asm_m = mul(translate(1, 2, 3), mul(kRotZ90, scaling(2, 2, 2)));
  struct Want {
    std::string path, name;
    Mat4 world;
    bool mirrored;
    const std::vector<float>* corners;
    std::vector<int> order;  // file triangles' corner indices
  };
  const std::vector<Want> want = {
      {"/asm/arm/node2",
       "node2",
       mul(asm_m, mul(arm, translate(0.5, 0, 0))),
       false,
       &square,
       {0, 1, 2, 0, 2, 3}},
      {"/asm/mirror", "mirror", mul(asm_m, scaling(-1, 1, 1)), true, &soup, {0, 1, 2, 3, 4, 5}},
      {"/lonely",
       "lonely",
       mul(translate(0, 0, -7), scaling(1, 3, 1)),
       false,
       &square,
       {0, 1, 2, 0, 2, 3}}};
  auto flat = read_mesh(file, {.weld = false});
  ASSERT_TRUE(flat.has_value()) << flat.error().message();
  ASSERT_EQ(flat->num_triangles(), 6u);
  std::uint32_t flat_t = 0;
  for (std::size_t i = 0; i < want.size(); ++i) {
    const Body& b = (*bodies)[i];
    const Want& w = want[i];
    EXPECT_EQ(b.path, w.path);
    EXPECT_EQ(b.name, w.name);
    EXPECT_EQ(b.id, w.path);
    ASSERT_EQ(b.mesh->num_triangles(), 2u);
    for (std::uint32_t t = 0; t < 2; ++t, ++flat_t) {
      const auto c = b.mesh->corners(t);
      Vec3 got[3], expect[3];
      for (int k = 0; k < 3; ++k) {
        got[k] = b.pose.apply(c[k]);
        // The spec's winding: reversed under a mirroring transform.
        const int corner = w.order[3 * t + (w.mirrored && k > 0 ? 3 - k : k)];
        const Vec3 p{(*w.corners)[3 * corner], (*w.corners)[3 * corner + 1],
                     (*w.corners)[3 * corner + 2]};
        expect[k] = apply(w.world, p) * 1000.0;
        EXPECT_LE(norm(got[k] - expect[k]), 1e-9 * (1 + norm(expect[k])))
            << w.path << " " << t << " " << k;
        // The flattening reader (metres) walks the same nodes: the same triangle.
        EXPECT_LE(norm(flat->corners(flat_t)[k] * 1000.0 - got[k]), 1e-9 * (1 + norm(got[k])))
            << w.path;
      }
      // Outward stays outward: the squares face the world image of +z (for the mirror, that is
      // what its clockwise winding means).
      const Vec3 up = apply(w.world, {0, 0, 1}) - apply(w.world, {0, 0, 0});
      const Vec3 n = cross(got[1] - got[0], got[2] - got[0]);
      EXPECT_GT(dot(n, up), 0) << w.path;
    }
  }
  EXPECT_FALSE((*bodies)[2].pose.is_rigid());  // a non-uniform scale stays in the pose
  EXPECT_TRUE((*bodies)[1].pose.determinant_sign() < 0);
}

TEST(GltfBodies, BadInputsAreErrors) {
  EXPECT_FALSE(read_gltf_bodies(tmp("missing.glb").string()).has_value());
  const auto file = tmp("empty_scene.gltf");
  std::ofstream(file)
      << R"({"asset": {"version": "2.0"}, "nodes": [{"name": "a"}], "scenes": [{"nodes": [0]}]})";
  auto r = read_gltf_bodies(file.string());
  ASSERT_FALSE(r.has_value());
  EXPECT_NE(r.error().message().find("no triangles"), std::string::npos) << r.error().message();
  EXPECT_FALSE(read_gltf_bodies(file.string(), 0.0).has_value());
  const auto bad = tmp("bad.gltf");
  std::ofstream(bad)
      << R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 3}], "scenes": [{"nodes": [0]}]})";
  auto e = read_gltf_bodies(bad.string());
  ASSERT_FALSE(e.has_value());
  EXPECT_NE(e.error().message().find("nodes[0].mesh"), std::string::npos) << e.error().message();
}

}  // namespace
}  // namespace interfere::scene
