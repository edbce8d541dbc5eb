// Rank 0's merge (merge.h; issue #31, item 2). The order, the summaries, the frames x pairs
// summary and the grouping are the engine's own (scene::finish_result, the end of clash_scene).
#include "merge.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <stdexcept>
#include <iterator>
#include <map>
#include <set>
#include <tuple>

#include <nlohmann/json.hpp>


namespace interfere::mpi {

void add_row(scene::FrameRow& into, const scene::FrameRow& from) {
  into.label = from.label, into.time = from.time;
  into.clashes += from.clashes, into.contacts += from.contacts, into.clearances += from.clearances;
  into.undecided += from.undecided;
  if (from.min_distance >= 0) into.min_distance = into.min_distance < 0 ? from.min_distance : std::min(into.min_distance, from.min_distance);
  into.max_depth = std::max(into.max_depth, from.max_depth);
  into.verdict = worst(into.verdict, from.verdict);
}

scene::SceneClashResult merge(const scene::Scene& skeleton, const std::vector<scene::ClashTest>& tests,
                              const scene::SceneClashOptions& options, const BroadResult& broad,
                              const std::vector<std::uint64_t>& triangles, std::vector<RankResult>& ranks,
                              bool reference_checked) {
  scene::SceneClashResult result;
  result.reference_checked = reference_checked;
  result.bodies = skeleton.bodies.size();
  for (const std::uint64_t t : triangles) result.triangles += t;
  result.candidate_pairs = broad.candidate_pairs;
  result.suppressed = broad.suppressed;
  result.warnings = broad.warnings;
  const bool moving = !skeleton.frames.empty();
  if (moving) {
    result.frames.resize(skeleton.frames.size());
    for (std::size_t f = 0; f < result.frames.size(); ++f) {
      result.frames[f].frame = static_cast<std::uint32_t>(f);
      result.frames[f].label = skeleton.frames[f].label, result.frames[f].time = skeleton.frames[f].time;
    }
  }
  std::set<std::string> open;
  std::size_t clashes = 0, frame_pairs = 0, reference_pairs = 0;
  for (const RankResult& r : ranks)
    clashes += r.clashes.size(), frame_pairs += r.frame_pairs.size(), reference_pairs += r.reference_pairs.size();
  result.clashes.reserve(clashes), result.frame_pairs.reserve(frame_pairs), result.reference_pairs.reserve(reference_pairs);
  for (RankResult& r : ranks) {
    result.core_runs += r.core_runs;
    result.prepare_seconds += r.prepare_seconds, result.broad_seconds += r.broad_seconds, result.narrow_seconds += r.narrow_seconds;
    std::move(r.clashes.begin(), r.clashes.end(), std::back_inserter(result.clashes));
    result.frame_pairs.insert(result.frame_pairs.end(), r.frame_pairs.begin(), r.frame_pairs.end());
    result.reference_pairs.insert(result.reference_pairs.end(), r.reference_pairs.begin(), r.reference_pairs.end());
    r.clashes = {}, r.frame_pairs = {}, r.reference_pairs = {};
    for (std::size_t f = 0; f < r.frames.size() && f < result.frames.size(); ++f) {
      const std::string label = result.frames[f].label;
      const double time = result.frames[f].time;
      add_row(result.frames[f], r.frames[f]);
      result.frames[f].label = label, result.frames[f].time = time;
    }
    open.insert(r.warnings.begin(), r.warnings.end());
  }
  scene::finish_result(skeleton, tests, options, result);  // (the engine's order, summaries and groups)
  const auto& bodies = skeleton.bodies;
  // The engine's open-body warnings, in body order ("body '<id>' is not closed ...").
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < bodies.size(); ++i) index.emplace(bodies[i].id, i);
  std::vector<std::pair<std::size_t, std::string>> keyed;
  for (const std::string& w : open) {
    const std::size_t end = w.find("' is not closed");
    const auto it = end == std::string::npos ? index.end() : index.find(w.substr(6, end - 6));
    keyed.emplace_back(it == index.end() ? bodies.size() : it->second, w);
  }
  std::sort(keyed.begin(), keyed.end());
  for (auto& [i, w] : keyed) result.warnings.push_back(std::move(w));
  return result;
}

