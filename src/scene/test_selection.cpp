// The clash tests of a scene run, chosen the same way by `interfere clash --scene`
// (apps/cli/cmd_clash_scene.cpp) and interfere-mpi (apps/mpi/main.cpp): one rule, one place.
#include <set>
#include <stdexcept>

#include "interfere/scene/io.h"

namespace interfere::scene {

Expected<std::vector<ClashTest>> select_clash_tests(const TestSelection& s) {
  std::vector<ClashTest> tests;
  for (const std::string& text : s.texts) {
    auto parsed = parse_clash_test(text);
    if (!parsed) return Error{.reason = "--test \"" + text + "\": " + parsed.error().reason};
    if (parsed->name == "default" && s.texts.size() > 1) parsed->name = "test" + std::to_string(tests.size() + 1);
    tests.push_back(std::move(*parsed));
  }
  if (!s.tests_file.empty()) {
    auto file = read_scene_file(s.tests_file);
    if (!file) return file.error();
    if (!file->bodies.empty())
      return Error{.reason = "--tests " + s.tests_file + ": a tests file holds only \"tests\" (its bodies would be ignored)"};
    tests.insert(tests.end(), file->tests.begin(), file->tests.end());
  }
  if (tests.empty()) tests = s.scene_tests;
  if (tests.empty()) {
    ClashTest t;
    t.name = "default";
    if (s.clearance > 0) t.mode = ClashMode::clearance, t.clearance = s.clearance;
    t.tolerance = s.tolerance;
    tests.push_back(t);
  } else if (s.default_options_given) {
    return Error{.reason = "--clearance/--tolerance set the default test; with --test/--tests/scene tests, give them in the tests"};
  }
  std::set<std::string> names;
  for (const ClashTest& t : tests) {
    try {
      t.validate();
    } catch (const std::invalid_argument& e) {
      return Error{.reason = e.what()};
    }
    if (!names.insert(t.name).second) return Error{.reason = "clash test '" + t.name + "': duplicate test name"};
  }
  return tests;
}

}  // namespace interfere::scene
