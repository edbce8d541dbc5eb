// The input side of the scene layer (issue #24, items 1-2 and "Bad input"): globs (against POSIX
// fnmatch as the oracle), selectors, command-line clash tests, the JSON scene file (good files, the
// two-part form, and every bad input with the file and JSON path in the message), motion files in
// CSV and JSON (good files, and bad rows with the file, line and field).
#include <fnmatch.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <stdexcept>

#include "interfere/scene/clash_test.h"
#include "interfere/scene/io.h"

namespace interfere::scene {
namespace {

namespace fs = std::filesystem;

// ---- globs ----

TEST(SceneGlob, Basics) {
  EXPECT_TRUE(glob_match("*", ""));
  EXPECT_TRUE(glob_match("*", "anything/at all"));
  EXPECT_TRUE(glob_match("a*c", "abc"));
  EXPECT_TRUE(glob_match("a*c", "ac"));
  EXPECT_FALSE(glob_match("a*c", "ab"));
  EXPECT_FALSE(glob_match("bolt", "bolt-1"));  // the whole value
  EXPECT_FALSE(glob_match("bolt", "a-bolt"));
  EXPECT_TRUE(glob_match("*bolt*", "a-bolt-1"));
  EXPECT_TRUE(glob_match("gear-?", "gear-7"));
  EXPECT_FALSE(glob_match("gear-?", "gear-12"));
  EXPECT_TRUE(glob_match("[abc]x", "bx"));
  EXPECT_FALSE(glob_match("[abc]x", "dx"));
  EXPECT_TRUE(glob_match("r[0-9][0-9]", "r42"));
  EXPECT_FALSE(glob_match("r[0-9]", "rx"));
  EXPECT_TRUE(glob_match("[!a]", "b"));
  EXPECT_FALSE(glob_match("[!a]", "a"));
  EXPECT_TRUE(glob_match("a[!b-d]e", "aze"));
  EXPECT_FALSE(glob_match("a[!b-d]e", "ace"));
  EXPECT_TRUE(glob_match("[]]", "]"));      // ']' first in a class is a member
  EXPECT_TRUE(glob_match("[a-]", "-"));     // '-' last is a member
  EXPECT_TRUE(glob_match("x[ab", "x[ab"));  // an unclosed '[' is literal
  EXPECT_FALSE(glob_match("x[ab", "xa"));
  EXPECT_TRUE(glob_match("/Asm/*/Bolt", "/Asm/Sub/Deeper/Bolt"));  // '*' crosses '/'
}

TEST(SceneGlob, NoExponentialBacktracking) {
  // A recursive matcher takes ~C(60, 8) steps here; the iterative one O(|p|·|t|). Not timed: the
  // test would not finish in any reasonable time with exponential backtracking.
  const std::string text(60, 'a');
  EXPECT_FALSE(glob_match("a*a*a*a*a*a*a*a*b", text));
  EXPECT_TRUE(glob_match("a*a*a*a*a*a*a*a*a", text));
}

TEST(SceneGlob, AgreesWithFnmatch) {
  // Oracle: POSIX fnmatch (flags 0: '*' and '?' match any character, including '/').
  std::mt19937 rng(24);
  const char* atoms[] = {"a", "b", "c", "*", "?", "[ab]", "[!a]", "[a-b]", "**", "/"};
  const char alphabet[] = {'a', 'b', 'c', '/'};
  int positives = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    std::string pattern, text;
    const int np = static_cast<int>(rng() % 7), nt = static_cast<int>(rng() % 8);
    for (int i = 0; i < np; ++i) pattern += atoms[rng() % std::size(atoms)];
    for (int i = 0; i < nt; ++i) text += alphabet[rng() % std::size(alphabet)];
    const bool expected = fnmatch(pattern.c_str(), text.c_str(), 0) == 0;
    positives += expected;
    ASSERT_EQ(glob_match(pattern, text), expected)
        << "pattern '" << pattern << "' text '" << text << "'";
  }
  EXPECT_GT(positives, 1000);  // both outcomes exercised
}

// ---- selectors ----

std::vector<Body> bodies() {
  std::vector<Body> b(3);
  b[0].id = "bolt-1", b[0].name = "Bolt", b[0].path = "/Asm/Fasteners/Bolt",
  b[0].tags = {"fastener", "m8"};
  b[0].source = {SourceKind::mesh_file, "/data/parts/bolt.stl", ""};
  b[1].id = "plate", b[1].name = "Plate", b[1].path = "/Asm/Plate";
  b[1].source = {SourceKind::memory, "", ""};
  b[2].id = "gear-2", b[2].name = "Gear 2", b[2].path = "/Gears/Gear 2", b[2].tags = {"gear"};
  b[2].source = {SourceKind::fe_body, "model.inp", "body 2"};
  return b;
}

std::vector<std::string> selected(const std::string& text) {
  auto s = parse_selection(text);
  EXPECT_TRUE(s) << text << ": " << (s ? "" : s.error().reason);
  std::vector<std::string> out;
  if (s)
    for (const Body& b : bodies())
      if (selects(*s, b)) out.push_back(b.id);
  return out;
}

using Ids = std::vector<std::string>;

TEST(SceneSelector, ParseAndPrint) {
  auto s = Selector::parse("tag:bolt*");
  ASSERT_TRUE(s);
  EXPECT_EQ(s->kind, Selector::Kind::tag);
  EXPECT_EQ(s->pattern, "bolt*");
  EXPECT_EQ(s->to_string(), "tag:bolt*");
  auto bare = Selector::parse(" Gear* ");
  ASSERT_TRUE(bare);
  EXPECT_EQ(bare->kind, Selector::Kind::name);
  EXPECT_EQ(bare->pattern, "Gear*");
  EXPECT_EQ(bare->to_string(), "name:Gear*");
  for (const char* all : {"*", "all"}) {
    auto a = Selector::parse(all);
    ASSERT_TRUE(a);
    EXPECT_EQ(a->kind, Selector::Kind::all);
    EXPECT_EQ(a->to_string(), "all");
  }
  auto colon = Selector::parse("name:Part:1");  // a ':' in the pattern
  ASSERT_TRUE(colon);
  EXPECT_EQ(colon->pattern, "Part:1");
  for (const char* k : {"id", "name", "path", "tag", "file", "source"}) {
    auto x = Selector::parse(std::string(k) + ":p?");
    ASSERT_TRUE(x) << k;
    EXPECT_EQ(x->to_string(), std::string(k) + ":p?");
  }
  auto unknown = Selector::parse("tags:bolt");
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.error().reason.find("'tags'"), std::string::npos) << unknown.error().reason;
  EXPECT_FALSE(Selector::parse("name:"));
  EXPECT_FALSE(Selector::parse("  "));
}

