// The committed hand-written files of tests/data/fem (make_fem_files.py, README.md) read with the
// values they were written with, and corrupted inputs of every format give an error naming the
// file, the line or byte and the reason.
#include <gtest/gtest.h>

#include <algorithm>

#include "fem_io_test_util.h"

namespace interfere::fem_test {
namespace {

fs::path data(const std::string& name) { return fs::path(INTERFERE_SOURCE_DIR) / "tests" / "data" / "fem" / name; }

FemMesh must_read(const std::string& name) {
  Expected<FemMesh> m = read_fem(data(name));
  EXPECT_TRUE(m) << m.error().message();
  if (!m) return {};
  EXPECT_TRUE(validate_fem_mesh(*m));
  return std::move(*m);
}

std::size_t node_index(const FemMesh& m, std::int64_t id) {
  return static_cast<std::size_t>(std::find(m.node_ids.begin(), m.node_ids.end(), id) - m.node_ids.begin());
}

const FemSet* find_set(const std::vector<FemSet>& sets, const std::string& name) {
  for (const FemSet& s : sets) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

TEST(FemIoFiles, NastranSmallFieldContinuationsIncludeShorthand) {
  const FemMesh m = must_read("small_field.bdf");
  ASSERT_EQ(m.num_nodes(), 13u);  // GRID 99 after ENDDATA is not read
  EXPECT_EQ(m.nodes[node_index(m, 2)], (Vec3{1, 0, 0}));
  EXPECT_EQ(m.nodes[node_index(m, 13)], (Vec3{0.25, 0.25, -25}));
  ASSERT_EQ(m.num_elements(), 3u);
  EXPECT_EQ(m.elem_ids, (std::vector<std::int64_t>{20, 21, 30}));
  EXPECT_EQ(m.elem_types, (std::vector<ElemType>{ElemType::hex8, ElemType::hex8, ElemType::tet4}));
  // CHEXA 21 continued by a line with a blank first field: grids 5..12.
  for (int k = 0; k < 8; ++k) EXPECT_EQ(m.node_ids[m.element_nodes(1)[k]], 5 + k);
  ASSERT_EQ(m.groups.size(), 2u);
  EXPECT_EQ(m.groups[0].name, "PID 1");
  EXPECT_EQ(m.groups[1].id, 2);
  EXPECT_EQ(m.elem_groups, (std::vector<std::int32_t>{0, 1, 1}));
}

TEST(FemIoFiles, NastranTabsExpandToEightColumns) {
  std::string text = "BEGIN BULK\n";
  for (int i = 1; i <= 40; ++i) text += "GRID\t" + std::to_string(i) + "\t\t" + std::to_string(i) + ".\t2.5-1\t0.\n";
  text += "CTETRA\t7\t3\t1\t2\t3\t40\n";
  const fs::path p = temp_dir() / "tabs.bdf";
  write_text(p, text);
  Expected<FemMesh> m = read_fem(p);
  ASSERT_TRUE(m) << m.error().message();
  ASSERT_EQ(m->num_nodes(), 40u);
  for (std::size_t i = 0; i < 40; ++i) EXPECT_EQ(m->nodes[i], (Vec3{static_cast<double>(i + 1), 0.25, 0})) << i;
  EXPECT_EQ(m->node_ids[m->element_nodes(0)[3]], 40);
  EXPECT_EQ(m->groups[0].name, "PID 3");
}

TEST(FemIoFiles, NastranLargeAndFreeFieldWedge15InVtkOrder) {
  const FemMesh m = must_read("large_free_field.bdf");
  ASSERT_EQ(m.num_nodes(), 15u);
  ASSERT_EQ(m.num_elements(), 1u);  // the CTRIA3 next to the solid is dropped
  EXPECT_EQ(m.elem_types[0], ElemType::wedge15);
  std::size_t checked = 0;
  EXPECT_EQ(midside_error(m, &checked), 0.0);
  EXPECT_EQ(checked, 1u);
  EXPECT_EQ(m.nodes[node_index(m, 5)], (Vec3{1, 0, 1}));  // large-field GRID* with '*' continuation
  EXPECT_EQ(m.groups.size(), 1u);
  EXPECT_EQ(m.groups[0].name, "PID 5");
}

TEST(FemIoFiles, QuadraticSolidsInTheSolversOrdersComeOutInVtkOrder) {
  // Files written from the solvers' manuals' mid-side orders (make_fem_files.py): every mid-side
  // node must sit at the midpoint of the VTK corner pair of its position.
  const FemMesh nas = must_read("quadratic.bdf");
  EXPECT_EQ(nas.elem_types, (std::vector<ElemType>{ElemType::tet10, ElemType::hex20, ElemType::wedge15, ElemType::pyr13}));
  std::size_t checked = 0;
  EXPECT_EQ(midside_error(nas, &checked), 0.0);
  EXPECT_EQ(checked, 4u);
  const FemMesh abq = must_read("quadratic.inp");
  EXPECT_EQ(abq.elem_types, (std::vector<ElemType>{ElemType::tet10, ElemType::wedge15, ElemType::hex20}));
  EXPECT_EQ(midside_error(abq, &checked), 0.0);
  EXPECT_EQ(checked, 3u);
  EXPECT_EQ(abq.groups.size(), 3u);
}

TEST(FemIoFiles, AbaqusInstancesAreTranslatedThenRotatedWithOffsetIds) {
  const FemMesh m = must_read("assembly.inp");
  ASSERT_EQ(m.num_nodes(), 16u);
  ASSERT_EQ(m.num_elements(), 2u);
  // Ids: instance k gets + k * 10 (10 = smallest power of ten above every part id).
  EXPECT_EQ(m.elem_ids, (std::vector<std::int64_t>{1, 11}));
  EXPECT_EQ(m.node_ids[8], 11);
  ASSERT_EQ(m.groups.size(), 2u);
  EXPECT_EQ(m.groups[0].name, "B1");
  EXPECT_EQ(m.groups[1].name, "B2");
  EXPECT_EQ(m.groups[1].id, 2);
  EXPECT_EQ(m.elem_groups, (std::vector<std::int32_t>{0, 1}));
  EXPECT_EQ(m.nodes[node_index(m, 2)], (Vec3{1, 0, 0}));
  // Part node 2 (1,0,0): translated to (11,0,0), then 90 degrees about the z axis through (10,0,0).
  EXPECT_LT(distance(m.nodes[node_index(m, 12)], Vec3{10, 1, 0}), 1e-12);
  EXPECT_LT(distance(m.nodes[node_index(m, 17)], Vec3{9, 1, 1}), 1e-12);  // part node 7 (1,1,1)
  const FemSet* bottom = find_set(m.node_sets, "b2.bottom");
  ASSERT_TRUE(bottom);
  EXPECT_EQ(bottom->members.size(), 4u);
  for (std::uint32_t i : bottom->members) EXPECT_LT(std::abs(m.nodes[i].z), 1e-12);
  const FemSet* corner = find_set(m.node_sets, "b2.corner");
  ASSERT_TRUE(corner);
  ASSERT_EQ(corner->members.size(), 1u);
  EXPECT_EQ(m.node_ids[corner->members[0]], 12);
  EXPECT_FALSE(find_set(m.node_sets, "b1.corner"));
}

TEST(FemIoFiles, AbaqusHex20ContinuationIncludeGenerate) {
  const FemMesh m = must_read("hex20.inp");
  ASSERT_EQ(m.num_elements(), 2u);
  EXPECT_EQ(m.elem_types[0], ElemType::hex20);
  EXPECT_EQ(midside_error(m), 0.0);
  ASSERT_EQ(m.groups.size(), 2u);
  EXPECT_EQ(m.groups[0].name, "cube");
  EXPECT_EQ(m.groups[1].name, "spike");
  const FemSet* all = find_set(m.elem_sets, "everything");
  ASSERT_TRUE(all);
  EXPECT_EQ(all->members, (std::vector<std::uint32_t>{0, 1}));
}

TEST(FemIoFiles, MshPhysicalGroupsFirstWinsAndLowerDimensionBecomesNodeSet) {
  for (const char* f : {"two_bodies_v22.msh", "two_bodies_v41.msh"}) {
    SCOPED_TRACE(f);
    const FemMesh m = must_read(f);
    ASSERT_EQ(m.num_elements(), 2u);
    ASSERT_EQ(m.groups.size(), 2u);
    EXPECT_EQ(m.groups[0].name, "steel");
    EXPECT_EQ(m.groups[1].name, "rubber");
    // The second tet is in "rubber" first (and "steel" too): its first group wins.
    EXPECT_EQ(m.elem_groups, (std::vector<std::int32_t>{0, 1}));
    const FemSet* contact = find_set(m.node_sets, "contact");
    ASSERT_TRUE(contact);
    EXPECT_EQ(contact->members, (std::vector<std::uint32_t>{0, 1, 2}));
  }
}

TEST(FemIoFiles, LegacyVtk51AndBinary) {
  const FemMesh w = must_read("wedge_v51.vtk");
  ASSERT_EQ(w.num_elements(), 2u);
  EXPECT_EQ(w.elem_types, (std::vector<ElemType>{ElemType::wedge6, ElemType::pyr5}));
  ASSERT_EQ(w.groups.size(), 2u);
  EXPECT_EQ(w.groups[0].name, "mat_id 4");
  EXPECT_EQ(w.groups[1].id, 9);
  ASSERT_EQ(w.fields.size(), 1u);
  EXPECT_EQ(w.fields[0].name, "displacement");
  EXPECT_EQ(w.fields[0].values[0][3], (Vec3{0, 0, 0.5}));
  EXPECT_EQ(w.elem_ids, (std::vector<std::int64_t>{1, 2}));  // 1-based positions
  // Arrays we do not use are read past.
  const fs::path extra = temp_dir() / "extra.vtk";
  std::string tensors;
  for (int k = 0; k < 36; ++k) tensors += "0.5 ";
  write_text(extra, "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n0 0 0 1 0 0 0 1 0 0 0 1\n"
                    "CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\nPOINT_DATA 4\nTENSORS t float\n" + tensors +
                    "\nTEXTURE_COORDINATES uv 2 float\n0 0 1 0 0 1 1 1\nCOLOR_SCALARS c 1\n0 0.5 1 1\nVECTORS u float\n1 2 3 1 2 3 1 2 3 1 2 3\n");
  Expected<FemMesh> e = read_fem(extra);
  ASSERT_TRUE(e) << e.error().message();
  ASSERT_EQ(e->fields.size(), 1u);
  EXPECT_EQ(e->fields[0].values[0][3], (Vec3{1, 2, 3}));
  const FemMesh t = must_read("tet_binary.vtk");
  ASSERT_EQ(t.num_elements(), 1u);
  EXPECT_EQ(t.elem_ids[0], 77);
  EXPECT_EQ(t.node_ids, (std::vector<std::int64_t>{11, 12, 13, 14}));
  EXPECT_EQ(t.nodes[3], (Vec3{0, 0, 1}));
}

TEST(FemIoFiles, VtuEveryEncodingGivesTheSameMesh) {
  const char* files[] = {"tets_ascii.vtu", "tets_binary_u32.vtu", "tets_binary_zlib_u64.vtu", "tets_appended_raw_zlib.vtu",
                         "tets_appended_base64_u64.vtu", "tets_appended_raw_big_endian.vtu"};
  for (const char* f : files) {
    SCOPED_TRACE(f);
    const FemMesh m = must_read(f);
    ASSERT_EQ(m.num_nodes(), 5u);
    ASSERT_EQ(m.num_elements(), 2u);
    EXPECT_EQ(m.node_ids, (std::vector<std::int64_t>{101, 102, 103, 104, 105}));
    EXPECT_EQ(m.elem_ids, (std::vector<std::int64_t>{7, 9}));
    EXPECT_EQ(m.nodes[4], (Vec3{1, 1, 1}));
    EXPECT_EQ(m.elem_nodes, (std::vector<std::uint32_t>{0, 1, 2, 3, 1, 2, 3, 4}));
    ASSERT_EQ(m.groups.size(), 2u);
    EXPECT_EQ(m.groups[0].name, "MaterialIds -2");
    EXPECT_EQ(m.elem_groups, (std::vector<std::int32_t>{1, 0}));
    ASSERT_EQ(m.fields.size(), 1u);
    EXPECT_EQ(m.fields[0].name, "DISPL");
    const double x = std::string(f) == "tets_ascii.vtu" ? 0.1 * 13 : static_cast<double>(static_cast<float>(0.1 * 13));
    EXPECT_EQ(m.fields[0].values[0][4].y, x);
  }
}

TEST(FemIoFiles, VtuInformationKeysCommentsAndEntities) {
  std::string x = read_text(data("tets_ascii.vtu"));
  const std::string tag = "Name=\"DISPL\" NumberOfComponents=\"3\" format=\"ascii\">";
  const std::size_t at = x.find(tag);
  ASSERT_NE(at, std::string::npos);
  x.insert(at + tag.size(), "\n  <InformationKey name=\"L2_NORM_RANGE\" location=\"vtkDataArray\" length=\"2\">\n"
                            "<Value index=\"0\">0</Value></InformationKey>\n  <!-- a comment -->\n");
  x.replace(x.find("Name=\"DISPL\""), 13, "Name=\"D&amp;U\"");
  const fs::path p = temp_dir() / "info.vtu";
  write_text(p, x);
  Expected<FemMesh> m = read_fem(p);
  ASSERT_TRUE(m) << m.error().message();
  ASSERT_EQ(m->fields.size(), 1u);
  EXPECT_EQ(m->fields[0].name, "D&U");
  EXPECT_EQ(m->fields[0].values[0][4].y, 0.1 * 13);
}

TEST(FemIoFiles, DisplacementCsvStepsAnyOrder) {
  const FemMesh m = must_read("tets_ascii.vtu");
  CsvDisplacementInfo info;
  Expected<NodalSeries> s = read_displacements_csv(data("tets_disp.csv"), m, &info);
  ASSERT_TRUE(s) << s.error().message();
  EXPECT_EQ(s->name, "tets_disp");
  EXPECT_EQ(s->times, (std::vector<double>{1, 2}));
  EXPECT_EQ(s->values[0][0], (Vec3{1e-3, 0, 0}));
  EXPECT_EQ(s->values[0][4], (Vec3{0.25, 0, 0}));
  EXPECT_EQ(s->values[1][0], (Vec3{2e-3, 0, -1}));
  EXPECT_EQ(s->values[1][4], (Vec3{0.5, 0, 0}));
  EXPECT_EQ(s->values[1][2], Vec3{});
  EXPECT_EQ(info.rows, 4u);
  EXPECT_EQ(info.missing_nodes, 6u);
  // One step, other header spellings, semicolons.
  const fs::path p = temp_dir() / "one.csv";
  write_text(p, "Node;UX;UY;UZ\n103;1;2;3\n");
  s = read_displacements_csv(p, m);
  ASSERT_TRUE(s) << s.error().message();
  EXPECT_EQ(s->num_steps(), 1u);
  EXPECT_EQ(s->values[0][2], (Vec3{1, 2, 3}));
  // Errors name the row.
  auto bad = [&](const std::string& text, const std::string& what, std::int64_t line) {
    write_text(p, text);
    Expected<NodalSeries> r = read_displacements_csv(p, m);
    ASSERT_FALSE(r) << text;
    EXPECT_NE(r.error().reason.find(what), std::string::npos) << r.error().message();
    EXPECT_EQ(r.error().line, line) << r.error().message();
    EXPECT_EQ(r.error().file, p.string());
  };
  bad("node_id,ux,uy,uz\n101,0,0,0\n999,0,0,0\n", "node 999 is not in the mesh", 3);
  bad("node_id,ux,uy,uz\n101,0,nan,0\n", "non-finite", 2);
  bad("node_id,ux,uy,uz\n101,0,1x,0\n", "malformed number", 2);
  bad("step,node_id,ux,uy,uz\n1,101,0,0,0\n2,101,0,0,0\n1,101,1,0,0\n", "duplicate row for node 101", 4);
  bad("node_id,ux,uy,uz\n101,0,0\n", "3 columns", 2);
  bad("node_id,ux,uy,pressure\n", "unknown column", 1);
}

TEST(FemIoFiles, CorruptedInputsOfEveryFormat) {
  // Nastran.
  const std::string grids = "BEGIN BULK\nGRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,0.,1.,0.\nGRID,4,,0.,0.,1.\n";
  EXPECT_TRUE(bad_input("cp.bdf", "BEGIN BULK\nGRID    1       5       0.      0.      0.\n", "CP=5 is not supported"));
  EXPECT_TRUE(bad_input("missing.bdf", grids + "CTETRA,1,1,1,2,3,9\n", "grid 9 is not defined"));
  EXPECT_TRUE(bad_input("dupgrid.bdf", grids + "GRID,4,,0.,0.,2.\nCTETRA,1,1,1,2,3,4\n", "duplicate GRID id 4"));
  EXPECT_TRUE(bad_input("dupelem.bdf", grids + "CTETRA,1,1,1,2,3,4\nCTETRA,1,1,1,2,4,3\n", "duplicate element id 1"));
  EXPECT_TRUE(bad_input("badreal.bdf", "BEGIN BULK\nGRID,1,,0.,abc,0.\n", "malformed coordinate"));
  EXPECT_TRUE(bad_input("count.bdf", grids + "CTETRA,1,1,1,2,3\n", "corner grid G4 is blank"));
  EXPECT_TRUE(bad_input("include.bdf", "BEGIN BULK\nINCLUDE 'nowhere.bdf'\n", "cannot open"));
  EXPECT_TRUE(bad_input("include_dir.bdf", "BEGIN BULK\nINCLUDE /\n", "is a directory"));
  EXPECT_TRUE(bad_input("include_dev.inp", "*INCLUDE, INPUT=/dev/zero\n", "not a regular file"));
  // Abaqus.
  const std::string nodes = "*NODE\n1,0,0,0\n2,1,0,0\n3,0,1,0\n4,0,0,1\n";
  EXPECT_TRUE(bad_input("type.inp", nodes + "*ELEMENT, TYPE=C3D11\n1,1,2,3,4\n", "unsupported element type"));
  EXPECT_TRUE(bad_input("missing.inp", nodes + "*ELEMENT, TYPE=C3D4\n1,1,2,3,7\n", "node 7 is not defined"));
  EXPECT_TRUE(bad_input("short.inp", nodes + "*ELEMENT, TYPE=C3D4\n1,1,2,3\n", "needs 4 nodes"));
  EXPECT_TRUE(bad_input("nan.inp", "*NODE\n1,0,nan,0\n", "non-finite"));
  EXPECT_TRUE(bad_input("system.inp", "*NODE, SYSTEM=C\n1,1,0,0\n", "SYSTEM=C is not supported"));
  EXPECT_TRUE(bad_input("instance.inp", "*ASSEMBLY\n*INSTANCE, NAME=a, PART=nope\n*END INSTANCE\n", "unknown part"));
  EXPECT_TRUE(bad_input("dup.inp", nodes + "*ELEMENT, TYPE=C3D4\n1,1,2,3,4\n1,1,2,4,3\n", "duplicate element id 1", false));
  // Legacy VTK.
  const std::string vtk = "# vtk DataFile Version 2.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n0 0 0 1 0 0 0 1 0 0 0 1\n";
  EXPECT_TRUE(bad_input("type.vtk", vtk + "CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n42\n", "unsupported VTK cell type 42"));
  EXPECT_TRUE(bad_input("range.vtk", vtk + "CELLS 1 5\n4 0 1 2 7\nCELL_TYPES 1\n10\n", "point index 7 out of range"));
  EXPECT_TRUE(bad_input("size.vtk", vtk + "CELLS 1 6\n4 0 1 2 3\nCELL_TYPES 1\n10\n", "malformed integer 'CELL_TYPES'"));
  EXPECT_TRUE(bad_input("num.vtk", "# vtk DataFile Version 2.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 1 float\n0 0 zz\n", "malformed number"));
  EXPECT_TRUE(bad_input("nan.vtk", "# vtk DataFile Version 2.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n0 0 nan 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n", "non-finite", false));
  std::string trunc = read_text(data("tet_binary.vtk"));
  EXPECT_TRUE(bad_input("trunc.vtk", trunc.substr(0, trunc.find("CELLS") + 14), "truncated binary block"));
  // VTU.
  const std::string good = read_text(data("tets_ascii.vtu"));
  std::string x = good;
  x.replace(x.find("</Points>"), 9, "</Pointz>");
  EXPECT_TRUE(bad_input("xml.vtu", x, "XML: end tag </Pointz> does not match"));
  x = good;
  x.replace(x.find("1.0 1.0 1.0"), 3, "1.x");
  EXPECT_TRUE(bad_input("num.vtu", x, "malformed number"));
  x = read_text(data("tets_binary_u32.vtu"));
  const std::size_t b64 = x.find("format=\"binary\">\n") + 17;
  x[b64 + 5] = '!';
  EXPECT_TRUE(bad_input("b64.vtu", x, "bad base64 character"));
  x = read_text(data("tets_appended_raw_zlib.vtu"));
  const std::size_t us = x.find("   _") + 4;
  for (std::size_t k = us + 52; k < us + 70 && k < x.size(); ++k) x[k] = static_cast<char>(x[k] ^ 0x5a);
  EXPECT_TRUE(bad_input("zlib.vtu", x, "zlib"));
  x = read_text(data("tets_appended_raw_zlib.vtu"));
  for (int k = 4; k < 12; ++k) x[us + static_cast<std::size_t>(k)] = k % 4 == 3 ? '\x7f' : '\xff';  // block sizes 2^31-1
  EXPECT_TRUE(bad_input("bomb.vtu", x, "zlib header announces"));
  x = read_text(data("tets_appended_raw_big_endian.vtu"));
  EXPECT_TRUE(bad_input("trunc.vtu", x.substr(0, x.find("   _") + 30), "truncated"));
  x = good;
  x.replace(x.find("10 10"), 5, "10 77");
  EXPECT_TRUE(bad_input("celltype.vtu", x, "unsupported VTK cell type 77"));
}

}  // namespace
}  // namespace interfere::fem_test
