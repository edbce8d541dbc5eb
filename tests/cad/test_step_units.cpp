// STEP files whose own length unit is not the millimetre (issue #23, item 6: units per input): the
// importer gives every length in mm whatever the file declares, and names what it declares
// (CadModel::file_length_units). Two kinds of file: written by OCCT's STEPControl_Writer in inches
// and in metres (write_test_part with write.step.unit: the 40 x 30 x 10 mm counterbored plate's
// coordinates converted to the file's unit, 40 mm = 1.5748... in), and the plate's mm file with its
// length unit rewritten to the metre, the numbers kept (a 40 m plate: 40000 mm). The checks are the
// geometry itself: bounding box, enclosed volume of the tessellation (divergence theorem, here) and
// the counterbore's radii and axis, against the mm file and the scale the unit implies.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cad_test_util.h"
#include "interfere/cad/features.h"
#include "interfere/cad/model.h"

namespace interfere::cad {
namespace {

std::filesystem::path work_dir() {
  return testing::scratch_dir("interfere_cad_step_units");
}

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Volume enclosed by a closed, outward mesh: the sum of the signed tetrahedra from the origin.
double enclosed_volume(const TriMesh& m) {
  double v = 0;
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    const auto c = m.corners(t);
    v += dot(c[0], cross(c[1], c[2])) / 6;
  }
  return v;
}

struct Measured {
  Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  double volume = 0;
  std::vector<double> radii;  ///< the counterbored hole's, sorted
  Vec3 axis_point;
  std::vector<std::string> file_units;
  std::string units;
};

Measured measure(const std::filesystem::path& file) {
  Measured r;
  auto m = import_step(file);
  EXPECT_TRUE(m.has_value()) << m.error().message();
  if (!m.has_value() || m->parts.size() != 1) {
    ADD_FAILURE() << file << ": expected one part";
    return r;
  }
  const TriMesh mesh = world_mesh(*m);
  for (const Vec3& p : mesh.positions)
    for (int k = 0; k < 3; ++k)
      r.lo[k] = std::min(r.lo[k], p[k]), r.hi[k] = std::max(r.hi[k], p[k]);
  r.volume = enclosed_volume(mesh);
  auto lib = default_feature_library();
  EXPECT_TRUE(lib.has_value());
  if (lib.has_value())
    for (const Feature& f : recognize_features(m->parts[0].aag, *lib))
      if (f.type == "counterbored_hole") r.radii = f.radii, r.axis_point = f.axis_point;
  std::sort(r.radii.begin(), r.radii.end());
  r.file_units = m->file_length_units;
  r.units = m->units;
  return r;
}

// The plate measured from `file` is the mm plate scaled by `scale`.
void expect_scaled(const Measured& got, const Measured& mm, double scale, const std::string& what) {
  const double tol = 1e-9 * 40 * scale;
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(got.lo[k], mm.lo[k] * scale, tol) << what << " axis " << k;
    EXPECT_NEAR(got.hi[k], mm.hi[k] * scale, tol) << what << " axis " << k;
  }
  // The tessellation's chords depend on the deflection (0.1 % of the diagonal: the same relative
  // sag at every scale); its volume within 1e-6 of the mm file's, scaled.
  EXPECT_NEAR(got.volume, mm.volume * scale * scale * scale,
              1e-6 * mm.volume * scale * scale * scale)
      << what;
  ASSERT_EQ(got.radii.size(), 2u) << what << ": counterbored hole not recognised";
  EXPECT_NEAR(got.radii[0], 3 * scale, 1e-6 * scale) << what;
  EXPECT_NEAR(got.radii[1], 6 * scale, 1e-6 * scale) << what;
  EXPECT_NEAR(got.axis_point.x, 20 * scale, 1e-6 * scale) << what;
  EXPECT_NEAR(got.axis_point.y, 15 * scale, 1e-6 * scale) << what;
  EXPECT_EQ(got.units, "mm") << what;
}

Measured mm_plate() {
  const auto file = work_dir() / "plate_mm.step";
  EXPECT_TRUE(write_test_part(TestPart::counterbored_plate, file).ok());
  Measured mm = measure(file);
  EXPECT_EQ(mm.file_units, std::vector<std::string>{"millimetre"});
  EXPECT_NEAR(mm.hi.x - mm.lo.x, 40, 1e-9);
  EXPECT_NEAR(mm.hi.z - mm.lo.z, 10, 1e-9);
  EXPECT_EQ(mm.radii, (std::vector<double>{3, 6}));
  return mm;
}

// OCCT writes the same solid in inches and in metres: the file's numbers are in that unit, the
// import gives the plate in mm again.
TEST(StepUnits, FilesWrittenInInchesAndMetresAreReadInMillimetres) {
  const Measured mm = mm_plate();
  struct Case {
    const char* unit;
    const char* declared;     ///< CadModel::file_length_units
    const char* unit_entity;  ///< the file's length unit
    const char* in_file;      ///< the plate's 40 mm length as the file writes it
  };
  for (const Case& c :
       {Case{"INCH", "INCH", "CONVERSION_BASED_UNIT('INCH'", "1.574803149606"},
        Case{"M", "metre", "( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT($,.METRE.) )", "4.E-02"}}) {
    const auto file = work_dir() / (std::string("plate_") + c.unit + ".step");
    const Status s = write_test_part(TestPart::counterbored_plate, file, c.unit);
    ASSERT_TRUE(s.ok()) << s.error().message();
    const std::string text = read_text(file);
    EXPECT_NE(text.find(c.unit_entity), std::string::npos)
        << c.unit << ": declared as " << c.unit_entity;
    EXPECT_NE(text.find(c.in_file), std::string::npos)
        << c.unit << ": 40 mm written as " << c.in_file;
    const Measured got = measure(file);
    EXPECT_EQ(got.file_units, std::vector<std::string>{c.declared}) << c.unit;
    expect_scaled(got, mm, 1.0, c.unit);
  }
  // The process-wide writer setting is restored: the next file is in mm again.
  const auto again = work_dir() / "plate_mm_again.step";
  ASSERT_TRUE(write_test_part(TestPart::counterbored_plate, again).ok());
  EXPECT_NE(read_text(again).find(".MILLI.,.METRE."), std::string::npos);
  EXPECT_FALSE(
      write_test_part(TestPart::counterbored_plate, work_dir() / "bad.step", "FURLONG").ok());
}

// The mm file with its length unit declared as the metre (numbers unchanged): a 40 m plate, read
// as 40000 mm; every length scaled by 1000.
TEST(StepUnits, FileInMetresIsConvertedToMillimetres) {
  const Measured mm = mm_plate();
  std::string text = read_text(work_dir() / "plate_mm.step");
  const std::string from = "( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) )";
  const std::size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos);
  ASSERT_EQ(text.find(from, at + 1), std::string::npos);  // the one length unit
  text.replace(at, from.size(), "( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT($,.METRE.) )");
  const auto file = work_dir() / "plate_40m.step";
  std::ofstream(file, std::ios::binary) << text;
  const Measured got = measure(file);
  EXPECT_EQ(got.file_units, std::vector<std::string>{"metre"});
  EXPECT_NEAR(got.hi.x - got.lo.x, 40000, 1e-6);
  expect_scaled(got, mm, 1000.0, "metre");
}

}  // namespace
}  // namespace interfere::cad