TEST(SceneSelector, Matches) {
  EXPECT_EQ(selected("*"), (Ids{"bolt-1", "plate", "gear-2"}));
  EXPECT_EQ(selected("all"), (Ids{"bolt-1", "plate", "gear-2"}));
  EXPECT_EQ(selected("Plate"), (Ids{"plate"}));
  EXPECT_EQ(selected("Gear *"), (Ids{"gear-2"}));
  EXPECT_EQ(selected("id:*-?"), (Ids{"bolt-1", "gear-2"}));
  EXPECT_EQ(selected("path:/Asm/*"), (Ids{"bolt-1", "plate"}));
  EXPECT_EQ(selected("tag:m*"), (Ids{"bolt-1"}));           // any tag
  EXPECT_EQ(selected("tag:*"), (Ids{"bolt-1", "gear-2"}));  // a body without tags has none to match
  EXPECT_EQ(selected("file:bolt.stl"), (Ids{"bolt-1"}));    // the base name
  EXPECT_EQ(selected("file:/data/parts/*.stl"), (Ids{"bolt-1"}));  // the full path
  EXPECT_EQ(selected("file:*"), (Ids{"bolt-1", "gear-2"}));        // built in memory: no file
  EXPECT_EQ(selected("source:fe_body"), (Ids{"gear-2"}));
  EXPECT_EQ(selected("source:mem*"), (Ids{"plate"}));
  EXPECT_EQ(selected("tag:fastener, name:Plate"), (Ids{"bolt-1", "plate"}));  // a union
  EXPECT_EQ(selected("name:[BP]*"), (Ids{"bolt-1", "plate"}));
  EXPECT_TRUE(selected("name:bolt").empty());       // case-sensitive
  EXPECT_FALSE(selects(Selection{}, bodies()[0]));  // an empty selection selects nothing
}

TEST(SceneSelector, Selections) {
  auto s = parse_selection("name:[a,b]*, tag:x");  // a comma inside a class does not split
  ASSERT_TRUE(s);
  ASSERT_EQ(s->size(), 2u);
  EXPECT_EQ((*s)[0].pattern, "[a,b]*");
  auto empty_item = parse_selection("tag:a,,tag:b");
  ASSERT_FALSE(empty_item);
  EXPECT_NE(empty_item.error().reason.find("empty selector"), std::string::npos);
  EXPECT_FALSE(parse_selection(""));
  auto bad = parse_selection("tag:a, colour:red");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().reason.find("'colour'"), std::string::npos) << bad.error().reason;
}

// ---- clash modes and tests ----

TEST(SceneClashTest, Modes) {
  for (const ClashMode m : {ClashMode::hard, ClashMode::clearance, ClashMode::duplicates}) {
    auto p = parse_clash_mode(clash_mode_name(m));
    ASSERT_TRUE(p);
    EXPECT_EQ(*p, m);
  }
  EXPECT_STREQ(clash_mode_name(ClashMode::duplicates), "duplicates");
  auto bad = parse_clash_mode("soft");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().reason.find("'soft'"), std::string::npos);
}

TEST(SceneClashTest, ParseText) {
  auto t = parse_clash_test("tag:bolt vs tag:plate clearance 2");
  ASSERT_TRUE(t) << t.error().reason;
  EXPECT_EQ(t->name, "default");
  ASSERT_EQ(t->a.size(), 1u);
  EXPECT_EQ(t->a[0].to_string(), "tag:bolt");
  ASSERT_EQ(t->b.size(), 1u);
  EXPECT_EQ(t->b[0].to_string(), "tag:plate");
  EXPECT_EQ(t->mode, ClashMode::clearance);
  EXPECT_EQ(t->clearance, 2.0);
  EXPECT_EQ(t->tolerance, 0.0);

  auto h = parse_clash_test("hard: all hard tolerance 0.01");
  ASSERT_TRUE(h) << h.error().reason;
  EXPECT_EQ(h->name, "hard");
  ASSERT_EQ(h->a.size(), 1u);
  EXPECT_EQ(h->a[0].kind, Selector::Kind::all);
  EXPECT_TRUE(h->b.empty());
  EXPECT_EQ(h->mode, ClashMode::hard);
  EXPECT_EQ(h->tolerance, 0.01);

  auto d = parse_clash_test("name:gear* duplicates tolerance 1e-6");
  ASSERT_TRUE(d) << d.error().reason;
  EXPECT_EQ(d->a[0].to_string(), "name:gear*");
  EXPECT_EQ(d->mode, ClashMode::duplicates);
  EXPECT_EQ(d->tolerance, 1e-6);

  auto u = parse_clash_test("fits: tag:bolt, tag:nut vs tag:plate");  // a comma list with spaces
  ASSERT_TRUE(u) << u.error().reason;
  EXPECT_EQ(u->name, "fits");
  EXPECT_EQ(u->a.size(), 2u);
  EXPECT_EQ(u->mode, ClashMode::hard);
}

