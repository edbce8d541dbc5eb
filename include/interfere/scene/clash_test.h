// Clash tests (issue #24, item 2), as Navisworks Clash Detective, CATIA DMU and IfcClash define them:
// selection A against selection B, or all pairs within A; a mode (hard with a penetration
// tolerance, clearance with per-pair overrides, duplicates); suppression rules for designed fits.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/scene/scene.h"

namespace interfere::scene {

/// Selects bodies by one property. Text form "kind:pattern" (kind: id, name, path, tag, file,
/// source; a bare pattern is a name; "*" or "all" selects every body). Patterns are globs ('*' any
/// run of characters, '?' one character, '[abc]' a class), matched against the whole value; a
/// tag selector matches when any tag matches; file compares the file's name and its full path.
struct Selector {
  enum class Kind : std::uint8_t { all, id, name, path, tag, file, source };
  Kind kind = Kind::all;
  std::string pattern;

  static Expected<Selector> parse(std::string_view text);
  std::string to_string() const;
  bool matches(const Body& body) const;
};

/// A union of selectors (a body is selected when any selector matches). Empty selects nothing.
using Selection = std::vector<Selector>;
bool selects(const Selection& s, const Body& body);
/// Parses "sel1,sel2,..." (comma-separated selectors).
Expected<Selection> parse_selection(std::string_view text);

/// Glob match of the whole `text` ('*', '?', '[...]'; no escapes).
bool glob_match(std::string_view pattern, std::string_view text);

enum class ClashMode : std::uint8_t {
  /// Interiors overlap. A clash whose depth bound (engine.h) is at most ClashTest::tolerance is
  /// reported as a contact (a press fit or tessellation noise the user accepts). Never hides a
  /// deeper clash: the bound is an upper bound.
  hard,
  /// Also bodies apart but closer than ClashTest::clearance (or the pair's override): verdict
  /// clearance; clashes and contacts as in hard.
  clearance,
  /// The same geometry placed twice: every vertex of each body within ClashTest::tolerance of
  /// the other body's surface, and the same triangle count. Reported as clashes (the two solids
  /// coincide); other pairs are not reported.
  duplicates,
};
const char* clash_mode_name(ClashMode m);
Expected<ClashMode> parse_clash_mode(std::string_view text);

/// Pairs (one body selected by `a`, the other by `b`, either way round) whose clearance differs.
struct ClearanceOverride {
  Selection a, b;
  double clearance = 0;
};

/// Pairs (one body selected by `a`, the other by `b`, either way round) left out of the test:
/// never checked, counted in SceneClashResult::suppressed, listed with `reason` when asked.
struct Suppression {
  Selection a, b;
  std::string reason;
};

struct ClashTest {
  std::string name = "default";  ///< unique among the tests of a run; part of every clash id
  Selection a{Selector{}};       ///< default: every body
  /// Empty: all pairs within `a`; else pairs with one body in `a` and the other in `b` (a body in
  /// both is paired with every other body selected by either side, never with itself).
  Selection b;
  ClashMode mode = ClashMode::hard;
  /// hard: penetration tolerance (clashes whose depth bound is at most this are contacts);
  /// duplicates: placement tolerance. Working unit, >= 0.
  double tolerance = 0;
  double clearance = 0;  ///< clearance mode: the required clearance (> 0), working unit
  std::vector<ClearanceOverride> clearance_overrides;  ///< the first that matches a pair wins
  std::vector<Suppression> suppressions;
  /// The default suppression rule of CAD assemblies: crossings only where B-Rep faces coincide
  /// within the tessellation error are a nominal fit, reported as a contact (cad/assembly_scene.h
  /// supplies the check; mesh bodies have no B-Rep faces and are unaffected).
  bool nominal_fits_are_contacts = true;
  /// The grid (working unit) at which a clash's location is quantised for its id; 0: the
  /// tolerance when > 0, else 1 mm in the working unit.
  double id_grid = 0;

  /// Throws std::invalid_argument naming the test and the problem (negative or non-finite
  /// tolerance, clearance mode without a clearance, empty selection a).
  void validate() const;
};

/// Parses the command line's test text: "NAME: SEL_A [vs SEL_B] [hard|clearance D|duplicates] [tolerance T]"
/// or without the name, e.g. "tag:bolt vs tag:plate clearance 2", "all hard tolerance 0.01".
Expected<ClashTest> parse_clash_test(std::string_view text);

}  // namespace interfere::scene
