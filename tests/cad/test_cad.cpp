// CAD pipeline (issue #6, items 1-4, 9) on solids generated with OCCT (write_test_part: primitives
// + Booleans written with STEPControl_Writer): STEP import with face ids, AAG against hand-written
// expected graphs, convexity of known edges, B-spline faces recognised as planes/cylinders, each
// library feature recognised on its part and not on near-misses, semantics per process step, and
// feature-preserving simplification of the casing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <tuple>

#include "cad_test_util.h"
#include "interfere/cad/features.h"
#include "interfere/cad/model.h"
#include "interfere/cad/pipeline.h"
#include "interfere/cad/semantics.h"
#include "interfere/simplify/hausdorff.h"
#include "interfere/simplify/qem.h"
#include "../unit/reference_distance.h"  // (tests/unit: the independent triangle distances)

namespace interfere::cad {
namespace {

std::filesystem::path work_dir() { return testing::scratch_dir("interfere_cad_tests"); }

const CadModel& load(TestPart p) {
  static std::map<TestPart, CadModel> cache;
  auto it = cache.find(p);
  if (it != cache.end()) return it->second;
  const auto file = work_dir() / (std::string(test_part_name(p)) + ".step");
  const Status s = write_test_part(p, file);
  EXPECT_TRUE(s.ok()) << s.error().message();
  auto m = import_step(file);
  EXPECT_TRUE(m.has_value()) << m.error().message();
  return cache[p] = m.has_value() ? std::move(*m) : CadModel{};
}

using ArcKey = std::tuple<std::string, std::string, std::string, std::string>;  // types (sorted), curve, convexity
std::multiset<ArcKey> arc_keys(const Aag& g) {
  std::multiset<ArcKey> out;
  for (const AagArc& a : g.arcs) {
    std::string ta = surface_type_name(g.nodes[a.a].type), tb = surface_type_name(g.nodes[a.b].type);
    if (tb < ta) std::swap(ta, tb);
    out.insert({ta, tb, curve_type_name(a.curve), convexity_name(a.convexity)});
  }
  return out;
}
std::multiset<std::string> node_types(const Aag& g) {
  std::multiset<std::string> out;
  for (const AagNode& n : g.nodes) out.insert(surface_type_name(n.type));
  return out;
}

TEST(CadImport, EveryTriangleCarriesItsFaceAndFacesMeetWatertight) {
  const CadModel& m = load(TestPart::box_through_hole);
  ASSERT_EQ(m.parts.size(), 1u);
  ASSERT_EQ(m.instances.size(), 1u);
  const Part& p = m.parts[0];
  EXPECT_EQ(p.solids, 1u);
  ASSERT_EQ(p.face_ids.size(), p.mesh.num_triangles());
  std::set<std::uint32_t> faces(p.face_ids.begin(), p.face_ids.end());
  EXPECT_EQ(faces.size(), p.faces);
  // Vertices are duplicated along face boundaries: no vertex is used by two faces ...
  std::vector<std::int64_t> face_of(p.mesh.num_vertices(), -1);
  for (std::size_t t = 0; t < p.mesh.num_triangles(); ++t)
    for (auto v : p.mesh.triangles[t]) {
      if (face_of[v] >= 0) EXPECT_EQ(face_of[v], p.face_ids[t]);
      face_of[v] = p.face_ids[t];
    }
  // ... but the copies coincide: welded by position the mesh is closed and consistently oriented.
  const TriMesh w = weld_positions(p.mesh);
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const Tri& t : w.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  for (const auto& [e, n] : directed) {
    EXPECT_EQ(n, 1);
    EXPECT_EQ(directed.count({e.second, e.first}), 1u) << "open edge";
  }
  // Outward orientation: positive signed volume = box minus hole.
  double vol = 0;
  for (const Tri& t : w.triangles)
    vol += dot(w.positions[t[0]], cross(w.positions[t[1]], w.positions[t[2]])) / 6;
  EXPECT_NEAR(vol, 40 * 30 * 10 - M_PI * 16 * 10, 0.02 * 12000);
}

TEST(CadImport, WithoutTheAagTheTessellationIsTheSame) {
  // build_aag = false (the mesh commands): the same triangles, face ids and deflection, no graph.
  const CadModel& full = load(TestPart::counterbored_plate);
  auto bare = import_step(work_dir() / "counterbored_plate.step", {.build_aag = false});
  ASSERT_TRUE(bare.has_value()) << bare.error().message();
  ASSERT_EQ(bare->parts.size(), 1u);
  ASSERT_EQ(full.parts.size(), 1u);
  const Part& a = full.parts[0];
  const Part& b = bare->parts[0];
  EXPECT_FALSE(a.aag.nodes.empty());
  EXPECT_TRUE(b.aag.nodes.empty());
  EXPECT_TRUE(b.aag.arcs.empty());
  EXPECT_EQ(a.mesh.positions, b.mesh.positions);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  EXPECT_EQ(a.face_ids, b.face_ids);
  EXPECT_EQ(a.faces, b.faces);
  EXPECT_EQ(a.linear_deflection, b.linear_deflection);
}

TEST(CadImport, MeasuredDeviationMatchesTheHoleGeometry) {
  // box_through_hole: planes and one r = 4 cylinder along z through (20, 15). The deviation at a
  // triangle's centroid and edge midpoints is |4 - their distance to the axis| (0 on the planes):
  // measured from the mesh alone, the oracle.
  const auto file = work_dir() / "box_through_hole.step";
  ASSERT_TRUE(write_test_part(TestPart::box_through_hole, file).ok());
  for (const double lin : {0.05, 0.005}) {
    auto m = import_step(file, {.linear_deflection = lin, .measure_deviation = true});
    ASSERT_TRUE(m.has_value()) << m.error().message();
    const Part& p = m->parts[0];
    double oracle = 0;
    for (std::size_t t = 0; t < p.mesh.num_triangles(); ++t) {
      if (p.aag.nodes[p.face_ids[t]].type != SurfaceType::cylinder) continue;
      const auto c = p.mesh.corners(t);
      for (const Vec3& q : {(c[0] + c[1] + c[2]) / 3.0, (c[0] + c[1]) * 0.5, (c[1] + c[2]) * 0.5, (c[2] + c[0]) * 0.5})
        oracle = std::max(oracle, std::fabs(4 - std::hypot(q.x - 20, q.y - 15)));
    }
    EXPECT_GT(oracle, 0);
    EXPECT_GE(p.tessellation_deviation, oracle * (1 - 1e-9)) << lin;  // each sample an upper estimate
    EXPECT_LE(p.tessellation_deviation, oracle * 1.1) << lin;          // close to it on a cylinder
    EXPECT_LE(p.tessellation_deviation, lin * (1 + 1e-9)) << lin;      // BRepMesh held its tolerance here
  }
  // Not asked for: not measured.
  auto plain = import_step(file);
  ASSERT_TRUE(plain.has_value());
  EXPECT_EQ(plain->parts[0].tessellation_deviation, -1);
}

TEST(CadImport, AssemblyKeepsNamesInstancesAndPlacements) {
  const auto file = work_dir() / "assembly.step";
  const Status s = write_test_assembly(file);
  ASSERT_TRUE(s.ok()) << s.error().message();
  auto m = import_step(file);
  ASSERT_TRUE(m.has_value()) << m.error().message();
  ASSERT_EQ(m->parts.size(), 2u);  // the plate is shared by two instances
  ASSERT_EQ(m->instances.size(), 3u);
  std::map<std::string, const Instance*> by_name;
  for (const Instance& i : m->instances) by_name[i.name] = &i;
  // (OCCT 7.6 reads the identity-placed component's name back as "1": only the moved ones are checked.)
  ASSERT_TRUE(by_name.count("plate_2") && by_name.count("shaft_1"));
  EXPECT_EQ(m->parts[by_name["plate_2"]->part].name, "plate");
  const Instance* plate_1 = nullptr;
  for (const Instance& i : m->instances)
    if (i.part == by_name["plate_2"]->part && i.name != "plate_2") plate_1 = &i;
  ASSERT_NE(plate_1, nullptr);
  EXPECT_TRUE(plate_1->placement.is_identity());
  by_name["plate_1"] = plate_1;
  EXPECT_EQ(m->parts[by_name["shaft_1"]->part].name, "shaft");
  EXPECT_NE(by_name["plate_2"]->path.find("assembly"), std::string::npos);
  // plate_2: rotation by 90 degrees about z, then (0, 0, 20): (1, 0, 0) -> (0, 1, 20).
  const Vec3 q = by_name["plate_2"]->placement.apply({1, 0, 0});
  EXPECT_NEAR(q.x, 0, 1e-12);
  EXPECT_NEAR(q.y, 1, 1e-12);
  EXPECT_NEAR(q.z, 20, 1e-12);
  const Vec3 r = by_name["shaft_1"]->placement.apply({0, 0, 0});
  EXPECT_NEAR(r.x, 100, 1e-12);
  std::vector<std::uint32_t> faces;
  const TriMesh w = world_mesh(*m, &faces);
  const std::size_t plate = m->parts[by_name["plate_1"]->part].mesh.num_triangles();
  const std::size_t shaft = m->parts[by_name["shaft_1"]->part].mesh.num_triangles();
  EXPECT_EQ(w.num_triangles(), 2 * plate + shaft);
  EXPECT_EQ(faces.size(), w.num_triangles());
  EXPECT_EQ(std::set<std::uint32_t>(faces.begin(), faces.end()).size(), 2u * 9u + 5u);  // unique per instance
}

TEST(CadImport, SharedDataAssemblyIfPresent) {
  // Extended check on a real exported assembly (skipped when the shared data set is absent).
  const auto file = std::filesystem::path(INTERFERE_SOURCE_DIR) / ".." / "shared" / "data" / "step" / "as1-oc-214.stp";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "no " << file;
  auto m = import_step(file);
  ASSERT_TRUE(m.has_value()) << m.error().message();
  EXPECT_GT(m->parts.size(), 1u);
  EXPECT_GE(m->instances.size(), m->parts.size());
  for (const Part& p : m->parts) EXPECT_EQ(p.face_ids.size(), p.mesh.num_triangles());
}

TEST(CadImport, NonSolidShapesAreImportedWithAWarningNamingThePart) {
  const CadModel& m = load(TestPart::single_face);
  ASSERT_EQ(m.parts.size(), 1u);
  EXPECT_EQ(m.parts[0].solids, 0u);
  EXPECT_EQ(m.parts[0].faces, 1u);
  EXPECT_GT(m.parts[0].mesh.num_triangles(), 0u);
  ASSERT_FALSE(m.warnings.empty());
  EXPECT_NE(m.warnings[0].find("no solid"), std::string::npos);
  EXPECT_NE(m.warnings[0].find(m.parts[0].name), std::string::npos);
}

TEST(CadImport, BadFilesAreErrors) {
  const auto d = work_dir();
  EXPECT_FALSE(import_step(d / "missing.step").has_value());
  { std::ofstream(d / "empty.step"); }
  auto e = import_step(d / "empty.step");
  ASSERT_FALSE(e.has_value());
  EXPECT_NE(e.error().reason.find("empty"), std::string::npos);
  { std::ofstream(d / "junk.step") << "this is not ISO-10303-21\n"; }
  EXPECT_FALSE(import_step(d / "junk.step").has_value());
}

TEST(Aag, BoxWithThroughHoleMatchesTheHandWrittenGraph) {
  const Aag& g = load(TestPart::box_through_hole).parts[0].aag;
  EXPECT_EQ(node_types(g), (std::multiset<std::string>{"plane", "plane", "plane", "plane", "plane", "plane", "cylinder"}));
  std::multiset<ArcKey> expected;
  for (int i = 0; i < 12; ++i) expected.insert({"plane", "plane", "line", "convex"});
  expected.insert({"cylinder", "plane", "circle", "convex"});
  expected.insert({"cylinder", "plane", "circle", "convex"});
  EXPECT_EQ(arc_keys(g), expected);
  for (const AagNode& n : g.nodes) {
    if (n.type == SurfaceType::cylinder) {
      EXPECT_TRUE(n.hole);
      EXPECT_NEAR(n.radius, 4, 1e-9);
      EXPECT_NEAR(std::abs(n.axis.z), 1, 1e-12);
    }
    if (n.type == SurfaceType::plane && std::abs(n.normal.z) > 0.5) EXPECT_EQ(n.inner_loops, 1u);  // top, bottom
  }
  for (const AagArc& a : g.arcs) {
    if (a.curve == CurveType::line) EXPECT_NEAR(a.angle, M_PI / 2, 1e-9);
    if (a.curve == CurveType::circle) EXPECT_TRUE(a.inner_loop_a || a.inner_loop_b);
  }
}

TEST(Aag, SteppedShaftHasAConcaveShoulderCircle) {
  const Aag& g = load(TestPart::stepped_shaft).parts[0].aag;
  EXPECT_EQ(node_types(g), (std::multiset<std::string>{"plane", "plane", "plane", "cylinder", "cylinder"}));
  const std::multiset<ArcKey> expected{{"cylinder", "plane", "circle", "convex"},
                                       {"cylinder", "plane", "circle", "convex"},
                                       {"cylinder", "plane", "circle", "convex"},
                                       {"cylinder", "plane", "circle", "concave"}};
  EXPECT_EQ(arc_keys(g), expected);
  for (const AagArc& a : g.arcs) {
    if (a.convexity != Convexity::concave) continue;
    const AagNode& cyl = g.nodes[a.a].type == SurfaceType::cylinder ? g.nodes[a.a] : g.nodes[a.b];
    EXPECT_NEAR(cyl.radius, 6, 1e-9);  // the shoulder meets the small cylinder
    EXPECT_FALSE(cyl.hole);
  }
}

TEST(Aag, CounterboredPlateMatchesTheHandWrittenGraph) {
  const Aag& g = load(TestPart::counterbored_plate).parts[0].aag;
  EXPECT_EQ(node_types(g), (std::multiset<std::string>{"plane", "plane", "plane", "plane", "plane", "plane", "plane",
                                                       "cylinder", "cylinder"}));
  std::multiset<ArcKey> expected;
  for (int i = 0; i < 12; ++i) expected.insert({"plane", "plane", "line", "convex"});
  expected.insert({"cylinder", "plane", "circle", "convex"});   // top - counterbore
  expected.insert({"cylinder", "plane", "circle", "concave"});  // counterbore - seat
  expected.insert({"cylinder", "plane", "circle", "convex"});   // seat - bore
  expected.insert({"cylinder", "plane", "circle", "convex"});   // bore - bottom
  EXPECT_EQ(arc_keys(g), expected);
}

TEST(Aag, BsplineFacesAreRecognisedAsPlanesAndCylinders) {
  const Aag& g = load(TestPart::box_through_hole_nurbs).parts[0].aag;
  ASSERT_EQ(g.nodes.size(), 7u);
  int planes = 0, cylinders = 0;
  for (const AagNode& n : g.nodes) {
    EXPECT_TRUE(n.from_bspline);
    planes += n.type == SurfaceType::plane;
    if (n.type == SurfaceType::cylinder) {
      ++cylinders;
      EXPECT_NEAR(n.radius, 4, 1e-3);
      EXPECT_TRUE(n.hole);
      EXPECT_NEAR(std::abs(n.axis.z), 1, 1e-6);
    }
  }
  EXPECT_EQ(planes, 6);
  EXPECT_EQ(cylinders, 1);
}

TEST(Aag, BsplineConesAreRecognisedWithAxisRadiusAndHalfAngle) {
  // The countersunk plate with every face a B-spline: the 90-degree countersink (r 3 -> 6 over a
  // depth of 3, at (20, 15)) is a cone again, and the feature is found as on the analytic part.
  const Aag& g = load(TestPart::countersunk_plate_nurbs).parts[0].aag;
  int cones = 0, cylinders = 0, planes = 0;
  for (const AagNode& n : g.nodes) {
    EXPECT_TRUE(n.from_bspline) << n.face;
    planes += n.type == SurfaceType::plane;
    cylinders += n.type == SurfaceType::cylinder;
    if (n.type != SurfaceType::cone) continue;
    ++cones;
    EXPECT_NEAR(n.half_angle, M_PI / 4, 1e-3);
    EXPECT_NEAR(std::abs(n.axis.z), 1, 1e-6);
    EXPECT_TRUE(n.hole);
    // On the axis x = 20, y = 15; the radius at axis_point follows the 45-degree slope.
    EXPECT_NEAR(n.axis_point.x, 20, 1e-3);
    EXPECT_NEAR(n.axis_point.y, 15, 1e-3);
    EXPECT_GT(n.radius, 3 - 1e-3);
    EXPECT_LT(n.radius, 6 + 1e-3);
  }
  EXPECT_EQ(cones, 1);
  EXPECT_EQ(cylinders, 1);
  EXPECT_EQ(planes, 6);
  // A cylinder is not taken for a cone, nor a plane (the box with a hole, all B-spline).
  for (const AagNode& n : load(TestPart::box_through_hole_nurbs).parts[0].aag.nodes)
    EXPECT_NE(n.type, SurfaceType::cone);
}

std::multiset<std::string> feature_types(TestPart p) {
  auto lib = default_feature_library();
  EXPECT_TRUE(lib.has_value()) << lib.error().message();
  std::multiset<std::string> out;
  for (const Feature& f : recognize_features(load(p).parts[0].aag, *lib)) out.insert(f.type);
  return out;
}

TEST(Features, EachLibraryFeatureOnItsPartAndNotOnNearMisses) {
  EXPECT_EQ(feature_types(TestPart::box_through_hole), (std::multiset<std::string>{"through_hole"}));
  EXPECT_EQ(feature_types(TestPart::box_blind_hole), (std::multiset<std::string>{"blind_hole"}));
  EXPECT_EQ(feature_types(TestPart::countersunk_plate_nurbs), (std::multiset<std::string>{"countersunk_hole"}));
  EXPECT_EQ(feature_types(TestPart::counterbored_plate), (std::multiset<std::string>{"counterbored_hole"}));
  EXPECT_EQ(feature_types(TestPart::countersunk_plate), (std::multiset<std::string>{"countersunk_hole"}));
  EXPECT_EQ(feature_types(TestPart::stepped_shaft), (std::multiset<std::string>{"boss", "boss", "ring_face"}));
  EXPECT_EQ(feature_types(TestPart::slot_block), (std::multiset<std::string>{"slot"}));
  EXPECT_EQ(feature_types(TestPart::step_block), (std::multiset<std::string>{"through_step"}));
  // Exporter variants: every face and edge as B-spline (recognised as planes, cylinders, circles),
  // and the hole split in two half cylinders (merged through their smooth edges).
  EXPECT_EQ(feature_types(TestPart::box_through_hole_nurbs), (std::multiset<std::string>{"through_hole"}));
  EXPECT_EQ(feature_types(TestPart::box_through_hole_split), (std::multiset<std::string>{"through_hole"}));
  // Eccentric counterbore (same topology, axes 2 mm apart): no counterbored hole; the bore is a
  // through hole from the seat to the bottom.
  const auto near = feature_types(TestPart::near_miss_plate);
  EXPECT_EQ(near.count("counterbored_hole"), 0u);
  EXPECT_EQ(near.count("through_hole"), 1u);
}

TEST(Features, SplitHoleReportsBothHalvesInItsRole) {
  auto lib = default_feature_library();
  ASSERT_TRUE(lib.has_value());
  const Aag& g = load(TestPart::box_through_hole_split).parts[0].aag;
  ASSERT_EQ(g.nodes.size(), 8u);  // 6 planes + 2 half cylinders
  const auto f = recognize_features(g, *lib);
  ASSERT_EQ(f.size(), 1u);
  ASSERT_EQ(f[0].role_faces.at("wall").size(), 2u);
  for (auto id : f[0].role_faces.at("wall")) EXPECT_EQ(g.nodes[id].type, SurfaceType::cylinder);
  EXPECT_EQ(f[0].faces.size(), 4u);
}

TEST(Features, CounterboreRolesAxesAndRadii) {
  auto lib = default_feature_library();
  ASSERT_TRUE(lib.has_value());
  const Aag& g = load(TestPart::counterbored_plate).parts[0].aag;
  const auto f = recognize_features(g, *lib);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_NEAR(g.nodes[f[0].roles.at("bore")].radius, 3, 1e-9);
  EXPECT_NEAR(g.nodes[f[0].roles.at("counterbore")].radius, 6, 1e-9);
  EXPECT_EQ(g.nodes[f[0].roles.at("seat")].type, SurfaceType::plane);
  EXPECT_NEAR(f[0].axis_point.x, 20, 1e-9);
  EXPECT_NEAR(f[0].axis_point.y, 15, 1e-9);
  // counterbore, seat, bore, top and (issue #29) the exit face as "bottom".
  EXPECT_EQ(f[0].faces.size(), 5u);
  ASSERT_EQ(f[0].role_faces.at("bottom").size(), 1u);
  EXPECT_EQ(g.nodes[f[0].roles.at("bottom")].type, SurfaceType::plane);
}

TEST(Features, MinimalSubgraphsSplitAtInnerLoopsAndConvexArcs) {
  // Counterbored plate: the only non-inner, non-convex arc joins counterbore and seat.
  const auto groups = minimal_subgraphs(load(TestPart::counterbored_plate).parts[0].aag);
  std::size_t pairs = 0, singles = 0;
  for (const auto& g : groups) (g.size() == 2 ? pairs : singles) += 1;
  EXPECT_EQ(pairs, 1u);
  EXPECT_EQ(singles, 7u);
}

TEST(Features, LibraryErrorsNameTheProblem) {
  EXPECT_FALSE(parse_feature_library("{").has_value());
  auto e = parse_feature_library(R"({"patterns":[{"type":"x","nodes":[{"role":"a","types":["donut"]}]}]})");
  ASSERT_FALSE(e.has_value());
  EXPECT_NE(e.error().reason.find("donut"), std::string::npos);
  auto twice = parse_feature_library(
      R"({"patterns":[{"type":"x","nodes":[{"role":"a","types":["plane"]},{"role":"a","types":["cylinder"]}]}]})");
  ASSERT_FALSE(twice.has_value());
  EXPECT_NE(twice.error().reason.find("role 'a' appears twice"), std::string::npos) << twice.error().reason;
  auto arc = parse_feature_library(
      R"({"patterns":[{"type":"x","nodes":[{"role":"a","types":["plane"]}],"arcs":[{"a":"a","b":"b"}]}]})");
  ASSERT_FALSE(arc.has_value());
  EXPECT_NE(arc.error().reason.find("unknown roles"), std::string::npos) << arc.error().reason;
}

const char* kProcess = R"({"steps":[
  {"id":"P1","parts":["*"],"constraint":"bolt"},
  {"id":"P2","parts":["*"],"constraint":"screw"},
  {"id":"P3","parts":["other"],"constraint":"screw"}]})";