void expect_test_error(const std::string& text, const std::string& fragment) {
  auto t = parse_clash_test(text);
  ASSERT_FALSE(t) << text;
  EXPECT_NE(t.error().reason.find(fragment), std::string::npos)
      << text << " -> " << t.error().reason;
}

TEST(SceneClashTest, ParseErrorsNameTheToken) {
  expect_test_error("", "empty");
  expect_test_error("tag:bolt vs", "selection B");
  expect_test_error("vs tag:plate", "before 'vs'");
  expect_test_error("tag:bolt clearance", "'clearance' needs a number");
  expect_test_error("tag:bolt clearance abc", "'abc'");
  expect_test_error("tag:bolt tolerance nan", "'nan'");
  expect_test_error("tag:bolt hard frob", "'frob'");
  expect_test_error("tag:bolt hard duplicates", "'duplicates'");
  expect_test_error("tag:bolt clearance 0", "clearance > 0");
  expect_test_error("t1: tag:bolt tolerance -1", "tolerance");
  expect_test_error("t1: tag:bolt tolerance -1", "'t1'");
  expect_test_error("x: tagz:bolt", "'tagz'");
  expect_test_error(": all", "name");
}

void expect_invalid(const ClashTest& t, const std::string& fragment) {
  try {
    t.validate();
    ADD_FAILURE() << "no error, expected '" << fragment << "'";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("'" + t.name + "'"), std::string::npos) << m;
    EXPECT_NE(m.find(fragment), std::string::npos) << m;
  }
}

TEST(SceneClashTest, Validate) {
  ClashTest ok;
  ok.name = "fine";
  EXPECT_NO_THROW(ok.validate());
  ClashTest t = ok;
  t.tolerance = -1;
  expect_invalid(t, "tolerance");
  t = ok, t.tolerance = std::numeric_limits<double>::quiet_NaN();
  expect_invalid(t, "tolerance");
  t = ok, t.id_grid = std::numeric_limits<double>::infinity();
  expect_invalid(t, "id_grid");
  t = ok, t.mode = ClashMode::clearance;
  expect_invalid(t, "clearance");
  t.clearance = -2;
  expect_invalid(t, "clearance");
  t.clearance = 2;
  EXPECT_NO_THROW(t.validate());
  t.clearance_overrides.push_back({{Selector{}}, {Selector{}}, -1});
  expect_invalid(t, "override");
  t.clearance_overrides[0].clearance = 1;
  EXPECT_NO_THROW(t.validate());
  t = ok, t.a.clear();
  expect_invalid(t, "selection a");
  t = ok, t.clearance = 3;  // given, but the mode ignores it
  expect_invalid(t, "clearance");
}

// ---- files ----

