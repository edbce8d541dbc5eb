// A downstream program built against the installed package (tests/CMakeLists.txt: package_consumer).
// Exit status 0 when every check holds; each failing check prints what it found.
#include <cstdio>
#include <filesystem>

#include <interfere/mesh/generate.h>
#include <interfere/query/clash.h>
#include <interfere/simplify/qem.h>
#ifdef CONSUMER_HAS_CAD
#include <interfere/cad/features.h>
#include <interfere/cad/model.h>
#endif

int main(int argc, char** argv) {
  using namespace interfere;
  int failures = 0;
  const auto check = [&](bool ok, const char* what) {
    if (!ok) std::fprintf(stderr, "consumer: %s\n", what), ++failures;
  };
  const Model a = make_model(make_box({0, 0, 0}, {1, 1, 1}));
  const Model b = make_model(make_box({0.5, 0.5, 0.5}, {2, 2, 2}));
  check(clash(a, b).cross_pairs > 0, "overlapping boxes do not clash");

  const TriMesh sphere = make_sphere({.target_triangles = 2000});
  const auto s = simplify(sphere, {.target_triangles = 200});
  check(s.has_value() && s->mesh.num_triangles() == 200, "simplify missed its budget");

#ifdef CONSUMER_HAS_CAD
  // The CAD library with its installed data (INTERFERE_DATA_DIR set by the test to the stage).
  const std::filesystem::path step =
      std::filesystem::path(argc > 1 ? argv[1] : ".") / "consumer_counterbored_plate.step";
  check(static_cast<bool>(cad::write_test_part(cad::TestPart::counterbored_plate, step)), "write_test_part failed");
  const auto model = cad::import_step(step);
  check(model.has_value() && model->parts.size() == 1, "import_step failed");
  const auto library = cad::default_feature_library();
  check(library.has_value(), "the installed feature library was not found");
  if (model && library && !model->parts.empty()) {
    const auto features = cad::recognize_features(model->parts[0].aag, *library);
    bool counterbore = false;
    for (const auto& f : features) counterbore = counterbore || f.type == "counterbored_hole";
    check(counterbore, "no counterbored hole recognised on the counterbored plate");
  }
#else
  (void)argc, (void)argv;
#endif
  return failures == 0 ? 0 : 1;
}
