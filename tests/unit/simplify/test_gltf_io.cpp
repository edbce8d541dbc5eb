// GLB writer (simplify/gltf_io.h): bad input is an error naming the part or instance and writes
// nothing; a good file has the GLB header, chunk lengths and a BIN chunk as the JSON declares.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

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

}  // namespace
}  // namespace interfere