struct TempDir {
  fs::path dir;
  explicit TempDir(const std::string& name) {
    dir = fs::temp_directory_path() /
          ("interfere_scene_inputs_" + std::to_string(::getpid()) + "_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = dir / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
};

std::string test_name() {
  return ::testing::UnitTest::GetInstance()->current_test_info()->name();
}

TEST(SceneFile, Good) {
  TempDir t(test_name());
  t.write("parts/bolt.stl", "solid x\nendsolid x\n");
  t.write("plate.stl", "solid x\nendsolid x\n");
  t.write("frames.csv", "frame,body,r00,r01,r02,tx,r10,r11,r12,ty,r20,r21,r22,tz\n");
  const std::string path = t.write("scene.json", R"({
    "units": "mm",
    "bodies": [
      {"file": "parts/bolt.stl", "id": "bolt-1", "name": "Bolt", "path": "/Asm/Bolt", "units": "in",
       "transform": [0, -1, 0, 10, 1, 0, 0, 20, 0, 0, 1, 30.5], "tags": ["fastener", "m8"]},
      {"file": "plate.stl", "transform": "1 0 0 0  0 1 0 0  0 0 1 -2", "select": "body*"},
      {"file": "plate.stl", "id": "plate-2"}
    ],
    "tests": [
      {"name": "hard", "a": ["tag:fastener"], "b": "name:Plate*, id:plate-2", "tolerance": 0.01},
      {"a": "*", "clearance": 2,
       "clearance_overrides": [{"a": ["tag:m8"], "b": ["id:plate*"], "clearance": 0.5}],
       "suppress": [{"a": ["tag:fastener"], "reason": "designed fit"}],
       "nominal_fits_are_contacts": false, "id_grid": 0.1},
      {"name": "dups", "mode": "duplicates", "tolerance": 1e-6}
    ],
    "motion": "frames.csv"
  })");
  auto s = read_scene_file(path);
  ASSERT_TRUE(s) << s.error().message();
  EXPECT_EQ(s->file, path);
  EXPECT_EQ(s->units, "mm");
  ASSERT_EQ(s->bodies.size(), 3u);
  const BodySpec& b0 = s->bodies[0];
  EXPECT_EQ(b0.where, path + ": bodies[0]");
  EXPECT_EQ(fs::path(b0.file), t.dir / "parts/bolt.stl");  // relative to the scene file
  EXPECT_EQ(b0.id, "bolt-1");
  EXPECT_EQ(b0.name, "Bolt");
  EXPECT_EQ(b0.path, "/Asm/Bolt");
  EXPECT_EQ(b0.units, "in");
  EXPECT_TRUE(b0.pose_given);
  EXPECT_EQ(b0.pose.r[0][1], -1.0);
  EXPECT_EQ(b0.pose.r[1][0], 1.0);
  EXPECT_EQ(b0.pose.t.x, 10.0);
  EXPECT_EQ(b0.pose.t.y, 20.0);
  EXPECT_EQ(b0.pose.t.z, 30.5);
  EXPECT_EQ(b0.tags, (std::vector<std::string>{"fastener", "m8"}));
  const BodySpec& b1 = s->bodies[1];
  EXPECT_TRUE(b1.id.empty());
  EXPECT_TRUE(b1.units.empty());
  EXPECT_TRUE(b1.pose_given);
  EXPECT_EQ(b1.pose.t.z, -2.0);
  EXPECT_EQ(b1.select, "body*");
  EXPECT_FALSE(s->bodies[2].pose_given);
  EXPECT_TRUE(s->bodies[2].pose.is_identity());
  EXPECT_EQ(fs::path(s->motion), t.dir / "frames.csv");

  ASSERT_EQ(s->tests.size(), 3u);
  const ClashTest& h = s->tests[0];
  EXPECT_EQ(h.name, "hard");
  EXPECT_EQ(h.mode, ClashMode::hard);
  EXPECT_EQ(h.tolerance, 0.01);
  ASSERT_EQ(h.a.size(), 1u);
  EXPECT_EQ(h.a[0].to_string(), "tag:fastener");
  ASSERT_EQ(h.b.size(), 2u);
  EXPECT_EQ(h.b[1].to_string(), "id:plate-2");
  const ClashTest& c = s->tests[1];
  EXPECT_EQ(c.name, "test2");               // unnamed among several: its position
  EXPECT_EQ(c.mode, ClashMode::clearance);  // a clearance alone means a clearance test
  EXPECT_EQ(c.clearance, 2.0);
  EXPECT_EQ(c.a[0].kind, Selector::Kind::all);
  EXPECT_TRUE(c.b.empty());
  ASSERT_EQ(c.clearance_overrides.size(), 1u);
  EXPECT_EQ(c.clearance_overrides[0].clearance, 0.5);
  EXPECT_EQ(c.clearance_overrides[0].b[0].to_string(), "id:plate*");
  ASSERT_EQ(c.suppressions.size(), 1u);
  EXPECT_EQ(c.suppressions[0].reason, "designed fit");
  ASSERT_EQ(c.suppressions[0].b.size(), 1u);  // "b" left out: every body
  EXPECT_EQ(c.suppressions[0].b[0].kind, Selector::Kind::all);
  EXPECT_FALSE(c.nominal_fits_are_contacts);
  EXPECT_EQ(c.id_grid, 0.1);
  EXPECT_EQ(s->tests[2].mode, ClashMode::duplicates);
  EXPECT_EQ(s->tests[2].a[0].kind, Selector::Kind::all);  // "a" left out: every body
}

TEST(SceneFile, TestsOnlyAndDefaultName) {
  TempDir t(test_name());
  const std::string path =
      t.write("tests.json", "\xEF\xBB\xBF{\"tests\": [{\"a\": [\"*\"]}]}");  // with a BOM
  auto s = read_scene_file(path);
  ASSERT_TRUE(s) << s.error().message();
  EXPECT_TRUE(s->bodies.empty());
  ASSERT_EQ(s->tests.size(), 1u);
  EXPECT_EQ(s->tests[0].name, "default");
  EXPECT_TRUE(s->units.empty());
  EXPECT_TRUE(s->motion.empty());
}

TEST(SceneFile, TwoPartForm) {
  TempDir t(test_name());
  t.write("a.stl", "x");
  t.write("sub/b.obj", "x");
  const std::string path = t.write("pair.json", R"({"units": "cm",
      "a": {"file": "a.stl", "units": "m", "transform": "1 0 0 5 0 1 0 0 0 0 1 0"},
      "b": {"file": "sub/b.obj"}})");
  auto s = read_scene_file(path);
  ASSERT_TRUE(s) << s.error().message();
  EXPECT_EQ(s->units, "cm");
  ASSERT_EQ(s->bodies.size(), 2u);
  EXPECT_EQ(s->bodies[0].id, "a");
  EXPECT_EQ(s->bodies[1].id, "b");
  EXPECT_EQ(fs::path(s->bodies[0].file), t.dir / "a.stl");
  EXPECT_EQ(fs::path(s->bodies[1].file), t.dir / "sub/b.obj");
  EXPECT_EQ(s->bodies[0].units, "m");
  EXPECT_TRUE(s->bodies[0].pose_given);
  EXPECT_EQ(s->bodies[0].pose.t.x, 5.0);
  EXPECT_FALSE(s->bodies[1].pose_given);
  EXPECT_EQ(s->bodies[0].where, path + ": a");
}

