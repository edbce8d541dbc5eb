// Hole recognition on generated parts (issue #29, item 1), runnable without ../shared/data: corner
// rounds and slot ends are no holes; entry on an inclined and on a curved face; a blind hole whose
// floor circle is split in two edges; two crossing through holes. Expected answers from the parts'
// construction (src/cad/generate.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>

#include "cad_test_util.h"
#include "interfere/cad/features.h"
#include "interfere/cad/model.h"

namespace interfere::cad {
namespace {

const CadModel& model(TestPart p) {
  static std::map<TestPart, CadModel> cache;
  if (auto it = cache.find(p); it != cache.end()) return it->second;
  const auto file = testing::scratch_dir("interfere_hole_cases") / (std::string(test_part_name(p)) + ".step");
  const Status s = write_test_part(p, file);
  EXPECT_TRUE(s.ok()) << s.error().message();
  auto m = import_step(file);
  EXPECT_TRUE(m.has_value()) << m.error().message();
  return cache[p] = m.has_value() ? std::move(*m) : CadModel{};
}

std::multimap<std::string, Feature> holes(TestPart p) {
  auto lib = default_feature_library();
  EXPECT_TRUE(lib.has_value());
  std::multimap<std::string, Feature> out;
  const CadModel& m = model(p);
  if (m.parts.size() != 1 || !lib) return out;
  for (const Feature& f : recognize_features(m.parts[0].aag, *lib))
    if (f.type.find("hole") != std::string::npos) out.emplace(f.type, f);
  return out;
}

TEST(HoleCases, CornerRoundsAndSlotEndsAreNoHoles) {
  const auto h = holes(TestPart::pocket_block);
  EXPECT_TRUE(h.empty()) << h.size() << " holes, first: " << (h.empty() ? "" : h.begin()->first);
  // The part does have the concave cylinder patches the old rule took for holes.
  std::size_t concave_cylinders = 0;
  for (const AagNode& n : model(TestPart::pocket_block).parts[0].aag.nodes)
    concave_cylinders += n.type == SurfaceType::cylinder && n.hole;
  EXPECT_EQ(concave_cylinders, 6u);  // 4 corner rounds, 2 slot ends
}

TEST(HoleCases, ThroughHoleEnteringAnInclinedFace) {
  const auto h = holes(TestPart::inclined_entry_block);
  ASSERT_EQ(h.size(), 1u);
  EXPECT_EQ(h.begin()->first, "through_hole");
  const Feature& f = h.begin()->second;
  ASSERT_TRUE(f.role_faces.count("top") && f.role_faces.count("bottom"));
  const Aag& g = model(TestPart::inclined_entry_block).parts[0].aag;
  // One opening on the inclined plane (normal 30 degrees off z), one on the bottom plane.
  int inclined = 0, flat = 0;
  for (const char* role : {"top", "bottom"})
    for (std::uint32_t x : f.role_faces.at(role)) {
      const AagNode& n = g.nodes[x];
      ASSERT_EQ(n.type, SurfaceType::plane);
      if (std::abs(std::abs(n.normal.z) - 1) < 1e-9) ++flat;
      else if (std::abs(std::abs(n.normal.z) - std::cos(M_PI / 6)) < 1e-6) ++inclined;
    }
  EXPECT_EQ(inclined, 1);
  EXPECT_EQ(flat, 1);
}

TEST(HoleCases, ThroughHoleEnteringAndLeavingACurvedFace) {
  const auto h = holes(TestPart::shaft_cross_hole);
  ASSERT_EQ(h.size(), 1u);
  EXPECT_EQ(h.begin()->first, "through_hole");
  EXPECT_NEAR(h.begin()->second.radii.at(0), 3, 1e-9);
  const Aag& g = model(TestPart::shaft_cross_hole).parts[0].aag;
  for (const auto& [role, faces] : h.begin()->second.role_faces)
    if (role == "top" || role == "bottom")
      for (std::uint32_t x : faces) EXPECT_EQ(g.nodes[x].type, SurfaceType::cylinder) << role;
}

TEST(HoleCases, BlindHoleWithItsFloorCircleSplit) {
  const auto h = holes(TestPart::blind_split_floor);
  ASSERT_EQ(h.size(), 1u);
  EXPECT_EQ(h.begin()->first, "blind_hole");
  const Feature& f = h.begin()->second;
  EXPECT_EQ(f.role_faces.at("wall").size(), 2u);  // two half cylinders
  ASSERT_EQ(f.role_faces.at("bottom").size(), 1u);
  const Aag& g = model(TestPart::blind_split_floor).parts[0].aag;
  std::size_t floor_arcs = 0;
  for (const AagArc& a : g.arcs) floor_arcs += a.a == f.roles.at("bottom") || a.b == f.roles.at("bottom");
  EXPECT_EQ(floor_arcs, 2u);  // the floor circle is two edges
}

TEST(HoleCases, CrossingThroughHoles) {
  // The r = 4 bore along x is one wall (two openings cut into it). The r = 3 hole along y passes
  // through the bore's void, so its wall is two faces whose extents do not touch: two through holes,
  // as the independent labeller of the truth set counts them too (one drilling, two walls).
  const auto h = holes(TestPart::crossing_holes);
  std::multiset<long> radii;
  for (const auto& [type, f] : h) {
    EXPECT_EQ(type, "through_hole");
    radii.insert(std::lround(f.radii.at(0)));
  }
  EXPECT_EQ(radii, (std::multiset<long>{3, 3, 4}));
}

}  // namespace
}  // namespace interfere::cad
