// Mates inferred from an assembly's geometry (issue #29, item 4). Oracle: the CAx-IF AS1 assembly's
// structure as its product tree names it (../shared/data/step, skipped when absent): every bolt
// instance sits in holes of the plate or brackets and carries a nut; every rod sits in bracket
// holes; nuts sit on bolts (their hole, a through hole, around the bolt); heads, nuts and brackets
// lie on the plate or brackets. Same answer from the AP203 (analytic, inch) and the AP214 (B-spline
// cylinders, mm) export.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "interfere/cad/features.h"
#include "interfere/cad/mates.h"
#include "interfere/cad/model.h"

namespace interfere::cad {
namespace {

// The kind of an instance from its part's name (AS1: PLATE, L-BRACKET, BOLT, NUT, ROD), any case.
std::string kind_of(const CadModel& m, std::uint32_t instance) {
  std::string name = m.parts[m.instances[instance].part].name;
  for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
  for (const char* k : {"bolt", "nut", "rod", "plate", "bracket"})
    if (name.find(k) != std::string::npos) return k;
  return "?";
}

TEST(Mates, As1InsertionsFollowTheProductStructure) {
  const auto dir = std::filesystem::path(INTERFERE_SOURCE_DIR) / ".." / "shared" / "data" / "step";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "../shared/data not present";
  auto lib = default_feature_library();
  ASSERT_TRUE(lib.has_value());
  std::map<std::string, std::multiset<std::string>> per_file;
  for (const char* file : {"as1_pe_203.stp", "as1-oc-214.stp"}) {
    if (!std::filesystem::exists(dir / file)) continue;
    auto m = import_step(dir / file);
    ASSERT_TRUE(m.has_value()) << file;
    const auto mates = infer_mates(*m, *lib);
    std::map<std::uint32_t, std::set<std::string>> hosts;  // inserted instance -> kinds of the holed instances
    std::size_t insertions = 0, contacts = 0;
    for (const Mate& x : mates) {
      const std::string a = kind_of(*m, x.instance_a), b = kind_of(*m, x.instance_b);
      if (x.kind == Mate::Kind::insertion) {
        ++insertions;
        hosts[x.instance_b].insert(a);
        per_file[file].insert(b + " in " + a + " (" + x.constraint + ")");
        EXPECT_TRUE(b == "bolt" || b == "rod") << file << ": " << b << " inserted into " << a;
      } else {
        ++contacts;
        per_file[file].insert("contact " + std::min(a, b) + "-" + std::max(a, b));
      }
    }
    std::printf("%s: %zu instances, %zu insertions, %zu planar contacts\n", file, m->instances.size(), insertions, contacts);
    for (std::uint32_t k = 0; k < m->instances.size(); ++k) {
      const std::string kind = kind_of(*m, k);
      if (kind == "bolt") {
        EXPECT_TRUE(hosts[k].count("nut")) << file << " " << m->instances[k].path << " has no nut";
        EXPECT_TRUE(hosts[k].count("plate") || hosts[k].count("bracket")) << file << " " << m->instances[k].path;
      }
      if (kind == "rod") EXPECT_TRUE(hosts[k].count("bracket")) << file << " " << m->instances[k].path;
    }
    EXPECT_GT(contacts, 0u) << file;
  }
  if (per_file.size() == 2) EXPECT_EQ(per_file["as1_pe_203.stp"], per_file["as1-oc-214.stp"]);
  // AS1's structure: 6 bolts each through an L-bracket and the plate with a nut (head on the bracket,
  // nut under the plate), a rod through both brackets with a nut on each side, brackets on the plate.
  const std::map<std::string, std::size_t> expected{
      {"bolt in bracket (bolt)", 6}, {"bolt in plate (bolt)", 6}, {"bolt in nut (bolt)", 6},
      {"rod in bracket (bolt)", 2},  {"rod in nut (bolt)", 2},    {"contact bolt-bracket", 6},
      {"contact nut-plate", 6},      {"contact bracket-plate", 2}, {"contact bracket-nut", 2}};
  for (const auto& [file, s] : per_file) {
    std::map<std::string, std::size_t> got;
    for (const auto& line : s) ++got[line];
    EXPECT_EQ(got, expected) << file;
  }
  for (const auto& [file, s] : per_file)
    for (const auto& line : std::set<std::string>(s.begin(), s.end()))
      std::printf("  %s: %zu x %s\n", file.c_str(), s.count(line), line.c_str());
}

TEST(Mates, ApartPartsHaveNoMates) {
  // write_test_assembly: two counterbored plates 10 mm apart along z (one turned) and a stepped shaft
  // 100 mm away: nothing touches, nothing is inserted.
  const auto file = std::filesystem::temp_directory_path() / ("interfere_mates_" + std::to_string(::getpid()) + ".step");
  ASSERT_TRUE(write_test_assembly(file).ok());
  auto m = import_step(file);
  std::filesystem::remove(file);
  ASSERT_TRUE(m.has_value()) << m.error().message();
  auto lib = default_feature_library();
  ASSERT_TRUE(lib.has_value());
  ASSERT_EQ(m->instances.size(), 3u);
  EXPECT_TRUE(infer_mates(*m, *lib).empty());
}

// A planar contact needs the two faces' regions to overlap, not only their boxes (issue #29: planar
// mates compared face boxes). pocket_block's top face (z = 20) is a frame around the pocket opening
// x 15..45, y 10..30; stepped_shaft's bottom disc (r = 10, normal -z) set down on that plane:
//   centred in the opening (30, 20): inside it (tangent to two walls): the boxes overlap, the regions
//   only touch at points: no contact;
//   at (50, 20): the disc covers x 40..60, half of it on the frame: a contact with the top face.
TEST(Mates, PlanarContactNeedsOverlappingRegions) {
  const auto dir = std::filesystem::temp_directory_path();
  const auto fa = dir / ("interfere_mates_pocket_" + std::to_string(::getpid()) + ".step");
  const auto fb = dir / ("interfere_mates_shaft_" + std::to_string(::getpid()) + ".step");
  ASSERT_TRUE(write_test_part(TestPart::pocket_block, fa).ok());
  ASSERT_TRUE(write_test_part(TestPart::stepped_shaft, fb).ok());
  auto block = import_step(fa), shaft = import_step(fb);
  std::filesystem::remove(fa), std::filesystem::remove(fb);
  ASSERT_TRUE(block.has_value()) << block.error().message();
  ASSERT_TRUE(shaft.has_value()) << shaft.error().message();
  ASSERT_EQ(block->parts.size(), 1u);
  ASSERT_EQ(shaft->parts.size(), 1u);
  auto lib = default_feature_library();
  ASSERT_TRUE(lib.has_value());
  for (const double x : {30.0, 50.0}) {
    CadModel m = *block;
    m.parts.push_back(shaft->parts[0]);
    m.instances.resize(1);
    m.instances[0].part = 0;
    Instance s;
    s.name = s.path = "shaft";
    s.part = 1;
    s.placement.t = {x, 20, 20};
    m.instances.push_back(s);
    std::size_t contacts = 0;
    for (const Mate& mate : infer_mates(m, *lib)) {
      if (mate.kind != Mate::Kind::planar_contact) continue;
      ++contacts;
      ASSERT_EQ(mate.faces_a.size(), 1u);
      ASSERT_EQ(mate.faces_b.size(), 1u);
      const AagNode& top = m.parts[m.instances[mate.instance_a].part].aag.nodes[mate.faces_a[0]];
      EXPECT_EQ(top.type, SurfaceType::plane);
    }
    EXPECT_EQ(contacts, x == 30.0 ? 0u : 1u) << "shaft at x = " << x;
  }
}

}  // namespace
}  // namespace interfere::cad