// Entries' files resolved against the scene file's folder as std::filesystem's `folder / file`
// gives them (read_scene_file joins the strings, issue #31): relative, absolute, with "..".
TEST(SceneFile, FilesResolvedAsFilesystemPaths) {
  TempDir t(test_name());
  const std::string path = t.write("scene.json", R"({"bodies": [{"file": "a.stl"}, {"file": "/abs/b.stl"},
      {"file": "sub/../c.stl"}, {"file": "./d.stl"}, {"file": "e/"}]})");
  auto s = read_scene_file(path, {.check_body_files = false});
  ASSERT_TRUE(s) << s.error().message();
  const fs::path dir = fs::path(path).parent_path();
  for (const BodySpec& b : s->bodies) EXPECT_EQ(b.file, (dir / b.given).string()) << b.given;
  EXPECT_EQ(s->bodies[1].file, "/abs/b.stl");
}

// interfere-mpi's ranks each check only their share of the entries' files (issue #31): with
// check_body_files off the scene file reads without asking for the files, and check_body_file
// then gives read_scene_file's own message for a missing file or a directory, and a file's size.
TEST(SceneFile, BodyFilesCheckedLater) {
  TempDir t(test_name());
  t.write("a.stl", "12345");
  t.write("d/x.stl", "x");
  const std::string path = t.write("scene.json", R"({"bodies": [{"file": "a.stl"}, {"file": "gone.stl"}, {"file": "d"}]})");
  auto whole = read_scene_file(path);
  ASSERT_FALSE(whole);
  auto s = read_scene_file(path, {.check_body_files = false});
  ASSERT_TRUE(s) << s.error().message();
  ASSERT_EQ(s->bodies.size(), 3u);
  EXPECT_EQ(fs::path(s->bodies[1].file), t.dir / "gone.stl");
  auto size = check_body_file(s->bodies[0]);
  ASSERT_TRUE(size) << size.error().message();
  EXPECT_EQ(*size, 5u);
  auto gone = check_body_file(s->bodies[1]);
  ASSERT_FALSE(gone);
  EXPECT_EQ(gone.error().message(), whole.error().message());  // (the first problem in file order)
  auto dir = check_body_file(s->bodies[2]);
  ASSERT_FALSE(dir);
  EXPECT_EQ(dir.error().message(), path + ": bodies[2].file: '" + (t.dir / "d").string() + "' is a directory, not a file");
}

/// The scene file `text` (in a directory holding a.stl and b.stl) fails with a message that begins
/// with the file and `json_path`, and contains `fragment`.
void expect_scene_error(const std::string& text, const std::string& json_path,
                        const std::string& fragment) {
  TempDir t(test_name());
  t.write("a.stl", "x");
  t.write("b.stl", "x");
  const std::string path = t.write("scene.json", text);
  auto s = read_scene_file(path);
  ASSERT_FALSE(s) << text;
  const std::string m = s.error().message();
  EXPECT_EQ(s.error().file, path);
  EXPECT_EQ(m.rfind(path + ": " + json_path + (json_path.empty() ? "" : ": "), 0), 0u) << m;
  EXPECT_NE(m.find(fragment), std::string::npos) << m;
}

TEST(SceneFile, UnknownKeys) {
  expect_scene_error(R"({"bodies": [], "frobnicate": 1})", "frobnicate", "unknown key");
  expect_scene_error(R"({"bodies": [{"file": "a.stl"}, {"file": "b.stl", "colour": "red"}]})",
                     "bodies[1].colour", "unknown key");
  expect_scene_error(R"({"tests": [{"name": "t", "modee": "hard"}]})", "tests[0].modee",
                     "unknown key");
  expect_scene_error(R"({"tests": [{"suppress": [{"a": "*", "why": "x"}]}]})",
                     "tests[0].suppress[0].why", "unknown key");
  expect_scene_error(R"({"a": {"file": "a.stl", "tags": []}, "b": {"file": "b.stl"}})", "a.tags",
                     "unknown key");
  expect_scene_error(R"({"a": {"file": "a.stl"}, "b": {"file": "b.stl"}, "bodies": []})", "bodies",
                     "unknown key");
}

TEST(SceneFile, MissingFiles) {
  expect_scene_error(R"({"bodies": [{"id": "x"}]})", "bodies[0]", "missing \"file\"");
  expect_scene_error(R"({"bodies": [{"file": "a.stl"}, {"file": "nothere.stl"}]})",
                     "bodies[1].file", "not found");
  expect_scene_error(R"({"bodies": [{"file": "nothere.stl"}]})", "bodies[0].file", "nothere.stl");
  expect_scene_error(R"({"bodies": [{"file": "a.stl"}], "motion": "frames.csv"})", "motion",
                     "not found");
  expect_scene_error(R"({"a": {"file": "a.stl"}, "b": {"file": "c.stl"}})", "b.file", "not found");
  expect_scene_error(R"({"a": {"file": "a.stl"}})", "b", "missing");
}

