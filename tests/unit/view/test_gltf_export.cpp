// glTF scene export of a viewer document (issue #25, item 2; include/interfere/view/gltf.h): the GLB
// container (header, chunk types and lengths, 4-byte alignment), accessors (counts, exact POSITION
// min/max from the stored floats), one set of accessors per mesh shared by the bodies drawing it,
// materials (body colour and opacity, red clash and orange contact regions, unlit lines), nodes
// and extras, frames as an animation, bad documents refused with the field named and nothing written.
// The independent readers (three.js, a glTF schema, world boxes) are in tests/view/check_gltf.py.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

#include "interfere/mesh/generate.h"
#include "interfere/view/gltf.h"

namespace interfere::view {
namespace {

using json = nlohmann::json;

std::filesystem::path tmp(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("interfere_view_gltf_" + std::to_string(::getpid()) + "_" + name);
}

struct Glb {
  std::string bytes;
  std::uint32_t header[3]{}, json_chunk[2]{}, bin_chunk[2]{};
  json doc;
  std::string bin;
};

Glb read_glb(const std::filesystem::path& file) {
  Glb g;
  std::ifstream in(file, std::ios::binary);
  g.bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (g.bytes.size() < 20) return g;
  std::memcpy(g.header, g.bytes.data(), 12);
  std::memcpy(g.json_chunk, g.bytes.data() + 12, 8);
  g.doc = json::parse(g.bytes.substr(20, g.json_chunk[0]));
  const std::size_t at = 20 + g.json_chunk[0];
  if (at + 8 <= g.bytes.size()) {
    std::memcpy(g.bin_chunk, g.bytes.data() + at, 8);
    g.bin = g.bytes.substr(at + 8, g.bin_chunk[0]);
  }
  return g;
}

/// The float values of accessor `a` (tightly packed, as the writer stores them).
std::vector<float> floats(const Glb& g, std::size_t a) {
  const json& acc = g.doc["accessors"][a];
  const json& view = g.doc["bufferViews"][acc["bufferView"].get<std::size_t>()];
  const int width = acc["type"] == "VEC3" ? 3 : acc["type"] == "VEC4" ? 4 : 1;
  std::vector<float> out(acc["count"].get<std::size_t>() * width);
  std::memcpy(out.data(), g.bin.data() + view["byteOffset"].get<std::size_t>(), out.size() * 4);
  return out;
}

ViewMesh tetra() {
  ViewMesh m;
  m.mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0, 0, 3}};
  m.mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  m.source_triangles = 4;
  return m;
}

Document two_bodies_one_mesh() {
  Document d;
  d.title = "t";
  d.command = "interfere clash a b";
  d.units = "mm";
  d.verdict = "clash";
  d.meshes = {tetra()};
  ViewMesh region;
  region.mesh.positions = {{100, 0, 0}, {101, 0, 0}, {100, 1, 0}};
  region.mesh.triangles = {{0, 1, 2}};
  d.meshes.push_back(region);
  d.meshes.push_back(region);
  ViewBody a;
  a.id = "A", a.name = "alpha", a.path = "/asm/alpha", a.mesh = 0, a.tags = {"t1"};
  a.color = {1, 0, 0};
  ViewBody b = a;
  b.id = "B", b.name = "beta", b.pose.t = {100, 0, 0}, b.color = {0, 0, 1};
  d.bodies = {a, b};
  ViewClash c;
  c.id = "K1", c.verdict = "clash", c.status = "new", c.body_a = 0, c.body_b = 1, c.depth = 0.25;
  c.point = {100, 0.5, 0}, c.region_mesh = 1;
  c.curves = {{{100, 0, 0}, {100.5, 0.5, 0}, {101, 0, 0}}};
  ViewClash t = c;
  t.id = "K2", t.verdict = "contact", t.depth = -1, t.region_mesh = 2, t.curves.clear();
  t.has_witness = true, t.witness_a = {0, 0, 0}, t.witness_b = {0, 0, 1};
  d.clashes = {c, t};
  return d;
}

const json* node_named(const json& doc, const std::string& name) {
  for (const json& n : doc["nodes"])
    if (n.value("name", "") == name) return &n;
  return nullptr;
}

