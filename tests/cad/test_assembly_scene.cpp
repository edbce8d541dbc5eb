// cad::assembly_scene and cad::nominal_fit_check (issue #24, item 1): a STEP assembly expands to
// one body per instance (names, product paths, poses, B-Rep face ids, meshes shared per part), and
// the nominal fit of assembly-clash is found on the scene's bodies, also when a frame moves them.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "cad_test_util.h"
#include "interfere/cad/assembly_clash.h"
#include "interfere/cad/assembly_scene.h"
#include "interfere/cad/model.h"
#include "interfere/mesh/validate.h"
#include "interfere/query/clash.h"
#include "interfere/query/depth.h"

namespace interfere::cad {
namespace {

std::filesystem::path dir() {
  return testing::scratch_dir("interfere_assembly_scene");
}

TEST(AssemblyScene, BodiesAreTheInstances) {
  const auto file = dir() / "ap203.step";
  ASSERT_TRUE(write_test_assembly_ap203(file).ok());
  auto m = import_step(file);
  ASSERT_TRUE(m.has_value()) << m.error().message();
  const scene::Scene s = assembly_scene(*m);
  ASSERT_NO_THROW(s.validate());
  ASSERT_EQ(s.bodies.size(), m->instances.size());
  ASSERT_EQ(s.bodies.size(), 3u);
  EXPECT_EQ(s.units, "mm");
  std::set<std::string> ids, paths;
  std::multiset<std::string> names;
  std::set<const TriMesh*> meshes;
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const scene::Body& b = s.bodies[i];
    const Instance& in = m->instances[i];
    const Part& part = m->parts[in.part];
    names.insert(b.name);
    paths.insert(b.path);
    ids.insert(b.id);
    meshes.insert(b.mesh.get());
    EXPECT_EQ(b.id, b.path);  // (the generated paths need no replacement characters)
    EXPECT_EQ(b.source.kind, scene::SourceKind::step_instance);
    EXPECT_EQ(b.source.file, file.string());
    EXPECT_EQ(b.source.detail, in.path);
    EXPECT_EQ(b.unit, "mm");
    EXPECT_EQ(b.pose, in.placement);
    EXPECT_EQ(b.tessellation_error, part.tessellation_error());
    EXPECT_GT(b.tessellation_error, 0);
    ASSERT_EQ(b.source_id_kind, scene::SourceIdKind::brep_face);
    ASSERT_TRUE(b.source_ids);
    ASSERT_EQ(b.mesh->num_triangles(), part.mesh.num_triangles());
    // Welded (closed solids), same triangles in the same order: each body triangle's corners are
    // the part's, and its source id the 1-based B-Rep face.
    EXPECT_TRUE(mesh_stats(*b.mesh).closed()) << b.path;
    std::set<std::int64_t> faces;
    for (std::uint32_t t = 0; t < part.mesh.num_triangles(); ++t) {
      ASSERT_EQ(b.mesh->corners(t), part.mesh.corners(t)) << t;
      ASSERT_EQ(b.source_id(t), std::int64_t{part.face_ids[t]} + 1) << t;
      faces.insert(b.source_id(t));
    }
    EXPECT_EQ(*faces.begin(), 1);
    EXPECT_EQ(static_cast<std::uint32_t>(*faces.rbegin()), part.faces);
  }
  EXPECT_EQ(names, (std::multiset<std::string>{"PLATE", "ROD", "ROD"}));
  EXPECT_EQ(paths, (std::set<std::string>{"/ASM/PLATE", "/ASM/ROD", "/ASM/ROD#2"}));
  EXPECT_EQ(ids.size(), 3u);
  EXPECT_EQ(meshes.size(), 2u);  // the rods share one mesh
  // Placements: the rods at x = +-100 (the generator's), the plate at the identity.
  for (const scene::Body& b : s.bodies)
    EXPECT_NEAR(b.pose.apply({0, 0, 0}).x,
                b.name == "PLATE" ? 0.0 : (b.path == "/ASM/ROD" ? 100.0 : -100.0), 1e-9)
        << b.path;
}

TEST(AssemblyScene, IdsOfLikeNamedPathsAreMadeUnique) {
  CadModel m;
  Part p;
  p.mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  p.mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  p.face_ids = {0, 1, 2, 3};
  m.parts = {p};
  m.instances = {{.name = "a b", .part = 0, .placement = {}, .path = "/A/a b"},
                 {.name = "a_b", .part = 0, .placement = {}, .path = "/A/a_b"}};
  const scene::Scene s = assembly_scene(m);
  ASSERT_EQ(s.bodies.size(), 2u);
  EXPECT_EQ(s.bodies[0].id, "/A/a_b");
  EXPECT_EQ(s.bodies[1].id, "/A/a_b#2");
  EXPECT_EQ(s.bodies[0].mesh, s.bodies[1].mesh);
  EXPECT_NO_THROW(s.validate());
}

Part load_part(TestPart which) {
  const auto file = dir() / (std::string(test_part_name(which)) + ".step");
  EXPECT_TRUE(write_test_part(which, file).ok());
  auto m = import_step(file);
  EXPECT_TRUE(m.has_value()) << m.error().message();
  return m->parts.at(0);
}

// The world model the engine builds for a body at pose `t`, and the sampled depth of a crossing.
Model world(const scene::Body& b, const Transform& t) {
  return make_model(transformed(*b.mesh, t));
}
double depth(const Model& a, const Model& b, const ClashResult& r) {
  std::vector<char> pa(a.mesh.num_triangles(), 0), pb(b.mesh.num_triangles(), 0);
  for (const TrianglePair& q : r.pairs) pa[q.a] = 1, pb[q.b] = 1;
  return std::max(
      interfere::detail::depth_into(a, b, pa, interfere::detail::untouched_sides(a, b, pa)),
      interfere::detail::depth_into(b, a, pb, interfere::detail::untouched_sides(b, a, pb)));
}

TEST(AssemblyScene, NominalFitCheckOnSceneBodies) {
  // A shaft seated in a counterbore of its own radius (test_assembly_fit.cpp): a nominal fit on
  // the axis, a clash 0.3 mm off it; the same when a frame moves both bodies together (the
  // placement is then recovered from the world models), and never a fit for a mirrored frame.
  CadModel m;
  m.parts = {load_part(TestPart::counterbored_plate), load_part(TestPart::stepped_shaft)};
  Transform flipped;
  flipped.r = {{{1, 0, 0}, {0, -1, 0}, {0, 0, -1}}};
  Transform motion;  // 90 degrees about z, then (5, -7, 11)
  motion.r = {{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}};
  motion.t = {5, -7, 11};
  Transform mirror;
  mirror.r = {{{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  for (double off : {0.0, 0.3}) {
    flipped.t = {20 + off, 15, 61};
    m.instances = {{.name = "plate", .part = 0, .placement = Transform{}, .path = "/plate"},
                   {.name = "shaft", .part = 1, .placement = flipped, .path = "/shaft"}};
    const AssemblyClashResult old = assembly_clash(m);
    ASSERT_EQ(old.pairs.size(), 1u);
    const scene::Scene s = assembly_scene(m);
    const auto fit = nominal_fit_check(m, s);
    ASSERT_TRUE(fit);
    for (const Transform* moved : std::vector<const Transform*>{nullptr, &motion, &mirror}) {
      const auto at = [&](const scene::Body& b) {
        return moved ? scene::compose(*moved, b.pose) : b.pose;
      };
      const Model wa = world(s.bodies[0], at(s.bodies[0])),
                  wb = world(s.bodies[1], at(s.bodies[1]));
      const ClashResult r = clash(wa, wb, {});
      ASSERT_GT(r.cross_pairs, 0u);
      const double d = depth(wa, wb, r);
      const bool expected = off == 0 && moved != &mirror;
      EXPECT_EQ(fit(0, 1, wa, wb, r, d), expected) << "off " << off
                                                   << (moved == &motion ? " moved"
                                                       : moved          ? " mirrored"
                                                                        : "");
      if (!moved) {
        EXPECT_EQ(old.pairs[0].nominal_fit, expected) << "off " << off;  // assembly-clash agrees
      }
    }
  }
}

TEST(AssemblyScene, NominalFitCheckIgnoresBodiesOfOtherSources) {
  CadModel m;
  m.parts = {load_part(TestPart::counterbored_plate), load_part(TestPart::stepped_shaft)};
  Transform flipped;
  flipped.r = {{{1, 0, 0}, {0, -1, 0}, {0, 0, -1}}};
  flipped.t = {20, 15, 61};
  m.instances = {{.name = "plate", .part = 0, .placement = Transform{}, .path = "/plate"},
                 {.name = "shaft", .part = 1, .placement = flipped, .path = "/shaft"}};
  scene::Scene s = assembly_scene(m);
  s.bodies[1].source.kind = scene::SourceKind::mesh_file;  // the same geometry from a mesh file
  const auto fit = nominal_fit_check(m, s);
  const Model wa = world(s.bodies[0], s.bodies[0].pose), wb = world(s.bodies[1], s.bodies[1].pose);
  const ClashResult r = clash(wa, wb, {});
  EXPECT_FALSE(fit(0, 1, wa, wb, r, depth(wa, wb, r)));
  EXPECT_FALSE(fit(0, 7, wa, wb, r, 0));  // out of range
}

}  // namespace
}  // namespace interfere::cad
