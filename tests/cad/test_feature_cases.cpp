// Counterdrilled holes and pockets on generated parts (issue #29, item 3), runnable without
// ../shared/data. Expected answers from the parts' construction (src/cad/generate.cpp), the faces
// found by their own geometry (surface type, radius, normal, the height of their triangles).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <map>
#include <set>
#include <string>

#include "cad_test_util.h"
#include "interfere/cad/features.h"
#include "interfere/cad/model.h"
#include "interfere/cad/semantics.h"

namespace interfere::cad {
namespace {

const Part& part(TestPart p) { return testing::generated_part(p); }

std::vector<Feature> features(TestPart p) {
  auto lib = default_feature_library();
  EXPECT_TRUE(lib.has_value());
  return recognize_features(part(p).aag, *lib);
}

std::vector<Feature> of_type(const std::vector<Feature>& fs, const std::string& type) {
  std::vector<Feature> out;
  std::copy_if(fs.begin(), fs.end(), std::back_inserter(out), [&](const Feature& f) { return f.type == type; });
  return out;
}

// Mean z of a face's triangle corners (part coordinates).
double face_z(const Part& p, std::uint32_t f) {
  double s = 0;
  int k = 0;
  for (std::size_t t = 0; t < p.mesh.num_triangles(); ++t)
    if (p.face_ids[t] == f)
      for (int c = 0; c < 3; ++c) s += p.mesh.positions[p.mesh.triangles[t][c]].z, ++k;
  return k ? s / k : NAN;
}

std::set<std::uint32_t> faces_where(const Part& p, const std::function<bool(const AagNode&)>& pred) {
  std::set<std::uint32_t> out;
  for (const AagNode& n : p.aag.nodes)
    if (pred(n)) out.insert(n.face);
  return out;
}
std::set<std::uint32_t> as_set(const std::vector<std::uint32_t>& v) { return {v.begin(), v.end()}; }

TEST(FeatureCases, CounterdrilledHoleIsNotACounterbore) {
  const Part& p = part(TestPart::counterdrilled_plate);
  const auto fs = features(TestPart::counterdrilled_plate);
  ASSERT_EQ(of_type(fs, "counterdrilled_hole").size(), 1u);
  EXPECT_TRUE(of_type(fs, "counterbored_hole").empty());
  EXPECT_TRUE(of_type(fs, "countersunk_hole").empty());
  const std::vector<Feature> drilled = of_type(fs, "counterdrilled_hole");
  const Feature& h = drilled[0];
  const auto cyl = [&](double r) {
    return faces_where(p, [&](const AagNode& n) { return n.type == SurfaceType::cylinder && n.hole && std::abs(n.radius - r) < 1e-6; });
  };
  EXPECT_EQ(as_set(h.role_faces.at("counterdrill")), cyl(6));
  EXPECT_EQ(as_set(h.role_faces.at("bore")), cyl(3));
  EXPECT_EQ(as_set(h.role_faces.at("cone")), faces_where(p, [](const AagNode& n) { return n.type == SurfaceType::cone; }));
  // The hole opens on the plate's top (z = 10) and leaves through its bottom (z = 0).
  ASSERT_EQ(h.role_faces.at("top").size(), 1u);
  ASSERT_EQ(h.role_faces.at("bottom").size(), 1u);
  EXPECT_NEAR(face_z(p, h.role_faces.at("top")[0]), 10, 1e-9);
  EXPECT_NEAR(face_z(p, h.role_faces.at("bottom")[0]), 0, 1e-9);
  EXPECT_LT(h.axis.z, -0.999);  // from the opening into the part
  // The screw rule takes it (bore, counterdrill, cone; the BottomFace's annulus).
  auto lib = default_feature_library();
  auto rules = default_semantic_rules(*lib);
  ASSERT_TRUE(rules.has_value());
  auto process = parse_process(R"({"steps":[{"id":"P1","constraint":"screw"}]})");
  auto sel = select_step_features(*process, "P1", *rules, "plate", fs, &p.aag);
  ASSERT_TRUE(sel.has_value());
  std::set<std::uint32_t> want = cyl(6);
  for (std::uint32_t f : cyl(3)) want.insert(f);
  for (std::uint32_t f : h.role_faces.at("cone")) want.insert(f);
  EXPECT_EQ(as_set(sel->faces), want);
  ASSERT_EQ(sel->annuli.size(), 1u);
  EXPECT_EQ(sel->annuli[0].face, h.role_faces.at("bottom")[0]);
}

TEST(FeatureCases, PocketWithCornerRoundsIsOnePocket) {
  // pocket_block: pocket 15..45 x 10..30 from z 12 up (floor at z = 12), corners rounded r = 4; a
  // through slot with round ends at x 5..13 (no floor: no pocket).
  const Part& p = part(TestPart::pocket_block);
  const auto pockets = of_type(features(TestPart::pocket_block), "pocket");
  ASSERT_EQ(pockets.size(), 1u);
  const Feature& k = pockets[0];
  ASSERT_EQ(k.role_faces.at("floor").size(), 1u);
  const std::uint32_t floor = k.role_faces.at("floor")[0];
  EXPECT_NEAR(face_z(p, floor), 12, 1e-9);
  EXPECT_GT(p.aag.nodes[floor].normal.z, 0.999);
  // The walls: the faces above the floor inside the pocket's box, found by their triangles.
  std::set<std::uint32_t> walls;
  for (std::size_t t = 0; t < p.mesh.num_triangles(); ++t) {
    bool inside = true;
    for (int c = 0; c < 3; ++c) {
      const Vec3& v = p.mesh.positions[p.mesh.triangles[t][c]];
      inside = inside && v.x >= 15 - 1e-9 && v.x <= 45 + 1e-9 && v.y >= 10 - 1e-9 && v.y <= 30 + 1e-9 && v.z > 12 - 1e-9;
    }
    const std::uint32_t f = p.face_ids[t];
    if (inside && f != floor && std::abs(p.aag.nodes[f].normal.z) < 0.5) walls.insert(f);
  }
  EXPECT_EQ(walls.size(), 8u);  // 4 sides, 4 corner rounds
  EXPECT_EQ(as_set(k.role_faces.at("wall")), walls);
}

TEST(FeatureCases, SlotsAndStepsAreNoPockets) {
  const auto slot = features(TestPart::slot_block);
  EXPECT_TRUE(of_type(slot, "pocket").empty());
  EXPECT_EQ(of_type(slot, "slot").size(), 1u);
  const auto step = features(TestPart::step_block);
  EXPECT_TRUE(of_type(step, "pocket").empty());
  EXPECT_EQ(of_type(step, "through_step").size(), 1u);
  // A blind hole's floor has one wall all round: a hole, no pocket.
  const auto blind = features(TestPart::box_blind_hole);
  EXPECT_TRUE(of_type(blind, "pocket").empty());
  EXPECT_EQ(of_type(blind, "blind_hole").size(), 1u);
}

// He & Xu 2023 §4's casing as the paper states its steps (issue #29, item 4): P1, screw tightening of
// the counterbored holes on the working ring, keeps them and the BottomFace, the casing's inner ring
// face (the paper's node 344), as the clamped annulus around each hole; P2, bolting of the end
// flanges' through holes, keeps their walls and the flanges' faces around them, and none of the
// working ring's holes. Faces found by their own geometry (paper_casing's construction).
TEST(FeatureCases, PaperCasingStepsKeepThePapersFeatures) {
  const Part& p = part(TestPart::paper_casing);
  const auto fs = features(TestPart::paper_casing);
  EXPECT_EQ(of_type(fs, "counterbored_hole").size(), 6u);
  EXPECT_EQ(of_type(fs, "through_hole").size(), 13u);  // 12 flange bolt holes, the main bore
  const auto radial_cyl = [&](double r) {
    return faces_where(p, [&](const AagNode& n) {
      return n.type == SurfaceType::cylinder && n.hole && std::abs(n.radius - r) < 1e-6 && std::abs(n.axis.z) < 1e-6;
    });
  };
  const auto axial_cyl = [&](double r) {
    return faces_where(p, [&](const AagNode& n) {
      return n.type == SurfaceType::cylinder && n.hole && std::abs(n.radius - r) < 1e-6 && std::abs(std::abs(n.axis.z) - 1) < 1e-6;
    });
  };
  const auto r6 = radial_cyl(6), r3 = radial_cyl(3), r5 = axial_cyl(5), ring = axial_cyl(88);
  ASSERT_GE(r6.size(), 6u);
  ASSERT_GE(r3.size(), 6u);
  ASSERT_GE(r5.size(), 12u);
  ASSERT_FALSE(ring.empty());
  auto lib = default_feature_library();
  auto rules = default_semantic_rules(*lib);
  ASSERT_TRUE(rules.has_value());
  auto process = parse_process(R"({"steps":[{"id":"P1","constraint":"screw"},{"id":"P2","constraint":"bolt"}]})");
  ASSERT_TRUE(process.has_value());
  auto p1 = select_step_features(*process, "P1", *rules, "casing", fs, &p.aag);
  auto p2 = select_step_features(*process, "P2", *rules, "casing", fs, &p.aag);
  ASSERT_TRUE(p1.has_value() && p2.has_value());
  const auto s1 = as_set(p1->faces), s2 = as_set(p2->faces);
  const auto contains = [](const std::set<std::uint32_t>& a, const std::set<std::uint32_t>& b) {
    return std::includes(a.begin(), a.end(), b.begin(), b.end());
  };
  const auto disjoint = [](const std::set<std::uint32_t>& a, const std::set<std::uint32_t>& b) {
    return std::none_of(b.begin(), b.end(), [&](std::uint32_t f) { return a.count(f); });
  };
  // P1: the counterbored holes (counterbore, bore, seat) and the inner ring face's annuli (2 x r = 6).
  EXPECT_TRUE(contains(s1, r6));
  EXPECT_TRUE(contains(s1, r3));
  EXPECT_TRUE(disjoint(s1, r5));
  EXPECT_TRUE(disjoint(s1, ring));  // the inner ring face is kept around each hole only
  ASSERT_EQ(p1->annuli.size(), 6u);
  for (const Annulus& a : p1->annuli) {
    EXPECT_TRUE(ring.count(a.face)) << "annulus on face " << a.face;
    EXPECT_NEAR(a.radius, 6, 1e-6);
    EXPECT_LT(std::abs(a.axis.z), 1e-6);  // a radial hole's axis
  }
  // P2: the flanges' bolt holes and their top and bottom faces' annuli (planes z = 0, 12, 48, 60);
  // none of the working ring's holes; the main bore skipped (no washer fits its flange ring).
  EXPECT_TRUE(contains(s2, r5));
  EXPECT_TRUE(disjoint(s2, r6));
  EXPECT_TRUE(disjoint(s2, r3));
  EXPECT_EQ(p2->annuli.size(), 24u);  // 12 holes, a top and a bottom face each
  for (const Annulus& a : p2->annuli) {
    EXPECT_EQ(p.aag.nodes[a.face].type, SurfaceType::plane);
    EXPECT_GT(std::abs(p.aag.nodes[a.face].normal.z), 0.999);
    const double z = face_z(p, a.face);
    EXPECT_TRUE(std::abs(z) < 1e-6 || std::abs(z - 12) < 1e-6 || std::abs(z - 48) < 1e-6 || std::abs(z - 60) < 1e-6) << z;
  }
  EXPECT_TRUE(std::any_of(p2->warnings.begin(), p2->warnings.end(),
                          [](const std::string& w) { return w.find("radius 88") != std::string::npos; }));
}

// ImportOptions::delabella (issue #29, item 4: the casing's tessellation is most of its whole
// command): OCCT's Delabella triangulation gives every face triangles within the deflection (as
// measured on the surfaces) and the same features as the default algorithm.
TEST(FeatureCases, DelabellaTessellationKeepsFacesAndFeatures) {
  for (TestPart tp : {TestPart::counterbored_plate, TestPart::paper_casing}) {
    const auto file = testing::scratch_dir("interfere_feature_cases") / (std::string(test_part_name(tp)) + "_d.step");
    ASSERT_TRUE(write_test_part(tp, file).ok());
    auto plain = import_step(file, {.measure_deviation = true});
    auto fast = import_step(file, {.measure_deviation = true, .delabella = true});
    ASSERT_TRUE(plain.has_value() && fast.has_value());
    const Part &a = plain->parts.at(0), &b = fast->parts.at(0);
    EXPECT_TRUE(b.untessellated_faces.empty());
    EXPECT_EQ(as_set(b.face_ids).size(), b.faces) << test_part_name(tp);  // every face has triangles
    EXPECT_GT(b.mesh.num_triangles(), 0u);
    EXPECT_LE(b.tessellation_deviation, 2 * b.linear_deflection) << test_part_name(tp);
    auto lib = default_feature_library();
    std::multiset<std::string> ta, tb;
    for (const Feature& f : recognize_features(a.aag, *lib)) ta.insert(f.type + ":" + std::to_string(f.faces.size()));
    for (const Feature& f : recognize_features(b.aag, *lib)) tb.insert(f.type + ":" + std::to_string(f.faces.size()));
    EXPECT_EQ(ta, tb) << test_part_name(tp);
  }
}

}  // namespace
}  // namespace interfere::cad
