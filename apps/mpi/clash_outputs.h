// What `interfere-mpi clash` writes on rank 0 besides its JSON report, by body pairs (main.cpp) or
// by frames (series.cpp), as `interfere clash --scene` writes it (issue #31): the CSV tables and the
// summary line's stream and verdict.
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "args.h"
#include "interfere/query/verdict.h"
#include "interfere/scene/engine.h"

namespace interfere::mpi {

/// --csv, --frames-csv and --frame-pairs-csv (those given) of the merged result.
void write_clash_tables(const Options& o, const scene::Scene& s, const std::vector<scene::ClashTest>& tests,
                        const scene::SceneClashResult& result);
/// Where the summary line goes: stderr when an output is stdout ("-"), else stdout.
std::FILE* summary_stream(const Options& o);
/// The verdict as the summary line names it: clash and undecided in capitals.
std::string summary_verdict(Verdict v);

}  // namespace interfere::mpi
