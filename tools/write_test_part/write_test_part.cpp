// Writes one of the generated test parts (interfere::cad::TestPart, src/cad/generate.cpp) to a STEP
// file: how the bundled data/examples/casing.step is made (issue #29: the paper's casing, He & Xu
// 2023 §4, TestPart::paper_casing, its product named "casing" for data/examples/casing_process.json):
//   interfere_write_test_part paper_casing data/examples/casing.step --name casing
// and the bolted joints of tests/cli/data (write_bolted_test_assembly, the cover lifted by GAP mm):
//   interfere_write_test_part bolted_joint tests/cli/data/bolted_joint_lifted.step --gap 1e-6
// Exit status 0 on success, 2 on a usage error or a failed write (the message names the part or file).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "interfere/cad/model.h"

namespace {
int usage(const char* why) {
  std::fprintf(stderr, "interfere_write_test_part: error: %s\nusage: interfere_write_test_part PART OUT.step [--name PRODUCT]\n       interfere_write_test_part bolted_joint OUT.step [--gap MM]\nparts:", why);
  for (int i = 0; std::strcmp(interfere::cad::test_part_name(static_cast<interfere::cad::TestPart>(i)), "?") != 0; ++i)
    std::fprintf(stderr, " %s", interfere::cad::test_part_name(static_cast<interfere::cad::TestPart>(i)));
  std::fprintf(stderr, " bolted_joint");
  std::fprintf(stderr, "\n");
  return 2;
}
}  // namespace

int main(int argc, char** argv) {
  using namespace interfere::cad;
  const std::string name = argc > 1 ? argv[1] : "";
  if (name == "bolted_joint") {
    if (argc != 3 && !(argc == 5 && std::strcmp(argv[3], "--gap") == 0)) return usage("wrong arguments");
    char* end = nullptr;
    const double gap = argc == 5 ? std::strtod(argv[4], &end) : 0;
    if (argc == 5 && (end == argv[4] || *end != '\0' || !(gap >= 0))) return usage("--gap: not a length >= 0");
    const interfere::Status s = write_bolted_test_assembly(argv[2], gap);
    if (!s.ok()) {
      std::fprintf(stderr, "interfere_write_test_part: error: %s: %s\n", argv[2], s.error().reason.c_str());
      return 2;
    }
    return 0;
  }
  if (argc != 3 && !(argc == 5 && std::strcmp(argv[3], "--name") == 0)) return usage("wrong arguments");
  for (int i = 0; std::strcmp(test_part_name(static_cast<TestPart>(i)), "?") != 0; ++i) {  // (every part, in order)
    const auto part = static_cast<TestPart>(i);
    if (name != test_part_name(part)) continue;
    const interfere::Status s = argc == 5 ? write_test_part_named(part, argv[2], argv[4]) : write_test_part(part, argv[2]);
    if (!s.ok()) {
      std::fprintf(stderr, "interfere_write_test_part: error: %s: %s\n", argv[2], s.error().reason.c_str());
      return 2;
    }
    return 0;
  }
  return usage(("unknown part '" + name + "'").c_str());
}
