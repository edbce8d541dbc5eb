#include <gtest/gtest.h>

#include <limits>

#include "interfere/fem/fem_mesh.h"

namespace interfere {
namespace {

FemMesh one_tet() {
  FemMesh m;
  m.nodes = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.node_ids = {10, 11, 12, 13};
  const std::uint32_t v[4] = {0, 1, 2, 3};
  m.add_element(ElemType::tet4, 7, -1, v, 4);
  return m;
}

TEST(FemMesh, ElementTableIsConsistent) {
  for (int i = 0; i < kNumElemTypes; ++i) {
    const ElemInfo& info = elem_info(static_cast<ElemType>(i));
    ElemType back{};
    ASSERT_TRUE(elem_type_from_name(info.name, back)) << info.name;
    EXPECT_EQ(static_cast<int>(back), i);
    EXPECT_LE(info.corners, info.nodes);
    EXPECT_EQ(info.order == 1, info.corners == info.nodes) << info.name;
  }
  ElemType t{};
  EXPECT_FALSE(elem_type_from_name("tet5", t));
}

TEST(FemMesh, ValidateAcceptsAGoodMeshAndNamesTheBadElementOrNode) {
  EXPECT_TRUE(validate_fem_mesh(one_tet()));
  FemMesh bad = one_tet();
  bad.elem_nodes[2] = 9;
  Status s = validate_fem_mesh(bad);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().reason.find("element 7"), std::string::npos) << s.error().reason;
  bad = one_tet();
  bad.node_ids[3] = 10;
  s = validate_fem_mesh(bad);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().reason.find("duplicate node id 10"), std::string::npos);
  bad = one_tet();
  bad.nodes[1].y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(validate_fem_mesh(bad));
  bad = one_tet();
  bad.fields.push_back({"u", {0.0}, {std::vector<Vec3>(3)}});
  EXPECT_FALSE(validate_fem_mesh(bad));
}

}  // namespace
}  // namespace interfere
