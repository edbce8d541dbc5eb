// JSON glTF (.gltf) reading and writing (mesh/io.h, src/mesh/io/glb.cpp; simplify/gltf_io.h) and
// the base64 of its data: URIs (core/base64.h): write_glb's .gltf reads back as its GLB does;
// buffers in external files (percent-encoded names), in data: URIs and several per file; bad URIs,
// files and JSON are errors naming the file and the glTF object, and nothing is fetched from a
// network.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "interfere/core/base64.h"
#include "interfere/mesh/generate.h"
#include "interfere/mesh/io.h"
#include "interfere/simplify/gltf_io.h"
#include "interfere/simplify/tagged_io.h"

namespace interfere {
namespace {

std::filesystem::path dir() {
  const auto d = std::filesystem::temp_directory_path() /
                 ("interfere_gltf_read_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

void write(const std::filesystem::path& f, const std::string& bytes) {
  std::ofstream(f, std::ios::binary) << bytes;
}

template <class T>
std::string raw(const std::vector<T>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

const std::vector<float> kSquare = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
const std::vector<std::uint16_t> kIndices = {0, 1, 2, 0, 2, 3};

// A unit square: positions in buffer 0 (`uri0`), indices in buffer 1 (`uri1`).
nlohmann::json square(const std::string& uri0, const std::string& uri1) {
  nlohmann::json d;
  d["asset"] = {{"version", "2.0"}};
  d["buffers"] = {{{"byteLength", 48}, {"uri", uri0}}, {{"byteLength", 12}, {"uri", uri1}}};
  d["bufferViews"] = {{{"buffer", 0}, {"byteLength", 48}}, {{"buffer", 1}, {"byteLength", 12}}};
  d["accessors"] = {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                    {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}};
  d["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}};
  d["nodes"] = {{{"mesh", 0}, {"translation", {0, 0, 2}}}};
  d["scenes"] = {{{"nodes", {0}}}};
  return d;
}

TEST(Base64, RoundTripsEveryLengthAndRejectsBadText) {
  std::mt19937 rng(7);
  for (std::size_t n = 0; n < 40; ++n) {
    std::string bytes(n, '\0');
    for (char& c : bytes) c = static_cast<char>(rng());
    const std::string text = base64_encode(bytes);
    EXPECT_EQ(text.size(), (n + 2) / 3 * 4);
    std::size_t bad = 0;
    const auto back = base64_decode(text, bad);
    ASSERT_TRUE(back.has_value()) << n;
    EXPECT_EQ(*back, bytes) << n;
  }
  EXPECT_EQ(base64_encode("Man"), "TWFu");  // RFC 4648 §10's vectors
  EXPECT_EQ(base64_encode("fo"), "Zm8=");
  EXPECT_EQ(base64_encode("f"), "Zg==");
  std::size_t bad = 0;
  EXPECT_FALSE(base64_decode("Zm8", bad).has_value());  // length not a multiple of 4
  EXPECT_EQ(bad, 3u);
  EXPECT_FALSE(base64_decode("Zm!=", bad).has_value());
  EXPECT_EQ(bad, 2u);
  EXPECT_FALSE(base64_decode("Zg==Zg==", bad).has_value());  // padding only at the end
  EXPECT_EQ(bad, 2u);
}

TEST(GltfRead, WriteGlbAsGltfReadsBackAsTheGlbDoes) {
  const TriMesh ball = make_sphere({.target_triangles = 300});
  Transform moved;
  moved.t = {3, 0, 1};
  const std::vector<GltfPart> parts{{"ball", ball, {}, {}, 0.5}};
  const std::vector<GltfInstance> inst{{"a", 0, Transform{}}, {"b", 0, moved}};
  const auto g = dir() / "ball.gltf", b = dir() / "ball.glb", forced = dir() / "ball_json.bin";
  ASSERT_TRUE(write_glb(g, parts, inst, "mm").ok());
  ASSERT_TRUE(write_glb(b, parts, inst, "mm").ok());
  ASSERT_TRUE(write_glb(forced, parts, inst, "mm", GltfContainer::gltf).ok());
  {
    std::ifstream in(g);
    const auto doc = nlohmann::json::parse(in);  // JSON text, the buffer a data: URI
    EXPECT_EQ(doc["buffers"][0]["uri"].get<std::string>().rfind(
                  "data:application/octet-stream;base64,", 0),
              0u);
  }
  MeshReadInfo gi, bi;
  auto mg = read_mesh(g, {}, &gi);
  auto mb = read_mesh(b, {}, &bi);
  ASSERT_TRUE(mg.has_value()) << mg.error().message();
  ASSERT_TRUE(mb.has_value()) << mb.error().message();
  EXPECT_EQ(gi.format, MeshFormat::gltf);
  EXPECT_EQ(bi.format, MeshFormat::glb);
  EXPECT_EQ(mg->positions, mb->positions);
  EXPECT_EQ(mg->triangles, mb->triangles);
  EXPECT_EQ(mg->num_triangles(), 2 * ball.num_triangles());
  EXPECT_DOUBLE_EQ(*read_error_bound(g), 0.5e-3);  // metres, as the coordinates
  // The container follows the argument, not the name: found by content.
  auto mf = read_mesh(forced, {.format = MeshFormat::gltf});
  ASSERT_TRUE(mf.has_value()) << mf.error().message();
  EXPECT_EQ(mf->positions, mb->positions);
  auto sniffed = read_mesh(forced);
  ASSERT_TRUE(sniffed.has_value()) << sniffed.error().message();
}

TEST(GltfRead, BuffersFromFilesAndDataUris) {
  const auto d = dir() / "sub dir";
  std::filesystem::create_directories(d);
  write(d / "pos data.bin", raw(kSquare));
  const std::string idx_uri = "data:application/gltf-buffer;base64," + base64_encode(raw(kIndices));
  write(d / "square.gltf", square("pos%20data.bin", idx_uri).dump(1));
  auto m = read_mesh(d / "square.gltf");
  ASSERT_TRUE(m.has_value()) << m.error().message();
  ASSERT_EQ(m->num_triangles(), 2u);
  EXPECT_EQ(m->triangles[1], (Tri{0, 2, 3}));
  const Aabb box = m->bounds();
  EXPECT_EQ(box.lo, (Vec3{0, 0, 2}));
  EXPECT_EQ(box.hi, (Vec3{1, 1, 2}));
  // The same from the working directory elsewhere: URIs resolve against the file's folder.
  const auto cwd = std::filesystem::current_path();
  std::filesystem::current_path(std::filesystem::temp_directory_path());
  auto again = read_mesh(d / "square.gltf");
  std::filesystem::current_path(cwd);
  ASSERT_TRUE(again.has_value()) << again.error().message();
  EXPECT_EQ(again->positions, m->positions);
}

TEST(GltfRead, BadFilesAndUrisAreErrorsNamingWhere) {
  const auto d = dir();
  write(d / "pos.bin", raw(kSquare));
  const std::string idx = "data:application/octet-stream;base64," + base64_encode(raw(kIndices));
  const auto expect_error = [&](const std::string& text, const std::string& what,
                                const std::string& tag) {
    const auto f = d / ("bad_" + tag + ".gltf");
    write(f, text);
    auto m = read_mesh(f);
    ASSERT_FALSE(m.has_value()) << tag;
    EXPECT_NE(m.error().message().find(what), std::string::npos)
        << tag << ": " << m.error().message();
    EXPECT_NE(m.error().file.find("bad_" + tag), std::string::npos) << tag;
  };
  ASSERT_TRUE(
      read_mesh((write(d / "ok.gltf", square("pos.bin", idx).dump()), d / "ok.gltf")).has_value());
  expect_error(square("https://example.com/pos.bin", idx).dump(), "nothing is fetched", "http");
  expect_error(square("file:///etc/pos.bin", idx).dump(), "nothing is fetched", "file");
  expect_error(square("missing.bin", idx).dump(), "buffers[0].uri: cannot open", "missing");
  expect_error(square("/dev/zero", idx).dump(), "no such file", "device");  // endless: not read
  expect_error(square("pos%2.bin", idx).dump(), "bad percent escape at character 4", "escape");
  expect_error(square("pos.bin", "data:application/octet-stream;base64,AAA!").dump(),
               "not base64 at character 41", "base64");
  expect_error(square("pos.bin", "data:text/plain,0123").dump(), "must be base64", "plain");
  expect_error(square("pos.bin", "data:application/octet-stream;base64,AAAA").dump(),
               "12 bytes, but its uri holds 3", "short");
  auto no_uri = square("pos.bin", idx);
  no_uri["buffers"][1].erase("uri");
  expect_error(no_uri.dump(), "buffers[1]: no uri", "nouri");
  auto wrong_buffer = square("pos.bin", idx);
  wrong_buffer["bufferViews"][1]["buffer"] = 2;
  expect_error(wrong_buffer.dump(), "bufferViews[1].buffer: not an index of buffers", "buffer");
  std::string text = square("pos.bin", idx).dump();
  expect_error(text.substr(0, text.size() / 2), "not valid JSON", "truncated");
  expect_error("{\"asset\": [1, 2,, 3]}", "byte 16", "syntax");  // the second comma
  expect_error("{}", "no triangles", "empty");
  expect_error("{\"asset\": 9e308}", "number overflow",
               "overflow");  // nlohmann throws out_of_range
  // A bad error bound in the scene's extras is an error of read_error_bound.
  auto bounded = square("pos.bin", idx);
  bounded["scenes"][0]["extras"]["error_bound"] = -2;
  write(d / "eb.gltf", bounded.dump());
  auto b = read_error_bound(d / "eb.gltf");
  ASSERT_FALSE(b.has_value());
  EXPECT_NE(b.error().message().find("error_bound"), std::string::npos);
}

}  // namespace
}  // namespace interfere
