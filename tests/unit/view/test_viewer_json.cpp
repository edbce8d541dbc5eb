// The viewer document's JSON (issue #25, include/interfere/view/json.h): written, then read back with
// nlohmann and an independent base64 decoder, against the document's own numbers.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>

#include "interfere/view/json.h"
#include "unit/view/viewer_json_decode.h"

namespace interfere::view {
namespace {

using nlohmann::json;
using testing::apply_column_major;
using testing::decode_base64;
using testing::le_f32;
using testing::le_u16;
using testing::le_u32;

Transform rot_z90(Vec3 t) {
  Transform p;
  p.r = {{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}};
  p.t = t;
  return p;
}

// Two bodies sharing a tetrahedron far from the world origin, a clash with a region mesh and a
// curve, a clearance with a witness, two frames.
Document sample() {
  Document d;
  d.title = "sample";
  d.command = "interfere clash a b";
  d.verdict = "clash";
  d.legend = {{"plane", {1, 0, 0}}, {"other", {0.5f, 0.5f, 0.5f}}};
  ViewMesh tet;
  tet.mesh.positions = {{0, 0, 0}, {1.5, 0, 0}, {0, 2.25, 0}, {0, 0, -3.125}};
  tet.mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  tet.face_colors = {0, 1, 0, 1};
  tet.clash_flags = {1, 0, 0, 1};
  tet.source_triangles = 4;
  d.meshes.push_back(tet);
  ViewMesh region;
  region.mesh.positions = {{1001, 2001, 3001}, {1002, 2001, 3001}, {1001, 2002, 3001}};
  region.mesh.triangles = {{0, 1, 2}};
  d.meshes.push_back(region);
  ViewBody a;
  a.id = "a", a.name = "part a", a.path = "/asm/a", a.mesh = 0, a.pose = rot_z90({1000, 2000, 3000});
  a.frame_poses = {rot_z90({1000, 2000, 3000}), rot_z90({1000, 2000, 3004})};
  ViewBody b;
  b.id = "b", b.name = "part b", b.path = "/asm/b", b.mesh = 0;
  b.pose.t = {1010, 2000, 3000};
  d.bodies = {a, b};
  ViewClash c;
  c.id = "C1", c.verdict = "clash", c.status = "new", c.kind = "crossing";
  c.body_a = 0, c.body_b = 1;
  c.depth = 0.5, c.depth_bound = 0.625;
  c.point = {1001.5, 2001, 3001};
  c.box_min = {1001, 2001, 3001}, c.box_max = {1002, 2002, 3001};
  c.curves = {{{1001, 2001, 3001}, {1002, 2001, 3001}}};
  c.region_mesh = 1;
  c.frames = {1};
  ViewClash g;
  g.id = "C2", g.verdict = "clearance", g.kind = "clearance", g.body_a = 0, g.body_b = 1;
  g.distance = 0.25;
  g.point = {1005, 2000, 3000};
  g.box_min = g.box_max = g.point;
  g.has_witness = true, g.witness_a = {1004.875, 2000, 3000}, g.witness_b = {1005.125, 2000, 3000};
  d.clashes = {c, g};
  d.frames.labels = {"frame 0", "frame 1"};
  d.frames.times = {0, 0.5};
  d.frames.verdicts = {"clear", "clash"};
  return d;
}

// The origin by brute force: every vertex of every body at every pose, every clash coordinate.
Vec3 expected_origin(const Document& d) {
  Aabb box;
  for (const ViewBody& b : d.bodies) {
    std::vector<Transform> poses = b.frame_poses;
    poses.push_back(b.pose);
    for (const Transform& t : poses)
      for (const Vec3& p : d.meshes[b.mesh].mesh.positions) box.expand(t.apply(p));
  }
  for (const ViewClash& c : d.clashes) {
    box.expand(c.point), box.expand(c.box_min), box.expand(c.box_max);
    for (const auto& l : c.curves)
      for (const Vec3& p : l) box.expand(p);
    if (c.has_witness) box.expand(c.witness_a), box.expand(c.witness_b);
    if (c.region_mesh >= 0)
      for (const Vec3& p : d.meshes[static_cast<std::size_t>(c.region_mesh)].mesh.positions) box.expand(p);
  }
  return box.center();
}

json written(const Document& d) {
  const Expected<std::string> text = document_json(d);
  if (!text) ADD_FAILURE() << text.error().message();
  return text ? json::parse(*text) : json();
}

TEST(ViewerJson, SchemaAndHeader) {
  const json j = written(sample());
  EXPECT_EQ(j["schema"], "interfere.viewer");
  EXPECT_EQ(j["schema_version"], 1);
  EXPECT_EQ(j["title"], "sample");
  EXPECT_EQ(j["command"], "interfere clash a b");
  EXPECT_EQ(j["units"], "mm");
  EXPECT_EQ(j["verdict"], "clash");
  EXPECT_EQ(j["error"], "");
  EXPECT_EQ(j["legend"].size(), 2u);
  EXPECT_EQ(j["legend"][1]["color"], json::array({0.5, 0.5, 0.5}));
}

TEST(ViewerJson, OriginIsTheCentreOfEveryWorldCoordinate) {
  const Document d = sample();
  const Vec3 want = expected_origin(d);
  // The sample's box: x from 997.75 (body a rotated) to 1011.5 (body b), y 2000..2002.25, z 2996.875..3004.
  EXPECT_DOUBLE_EQ(want.x, (997.75 + 1011.5) / 2);
  const Vec3 o = document_origin(d);
  EXPECT_DOUBLE_EQ(o.x, want.x);
  EXPECT_DOUBLE_EQ(o.y, want.y);
  EXPECT_DOUBLE_EQ(o.z, want.z);
  const json j = written(d);
  EXPECT_EQ(j["origin"], json::array({want.x, want.y, want.z}));
  // No coordinates at all: the origin is 0.
  const Vec3 none = document_origin(Document{});
  EXPECT_EQ(none, (Vec3{0, 0, 0}));
}

TEST(ViewerJson, LocalMeshBuffersRoundTrip) {
  const Document d = sample();
  const json j = written(d);
  const json& m = j["meshes"][0];
  const TriMesh& tm = d.meshes[0].mesh;
  ASSERT_EQ(m["vertices"], tm.num_vertices());
  ASSERT_EQ(m["triangles"], tm.num_triangles());
  const std::string pos = decode_base64(m["positions"]);
  ASSERT_EQ(pos.size(), tm.num_vertices() * 12);
  for (std::size_t v = 0; v < tm.num_vertices(); ++v)
    for (std::size_t k = 0; k < 3; ++k)  // local positions as given (exact in float32 here)
      EXPECT_EQ(le_f32(pos, 12 * v + 4 * k), static_cast<float>(tm.positions[v][k])) << v << " " << k;
  const std::string idx = decode_base64(m["indices"]);
  ASSERT_EQ(idx.size(), tm.num_triangles() * 12);
  for (std::size_t t = 0; t < tm.num_triangles(); ++t)
    for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(le_u32(idx, 12 * t + 4 * k), tm.triangles[t][k]);
  const std::string fc = decode_base64(m["face_colors"]);
  ASSERT_EQ(fc.size(), 8u);
  for (std::size_t t = 0; t < 4; ++t) EXPECT_EQ(le_u16(fc, 2 * t), d.meshes[0].face_colors[t]);
  const std::string flags = decode_base64(m["clash_flags"]);
  ASSERT_EQ(flags.size(), 4u);
  for (std::size_t t = 0; t < 4; ++t) EXPECT_EQ(static_cast<unsigned char>(flags[t]), d.meshes[0].clash_flags[t]);
  EXPECT_EQ(m["source_triangles"], 4);
  EXPECT_EQ(m["decimation_error"], 0.0);
  // Optional buffers left out when empty.
  EXPECT_FALSE(j["meshes"][1].contains("face_colors"));
  EXPECT_FALSE(j["meshes"][1].contains("clash_flags"));
}

TEST(ViewerJson, RegionMeshIsWorldMinusOrigin) {
  const Document d = sample();
  const json j = written(d);
  const Vec3 o = expected_origin(d);
  const std::string pos = decode_base64(j["meshes"][1]["positions"]);
  const TriMesh& tm = d.meshes[1].mesh;
  for (std::size_t v = 0; v < tm.num_vertices(); ++v)
    for (std::size_t k = 0; k < 3; ++k)
      EXPECT_NEAR(le_f32(pos, 12 * v + 4 * k) + o[k], tm.positions[v][k], 1e-4) << v << " " << k;
  EXPECT_EQ(j["clashes"][0]["region_mesh"], 1);
  EXPECT_TRUE(j["clashes"][1]["region_mesh"].is_null());
}

TEST(ViewerJson, PoseMatricesAreColumnMajorWithTranslationMinusOrigin) {
  const Document d = sample();
  const json j = written(d);
  const Vec3 o = expected_origin(d);
  const Vec3 p{0.25, -1.5, 2};  // a local point; the matrix applied to it, plus the origin, is the pose's image
  for (std::size_t b = 0; b < 2; ++b) {
    const std::vector<double> m = j["bodies"][b]["pose"].get<std::vector<double>>();
    ASSERT_EQ(m.size(), 16u);
    EXPECT_EQ(m[3], 0.0);
    EXPECT_EQ(m[7], 0.0);
    EXPECT_EQ(m[11], 0.0);
    EXPECT_EQ(m[15], 1.0);
    const auto q = apply_column_major(m, p.x, p.y, p.z);
    const Vec3 want = d.bodies[b].pose.apply(p);
    for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(q[k] + o[k], want[k], 1e-9) << b << " " << k;
  }
  // The rotation about z sends local x to world y: column 0 is (0, 1, 0).
  const std::vector<double> m = j["bodies"][0]["pose"].get<std::vector<double>>();
  EXPECT_EQ(m[0], 0.0);
  EXPECT_EQ(m[1], 1.0);
  EXPECT_EQ(m[2], 0.0);
  ASSERT_EQ(j["bodies"][0]["frame_poses"].size(), 2u);
  const auto q = apply_column_major(j["bodies"][0]["frame_poses"][1].get<std::vector<double>>(), p.x, p.y, p.z);
  const Vec3 want = d.bodies[0].frame_poses[1].apply(p);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(q[k] + o[k], want[k], 1e-9);
  EXPECT_FALSE(j["bodies"][1].contains("frame_poses"));
  EXPECT_EQ(j["bodies"][0]["path"], "/asm/a");
  EXPECT_EQ(j["bodies"][0]["mesh"], 0);
}

TEST(ViewerJson, ClashRows) {
  const Document d = sample();
  const json j = written(d);
  const Vec3 o = expected_origin(d);
  ASSERT_EQ(j["clashes"].size(), 2u);
  const json& c = j["clashes"][0];
  EXPECT_EQ(c["id"], "C1");
  EXPECT_EQ(c["verdict"], "clash");
  EXPECT_EQ(c["bodies"], json::array({0, 1}));
  EXPECT_EQ(c["depth"], 0.5);
  EXPECT_EQ(c["depth_bound"], 0.625);
  EXPECT_TRUE(c["distance"].is_null());
  EXPECT_TRUE(c["witness"].is_null());
  EXPECT_EQ(c["point"], json::array({1001.5 - o.x, 2001 - o.y, 3001 - o.z}));
  EXPECT_EQ(c["box"][1], json::array({1002 - o.x, 2002 - o.y, 3001 - o.z}));
  ASSERT_EQ(c["curves"].size(), 1u);
  EXPECT_EQ(c["curves"][0].size(), 6u);
  EXPECT_EQ(c["curves"][0][3], 1002 - o.x);
  EXPECT_EQ(c["frames"], json::array({1}));
  const json& g = j["clashes"][1];
  EXPECT_TRUE(g["depth"].is_null());
  EXPECT_EQ(g["distance"], 0.25);
  EXPECT_EQ(g["witness"][0], json::array({1004.875 - o.x, 2000 - o.y, 3000 - o.z}));
  EXPECT_EQ(j["frames"]["labels"], json::array({"frame 0", "frame 1"}));
  EXPECT_EQ(j["frames"]["times"], json::array({0.0, 0.5}));
  EXPECT_EQ(j["frames"]["verdicts"], json::array({"clear", "clash"}));
}

// A NaN or an infinity anywhere is an error naming the field, never "null" or "nan" in the JSON.
TEST(ViewerJson, NonFiniteNumbersAreErrors) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  struct Case {
    const char* field;
    void (*spoil)(Document&, double);
  };
  const Case cases[] = {
      {"meshes[0].positions[2]", [](Document& d, double v) { d.meshes[0].mesh.positions[2].y = v; }},
      {"meshes[1].positions[0]", [](Document& d, double v) { d.meshes[1].mesh.positions[0].x = v; }},
      {"bodies[1].pose", [](Document& d, double v) { d.bodies[1].pose.r[2][1] = v; }},
      {"bodies[0].frame_poses[1]", [](Document& d, double v) { d.bodies[0].frame_poses[1].t.z = v; }},
      {"clashes[0].depth", [](Document& d, double v) { d.clashes[0].depth = v; }},
      {"clashes[1].distance", [](Document& d, double v) { d.clashes[1].distance = v; }},
      {"clashes[0].point", [](Document& d, double v) { d.clashes[0].point.z = v; }},
      {"clashes[0].curves[0]", [](Document& d, double v) { d.clashes[0].curves[0][1].x = v; }},
      {"clashes[1].witness", [](Document& d, double v) { d.clashes[1].witness_b.y = v; }},
      {"frames.times[1]", [](Document& d, double v) { d.frames.times[1] = v; }},
      {"bodies[0].color", [](Document& d, double v) { d.bodies[0].color[1] = static_cast<float>(v); }},
      {"meshes[0].decimation_error", [](Document& d, double v) { d.meshes[0].decimation_error = v; }},
  };
  for (const Case& c : cases)
    for (const double v : {nan, inf, -inf}) {
      Document d = sample();
      c.spoil(d, v);
      const Expected<std::string> text = document_json(d);
      ASSERT_FALSE(text) << c.field << " " << v;
      EXPECT_NE(text.error().reason.find(c.field), std::string::npos) << text.error().reason;
    }
  // A local position beyond float32's range.
  Document d = sample();
  d.meshes[0].mesh.positions[1].x = 1e300;
  const Expected<std::string> text = document_json(d);
  ASSERT_FALSE(text);
  EXPECT_NE(text.error().reason.find("float32"), std::string::npos) << text.error().reason;
}

TEST(ViewerJson, InconsistentDocumentsAreErrors) {
  const auto reason = [](const Document& d) {
    const Expected<std::string> t = document_json(d);
    return t ? std::string("(no error)") : t.error().reason;
  };
  Document d = sample();
  d.bodies[1].mesh = 7;
  EXPECT_NE(reason(d).find("bodies[1].mesh"), std::string::npos) << reason(d);
  d = sample();
  d.meshes[0].mesh.triangles[3][2] = 4;
  EXPECT_NE(reason(d).find("meshes[0].triangles[3]"), std::string::npos) << reason(d);
  d = sample();
  d.meshes[0].face_colors[2] = 2;  // two legend entries
  EXPECT_NE(reason(d).find("meshes[0].face_colors[2]"), std::string::npos) << reason(d);
  d = sample();
  d.meshes[0].clash_flags.pop_back();
  EXPECT_NE(reason(d).find("meshes[0].clash_flags"), std::string::npos) << reason(d);
  d = sample();
  d.clashes[0].region_mesh = 0;  // the bodies' local mesh
  EXPECT_NE(reason(d).find("used both"), std::string::npos) << reason(d);
  d = sample();
  d.clashes[0].verdict = "clear";
  EXPECT_NE(reason(d).find("clashes[0].verdict"), std::string::npos) << reason(d);
  d = sample();
  d.clashes[1].body_b = 2;
  EXPECT_NE(reason(d).find("clashes[1].bodies"), std::string::npos) << reason(d);
  d = sample();
  d.clashes[0].frames = {2};
  EXPECT_NE(reason(d).find("clashes[0].frames[0]"), std::string::npos) << reason(d);
  d = sample();
  d.bodies[0].frame_poses.pop_back();
  EXPECT_NE(reason(d).find("bodies[0].frame_poses"), std::string::npos) << reason(d);
  d = sample();
  d.frames.verdicts.pop_back();
  EXPECT_NE(reason(d).find("frames.verdicts"), std::string::npos) << reason(d);
}

// Invalid UTF-8 in a name (a Latin-1 STEP label) is replaced, not an exception.
TEST(ViewerJson, InvalidUtf8IsReplaced) {
  Document d = sample();
  d.bodies[0].name = "Stra\xdf" "e";
  const json j = written(d);
  EXPECT_EQ(j["bodies"][0]["name"], "Stra\xef\xbf\xbd" "e");
}

}  // namespace
}  // namespace interfere::view