TEST(Semantics, EachStepSelectsItsAssemblyFeaturesOnTheCasing) {
  auto lib = default_feature_library();
  ASSERT_TRUE(lib.has_value());
  auto rules = default_semantic_rules(*lib);
  ASSERT_TRUE(rules.has_value()) << rules.error().message();
  auto process = parse_process(kProcess);
  ASSERT_TRUE(process.has_value());
  const Part& casing = load(TestPart::casing).parts[0];
  const auto feats = recognize_features(casing.aag, *lib);
  std::map<std::string, int> count;
  for (const Feature& f : feats) ++count[f.type];
  EXPECT_EQ(count["counterbored_hole"], 6);
  EXPECT_EQ(count["through_hole"], 7);  // 6 upper bolt holes and the casing's own bore
  auto p1 = select_assembly_features(*process, "P1", *rules, casing.name, feats, &casing.aag);
  auto p2 = select_assembly_features(*process, "P2", *rules, casing.name, feats, &casing.aag);
  auto p3 = select_assembly_features(*process, "P3", *rules, casing.name, feats);
  ASSERT_TRUE(p1.has_value() && p2.has_value() && p3.has_value());
  // P1 bolt connection: the 6 upper bolt-hole walls (r = 6) whole, the upper flange's top and
  // bottom faces within 2 x 6 of each hole's axis (issue #29: the clamped annulus, not the whole
  // faces); the casing's bore r = 88, a through hole too, is skipped with a warning: its flange ring
  // cannot hold a washer of radius 176.
  std::map<int, int> p1_radii;
  for (auto f : p1->faces) {
    const AagNode& n = casing.aag.nodes[f];
    EXPECT_EQ(n.type, SurfaceType::cylinder);
    ++p1_radii[int(std::lround(n.radius))];
  }
  EXPECT_EQ(p1_radii, (std::map<int, int>{{6, 6}}));
  EXPECT_EQ(p1->annuli.size(), 12u);
  std::set<std::uint32_t> planes;
  for (const Annulus& a : p1->annuli) {
    EXPECT_EQ(casing.aag.nodes[a.face].type, SurfaceType::plane);
    EXPECT_NEAR(a.radius, 12.0, 1e-6);
    planes.insert(a.face);
  }
  EXPECT_EQ(planes.size(), 2u);
  // P2 screw tightening: 6 x (bore r=5, counterbore r=9, seat).
  std::map<int, int> radii;
  int seats = 0;
  for (auto f : p2->faces) {
    const AagNode& n = casing.aag.nodes[f];
    if (n.type == SurfaceType::cylinder) ++radii[int(std::lround(n.radius))];
    else ++seats;
  }
  EXPECT_EQ(radii, (std::map<int, int>{{5, 6}, {9, 6}}));
  EXPECT_EQ(seats, 6);
  // ... and the paper's BottomFace (§4, FeatureE = {CounterboredHole, BottomFace}): where each bore
  // leaves the part (here the lower flange's underside), within 2 x 5 of its axis.
  ASSERT_EQ(p2->annuli.size(), 6u);
  for (const Annulus& a : p2->annuli) {
    EXPECT_LT(casing.aag.nodes[a.face].normal.z, -0.99);
    EXPECT_NEAR(a.radius, 10.0, 1e-6);
  }
  EXPECT_TRUE(p3->faces.empty());  // the casing is not in P3
  EXPECT_FALSE(select_assembly_features(*process, "P9", *rules, casing.name, feats).has_value());
}

