#include "common.h"

#include "interfere/query/clash.h"

#include <CLI/CLI.hpp>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_invoke.h>

namespace interfere::cli {

void warning(const std::string& text) { std::fprintf(stderr, "[interfere] warning: %s\n", text.c_str()); }

Progress::Progress(std::string what) : what_(std::move(what)), start_(std::chrono::steady_clock::now()) {
  if (!quiet_) std::fprintf(stderr, "[interfere] %s ...\n", what_.c_str());
}
Progress::~Progress() {
  if (!quiet_) std::fprintf(stderr, "[interfere] %s: %.3f s\n", what_.c_str(), seconds());
}
double Progress::seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

namespace {
// Reads, validates and poses one part (p' = R·p + t in double); the tree is built later.
LoadedPart read_part(const PartSpec& spec, const std::string& label, const StepTessellation& tessellation,
                     TriMesh& mesh) {
  LoadedPart p;
  p.file = spec.file;
  if (!spec.transform.empty()) {
    auto t = Transform::parse(spec.transform);
    if (!t) throw InputError("--transform-" + label + ": " + t.error().reason);
    p.transform = *t;
  }
  {
    Progress progress("reading " + label + " (" + spec.file + ")");
    PartMesh m = read_part_mesh(spec.file, tessellation);
    mesh = std::move(m.mesh);
    p.format = m.format;
    p.linear_deflection = m.linear_deflection;
    p.tessellation_deviation = m.tessellation_deviation;
    p.warnings = std::move(m.warnings);
    p.read_seconds = progress.seconds();
  }
  if (!p.transform.is_identity()) mesh = transformed(mesh, p.transform);
  for (const Vec3& v : mesh.positions) {
    if (!is_finite(v)) throw InputError(spec.file + ": transform produced a non-finite coordinate");
  }
  return p;
}

void warn_about(LoadedPart& p, const std::string& label) {
  const MeshStats& s = p.model.stats;
  auto warn = [&](std::size_t n, const char* what) {
    if (n == 0) return;
    p.warnings.push_back("part " + label + " (" + p.file + "): " + std::to_string(n) + " " + what);
    warning(p.warnings.back());
  };
  warn(s.degenerate_triangles, "degenerate triangles (zero area; tested as segments/points)");
  warn(s.duplicate_triangles, "duplicate triangles");
  warn(s.open_edges, "open edges");
  warn(s.nonmanifold_edges, "non-manifold edges");
  warn(s.inconsistent_edges, "inconsistently oriented edges");
}
}  // namespace

LoadedParts load_parts(const ResolvedParts& parts) {
  LoadedParts r;
  TriMesh ma, mb;  // read one after the other, so an input error always names the first bad file
  r.a = read_part(parts.a, "A", parts.tessellation, ma);
  r.b = read_part(parts.b, "B", parts.tessellation, mb);
  {
    Progress progress("building trees (A: " + std::to_string(ma.num_triangles()) + ", B: " +
                      std::to_string(mb.num_triangles()) + " triangles)");
    // Both trees at once (make_models): on few cores two concurrent builds beat two consecutive
    // ones. Each part's own build time is measured inside its task (the two overlap).
    tbb::parallel_invoke(
        [&] {
          const auto t0 = std::chrono::steady_clock::now();
          r.a.model = make_model(std::move(ma), parts.bvh, true);
          r.a.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        },
        [&] {
          const auto t0 = std::chrono::steady_clock::now();
          r.b.model = make_model(std::move(mb), parts.bvh, true);
          r.b.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        });
    r.build_seconds = progress.seconds();
  }
  warn_about(r.a, "A");
  warn_about(r.b, "B");
  return r;
}

namespace {
std::string transform_from_json(const nlohmann::json& j, const std::string& where) {
  if (j.is_string()) return j.get<std::string>();
  if (j.is_array()) {
    std::string s;  // JSON's own number text keeps every digit
    for (const auto& x : j) {
      if (!x.is_number()) throw InputError(where + ": transform entries must be numbers");
      s += x.dump() + " ";
    }
    return s;
  }
  throw InputError(where + ": transform must be an array of 12 numbers or a string");
}
}  // namespace

void apply_scene(const std::string& scene_path, PartSpec& a, PartSpec& b, std::string& units) {
  std::ifstream in(scene_path);
  if (!in) throw InputError(scene_path + ": cannot open scene file");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(scene_path + ": byte " + std::to_string(e.byte) + ": invalid JSON: " + e.what());
  } catch (const nlohmann::json::exception& e) {  // a number beyond double ("9e308")
    throw InputError(scene_path + ": invalid JSON: " + e.what());
  }
  if (!j.is_object()) throw InputError(scene_path + ": scene must be a JSON object");
  const std::filesystem::path dir = std::filesystem::path(scene_path).parent_path();
  auto part = [&](const char* key, PartSpec& spec) {
    if (!j.contains(key)) throw InputError(scene_path + ": missing part \"" + key + "\"");
    const auto& p = j[key];
    if (!p.is_object() || !p.contains("file") || !p["file"].is_string()) {
      throw InputError(scene_path + ": part \"" + key + "\" needs a \"file\" string");
    }
    if (spec.file.empty()) {
      std::filesystem::path f = p["file"].get<std::string>();
      spec.file = (f.is_relative() ? dir / f : f).string();
    }
    if (spec.transform.empty() && p.contains("transform")) {
      spec.transform = transform_from_json(p["transform"], scene_path + ": part \"" + key + "\"");
    }
  };
  part("a", a);
  part("b", b);
  if (j.contains("units")) {
    if (!j["units"].is_string()) throw InputError(scene_path + ": \"units\" must be a string");
    if (units.empty()) units = j["units"].get<std::string>();
  }
}

