// The bundled CAD example is what its generator writes (issue #29, data/examples/README.md):
// data/examples/casing.step is TestPart::paper_casing (He & Xu 2023 §4's casing) with its product
// named "casing" (tools/write_test_part). The STEP text differs by its header's time stamp, so the
// two are compared as read: product name, faces, each face's surface type, radius and area, the
// tessellation at the README's deflection.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "cad_test_util.h"
#include "interfere/cad/model.h"

namespace interfere::cad {
namespace {

TEST(ExampleFiles, CasingIsThePaperCasing) {
  const auto bundled = std::filesystem::path(INTERFERE_SOURCE_DIR) / "data" / "examples" / "casing.step";
  const auto fresh = testing::scratch_dir("interfere_cad_tests") / "paper_casing_as_casing.step";
  ASSERT_TRUE(write_test_part_named(TestPart::paper_casing, fresh, "casing").ok());
  for (const double deflection : {0.5, 0.01696}) {
    auto a = import_step(bundled, {.linear_deflection = deflection});
    auto b = import_step(fresh, {.linear_deflection = deflection});
    ASSERT_TRUE(a.has_value()) << a.error().message();
    ASSERT_TRUE(b.has_value()) << b.error().message();
    ASSERT_EQ(a->parts.size(), 1u);
    ASSERT_EQ(b->parts.size(), 1u);
    const Part &pa = a->parts[0], &pb = b->parts[0];
    EXPECT_EQ(pa.name, "casing");
    EXPECT_EQ(pb.name, "casing");
    EXPECT_EQ(a->instances.size(), 1u);
    ASSERT_EQ(pa.faces, pb.faces);
    ASSERT_EQ(pa.aag.nodes.size(), pb.aag.nodes.size());
    for (std::size_t f = 0; f < pa.aag.nodes.size(); ++f) {
      const AagNode &x = pa.aag.nodes[f], &y = pb.aag.nodes[f];
      EXPECT_EQ(x.type, y.type) << "face " << f;
      EXPECT_NEAR(x.radius, y.radius, 1e-9 * (1 + y.radius)) << "face " << f;
      EXPECT_NEAR(x.area, y.area, 1e-9 * (1 + y.area)) << "face " << f;
    }
    EXPECT_EQ(pa.aag.arcs.size(), pb.aag.arcs.size());
    EXPECT_EQ(pa.mesh.num_triangles(), pb.mesh.num_triangles()) << "deflection " << deflection;
    // The README's and the docs' count: the paper's 35,548 case (35,552 at 0.0205 until the wall was
    // meshed as sectors, issue #29: test_sector_split.cpp).
    if (deflection == 0.01696) EXPECT_EQ(pa.mesh.num_triangles(), 35556u);
  }
}

}  // namespace
}  // namespace interfere::cad
