// `interfere bearing --assembly FILE.json` (issue #27): bearing assemblies (bearing/assembly.h), the
// body of the command; cmd_bearing.cpp registers the options and dispatches here.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "view_output.h"

namespace interfere::cli {

struct BearingAssemblyOptions {
  std::string assembly, motion, out, json, fail_on;
  std::optional<int> frames, threads;
  std::optional<std::uint64_t> seed;
  std::optional<double> clearance;
  ViewOutputs views;
};

/// Runs the assembly; returns the exit status (verdict_exit_status). Throws InputError.
int run_bearing_assembly(const BearingAssemblyOptions& o);

}  // namespace interfere::cli
