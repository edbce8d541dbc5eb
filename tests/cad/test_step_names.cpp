// Instance and part names of STEP assemblies (issue #24, item 1): AP203 exports hold each
// product's solid as a nameless sub-shape and leave instances unnamed, which OCCT's XCAF names
// "=>[0:1:1:3]", "SOLID" or by the NAUO id; the instances must carry their products' names.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "cad_test_util.h"
#include "interfere/cad/model.h"

namespace interfere::cad {
namespace {

std::string file_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(StepNames, Ap203InstancesCarryTheirProductNames) {
  const auto file = testing::scratch_dir("interfere_step_names") / "ap203_assembly.step";
  const Status w = write_test_assembly_ap203(file);
  ASSERT_TRUE(w.ok()) << w.error().message();
  const std::string text = file_text(file);
  ASSERT_NE(text.find("CONFIG_CONTROL_DESIGN"), std::string::npos) << "not written as AP203";
  auto m = import_step(file);
  ASSERT_TRUE(m.has_value()) << m.error().message();
  ASSERT_EQ(m->instances.size(), 3u);
  std::multiset<std::string> names, paths;
  for (const Instance& i : m->instances) {
    names.insert(i.name);
    paths.insert(i.path);
    EXPECT_EQ(i.name, m->parts[i.part].name)
        << "an instance without a name of its own is named by its product";
  }
  EXPECT_EQ(names, (std::multiset<std::string>{"PLATE", "ROD", "ROD"}));
  // The plate's solid is a level of XCAF's tree, not of the product tree; the two unnamed rods are
  // told apart by "#2".
  EXPECT_EQ(paths, (std::multiset<std::string>{"/ASM/PLATE", "/ASM/ROD", "/ASM/ROD#2"}));
  std::set<std::string> parts;
  for (const Part& p : m->parts) parts.insert(p.name);
  EXPECT_EQ(parts, (std::set<std::string>{"PLATE", "ROD"}));
  for (const Instance& i : m->instances)
    if (i.name == "ROD") EXPECT_NEAR(std::fabs(i.placement.t.x), 100, 1e-9);
}

TEST(StepNames, Ap214AssemblyKeepsItsInstanceNames) {
  const auto file = testing::scratch_dir("interfere_step_names") / "ap214_assembly.step";
  ASSERT_TRUE(write_test_assembly(file).ok());
  auto m = import_step(file);
  ASSERT_TRUE(m.has_value()) << m.error().message();
  std::set<std::string> names;
  for (const Instance& i : m->instances) names.insert(i.name);
  // plate_2 and shaft_1 are the file's NAUO names; OCCT writes the identity-placed plate_1's as ''
  // (its id, "1", comes back): the product's name then.
  EXPECT_EQ(names, (std::set<std::string>{"plate", "plate_2", "shaft_1"}));
}

// The CAx-IF AS1 assembly as a Pro/E AP203 export (when ../shared/data is present): every
// instance is named after a PRODUCT of the file (a text scan), and every path is distinct.
TEST(StepNames, SharedAs1Ap203NamesAreProductNames) {
  const auto file = std::filesystem::path(INTERFERE_SOURCE_DIR) / ".." / "shared" / "data" /
                    "step" / "as1_pe_203.stp";
  if (!std::filesystem::exists(file))
    GTEST_SKIP() << "../shared/data/step/as1_pe_203.stp not present";
  const std::string text = file_text(file);
  std::set<std::string> products;
  const std::regex product(R"(=\s*PRODUCT\s*\(\s*'([^']*)')");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), product);
       it != std::sregex_iterator(); ++it)
    products.insert((*it)[1]);
  ASSERT_TRUE(products.count("PLATE"));
  auto m = import_step(file, {.build_aag = false});
  ASSERT_TRUE(m.has_value()) << m.error().message();
  ASSERT_FALSE(m->instances.empty());
  std::set<std::string> paths;
  std::map<std::string, int> count;
  for (const Instance& i : m->instances) {
    EXPECT_TRUE(products.count(i.name)) << "instance '" << i.name << "' at " << i.path;
    EXPECT_TRUE(products.count(m->parts[i.part].name)) << "part '" << m->parts[i.part].name << "'";
    EXPECT_EQ(i.path.find("=>["), std::string::npos) << i.path;
    EXPECT_TRUE(paths.insert(i.path).second) << "two instances at " << i.path;
    ++count[i.name];
  }
  // AS1: one plate, two L-brackets, one rod, six bolts, eight nuts (six on the bolts, two on the
  // rod).
  EXPECT_EQ(count, (std::map<std::string, int>{
                       {"PLATE", 1}, {"L-BRACKET", 2}, {"ROD", 1}, {"BOLT", 6}, {"NUT", 8}}));
}

}  // namespace
}  // namespace interfere::cad
