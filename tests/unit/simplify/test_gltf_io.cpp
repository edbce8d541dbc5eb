// GLB writer (simplify/gltf_io.h): bad input is an error naming the part or instance and writes
// nothing; a good file has the GLB header, chunk lengths and a BIN chunk as the JSON declares.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "interfere/mesh/generate.h"
#include "interfere/simplify/gltf_io.h"

namespace interfere {
namespace {

std::filesystem::path tmp(const char* name) {
  return std::filesystem::temp_directory_path() / (std::string("interfere_gltf_") + std::to_string(::getpid()) + name);
}

TEST(Gltf, HeaderChunksAndErrors) {
  GltfPart part{"ball", make_sphere({.target_triangles = 200}), {}, {}, 0.25};
  part.face_ids.assign(part.mesh.num_triangles(), 7);
  part.feature_faces = {7};
  const auto file = tmp("ok.glb");
  ASSERT_TRUE(write_glb(file, {part}, {{"a", 0, Transform{}}, {"b", 0, Transform{}}}, "mm").ok());
  std::ifstream in(file, std::ios::binary);
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GE(data.size(), 28u);
  std::uint32_t h[5];
  std::memcpy(h, data.data(), sizeof h);
  EXPECT_EQ(h[0], 0x46546C67u);  // "glTF"
  EXPECT_EQ(h[1], 2u);
  EXPECT_EQ(h[2], data.size());
  EXPECT_EQ(h[4], 0x4E4F534Au);  // JSON chunk
  EXPECT_EQ(h[3] % 4, 0u);
  const std::string json = data.substr(20, h[3]);
  EXPECT_NE(json.find("\"_FACE_ID\""), std::string::npos);
  EXPECT_NE(json.find("\"error_bound\":0.25"), std::string::npos);
  std::uint32_t b[2];
  std::memcpy(b, data.data() + 20 + h[3], sizeof b);
  EXPECT_EQ(b[1], 0x004E4942u);  // BIN chunk
  EXPECT_EQ(28 + h[3] + b[0], data.size());
  std::filesystem::remove(file);

  const auto bad = tmp("bad.glb");
  auto e = write_glb(bad, {part}, {{"x", 3, Transform{}}});
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().reason.find("instance 0"), std::string::npos);
  GltfPart empty{"empty", TriMesh{}, {}, {}, -1};
  e = write_glb(bad, {empty}, {});
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().reason.find("'empty'"), std::string::npos);
  GltfPart far = part;
  far.mesh.positions[0].x = 1e300;
  e = write_glb(bad, {far}, {});
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().reason.find("float"), std::string::npos);
  EXPECT_FALSE(write_glb(bad, {}, {}).ok());
  EXPECT_FALSE(std::filesystem::exists(bad));
}

// Issue #29, item 6: a part's own colour becomes its material (named after it); the assembly
// features keep the orange one; per-triangle feature flags split the mesh into the two primitives.
TEST(Gltf, PartColourAndFeatureMaterials) {
  GltfPart part{"ball", make_sphere({.target_triangles = 200}), {}, {}, 0.25};
  const std::size_t nt = part.mesh.num_triangles();
  part.face_ids.assign(nt, 3);
  part.feature_flags.assign(nt, 0);
  for (std::size_t t = 0; t < nt; t += 4) part.feature_flags[t] = 1;
  part.has_color = true;
  part.color[0] = 0.8f, part.color[1] = 0.2f, part.color[2] = 0.1f;
  GltfPart grey = part;
  grey.name = "grey", grey.has_color = false;
  const auto file = tmp("colour.glb");
  ASSERT_TRUE(write_glb(file, {part, grey}, {{"a", 0, Transform{}, "/asm/sub/a"}, {"b", 1, Transform{}, "/asm/b"}}, "mm").ok());
  std::ifstream in(file, std::ios::binary);
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::uint32_t json_length = 0;
  std::memcpy(&json_length, data.data() + 12, 4);
  const auto doc = nlohmann::json::parse(data.substr(20, json_length));
  ASSERT_EQ(doc["materials"].size(), 3u);
  EXPECT_EQ(doc["materials"][2]["name"], "ball");
  EXPECT_NEAR(doc["materials"][2]["pbrMetallicRoughness"]["baseColorFactor"][0].get<double>(), 0.8, 1e-6);
  const auto& p0 = doc["meshes"][0]["primitives"];
  ASSERT_EQ(p0.size(), 2u);
  EXPECT_EQ(p0[0]["material"], 2);
  EXPECT_EQ(p0[1]["material"], 1);
  EXPECT_EQ(doc["accessors"][p0[1]["indices"].get<std::size_t>()]["count"].get<std::size_t>(), 3 * ((nt + 3) / 4));
  EXPECT_EQ(doc["meshes"][1]["primitives"][0]["material"], 0);
  // The hierarchy: root -> asm -> {sub -> a, b}.
  const auto& nodes = doc["nodes"];
  ASSERT_EQ(nodes[0]["children"].size(), 1u);
  const auto& asm_node = nodes[nodes[0]["children"][0].get<std::size_t>()];
  EXPECT_EQ(asm_node["name"], "asm");
  ASSERT_EQ(asm_node["children"].size(), 2u);
  EXPECT_EQ(nodes[asm_node["children"][0].get<std::size_t>()]["name"], "sub");
  EXPECT_EQ(nodes[asm_node["children"][1].get<std::size_t>()]["extras"]["path"], "/asm/b");
  std::filesystem::remove(file);
}

