// Faces meshed as angular sectors (issue #29, src/cad/sector_split.cpp): the casing's working-ring
// wall (a closed surface of revolution with counterbore rims as inner wires) is divided between its
// rims before BRepMesh, the sectors triangulated by OCCT's Delabella, and their triangles carry the
// wall's face id. Checked against the
// B-Rep and against the unsplit import, with oracles of their own: the mesh welded by exact
// coordinates (a map, not the library's weld) has every edge in exactly two triangles, once each
// way (closed and consistently oriented), the same Euler characteristic as the unsplit mesh; each
// face's triangle area matches the B-Rep face's area (BRepGProp in the AAG, not the tessellation);
// parts without a qualifying face are tessellated exactly as before; one thread and many give the
// same triangles bit for bit.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <array>
#include <cstdlib>
#include <cmath>
#include <filesystem>
#include <map>
#include <utility>
#include <vector>

#include "cad_test_util.h"
#include "interfere/cad/model.h"

namespace interfere::cad {
namespace {

constexpr double kCasingDeflection = 0.01696;  // data/examples/README.md: the paper's 35,548 case

std::filesystem::path casing_file() {
  return std::filesystem::path(INTERFERE_SOURCE_DIR) / "data" / "examples" / "casing.step";
}

Part import_casing(bool split) {
  auto m = import_step(casing_file(), {.linear_deflection = kCasingDeflection, .sector_split = split});
  EXPECT_TRUE(m.has_value()) << (m ? "" : m.error().message());
  return m ? m->parts.at(0) : Part{};
}

struct Closure {
  std::size_t vertices = 0, edges = 0, open_or_nonmanifold = 0, misoriented = 0;
};

// Welds by exact coordinates and counts directed edges.
Closure closure(const TriMesh& mesh) {
  std::map<std::array<double, 3>, std::size_t> id;
  std::vector<std::size_t> w(mesh.positions.size());
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const auto& p = mesh.positions[i];
    w[i] = id.emplace(std::array<double, 3>{p.x, p.y, p.z}, id.size()).first->second;
  }
  std::map<std::pair<std::size_t, std::size_t>, int> directed;
  for (const auto& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) ++directed[{w[t[e]], w[t[(e + 1) % 3]]}];
  Closure c;
  c.vertices = id.size();
  std::map<std::pair<std::size_t, std::size_t>, int> undirected;
  for (const auto& [e, n] : directed) {
    if (n != 1) ++c.misoriented;
    undirected[{std::min(e.first, e.second), std::max(e.first, e.second)}] += n;
  }
  c.edges = undirected.size();
  for (const auto& [e, n] : undirected)
    if (n != 2) ++c.open_or_nonmanifold;
  return c;
}

double triangle_area(const TriMesh& m, std::size_t t) {
  const auto& a = m.positions[m.triangles[t][0]];
  const auto& b = m.positions[m.triangles[t][1]];
  const auto& c = m.positions[m.triangles[t][2]];
  const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z, vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
  const double x = uy * vz - uz * vy, y = uz * vx - ux * vz, z = ux * vy - uy * vx;
  return 0.5 * std::sqrt(x * x + y * y + z * z);
}

TEST(SectorSplit, CasingWallSectorsAreClosedAndKeepTheFaceIds) {
  const Part on = import_casing(true), off = import_casing(false);
  ASSERT_EQ(on.faces, off.faces);
  ASSERT_EQ(on.aag.nodes.size(), on.faces);
  EXPECT_TRUE(on.untessellated_faces.empty());
  // The README's count (the paper's 35,548 case) with sectors; 40,430 unsplit at this deflection.
  EXPECT_EQ(on.mesh.num_triangles(), 35556u);
  EXPECT_LT(on.mesh.num_triangles(), off.mesh.num_triangles());
  const Closure a = closure(on.mesh), b = closure(off.mesh);
  EXPECT_EQ(a.open_or_nonmanifold, 0u);
  EXPECT_EQ(a.misoriented, 0u);
  EXPECT_EQ(b.open_or_nonmanifold, 0u);
  // Same topology: V - E + F of the welded meshes (a sector seam left open or a rim doubled would change it).
  EXPECT_EQ(static_cast<long>(a.vertices) - static_cast<long>(a.edges) + static_cast<long>(on.mesh.num_triangles()),
            static_cast<long>(b.vertices) - static_cast<long>(b.edges) + static_cast<long>(off.mesh.num_triangles()));
  // Per face: triangles present, area within 0.5 % of the B-Rep face's; the wall's triangles change,
  // the other faces' by a few triangles at most (the split lines cross the wall's two circle edges,
  // whose neighbours then hold them in two pieces; the rims' edges are discretised on the sectors'
  // surfaces; ShapeUpgrade copies the wall's vertices: at this deflection faces 0, 1, 16 and the
  // flange faces at the circles differ by 1-2 triangles).
  std::vector<double> area_on(on.faces, 0.0);
  std::vector<std::size_t> count_on(on.faces, 0), count_off(off.faces, 0);
  for (std::size_t t = 0; t < on.face_ids.size(); ++t) area_on[on.face_ids[t]] += triangle_area(on.mesh, t), ++count_on[on.face_ids[t]];
  for (const std::uint32_t f : off.face_ids) ++count_off[f];
  std::uint32_t wall = 0;
  for (std::uint32_t f = 0; f < off.faces; ++f)
    if (count_off[f] > count_off[wall]) wall = f;
  for (std::uint32_t f = 0; f < on.faces; ++f) {
    EXPECT_GT(count_on[f], 0u) << "face " << f;
    EXPECT_NEAR(area_on[f], on.aag.nodes[f].area, 5e-3 * on.aag.nodes[f].area) << "face " << f;
    if (f != wall) EXPECT_LE(std::abs(static_cast<long>(count_on[f]) - static_cast<long>(count_off[f])), 8) << "face " << f;
  }
  EXPECT_NE(count_on[wall], count_off[wall]);
  EXPECT_EQ(on.aag.nodes[wall].inner_loops, 5u);  // (the sixth rim crosses the seam: part of the outer wire)
  // Within the deflection as measured (tessellation_deviation.cpp), as the unsplit mesh is.
  auto measured = import_step(casing_file(), {.linear_deflection = kCasingDeflection, .measure_deviation = true});
  ASSERT_TRUE(measured.has_value());
  EXPECT_LE(measured->parts[0].tessellation_deviation, 1.001 * kCasingDeflection);
}

TEST(SectorSplit, OneThreadAndManyGiveTheSameTriangles) {
  const Part many = import_casing(true);
  Part one;
  {
    const tbb::global_control only(tbb::global_control::max_allowed_parallelism, 1);
    one = import_casing(true);
  }
  ASSERT_EQ(one.mesh.num_triangles(), many.mesh.num_triangles());
  EXPECT_EQ(one.face_ids, many.face_ids);
  ASSERT_EQ(one.mesh.positions.size(), many.mesh.positions.size());
  for (std::size_t i = 0; i < one.mesh.positions.size(); ++i) {
    ASSERT_EQ(one.mesh.positions[i].x, many.mesh.positions[i].x) << i;
    ASSERT_EQ(one.mesh.positions[i].y, many.mesh.positions[i].y) << i;
    ASSERT_EQ(one.mesh.positions[i].z, many.mesh.positions[i].z) << i;
  }
  for (std::size_t t = 0; t < one.mesh.triangles.size(); ++t) ASSERT_EQ(one.mesh.triangles[t], many.mesh.triangles[t]) << t;
}

// Parts with no closed face of revolution holding three or more rims: the same tessellation either way.
TEST(SectorSplit, OtherPartsAreTessellatedAsBefore) {
  const auto dir = testing::scratch_dir("interfere_sector_split");
  for (const TestPart p : {TestPart::perforated_plate, TestPart::shaft_cross_hole, TestPart::casing,
                           TestPart::crossing_holes, TestPart::countersunk_plate_nurbs}) {
    const auto file = dir / ("part" + std::to_string(static_cast<int>(p)) + ".step");
    ASSERT_TRUE(write_test_part(p, file).ok());
    auto on = import_step(file, {.sector_split = true});
    auto off = import_step(file, {.sector_split = false});
    ASSERT_TRUE(on.has_value() && off.has_value());
    ASSERT_EQ(on->parts.size(), off->parts.size());
    for (std::size_t k = 0; k < on->parts.size(); ++k) {
      EXPECT_EQ(on->parts[k].face_ids, off->parts[k].face_ids) << file;
      ASSERT_EQ(on->parts[k].mesh.positions.size(), off->parts[k].mesh.positions.size()) << file;
      for (std::size_t i = 0; i < on->parts[k].mesh.positions.size(); ++i)
        ASSERT_EQ(on->parts[k].mesh.positions[i].x, off->parts[k].mesh.positions[i].x) << file << " " << i;
    }
  }
}

}  // namespace
}  // namespace interfere::cad