TEST(SceneFile, DuplicateIds) {
  expect_scene_error(R"({"bodies": [{"file": "a.stl", "id": "p"}, {"file": "b.stl", "id": "q"},
                                    {"file": "b.stl", "id": "p"}]})",
                     "bodies[2].id", "duplicate id 'p' (also bodies[0].id)");
  expect_scene_error(R"({"bodies": [{"file": "a.stl", "id": "a b"}]})", "bodies[0].id",
                     "characters");
  expect_scene_error(R"({"tests": [{"name": "t"}, {"name": "t"}]})", "tests[1].name",
                     "duplicate test name 't'");
  // A key twice in one object (a JSON parser keeps the last silently).
  expect_scene_error(R"({"bodies": [{"file": "a.stl", "file": "b.stl"}]})", "bodies[0].file",
                     "given twice");
  // The path of the key, built only for the message (issue #31): in arrays of arrays, and in an
  // object with many keys (the check keeps a set of them past 16).
  expect_scene_error(R"({"bodies": [], "x": [[1, {"a": 1, "b": [{"c": 0, "c": 1}]}]]})", "x[0][1].b[0].c",
                     "given twice");
  std::string many = R"({"tests": [{}, {)";
  for (int k = 0; k < 40; ++k) many += "\"k" + std::to_string(k) + "\": 0, ";
  expect_scene_error(many + R"("k7": 1}]})", "tests[1].k7", "given twice");
  expect_scene_error(many + R"("k39": 1}], "tests": []})", "tests[1].k39", "given twice");
  expect_scene_error(R"({"bodies": [{"file": "a.stl"}], "units": "mm", "units": "m"})", "units", "given twice");
}

TEST(SceneFile, WrongTypesAndValues) {
  expect_scene_error(R"([1, 2])", "", "must be an object");
  expect_scene_error(R"({"bodies": {"file": "a.stl"}})", "bodies", "must be an array");
  expect_scene_error(R"({"bodies": ["a.stl"]})", "bodies[0]", "must be an object");
  expect_scene_error(R"({"bodies": [{"file": 3}]})", "bodies[0].file", "must be a string");
  expect_scene_error(R"({"bodies": [{"file": "a.stl", "tags": ["x", 2]}]})", "bodies[0].tags[1]",
                     "must be a string");
  expect_scene_error(R"({"bodies": [{"file": "a.stl", "tags": "x"}]})", "bodies[0].tags", "array");
  expect_scene_error(R"({"units": "furlong"})", "units", "unknown unit 'furlong'");
  expect_scene_error(R"({"bodies": [{"file": "a.stl", "units": "yd"}]})", "bodies[0].units",
                     "'yd'");
  expect_scene_error(R"({"tests": [{"tolerance": "0.1"}]})", "tests[0].tolerance",
                     "must be a number");
  expect_scene_error(R"({"tests": [{"nominal_fits_are_contacts": 1}]})",
                     "tests[0].nominal_fits_are_contacts", "true or false");
  expect_scene_error(R"({"tests": [{"mode": "soft"}]})", "tests[0].mode", "'soft'");
  expect_scene_error(R"({"tests": [{"a": ["tag:x", "tagz:y"]}]})", "tests[0].a[1]", "'tagz'");
  expect_scene_error(R"({"tests": [{"a": []}]})", "tests[0].a", "empty");
  expect_scene_error(R"({"tests": [{"name": "cl", "mode": "clearance"}]})", "tests[0]",
                     "clearance > 0");
  expect_scene_error(R"({"tests": [{"name": "neg", "tolerance": -1}]})", "tests[0]", "'neg'");
  expect_scene_error(
      R"({"tests": [{"clearance": 1, "clearance_overrides": [{"a": "*", "clearance": -1}]}]})",
      "tests[0].clearance_overrides[0].clearance", ">= 0");
  expect_scene_error(R"({"tests": [{"clearance": 1, "clearance_overrides": [{"a": "*"}]}]})",
                     "tests[0].clearance_overrides[0]", "missing \"clearance\"");
}

TEST(SceneFile, Transforms) {
  expect_scene_error(
      R"({"bodies": [{"file": "a.stl", "transform": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}]})",
      "bodies[0].transform", "got 11");
  expect_scene_error(
      R"({"bodies": [{"file": "a.stl", "transform": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0]}]})",
      "bodies[0].transform", "got 13");
  expect_scene_error(
      R"({"bodies": [{"file": "a.stl", "transform": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0]}]})",
      "bodies[0].transform", "singular");
  expect_scene_error(
      R"({"bodies": [{"file": "a.stl", "transform": [1, 0, 0, 0, 0, 1, 0, "x", 0, 0, 1, 0]}]})",
      "bodies[0].transform[7]", "must be a number");
  expect_scene_error(R"({"bodies": [{"file": "a.stl"}, {"file": "b.stl", "transform": ""}]})",
                     "bodies[1].transform", "empty");
  expect_scene_error(R"({"bodies": [{"file": "a.stl", "transform": "1 0 0 0 0 1 0 0 0 0 1"}]})",
                     "bodies[0].transform", "12 numbers");
  expect_scene_error(R"({"bodies": [{"file": "a.stl", "transform": "1 0 0 0 0 1 0 0 0 0 1 inf"}]})",
                     "bodies[0].transform", "finite");
  expect_scene_error(R"({"bodies": [{"file": "a.stl", "transform": {"r": 1}}]})",
                     "bodies[0].transform", "12 numbers or a string");
  expect_scene_error(R"({"a": {"file": "a.stl", "transform": [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]},
                         "b": {"file": "b.stl"}})",
                     "a.transform", "singular");
}