BvhBuilder parse_builder(const std::string& name) {
  if (name == "lbvh") return BvhBuilder::lbvh;
  if (name == "lbvh_treelet" || name == "treelet") return BvhBuilder::lbvh_treelet;
  if (name == "sah" || name == "binned_sah") return BvhBuilder::binned_sah;
  if (name == "median" || name == "median_split") return BvhBuilder::median_split;
  if (name == "insertion") return BvhBuilder::insertion;
  throw InputError("--builder: unknown builder '" + name + "' (lbvh, lbvh_treelet, sah, median, insertion)");
}

void check_units(const std::string& units) {
  for (const char* u : {"mm", "cm", "m", "um", "in", "ft"}) {
    if (units == u) return;
  }
  throw InputError("--units: unknown unit '" + units + "' (mm, cm, m, um, in, ft)");
}

void print_clash_summary(const ClashResult& result, const std::string& units) {
  double curve_length = 0;
  for (const ClashRegion& g : result.regions) curve_length += g.curve_length;
  std::printf("%s: %zu pairs (%zu cross, %zu touch), %zu regions, curve length %.6g %s, containment %s",
              result.interference() ? "INTERFERENCE" : "clear", result.pairs.size(), result.cross_pairs,
              result.touch_pairs, result.regions.size(), curve_length, units.c_str(),
              containment_name(result.containment));
  if (result.touching_overlap) std::printf(", the solids overlap behind touching faces");
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

void check_output(const std::string& path, const std::vector<std::string>& extensions, const char* flag) {
  if (path.empty()) return;
  const std::filesystem::path p(path);
  const std::string ext = lower_extension(path);
  bool ok = extensions.empty();
  for (const std::string& e : extensions) ok |= ext == e;
  if (!ok) throw InputError(std::string(flag) + ": " + path + ": unsupported extension '" + ext + "'");
  const std::filesystem::path dir = p.parent_path().empty() ? std::filesystem::path(".") : p.parent_path();
  if (!std::filesystem::is_directory(dir)) {
    throw InputError(std::string(flag) + ": " + path + ": directory does not exist");
  }
  if (std::filesystem::is_directory(p)) throw InputError(std::string(flag) + ": " + path + ": is a directory");
}

namespace {
bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (std::filesystem::exists(a, ec) && std::filesystem::exists(b, ec)) {
    const bool same = std::filesystem::equivalent(a, b, ec);
    if (!ec) return same;
  }
  const auto canonical = [](const std::string& p) {
    std::error_code e;
    auto c = std::filesystem::weakly_canonical(std::filesystem::absolute(p, e), e);
    return e ? std::filesystem::absolute(p, e).lexically_normal() : c;
  };
  return canonical(a) == canonical(b);
}
}  // namespace

void check_distinct_files(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const NamedPath& out = outputs[i];
    if (out.path.empty()) continue;
    for (const NamedPath& in : inputs)
      if (!in.path.empty() && same_file(out.path, in.path))
        throw InputError(out.flag + ": " + out.path + " is the input file of " + in.flag +
                         ": writing it would lose the input; write elsewhere");
    for (std::size_t k = 0; k < i; ++k)
      if (!outputs[k].path.empty() && same_file(out.path, outputs[k].path))
        throw InputError(out.flag + ": " + out.path + " is also the file of " + outputs[k].flag +
                         ": one would overwrite the other");
  }
}

void write_or_throw(const Status& s) {
  if (!s) throw InputError(s.error());
}

namespace {
std::unique_ptr<tbb::global_control> g_threads;
}

void set_threads(int threads) {
  if (threads < 0) throw InputError("--threads must be >= 0 (0 = all cores)");
  const int n = threads == 0 ? tbb::info::default_concurrency() : threads;
  g_threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, n);
}

