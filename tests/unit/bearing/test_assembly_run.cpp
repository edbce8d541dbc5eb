// Bearing assemblies (issue #27): the per-frame run is deterministic (1 thread and all threads give
// bitwise the same rows), the generated motion is reproducible per frame and bounded by the
// description (tilts within max_tilt in the roller's axial plane, rollers orbiting with the cage),
// and a motion file drives the parts (unknown part ids are errors naming the file and line).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <tbb/global_control.h>

#include "unit/bearing/assembly_fixture.h"
#include "interfere/bearing/assembly.h"

namespace interfere::bearing {
namespace {

constexpr double kPi = std::numbers::pi;

Assembly lively() {
  Expected<AssemblySpec> s = parse_assembly(test::assembly_json(test::kLively, test::both_bearings()), "t.json");
  EXPECT_TRUE(s) << s.error().message();
  Expected<Assembly> a = build_assembly(*s);
  EXPECT_TRUE(a) << a.error().message();
  return *a;
}

bool same(const AssemblyPairResult& a, const AssemblyPairResult& b) {
  return a.distance == b.distance && a.point_a == b.point_a && a.point_b == b.point_b && a.solver == b.solver &&
         a.scar == b.scar && a.exact == b.exact && a.verdict == b.verdict;
}

TEST(BearingAssemblyRun, IdenticalForAnyThreadCount) {
  const Assembly as = lively();
  const AssemblyMotion m = generate_motion(as, 3, 5);
  AssemblyResult one, many;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = run_assembly(as, m);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 4);
    many = run_assembly(as, m);
  }
  ASSERT_EQ(one.rows.size(), as.pairs.size() * 3);
  ASSERT_EQ(one.rows.size(), many.rows.size());
  for (std::size_t i = 0; i < one.rows.size(); ++i) {
    ASSERT_EQ(one.rows[i].frame, many.rows[i].frame);
    ASSERT_EQ(one.rows[i].pair, many.rows[i].pair);
    ASSERT_TRUE(same(one.rows[i].result, many.rows[i].result)) << i;
  }
  EXPECT_EQ(one.worst, many.worst);
  EXPECT_EQ(one.worst_per_frame, many.worst_per_frame);
  EXPECT_EQ(one.verdicts, many.verdicts);
  // the summary is that of the rows
  std::uint64_t clashes = 0;
  double dmin = INFINITY;
  for (const AssemblyRow& r : one.rows) clashes += r.result.verdict == Verdict::clash, dmin = std::min(dmin, r.result.distance);
  EXPECT_EQ(one.verdicts[static_cast<int>(Verdict::clash)], clashes);
  EXPECT_EQ(one.rows[one.worst].result.distance, dmin);
  EXPECT_EQ(one.verdict, Verdict::clash);
  for (std::size_t f = 0; f < 3; ++f) {
    const AssemblyRow& w = one.rows[one.worst_per_frame[f]];
    EXPECT_EQ(w.frame, static_cast<int>(f));
    for (std::size_t p = 0; p < as.pairs.size(); ++p)
      EXPECT_GE(one.rows[f * as.pairs.size() + p].result.distance, w.result.distance);
  }
}

TEST(BearingAssemblyRun, GeneratedMotion) {
  const Assembly as = lively();
  const AssemblyMotion a = generate_motion(as, 4, 5), b = generate_motion(as, 2, 5), c = generate_motion(as, 2, 6);
  EXPECT_EQ(a.poses[1], b.poses[1]);  // frame 1 does not depend on how many frames are made
  EXPECT_NE(a.poses[1], c.poses[1]);  // but on the seed
  const double max_tilt = as.spec.motion.max_tilt_deg * kPi / 180;
  double largest = 0;
  for (const auto& poses : a.poses)
    for (std::size_t i = 0; i < as.parts.size(); ++i) {
      const AssemblyPart& p = as.parts[i];
      EXPECT_TRUE(poses[i].is_rigid());
      if (p.kind != PartKind::roller) continue;
      const BearingSpec& bs = as.spec.bearings[p.bearing];
      const BearingGeometry& g = as.geometry[p.bearing];
      // the axis stays in the roller's axial plane (the plane of the bearing axis and the roller's
      // mid point) and leans from the nominal lean by at most max_tilt
      const Vec3 u = poses[i].rotate({0, 0, 1});
      const Vec3 mid = poses[i].apply({0, 0, 0.5 * bs.rollers.length}) - bs.position;
      const Vec3 radial = mid - bs.axis * dot(mid, bs.axis);
      const Vec3 tangential = cross(bs.axis, radial / norm(radial));
      EXPECT_NEAR(dot(u, tangential), 0, 1e-12);
      const double lean = std::atan2(dot(u, radial / norm(radial)), dot(u, bs.axis));
      EXPECT_LE(std::fabs(lean - g.roller_lean), max_tilt + 1e-12);
      largest = std::max(largest, std::fabs(lean - g.roller_lean));
      // on the pitch circle
      EXPECT_NEAR(norm(radial), g.pitch_radius, 1e-9);
    }
  EXPECT_GT(largest, 0.5 * max_tilt);  // the perturbation is used
}

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

std::string pose_row(int frame, const std::string& id, const Transform& t) {
  std::string s = std::to_string(frame) + "," + id;
  char buf[64];
  for (double v : t.to_row_major()) std::snprintf(buf, sizeof buf, ",%.17g", v), s += buf;
  return s + "\n";
}

