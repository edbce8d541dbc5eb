// One verdict model for every command, report and Python result (issue #23, item 13;
// docs/robustness.md "Verdicts"):
//   clash      the interiors overlap: surfaces cross, one solid lies inside the other, or faces
//              coincide while the solids overlap;
//   contact    the surfaces touch (faces, edges or points in common), the interiors are disjoint;
//   clearance  apart, but closer than the requested clearance;
//   clear      apart by at least the clearance (or simply apart when none was asked);
//   undecided  the engine could not decide (an open part where inside/outside matters, ray parity
//              degenerate in every direction, refinement exhausted, ...): never reported as clear.
// Ordered by severity so that the verdict of many pairs, poses or frames is the largest of theirs.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace interfere {

enum class Verdict : std::uint8_t {
  clear = 0,
  clearance = 1,
  contact = 2,
  undecided = 3,
  clash = 4
};

/// "clear", "clearance", "contact", "undecided", "clash" (the names in every JSON report).
const char* verdict_name(Verdict v);
std::optional<Verdict> verdict_from_name(std::string_view name);

/// The more severe of two verdicts (clash > undecided > contact > clearance > clear).
inline Verdict worst(Verdict a, Verdict b) {
  return a > b ? a : b;
}

/// What makes a command exit non-zero besides a clash (`--fail-on contact|clearance`).
struct FailOn {
  bool contact = false;    ///< a contact fails too
  bool clearance = false;  ///< a clearance pair fails too (implies nothing about contacts)
};
/// Parses a --fail-on value: "clash" (the default, nothing more), "contact", "clearance" or a
/// comma-separated list of them; nullopt for anything else.
std::optional<FailOn> parse_fail_on(std::string_view text);

/// The process exit status of a verdict: 1 for clash (and for contact/clearance when `fail_on`
/// says so), 3 for undecided, 0 otherwise. (2 is reserved for usage and input errors.)
int verdict_exit_status(Verdict v, const FailOn& fail_on = {});

/// A verdict with the reasons it was not simply clear (for undecided: what could not be decided).
struct VerdictReport {
  Verdict verdict = Verdict::clear;
  std::vector<std::string> reasons;
};

}  // namespace interfere
