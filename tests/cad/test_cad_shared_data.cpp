// Extended checks of the CAD pipeline (issue #6) on the public STEP files of ../shared/data/step
// (skipped cleanly when that folder is absent): the import and the AAG's surface types against an
// independent text scan of the Part 21 files (the table of shared/data/SOURCES.md), B-spline
// cylinders recognised exactly like the analytic export of the same assembly, and every part
// simplified with its bolt-connection features locked: budget or a warning, feature triangles
// bit-identical, no self-intersection the tessellation did not have.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "interfere/cad/assembly_clash.h"
#include "interfere/cad/features.h"
#include "interfere/cad/model.h"
#include "interfere/cad/semantics.h"
#include "interfere/simplify/hausdorff.h"
#include "interfere/simplify/qem.h"

namespace interfere::cad {
namespace {

std::filesystem::path shared_step_dir() {
  return std::filesystem::path(INTERFERE_SOURCE_DIR) / ".." / "shared" / "data" / "step";
}

// From shared/data/SOURCES.md ("step/" table, a text scan of each file: B-Rep faces of the unique
// solids and shells, and the surface entities by type). The type counts are of surface entities,
// which several faces may share; they are compared where they add up to the face count.
struct ScanRow {
  const char* file;
  std::size_t faces;
  std::size_t plane, cylinder, cone, sphere, torus, bspline;
};
constexpr ScanRow kScan[] = {
    {"as1-oc-214.stp", 53, 25, 0, 0, 0, 0, 28},
    {"as1_pe_203.stp", 53, 25, 28, 0, 0, 0, 0},
    {"eight_cyl.stp", 24, 16, 8, 0, 0, 0, 0},
    {"gmsh_Angled.step", 69, 45, 24, 0, 0, 0, 0},
    {"gmsh_Block.stp", 533, 90, 65, 32, 4, 8, 2},
    {"gmsh_Kurbelwelle.stp", 58, 12, 13, 6, 0, 0, 0},
    {"gmsh_Zylkopf.stp", 137, 34, 13, 0, 0, 1, 0},
    {"gmsh_part.step", 26, 17, 8, 0, 0, 0, 0},
    {"gmsh_pump_carter_sup.stp", 119, 30, 83, 6, 0, 0, 0},
    {"gmsh_wrenchnut.stp", 36, 0, 0, 0, 0, 0, 36},
    {"nist_ctc_01_asme1_rd.stp", 139, 80, 57, 2, 0, 0, 0},
    {"nist_ctc_02_asme1_rc.stp", 664, 130, 318, 158, 24, 0, 34},
    {"nist_ftc_06_asme1_rd.stp", 144, 71, 58, 4, 5, 6, 0},
    {"nist_ftc_07_asme1_rd.stp", 269, 73, 106, 28, 18, 24, 20},
    {"nist_ftc_08_asme1_rc.stp", 270, 60, 134, 0, 20, 12, 0},
    {"nist_ftc_09_asme1_rd.stp", 158, 62, 88, 8, 0, 0, 0},
    {"nist_ftc_10_asme1_rb.stp", 214, 53, 103, 8, 10, 39, 1},
    {"occt_screw.step", 10, 4, 1, 2, 0, 3, 0},
    {"trimesh_base_interface_AP203.STEP", 30, 8, 22, 0, 0, 0, 0},
    {"trimesh_box_sides.STEP", 310, 289, 21, 0, 0, 0, 0},
    {"trimesh_featuretype.STEP", 96, 49, 46, 0, 0, 0, 1},
};

const CadModel* load_shared(const std::string& file) {
  static std::map<std::string, CadModel> cache;
  auto it = cache.find(file);
  if (it != cache.end()) return &it->second;
  const auto path = shared_step_dir() / file;
  if (!std::filesystem::exists(path)) return nullptr;
  auto m = import_step(path);
  EXPECT_TRUE(m.has_value()) << file << ": " << m.error().message();
  if (!m.has_value()) return nullptr;
  return &(cache[file] = std::move(*m));
}

#define SKIP_WITHOUT_SHARED_DATA()                                                         \
  if (!std::filesystem::is_directory(shared_step_dir())) GTEST_SKIP() << "../shared/data not present"

TEST(SharedStep, FacesAndSurfaceTypesMatchTheFileScan) {
  SKIP_WITHOUT_SHARED_DATA();
  std::size_t checked = 0, typed = 0;
  for (const ScanRow& row : kScan) {
    const CadModel* m = load_shared(row.file);
    if (!m) continue;  // a file the data set no longer ships
    ++checked;
    std::size_t faces = 0;
    std::map<SurfaceType, std::size_t> types;
    for (const Part& p : m->parts) {
      faces += p.faces;
      ASSERT_EQ(p.aag.nodes.size(), p.faces) << row.file << " part " << p.name;
      ASSERT_EQ(p.face_ids.size(), p.mesh.num_triangles()) << row.file;
      for (std::uint32_t f : p.face_ids) ASSERT_LT(f, p.faces) << row.file;
      // Faces recognised from B-spline surfaces count as B-splines in the file's own terms.
      for (const AagNode& n : p.aag.nodes) ++types[n.from_bspline ? SurfaceType::bspline : n.type];
    }
    EXPECT_EQ(faces, row.faces) << row.file;
    if (row.plane + row.cylinder + row.cone + row.sphere + row.torus + row.bspline != row.faces) continue;
    ++typed;
    EXPECT_EQ(types[SurfaceType::plane], row.plane) << row.file;
    EXPECT_EQ(types[SurfaceType::cylinder], row.cylinder) << row.file;
    EXPECT_EQ(types[SurfaceType::cone], row.cone) << row.file;
    EXPECT_EQ(types[SurfaceType::sphere], row.sphere) << row.file;
    EXPECT_EQ(types[SurfaceType::torus], row.torus) << row.file;
    EXPECT_EQ(types[SurfaceType::bspline], row.bspline) << row.file;
  }
  if (checked == 0) GTEST_SKIP() << "none of the scanned STEP files present";
  EXPECT_GT(typed, 0u);
}

// The CAx-IF AS1 assembly exported twice: by Open CASCADE with every cylinder as a B-spline surface
// (as1-oc-214, millimetres) and by another system with analytic cylinders (as1_pe_203, whose
// length unit is the inch: OCCT reads it in millimetres, 25.4 times larger). The recognised
// features must be the same, part by part, radii in proportion.
TEST(SharedStep, BsplineCylindersAreRecognisedLikeTheAnalyticExport) {
  SKIP_WITHOUT_SHARED_DATA();
  const CadModel* oc = load_shared("as1-oc-214.stp");
  const CadModel* pe = load_shared("as1_pe_203.stp");
  if (!oc || !pe) GTEST_SKIP() << "AS1 pair not present";
  EXPECT_EQ(pe->file_length_units, std::vector<std::string>{"INCH"});
  EXPECT_EQ(oc->units, "mm");
  EXPECT_EQ(pe->units, "mm");
  auto lib = default_feature_library();
  ASSERT_TRUE(lib.has_value());
  using Sig = std::multiset<std::pair<std::string, std::vector<long>>>;
  // Per part (keyed by face count, unique in AS1): feature types with radii in 1/1000 mm.
  auto signature = [&](const CadModel& m, double scale) {
    std::map<std::uint32_t, Sig> out;
    for (const Part& p : m.parts) {
      Sig s;
      for (const Feature& f : recognize_features(p.aag, *lib)) {
        std::vector<long> r;
        for (double x : f.radii) r.push_back(std::lround(x * scale * 1000));
        s.insert({f.type, r});
      }
      EXPECT_TRUE(out.emplace(p.faces, s).second) << "two AS1 parts with " << p.faces << " faces";
    }
    return out;
  };
  std::size_t bspline_cylinders = 0;
  for (const Part& p : oc->parts)
    for (const AagNode& n : p.aag.nodes) bspline_cylinders += n.from_bspline && n.type == SurfaceType::cylinder;
  EXPECT_EQ(bspline_cylinders, 28u);
  const auto a = signature(*oc, 1.0), b = signature(*pe, 1.0 / 25.4);
  EXPECT_EQ(a, b);
  std::size_t holes = 0;
  for (const auto& [faces, sig] : a)
    for (const auto& [type, radii] : sig) holes += type == "through_hole";
  EXPECT_EQ(holes, 11u);  // plate 6, l-bracket 4, nut 1
}

/// The triangles on the given faces as corner positions, each rotated to start at its smallest
/// corner (orientation kept): equal sets = bit-identical feature triangles.
std::multiset<std::array<double, 9>> feature_triangles(const TriMesh& m, const std::vector<std::uint32_t>& face_ids,
                                                      const std::vector<std::uint32_t>& faces) {
  std::multiset<std::array<double, 9>> out;
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    if (!std::binary_search(faces.begin(), faces.end(), face_ids[t])) continue;
    std::array<std::array<double, 3>, 3> c;
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = m.positions[m.triangles[t][k]];
      c[k] = {p.x, p.y, p.z};
    }
    const int s = static_cast<int>(std::min_element(c.begin(), c.end()) - c.begin());
    std::array<double, 9> key;
    for (int k = 0; k < 3; ++k) std::copy(c[(s + k) % 3].begin(), c[(s + k) % 3].end(), key.begin() + 3 * k);
    out.insert(key);
  }
  return out;
}

