// Bearing assemblies (issue #27): the JSON reader and every bad input, each error naming the
// parameter by its JSON path (assembly.h, read_assembly_file / parse_assembly / validate_assembly).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "unit/bearing/assembly_fixture.h"
#include "interfere/bearing/assembly.h"

namespace interfere::bearing {
namespace {

using test::assembly_json;
using test::kCylindricalBearing;
using test::kTaperedBearing;

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

/// The error of a description whose cylindrical bearing has `from` replaced by `to`.
std::string error_of(const std::string& text) {
  Expected<AssemblySpec> s = parse_assembly(text, "axle.json");
  if (s) return "(no error)";
  return s.error().message();
}
std::string cyl_error(const std::string& from, const std::string& to, const std::string& extra = "") {
  return error_of(assembly_json(extra, replace(kCylindricalBearing, from, to)));
}
std::string tap_error(const std::string& from, const std::string& to) {
  return error_of(assembly_json("", replace(kTaperedBearing, from, to)));
}

#define EXPECT_HAS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << (text)

TEST(BearingAssemblyRead, ReadsBothTypes) {
  Expected<AssemblySpec> s =
      parse_assembly(assembly_json(R"("frames": 5, "seed": 9, "clearance": 0.1, "ring_segments": 48,)",
                                   test::both_bearings()),
                     "axle.json");
  ASSERT_TRUE(s) << s.error().message();
  EXPECT_EQ(s->frames, 5);
  EXPECT_EQ(s->seed, 9u);
  EXPECT_EQ(s->clearance, 0.1);
  EXPECT_EQ(s->ring_segments, 48);
  ASSERT_EQ(s->bearings.size(), 2u);
  const BearingSpec& c = s->bearings[0];
  EXPECT_EQ(c.id, "cyl");
  EXPECT_EQ(c.type, BearingType::cylindrical);
  EXPECT_EQ(c.rollers.count, 10);
  EXPECT_EQ(c.rollers.pitch_radius, 40.05);
  EXPECT_EQ(c.rib_height, 3);
  EXPECT_EQ(c.outer_raceway, 50.1);
  EXPECT_EQ(c.cage.pocket_clearance, 0.25);
  const BearingSpec& t = s->bearings[1];
  EXPECT_EQ(t.type, BearingType::tapered);
  EXPECT_EQ(t.rollers.top_radius, 9.5);
  EXPECT_NEAR(norm(t.axis), 1.0, 1e-15);  // normalised
  EXPECT_NEAR(t.axis.x, std::sqrt(0.5), 1e-15);
  EXPECT_EQ(t.contact_angle_deg, 20);
}

TEST(BearingAssemblyRead, TheExampleFileReads) {
  Expected<AssemblySpec> s = read_assembly_file(std::string(INTERFERE_SOURCE_DIR) + "/data/examples/bearing_axle.json");
  ASSERT_TRUE(s) << s.error().message();
  EXPECT_EQ(s->bearings.size(), 4u);
}

TEST(BearingAssemblyRead, UnknownKeysWrongTypesMissingFields) {
  EXPECT_HAS(cyl_error("\"web_thickness\": 6", "\"web_thickness\": 6, \"colour\": 1"), "bearings[0].cage.colour: unknown key");
  EXPECT_HAS(error_of(assembly_json("\"frame\": 3,", kCylindricalBearing)), "frame: unknown key");
  EXPECT_HAS(cyl_error("\"count\": 10", "\"count\": \"10\""), "bearings[0].rollers.count: expected an integer, got a string");
  EXPECT_HAS(cyl_error("\"count\": 10", "\"count\": 10.5"), "bearings[0].rollers.count: expected an integer");
  EXPECT_HAS(cyl_error("\"radius\": 10,", "\"radius\": true,"), "bearings[0].rollers.radius: expected a number");
  EXPECT_HAS(cyl_error("\"position\": [0, 0, 0]", "\"position\": [0, 0]"), "bearings[0].position: expected an array of 3");
  EXPECT_HAS(cyl_error("\"pitch_radius\": 40.05, ", ""), "bearings[0].rollers.pitch_radius: missing");
  EXPECT_HAS(cyl_error("\"rib\": {\"height\": 3, \"width\": 4}", "\"rib\": 3"), "bearings[0].inner_ring.rib: expected an object");
  EXPECT_HAS(cyl_error("\"type\": \"cylindrical\"", "\"type\": \"ball\""), "bearings[0].type: expected \"cylindrical\" or \"tapered\"");
  EXPECT_HAS(tap_error("\"top_radius\": 9.5, ", ""), "bearings[0].rollers.top_radius: missing");
  EXPECT_HAS(cyl_error("\"axis\": [0, 0, 1]", "\"axis\": [0, 0, 0]"), "bearings[0].axis: must be a non-zero");
  EXPECT_HAS(error_of("{\"frames\": 3}"), "bearings: missing");
  EXPECT_HAS(error_of("{\"bearings\": []}"), "bearings: no bearings");
  EXPECT_HAS(error_of("[1]"), "expected an object");
  EXPECT_HAS(error_of("{\"bearings\": ["), "axle.json");
  EXPECT_HAS(error_of(assembly_json("\"motion\": {\"load\": {\"direction_deg\": 3}},", kCylindricalBearing)),
             "motion.load.displacement: missing");
  EXPECT_HAS(error_of(assembly_json("\"scar\": {\"depth\": 0.1},", kCylindricalBearing)), "scar.fraction: missing");
  // the file's name in every message
  EXPECT_HAS(cyl_error("\"count\": 10", "\"count\": \"10\""), "axle.json");
}

TEST(BearingAssemblyRead, NonFiniteNumbers) {
  // JSON has no NaN or infinity literals; a number beyond double reads as an error of the parser
  EXPECT_HAS(cyl_error("\"radius\": 10,", "\"radius\": 1e999,"), "axle.json");
  EXPECT_NE(cyl_error("\"radius\": 10,", "\"radius\": 1e999,"), "(no error)");
}

TEST(BearingAssemblyRead, RollersThatDoNotFit) {
  // radially: pitch radius - roller radius below the inner raceway, + roller radius beyond the bore
  EXPECT_HAS(cyl_error("\"pitch_radius\": 40.05", "\"pitch_radius\": 39.9"), "bearings[0].rollers.pitch_radius: the rollers do not fit");
  EXPECT_HAS(cyl_error("\"pitch_radius\": 40.05", "\"pitch_radius\": 40.2"), "exceeds the outer raceway radius");
  // axially between the ribs
  EXPECT_HAS(cyl_error("\"length\": 20", "\"length\": 23"), "bearings[0].rollers.length: the rollers do not fit between the ribs");
  // neighbours overlap: too many rollers for the pitch circle
  EXPECT_HAS(cyl_error("\"count\": 10", "\"count\": 13"), "bearings[0].rollers.count: 13 rollers of radius 10 overlap");
  // a rib above the roller axis cannot guide the end face
  EXPECT_HAS(cyl_error("\"height\": 3,", "\"height\": 10,"), "bearings[0].inner_ring.rib.height");
  EXPECT_HAS(tap_error("\"count\": 12", "\"count\": 20"), "bearings[0].rollers.count");
  EXPECT_HAS(tap_error("\"contact_angle_deg\": 20", "\"contact_angle_deg\": 5"), "bearings[0].contact_angle_deg: must exceed twice");
  EXPECT_HAS(tap_error("\"outer_radius\": 75", "\"outer_radius\": 50"), "bearings[0].cup.outer_radius");
  EXPECT_HAS(tap_error("\"bore_radius\": 25", "\"bore_radius\": 45"), "bearings[0].cone.bore_radius");
  EXPECT_HAS(tap_error("\"top_radius\": 9.5", "\"top_radius\": 7"), "bearings[0].rollers.top_radius");
}

TEST(BearingAssemblyRead, CagePockets) {
  EXPECT_HAS(cyl_error("\"pocket_clearance\": 0.25", "\"pocket_clearance\": -0.1"),
             "bearings[0].cage.pocket_clearance: the cage pocket (width 19.8) is smaller than its roller (diameter 20)");
  EXPECT_HAS(cyl_error("\"pocket_clearance\": 0.25", "\"pocket_clearance\": 3"), "leave no web");
  EXPECT_HAS(cyl_error("\"web_thickness\": 6", "\"web_thickness\": 25"), "bearings[0].cage.web_thickness");
  EXPECT_HAS(cyl_error("\"web_thickness\": 6", "\"web_thickness\": 6, \"width\": 40"), "bearings[0].cage.width");
}

TEST(BearingAssemblyRead, TiltsOutsideEquation1) {
  // Eq. (1) (window.h): alpha < atan(2 min(r, R) / h_b) = atan(20 / 20) = 45 degrees here
  EXPECT_HAS(cyl_error("", "", "\"motion\": {\"max_tilt_deg\": 50},"), "motion.max_tilt_deg: outside Eq. (1)'s validity range");
  EXPECT_EQ(cyl_error("", "", "\"motion\": {\"max_tilt_deg\": 1},"), "(no error)");
  EXPECT_HAS(cyl_error("", "", "\"motion\": {\"max_tilt_deg\": -1},"), "motion.max_tilt_deg");
}

TEST(BearingAssemblyRead, OtherParameters) {
  EXPECT_HAS(cyl_error("", "", "\"frames\": 0,"), "frames: must lie in");
  EXPECT_HAS(cyl_error("", "", "\"clearance\": -1,"), "clearance: must be >= 0");
  EXPECT_HAS(cyl_error("", "", "\"ring_segments\": 4,"), "ring_segments");
  EXPECT_HAS(cyl_error("", "", "\"motion\": {\"pocket_play\": 9},"), "motion.pocket_play");
  EXPECT_HAS(cyl_error("", "", "\"motion\": {\"load\": {\"displacement\": 20}},"), "motion.load.displacement");
  EXPECT_HAS(cyl_error("", "", "\"scar\": {\"fraction\": 2},"), "scar.fraction");
  EXPECT_HAS(cyl_error("", "", "\"scar\": {\"fraction\": 0.5, \"depth\": 50},"), "scar");
  EXPECT_HAS(cyl_error("\"radial_segments\": 24", "\"radial_segments\": 2"), "bearings[0].rollers");
  // two bearings in one place, duplicate ids
  EXPECT_HAS(error_of(assembly_json("", std::string(kCylindricalBearing) + "," +
                                            replace(kCylindricalBearing, "\"id\": \"cyl\"", "\"id\": \"cyl2\""))),
             "bearings[1].position: bearing 'cyl2' overlaps bearing 'cyl'");
  EXPECT_HAS(error_of(assembly_json("", std::string(kCylindricalBearing) + "," +
                                            replace(kCylindricalBearing, "[0, 0, 0]", "[0, 0, 500]"))),
             "bearings[1].id: 'cyl' is used by another bearing");
  EXPECT_HAS(cyl_error("\"id\": \"cyl\"", "\"id\": \"a/b\""), "bearings[0].id");
}

TEST(BearingAssemblyRead, MissingFile) {
  Expected<AssemblySpec> s = read_assembly_file("/nonexistent/axle.json");
  ASSERT_FALSE(s);
  EXPECT_HAS(s.error().message(), "/nonexistent/axle.json");
}

}  // namespace
}  // namespace interfere::bearing