namespace {

nlohmann::json mpi_section(const std::vector<RankResult>& ranks, const Partition& part, const std::array<double, 2>& merge_s) {
  nlohmann::json per = nlohmann::json::array();
  for (std::size_t r = 0; r < ranks.size(); ++r) {
    nlohmann::json phases = nlohmann::json::object();
    for (std::size_t k = 0; k < kPhaseCount && k < ranks[r].phases.size(); ++k)
      phases[kPhases[k]] = {{"wall_s", ranks[r].phases[k][0]}, {"cpu_s", ranks[r].phases[k][1]}};
    per.push_back({{"rank", r},
                   {"pairs", ranks[r].pairs},
                   {"engine_calls", ranks[r].calls},
                   {"bodies_used", ranks[r].bodies_used},
                   {"body_triangles", ranks[r].body_triangles},
                   {"core_runs", ranks[r].core_runs},
                   {"bodies_read", ranks[r].bodies_loaded},
                   {"triangles_read", ranks[r].triangles_loaded},
                   {"pair_triangles", ranks[r].pair_triangles},
                   {"estimated_cost", r < part.rank_cost.size() ? part.rank_cost[r] : 0.0},
                   {"load_s", ranks[r].load_seconds},
                   {"engine_s", ranks[r].engine_seconds},
                   {"peak_rss_mb", ranks[r].peak_rss_mb},
                   {"cpu_s", ranks[r].cpu_seconds},
                   {"load_cpu_s", ranks[r].load_cpu_seconds},
                   {"engine_cpu_s", ranks[r].engine_cpu_seconds},
                   {"phases", phases}});
  }
  return {{"ranks", ranks.size()}, {"per_rank", per}, {"merge", {{"wall_s", merge_s[0]}, {"cpu_s", merge_s[1]}}}};
}

// The report through its document (parsed and written again): the reference for the text edit below.
std::string report_with_mpi_dom(const std::string& report, const std::vector<std::uint64_t>& triangles,
                                const nlohmann::json& mpi, double seconds) {
  nlohmann::json j = nlohmann::json::parse(report);
  for (std::size_t i = 0; i < triangles.size() && i < j["bodies"].size(); ++i) j["bodies"][i]["triangles"] = triangles[i];
  j["mpi"] = mpi;
  // The envelope every command's report has (apps/cli/report_envelope.cpp, docs/report.md: the
  // clash command's options and result; seconds, the process's wall time).
  j["options"] = {{"units", j["units"]}, {"threads", j["threads"]}};
  j["result"] = {{"verdict", j["verdict"]}, {"exit_status", j["exit_status"]}, {"summary", j["summary"]}};
  j["seconds"] = seconds;
  return j.dump(2) + "\n";
}

// The same edit on the text of scene::report_json (nlohmann's dump(2): top-level keys sorted, each
// at "\n  \"key\": "; a body's keys at "\n      \"key\": "; no raw line break inside a value):
// the bodies' triangle counts replaced in order, "mpi" inserted in key order, "seconds" replaced
// (report_json already writes "options" and "result" as above). Parsing and writing the 10^5-body
// product's 126 MB report again took 3-6 s on rank 0 after the job (issue #31). Empty when the text
// is not of that shape (the caller then goes through the document).
std::string report_with_mpi_text(const std::string& report, const std::vector<std::uint64_t>& triangles,
                                 const nlohmann::json& mpi, double seconds) {
  // Top-level keys and where their lines start.
  std::vector<std::pair<std::string, std::size_t>> keys;
  for (std::size_t at = report.find("\n  \""); at != std::string::npos; at = report.find("\n  \"", at + 1)) {
    const std::size_t close = report.find('"', at + 4);
    if (close == std::string::npos) return {};
    keys.emplace_back(report.substr(at + 4, close - at - 4), at);
  }
  if (!report.starts_with("{") || keys.empty() || !std::is_sorted(keys.begin(), keys.end())) return {};
  const auto section = [&](const std::string& key) -> std::pair<std::size_t, std::size_t> {  // [line start, next line start)
    for (std::size_t k = 0; k < keys.size(); ++k)
      if (keys[k].first == key) return {keys[k].second, k + 1 < keys.size() ? keys[k + 1].second : report.rfind("\n}")};
    return {std::string::npos, std::string::npos};
  };
  const auto [bodies_at, bodies_end] = section("bodies");
  const auto [seconds_at, seconds_end] = section("seconds");
  if (bodies_at == std::string::npos || seconds_at == std::string::npos || section("mpi").first != std::string::npos) return {};
  // The "mpi" entry as dump(2) writes it one level in: {"mpi": ...} without its braces.
  std::string entry = nlohmann::json{{"mpi", mpi}}.dump(2);
  entry = entry.substr(1, entry.size() - 3) + ",";  // ("{" + "\n  \"mpi\": ..." + "\n}")
  std::size_t insert_at = std::string::npos;
  for (const auto& [key, at] : keys)
    if (key > "mpi") {
      insert_at = at;
      break;
    }
  if (insert_at == std::string::npos || insert_at < bodies_end) return {};
  std::string out;
  out.reserve(report.size() + entry.size() + triangles.size() * 8);
  // Bodies: every "\n      \"triangles\": N" in order.
  const std::string field = "\n      \"triangles\": ";
  std::size_t from = 0, body = 0;
  for (std::size_t at = report.find(field, bodies_at); at != std::string::npos && at < bodies_end; at = report.find(field, at + 1)) {
    if (body >= triangles.size()) return {};
    const std::size_t value = at + field.size();
    std::size_t end = value;
    while (end < report.size() && std::isdigit(static_cast<unsigned char>(report[end]))) ++end;
    if (end == value) return {};
    out.append(report, from, value - from);
    out += std::to_string(triangles[body++]);
    from = end;
  }
  if (body != triangles.size()) return {};
  // Up to "mpi"'s place, the entry, on to "seconds", its value, the rest.
  out.append(report, from, insert_at - from);
  out += entry;
  if (seconds_at < insert_at) return {};
  const std::string seconds_key = "\n  \"seconds\": ";
  std::size_t value_end = report.find_first_of(",\n", seconds_at + seconds_key.size());
  if (value_end == std::string::npos || value_end > seconds_end) return {};
  out.append(report, insert_at, seconds_at + seconds_key.size() - insert_at);
  out += nlohmann::json(seconds).dump();
  out.append(report, value_end, std::string::npos);
  return out;
}

}  // namespace

std::string report_with_mpi(const std::string& report, const std::vector<std::uint64_t>& triangles,
                            const std::vector<RankResult>& ranks, const Partition& part, double seconds,
                            const std::array<double, 2>& merge_s) {
  const nlohmann::json mpi = mpi_section(ranks, part, merge_s);
  std::string out = report_with_mpi_text(report, triangles, mpi, seconds);
  if (out.empty() || std::getenv("INTERFERE_MPI_CHECK_REPORT_EDIT")) {
    std::string dom = report_with_mpi_dom(report, triangles, mpi, seconds);
    if (!out.empty() && out != dom) throw std::logic_error("interfere-mpi: the report's text edit differs from its document's");
    return dom;
  }
  return out;
}

}  // namespace interfere::mpi