TEST(Semantics, RulesReferringToUnknownFeatureTypesAreErrors) {
  auto lib = default_feature_library();
  ASSERT_TRUE(lib.has_value());
  auto r = parse_semantic_rules(R"({"rules":[{"name":"weld","constraint":"w","features":[{"type":"weld_seam"}]}]})", *lib);
  ASSERT_FALSE(r.has_value());
  EXPECT_NE(r.error().reason.find("weld_seam"), std::string::npos);
  EXPECT_NE(r.error().reason.find("weld"), std::string::npos);
  EXPECT_FALSE(parse_process(R"({"steps":[{"id":"a","constraint":"x"},{"id":"a","constraint":"y"}]})").has_value());
  EXPECT_FALSE(parse_process(R"({"steps":[{"id":"","constraint":"x"}]})").has_value());
  auto none = parse_process(R"({"steps":[{"id":"P1","parts":[],"constraint":"x"}]})");
  ASSERT_FALSE(none.has_value());
  EXPECT_NE(none.error().reason.find("empty parts list"), std::string::npos);
  auto every = parse_process(R"({"steps":[{"id":"P1","constraint":"x"}]})");  // no list: every part
  ASSERT_TRUE(every.has_value());
  EXPECT_EQ(every->steps[0].parts, std::vector<std::string>{"*"});
  auto all = parse_process(R"({"steps":[{"id":"all","constraint":"x"}]})");  // --step all
  ASSERT_FALSE(all.has_value());
  EXPECT_NE(all.error().reason.find("reserved"), std::string::npos);
  // A misspelt role would drop its faces from every selection: an error naming the roles there are.
  auto role = parse_semantic_rules(
      R"({"rules":[{"name":"screw","constraint":"s","features":[{"type":"counterbored_hole","roles":["bore","sead"]}]}]})",
      *lib);
  ASSERT_FALSE(role.has_value());
  EXPECT_NE(role.error().reason.find("'sead'"), std::string::npos) << role.error().reason;
  EXPECT_NE(role.error().reason.find("'seat'"), std::string::npos);
  EXPECT_TRUE(parse_semantic_rules(
                  R"({"rules":[{"name":"screw","constraint":"s","features":[{"type":"counterbored_hole","roles":["bore","seat"]}]}]})",
                  *lib)
                  .has_value());
  EXPECT_EQ(lib->roles("weld_seam"), std::vector<std::string>{});
  auto empty = parse_semantic_rules(R"({"rules":[{"name":"r","constraint":"c","features":[]}]})", *lib);
  ASSERT_FALSE(empty.has_value());
  EXPECT_NE(empty.error().reason.find("names no feature"), std::string::npos);
  auto twice = parse_semantic_rules(
      R"({"rules":[{"name":"r","constraint":"c","features":[{"type":"slot"}]},
                   {"name":"r","constraint":"d","features":[{"type":"slot"}]}]})",
      *lib);
  ASSERT_FALSE(twice.has_value());
  EXPECT_NE(twice.error().reason.find("appears twice"), std::string::npos);
}