TEST(ViewGltf, ContainerChunksAndAlignment) {
  const auto file = tmp("container.glb");
  ASSERT_TRUE(write_glb(file, two_bodies_one_mesh()).ok());
  const Glb g = read_glb(file);
  EXPECT_EQ(g.header[0], 0x46546C67u);  // "glTF"
  EXPECT_EQ(g.header[1], 2u);
  EXPECT_EQ(g.header[2], g.bytes.size());
  EXPECT_EQ(g.json_chunk[1], 0x4E4F534Au);  // JSON
  EXPECT_EQ(g.json_chunk[0] % 4, 0u);
  EXPECT_EQ(g.bin_chunk[1], 0x004E4942u);  // BIN
  EXPECT_EQ(g.bin_chunk[0] % 4, 0u);
  EXPECT_EQ(28 + g.json_chunk[0] + g.bin_chunk[0], g.bytes.size());
  EXPECT_EQ(g.doc["asset"]["version"], "2.0");
  EXPECT_EQ(g.doc["buffers"][0]["byteLength"].get<std::size_t>(), g.bin.size());
  for (const json& v : g.doc["bufferViews"]) {
    EXPECT_EQ(v["byteOffset"].get<std::size_t>() % 4, 0u);
    EXPECT_LE(v["byteOffset"].get<std::size_t>() + v["byteLength"].get<std::size_t>(), g.bin.size());
  }
  std::filesystem::remove(file);
}

TEST(ViewGltf, AccessorsBoundsAndSharedMesh) {
  const auto file = tmp("accessors.glb");
  ASSERT_TRUE(write_glb(file, two_bodies_one_mesh()).ok());
  const Glb g = read_glb(file);
  const json* alpha = node_named(g.doc, "alpha");
  const json* beta = node_named(g.doc, "beta");
  ASSERT_TRUE(alpha && beta);
  // Different colours: two glTF meshes, one POSITION and one index accessor between them.
  const json& ma = g.doc["meshes"][(*alpha)["mesh"].get<std::size_t>()]["primitives"][0];
  const json& mb = g.doc["meshes"][(*beta)["mesh"].get<std::size_t>()]["primitives"][0];
  EXPECT_NE((*alpha)["mesh"], (*beta)["mesh"]);
  EXPECT_EQ(ma["attributes"]["POSITION"], mb["attributes"]["POSITION"]);
  EXPECT_EQ(ma["indices"], mb["indices"]);
  EXPECT_NE(ma["material"], mb["material"]);
  const std::size_t pos = ma["attributes"]["POSITION"];
  EXPECT_EQ(g.doc["accessors"][pos]["count"], 4);
  EXPECT_EQ(g.doc["accessors"][ma["indices"].get<std::size_t>()]["count"], 12);
  EXPECT_EQ(g.doc["accessors"][pos]["min"], json::array({0.0, 0.0, 0.0}));
  EXPECT_EQ(g.doc["accessors"][pos]["max"], json::array({1.0, 2.0, 3.0}));
  const std::vector<float> p = floats(g, pos);
  EXPECT_EQ(p[3 * 3 + 2], 3.0f);
  // Every POSITION accessor's bounds are its stored floats' bounds.
  for (const json& mesh : g.doc["meshes"])
    for (const json& prim : mesh["primitives"]) {
      const std::size_t a = prim["attributes"]["POSITION"];
      const std::vector<float> v = floats(g, a);
      for (int k = 0; k < 3; ++k) {
        float lo = std::numeric_limits<float>::max(), hi = -lo;
        for (std::size_t i = k; i < v.size(); i += 3) lo = std::min(lo, v[i]), hi = std::max(hi, v[i]);
        EXPECT_EQ(g.doc["accessors"][a]["min"][k].get<float>(), lo);
        EXPECT_EQ(g.doc["accessors"][a]["max"][k].get<float>(), hi);
      }
    }
  // The region is stored relative to its clash's point (the node's translation).
  const json* k1 = node_named(g.doc, "K1");
  ASSERT_TRUE(k1);
  EXPECT_EQ((*k1)["translation"], json::array({100.0, 0.5, 0.0}));
  const json* region = node_named(g.doc, "K1 region");
  ASSERT_TRUE(region);
  const std::size_t rpos = g.doc["meshes"][(*region)["mesh"].get<std::size_t>()]["primitives"][0]["attributes"]["POSITION"];
  EXPECT_EQ(floats(g, rpos), (std::vector<float>{0, -0.5f, 0, 1, -0.5f, 0, 0, 0.5f, 0}));
  std::filesystem::remove(file);
}

