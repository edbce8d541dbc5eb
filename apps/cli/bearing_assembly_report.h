// The outputs of `interfere bearing --assembly` (issue #27; docs/bearing.md, "Bearing assemblies"):
// one CSV row per (frame, pair) and the JSON summary (schema_version 1, before finish_report's
// envelope). Shared by the CLI (bearing_assembly.cpp) and interfere-mpi's `bearing` (issue #31).
#pragma once
#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "interfere/bearing/assembly.h"

namespace interfere::cli {

/// The CSV (header and one row per AssemblyRow, in order); returns 0, or 1 on a write error.
int write_assembly_csv(std::FILE* f, const bearing::Assembly& as, const bearing::AssemblyResult& r);

/// The JSON summary; `threads` is the report's "threads", `status` its "exit_status".
nlohmann::json assembly_summary(const bearing::Assembly& as, const bearing::AssemblyMotion& m,
                                const bearing::AssemblyResult& r, std::uint64_t seed, int status, int threads);

}  // namespace interfere::cli