// The first mesh's POSITION and NORMAL arrays (float x, y, z per vertex) of a GLB file.
struct GlbVertices {
  std::vector<Vec3> position, normal;
};
GlbVertices read_vertices(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::uint32_t json_length = 0;
  std::memcpy(&json_length, data.data() + 12, 4);
  const auto doc = nlohmann::json::parse(data.substr(20, json_length));
  const std::size_t bin = 28 + json_length;
  const auto read = [&](std::size_t accessor) {
    const auto& a = doc["accessors"][accessor];
    const auto& v = doc["bufferViews"][a["bufferView"].get<std::size_t>()];
    std::vector<Vec3> out(a["count"].get<std::size_t>());
    for (std::size_t i = 0; i < out.size(); ++i) {
      float f[3];
      std::memcpy(f, data.data() + bin + v["byteOffset"].get<std::size_t>() + 12 * i, 12);
      out[i] = {f[0], f[1], f[2]};
    }
    return out;
  };
  const auto& attributes = doc["meshes"][0]["primitives"][0]["attributes"];
  return {read(attributes["POSITION"].get<std::size_t>()), read(attributes["NORMAL"].get<std::size_t>())};
}

GlbVertices write_and_read(const GltfPart& part, const char* name) {
  const auto file = tmp(name);
  EXPECT_TRUE(write_glb(file, {part}, {{"a", 0, Transform{}}}, "mm").ok());
  GlbVertices v = read_vertices(file);
  std::filesystem::remove(file);
  return v;
}

// A box's vertex normals are its sides' normals exactly, whether the sides come as face ids or as
// crease regions (a plain mesh: its 90-degree edges are creases); every vertex is split per side.
TEST(Gltf, NormalsAreSharpAcrossFacesAndCreases) {
  const TriMesh box = make_box({0, 0, 0}, {2, 1, 3}, 3);
  std::vector<std::uint32_t> side(box.num_triangles());
  for (std::size_t t = 0; t < side.size(); ++t) {
    const auto c = box.corners(t);
    const Vec3 n = cross(c[1] - c[0], c[2] - c[0]);
    for (int k = 0; k < 3; ++k)
      if (std::fabs(n[k]) > 0) side[t] = static_cast<std::uint32_t>(2 * k + (n[k] > 0));
  }
  for (const bool ids : {true, false}) {
    GltfPart part{"box", box, ids ? side : std::vector<std::uint32_t>{}, {}, -1};
    const GlbVertices v = write_and_read(part, ids ? "box_ids.glb" : "box_plain.glb");
    ASSERT_EQ(v.normal.size(), v.position.size());
    EXPECT_EQ(v.position.size(), 6u * 16u) << ids;  // 4 x 4 grid vertices per side
    for (std::size_t i = 0; i < v.normal.size(); ++i) {
      const Vec3& n = v.normal[i];
      const Vec3& p = v.position[i];
      // On the side whose coordinate is at the box's bound, the normal is that axis exactly.
      int axis = std::fabs(n.x) == 1 ? 0 : std::fabs(n.y) == 1 ? 1 : std::fabs(n.z) == 1 ? 2 : -1;
      ASSERT_GE(axis, 0) << "vertex " << i << " normal " << n.x << " " << n.y << " " << n.z;
      EXPECT_EQ(norm(n), 1.0);
      const double hi = axis == 0 ? 2 : axis == 1 ? 1 : 3;
      EXPECT_EQ(p[axis], n[axis] > 0 ? hi : 0.0);
    }
  }
}

// A sphere is one smooth face: its normals point along the radius (not the flat triangles'
// normals), unit length, with or without one face id for all of it; no vertex is split.
TEST(Gltf, NormalsAreSmoothWithinAFace) {
  const TriMesh sphere = make_sphere({.target_triangles = 800, .radius = 2});
  for (const bool ids : {true, false}) {
    GltfPart part{"ball", sphere, ids ? std::vector<std::uint32_t>(sphere.num_triangles(), 4) : std::vector<std::uint32_t>{},
                  {}, -1};
    const GlbVertices v = write_and_read(part, ids ? "ball_ids.glb" : "ball_plain.glb");
    EXPECT_EQ(v.position.size(), sphere.num_vertices());
    double worst = 1;
    for (std::size_t i = 0; i < v.normal.size(); ++i) {
      EXPECT_NEAR(norm(v.normal[i]), 1.0, 1e-6);
      worst = std::min(worst, dot(v.normal[i], v.position[i] / norm(v.position[i])));
    }
    EXPECT_GT(worst, 0.995);  // (its flat triangle normals are up to ~15 degrees off the radius)
  }
  // A vertex of degenerate triangles only still gets a unit normal.
  TriMesh flat;
  flat.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  flat.triangles = {{0, 1, 2}};
  const GlbVertices d = write_and_read({"flat", flat, {}, {}, -1}, "flat.glb");
  for (const Vec3& n : d.normal) EXPECT_EQ(norm(n), 1.0);
}

}  // namespace
}  // namespace interfere