TEST(ViewGltf, MaterialsNodesAndExtras) {
  const auto file = tmp("materials.glb");
  ASSERT_TRUE(write_glb(file, two_bodies_one_mesh(), {.body_opacity = 0.5f}).ok());
  const Glb g = read_glb(file);
  const auto material = [&](const std::string& node) -> const json& {
    const json* n = node_named(g.doc, node);
    EXPECT_TRUE(n) << node;
    return g.doc["materials"][g.doc["meshes"][(*n)["mesh"].get<std::size_t>()]["primitives"][0]["material"].get<std::size_t>()];
  };
  const json& alpha = material("alpha");
  EXPECT_EQ(alpha["pbrMetallicRoughness"]["baseColorFactor"], json::array({1.0, 0.0, 0.0, 0.5}));
  EXPECT_EQ(alpha["alphaMode"], "BLEND");
  EXPECT_EQ(material("beta")["pbrMetallicRoughness"]["baseColorFactor"], json::array({0.0, 0.0, 1.0, 0.5}));
  // Red clash region (#e02020 in linear light), orange contact region, both opaque.
  const json red = material("K1 region")["pbrMetallicRoughness"]["baseColorFactor"];
  EXPECT_GT(red[0].get<double>(), 0.7);
  EXPECT_LT(red[1].get<double>(), 0.02);
  EXPECT_LT(red[2].get<double>(), 0.02);
  EXPECT_EQ(red[3].get<double>(), 1.0);
  EXPECT_FALSE(material("K1 region").contains("alphaMode"));
  const json orange = material("K2 region")["pbrMetallicRoughness"]["baseColorFactor"];
  EXPECT_GT(orange[0].get<double>(), 0.8);
  EXPECT_GT(orange[1].get<double>(), 0.3);
  EXPECT_LT(orange[2].get<double>(), 0.02);
  // Curves and witness: LINES in unlit materials.
  const json* curves = node_named(g.doc, "K1 curves");
  ASSERT_TRUE(curves);
  const json& line = g.doc["meshes"][(*curves)["mesh"].get<std::size_t>()]["primitives"][0];
  EXPECT_EQ(line["mode"], 1);
  EXPECT_EQ(g.doc["accessors"][line["indices"].get<std::size_t>()]["count"], 4);  // 2 segments
  EXPECT_TRUE(material("K1 curves")["extensions"].contains("KHR_materials_unlit"));
  EXPECT_EQ(g.doc["extensionsUsed"], json::array({"KHR_materials_unlit"}));
  EXPECT_EQ(g.doc["meshes"][node_named(g.doc, "K2 witness")->at("mesh").get<std::size_t>()]["primitives"][0]["mode"], 1);
  EXPECT_EQ(node_named(g.doc, "K2 curves"), nullptr);
  // Extras.
  const json& ab = node_named(g.doc, "alpha")->at("extras");
  EXPECT_EQ(ab["id"], "A");
  EXPECT_EQ(ab["path"], "/asm/alpha");
  EXPECT_EQ(ab["tags"], json::array({"t1"}));
  const json& k1 = node_named(g.doc, "K1")->at("extras");
  EXPECT_EQ(k1["clash_id"], "K1");
  EXPECT_EQ(k1["verdict"], "clash");
  EXPECT_EQ(k1["status"], "new");
  EXPECT_EQ(k1["depth"], 0.25);
  EXPECT_TRUE(k1["distance"].is_null());
  EXPECT_EQ(k1["bodies"], json::array({"A", "B"}));
  EXPECT_TRUE(node_named(g.doc, "K2")->at("extras")["depth"].is_null());
  const json& scene = g.doc["scenes"][0]["extras"];
  EXPECT_EQ(scene["schema"], "interfere.viewer");
  EXPECT_EQ(scene["units"], "mm");
  EXPECT_EQ(scene["command"], "interfere clash a b");
  EXPECT_EQ(scene["verdict"], "clash");
  // mm -> metres on the root; bodies placed by column-major matrices.
  EXPECT_EQ(node_named(g.doc, "interfere_root")->at("scale"), json::array({0.001, 0.001, 0.001}));
  EXPECT_FALSE(node_named(g.doc, "alpha")->contains("matrix"));  // identity
  const json m = node_named(g.doc, "beta")->at("matrix");
  EXPECT_EQ(m[12], 100.0);
  EXPECT_EQ(m[15], 1.0);
  EXPECT_FALSE(g.doc.contains("animations"));
  std::filesystem::remove(file);
}