int active_threads() {
  return static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

nlohmann::json stats_json(const MeshStats& s) {
  return {{"vertices", s.vertices},
          {"triangles", s.triangles},
          {"degenerate_triangles", s.degenerate_triangles},
          {"duplicate_triangles", s.duplicate_triangles},
          {"open_edges", s.open_edges},
          {"nonmanifold_edges", s.nonmanifold_edges},
          {"inconsistent_edges", s.inconsistent_edges},
          {"components", s.components},
          {"closed", s.closed()}};
}

nlohmann::json part_json(const LoadedPart& p) {
  nlohmann::json j = {{"file", p.file}, {"format", p.format}};
  j.update(stats_json(p.model.stats));
  if (p.format == "step") {
    j["linear_deflection"] = p.linear_deflection;
    if (p.tessellation_deviation >= 0) j["tessellation_deviation"] = p.tessellation_deviation;
  }
  j.update({{"transform", p.transform.to_row_major()},
            {"read_seconds", p.read_seconds},
            {"build_seconds", p.build_seconds}});
  return j;
}

void add_two_part_options(CLI::App& c, TwoPartOptions& o) {
  c.add_option("A", o.a.file, "mesh file of part A (STL, OBJ, PLY, OFF, glTF .glb/.gltf, STEP; clash also takes FEM files: .msh .bdf .nas .dat .vtk .vtu .inp)");
  c.add_option("B", o.b.file, "mesh file of part B");
  c.add_option("--scene", o.scene, "JSON scene giving both parts and their transforms");
  c.add_option("--transform-a", o.a.transform, "pose of A: \"r00 r01 r02 tx r10 r11 r12 ty r20 r21 r22 tz\"");
  c.add_option("--transform-b", o.b.transform, "pose of B, same form (p' = R·p + t in double)");
  c.add_option("--json", o.json, "write the JSON report here");
  c.add_option("--threads", o.threads, "worker threads (0 = all cores)");
  c.add_option("--builder", o.builder, "tree builder: lbvh (default), lbvh_treelet, sah, median, insertion");
  c.add_option("--units", o.units, "length unit of the inputs, reported (mm, cm, m, um, in, ft)");
  add_step_tessellation_options(c, o.tessellation);
}

ResolvedParts resolve_two_parts(const TwoPartOptions& o, const CLI::App& command) {
  ResolvedParts r{.a = o.a, .b = o.b, .units = o.units, .tessellation = o.tessellation};
  if (!o.scene.empty()) apply_scene(o.scene, r.a, r.b, r.units);
  if (r.a.file.empty() || r.b.file.empty())
    throw InputError(command.get_name() + ": two parts are needed (A B, or --scene)");
  if (r.units.empty()) r.units = "mm";
  check_units(r.units);
  check_step_units({r.a.file, r.b.file}, r.units);
  resolve_step_tessellation(command, r.tessellation, {r.a.file, r.b.file});
  r.bvh.builder = parse_builder(o.builder);
  return r;
}

void add_step_tessellation_options(CLI::App& c, StepTessellation& t) {
  c.add_option("--linear-deflection", t.linear_deflection,
               "STEP inputs: tessellation linear deflection, mm (0 = 0.1 % of each part's diagonal)");
  c.add_option("--angular-deflection", t.angular_deflection, "STEP inputs: tessellation angular deflection, radians");
}

void resolve_step_tessellation(const CLI::App& c, StepTessellation& t, const std::vector<std::string>& files) {
  t.given = c.count("--linear-deflection") + c.count("--angular-deflection") > 0;
  if (!t.given) return;
  for (const std::string& f : files)
    if (is_step_file(f)) return;
  throw InputError("--linear-deflection/--angular-deflection tessellate STEP inputs (.step, .stp); no input is one");
}

void check_step_units(const std::vector<std::string>& files, const std::string& units) {
  if (units == "mm") return;
  for (const std::string& f : files)
    if (is_step_file(f))
      throw InputError(f + ": STEP input is read in millimetres (OpenCASCADE converts the file's units); --units is " +
                       units + ": give --units mm and meshes in millimetres");
}

nlohmann::json two_part_report(const std::string& command, const std::string& units, const LoadedParts& parts,
                               double query_seconds, double total_seconds) {
  const LoadedPart& a = parts.a;
  const LoadedPart& b = parts.b;
  return {{"interfere_version", INTERFERE_VERSION},
          {"command", command},
          {"units", units},
          {"inputs", {{"a", part_json(a)}, {"b", part_json(b)}}},
          {"input_warnings", [&] {
             std::vector<std::string> w = a.warnings;
             w.insert(w.end(), b.warnings.begin(), b.warnings.end());
             return w;
           }()},
          {"timings_s",
           {{"read", a.read_seconds + b.read_seconds},
            {"build", parts.build_seconds},
            {"query", query_seconds},
            {"total", total_seconds}}}};
}

}  // namespace interfere::cli