// Every part of every file, simplified to a quarter of its triangles with the bolt-connection
// features of a process step locked.
TEST(SharedStep, MeasuredTessellationDeviation) {
  // Every part's deviation is measured (finite, >= 0) and, with the projections where the
  // same-(u, v) estimate is loose, within a few deflections (the same-(u, v) estimate alone read up
  // to 24 of them on NIST parts at 0.05 mm). gmsh_Block's torus face lies 0.165 mm from its
  // triangles at a deflection of 0.084 mm (OCCT 7.6; BRepExtrema agrees): BRepMesh exceeds its
  // tolerance there, which the measurement must show.
  SKIP_WITHOUT_SHARED_DATA();
  std::size_t checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(shared_step_dir())) {
    auto m = import_step(entry.path(), {.measure_deviation = true, .build_aag = false});
    if (!m) continue;  // (import errors are other tests' business)
    ++checked;
    for (const Part& p : m->parts) {
      EXPECT_TRUE(p.tessellation_deviation >= 0 && std::isfinite(p.tessellation_deviation))
          << entry.path().filename() << " " << p.name;
      EXPECT_LE(p.tessellation_deviation, 5 * p.linear_deflection) << entry.path().filename() << " " << p.name;
    }
    if (entry.path().filename() == "gmsh_Block.stp") {
      ASSERT_EQ(m->parts.size(), 1u);
      EXPECT_GT(m->parts[0].tessellation_deviation, 1.5 * m->parts[0].linear_deflection);
    }
  }
  EXPECT_GT(checked, 0u);
}

