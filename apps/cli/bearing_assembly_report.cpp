// The outputs of `interfere bearing --assembly` (issue #27): the per-(frame, pair) CSV and the JSON
// summary, from an AssemblyResult. Split out of bearing_assembly.cpp so that interfere-mpi's
// `bearing` (issue #31, apps/mpi/bearing.cpp) writes the very same files from its merged rows.
#include "bearing_assembly_report.h"

#include <cmath>
#include <map>
#include <string>

namespace interfere::cli {
namespace {

using namespace interfere::bearing;

constexpr int kSchemaVersion = 1;

nlohmann::json vec_json(const Vec3& v) { return {v.x, v.y, v.z}; }

const char* path_name(const AssemblyPairResult& r) {
  return r.solver == AssemblySolver::standard || r.solver == AssemblySolver::raceway ||
                 r.solver == AssemblySolver::vertex
             ? analytic_path_name(r.path)
             : "-";
}

nlohmann::json verdict_counts(const std::array<std::uint64_t, 5>& c) {
  nlohmann::json j = nlohmann::json::object();
  for (std::size_t v = 0; v < c.size(); ++v) j[verdict_name(static_cast<Verdict>(v))] = c[v];
  return j;
}

nlohmann::json row_json(const Assembly& as, const AssemblyRow& row) {
  const AssemblyPair& p = as.pairs[row.pair];
  const AssemblyPairResult& x = row.result;
  return {{"frame", row.frame},
          {"pair", row.pair},
          {"kind", assembly_pair_kind_name(p.kind)},
          {"a", as.parts[p.a].id},
          {"b", as.parts[p.b].id},
          {"feature", p.feature},
          {"distance", x.distance},
          {"interference", x.distance < 0 ? -x.distance : 0.0},
          {"point_a", vec_json(x.point_a)},
          {"point_b", vec_json(x.point_b)},
          {"solver", assembly_solver_name(x.solver)},
          {"scar", x.scar},
          {"exact", x.exact},
          {"two_sided", x.two_sided},
          {"scar_part", x.scar_part == 1   ? nlohmann::json(as.parts[p.a].id)
                        : x.scar_part == 2 ? nlohmann::json(as.parts[p.b].id)
                                           : nlohmann::json(nullptr)},
          {"verdict", verdict_name(x.verdict)}};
}

}  // namespace

using namespace interfere::bearing;

int write_assembly_csv(std::FILE* f, const Assembly& as, const AssemblyResult& r) {
  std::fputs("frame,bearing,kind,a,b,distance,interference,ax,ay,az,bx,by,bz,solver,path,scar,exact,verdict,two_sided,"
             "scar_part\n",
             f);
  for (const AssemblyRow& row : r.rows) {
    const AssemblyPair& p = as.pairs[row.pair];
    const AssemblyPairResult& x = row.result;
    std::string b = as.parts[p.b].id;
    if (p.kind == AssemblyPairKind::roller_cage) b += "#web" + std::to_string(p.feature);
    if (p.kind == AssemblyPairKind::roller_rib) b += p.feature == 0 ? "#rib0" : "#rib1";
    // scar_part (issue #27): the id of the part whose scar the row measured, "-" when none
    const std::string scar_part = x.scar_part == 1 ? as.parts[p.a].id : x.scar_part == 2 ? as.parts[p.b].id : "-";
    std::fprintf(f, "%d,%s,%s,%s,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%s,%s,%d,%d,%s,%d,%s\n", row.frame,
                 as.spec.bearings[as.parts[p.a].bearing].id.c_str(), assembly_pair_kind_name(p.kind),
                 as.parts[p.a].id.c_str(), b.c_str(), x.distance, x.distance < 0 ? -x.distance : 0.0, x.point_a.x,
                 x.point_a.y, x.point_a.z, x.point_b.x, x.point_b.y, x.point_b.z, assembly_solver_name(x.solver),
                 path_name(x), x.scar ? 1 : 0, x.exact ? 1 : 0, verdict_name(x.verdict), x.two_sided ? 1 : 0,
                 scar_part.c_str());
  }
  return std::ferror(f) ? 1 : 0;
}

nlohmann::json assembly_summary(const Assembly& as, const AssemblyMotion& m, const AssemblyResult& r, std::uint64_t seed,
                                int status, int threads) {
  nlohmann::json j;
  j["schema_version"] = kSchemaVersion;
  j["version"] = INTERFERE_VERSION;
  j["command"] = "bearing";
  j["mode"] = "assembly";
  j["assembly"] = as.spec.file;
  j["motion"] = m.source;
  j["seed"] = seed;
  j["frames"] = r.frames;
  j["threads"] = threads;
  nlohmann::json bearings = nlohmann::json::array();
  for (std::size_t b = 0; b < as.spec.bearings.size(); ++b) {
    const BearingSpec& s = as.spec.bearings[b];
    int scarred = 0, pairs = 0;
    nlohmann::json raceway_scars = nlohmann::json::array();  // the scarred raceways' parts (issue #27)
    for (const AssemblyPart& p : as.parts) {
      scarred += p.bearing == static_cast<int>(b) && p.scarred;
      if (p.bearing == static_cast<int>(b) && p.raceway_scar) raceway_scars.push_back(p.id);
    }
    for (const AssemblyPair& p : as.pairs) pairs += as.parts[p.a].bearing == static_cast<int>(b);
    bearings.push_back({{"id", s.id},
                        {"type", bearing_type_name(s.type)},
                        {"rollers", s.rollers.count},
                        {"scarred_rollers", scarred},
                        {"scarred_raceways", std::move(raceway_scars)},
                        {"pitch_radius", as.geometry[b].pitch_radius},
                        {"parts", s.rollers.count + 3},
                        {"pairs", pairs}});
  }
  j["bearings"] = std::move(bearings);
  j["parts"] = as.parts.size();
  j["pairs_per_frame"] = as.pairs.size();
  // per pair kind
  struct Kind {
    std::uint64_t rows = 0;
    double min_distance = INFINITY;
    std::array<std::uint64_t, 5> verdicts{};
  };
  std::map<std::string, Kind> kinds;
  for (const AssemblyRow& row : r.rows) {
    Kind& k = kinds[assembly_pair_kind_name(as.pairs[row.pair].kind)];
    ++k.rows;
    k.min_distance = std::min(k.min_distance, row.result.distance);
    ++k.verdicts[static_cast<std::size_t>(row.result.verdict)];
  }
  nlohmann::json by_kind = nlohmann::json::object();
  for (const auto& [name, k] : kinds)
    by_kind[name] = {{"rows", k.rows}, {"min_distance", k.min_distance}, {"verdicts", verdict_counts(k.verdicts)}};
  const double dmin = r.rows.empty() ? 0.0 : r.rows[r.worst].result.distance;
  j["results"] = {{"rows", r.rows.size()},
                  {"verdicts", verdict_counts(r.verdicts)},
                  {"interfering_rows", r.interfering_rows},
                  {"scar_rows", r.scar_rows},
                  {"inexact_rows", r.inexact_rows},
                  {"min_distance", dmin},
                  {"max_interference", dmin < 0 ? -dmin : 0.0},
                  {"by_kind", std::move(by_kind)}};
  if (!r.rows.empty()) j["worst"] = row_json(as, r.rows[r.worst]);
  nlohmann::json frames = nlohmann::json::array();
  for (std::uint32_t i : r.worst_per_frame) frames.push_back(row_json(as, r.rows[i]));
  j["frame_worst"] = std::move(frames);
  j["verdict"] = verdict_name(r.verdict);
  j["exit_status"] = status;
  j["timing"] = {{"seconds", r.seconds}, {"frames_per_second", r.seconds > 0 ? r.frames / r.seconds : 0.0}};
  return j;
}

}  // namespace interfere::cli
