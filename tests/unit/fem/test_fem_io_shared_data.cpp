// Extended check on the shared FEM files (/work/shared/data/fem, provenance and counts in
// /work/shared/data/SOURCES.md): every file reads, passes validate_fem_mesh and has the node and
// element counts listed there. Located at INTERFERE_SOURCE_DIR/../shared/data or
// $INTERFERE_SHARED_DATA; skipped when absent.
#include <gtest/gtest.h>

#include <cstdlib>

#include "fem_io_test_util.h"

namespace interfere::fem_test {
namespace {

fs::path shared_fem_dir() {
  if (const char* env = std::getenv("INTERFERE_SHARED_DATA"); env && *env) return fs::path(env) / "fem";
  return fs::path(INTERFERE_SOURCE_DIR) / ".." / "shared" / "data" / "fem";
}

struct SharedFile {
  const char* name;
  std::size_t nodes, elements;
  std::size_t groups;  // 0 = not checked
};
// Counts from SOURCES.md (elements of the highest dimension only: lower ones are dropped).
constexpr SharedFile kFiles[] = {
    {"calculix_cubef2f1.inp", 2961, 120 + 512, 0},
    {"gmsh_adaptive_tet10_v2.msh", 27, 6, 0},
    {"gmsh_discrete_tet4_v41.msh", 2785, 13059, 0},
    {"pynastran_contact_model.bdf", 1080, 675, 3},
    {"pynastran_contact_model_hex_v41.msh", 1080, 675, 3},
    {"pynastran_model1_sim1_mixed.bdf", 2363, 128 + 1326 + 48, 0},
    {"pynastran_solid_bending.bdf", 72, 186, 1},
    {"sfepy_abaqus_tet.inp", 13, 14, 0},
    {"sfepy_cylinder_v2.vtk", 354, 1348, 0},
    {"sfepy_msh_tetra_v22.msh", 66, 127, 0},
    {"sfepy_multi_material_cylinder_plate.vtk", 2101, 10440, 0},
    {"sfepy_wheelset_v51.vtk", 5457, 21934, 0},
    {"vtkdata_can_hex.vtu", 6724, 4800, 0},
    {"vtkdata_notch_disp.vtu", 12717, 2188 + 4, 0},
};

TEST(FemIoSharedData, EveryFileReadsWithTheListedCounts) {
  const fs::path dir = shared_fem_dir();
  if (!fs::is_directory(dir)) GTEST_SKIP() << dir << " not present";
  for (const SharedFile& f : kFiles) {
    SCOPED_TRACE(f.name);
    Expected<FemMesh> m = read_fem(dir / f.name);
    if (!m) {
      ADD_FAILURE() << m.error().message();
      continue;
    }
    EXPECT_TRUE(validate_fem_mesh(*m));
    EXPECT_EQ(m->num_nodes(), f.nodes);
    EXPECT_EQ(m->num_elements(), f.elements);
    if (f.groups) EXPECT_EQ(m->groups.size(), f.groups);
  }
}

TEST(FemIoSharedData, VtuDisplacementsAndIdsAreRead) {
  const fs::path dir = shared_fem_dir();
  if (!fs::is_directory(dir)) GTEST_SKIP() << dir << " not present";
  Expected<FemMesh> can = read_fem(dir / "vtkdata_can_hex.vtu");
  ASSERT_TRUE(can) << can.error().message();
  bool displ = false;
  for (const NodalSeries& s : can->fields) displ |= s.name == "DISPL";
  EXPECT_TRUE(displ);
  Expected<FemMesh> notch = read_fem(dir / "vtkdata_notch_disp.vtu");
  ASSERT_TRUE(notch) << notch.error().message();
  ASSERT_FALSE(notch->fields.empty());
  EXPECT_EQ(notch->fields[0].name, "Nodal Displacement");
  // Quadratic hexes and wedges: each mid-edge node near its corner pair's midpoint (the notch's
  // curved edges bow them by under 1 % of the element size; a node paired with the wrong edge
  // would be off by a quarter of it or more), i.e. the file's order is VTK's and kept as is.
  std::size_t checked = 0;
  EXPECT_LT(midside_error(*notch, &checked), 0.05);
  EXPECT_EQ(checked, notch->num_elements());
}

}  // namespace
}  // namespace interfere::fem_test
