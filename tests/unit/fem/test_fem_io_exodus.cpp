// Exodus II dispatch (issue #26, item 1): .e/.exo go to the Exodus II library when the build has
// it (INTERFERE_WITH_EXODUS), else read_fem answers that this build has no Exodus II reader; bad
// files are errors naming the file either way. The reader itself is checked end to end on files
// meshio writes (tests/cli/test_exodus.py).
#include <gtest/gtest.h>

#include "fem_io_test_util.h"

namespace interfere::fem_test {
namespace {

TEST(FemIoExodus, FormatByNameExtensionAndContent) {
  EXPECT_EQ(fem_format_from_path("a/model.e"), FemFormat::exodus);
  EXPECT_EQ(fem_format_from_path("model.EXO"), FemFormat::exodus);
  EXPECT_EQ(fem_format_from_path("model.frd"), FemFormat::frd);
  EXPECT_EQ(fem_format_from_name("exodus"), FemFormat::exodus);
  EXPECT_EQ(fem_format_from_name("calculix"), FemFormat::frd);
  EXPECT_STREQ(fem_format_name(FemFormat::exodus), "exodus");
  // No writer for the result formats.
  FemMesh m;
  const Status st = write_fem(m, temp_dir() / "out.e");
  ASSERT_FALSE(st);
}

TEST(FemIoExodus, BadFilesAreErrorsNamingTheFile) {
  const fs::path text = temp_dir() / "not_exodus.e";
  write_text(text, "just text\n");
  Expected<FemMesh> m = read_fem(text);
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().file, text.string());
  if (fem_has_exodus_reader()) {
    EXPECT_NE(m.error().reason.find("cannot open as an Exodus II file"), std::string::npos) << m.error().message();
    Expected<FemMesh> missing = read_fem(temp_dir() / "missing.exo");
    ASSERT_FALSE(missing);
    EXPECT_NE(missing.error().reason.find("no such file"), std::string::npos) << missing.error().message();
  } else {
    EXPECT_NE(m.error().reason.find("this build has no Exodus II reader"), std::string::npos) << m.error().message();
  }
  // A netCDF signature without an extension is taken for Exodus (content sniffing).
  const fs::path sig = temp_dir() / "no_extension";
  write_text(sig, std::string("CDF\x01", 4) + std::string(60, '\0'));
  Expected<FemMesh> s = read_fem(sig);
  ASSERT_FALSE(s);
  EXPECT_TRUE(s.error().reason.find("Exodus") != std::string::npos) << s.error().message();
}

}  // namespace
}  // namespace interfere::fem_test
