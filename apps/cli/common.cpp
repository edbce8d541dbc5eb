#include "common.h"

#include "cad_exec.h"
#include "fem_surfaces.h"
#include "heap.h"

#include "interfere/core/atomic_file.h"
#include "interfere/core/coordinate_range.h"
#include "interfere/query/clash.h"
#include "interfere/core/units.h"
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

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
// Reads, validates, converts to the working unit and poses one part (p' = R·(s·p) + t in double);
// the tree is built later.
LoadedPart read_part(const PartSpec& spec, const std::string& label, const std::string& working_unit,
                     const StepTessellation& tessellation, const FemFlags* fem, TriMesh& mesh) {
  LoadedPart p;
  p.file = spec.file;
  p.unit = part_unit(spec);
  p.scale = unit_in_mm(p.unit.unit, p.unit.source) / unit_in_mm(working_unit, "--units");
  if (!spec.transform.empty()) {
    // (Checked by resolve_two_parts already; a caller that skipped it gets the same message.)
    p.transform = parse_transform(spec.transform, spec.transform_flag.empty() ? "--transform-" + std::string(label == "A" ? "a" : "b")
                                                                               : spec.transform_flag);
  }
  if (is_fem_file(spec.file)) {
    // An FE model (issue #26, item 5): the chosen body's surface at its step, as clash reads it
    // (load_fem_part); its warnings are prefixed "part A (": printed by load_parts.
    const FemFlags flags = fem ? *fem : FemFlags{};
    FemSurfaces s = read_fem_surfaces(spec.file, fem_part_options(flags, label == "A" ? 'a' : 'b'), flags.step,
                                      flags.scale, label, false);
    mesh = std::move(s.bodies.front());
    s.bodies.clear();
    p.format = s.part.format;
    p.warnings = s.part.warnings;
    p.read_seconds = s.part.read_seconds + s.part.extract_seconds;
    p.fem = std::make_shared<const FemSurfaces>(std::move(s));
  } else {
    Progress progress("reading " + label + " (" + spec.file + ")");
    PartMesh m = read_part_mesh(spec.file, tessellation);
    mesh = std::move(m.mesh);
    p.format = m.format;
    p.linear_deflection = m.linear_deflection;
    p.tessellation_deviation = m.tessellation_deviation;
    p.warnings = std::move(m.warnings);
    p.read_seconds = progress.seconds();
  }
  if (const std::string note = p.transform.non_rigid_note(); !note.empty())  // scaled, sheared, mirrored
    p.warnings.push_back("part " + label + " (" + spec.file + "): " + note);  // (printed by load_parts)
  if (p.scale != 1) {
    // Into the working unit before anything else (issue #23, item 6): queries see one unit.
    for (Vec3& v : mesh.positions) v = v * p.scale;
    p.linear_deflection *= p.scale;
    if (p.tessellation_deviation > 0) p.tessellation_deviation *= p.scale;
  }
  if (!p.transform.is_identity()) mesh = transformed(mesh, p.transform);
  if (p.scale != 1 || !p.transform.is_identity()) {
    // The coordinate range of the exact predicates (issue #23, item 7): the reader checked the
    // file's own coordinates, this the ones the queries see.
    if (const std::size_t i = first_out_of_range(mesh.positions); i < mesh.positions.size())
      throw InputError(spec.file + ": vertex " + std::to_string(i) + " (after welding), once " +
                       (p.transform.is_identity() ? "converted to " + working_unit
                                                  : "converted to " + working_unit + " and transformed") +
                       ": " + coordinate_range_reason(mesh.positions[i]));
  }
  return p;
}

