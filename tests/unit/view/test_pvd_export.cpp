// ParaView series export of a viewer document (issue #25, item 3; include/interfere/view/pvd.h): the
// collection's data sets and time steps, the step files' names, point and cell counts and arrays,
// files of an earlier longer series removed, bad documents refused before anything is written.
// ParaView itself reads the series back in tests/view/check_pvd.py.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include <unistd.h>

#include "interfere/view/pvd.h"

namespace interfere::view {
namespace {

std::filesystem::path tmp_dir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / ("interfere_view_pvd_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

std::string read(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The values of attribute `name` in every element `tag` of `xml`, in order.
std::vector<std::string> attributes(const std::string& xml, const std::string& tag, const std::string& name) {
  std::vector<std::string> out;
  const std::regex element("<" + tag + "\\b[^>]*>");
  const std::regex attribute("\\b" + name + "=\"([^\"]*)\"");
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), element); it != std::sregex_iterator(); ++it) {
    std::smatch m;
    const std::string e = it->str();
    if (std::regex_search(e, m, attribute)) out.push_back(m[1]);
  }
  return out;
}

ViewMesh tetra() {
  ViewMesh m;
  m.mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0, 0, 3}};
  m.mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

ViewMesh triangle(double x) {
  ViewMesh m;
  m.mesh.positions = {{x, 0, 0}, {x + 1, 0, 0}, {x, 1, 0}};
  m.mesh.triangles = {{0, 1, 2}};
  return m;
}

Document series() {
  Document d;
  d.meshes = {tetra(), triangle(5), triangle(9)};
  d.meshes[0].source_ids = {11, 12, 13, 14};
  d.meshes[2].point_depth = {0, 0.5, 0.25};
  ViewBody a;
  a.id = "A", a.name = "alpha", a.mesh = 0;
  ViewBody b;
  b.id = "B", b.name = "beta", b.mesh = 0, b.frame_meshes = {0, 0, 2};
  d.bodies = {a, b};
  d.frames.labels = {"s0", "s1", "s2"};
  d.frames.times = {0, 0.25, 1};
  ViewClash k1;
  k1.id = "K1", k1.verdict = "clash", k1.body_a = 0, k1.body_b = 1, k1.region_mesh = 1, k1.frames = {2};
  k1.curves = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}};
  ViewClash k2;
  k2.id = "K2", k2.verdict = "clearance", k2.body_a = 0, k2.body_b = 1, k2.has_witness = true;
  k2.witness_a = {0, 0, 0}, k2.witness_b = {0, 0, 1}, k2.region_mesh = 1;
  d.clashes = {k1, k2};
  return d;
}

TEST(ViewPvd, FilesFolderIsNamedAfterTheStem) {
  EXPECT_EQ(pvd_files_folder("/a/b/run.pvd"), std::filesystem::path("/a/b/run_files"));
  EXPECT_EQ(pvd_files_folder("run.pvd"), std::filesystem::path("run_files"));
}

