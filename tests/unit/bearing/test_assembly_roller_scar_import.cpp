// Imported roller scars in bearing assemblies (issue #27, deliverable 2: scars on any part,
// generated or imported; assembly.h, RollerScarImport): the top-level `scar` with `map` (CSV),
// `png` or `points` (text or a scanned mesh) puts the measured scar on every scarred roller,
// resampled onto each bearing's roller grid. Checked on the meshes themselves (each vertex's radial
// deviation against the height written in the file, at map nodes that fall on vertices), on the
// rows (scarred rollers' rows use the scarred solvers), and on bad input (errors naming the JSON
// path, or the file and line).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "assembly_fixture.h"
#include "interfere/bearing/assembly.h"

using namespace interfere;
using namespace interfere::bearing;
using namespace interfere::bearing::test;

namespace {

std::string tmp(const std::string& name) { return ::testing::TempDir() + "/roller_scar_import_" + name; }

void write(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
}

/// The cylindrical bearing's rollers: radius 10, length 20, 24 x 23 cells: vertex columns every
/// 15 degrees, rows every 20/23 mm. A CSV on that grid's columns -30..30 and rows 5..15 mm (nodes
/// at z = j * 20 / 23 for j = 6..17): height 0.04 at (0 deg, row 11), 0.02 beside it, 0 elsewhere.
std::string bump_csv() {
  std::string s = "# a raised bump, 16 x 16 mm\nz\\angle_deg, -30, -15, 0, 15, 30\n";
  for (int j = 6; j <= 17; ++j) {
    char line[160];
    const double z = j * 20.0 / 23;
    const double mid = j == 11 ? 0.04 : (j == 10 || j == 12) ? 0.02 : 0.0;
    const double side = j == 11 ? 0.02 : 0.0;
    std::snprintf(line, sizeof line, "%.17g, 0, %.17g, %.17g, %.17g, 0\n", z, side, mid, side);
    s += line;
  }
  return s;
}

std::string with_scar(const std::string& scar, const char* bearings = kCylindricalBearing) {
  return assembly_json(std::string(R"("frames": 2, "seed": 3, "clearance": 0.05,
       "motion": {"inner_deg_per_frame": 7, "max_tilt_deg": 0.1, "load": {"direction_deg": 270, "displacement": 0.08}},
       "scar": )") + scar + ",",
                       bearings);
}

/// Radial deviation of a body-frame vertex from the intact roller (radius r0 -> r1 over length h).
double deviation(const Vec3& p, double r0, double r1, double h) { return std::hypot(p.x, p.y) - (r0 + (r1 - r0) * p.z / h); }

}  // namespace

TEST(BearingAssemblyRollerScarImport, CsvMapOnEveryScarredRoller) {
  write(tmp("bump.csv"), bump_csv());
  const Expected<AssemblySpec> spec =
      parse_assembly(with_scar(R"({"fraction": 0.5, "map": ")" + tmp("bump.csv") + R"("})"), "a.json");
  ASSERT_TRUE(spec) << spec.error().message();
  const Expected<Assembly> as = build_assembly(*spec);
  ASSERT_TRUE(as) << as.error().message();
  int scarred = 0;
  for (const AssemblyPart& p : as->parts) {
    if (p.kind != PartKind::roller) continue;
    const Roller& r = *p.roller;
    if (!p.scarred) {
      EXPECT_FALSE(r.has_scar);
      continue;
    }
    ++scarred;
    // every node of the map on a vertex: the vertex deviates by the node's height exactly (to
    // rounding); vertices off the map stay intact
    for (int j = 0; j <= r.m(); ++j)
      for (int i = 0; i < r.n(); ++i) {
        const Vec3& v = r.mesh.positions[r.side_vertex(i, j)];
        const int col = i <= 2 ? i : i - r.n();  // columns -30..30 deg = vertex columns -2..2
        double want = 0;
        if (j >= 6 && j <= 17 && col >= -2 && col <= 2) {
          if (col == 0) want = j == 11 ? 0.04 : (j == 10 || j == 12) ? 0.02 : 0.0;
          else if (std::abs(col) == 1 && j == 11) want = 0.02;
        }
        EXPECT_NEAR(deviation(v, 10, 10, 20), want, 1e-12) << p.id << " vertex " << i << ", " << j;
      }
    EXPECT_NEAR(r.raise, 0.04, 1e-12);
    EXPECT_TRUE(r.has_scar);
  }
  EXPECT_EQ(scarred, 5);  // half of the 10 rollers
  // the rows: a scarred roller's rows are measured on its mesh (roller-inner: the scarred solver)
  const AssemblyResult res = run_assembly(*as, generate_motion(*as, 2, as->spec.seed));
  int scarred_inner = 0;
  for (const AssemblyRow& row : res.rows) {
    const AssemblyPair& pair = as->pairs[row.pair];
    if (pair.kind == AssemblyPairKind::roller_inner && as->parts[pair.a].scarred) {
      EXPECT_EQ(row.result.solver, AssemblySolver::scarred);
      ++scarred_inner;
    }
  }
  EXPECT_EQ(scarred_inner, 10);  // 5 scarred rollers x 2 frames
}