TEST(SceneFile, InvalidJsonGivesTheByte) {
  TempDir t(test_name());
  const std::string path = t.write("scene.json", "{\n  \"bodies\": [,]\n}");
  auto s = read_scene_file(path);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().byte, 15);  // the ',' (0-based)
  EXPECT_EQ(s.error().line, 2);
  EXPECT_EQ(s.error().message().rfind(path + ":2: byte 15: invalid JSON", 0), 0u)
      << s.error().message();
  const std::string big = t.write("big.json", R"({"tests": [{"tolerance": 1e999}]})");
  EXPECT_FALSE(read_scene_file(big));
  auto missing = read_scene_file((t.dir / "none.json").string());
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message().find("none.json: cannot open"), std::string::npos);
}

// ---- motion ----

Scene motion_scene() {
  Scene s;
  for (const char* id : {"a", "b", "c"}) {
    Body b;
    b.id = id;
    s.bodies.push_back(b);
  }
  return s;
}

const char* kHeader = "frame,body,r00,r01,r02,tx,r10,r11,r12,ty,r20,r21,r22,tz";
const char* kIdentity = "1,0,0,0,0,1,0,0,0,0,1,0";

TEST(SceneMotion, CsvGood) {
  TempDir t(test_name());
  // BOM, CRLF, blank lines, a time column, spaces around fields.
  const std::string path =
      t.write("m.csv",
              "\xEF\xBB\xBF"
              "frame,time,body,r00,r01,r02,tx,r10,r11,r12,ty,r20,r21,r22,tz\r\n"
              "\r\n"
              "0, 0.0, a, 1,0,0,1.5, 0,1,0,0, 0,0,1,0\r\n"
              "0, 0.0, c, 0,-1,0,0, 1,0,0,0, 0,0,1,-3\r\n"
              "   \r\n"
              "2, 0.25, a, 1,0,0,2, 0,1,0,0, 0,0,1,0\r\n");
  Scene s = motion_scene();
  const Status st = read_motion(path, s);
  ASSERT_TRUE(st) << st.error().message();
  ASSERT_EQ(s.frames.size(), 2u);
  EXPECT_EQ(s.frames[0].label, "frame 0");
  EXPECT_EQ(s.frames[0].time, 0.0);
  ASSERT_EQ(s.frames[0].poses.size(), 2u);
  EXPECT_EQ(s.frames[0].poses[0].body, 0u);
  EXPECT_EQ(s.frames[0].poses[0].pose.t.x, 1.5);
  EXPECT_EQ(s.frames[0].poses[1].body, 2u);
  EXPECT_EQ(s.frames[0].poses[1].pose.r[0][1], -1.0);
  EXPECT_EQ(s.frames[0].poses[1].pose.r[1][0], 1.0);
  EXPECT_EQ(s.frames[0].poses[1].pose.t.z, -3.0);
  EXPECT_EQ(s.frames[1].label, "frame 2");
  EXPECT_EQ(s.frames[1].time, 0.25);
  ASSERT_EQ(s.frames[1].poses.size(), 1u);
  EXPECT_EQ(s.frames[1].poses[0].pose.t.x, 2.0);
}

TEST(SceneMotion, CsvWithoutTimeUsesTheFrameNumber) {
  TempDir t(test_name());
  const std::string path = t.write("m.csv", std::string(kHeader) + "\n3,b," + kIdentity + "\n7,b," +
                                                kIdentity + "\n7,a," + kIdentity);
  Scene s = motion_scene();
  const Status st = read_motion(path, s);
  ASSERT_TRUE(st) << st.error().message();
  ASSERT_EQ(s.frames.size(), 2u);
  EXPECT_EQ(s.frames[0].time, 3.0);
  EXPECT_EQ(s.frames[1].time, 7.0);
  EXPECT_EQ(s.frames[1].poses.size(), 2u);
}

/// The CSV motion `rows` (after the header without time) fail at `line` with `field` and
/// `fragment`; the scene keeps no frames.
void expect_csv_error(const std::string& rows, int line, const std::string& field,
                      const std::string& fragment, const std::string& header = kHeader) {
  TempDir t(test_name());
  const std::string path = t.write("motion.csv", header + "\n" + rows);
  Scene s = motion_scene();
  const Status st = read_motion(path, s);
  ASSERT_FALSE(st) << rows;
  const std::string m = st.error().message();
  EXPECT_EQ(m.rfind(path + ":" + std::to_string(line) + ": " + field, 0), 0u) << m;
  EXPECT_NE(m.find(fragment), std::string::npos) << m;
  EXPECT_TRUE(s.frames.empty());
}

TEST(SceneMotion, CsvBadRows) {
  const std::string id = kIdentity;
  expect_csv_error("0,a," + id + "\n0,zz," + id + "\n", 3, "body", "unknown body 'zz'");
  expect_csv_error("0,a," + id + "\n2,a," + id + "\n1,a," + id + "\n", 4, "frame",
                   "frame 1 after frame 2");
  // One frame's rows not together: frame 0 comes back after frame 1.
  expect_csv_error("0,a," + id + "\n1,a," + id + "\n0,b," + id + "\n", 4, "frame", "ascending");
  expect_csv_error("0,a," + id + "\n0,b," + id + "\n0,a," + id + "\n", 4, "body",
                   "'a' twice in frame 0 (also line 2)");
  expect_csv_error("0,a,1,0,0,0,0,1,0,0,0,0,1\n", 2, "13 fields", "expected 14");
  expect_csv_error("0,a," + id + ",5\n", 2, "15 fields", "expected 14");
  expect_csv_error("0,a,1,0,0,0,0,nan,0,0,0,0,1,0\n", 2, "r11", "'nan'");
  expect_csv_error("0,a,1,0,0,0,0,1,0,0,0,0,1,1e999\n", 2, "tz", "not a finite number");
  expect_csv_error("0,a,1,0,0,0,0,1,0,x,0,0,1,0\n", 2, "ty", "'x'");
  expect_csv_error("1.5,a," + id + "\n", 2, "frame", "not an integer");
  expect_csv_error("\n\n0,a,1,0,0,0,0,0,0,0,0,0,1,0\n", 4, "pose of body 'a'", "singular");
  expect_csv_error("0,0.1,a," + id + "\n0,0.2,b," + id + "\n", 3, "time", "differs",
                   "frame,time,body,r00,r01,r02,tx,r10,r11,r12,ty,r20,r21,r22,tz");
  expect_csv_error("0,a," + id + "\n", 1, "header", "column 2 is 'bod'",
                   "frame,bod,r00,r01,r02,tx,r10,r11,r12,ty,r20,r21,r22,tz");
  expect_csv_error("", 1, "header", "got 3 columns", "0,a,b");
}

