// Slots, blind slots, steps and pockets with floor fillets and corner rounds on generated parts
// (issue #29, item 1), runnable without ../shared/data. The truth is the parts' construction
// (model.h's TestPart comments, src/cad/generate_floor_parts.cpp): each feature is the region its
// cutting tool removed, and its faces are found by their triangles alone (every corner inside that
// region's box), not by the AAG; fillets outside a feature's region (convex corner rounds and edge
// rounds) must be in no feature at all, and no part here has a hole.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>

#include "cad_test_util.h"
#include "interfere/cad/features.h"
#include "interfere/cad/model.h"

namespace interfere::cad {
namespace {

const Part& part(TestPart p) { return testing::generated_part(p); }

struct Box {
  double x0, y0, z0, x1, y1, z1;
  bool holds(const Vec3& q) const {
    constexpr double e = 1e-6;
    return q.x >= x0 - e && q.x <= x1 + e && q.y >= y0 - e && q.y <= y1 + e && q.z >= z0 - e && q.z <= z1 + e;
  }
};

// Faces every triangle corner of which lies in the box.
std::set<std::uint32_t> faces_in(const Part& p, const Box& b) {
  std::map<std::uint32_t, bool> inside;
  for (std::size_t t = 0; t < p.mesh.num_triangles(); ++t) {
    bool in = true;
    for (int c = 0; c < 3; ++c) in = in && b.holds(p.mesh.positions[p.mesh.triangles[t][c]]);
    auto [it, fresh] = inside.emplace(p.face_ids[t], in);
    if (!fresh) it->second = it->second && in;
  }
  std::set<std::uint32_t> out;
  for (const auto& [f, in] : inside)
    if (in) out.insert(f);
  return out;
}

// Faces whose corners all lie on the plane z = h.
std::set<std::uint32_t> faces_at_z(const Part& p, double h) {
  std::map<std::uint32_t, bool> on;
  for (std::size_t t = 0; t < p.mesh.num_triangles(); ++t) {
    bool in = true;
    for (int c = 0; c < 3; ++c) in = in && std::abs(p.mesh.positions[p.mesh.triangles[t][c]].z - h) <= 1e-6;
    auto [it, fresh] = on.emplace(p.face_ids[t], in);
    if (!fresh) it->second = it->second && in;
  }
  std::set<std::uint32_t> out;
  for (const auto& [f, in] : on)
    if (in) out.insert(f);
  return out;
}

struct Expected {
  std::string type;
  Box region;      ///< the tool's region inside the part: every face of the feature, nothing else
  double floor_z;  ///< the floor's height
  std::size_t fillets;  ///< faces of the floor fillets (0: none)
};

void check_part(TestPart tp, const std::vector<Expected>& expected) {
  SCOPED_TRACE(test_part_name(tp));
  const Part& p = part(tp);
  auto lib = default_feature_library();
  ASSERT_TRUE(lib.has_value()) << lib.error().message();
  const auto found = recognize_features(p.aag, *lib);
  static const std::set<std::string> floor_types{"pocket", "slot", "blind_slot", "through_step"};
  std::set<std::uint32_t> in_features;
  std::vector<const Feature*> floors;
  for (const Feature& f : found) {
    // No part here has a hole, a boss (a full outer cylinder) or a shoulder: fillets and corner rounds
    // are none of them.
    EXPECT_TRUE(floor_types.count(f.type)) << "unexpected " << f.type << " on faces " << f.faces.front();
    if (floor_types.count(f.type)) floors.push_back(&f), in_features.insert(f.faces.begin(), f.faces.end());
  }
  EXPECT_EQ(floors.size(), expected.size());
  for (const Expected& e : expected) {
    SCOPED_TRACE(e.type + " floor z " + std::to_string(e.floor_z));
    const std::set<std::uint32_t> faces = faces_in(p, e.region);
    const std::set<std::uint32_t> at = faces_at_z(p, e.floor_z);
    std::set<std::uint32_t> floor;
    std::set_intersection(faces.begin(), faces.end(), at.begin(), at.end(), std::inserter(floor, floor.end()));
    ASSERT_EQ(floor.size(), 1u) << "the construction's floor is one face";
    const Feature* match = nullptr;
    for (const Feature* f : floors)
      if (std::set<std::uint32_t>(f->faces.begin(), f->faces.end()) == faces) match = f;
    ASSERT_NE(match, nullptr) << "no feature with exactly the " << faces.size() << " faces of the region";
    EXPECT_EQ(match->type, e.type);
    const auto fl = match->role_faces.find("fillet");
    EXPECT_EQ(fl == match->role_faces.end() ? 0u : fl->second.size(), e.fillets);
    // The floor is the construction's floor, or (a step, a blind slot: two open sides) the face across
    // the concave edge: both readings name the same faces.
    if (e.type == "pocket" || e.type == "slot") EXPECT_EQ(match->role_faces.at("floor"), std::vector<std::uint32_t>(floor.begin(), floor.end()));
  }
  // Faces outside every region (convex corner rounds and edge fillets among them) are in no floor feature.
  std::set<std::uint32_t> regions;
  for (const Expected& e : expected) {
    const auto f = faces_in(p, e.region);
    regions.insert(f.begin(), f.end());
  }
  for (std::uint32_t f : in_features) EXPECT_TRUE(regions.count(f)) << "face " << f << " outside every feature's region";
}

TEST(FloorCases, SlotsThroughAndClosedAtOneEnd) {
  check_part(TestPart::slot_features_block,
             {{"slot", {0, 5, 22, 80, 17, 30}, 22, 2},
              {"blind_slot", {0, 25, 24, 45, 35, 30}, 24, 0},
              {"blind_slot", {50, 43, 20, 80, 55, 30}, 20, 0}});
}

TEST(FloorCases, PocketWithCornerRoundsAndFloorFillets) {
  // Floor fillets r = 2 along the four sides and the four corner blends between them and the corner
  // rounds r = 5.
  check_part(TestPart::filleted_pocket_block, {{"pocket", {15, 10, 15, 55, 40, 25}, 15, 8}});
}

TEST(FloorCases, StepsWithAndWithoutAFloorFillet) {
  // The first step's wall ends at z = 28 in the convex round r = 2 of its top edge, outside the region.
  check_part(TestPart::filleted_step_block,
             {{"through_step", {0, 0, 20, 60, 12, 28}, 20, 1}, {"through_step", {0, 30, 22, 60, 40, 30}, 22, 0}});
}

TEST(FloorCases, EarlierPartsKeepTheirFloorFeatures) {
  // slot_block, step_block (construction in model.h) and the pocket block's pocket.
  check_part(TestPart::slot_block, {{"slot", {0, 10, 12, 40, 20, 20}, 12, 0}});
  check_part(TestPart::step_block, {{"through_step", {0, 20, 12, 40, 30, 20}, 12, 0}});
  check_part(TestPart::pocket_block, {{"pocket", {15, 10, 12, 45, 30, 20}, 12, 0}});
}

}  // namespace
}  // namespace interfere::cad
