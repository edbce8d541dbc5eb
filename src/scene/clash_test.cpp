// Clash tests and selectors (include/interfere/scene/clash_test.h; issue #24, item 2): the text
// forms of selectors, selections and command-line tests, glob matching, and test validation.
#include "interfere/scene/clash_test.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "interfere/core/text_cells.h"

namespace interfere::scene {
namespace {

struct KindName {
  Selector::Kind kind;
  const char* name;
};
constexpr KindName kKinds[] = {{Selector::Kind::id, "id"},     {Selector::Kind::name, "name"},
                               {Selector::Kind::path, "path"}, {Selector::Kind::tag, "tag"},
                               {Selector::Kind::file, "file"}, {Selector::Kind::source, "source"}};

/// Matches one bracket expression starting at pattern[p] == '[' against `c`. Returns the index
/// after the closing ']' and sets `hit`; npos when the bracket is not closed (then '[' is literal).
std::size_t match_class(std::string_view pattern, std::size_t p, char c, bool& hit) {
  std::size_t i = p + 1;
  bool negate = false;
  if (i < pattern.size() && (pattern[i] == '!' || pattern[i] == '^')) negate = true, ++i;
  bool found = false;
  bool first = true;  // a ']' right after '[' or '[!' is a member (POSIX)
  for (; i < pattern.size(); first = false) {
    const char lo = pattern[i];
    if (lo == ']' && !first) {
      hit = found != negate;
      return i + 1;
    }
    if (i + 2 < pattern.size() && pattern[i + 1] == '-' && pattern[i + 2] != ']') {
      const auto l = static_cast<unsigned char>(lo), h = static_cast<unsigned char>(pattern[i + 2]),
                 x = static_cast<unsigned char>(c);
      found = found || (l <= x && x <= h);
      i += 3;
    } else {
      found = found || lo == c;
      ++i;
    }
  }
  return std::string_view::npos;
}

}  // namespace

bool glob_match(std::string_view pattern, std::string_view text) {
  // Iterative matching with one backtrack point, the last '*' seen (as in Krauss, "Matching
  // wildcards", Dr. Dobb's 2008): a later '*' subsumes every earlier choice, so at most
  // O(|pattern|·|text|) steps and never exponential.
  std::size_t p = 0, t = 0;
  std::size_t star = std::string_view::npos, star_t = 0;
  while (t < text.size()) {
    if (p < pattern.size()) {
      const char pc = pattern[p];
      if (pc == '*') {
        star = p++;
        star_t = t;
        continue;
      }
      if (pc == '?') {
        ++p, ++t;
        continue;
      }
      if (pc == '[') {
        bool hit = false;
        const std::size_t next = match_class(pattern, p, text[t], hit);
        if (next != std::string_view::npos) {
          if (hit) {
            p = next, ++t;
            continue;
          }
        } else if (text[t] == '[') {  // unclosed: a literal '['
          ++p, ++t;
          continue;
        }
      } else if (pc == text[t]) {
        ++p, ++t;
        continue;
      }
    }
    if (star == std::string_view::npos) return false;
    p = star + 1;  // let the last '*' absorb one more character
    t = ++star_t;
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

Expected<Selector> Selector::parse(std::string_view text) {
  const std::string_view s = trim_blanks(text);
  if (s.empty())
    return Error{.reason = "empty selector (give \"*\", \"kind:pattern\" or a name glob)"};
  if (s == "*" || s == "all") return Selector{};
  const std::size_t colon = s.find(':');
  if (colon == std::string_view::npos) return Selector{Kind::name, std::string(s)};
  const std::string_view kind = trim_blanks(s.substr(0, colon));
  const std::string_view pattern = trim_blanks(s.substr(colon + 1));
  for (const KindName& k : kKinds) {
    if (kind != k.name) continue;
    if (pattern.empty())
      return Error{.reason =
                       "selector '" + std::string(s) + "': empty pattern after '" + k.name + ":'"};
    return Selector{k.kind, std::string(pattern)};
  }
  return Error{.reason =
                   "selector '" + std::string(s) + "': unknown kind '" + std::string(kind) +
                   "' (id, name, path, tag, file, source; write name:PATTERN for a name with ':')"};
}

std::string Selector::to_string() const {
  if (kind == Kind::all) return "all";
  for (const KindName& k : kKinds)
    if (k.kind == kind) return std::string(k.name) + ":" + pattern;
  return "?";
}

bool Selector::matches(const Body& body) const {
  switch (kind) {
    case Kind::all:
      return true;
    case Kind::id:
      return glob_match(pattern, body.id);
    case Kind::name:
      return glob_match(pattern, body.name);
    case Kind::path:
      return glob_match(pattern, body.path);
    case Kind::tag:
      for (const std::string& t : body.tags)
        if (glob_match(pattern, t)) return true;
      return false;
    case Kind::file: {
      if (body.source.file.empty()) return false;  // built in memory: no file to match
      const std::string base = std::filesystem::path(body.source.file).filename().string();
      return glob_match(pattern, base) || glob_match(pattern, body.source.file);
    }
    case Kind::source:
      return glob_match(pattern, source_kind_name(body.source.kind));
  }
  return false;
}

bool selects(const Selection& s, const Body& body) {
  for (const Selector& x : s)
    if (x.matches(body)) return true;
  return false;
}

Expected<Selection> parse_selection(std::string_view text) {
  Selection out;
  if (trim_blanks(text).empty()) return Error{.reason = "empty selection (give \"*\" for every body)"};
  // Split at commas outside bracket expressions ("name:[a,b]*" is one selector).
  std::size_t start = 0;
  bool in_class = false;
  for (std::size_t i = 0; i <= text.size(); ++i) {
    if (i < text.size()) {
      const char c = text[i];
      if (c == '[' && !in_class) {
        in_class = text.find(']', i + 1) != std::string_view::npos;
        continue;
      }
      if (c == ']' && in_class) {
        in_class = false;
        continue;
      }
      if (c != ',' || in_class) continue;
    }
    const std::string_view item = text.substr(start, i - start);
    if (trim_blanks(item).empty())
      return Error{.reason = "selection '" + std::string(trim_blanks(text)) +
                             "': empty selector between commas"};
    auto s = Selector::parse(item);
    if (!s) return s.error();
    out.push_back(std::move(*s));
    start = i + 1;
  }
  return out;
}

const char* clash_mode_name(ClashMode m) {
  switch (m) {
    case ClashMode::hard:
      return "hard";
    case ClashMode::clearance:
      return "clearance";
    case ClashMode::duplicates:
      return "duplicates";
  }
  return "?";
}

Expected<ClashMode> parse_clash_mode(std::string_view text) {
  const std::string_view s = trim_blanks(text);
  for (const ClashMode m : {ClashMode::hard, ClashMode::clearance, ClashMode::duplicates})
    if (s == clash_mode_name(m)) return m;
  return Error{.reason =
                   "unknown clash mode '" + std::string(s) + "' (hard, clearance, duplicates)"};
}

void ClashTest::validate() const {
  const std::string where = "clash test '" + name + "'";
  auto fail = [&](const std::string& what) { throw std::invalid_argument(where + ": " + what); };
  if (name.empty()) throw std::invalid_argument("clash test: empty name");
  auto check = [&](double v, const char* what) {
    if (!std::isfinite(v) || v < 0)
      fail(std::string(what) + " must be a finite number >= 0 (got " + short_number(v) + ")");
  };
  check(tolerance, "tolerance");
  check(clearance, "clearance");
  check(id_grid, "id_grid");
  if (a.empty()) fail("selection a is empty (it would select no body; \"*\" selects every body)");
  if (mode == ClashMode::clearance && !(clearance > 0))
    fail("clearance mode needs a clearance > 0 (\"clearance D\")");
  if (mode != ClashMode::clearance && clearance != 0)
    fail("a clearance of " + short_number(clearance) + " is given but the mode is " +
         clash_mode_name(mode) + " (use mode clearance)");
  if (mode != ClashMode::clearance && !clearance_overrides.empty())
    fail(std::string("clearance overrides apply in clearance mode only (the mode is ") +
         clash_mode_name(mode) + ")");
  for (std::size_t i = 0; i < clearance_overrides.size(); ++i) {
    const ClearanceOverride& o = clearance_overrides[i];
    const std::string w = "clearance override " + std::to_string(i + 1);
    if (!std::isfinite(o.clearance) || o.clearance < 0)
      fail(w + ": clearance must be a finite number >= 0 (got " + short_number(o.clearance) + ")");
    if (o.a.empty() || o.b.empty()) fail(w + ": empty selection (it would match no pair)");
  }
  for (std::size_t i = 0; i < suppressions.size(); ++i)
    if (suppressions[i].a.empty() || suppressions[i].b.empty())
      fail("suppression " + std::to_string(i + 1) + ": empty selection (it would match no pair)");
}

Expected<ClashTest> parse_clash_test(std::string_view text) {
  // "NAME: SEL_A [vs SEL_B] [hard|clearance D|duplicates] [tolerance T]"
  std::vector<std::string_view> tokens;
  for (std::size_t i = 0; i < text.size();) {
    while (i < text.size() &&
           (text[i] == ' ' || text[i] == '\t' || text[i] == '\r' || text[i] == '\n'))
      ++i;
    const std::size_t start = i;
    while (i < text.size() &&
           !(text[i] == ' ' || text[i] == '\t' || text[i] == '\r' || text[i] == '\n'))
      ++i;
    if (i > start) tokens.push_back(text.substr(start, i - start));
  }
  const std::string grammar =
      " (NAME: SEL_A [vs SEL_B] [hard|clearance D|duplicates] [tolerance T])";
  if (tokens.empty()) return Error{.reason = "empty clash test" + grammar};
  ClashTest t;
  std::size_t k = 0;
  if (tokens[0].back() == ':') {
    const std::string_view name = tokens[0].substr(0, tokens[0].size() - 1);
    if (name.empty()) return Error{.reason = "empty test name before ':'" + grammar};
    t.name = std::string(name);
    ++k;
  }
  auto keyword = [](std::string_view w) {
    return w == "vs" || w == "hard" || w == "clearance" || w == "duplicates" || w == "tolerance";
  };
  // A selection: the tokens up to the next keyword, rejoined (comma lists may have spaces).
  auto selection = [&](const char* what, const char* after) -> Expected<Selection> {
    std::string joined;
    while (k < tokens.size() && !keyword(tokens[k]))
      joined += (joined.empty() ? "" : " ") + std::string(tokens[k++]);
    if (joined.empty())
      return Error{.reason = std::string("no selection ") + what +
                             (k < tokens.size() ? " before '" + std::string(tokens[k]) + "'"
                                                : std::string(after)) +
                             grammar};
    auto s = parse_selection(joined);
    if (!s) return Error{.reason = std::string("selection ") + what + ": " + s.error().reason};
    return s;
  };
  auto number = [&](const char* what, double& out) -> Status {
    if (k >= tokens.size())
      return Error{.reason = std::string("'") + what + "' needs a number" + grammar};
    if (!parse_finite_cell(tokens[k], out))
      return Error{.reason = std::string("'") + what + "' needs a finite number, not '" +
                             std::string(tokens[k]) + "'"};
    ++k;
    return {};
  };
  auto a = selection("A", " (the test is empty)");
  if (!a) return a.error();
  t.a = std::move(*a);
  if (k < tokens.size() && tokens[k] == "vs") {
    ++k;
    auto b = selection("B", " after 'vs'");
    if (!b) return b.error();
    t.b = std::move(*b);
  }
  bool mode_given = false, tolerance_given = false;
  while (k < tokens.size()) {
    const std::string_view w = tokens[k++];
    if (w == "hard" || w == "clearance" || w == "duplicates") {
      if (mode_given)
        return Error{.reason = "a second mode '" + std::string(w) + "' (the test has one mode)"};
      mode_given = true;
      t.mode = *parse_clash_mode(w);
      if (t.mode == ClashMode::clearance)
        if (Status s = number("clearance", t.clearance); !s) return s.error();
    } else if (w == "tolerance") {
      if (tolerance_given) return Error{.reason = "'tolerance' given twice"};
      tolerance_given = true;
      if (Status s = number("tolerance", t.tolerance); !s) return s.error();
    } else if (w == "vs") {
      return Error{.reason =
                       "'vs' must follow selection A, before the mode and tolerance" + grammar};
    } else {
      return Error{.reason = "unexpected '" + std::string(w) + "'" + grammar};
    }
  }
  try {
    t.validate();
  } catch (const std::invalid_argument& e) {
    return Error{.reason = e.what()};
  }
  return t;
}

}  // namespace interfere::scene