TEST(BearingAssemblyRollerScarImport, PointCloudsTextAndScannedMesh) {
  // a pit on the tapered rollers (radius 8 -> 9.5 over 30 mm): points of the worn surface in the
  // roller's body frame, 0.03 deep at (0 deg, z 15), fading to 0 over 4 mm
  std::string xyz = "# scanned pit\n";
  std::string stl = "solid pit\n";
  const auto r_at = [](double z) { return 8 + 1.5 * z / 30; };
  const auto point = [&](double a_deg, double z) {
    const double d = std::hypot(a_deg * std::numbers::pi / 180 * r_at(z), z - 15);
    const double rho = r_at(z) - 0.03 * std::max(0.0, 1 - d / 4);
    const double a = a_deg * std::numbers::pi / 180;
    return Vec3{rho * std::cos(a), rho * std::sin(a), z};
  };
  for (int ia = -30; ia <= 30; ++ia)
    for (int iz = -12; iz <= 12; ++iz) {
      const Vec3 p = point(ia * 0.5, 15 + iz * 0.5);
      char line[128];
      std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", p.x, p.y, p.z);
      xyz += line;
      if (ia < 30 && iz < 12)  // two facets per cell of the scan (the vertices are the points)
        for (const auto& tri : {std::array<Vec3, 3>{p, point((ia + 1) * 0.5, 15 + iz * 0.5), point((ia + 1) * 0.5, 15 + (iz + 1) * 0.5)},
                                std::array<Vec3, 3>{p, point((ia + 1) * 0.5, 15 + (iz + 1) * 0.5), point(ia * 0.5, 15 + (iz + 1) * 0.5)}}) {
          stl += "facet normal 0 0 0\nouter loop\n";
          for (const Vec3& v : tri) {
            std::snprintf(line, sizeof line, "vertex %.17g %.17g %.17g\n", v.x, v.y, v.z);
            stl += line;
          }
          stl += "endloop\nendfacet\n";
        }
    }
  stl += "endsolid pit\n";
  write(tmp("pit.xyz"), xyz);
  write(tmp("pit.stl"), stl);
  for (const char* file : {"pit.xyz", "pit.stl"}) {
    SCOPED_TRACE(file);
    const Expected<AssemblySpec> spec =
        parse_assembly(with_scar(R"({"fraction": 0.25, "points": ")" + tmp(file) + R"("})", kTaperedBearing), "a.json");
    ASSERT_TRUE(spec) << spec.error().message();
    const Expected<Assembly> as = build_assembly(*spec);
    ASSERT_TRUE(as) << as.error().message();
    int scarred = 0;
    for (const AssemblyPart& p : as->parts) {
      if (p.kind != PartKind::roller || !p.scarred) continue;
      ++scarred;
      const Roller& r = *p.roller;
      // the deepest vertex: within the pit, not deeper than the scan, a convex combination of the
      // measured deviations (scar_import.h)
      double deepest = 0;
      for (int j = 0; j <= r.m(); ++j)
        for (int i = 0; i < r.n(); ++i) {
          const Vec3& v = r.mesh.positions[r.side_vertex(i, j)];
          const double dev = deviation(v, 8, 9.5, 30);
          EXPECT_GE(dev, -0.03 - 1e-12);
          EXPECT_LE(dev, 1e-12);
          deepest = std::min(deepest, dev);
        }
      EXPECT_LT(deepest, -0.005);
      EXPECT_LT(r.raise, 1e-12);  // a pit: nothing outward
    }
    EXPECT_EQ(scarred, 3);  // a quarter of 12
    const AssemblyResult res = run_assembly(*as, generate_motion(*as, 1, as->spec.seed));
    int scarred_cone = 0;
    for (const AssemblyRow& row : res.rows) {
      const AssemblyPair& pair = as->pairs[row.pair];
      if (pair.kind == AssemblyPairKind::roller_cone && as->parts[pair.a].scarred) {
        EXPECT_EQ(row.result.solver, AssemblySolver::scarred);
        ++scarred_cone;
      }
    }
    EXPECT_EQ(scarred_cone, 3);
  }
}