TEST(Semantics, AStepConstraintNoRuleKnowsIsAnError) {
  // A misspelt constraint would select nothing: an error naming the step, the constraint and the
  // constraints the rules know, not an empty selection.
  auto lib = default_feature_library();
  ASSERT_TRUE(lib.has_value());
  auto rules = default_semantic_rules(*lib);
  ASSERT_TRUE(rules.has_value());
  auto p = parse_process(R"({"steps":[{"id":"P1","parts":["*"],"constraint":"bolt"},
                                      {"id":"P2","parts":["*"],"constraint":"blot"}]})");
  ASSERT_TRUE(p.has_value());
  EXPECT_TRUE(select_step_features(*p, "P1", *rules, "casing", {}).has_value());
  for (const auto& sel : {select_step_features(*p, "P2", *rules, "casing", {}),
                          select_assembly_features(*p, "P2", *rules, "casing", {})}) {
    ASSERT_FALSE(sel.has_value());
    EXPECT_NE(sel.error().reason.find("'P2'"), std::string::npos) << sel.error().reason;
    EXPECT_NE(sel.error().reason.find("'blot'"), std::string::npos);
    EXPECT_NE(sel.error().reason.find("'bolt'"), std::string::npos);  // known constraints listed
  }
  // load_semantics checks the step asked for ("all": every step) before any STEP file is read.
  const auto dir = std::filesystem::temp_directory_path() / "interfere_semantics_test";
  std::filesystem::create_directories(dir);
  const auto process_file = (dir / "process.json").string();
  std::ofstream(process_file) << R"({"steps":[{"id":"P1","constraint":"bolt"},{"id":"P2","constraint":"blot"}]})";
  EXPECT_TRUE(load_semantics({.process_file = process_file, .step = "P1"}).has_value());
  for (const std::string step : {"P2", "all", "P9", ""}) {
    auto sem = load_semantics({.process_file = process_file, .step = step});
    ASSERT_FALSE(sem.has_value()) << step;
    EXPECT_EQ(sem.error().file, process_file);
  }
  // Rules without a process select nothing: an error, not ignored.
  auto lone = load_semantics({.rules_file = process_file});
  ASSERT_FALSE(lone.has_value());
  EXPECT_NE(lone.error().reason.find("process"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(Pipeline, FeatureFacesNamedByWorldIdsGoToTheirInstancesParts) {
  // Two parts (3 and 5 faces), four instances: faces 0-2 part 0, 3-7 part 1, 8-12 part 1, 13-15 part 0.
  Prepared prep;
  prep.parts.resize(2);
  prep.parts[0].faces = 3, prep.parts[1].faces = 5;
  prep.parts[1].feature_faces = {2};  // the step's
  prep.instances = {{"a", 0, {}, 0}, {"b", 1, {}, 3}, {"c", 1, {}, 8}, {"d", 0, {}, 13}};
  Prepared unchanged = prep;
  auto bad = add_feature_faces(prep, {4, 16});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().reason.find("16"), std::string::npos);
  EXPECT_NE(bad.error().reason.find("0..15"), std::string::npos) << bad.error().reason;
  EXPECT_EQ(prep.parts[1].feature_faces, unchanged.parts[1].feature_faces);  // nothing changed
  EXPECT_TRUE(prep.parts[0].feature_faces.empty());
  ASSERT_TRUE(add_feature_faces(prep, {4, 14, 10}).ok());
  EXPECT_EQ(prep.parts[0].feature_faces, (std::vector<std::uint32_t>{1}));     // 14 - 13
  EXPECT_EQ(prep.parts[1].feature_faces, (std::vector<std::uint32_t>{1, 2}));  // 4 - 3, 10 - 8 = 2 (the step's)
  // Every instance of each part keeps them: world ids again.
  EXPECT_EQ(prep.feature_faces, (std::vector<std::uint32_t>{1, 4, 5, 9, 10, 14}));
}

TEST(Semantics, StepsNamingPartsNotInTheModelAreWarnings) {
  auto p = parse_process(
      R"({"steps":[{"id":"P1","parts":["casing","casnig"],"constraint":"bolt"},{"id":"P2","parts":["*"],"constraint":"screw"}]})");
  ASSERT_TRUE(p.has_value());
  const auto w = unknown_step_parts(*p, "P1", {"casing", "shaft"});
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("'casnig'"), std::string::npos);
  EXPECT_NE(w[0].find("'P1'"), std::string::npos);
  EXPECT_NE(w[0].find("'shaft'"), std::string::npos);  // the parts there are
  EXPECT_TRUE(unknown_step_parts(*p, "P2", {"casing"}).empty());  // "*"
  EXPECT_TRUE(unknown_step_parts(*p, "P9", {"casing"}).empty());  // unknown steps are errors elsewhere
  EXPECT_TRUE(step_includes(*p, "P1", "casing"));
  EXPECT_FALSE(step_includes(*p, "P1", "shaft"));
  EXPECT_TRUE(step_includes(*p, "P2", "anything"));  // "*"
  EXPECT_FALSE(step_includes(*p, "P9", "casing"));
}

