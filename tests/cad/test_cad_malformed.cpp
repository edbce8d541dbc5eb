// Malformed STEP files (issue #6, "Bad input": unreadable STEP; the project's rule "never a crash"):
// OCCT 7.6's reader dereferences null handles on some broken references and recurses without end
// along reference cycles. Each case is made from a generated part's file and must give a clear
// error naming the file and the line or entity — not a crash, and not a model missing a part.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "cad_test_util.h"
#include "interfere/cad/model.h"

namespace interfere::cad {
namespace {

std::filesystem::path dir() { return testing::scratch_dir("interfere_cad_malformed"); }

std::string plate_text() {
  static std::string text;
  if (text.empty()) {
    const auto f = dir() / "plate.step";
    EXPECT_TRUE(write_test_part(TestPart::counterbored_plate, f).ok());
    std::ifstream in(f);
    std::stringstream ss;
    ss << in.rdbuf();
    text = ss.str();
  }
  return text;
}

Expected<CadModel> import_text(const std::string& name, const std::string& text) {
  const auto f = dir() / name;
  std::ofstream(f, std::ios::binary) << text;
  return import_step(f);
}

// The file's first "#<a> = ORIENTED_EDGE('',*,*,#<b>" with its match.
std::smatch oriented_edge(const std::string& text) {
  std::smatch m;
  EXPECT_TRUE(std::regex_search(text, m, std::regex(R"(#(\d+) = ORIENTED_EDGE\('',\*,\*,#(\d+))")));
  return m;
}

TEST(CadMalformed, TheGeneratedFileReadsCleanly) {
  const auto m = import_text("ok.step", plate_text());
  ASSERT_TRUE(m.has_value()) << m.error().message();
  EXPECT_TRUE(m->warnings.empty());
  EXPECT_EQ(m->parts.size(), 1u);
}

// BRepMesh throws on deflections below Precision::Confusion() / Precision::Angular(): the options
// are checked first, with the valid range in the message.
TEST(CadMalformed, DeflectionsOutOfRangeAreErrors) {
  const auto f = dir() / "plate_ok.step";
  std::ofstream(f, std::ios::binary) << plate_text();
  for (double lin : {-1.0, 1e-9, std::nan("")}) {
    const auto m = import_step(f, {.linear_deflection = lin});
    ASSERT_FALSE(m.has_value()) << lin;
    EXPECT_NE(m.error().reason.find("linear deflection"), std::string::npos);
  }
  for (double ang : {0.0, -0.5, 4.0}) {
    const auto m = import_step(f, {.angular_deflection = ang});
    ASSERT_FALSE(m.has_value()) << ang;
    EXPECT_NE(m.error().reason.find("angular deflection"), std::string::npos);
  }
  EXPECT_TRUE(import_step(f, {.linear_deflection = 0.05, .angular_deflection = 0.3}).has_value());
}

TEST(CadMalformed, TruncatedFileNamesTheLine) {
  const std::string t = plate_text();
  const auto m = import_text("truncated.step", t.substr(0, t.size() * 6 / 10));
  ASSERT_FALSE(m.has_value());
  EXPECT_NE(m.error().file.find("truncated.step"), std::string::npos);
  EXPECT_NE(m.error().reason.find("Line"), std::string::npos) << m.error().reason;
}

TEST(CadMalformed, SyntaxErrorNamesTheLine) {
  std::string t = plate_text();
  const std::size_t at = t.find("#30 =");
  ASSERT_NE(at, std::string::npos);
  t.insert(at, "#30 = = FOO;\n");
  const auto m = import_text("syntax.step", t);
  ASSERT_FALSE(m.has_value());
  EXPECT_NE(m.error().reason.find("malformed STEP file"), std::string::npos) << m.error().reason;
  EXPECT_NE(m.error().reason.find("Line"), std::string::npos) << m.error().reason;
}

TEST(CadMalformed, UnresolvedReferenceIsAnErrorNotAMissingPart) {
  const std::string t = plate_text();
  const std::smatch e = oriented_edge(t);
  const std::string bad = t.substr(0, e.position(2)) + "99999" + t.substr(e.position(2) + e.length(2));
  const auto m = import_text("unresolved.step", bad);
  ASSERT_FALSE(m.has_value());
  EXPECT_NE(m.error().reason.find("Unresolved Reference"), std::string::npos) << m.error().reason;
  EXPECT_NE(m.error().reason.find("99999"), std::string::npos) << m.error().reason;
}

// An oriented edge whose edge is itself: OCCT's entity check recursed until the stack overflowed
// (SIGSEGV). The cycle is found before any OCCT check runs.
TEST(CadMalformed, ReferenceCycleIsAnErrorNotAStackOverflow) {
  const std::string t = plate_text();
  const std::smatch e = oriented_edge(t);
  const std::string self = e[1].str();
  const std::string bad = t.substr(0, e.position(2)) + self + t.substr(e.position(2) + e.length(2));
  const auto m = import_text("cycle.step", bad);
  ASSERT_FALSE(m.has_value());
  EXPECT_NE(m.error().reason.find("cycle"), std::string::npos) << m.error().reason;
  EXPECT_NE(m.error().reason.find("#" + self), std::string::npos) << m.error().reason;
}

// A reference to an entity of the wrong type (a point where an edge belongs): OCCT's translator
// dereferenced a null handle (SIGSEGV in StepToGeom); now a signal converted to an exception, or a
// failed entity reported as a warning — never a crash or a silently incomplete model.
TEST(CadMalformed, MistypedReferencesAreErrorsOrWarningsNeverCrashes) {
  const std::string t = plate_text();
  std::smatch p;
  ASSERT_TRUE(std::regex_search(t, p, std::regex(R"(#(\d+) = CARTESIAN_POINT)")));
  std::size_t cases = 0;
  const std::regex edge(R"(#(\d+) = ORIENTED_EDGE\('',\*,\*,#(\d+))");
  for (std::sregex_iterator it(t.begin(), t.end(), edge), end;
       it != end && cases < 6; ++it, ++cases) {
    const std::smatch& e = *it;
    const std::string bad = t.substr(0, e.position(2)) + p[1].str() + t.substr(e.position(2) + e.length(2));
    const auto m = import_text("mistyped_" + std::to_string(cases) + ".step", bad);
    if (m.has_value()) {
      EXPECT_FALSE(m->warnings.empty()) << "a broken edge read without a warning";
    } else {
      EXPECT_FALSE(m.error().reason.empty());
    }
  }
  EXPECT_EQ(cases, 6u);
}

}  // namespace
}  // namespace interfere::cad
