// scene::select_clash_tests: the one rule by which `interfere clash --scene` and interfere-mpi
// choose a run's clash tests (--test texts, --tests file, the scene file's tests, a default test).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "interfere/scene/io.h"

namespace interfere::scene {
namespace {

TEST(SelectClashTests, DefaultTestFromClearanceAndTolerance) {
  auto t = select_clash_tests({.clearance = 2.5, .tolerance = 0.01});
  ASSERT_TRUE(t) << t.error().message();
  ASSERT_EQ(t->size(), 1u);
  EXPECT_EQ((*t)[0].name, "default");
  EXPECT_EQ((*t)[0].mode, ClashMode::clearance);
  EXPECT_EQ((*t)[0].clearance, 2.5);
  EXPECT_EQ((*t)[0].tolerance, 0.01);
  auto hard = select_clash_tests({});
  ASSERT_TRUE(hard);
  EXPECT_NE((*hard)[0].mode, ClashMode::clearance);
}

TEST(SelectClashTests, TextsComeFirstAndUnnamedOnesAreNumbered) {
  ClashTest scene_test;
  scene_test.name = "from_scene";
  auto t = select_clash_tests({.texts = {"all hard", "tag:a vs tag:b clearance 1"}, .scene_tests = {scene_test}});
  ASSERT_TRUE(t) << t.error().message();
  ASSERT_EQ(t->size(), 2u);  // the scene file's tests only when nothing else is given
  EXPECT_EQ((*t)[0].name, "test1");
  EXPECT_EQ((*t)[1].name, "test2");
  EXPECT_EQ((*t)[1].clearance, 1.0);
  auto only_scene = select_clash_tests({.scene_tests = {scene_test}});
  ASSERT_TRUE(only_scene);
  ASSERT_EQ(only_scene->size(), 1u);
  EXPECT_EQ((*only_scene)[0].name, "from_scene");
}

TEST(SelectClashTests, ErrorsNameTheOptionOrFile) {
  auto bad_text = select_clash_tests({.texts = {"all clearance x"}});
  ASSERT_FALSE(bad_text);
  EXPECT_NE(bad_text.error().message().find("--test \"all clearance x\""), std::string::npos) << bad_text.error().message();

  auto both = select_clash_tests({.texts = {"all hard"}, .clearance = 1, .default_options_given = true});
  ASSERT_FALSE(both);
  EXPECT_NE(both.error().message().find("--clearance/--tolerance"), std::string::npos);

  auto dup = select_clash_tests({.texts = {"t: all hard", "t: all clearance 1"}});
  ASSERT_FALSE(dup);
  EXPECT_NE(dup.error().message().find("duplicate test name"), std::string::npos) << dup.error().message();

  const auto dir = std::filesystem::temp_directory_path() / "interfere_select_tests";
  std::filesystem::create_directories(dir);
  {
    std::ofstream(dir / "part.stl") << "solid p\nendsolid p\n";
    std::ofstream(dir / "with_bodies.json") << R"({"bodies": [{"file": "part.stl"}], "tests": [{"name": "x", "a": ["all"]}]})";
  }
  const std::string file = (dir / "with_bodies.json").string();
  auto with_bodies = select_clash_tests({.tests_file = file});
  ASSERT_FALSE(with_bodies);
  EXPECT_NE(with_bodies.error().message().find("--tests " + file + ": a tests file holds only"), std::string::npos)
      << with_bodies.error().message();
  auto missing = select_clash_tests({.tests_file = (dir / "nope.json").string()});
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message().find("nope.json"), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace interfere::scene