TEST(SharedStep, As1AssemblyHasContactsAndNominalFitsOnly) {
  // The CAx-IF AS1 assembly is modelled without interference: bolts and rods sit in holes of their
  // own diameter (B-spline cylinders in this export, recognised), nuts and brackets on plates. On
  // its tessellation such fits cross by up to the chordal errors, on coincident B-Rep faces: every
  // meeting pair is a contact, the fits among them nominal fits.
  // Both exports: B-spline cylinders in millimetres, and analytic ones in inches (placements
  // rounded to a hair's overlap of the seats, which faces coinciding back to back explain).
  std::size_t checked = 0;
  for (const char* file : {"as1-oc-214.stp", "as1_pe_203.stp"}) {
    const CadModel* as1 = load_shared(file);
    if (!as1) continue;
    ++checked;
    const AssemblyClashResult r = assembly_clash(*as1);
    EXPECT_EQ(r.clashes, 0u) << file;
    EXPECT_GT(r.contacts, 0u) << file;
    std::size_t fits = 0;
    for (const InstancePairResult& p : r.pairs) {
      EXPECT_EQ(p.meeting, InstanceMeeting::contact) << file << ": " << as1->instances[p.a].name << " x "
                                                     << as1->instances[p.b].name;
      EXPECT_EQ(p.cross_pairs > 0, p.nominal_fit) << file;
      if (p.nominal_fit) EXPECT_LE(p.depth, p.tessellation_error) << file;
      fits += p.nominal_fit;
    }
    EXPECT_GE(fits, 10u) << file;  // every bolt and rod in its holes
  }
  if (checked == 0) GTEST_SKIP() << "AS1 files not present";
}