TEST(ViewGltf, FaceColoursAsVertexColours) {
  Document d = two_bodies_one_mesh();
  d.legend = {{"a", {1, 0, 0}}, {"b", {0, 1, 0}}};
  d.meshes[0].face_colors = {0, 0, 1, 1};
  const auto file = tmp("colours.glb");
  ASSERT_TRUE(write_glb(file, d).ok());
  const Glb g = read_glb(file);
  const json& prim = g.doc["meshes"][node_named(g.doc, "alpha")->at("mesh").get<std::size_t>()]["primitives"][0];
  ASSERT_TRUE(prim["attributes"].contains("COLOR_0"));
  const std::vector<float> colour = floats(g, prim["attributes"]["COLOR_0"]);
  const std::size_t vertices = g.doc["accessors"][prim["attributes"]["POSITION"].get<std::size_t>()]["count"];
  EXPECT_GT(vertices, 4u);  // split between the two colours
  std::size_t red = 0, green = 0;
  for (std::size_t v = 0; v < vertices; ++v) {
    red += colour[3 * v] == 1 && colour[3 * v + 1] == 0;
    green += colour[3 * v] == 0 && colour[3 * v + 1] == 1;
  }
  EXPECT_EQ(red + green, vertices);
  EXPECT_GE(red, 3u);
  EXPECT_GE(green, 3u);
  std::filesystem::remove(file);
}

Document moving() {
  Document d = two_bodies_one_mesh();
  d.frames.labels = {"0", "1", "2"};
  d.frames.times = {0, 0.25, 1};
  Transform r;
  r.r = {{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}};  // 90 degrees about z
  r.t = {1, 2, 3};
  d.bodies[0].frame_poses = {Transform{}, r, r};
  d.bodies[1].frame_meshes = {0, 0, 2};
  d.clashes[0].frames = {2};
  return d;
}

TEST(ViewGltf, FramesAsAnimation) {
  const auto file = tmp("frames.glb");
  ASSERT_TRUE(write_glb(file, moving()).ok());
  const Glb g = read_glb(file);
  ASSERT_TRUE(g.doc.contains("animations"));
  const json& anim = g.doc["animations"][0];
  const json* alpha = node_named(g.doc, "alpha");
  ASSERT_TRUE(alpha);
  EXPECT_FALSE(alpha->contains("matrix"));
  EXPECT_TRUE(alpha->contains("rotation"));
  const std::size_t alpha_index = static_cast<std::size_t>(alpha - &g.doc["nodes"][0]);
  std::size_t translation = 0, rotation = 0, scale = 0;
  for (const json& ch : anim["channels"]) {
    const json& s = anim["samplers"][ch["sampler"].get<std::size_t>()];
    EXPECT_EQ(s["interpolation"], "STEP");
    EXPECT_EQ(floats(g, s["input"]), (std::vector<float>{0, 0.25f, 1}));
    const std::string path = ch["target"]["path"];
    if (ch["target"]["node"] == alpha_index && path == "translation") {
      ++translation;
      EXPECT_EQ(floats(g, s["output"]), (std::vector<float>{0, 0, 0, 1, 2, 3, 1, 2, 3}));
    }
    if (ch["target"]["node"] == alpha_index && path == "rotation") {
      ++rotation;
      const std::vector<float> q = floats(g, s["output"]);
      EXPECT_NEAR(q[4 + 2], std::sqrt(0.5), 1e-6);  // z of a 90-degree turn about z
      EXPECT_NEAR(q[4 + 3], std::sqrt(0.5), 1e-6);  // w
    }
    scale += path == "scale";
  }
  EXPECT_EQ(translation, 1u);
  EXPECT_EQ(rotation, 1u);
  EXPECT_EQ(scale, 3u);  // beta's two mesh children and clash K1
  const json* beta = node_named(g.doc, "beta");
  ASSERT_TRUE(beta);
  EXPECT_FALSE(beta->contains("mesh"));
  EXPECT_EQ((*beta)["children"].size(), 2u);
  // Without animation: the static view only.
  ASSERT_TRUE(write_glb(file, moving(), {.animation = false}).ok());
  const Glb s = read_glb(file);
  EXPECT_FALSE(s.doc.contains("animations"));
  EXPECT_TRUE(node_named(s.doc, "beta")->contains("mesh"));
  std::filesystem::remove(file);
}