TEST(Semantics, StepFeaturesIgnoreThePartList) {
  auto lib = default_feature_library();
  auto rules = default_semantic_rules(*lib);
  auto process = parse_process(R"({"steps":[{"id":"P1","parts":["other"],"constraint":"screw"}]})");
  ASSERT_TRUE(process.has_value());
  const Part& plate = load(TestPart::counterbored_plate).parts[0];
  const auto feats = recognize_features(plate.aag, *lib);
  auto named = select_assembly_features(*process, "P1", *rules, plate.name, feats);
  auto any = select_step_features(*process, "P1", *rules, plate.name, feats);
  ASSERT_TRUE(named.has_value() && any.has_value());
  EXPECT_TRUE(named->faces.empty());  // the step names another part
  EXPECT_EQ(any->faces.size(), 3u);   // bore, counterbore, seat
  EXPECT_FALSE(select_step_features(*process, "P9", *rules, plate.name, feats).has_value());
}

TEST(CadSimplify, ErrorBoundIsValidAndTightOnACadPart) {
  // The stepped shaft's end faces are fans of long triangles across a disk; halved, the result's
  // end polygons lie inside the input's circles. The bound must cover every point (dense samples,
  // brute force by the independent reference, unit/reference_distance.h: the bound's own
  // measurement uses np::closest_point_on_triangle, issue #23, item 14) and stay within 1.5x of the
  // largest distance found (it was 2.5x with the pairwise cuts alone).
  const Part& shaft = load(TestPart::stepped_shaft).parts[0];
  auto r = simplify(shaft.mesh, {.target_triangles = shaft.mesh.num_triangles() / 2, .face_ids = shaft.face_ids});
  ASSERT_TRUE(r.has_value());
  const OneSidedDistance d = one_sided(shaft.mesh, r->mesh);
  double dense = 0;
  constexpr int kN = 12;
  for (std::size_t t = 0; t < shaft.mesh.num_triangles(); ++t) {
    const auto c = shaft.mesh.corners(t);
    for (int i = 0; i <= kN; ++i)
      for (int j = 0; i + j <= kN; ++j) {
        const Vec3 p = c[0] + (c[1] - c[0]) * (double(i) / kN) + (c[2] - c[0]) * (double(j) / kN);
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t u = 0; u < r->mesh.num_triangles(); ++u)
          best = std::min(best, reference::point_triangle_distance(p, r->mesh.corners(u)));
        dense = std::max(dense, best);
      }
  }
  EXPECT_GT(dense, 0);
  EXPECT_GE(d.bound, dense);
  EXPECT_LE(d.bound, 1.5 * dense);
  EXPECT_GE(r->error_bound, d.bound);
}

