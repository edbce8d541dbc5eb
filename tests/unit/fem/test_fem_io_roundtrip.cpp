// Round trips of every reader/writer pair besides MSH (test_fem_io_msh.cpp): legacy VTK (ASCII,
// binary), VTU (ascii, binary, appended, zlib), Nastran, Abaqus. A mesh with every element type
// the format holds is written, read back and compared bit-exactly (nodes, ids, types, node order,
// group membership and the group ids/names the format keeps, the last field step for VTK).
#include <gtest/gtest.h>

#include <algorithm>

#include "fem_io_test_util.h"

namespace interfere::fem_test {
namespace {

FemMesh without(const FemMesh& m, std::vector<ElemType> drop) {
  FemMesh r = m;
  r.elem_types.clear();
  r.elem_ids.clear();
  r.elem_groups.clear();
  r.elem_offsets = {0};
  r.elem_nodes.clear();
  for (std::size_t e = 0; e < m.num_elements(); ++e) {
    if (std::find(drop.begin(), drop.end(), m.elem_types[e]) != drop.end()) continue;
    r.add_element(m.elem_types[e], m.elem_ids[e], m.elem_groups[e], m.element_nodes(e), m.element_size(e));
  }
  return r;
}

FemMesh last_step_only(FemMesh m) {
  for (NodalSeries& f : m.fields) {
    f.values.erase(f.values.begin(), f.values.end() - 1);
    f.times = {0.0};
  }
  return m;
}

void expect_groups_as(const FemMesh& a, const FemMesh& b, const std::string& prefix) {
  ASSERT_EQ(a.groups.size(), b.groups.size());
  EXPECT_EQ(a.elem_groups, b.elem_groups);
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    EXPECT_EQ(b.groups[g].id, a.groups[g].id);
    EXPECT_EQ(b.groups[g].name, prefix + std::to_string(a.groups[g].id));
  }
}

TEST(FemIoRoundTrip, VtkLegacyAndVtuEveryEncoding) {
  struct Case {
    const char* file;
    FemWriteOptions o;
  };
  const Case cases[] = {{"rt_ascii.vtk", {.binary = false}},
                        {"rt_binary.vtk", {.binary = true}},
                        {"rt_ascii.vtu", {.vtu_encoding = VtuEncoding::ascii}},
                        {"rt_binary.vtu", {.vtu_encoding = VtuEncoding::binary}},
                        {"rt_appended.vtu", {.vtu_encoding = VtuEncoding::appended}},
                        {"rt_zlib.vtu", {.vtu_encoding = VtuEncoding::zlib}}};
  for (bool shell : {false, true}) {
    const FemMesh m = every_type_mesh(shell);
    for (const Case& c : cases) {
      SCOPED_TRACE(std::string(c.file) + (shell ? " shell" : " volume"));
      const fs::path p = temp_dir() / ((shell ? "s_" : "v_") + std::string(c.file));
      ASSERT_TRUE(write_fem(m, p, c.o));
      Expected<FemMesh> back = read_fem(p);
      ASSERT_TRUE(back) << back.error().message();
      EXPECT_TRUE(validate_fem_mesh(*back));
      expect_same_mesh(last_step_only(m), *back, false, false, true);
      if (std::string(c.file).ends_with(".vtu")) {
        expect_same_mesh(last_step_only(m), *back, true, true, true);  // VTU keeps the group names
      } else {
        expect_groups_as(m, *back, "group ");
      }
    }
  }
}

TEST(FemIoRoundTrip, VtuExtraArraysAreWrittenAndReadAsData) {
  FemMesh m = every_type_mesh(false);
  m.fields.clear();
  FemWriteOptions o{.vtu_encoding = VtuEncoding::zlib};
  FemArray face{.name = "face", .components = 1};
  for (std::size_t e = 0; e < m.num_elements(); ++e) face.ints.push_back(static_cast<std::int64_t>(e) * 1000000007LL);
  o.cell_data.push_back(face);
  FemArray disp{.name = "u_0002", .components = 3};
  FemArray disp1{.name = "u_0001", .components = 3};
  for (std::size_t i = 0; i < m.num_nodes(); ++i) {
    for (int k = 0; k < 3; ++k) {
      disp.reals.push_back(0.1 * static_cast<double>(i) + k);
      disp1.reals.push_back(-0.1 * static_cast<double>(i) + k);
    }
  }
  o.point_data = {disp, disp1};
  const fs::path p = temp_dir() / "arrays.vtu";
  ASSERT_TRUE(write_fem(m, p, o));
  Expected<FemMesh> back = read_fem(p);
  ASSERT_TRUE(back) << back.error().message();
  // u_0001, u_0002: one series "u" with steps in numeric order.
  ASSERT_EQ(back->fields.size(), 1u);
  EXPECT_EQ(back->fields[0].name, "u");
  EXPECT_EQ(back->fields[0].times, (std::vector<double>{1, 2}));
  EXPECT_EQ(back->fields[0].values[0][5], (Vec3{-0.5, 1 - 0.5, 2 - 0.5}));
  EXPECT_EQ(back->fields[0].values[1][5], (Vec3{0.1 * 5, 0.1 * 5 + 1, 0.1 * 5 + 2}));
  // Wrong-sized arrays are refused before anything is written.
  o.cell_data[0].ints.pop_back();
  const fs::path q = temp_dir() / "never.vtu";
  EXPECT_FALSE(write_fem(m, q, o));
  EXPECT_FALSE(fs::exists(q));
}

TEST(FemIoRoundTrip, NastranAndAbaqus) {
  for (bool shell : {false, true}) {
    SCOPED_TRACE(shell ? "shell" : "volume");
    const FemMesh full = every_type_mesh(shell);
    {
      const FemMesh m = without(full, {ElemType::hex27, ElemType::quad9});
      const fs::path p = temp_dir() / (shell ? "rt_shell.bdf" : "rt_volume.bdf");
      ASSERT_TRUE(write_fem(m, p));
      Expected<FemMesh> back = read_fem(p);
      ASSERT_TRUE(back) << back.error().message();
      expect_same_mesh(m, *back, false, false, false);
      expect_groups_as(m, *back, "PID ");
    }
    {
      FemMesh m = without(full, {ElemType::pyr13, ElemType::quad9});
      m.node_sets = {{.name = "fixed", .members = {0, 3, 5}}};
      m.elem_sets = {{.name = "hot", .members = {1, 2}}};
      const fs::path p = temp_dir() / (shell ? "rt_shell.inp" : "rt_volume.inp");
      ASSERT_TRUE(write_fem(m, p));
      Expected<FemMesh> back = read_fem(p);
      ASSERT_TRUE(back) << back.error().message();
      expect_same_mesh(m, *back, true, false, false);
      ASSERT_EQ(back->node_sets.size(), 1u);
      EXPECT_EQ(back->node_sets[0].members, m.node_sets[0].members);
      // Element sets: the ELSETs of the *ELEMENT blocks (the groups) and "hot".
      bool hot = false;
      for (const FemSet& s : back->elem_sets) hot |= s.name == "hot" && s.members == m.elem_sets[0].members;
      EXPECT_TRUE(hot);
    }
  }
}

TEST(FemIoRoundTrip, FormatNamesAndDetection) {
  EXPECT_EQ(fem_format_from_name("BDF"), FemFormat::nastran);
  EXPECT_EQ(fem_format_from_name("abaqus"), FemFormat::abaqus);
  EXPECT_EQ(fem_format_from_name("foo"), FemFormat::automatic);
  EXPECT_EQ(fem_format_from_path("a/b.NAS"), FemFormat::nastran);
  EXPECT_EQ(fem_format_from_path("x.vtu"), FemFormat::vtu);
  EXPECT_EQ(fem_format_from_path("x.stl"), FemFormat::automatic);
  for (FemFormat f : {FemFormat::msh, FemFormat::nastran, FemFormat::vtk_legacy, FemFormat::vtu, FemFormat::abaqus}) {
    EXPECT_EQ(fem_format_from_name(fem_format_name(f)), f);
  }
  // Content detection: every writer's output under a neutral extension.
  const FemMesh m = without(every_type_mesh(false), {ElemType::hex27, ElemType::pyr13});
  for (FemFormat f : {FemFormat::msh, FemFormat::nastran, FemFormat::vtk_legacy, FemFormat::vtu, FemFormat::abaqus}) {
    SCOPED_TRACE(fem_format_name(f));
    const fs::path p = temp_dir() / (std::string("detect_") + fem_format_name(f) + ".txt");
    ASSERT_TRUE(write_fem(m, p, {.format = f}));
    Expected<FemMesh> back = read_fem(p);
    ASSERT_TRUE(back) << back.error().message();
    EXPECT_EQ(back->num_elements(), m.num_elements());
  }
  EXPECT_TRUE(bad_input("unknown.txt", "hello\nworld\n", "cannot tell the FEM format", false));
}

}  // namespace
}  // namespace interfere::fem_test