TEST(BearingAssemblyRollerScarImport, BadInputNamesThePathOrTheFileAndLine) {
  write(tmp("bump.csv"), bump_csv());
  write(tmp("nan.csv"), "z\\angle_deg, -15, 0, 15\n5, 0, 0, 0\n10, 0, nan, 0\n");
  write(tmp("off.csv"), "z\\angle_deg, -15, 0, 15\n25, 0, 0, 0\n30, 0, 0.01, 0\n");  // beyond the 20 mm rollers
  write(tmp("deep.csv"), "z\\angle_deg, -15, 0, 15\n5, 0, 0, 0\n10, 0, -10.5, 0\n");  // through the axis
  const auto error_of = [](const std::string& scar) -> Error {
    const Expected<AssemblySpec> spec = parse_assembly(with_scar(scar), "a.json");
    if (!spec) return spec.error();
    const Expected<Assembly> as = build_assembly(*spec);
    return as ? Error{.reason = "no error"} : as.error();
  };
  const std::string map = R"("map": ")" + tmp("bump.csv") + R"(")";
  const auto has = [](const Error& e, const std::string& what) {
    EXPECT_NE(e.message().find(what), std::string::npos) << e.message() << "\n  (expected: " << what << ")";
  };
  has(error_of(R"({"fraction": 0.5, )" + map + R"(, "points": "p.xyz"})"), "scar: map, png and points exclude each other");
  has(error_of(R"({"fraction": 0.5, )" + map + R"(, "depth": 0.1})"), "scar.depth: only for a generated scar");
  has(error_of(R"({"fraction": 0.5, )" + map + R"(, "raised": true})"), "scar.raised: only for a generated scar");
  has(error_of(R"({"fraction": 0.5, )" + map + R"(, "scale": 1})"), "scar.scale: unknown key");
  has(error_of(R"({"fraction": 0.5, "png": "a.png"})"), "scar.scale: missing (required)");
  has(error_of(R"({"fraction": 0.5, "png": "a.png", "scale": 0})"), "scar.scale: must be non-zero");
  has(error_of(R"({"fraction": 0.5, "points": "p.xyz", "window": -1})"), "scar.window: must be >= 0");
  has(error_of(R"({"fraction": 0.5, )" + map + R"(, "border": -2})"), "scar.border: must be >= 0");
  has(error_of(R"({"fraction": 0, )" + map + "}"), "scar.fraction: must be > 0 with scar.map");
  has(error_of(R"({"fraction": 0.5, "map": 5})"), "scar.map: expected a string");
  // the files: missing, non-finite, off the rollers, through the axis: the file (and line)
  has(error_of(R"({"fraction": 0.5, "map": "/nonexistent/m.csv"})"), "/nonexistent/m.csv");
  Error e = error_of(R"({"fraction": 0.5, "map": ")" + tmp("nan.csv") + R"("})");
  EXPECT_EQ(e.file, tmp("nan.csv"));
  EXPECT_EQ(e.line, 3);
  e = error_of(R"({"fraction": 0.5, "map": ")" + tmp("off.csv") + R"("})");
  EXPECT_EQ(e.file, tmp("off.csv")) << e.message();
  has(e, "bearings[0]");  // the bearing whose roller grid the map does not fit
  e = error_of(R"({"fraction": 0.5, "map": ")" + tmp("deep.csv") + R"("})");
  EXPECT_EQ(e.file, tmp("deep.csv")) << e.message();
  EXPECT_EQ(e.line, 3) << e.message();
  // a relative path: against the description's folder
  const Expected<AssemblySpec> rel =
      parse_assembly(with_scar(R"({"fraction": 0.5, "map": "roller_scar_import_bump.csv"})"), ::testing::TempDir() + "/a.json");
  ASSERT_TRUE(rel) << rel.error().message();
  EXPECT_TRUE(build_assembly(*rel).has_value());
}