TEST(SharedStep, EveryPartSimplifiesWithLockedFeaturesAndNoNewSelfIntersection) {
  SKIP_WITHOUT_SHARED_DATA();
  auto lib = default_feature_library();
  ASSERT_TRUE(lib.has_value());
  auto rules = default_semantic_rules(*lib);
  ASSERT_TRUE(rules.has_value());
  auto process = parse_process(R"({"steps":[{"id":"P1","parts":["*"],"constraint":"bolt"}]})");
  ASSERT_TRUE(process.has_value());
  std::size_t parts = 0, with_features = 0;
  for (const ScanRow& row : kScan) {
    const CadModel* m = load_shared(row.file);
    if (!m) continue;
    for (const Part& p : m->parts) {
      const std::size_t n = p.mesh.num_triangles();
      if (n < 8) continue;
      ++parts;
      const auto feats = recognize_features(p.aag, *lib);
      auto sel = select_assembly_features(*process, "P1", *rules, p.name, feats);
      ASSERT_TRUE(sel.has_value()) << row.file;
      with_features += !sel->faces.empty();
      SimplifyOptions o{.target_triangles = std::max<std::size_t>(1, n / 4), .face_ids = p.face_ids,
                        .feature_faces = sel->faces, .feature_mode = FeatureMode::lock};
      auto r = simplify(p.mesh, o);
      ASSERT_TRUE(r.has_value()) << row.file << " " << p.name << ": " << r.error().message();
      const std::string what = std::string(row.file) + " part " + p.name;
      EXPECT_LE(r->mesh.num_triangles(), n) << what;
      if (r->reached) EXPECT_EQ(r->mesh.num_triangles(), o.target_triangles) << what;
      else EXPECT_FALSE(r->warnings.empty()) << what;
      EXPECT_EQ(r->face_ids.size(), r->mesh.num_triangles()) << what;
      EXPECT_EQ(r->feature_triangles_out, r->feature_triangles_in) << what;
      EXPECT_EQ(feature_triangles(r->mesh, r->face_ids, sel->faces), feature_triangles(p.mesh, p.face_ids, sel->faces))
          << what;
      // Bit-identical triangles; the sampled distance itself is exact only to rounding (slivers).
      if (!sel->faces.empty()) EXPECT_LE(r->hausdorff_features, 1e-9 * r->bbox_diagonal) << what;
      EXPECT_LE(r->hausdorff, 0.25 * r->bbox_diagonal) << what;
      const std::size_t before = count_self_intersections(p.mesh);
      EXPECT_LE(count_self_intersections(r->mesh), before) << what;
    }
  }
  if (parts == 0) GTEST_SKIP() << "no shared STEP part present";
  EXPECT_GT(with_features, 0u);
}

}  // namespace
}  // namespace interfere::cad