TEST(CadSimplify, CasingToBudgetWithLockedScrewFeaturesBitIdentical) {
  auto lib = default_feature_library();
  auto rules = default_semantic_rules(*lib);
  auto process = parse_process(kProcess);
  const Part& casing = load(TestPart::casing).parts[0];
  const auto feats = recognize_features(casing.aag, *lib);
  auto sel = select_assembly_features(*process, "P2", *rules, casing.name, feats);
  ASSERT_TRUE(sel.has_value());
  const std::size_t n = casing.mesh.num_triangles();
  std::vector<std::uint32_t> sorted = sel->faces;
  std::size_t feature_tris = 0;
  for (auto f : casing.face_ids) feature_tris += std::binary_search(sorted.begin(), sorted.end(), f);
  ASSERT_GT(feature_tris, 0u);
  const std::size_t target = (feature_tris + (n - feature_tris) / 2) & ~std::size_t{1};  // even: closed mesh
  for (FeatureMode mode : {FeatureMode::lock, FeatureMode::weight}) {
    auto r = simplify(casing.mesh, {.target_triangles = target, .face_ids = casing.face_ids,
                                    .feature_faces = sel->faces, .feature_mode = mode});
    ASSERT_TRUE(r.has_value()) << r.error().message();
    EXPECT_EQ(r->mesh.num_triangles(), target) << "mode " << int(mode);
    EXPECT_LE(r->hausdorff_features, 1e-6 * r->bbox_diagonal);
    if (mode == FeatureMode::lock) EXPECT_EQ(r->feature_triangles_out, r->feature_triangles_in);
    EXPECT_EQ(count_self_intersections(r->mesh), 0u);
  }
  // Far beyond what the locks allow, the rest of the casing collapses as far as it can: large
  // errors, but still no self-intersection (plain QEM created some here before the guard existed).
  auto deep = simplify(casing.mesh, {.target_triangles = n / 4, .face_ids = casing.face_ids,
                                     .feature_faces = sel->faces, .feature_mode = FeatureMode::lock});
  ASSERT_TRUE(deep.has_value());
  EXPECT_FALSE(deep->reached);
  EXPECT_EQ(count_self_intersections(deep->mesh), 0u);
  EXPECT_LE(deep->hausdorff_features, 1e-12);
  // The per-collapse guard alone (no plain run first) also leaves none.
  SimplifyOptions guarded{.target_triangles = n / 4, .face_ids = casing.face_ids, .feature_faces = sel->faces,
                          .feature_mode = FeatureMode::lock};
  guarded.guard_every_collapse = true;
  auto g = simplify(casing.mesh, guarded);
  ASSERT_TRUE(g.has_value());
  EXPECT_EQ(count_self_intersections(g->mesh), 0u);
  EXPECT_FALSE(g->guard_rerun);
}

}  // namespace
}  // namespace interfere::cad
