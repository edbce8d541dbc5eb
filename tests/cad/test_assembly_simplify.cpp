// cad::simplify_assembly (issue #6, item 5): a prepared STEP assembly simplified part by part to one
// total budget, the instances placed; checked against the parts' own simplify() runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "cad_test_util.h"
#include "interfere/cad/assembly_simplify.h"
#include "interfere/cad/model.h"

namespace interfere::cad {
namespace {

std::filesystem::path dir() { return testing::scratch_dir("interfere_asm_simplify_tests"); }

// The test assembly (plate twice, shaft once), prepared; with `screw`: process step P1 screws
// plate_2 (its counterbore's faces are the step's features).
const Prepared& prepared(bool screw) {
  static const auto make = [](bool with_step) {
    const auto file = dir() / "assembly.step";
    if (!std::filesystem::exists(file)) EXPECT_TRUE(write_test_assembly(file).ok());
    PipelineOptions o;
    if (with_step) {
      o.process_file = (dir() / "process.json").string();
      std::ofstream(o.process_file) << R"({"steps": [{"id": "P1", "parts": ["plate_2"], "constraint": "screw"}]})";
      o.step = "P1";
    }
    auto p = prepare_for_simplify(file.string(), o);
    EXPECT_TRUE(p.has_value()) << p.error().message();
    return *p;
  };
  static const Prepared plain = make(false), step = make(true);
  return screw ? step : plain;
}

TEST(AssemblySimplify, TotalMetExactlyAndInstancesPlacedFromThePartsOwnRuns) {
  const Prepared& prep = prepared(false);
  ASSERT_EQ(prep.instances.size(), 3u);
  // Every part is closed (even triangle counts): an even total is met exactly whatever the
  // shares' rounding, an odd one ends one below.
  for (std::size_t total : {300u, 301u, 304u, 307u}) {
    auto a = simplify_assembly(prep, {.target_triangles = total});
    ASSERT_TRUE(a.has_value()) << a.error().message();
    const SimplifyResult& m = a->merged;
    EXPECT_EQ(m.mesh.num_triangles(), total - total % 2) << total;
    EXPECT_EQ(m.reached, total % 2 == 0) << total;
    EXPECT_EQ(m.target_triangles, total);
    EXPECT_GE(a->budget_rounds, 1);
    ASSERT_EQ(a->parts.size(), prep.parts.size());
    ASSERT_EQ(m.face_ids.size(), m.mesh.num_triangles());
    double bound = 0;
    // The merged mesh is the instances' parts, placed, in order; face ids offset per instance.
    std::size_t tri = 0;
    for (const PreparedInstance& inst : prep.instances) {
      const SimplifyResult& part = a->parts[inst.part];
      ASSERT_GT(a->part_budgets[inst.part], 0u);
      bound = std::max(bound, part.error_bound);
      for (std::size_t t = 0; t < part.mesh.num_triangles(); ++t, ++tri) {
        const auto c = part.mesh.corners(t), w = m.mesh.corners(tri);
        for (int k = 0; k < 3; ++k) EXPECT_EQ(inst.placement.apply(c[k]), w[k]);
        EXPECT_EQ(m.face_ids[tri], part.face_ids[t] + inst.face_offset);
      }
    }
    EXPECT_EQ(tri, m.mesh.num_triangles());
    EXPECT_EQ(m.error_bound, bound);
    // Each part's result is simplify() of the part to its budget, bit for bit.
    for (std::size_t i = 0; i < prep.parts.size(); ++i) {
      const PreparedPart& p = prep.parts[i];
      auto own = simplify(p.mesh, {.target_triangles = a->part_budgets[i], .face_ids = p.face_ids,
                                   .feature_faces = p.feature_faces});
      ASSERT_TRUE(own.has_value());
      EXPECT_EQ(own->mesh.triangles, a->parts[i].mesh.triangles) << p.name;
      EXPECT_EQ(own->mesh.positions, a->parts[i].mesh.positions) << p.name;
    }
  }
}

TEST(AssemblySimplify, PartsThatStopEarlyLeaveTheirExcessToTheOthers) {
  // 15 %: the plate stops above its share (seams and corners); the shaft takes up the rest.
  const Prepared& prep = prepared(false);
  // (Every seam kept: the default, --seams auto, would let the plate's seams go instead.)
  auto a = simplify_assembly(prep, {.ratio = 0.15, .seams = SeamMode::all});
  ASSERT_TRUE(a.has_value());
  EXPECT_GE(a->budget_rounds, 2);
  EXPECT_TRUE(a->merged.reached);
  bool stopped = false;
  for (std::size_t i = 0; i < prep.parts.size(); ++i)
    stopped = stopped || a->parts[i].mesh.num_triangles() > a->part_budgets[i];
  EXPECT_TRUE(stopped);
}

TEST(AssemblySimplify, TheStepsFeaturesStayOnTheInstanceItNames) {
  const Prepared& prep = prepared(true);
  ASSERT_EQ(prep.parts.size(), 3u);  // plate [P1], plate, shaft
  auto a = simplify_assembly(prep, {.ratio = 0.5, .feature_mode = FeatureMode::lock});
  ASSERT_TRUE(a.has_value());
  EXPECT_GT(a->merged.feature_triangles_in, 0u);
  EXPECT_EQ(a->merged.feature_triangles_out, a->merged.feature_triangles_in);
  EXPECT_LE(a->merged.hausdorff_features, 1e-12);
  // Only the part the step names carries features; the merged count is the instances' sum.
  std::size_t per_instance = 0;
  for (std::size_t i = 0; i < prep.parts.size(); ++i)
    EXPECT_EQ(a->parts[i].feature_triangles_in > 0, !prep.parts[i].feature_faces.empty()) << prep.parts[i].name;
  for (const PreparedInstance& inst : prep.instances) per_instance += a->parts[inst.part].feature_triangles_in;
  EXPECT_EQ(a->merged.feature_triangles_in, per_instance);
}

TEST(AssemblySimplify, BudgetsOutsideTheModelAreErrors) {
  const Prepared& prep = prepared(false);
  const std::size_t n = prep.mesh.num_triangles();
  for (SimplifyOptions o : {SimplifyOptions{.target_triangles = n + 1}, SimplifyOptions{.ratio = 1e-9},
                            SimplifyOptions{}}) {
    auto a = simplify_assembly(prep, o);
    ASSERT_FALSE(a.has_value());
    EXPECT_NE(a.error().reason.find("must lie in [1, " + std::to_string(n) + "]"), std::string::npos)
        << a.error().reason;
  }
  auto all = simplify_assembly(prep, {.target_triangles = n});
  ASSERT_TRUE(all.has_value());
  EXPECT_EQ(all->merged.mesh.num_triangles(), n);
}

}  // namespace
}  // namespace interfere::cad