TEST(ViewPvd, CollectionStepsCountsAndArrays) {
  const auto dir = tmp_dir("series");
  ASSERT_TRUE(write_pvd(dir / "run.pvd", series()).ok());
  const std::string pvd = read(dir / "run.pvd");
  EXPECT_EQ(attributes(pvd, "DataSet", "timestep"), (std::vector<std::string>{"0", "0", "0.25", "0.25", "1", "1"}));
  EXPECT_EQ(attributes(pvd, "DataSet", "part"), (std::vector<std::string>{"0", "1", "0", "1", "0", "1"}));
  EXPECT_EQ(attributes(pvd, "DataSet", "file")[4], "run_files/bodies_0002.vtp");
  for (const std::string& f : attributes(pvd, "DataSet", "file")) EXPECT_TRUE(std::filesystem::is_regular_file(dir / f)) << f;
  // Step 0: two tetrahedra; step 2: beta draws the triangle with depths.
  const std::string b0 = read(dir / "run_files/bodies_0000.vtp");
  EXPECT_EQ(attributes(b0, "Piece", "NumberOfPoints"), std::vector<std::string>{"8"});
  EXPECT_EQ(attributes(b0, "Piece", "NumberOfPolys"), std::vector<std::string>{"8"});
  // (penetration_depth in every step, NaN where a mesh has none, since step 2 has depths)
  EXPECT_EQ(attributes(b0, "DataArray", "Name"),
            (std::vector<std::string>{"body_names", "body_ids", "penetration_depth", "body", "clash", "source_id", "Points",
                                      "connectivity", "offsets"}));
  EXPECT_NE(b0.find("compressor=\"vtkZLibDataCompressor\""), std::string::npos);
  const std::string b2 = read(dir / "run_files/bodies_0002.vtp");
  EXPECT_EQ(attributes(b2, "Piece", "NumberOfPoints"), std::vector<std::string>{"7"});
  EXPECT_EQ(attributes(b2, "Piece", "NumberOfPolys"), std::vector<std::string>{"5"});
  EXPECT_NE(b2.find("Name=\"penetration_depth\""), std::string::npos);
  // Clashes: K1 only in step 2; K2 (witness + region) in every step.
  const std::string c0 = read(dir / "run_files/clashes_0000.vtp");
  EXPECT_EQ(attributes(c0, "Piece", "NumberOfPoints"), std::vector<std::string>{"5"});
  EXPECT_EQ(attributes(c0, "Piece", "NumberOfLines"), std::vector<std::string>{"1"});
  EXPECT_EQ(attributes(c0, "Piece", "NumberOfPolys"), std::vector<std::string>{"1"});
  const std::string c2 = read(dir / "run_files/clashes_0002.vtp");
  EXPECT_EQ(attributes(c2, "Piece", "NumberOfPoints"), std::vector<std::string>{"11"});
  EXPECT_EQ(attributes(c2, "Piece", "NumberOfLines"), std::vector<std::string>{"2"});
  EXPECT_EQ(attributes(c2, "Piece", "NumberOfPolys"), std::vector<std::string>{"2"});
  EXPECT_NE(c2.find("Name=\"verdict\""), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(ViewPvd, StaticDocumentIsOneStepAndOldStepsGo) {
  const auto dir = tmp_dir("static");
  ASSERT_TRUE(write_pvd(dir / "run.pvd", series()).ok());
  std::ofstream(dir / "run_files/notes.txt") << "mine";
  Document d = series();
  d.frames = {};
  d.bodies[1].frame_meshes.clear();
  d.clashes.clear();
  ASSERT_TRUE(write_pvd(dir / "run.pvd", d).ok());
  const std::string pvd = read(dir / "run.pvd");
  EXPECT_EQ(attributes(pvd, "DataSet", "timestep"), std::vector<std::string>{"0"});
  std::vector<std::string> left;
  for (const auto& e : std::filesystem::directory_iterator(dir / "run_files")) left.push_back(e.path().filename().string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"bodies_0000.vtp", "notes.txt"}));
  std::filesystem::remove_all(dir);
}

TEST(ViewPvd, TimesNotIncreasingUseTheFrameIndex) {
  const auto dir = tmp_dir("times");
  Document d = series();
  d.frames.times = {0, 2, 1};
  ASSERT_TRUE(write_pvd(dir / "run.pvd", d).ok());
  EXPECT_EQ(attributes(read(dir / "run.pvd"), "DataSet", "timestep"), (std::vector<std::string>{"0", "0", "1", "1", "2", "2"}));
  std::filesystem::remove_all(dir);
}

TEST(ViewPvd, BadDocumentsWriteNothing) {
  const auto dir = tmp_dir("bad");
  Document d = series();
  d.bodies[1].frame_meshes = {0, 9, 0};
  Status s = write_pvd(dir / "run.pvd", d);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message().find("bodies[1].frame_meshes[1]: mesh 9 out of range"), std::string::npos);
  d = series();
  d.meshes[2].point_depth.pop_back();
  s = write_pvd(dir / "run.pvd", d);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message().find("meshes[2].point_depth: 2 values for 3 vertices"), std::string::npos);
  d = series();
  d.error = "no geometry";
  s = write_pvd(dir / "run.pvd", d);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message().find("no geometry"), std::string::npos);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace interfere::view