// The bounding-box diagonal of a mesh (0 when empty).
double diagonal(const TriMesh& m) {
  const Aabb b = m.bounds();
  return b.empty() ? 0 : norm(b.extent());
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

LoadedParts load_parts(const ResolvedParts& parts, bool with_stats) {
  LoadedParts r;
  TriMesh ma, mb;
  {
    // Both files at once (issue #24, item 8): the readers' serial parts (the file read, the weld's
    // numbering) overlap. STEP inputs one after the other (OpenCASCADE, its own printed warnings).
    // Either way an input error names A first when both are bad.
    const auto t0 = std::chrono::steady_clock::now();
    {
      // The heap for inputs this large (heap.h): a binary STL's process peaks at about 2.6 times
      // its bytes (the file, the weld's scratch, mesh and tree); other formats differ (a hint).
      std::error_code ec;
      std::uintmax_t bytes = 0;
      for (const std::string& f : {parts.a.file, parts.b.file})
        if (const std::uintmax_t n = std::filesystem::file_size(f, ec); !ec) bytes += n;
      prepare_heap(static_cast<std::size_t>(3 * bytes));
    }
    std::exception_ptr ea, eb;
    const auto read_a = [&] {
      try {
        r.a = read_part(parts.a, "A", parts.units, parts.tessellation, parts.fem.get(), ma);
      } catch (...) {
        ea = std::current_exception();
      }
    };
    const auto read_b = [&] {
      try {
        r.b = read_part(parts.b, "B", parts.units, parts.tessellation, parts.fem.get(), mb);
      } catch (...) {
        eb = std::current_exception();
      }
    };
    if (is_step_file(parts.a.file) || is_step_file(parts.b.file)) {
      read_a();
      if (!ea) read_b();
    } else {
      tbb::parallel_invoke(read_a, read_b);
    }
    if (ea) std::rethrow_exception(ea);
    if (eb) std::rethrow_exception(eb);
    r.read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // The readers' own warnings (STEP) are printed already; the notes of the poses, in order.
    for (const auto& [p, label] : {std::pair{&r.a, "part A ("}, std::pair{&r.b, "part B ("}})
      for (const std::string& w : p->warnings)
        if (w.rfind(label, 0) == 0) warning(w);
  }
  {
    // Parts of one assembly rarely differ in size by two orders of magnitude; a unit mistake
    // (a glTF in metres beside a mesh in mm given without --units-a/-b) does.
    const double da = diagonal(ma), db = diagonal(mb);
    if (da > 0 && db > 0 && std::max(da, db) > 100 * std::min(da, db)) {
      const std::string w = fmt::format(
          "the parts' sizes differ by more than 100x (A {:g} {}, unit {} from {}; B {:g} {}, unit {} from {}): "
          "check their units (--units-a, --units-b)",
          da, parts.units, r.a.unit.unit, r.a.unit.source, db, parts.units, r.b.unit.unit, r.b.unit.source);
      r.a.warnings.push_back(w);
      warning(w);
    }
  }
  {
    Progress progress("building trees (A: " + std::to_string(ma.num_triangles()) + ", B: " +
                      std::to_string(mb.num_triangles()) + " triangles)");
    // Both trees at once (make_models): on few cores two concurrent builds beat two consecutive
    // ones. Each part's own build time is measured inside its task (the two overlap).
    tbb::parallel_invoke(
        [&] {
          const auto t0 = std::chrono::steady_clock::now();
          r.a.model = make_model(std::move(ma), parts.bvh, with_stats);
          r.a.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        },
        [&] {
          const auto t0 = std::chrono::steady_clock::now();
          r.b.model = make_model(std::move(mb), parts.bvh, with_stats);
          r.b.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        });
    r.build_seconds = progress.seconds();
  }
  if (with_stats) {
    warn_about(r.a, "A");
    warn_about(r.b, "B");
  }
  return r;
}

void add_statistics(LoadedParts& parts, bool a, bool b) {
  const auto compute = [](LoadedPart& p, bool wanted) {
    if (wanted && p.model.stats.triangles == 0 && !p.model.mesh.triangles.empty()) p.model.stats = mesh_stats(p.model.mesh);
  };
  tbb::parallel_invoke([&] { compute(parts.a, a); }, [&] { compute(parts.b, b); });
  if (a) warn_about(parts.a, "A");
  if (b) warn_about(parts.b, "B");
}

Transform parse_transform(const std::string& text, const std::string& flag) {
  auto t = Transform::parse(text);
  if (!t) throw InputError(flag + ": " + t.error().reason);
  return *t;
}

namespace {
// The transform of a scene part as the text Transform::parse reads, checked (an empty string or
// array is an error, not the identity).
std::string transform_from_json(const nlohmann::json& j, const std::string& where) {
  if (j.is_string()) {
    (void)parse_transform(j.get<std::string>(), where);
    return j.get<std::string>();
  }
  if (j.is_array()) {
    std::string s;  // JSON's own number text keeps every digit
    for (const auto& x : j) {
      if (!x.is_number()) throw InputError(where + ": transform entries must be numbers");
      s += x.dump() + " ";
    }
    (void)parse_transform(s, where);
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
    if (p.contains("transform")) {
      const std::string where = scene_path + ": part \"" + key + "\" \"transform\"";
      const std::string t = transform_from_json(p["transform"], where);  // checked even when the command line wins
      if (spec.transform.empty()) spec.transform = t, spec.transform_flag = where;
    }
    if (p.contains("units")) {
      if (!p["units"].is_string()) throw InputError(scene_path + ": part \"" + key + "\": \"units\" must be a string");
      if (spec.units.empty()) {
        spec.units = p["units"].get<std::string>();
        spec.units_flag = scene_path + ": part \"" + key + "\" \"units\"";
      }
    }
    for (const auto& [k, v] : p.items())
      if (k != "file" && k != "transform" && k != "units")
        throw InputError(scene_path + ": part \"" + key + "\": unknown key \"" + k + "\" (file, transform, units)");
  };
  for (const auto& [k, v] : j.items())
    if (k != "a" && k != "b" && k != "units")
      throw InputError(scene_path + ": unknown key \"" + k + "\" (a, b, units)");
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

void add_fail_on_option(CLI::App& command, std::string& fail_on_text) {
  command.add_option("--fail-on", fail_on_text,
                     "exit 1 also on these verdicts: contact, clearance or both, comma-separated (default: clash "
                     "only; undecided always exits 3)");
}

FailOn fail_on(const std::string& fail_on_text) {
  if (fail_on_text.empty()) return {};
  const std::optional<FailOn> f = parse_fail_on(fail_on_text);
  if (!f) throw InputError("--fail-on: unknown verdict in '" + fail_on_text + "' (clash, contact, clearance)");
  return *f;
}

void check_units(const std::string& units) { (void)unit_in_mm(units, "--units"); }

double unit_in_mm(const std::string& unit, const std::string& what) {
  const std::optional<double> mm = millimetres_per_unit(unit);
  if (!mm) throw InputError(what + ": unknown unit '" + unit + "' (" + known_units() + ")");
  return *mm;
}

PartUnit part_unit(const PartSpec& spec) {
  const std::string ext = lower_extension(spec.file);
  if (is_step_file(spec.file)) {
    if (!spec.units.empty())
      throw InputError(spec.units_flag + ": " + spec.file +
                       " is a STEP file, which carries its own length unit (read in mm): give no unit for it");
    return {"mm", "STEP file (its length unit, converted to mm)"};
  }
  if (!spec.units.empty()) {
    (void)unit_in_mm(spec.units, spec.units_flag);
    return {spec.units, "given (" + spec.units_flag + ")"};
  }
  if (ext == ".glb" || ext == ".gltf") return {"m", "glTF (metres by its specification)"};
  return {"mm", "default (mm; give --units-a/--units-b when not)"};
}

void print_clash_summary(const ClashResult& result, const std::string& units) {
  double curve_length = 0;
  for (const ClashRegion& g : result.regions) curve_length += g.curve_length;
  // The verdict first, upper case when the exit status says something is wrong (clash, undecided).
  std::string verdict = verdict_name(result.verdict);
  if (result.verdict == Verdict::clash || result.verdict == Verdict::undecided)
    for (char& ch : verdict) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  std::printf("%s: %zu pairs (%zu cross, %zu touch), %zu regions, curve length %.6g %s, containment %s",
              verdict.c_str(), result.pairs.size(), result.cross_pairs,
              result.touch_pairs, result.regions.size(), curve_length, units.c_str(),
              containment_name(result.containment));
  if (result.touching_overlap) std::printf(", the solids overlap behind touching faces");
  for (const std::string& why : result.verdict_reasons) std::printf("; undecided: %s", why.c_str());
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

namespace {
// Standard output as a report (issue #23, item 11). The first output taken as standard output
// moves the process's descriptor 1 to a new descriptor (g_report_fd) and points 1 at stderr:
// every printf of the command (summary lines) then lands on stderr, the report alone on stdout.
int g_report_fd = -1;
std::vector<std::string> g_stdout_paths;  // the paths check_output took as standard output

bool names_standard_output(const std::string& path) {
  if (path == "-") return true;
  if (g_report_fd >= 0) return false;  // (after the move, /dev/stdout would name stderr)
  struct stat out {}, st {};
  if (::fstat(STDOUT_FILENO, &out) != 0 || ::stat(path.c_str(), &st) != 0) return false;
  return out.st_dev == st.st_dev && out.st_ino == st.st_ino;
}

void claim_standard_output(const std::string& path) {
  g_stdout_paths.push_back(path);
  if (g_report_fd >= 0) return;
  std::fflush(stdout);
  g_report_fd = ::fcntl(STDOUT_FILENO, F_DUPFD_CLOEXEC, 3);
  if (g_report_fd < 0) throw InputError("cannot write a report on standard output: " + std::string(std::strerror(errno)));
  if (::dup2(STDERR_FILENO, STDOUT_FILENO) < 0)
    throw InputError("cannot move the summary to stderr: " + std::string(std::strerror(errno)));
}
}  // namespace

bool is_standard_output(const std::string& path) {
  return !path.empty() && std::find(g_stdout_paths.begin(), g_stdout_paths.end(), path) != g_stdout_paths.end();
}

Status write_output(const std::string& path, const std::function<int(std::FILE*)>& body) {
  if (is_standard_output(path)) return write_to_descriptor(g_report_fd, path == "-" ? "standard output" : path, body);
  return write_file_atomic(path, body);
}

Status write_output(const std::string& path, std::string_view content) {
  return write_output(path, [content](std::FILE* f) {
    return std::fwrite(content.data(), 1, content.size(), f) == content.size() ? 0 : (errno ? errno : EIO);
  });
}

void check_output(const std::string& path, const std::vector<std::string>& extensions, const char* flag) {
  if (path.empty()) return;
  if (path == "-" && !extensions.empty())
    throw InputError(std::string(flag) + ": '-' (standard output) is for text reports; give a file name for this output");
  if (extensions.empty() && names_standard_output(path)) {
    claim_standard_output(path);
    return;
  }
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
  // A symbolic link is written through: its final target's directory must exist too.
  const Expected<std::filesystem::path> target = resolve_output_path(p);
  if (!target) throw InputError(std::string(flag) + ": " + path + ": " + target.error().reason);
  if (*target != p) {
    const std::filesystem::path tdir = target->parent_path().empty() ? std::filesystem::path(".") : target->parent_path();
    if (!std::filesystem::is_directory(tdir))
      throw InputError(std::string(flag) + ": " + path + ": symbolic link to " + target->string() +
                       ", whose directory does not exist");
  }
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
    if (out.path == "-" || is_standard_output(out.path)) {  // one report per standard output, no input there
      for (std::size_t k = 0; k < i; ++k)
        if (outputs[k].path == "-" || is_standard_output(outputs[k].path))
          throw InputError(out.flag + " and " + outputs[k].flag + " both write to standard output: give one a file name");
      continue;
    }
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
  nlohmann::json j = {{"file", p.file}, {"format", p.format}, {"units", p.unit.unit}, {"units_source", p.unit.source},
                      {"scale_to_working_unit", p.scale}};
  if (p.model.stats.triangles > 0 || p.model.mesh.triangles.empty()) {
    j.update(stats_json(p.model.stats));
  } else {
    // Built without statistics, and no query needed them (issue #24, item 8).
    j.update({{"vertices", p.model.mesh.num_vertices()}, {"triangles", p.model.mesh.num_triangles()},
              {"statistics", "not needed"}});
  }
  if (p.fem) j["fem"] = fem_surfaces_json(*p.fem, false);  // body, displacements, step (issue #26, item 5)
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
  c.add_option("A", o.a.file, "file of part A: mesh (STL, OBJ, PLY, OFF, glTF .glb/.gltf), STEP, or FE model (.msh .bdf .nas .dat .vtk .vtu .inp .frd .e .exo: its boundary surface)");
  c.add_option("B", o.b.file, "mesh file of part B");
  c.add_option("--scene", o.scene, "JSON scene giving both parts and their transforms");
  c.add_option("--transform-a", o.a.transform, "pose of A: \"r00 r01 r02 tx r10 r11 r12 ty r20 r21 r22 tz\"");
  c.add_option("--transform-b", o.b.transform, "pose of B, same form (p' = R·p + t in double)");
  c.add_option("--json", o.json, "write the JSON report here");
  c.add_option("--threads", o.threads, "worker threads (0 = all cores)");
  c.add_option("--builder", o.builder, "tree builder: lbvh (default), lbvh_treelet, sah, median, insertion");
  c.add_option("--units", o.units,
               "working unit: every part is converted to it before any query, and the report is in it (mm, cm, "
               "m, um, in, ft; default mm)");
  c.add_option("--units-a", o.a.units,
               "unit of A's coordinates (default: metres for glTF, the file's own for STEP, mm otherwise)");
  c.add_option("--units-b", o.b.units, "unit of B's coordinates (as --units-a)");
  add_fail_on_option(c, o.fail_on);
  add_step_tessellation_options(c, o.tessellation);
}

ResolvedParts resolve_two_parts(const TwoPartOptions& o, const CLI::App& command) {
  ResolvedParts r{.a = o.a, .b = o.b, .units = o.units, .tessellation = o.tessellation};
  // Transforms given on the command line: an empty one is an error (it used to mean the identity),
  // every one is checked before any work (Transform::parse: 12 finite numbers, det R != 0).
  for (auto [spec, flag] : {std::pair{&r.a, "--transform-a"}, std::pair{&r.b, "--transform-b"}}) {
    if (command.count(flag) == 0) continue;
    spec->transform_flag = flag;
    (void)parse_transform(spec->transform, flag);
  }
  if (!o.scene.empty()) apply_scene(o.scene, r.a, r.b, r.units);
  if (r.a.file.empty() || r.b.file.empty())
    throw InputError(command.get_name() + ": two parts are needed (A B, or --scene)");
  if (r.units.empty()) r.units = "mm";
  check_units(r.units);
  if (r.a.units_flag.empty()) r.a.units_flag = "--units-a";
  if (r.b.units_flag.empty()) r.b.units_flag = "--units-b";
  (void)part_unit(r.a);  // unit errors before any work
  (void)part_unit(r.b);
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
  require_cad_for_step_files(files);  // (interfere hands a STEP run to interfere-cad here, before any output)
  t.given = c.count("--linear-deflection") + c.count("--angular-deflection") > 0;
  if (!t.given) return;
  for (const std::string& f : files)
    if (is_step_file(f)) return;
  throw InputError("--linear-deflection/--angular-deflection tessellate STEP inputs (.step, .stp); no input is one");
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
           {{"read", parts.read_seconds},
            {"build", parts.build_seconds},
            {"query", query_seconds},
            {"total", total_seconds}}}};
}

}  // namespace interfere::cli
