// cad::assembly_clash on generated OCCT parts: a shaft seated in a counterbore of its own radius is
// a nominal fit (a contact: the tessellations cross only where the B-Rep cylinders and planes
// coincide); moved 0.3 mm off the axis it is a clash.
#include <gtest/gtest.h>

#include "cad_test_util.h"
#include "interfere/cad/assembly_clash.h"
#include "interfere/cad/model.h"

namespace interfere::cad {
namespace {

Part load_part(TestPart which) {
  const auto file = testing::scratch_dir("interfere_fit_tests") / (std::string(test_part_name(which)) + ".step");
  EXPECT_TRUE(write_test_part(which, file).ok());
  auto m = import_step(file);
  EXPECT_TRUE(m.has_value()) << m.error().message();
  return m->parts.at(0);
}

TEST(AssemblyFit, ShaftInACounterboreOfItsRadiusIsANominalFit) {
  CadModel m;
  m.parts = {load_part(TestPart::counterbored_plate), load_part(TestPart::stepped_shaft)};
  ASSERT_GT(m.parts[0].linear_deflection, 0);
  // The shaft upside down (180 degrees about x: exact), its r = 6 end on the counterbore's floor
  // (z = 6) on the bore's axis (20, 15).
  Transform flipped;
  flipped.r = {{{1, 0, 0}, {0, -1, 0}, {0, 0, -1}}};
  for (double off : {0.0, 0.3}) {
    flipped.t = {20 + off, 15, 61};
    m.instances = {{.name = "plate", .part = 0, .placement = Transform{}}, {.name = "shaft", .part = 1, .placement = flipped}};
    const AssemblyClashResult r = assembly_clash(m);
    ASSERT_EQ(r.pairs.size(), 1u) << off;
    const InstancePairResult& p = r.pairs[0];
    EXPECT_GT(p.cross_pairs, 0u) << off;  // the tessellated cylinders cross either way
    if (off == 0) {
      EXPECT_TRUE(p.nominal_fit);
      EXPECT_EQ(p.meeting, InstanceMeeting::contact);
      EXPECT_LE(p.depth, p.tessellation_error);
    } else {
      EXPECT_FALSE(p.nominal_fit);
      EXPECT_EQ(p.meeting, InstanceMeeting::clash);
      EXPECT_GT(p.depth, 0.2);
    }
  }
}

}  // namespace
}  // namespace interfere::cad