TEST(BearingAssemblyRun, MotionFile) {
  const Assembly as = lively();
  const AssemblyMotion gen = generate_motion(as, 2, 5);
  // every part in frame 0; frame 1 moves only the inner ring and roller 3 (the rest keep frame 0's)
  std::string csv = "frame,body,r00,r01,r02,tx,r10,r11,r12,ty,r20,r21,r22,tz\n";
  for (std::size_t i = 0; i < as.parts.size(); ++i) csv += pose_row(0, as.parts[i].id, gen.poses[0][i]);
  csv += pose_row(1, "cyl/inner", gen.poses[1][0]);
  csv += pose_row(1, "cyl/roller3", gen.poses[1][6]);
  Expected<AssemblyMotion> m = read_assembly_motion(as, write_file("asm_motion.csv", csv));
  ASSERT_TRUE(m) << m.error().message();
  ASSERT_EQ(m->poses.size(), 2u);
  EXPECT_EQ(m->poses[0], gen.poses[0]);
  EXPECT_EQ(m->poses[1][0], gen.poses[1][0]);
  EXPECT_EQ(m->poses[1][6], gen.poses[1][6]);
  EXPECT_EQ(m->poses[1][7], gen.poses[0][7]);
  const AssemblyResult r = run_assembly(as, *m), g = run_assembly(as, gen);
  for (std::size_t p = 0; p < as.pairs.size(); ++p) EXPECT_TRUE(same(r.rows[p].result, g.rows[p].result));

  // unknown part: file and line named
  const std::string bad = write_file("asm_bad.csv", "frame,body,r00,r01,r02,tx,r10,r11,r12,ty,r20,r21,r22,tz\n" +
                                                        pose_row(0, "cyl/roller99", gen.poses[0][0]));
  Expected<AssemblyMotion> e = read_assembly_motion(as, bad);
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().message().find("asm_bad.csv:2"), std::string::npos) << e.error().message();
  EXPECT_NE(e.error().message().find("cyl/roller99"), std::string::npos) << e.error().message();
  // a scaled (non-rigid) pose
  Transform scaled = gen.poses[0][0];
  for (auto& row : scaled.r)
    for (double& v : row) v *= 2;
  Expected<AssemblyMotion> s = read_assembly_motion(
      as, write_file("asm_scaled.csv", "frame,body,r00,r01,r02,tx,r10,r11,r12,ty,r20,r21,r22,tz\n" +
                                           pose_row(0, "cyl/inner", scaled)));
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message().find("cyl/inner"), std::string::npos) << s.error().message();
  // a roller tilted beyond Eq. (1)'s validity range (45 degrees for r = 10, R = 30, h_b = 20)
  Transform tilted = gen.poses[0][6];
  const double c = std::cos(50 * kPi / 180), sn = std::sin(50 * kPi / 180);
  const std::array<std::array<double, 3>, 3> rx{{{1, 0, 0}, {0, c, -sn}, {0, sn, c}}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) tilted.r[i][j] = rx[i][j];
  Expected<AssemblyMotion> t = read_assembly_motion(
      as, write_file("asm_tilted.csv", "frame,body,r00,r01,r02,tx,r10,r11,r12,ty,r20,r21,r22,tz\n" +
                                           pose_row(0, "cyl/roller3", tilted)));
  ASSERT_FALSE(t);
  EXPECT_NE(t.error().message().find("cyl/roller3"), std::string::npos) << t.error().message();
  EXPECT_NE(t.error().message().find("Eq. (1)"), std::string::npos) << t.error().message();
}


// Bad numbers and structure in a motion file (issue #27, "Bad input": poses for unknown parts,
// never a NaN in the output): each an error naming the file and line, before any frame is solved.
TEST(BearingAssemblyRun, MotionFileBadInputNamesFileAndLine) {
  const Assembly as = lively();
  const AssemblyMotion gen = generate_motion(as, 1, 5);
  const std::string head = "frame,body,r00,r01,r02,tx,r10,r11,r12,ty,r20,r21,r22,tz\n";
  const std::string good = pose_row(0, "cyl/inner", gen.poses[0][0]);
  const auto error_of = [&](const std::string& name, const std::string& body) {
    Expected<AssemblyMotion> m = read_assembly_motion(as, write_file(name, head + body));
    return m ? std::string("(no error)") : m.error().message();
  };
  std::string nan_row = good;
  nan_row.replace(nan_row.rfind(','), std::string::npos, ",nan\n");  // tz not a number
  std::string inf_row = good;
  inf_row.replace(inf_row.rfind(','), std::string::npos, ",inf\n");
  for (const auto& [name, body] : std::vector<std::pair<std::string, std::string>>{
           {"asm_nan.csv", good + nan_row},
           {"asm_inf.csv", inf_row},
           {"asm_short.csv", "0,cyl/inner,1,0,0\n"},
           {"asm_twice.csv", good + good},
           {"asm_order.csv", pose_row(1, "cyl/inner", gen.poses[0][0]) + good}}) {
    const std::string e = error_of(name, body);
    SCOPED_TRACE(name + ": " + e);
    EXPECT_NE(e, "(no error)");
    EXPECT_NE(e.find(name + ":"), std::string::npos);  // the file and its line
    EXPECT_EQ(e.find("nan)"), std::string::npos);
  }
  // an unknown bearing id, and a missing file
  EXPECT_NE(error_of("asm_other.csv", pose_row(0, "axle/roller0", gen.poses[0][0])).find("asm_other.csv:2"), std::string::npos);
  Expected<AssemblyMotion> missing = read_assembly_motion(as, "/nonexistent/poses.csv");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message().find("/nonexistent/poses.csv"), std::string::npos);
}

}  // namespace
}  // namespace interfere::bearing