TEST(ViewGltf, NonRigidPosesStayStatic) {
  Document d = moving();
  d.bodies[0].frame_poses[1].r[0][0] = 2;  // a scaled pose
  const auto file = tmp("scaled.glb");
  ASSERT_TRUE(write_glb(file, d).ok());
  const Glb g = read_glb(file);
  const json* alpha = node_named(g.doc, "alpha");
  ASSERT_TRUE(alpha);
  EXPECT_EQ((*alpha)["extras"]["animated"], false);
  EXPECT_FALSE(alpha->contains("rotation"));
  std::filesystem::remove(file);
}

TEST(ViewGltf, UnknownUnitsEmptyDocumentAndBadText) {
  Document d;
  d.units = "furlong";
  d.title = std::string("bad \xff utf-8");
  const auto file = tmp("empty.glb");
  ASSERT_TRUE(write_glb(file, d).ok());
  const Glb g = read_glb(file);
  EXPECT_EQ(g.header[2], g.bytes.size());
  EXPECT_FALSE(g.doc.contains("buffers"));
  EXPECT_FALSE(g.doc.contains("meshes"));
  EXPECT_FALSE(node_named(g.doc, "interfere_root")->contains("scale"));
  EXPECT_FALSE(node_named(g.doc, "bodies")->contains("children"));  // glTF: children has >= 1 item
  EXPECT_EQ(g.doc["scenes"][0]["extras"]["title"], "bad \xEF\xBF\xBD utf-8");
  std::filesystem::remove(file);
}

TEST(ViewGltf, BadDocumentsNameTheFieldAndWriteNothing) {
  const auto file = tmp("bad.glb");
  std::filesystem::remove(file);
  const auto error = [&](const Document& d, const GltfOptions& o = {}) {
    const Status s = write_glb(file, d, o);
    EXPECT_FALSE(s.ok());
    EXPECT_FALSE(std::filesystem::exists(file));
    return s.ok() ? std::string() : s.error().message();
  };
  Document d = two_bodies_one_mesh();
  d.bodies[1].mesh = 7;
  EXPECT_NE(error(d).find("bodies[1].mesh: mesh 7 out of range"), std::string::npos);
  d = moving();
  d.bodies[0].frame_poses.pop_back();
  EXPECT_NE(error(d).find("bodies[0].frame_poses: 2 poses for 3 frames"), std::string::npos);
  d = two_bodies_one_mesh();
  d.meshes[0].mesh.positions[1].y = std::nan("");
  EXPECT_NE(error(d).find("meshes[0].positions[1]: not finite"), std::string::npos);
  d = two_bodies_one_mesh();
  d.meshes[0].mesh.triangles[0][1] = 9;
  EXPECT_NE(error(d).find("meshes[0].triangles[0]"), std::string::npos);
  d = two_bodies_one_mesh();
  d.clashes[0].verdict = "boom";
  EXPECT_NE(error(d).find("clashes[0].verdict"), std::string::npos);
  d = two_bodies_one_mesh();
  d.error = "schema version 9";
  EXPECT_NE(error(d).find("could not be shown: schema version 9"), std::string::npos);
  EXPECT_NE(error(two_bodies_one_mesh(), {.body_opacity = 1.5f}).find("opacity"), std::string::npos);
  EXPECT_NE(error(d).find(file.string()), std::string::npos);  // the message names the file
}

}  // namespace
}  // namespace interfere::view
