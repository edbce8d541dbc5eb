// Issue #23, item 10: what real exports contain beside the volumes. 1-D and point elements
// (trusses, beams, springs, masses, rigid elements, lines) are skipped with a warning that counts
// them; 2-D elements on the faces of the 3-D elements are their boundary (no body of their own);
// other 2-D elements beside volumes are counted in a warning; unknown types remain errors naming
// file, line and type. The counts are those written into each file here.
#include <gtest/gtest.h>

#include "fem_io_test_util.h"
#include "interfere/fem/surface.h"

namespace interfere::fem_test {
namespace {

bool has_warning(const FemMesh& m, const std::string& needle) {
  for (const std::string& w : m.warnings) {
    if (w.find(needle) != std::string::npos) return true;
  }
  return false;
}

std::string all_warnings(const FemMesh& m) {
  std::string s;
  for (const std::string& w : m.warnings) s += w + "\n";
  return s;
}

// One tet (nodes 1-4) with: its face (1,2,3) as CPS3, an edge as T3D2 and B31, node 1 as MASS and
// SPRING1, and a triangle (1,2,5) that is no face of the tet as CPS3.
const char* kAbaqus = R"(*NODE
1, 0, 0, 0
2, 1, 0, 0
3, 0, 1, 0
4, 0, 0, 1
5, 3, 3, 3
*ELEMENT, TYPE=C3D4, ELSET=Volume1
1, 1, 2, 3, 4
*ELEMENT, TYPE=CPS3, ELSET=Surface1
2, 1, 3, 2
*ELEMENT, TYPE=T3D2, ELSET=Line1
3, 1, 2
*ELEMENT, TYPE=B31H
4, 2, 3
*ELEMENT, TYPE=MASS, ELSET=m
5, 1
*ELEMENT, TYPE=SPRING1
6, 4
*ELEMENT, TYPE=CPS3, ELSET=Plate
7, 1, 2, 5
)";

TEST(FemIoExports, AbaqusLinesPointsAndBoundaryTrianglesAreSkippedAndCounted) {
  const fs::path p = temp_dir() / "exports.inp";
  write_text(p, kAbaqus);
  auto m = read_fem(p);
  ASSERT_TRUE(m) << m.error().message();
  ASSERT_EQ(m->num_elements(), 1u);
  EXPECT_EQ(m->elem_types[0], ElemType::tet4);
  EXPECT_TRUE(has_warning(*m, "skipped 4 elements without a surface (2 1-D")) << all_warnings(*m);
  EXPECT_TRUE(has_warning(*m, "2 points")) << all_warnings(*m);
  EXPECT_TRUE(has_warning(*m, "skipped 1 2-D elements that are not faces")) << all_warnings(*m);
  EXPECT_TRUE(has_warning(*m, "1 2-D elements on the volumes' faces")) << all_warnings(*m);
  auto s = extract_surface(*m);
  ASSERT_TRUE(s);
  ASSERT_EQ(s->parts.size(), 1u);  // the boundary triangle is no second body
  EXPECT_EQ(s->parts[0].mesh.num_triangles(), 4u);
}

TEST(FemIoExports, AbaqusUnknownTypeIsAnErrorNamingLineAndType) {
  EXPECT_TRUE(
      bad_input("unknown.inp", "*NODE\n1, 0, 0, 0\n*ELEMENT, TYPE=XYZ42\n1, 1\n", "'XYZ42'"));
  EXPECT_TRUE(bad_input("b31x.inp", "*NODE\n1, 0, 0, 0\n*ELEMENT, TYPE=B319\n1, 1\n", "'B319'"));
}

TEST(FemIoExports, NastranBeamAndMassCardsAreCounted) {
  const fs::path p = temp_dir() / "exports.bdf";
  write_text(p,
             "BEGIN BULK\n"
             "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,0.,1.,0.\nGRID,4,,0.,0.,1.\n"
             "CTETRA,1,1,1,2,3,4\n"
             "CBAR,2,2,1,2,0.,0.,1.\nCBAR,3,2,2,3,0.,0.,1.\nCONM2,4,1,,1.\nRBE2,5,1,123456,2,3\n"
             "CTRIA3,6,3,1,3,2\n"
             "ENDDATA\n");
  auto m = read_fem(p);
  ASSERT_TRUE(m) << m.error().message();
  ASSERT_EQ(m->num_elements(), 1u);
  EXPECT_TRUE(has_warning(*m, "skipped 4 element cards without a surface")) << all_warnings(*m);
  EXPECT_TRUE(has_warning(*m, "CBAR 2, CONM2 1, RBE2 1")) << all_warnings(*m);
  EXPECT_FALSE(has_warning(*m, "not faces")) << all_warnings(*m);  // the CTRIA3 is the tet's face
}

TEST(FemIoExports, VtkPolyLinesAndVerticesAreSkipped) {
  const fs::path p = temp_dir() / "exports.vtk";
  write_text(p,
             "# vtk DataFile Version 2.0\nexports\nASCII\nDATASET UNSTRUCTURED_GRID\n"
             "POINTS 4 double\n0 0 0 1 0 0 0 1 0 0 0 1\n"
             "CELLS 5 19\n4 0 1 2 3\n3 0 1 2\n2 0 1\n1 3\n4 0 1 2 3\n"
             "CELL_TYPES 5\n10\n4\n3\n1\n2\n");
  auto m = read_fem(p);
  ASSERT_TRUE(m) << m.error().message();
  ASSERT_EQ(m->num_elements(), 1u);
  EXPECT_TRUE(has_warning(*m, "skipped 2 VTK empty, poly-vertex and poly-line cells"))
      << all_warnings(*m);
  EXPECT_TRUE(has_warning(*m, "skipped 2 elements without a surface (1 1-D")) << all_warnings(*m);
}

}  // namespace
}  // namespace interfere::fem_test