TEST(SceneMotion, EmptyAndRepeated) {
  TempDir t(test_name());
  Scene s = motion_scene();
  const Status empty = read_motion(t.write("e.csv", "\n \n"), s);
  ASSERT_FALSE(empty);
  EXPECT_NE(empty.error().message().find("header"), std::string::npos);
  const Status rows = read_motion(t.write("h.csv", std::string(kHeader) + "\n"), s);
  ASSERT_FALSE(rows);
  EXPECT_NE(rows.error().message().find("no frames"), std::string::npos);
  const std::string good = t.write("g.csv", std::string(kHeader) + "\n0,a," + kIdentity + "\n");
  ASSERT_TRUE(read_motion(good, s));
  const Status again = read_motion(good, s);  // one motion per scene
  ASSERT_FALSE(again);
  EXPECT_NE(again.error().message().find("already has 1 frames"), std::string::npos);
}

TEST(SceneMotion, JsonGood) {
  TempDir t(test_name());
  const std::string path = t.write("m.json", R"({"frames": [
      {"frame": 0, "time": 0.5, "poses": {"b": [1, 0, 0, 4, 0, 1, 0, 0, 0, 0, 1, 0]}},
      {"frame": 1, "poses": {"a": "1 0 0 0 0 1 0 0 0 0 1 9", "c": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0]}}]})");
  Scene s = motion_scene();
  const Status st = read_motion(path, s);
  ASSERT_TRUE(st) << st.error().message();
  ASSERT_EQ(s.frames.size(), 2u);
  EXPECT_EQ(s.frames[0].label, "frame 0");
  EXPECT_EQ(s.frames[0].time, 0.5);
  ASSERT_EQ(s.frames[0].poses.size(), 1u);
  EXPECT_EQ(s.frames[0].poses[0].body, 1u);
  EXPECT_EQ(s.frames[0].poses[0].pose.t.x, 4.0);
  EXPECT_EQ(s.frames[1].time, 1.0);
  ASSERT_EQ(s.frames[1].poses.size(), 2u);
  EXPECT_EQ(s.frames[1].poses[0].body, 0u);
  EXPECT_EQ(s.frames[1].poses[0].pose.t.z, 9.0);
}

void expect_json_motion_error(const std::string& text, const std::string& json_path,
                              const std::string& fragment) {
  TempDir t(test_name());
  const std::string path = t.write("motion.json", text);
  Scene s = motion_scene();
  const Status st = read_motion(path, s);
  ASSERT_FALSE(st) << text;
  const std::string m = st.error().message();
  EXPECT_EQ(m.rfind(path + ": " + json_path + ": ", 0), 0u) << m;
  EXPECT_NE(m.find(fragment), std::string::npos) << m;
  EXPECT_TRUE(s.frames.empty());
}

TEST(SceneMotion, JsonBad) {
  const std::string id = "[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0]";
  expect_json_motion_error(R"({"frames": [{"frame": 0, "poses": {"a": )" + id +
                               R"(}}, {"frame": 1, "poses": {"zz": )" + id + "}}]}",
                           "frames[1].poses.zz", "unknown body 'zz'");
  expect_json_motion_error(R"({"frames": [{"frame": 3, "poses": {}}, {"frame": 2, "poses": {}}]})",
                           "frames[1].frame", "frame 2 after frame 3");
  expect_json_motion_error(R"({"frames": [{"frame": 3, "poses": {}}, {"frame": 3, "poses": {}}]})",
                           "frames[1].frame", "again");
  expect_json_motion_error(
      R"({"frames": [{"frame": 0, "poses": {"a": )" + id + R"(, "a": )" + id + "}}]}",
      "frames[0].poses.a", "given twice");
  expect_json_motion_error(R"({"frames": [{"frame": 0, "pose": {}}]})", "frames[0].pose",
                           "unknown key");
  expect_json_motion_error(R"({"frames": [{"frame": 0.5, "poses": {}}]})", "frames[0].frame",
                           "integer");
  expect_json_motion_error(R"({"frames": [{"frame": 0, "poses": {"a": [1, 0, 0]}}]})",
                           "frames[0].poses.a", "got 3");
  expect_json_motion_error(
      R"({"frames": [{"frame": 0, "poses": {"a": [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]}}]})",
      "frames[0].poses.a", "singular");
  expect_json_motion_error(R"({"frame": []})", "frame", "unknown key");
}

}  // namespace
}  // namespace interfere::scene
