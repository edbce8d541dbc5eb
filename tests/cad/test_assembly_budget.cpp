// Issue #29, item 3: assembly semantics that protect the mating parts. The paper's TopFace and
// BottomFace (He & Xu 2023 §3) are kept only within the clamped annulus around the hole, and the
// renderer's maximum is a cap that starves no part (include/interfere/simplify/budget.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <array>
#include <fstream>
#include <map>
#include <numbers>
#include <set>

#include "cad_test_util.h"
#include "interfere/cad/assembly_simplify.h"
#include "interfere/cad/model.h"
#include "interfere/simplify/budget.h"
#include "interfere/simplify/hausdorff.h"

namespace interfere::cad {
namespace {

std::filesystem::path dir() { return testing::scratch_dir("interfere_asm_budget_tests"); }

std::string write_process(const std::string& name, const std::string& json) {
  const auto p = dir() / name;
  std::ofstream(p) << json;
  return p.string();
}

// Distance from point p to the line (o, unit d).
double axis_distance(const Vec3& p, const Vec3& o, const Vec3& d) {
  const Vec3 v = p - o;
  const Vec3 r = v - dot(v, d) * d;
  return std::sqrt(dot(r, r));
}

TEST(AssemblyBudget, BoltRuleKeepsTheAnnulusAroundTheHoleNotTheWholeFace) {
  const auto file = dir() / "box_through_hole.step";
  ASSERT_TRUE(write_test_part(TestPart::box_through_hole, file).ok());
  // A fine tessellation, so the 40 x 30 faces have triangles away from the hole (r = 4).
  auto model = import_step(file, {.linear_deflection = 0.05, .angular_deflection = 0.1});
  ASSERT_TRUE(model.has_value()) << model.error().message();
  const Part& part = model->parts[0];
  auto lib = default_feature_library();
  auto rules = default_semantic_rules(*lib);
  ASSERT_TRUE(rules.has_value()) << rules.error().message();
  auto process = parse_process(R"({"steps":[{"id":"P1","constraint":"bolt"}]})");
  const auto feats = recognize_features(part.aag, *lib);
  auto sel = select_step_features(*process, "P1", *rules, part.name, feats, &part.aag);
  ASSERT_TRUE(sel.has_value()) << sel.error().message();
  // The hole's wall whole; its top and bottom faces as annuli of radius 2 r = 8 (the washer).
  ASSERT_EQ(sel->annuli.size(), 2u);
  for (const Annulus& a : sel->annuli) {
    EXPECT_NEAR(a.radius, 8.0, 1e-6);
    EXPECT_EQ(part.aag.nodes[a.face].type, SurfaceType::plane);
    EXPECT_FALSE(std::binary_search(sel->faces.begin(), sel->faces.end(), a.face));
  }
  for (std::uint32_t f : sel->faces) EXPECT_EQ(part.aag.nodes[f].type, SurfaceType::cylinder);
  // The triangles selected: those of the two faces with every corner within 8 of the axis.
  const auto tris = annulus_triangles(part.mesh, part.face_ids, sel->annuli);
  std::size_t on_faces = 0, expected = 0;
  for (std::size_t t = 0; t < part.mesh.num_triangles(); ++t) {
    const Annulus* a = nullptr;
    for (const Annulus& x : sel->annuli)
      if (x.face == part.face_ids[t]) a = &x;
    if (!a) continue;
    ++on_faces;
    bool in = true;
    for (std::uint32_t v : part.mesh.triangles[t]) in = in && axis_distance(part.mesh.positions[v], a->axis_point, a->axis) <= 8;
    expected += in;
    EXPECT_EQ(in, std::binary_search(tris.begin(), tris.end(), std::uint32_t(t))) << t;
  }
  EXPECT_EQ(tris.size(), expected);
  EXPECT_LT(tris.size(), on_faces);  // not the whole faces (BRepMesh fans the rim out to the border)
}

// annulus_triangles on a finely meshed face: a 100 x 100 square of 2 x 50 x 50 triangles, an
// annulus of radius 20 about the z axis through (50, 50): the triangles inside number about the
// disc's area over a triangle's (pi 20^2 / 2 = 628), less those the circle cuts (its length over
// the cells' size: about 2 pi 20 / 2 x 3 = 188 at most).
TEST(AssemblyBudget, AnnulusTrianglesOfAFinelyMeshedFaceFollowTheDisc) {
  TriMesh m;
  constexpr int n = 50;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.positions.push_back({2.0 * i, 2.0 * j, 0});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t v = j * (n + 1) + i;
      m.triangles.push_back({v, v + 1, v + n + 2});
      m.triangles.push_back({v, v + n + 2, v + n + 1});
    }
  const std::vector<std::uint32_t> faces(m.num_triangles(), 7);
  const auto tris = annulus_triangles(m, faces, {{.face = 7, .axis_point = {50, 50, -3}, .axis = {0, 0, 1}, .radius = 20}});
  const double disc = std::numbers::pi * 400 / 2;
  EXPECT_LE(double(tris.size()), disc);
  EXPECT_GE(double(tris.size()), disc - 190);
  for (std::uint32_t t : tris)
    for (std::uint32_t v : m.triangles[t]) EXPECT_LE(axis_distance(m.positions[v], {50, 50, 0}, {0, 0, 1}), 20.0);
  // Another face id: nothing.
  EXPECT_TRUE(annulus_triangles(m, faces, {{.face = 3, .axis_point = {50, 50, 0}, .axis = {0, 0, 1}, .radius = 20}}).empty());
}

TEST(AssemblyBudget, AHoleWhoseFaceCannotHoldAWasherIsNoBoltHole) {
  // The casing's main bore (r = 88) is a through hole of the flange ring, whose top face (about
  // 28,000 mm^2) is far below the annulus of radius 176 a bolt's washer would need: the bolt rule
  // skips it with a warning naming it; the 6 bolt holes (r = 6) stay.
  const auto file = dir() / "casing.step";
  ASSERT_TRUE(write_test_part(TestPart::casing, file).ok());
  auto model = import_step(file);
  ASSERT_TRUE(model.has_value());
  const Part& casing = model->parts[0];
  auto lib = default_feature_library();
  auto rules = default_semantic_rules(*lib);
  auto process = parse_process(R"({"steps":[{"id":"P2","constraint":"bolt"}]})");
  const auto feats = recognize_features(casing.aag, *lib);
  auto sel = select_step_features(*process, "P2", *rules, casing.name, feats, &casing.aag);
  ASSERT_TRUE(sel.has_value());
  for (std::uint32_t f : sel->faces) {
    const AagNode& n = casing.aag.nodes[f];
    EXPECT_EQ(n.type, SurfaceType::cylinder);
    EXPECT_NEAR(n.radius, 6.0, 1e-6);
  }
  EXPECT_EQ(sel->faces.size(), 6u);
  EXPECT_EQ(sel->annuli.size(), 12u);  // the upper flange's top and bottom around each hole
  bool warned = false;
  for (const auto& w : sel->warnings) warned = warned || (w.find("radius 88") != std::string::npos);
  EXPECT_TRUE(warned);
}

TEST(AssemblyBudget, ScrewRuleAddsTheBottomFaceWhereTheBoreLeaves) {
  // counterbored_plate: bore r = 3 through, counterbore r = 6 from the top: the screw rule keeps
  // bore, counterbore and seat whole and the plate's bottom face within 2 x 3 of the axis.
  const auto file = dir() / "counterbored.step";
  ASSERT_TRUE(write_test_part(TestPart::counterbored_plate, file).ok());
  auto model = import_step(file);
  ASSERT_TRUE(model.has_value());
  const Part& part = model->parts[0];
  auto lib = default_feature_library();
  auto rules = default_semantic_rules(*lib);
  auto process = parse_process(R"({"steps":[{"id":"P1","constraint":"screw"}]})");
  const auto feats = recognize_features(part.aag, *lib);
  auto sel = select_step_features(*process, "P1", *rules, part.name, feats, &part.aag);
  ASSERT_TRUE(sel.has_value());
  EXPECT_EQ(sel->faces.size(), 3u);
  ASSERT_EQ(sel->annuli.size(), 1u);
  const AagNode& bottom = part.aag.nodes[sel->annuli[0].face];
  EXPECT_EQ(bottom.type, SurfaceType::plane);
  EXPECT_LT(bottom.normal.z, -0.99);  // the plate's underside
  EXPECT_NEAR(sel->annuli[0].radius, 6.0, 1e-6);
  for (const auto& w : sel->warnings) EXPECT_EQ(w.find("found no"), std::string::npos) << w;
}

TEST(AssemblyBudget, RendererMaxIsACapAndEveryPartKeepsItsShape) {
  // The test assembly (two counterbored plates, a stepped shaft) with every part in a screw step,
  // to a cap far below the step's feature triangles: the total stays within the cap, every part
  // gets at least half its proportional share, and none collapses (error within 8 % of its size;
  // the issue's rod at 2 triangles was 12 %).
  const auto file = dir() / "assembly.step";
  ASSERT_TRUE(write_test_assembly(file).ok());
  PipelineOptions o;
  o.process_file = write_process("screw_all.json", R"({"steps":[{"id":"P1","constraint":"screw"}]})");
  o.step = "P1";
  auto prep = prepare_for_simplify(file.string(), o);
  ASSERT_TRUE(prep.has_value()) << prep.error().message();
  const std::size_t total = prep->mesh.num_triangles();
  std::size_t features = 0;
  for (const PreparedPart& p : prep->parts)
    features += p.instances * count_feature_triangles(p.face_ids, p.feature_faces, p.feature_triangles);
  const std::size_t cap = features / 2;
  ASSERT_GT(cap, 20u);
  SimplifyOptions so;
  so.target_triangles = triangle_budgets({{total, features}}, cap).budgets[0];
  EXPECT_EQ(so.target_triangles, cap);
  auto r = simplify_assembly(*prep, so);
  ASSERT_TRUE(r.has_value()) << r.error().message();
  EXPECT_LE(r->merged.mesh.num_triangles(), cap);
  EXPECT_TRUE(r->features_exceed_budget);
  for (std::size_t i = 0; i < prep->parts.size(); ++i) {
    const PreparedPart& p = prep->parts[i];
    const std::size_t floor = cap * p.mesh.num_triangles() / (2 * total);  // per instance, about
    EXPECT_GE(r->part_budgets[i] + 1, floor) << p.name;
    // The part's error against its own size, measured here (sampled both ways).
    const double d = norm(p.mesh.bounds().extent());
    const auto h = hausdorff(p.mesh, r->parts[i].mesh);
    EXPECT_LE(h.symmetric(), 0.08 * d) << p.name << " " << r->parts[i].mesh.num_triangles() << " triangles";
  }
}

// The CAx-IF AS1 assembly when ../shared/data is present (the issue's case): --renderer-max 1500
// gave 3,570 triangles with the bolts at 10 and the rod at 2.
TEST(AssemblyBudget, As1WithRendererMax1500StaysWithinAndKeepsBoltsAndRod) {
  const std::filesystem::path as1 = std::filesystem::path(INTERFERE_SOURCE_DIR) / "../shared/data/step/as1-oc-214.stp";
  if (!std::filesystem::exists(as1)) GTEST_SKIP() << as1 << " absent";
  PipelineOptions o;
  o.process_file = write_process("as1_bolt.json", R"({"steps":[{"id":"P1","constraint":"bolt"}]})");
  o.step = "P1";
  auto prep = prepare_for_simplify(as1.string(), o);
  ASSERT_TRUE(prep.has_value()) << prep.error().message();
  SimplifyOptions so;
  so.target_triangles = triangle_budgets({{prep->mesh.num_triangles(), 0}}, 1500).budgets[0];
  auto r = simplify_assembly(*prep, so);
  ASSERT_TRUE(r.has_value()) << r.error().message();
  EXPECT_LE(r->merged.mesh.num_triangles(), 1500u);
  for (std::size_t i = 0; i < prep->parts.size(); ++i) {
    const PreparedPart& p = prep->parts[i];
    const double d = norm(p.mesh.bounds().extent());
    const double h = hausdorff(p.mesh, r->parts[i].mesh).symmetric();
    EXPECT_LE(h, 0.06 * d) << p.name << " " << r->parts[i].mesh.num_triangles() << " triangles";
    if (p.name == "bolt" || p.name == "rod") EXPECT_GE(r->parts[i].mesh.num_triangles(), 16u) << p.name;
  }
}

// Issue #29, item 6: STEP colours are read with the parts (and kept in the glTF, whose part material
// takes them: tests/cli/test_simplify.py reads that back).
TEST(AssemblyBudget, StepColoursAreReadWithTheParts) {
  const auto file = dir() / "coloured.step";
  ASSERT_TRUE(write_test_assembly(file).ok());
  auto model = import_step(file);
  ASSERT_TRUE(model.has_value()) << model.error().message();
  std::map<std::string, std::array<float, 3>> want{{"plate", {0.8f, 0.2f, 0.1f}}, {"shaft", {0.1f, 0.3f, 0.9f}}};
  ASSERT_EQ(model->parts.size(), 2u);
  for (const Part& p : model->parts) {
    ASSERT_TRUE(p.has_color) << p.name;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(p.color[k], want.at(p.name)[k], 1e-3) << p.name << " " << k;
  }
  // A file without colours: none.
  const auto plain = dir() / "plain_box.step";
  ASSERT_TRUE(write_test_part(TestPart::box_through_hole, plain).ok());
  auto m2 = import_step(plain);
  ASSERT_TRUE(m2.has_value());
  EXPECT_FALSE(m2->parts[0].has_color);
}

// Issue #29, item 5: AP203 names and instance paths (CAx-IF AS1, AP203 export, when ../shared/data is
// there): products by name (not "=>[0:1:1:3]"), each instance's path unique and the second of two
// like sub-assemblies told apart at its own level ("L_BRACKET_ASSEMBLY#2"), not only at its leaves.
TEST(AssemblyBudget, Ap203PathsNameEachLevelsInstance) {
  const std::filesystem::path f = std::filesystem::path(INTERFERE_SOURCE_DIR) / "../shared/data/step/as1_pe_203.stp";
  if (!std::filesystem::exists(f)) GTEST_SKIP() << f << " absent";
  auto model = import_step(f, {.build_aag = false});
  ASSERT_TRUE(model.has_value()) << model.error().message();
  std::set<std::string> names, paths;
  for (const Part& p : model->parts) names.insert(p.name);
  EXPECT_EQ(names, (std::set<std::string>{"PLATE", "L-BRACKET", "BOLT", "NUT", "ROD"}));
  for (const Instance& in : model->instances) {
    EXPECT_TRUE(paths.insert(in.path).second) << in.path;
    EXPECT_EQ(in.path.find("=>"), std::string::npos) << in.path;
  }
  EXPECT_EQ(model->instances.size(), 18u);
  EXPECT_TRUE(paths.count("/AS1_PE_ASM/L_BRACKET_ASSEMBLY#2/NUT_BOLT_ASSEMBLY#3/BOLT")) << *paths.begin();
}

}  // namespace
}  // namespace interfere::cad
