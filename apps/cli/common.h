// Shared CLI plumbing: loading posed parts, scene files, progress lines, exit codes.
#pragma once
#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <string_view>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "interfere/core/error.h"
#include "interfere/core/transform.h"
#include "interfere/mesh/io.h"
#include "interfere/query/model.h"
#include "interfere/query/verdict.h"

namespace CLI {
class App;
}

namespace interfere::cli {

/// Exit status (documented in the README and docs/robustness.md): 0 clear, contact or clearance
/// (unless --fail-on says otherwise), 1 clash, 2 usage/input error, 3 undecided (the engine could
/// not decide: never reported as clear). interfere::verdict_exit_status maps a Verdict to it.
enum ExitCode : int { kClear = 0, kInterference = 1, kInputError = 2, kUndecided = 3 };

/// Thrown by command code for usage/input errors; main() prints it and exits with 2.
struct InputError : std::runtime_error {
  explicit InputError(const Error& e) : std::runtime_error(e.message()) {}
  explicit InputError(const std::string& m) : std::runtime_error(m) {}
};

/// A warning on stderr ("[interfere] warning: ..."): printed with --quiet too, which silences only
/// the progress lines (every warning is also in the command's JSON report).
void warning(const std::string& text);

/// Progress lines on stderr ("[interfere] reading A.stl ... 0.12 s"), silenced by --quiet.
class Progress {
 public:
  static void set_quiet(bool q) { quiet_ = q; }
  static bool quiet() { return quiet_; }
  explicit Progress(std::string what);
  ~Progress();
  double seconds() const;

 private:
  std::string what_;
  std::chrono::steady_clock::time_point start_;
  static inline bool quiet_ = false;
};

/// A part's triangles for clash, distance, check and sweep: a mesh file, or a STEP file when built
/// with OpenCASCADE (part_mesh.cpp: every instance placed, mm, welded; its import warnings are
/// printed and kept). Throws InputError naming the file, also for an FE file (is_fem_file: clash,
/// distance and check read those through fem_parts.h / fem_surfaces.h).
struct PartMesh {
  TriMesh mesh;
  std::string format;  ///< mesh_format_name, or "step"
  MeshReadInfo info;   ///< mesh files: as read_mesh reports it; STEP: vertices_before_weld only
  std::vector<std::string> warnings;
  /// STEP: the largest linear deflection its parts were tessellated with (mm; BRepMesh's tolerance
  /// on the distance of the triangles from the B-Rep surfaces); 0 for mesh files (exact as given).
  double linear_deflection = 0;
  /// STEP with StepTessellation::measure_deviation: the largest measured distance of its triangles
  /// from their surfaces (cad::Part::tessellation_deviation; BRepMesh may exceed its tolerance);
  /// -1 when not measured.
  double tessellation_deviation = -1;
};
/// The tessellation of STEP inputs (--linear-deflection, --angular-deflection; cad::ImportOptions).
struct StepTessellation {
  double linear_deflection = 0;     ///< mm; 0 = 0.1 % of each part's bounding-box diagonal
  double angular_deflection = 0.5;  ///< radians
  bool given = false;               ///< either flag was on the command line
  bool measure_deviation = false;   ///< measure PartMesh::tessellation_deviation (check, clash --conservative)
};
/// Registers --linear-deflection and --angular-deflection on a command that reads parts.
void add_step_tessellation_options(CLI::App& command, StepTessellation& t);
/// Called when the command runs: sets `given`, and throws InputError when the flags were given
/// although none of `files` is a STEP file (they would silently do nothing).
void resolve_step_tessellation(const CLI::App& command, StepTessellation& t, const std::vector<std::string>& files);
PartMesh read_part_mesh(const std::string& file, const StepTessellation& tessellation = {});
bool is_step_file(const std::string& file);

struct PartSpec {
  std::string file;
  std::string transform;  ///< 12 numbers, empty = identity (translation in the working unit)
  std::string transform_flag;  ///< where `transform` came from, for messages ("--transform-a", "scene.json: part \"a\" \"transform\"")
  /// The unit of the file's coordinates (--units-a/-b, a scene part's "units"); empty: by the
  /// format (part_unit()).
  std::string units;
  std::string units_flag;  ///< where `units` came from, for messages ("--units-a", "scene.json: part \"a\"")
};

/// The unit of a part's coordinates and where it comes from (issue #23, item 6): given
/// (--units-a/-b or the scene) wins for mesh and FEM files; glTF is in metres by its
/// specification; STEP files carry their own length unit, which OpenCASCADE converts to mm (giving
/// a unit for a STEP file is an error); other files default to mm.
struct PartUnit {
  std::string unit;    ///< mm, cm, m, um, in, ft
  std::string source;  ///< "given (--units-a)", "glTF (metres by its specification)", "STEP file", "default"
};
PartUnit part_unit(const PartSpec& spec);
/// Millimetres per unit; throws InputError naming `what` for an unknown unit.
double unit_in_mm(const std::string& unit, const std::string& what);

struct FemFlags;     // fem_surfaces.h
struct FemSurfaces;  // fem_surfaces.h

struct LoadedPart {
  std::string file;
  std::string format;  ///< mesh_format_name, or "step"
  PartUnit unit;            ///< of the file's coordinates
  double scale = 1;         ///< file units to the working unit (applied before the transform)
  Transform transform;
  Model model;
  double linear_deflection = 0;         ///< PartMesh::linear_deflection (STEP inputs)
  double tessellation_deviation = -1;   ///< PartMesh::tessellation_deviation (STEP inputs, when measured)
  double read_seconds = 0, build_seconds = 0;
  std::vector<std::string> warnings;  ///< degenerate/duplicate triangles, open or non-manifold edges
  /// An FE file (issue #26, item 5): its model, chosen body, displacements and step (the body's
  /// surface is `model`'s mesh); null for mesh and STEP files.
  std::shared_ptr<const FemSurfaces> fem;
};

struct ResolvedParts;

struct LoadedParts {
  LoadedPart a, b;
  double read_seconds = 0;   ///< wall time of reading both parts (mesh files are read concurrently)
  double build_seconds = 0;  ///< wall time of building both models (they are built concurrently)
};

/// Reads, validates, converts to the working unit `parts.units` (each part's unit: part_unit) and
/// poses (p' = R·(s·p) + t in double) both parts (concurrently, mesh files; an input error names A
/// before B), then builds their models concurrently and collects the input warnings (also: the
/// parts' sizes differ by more than 100x, a likely unit mistake). `with_stats` false: the models
/// carry no statistics (MeshStats::triangles == 0; issue #24, item 8: only a query that needs
/// closedness computes them, see add_statistics) and the statistics' input warnings are not given.
LoadedParts load_parts(const ResolvedParts& parts, bool with_stats = true);
/// Computes the statistics of the parts chosen (concurrently) where the models have none, and
/// adds their input warnings (open, non-manifold edges...), as load_parts with statistics does.
void add_statistics(LoadedParts& parts, bool a, bool b);

/// Fills part specs from a scene JSON file: {"a": {"file": ..., "transform": [12] | "...", "units":
/// "m"}, "b": ..., "units": "mm"} (top-level "units": the working unit; a part's: its file's).
/// Files are relative to the scene's directory. Command-line values win. Unknown keys are errors.
void apply_scene(const std::string& scene_path, PartSpec& a, PartSpec& b, std::string& units);
/// Transform::parse, throwing InputError "FLAG: reason" (empty, not 12 numbers, non-finite,
/// singular: issue #23, item 8).
Transform parse_transform(const std::string& text, const std::string& flag);

BvhBuilder parse_builder(const std::string& name);
void check_units(const std::string& units);

/// Checks an output path before any work: its extension (one of `extensions`, lower case with the
/// dot; empty = any) and that its directory exists. Throws InputError naming `flag`.
}  // namespace interfere::cli
namespace interfere {
struct ClashResult;
}  // namespace interfere
namespace interfere::cli {

/// The one-line result of a clash on stdout, without the line end ("INTERFERENCE: 878 pairs (878
/// cross, 0 touch), 1 regions, curve length 1.25 mm, containment none"); callers append details.
void print_clash_summary(const ClashResult& result, const std::string& units);

/// The file's extension, lower case, with its dot (".stl"; "" without one).
std::string lower_extension(const std::string& path);

/// Standard output as an output (issue #23, item 11): "-" means standard output, and so does a
/// path that names the file standard output already is (/dev/stdout, /proc/self/fd/1, or the file
/// the shell redirected it to). Text reports are then written there directly; every other line the
/// command prints on stdout (its summary) goes to stderr, so the report stays parseable. Mesh
/// outputs (check_output with an extension list) reject "-".
void check_output(const std::string& path, const std::vector<std::string>& extensions, const char* flag);
/// Whether check_output took `path` as standard output.
bool is_standard_output(const std::string& path);
/// Writes a text output: to standard output when check_output took `path` as it, otherwise
/// through write_file_atomic (a symbolic link written through, a special file written directly).
Status write_output(const std::string& path, std::string_view content);
Status write_output(const std::string& path, const std::function<int(std::FILE*)>& body);
/// A file a command reads or writes, with the flag or argument that names it ("IN", "--json").
struct NamedPath {
  std::string flag, path;
};
/// Throws InputError when an output is the same file as an input (writing it would lose the input)
/// or as another output (one would overwrite the other): the same path after `.`/`..` and symbolic
/// links are resolved, or one file under two names (hard links). Empty paths are skipped.
void check_distinct_files(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);
/// Throws InputError when a write failed.
void write_or_throw(const Status& s);

/// Registers `--fail-on clash|contact|clearance` (comma-separated; default clash) on a command
/// that reports verdicts; parse the stored text with fail_on().
void add_fail_on_option(CLI::App& command, std::string& fail_on_text);
/// The parsed --fail-on value; throws InputError on an unknown name.
FailOn fail_on(const std::string& fail_on_text);

/// Sets the oneTBB thread count for the rest of the process (0 = all cores).
void set_threads(int threads);
int active_threads();

nlohmann::json part_json(const LoadedPart& p);
nlohmann::json stats_json(const MeshStats& s);

/// Options shared by the two-part commands (clash, distance).
struct TwoPartOptions {
  PartSpec a, b;
  std::string scene, units, json, builder = "lbvh";  ///< units: the working unit (--units)
  std::string fail_on;  ///< --fail-on (fail_on())
  int threads = 0;
  StepTessellation tessellation;
};
/// Registers A, B, --scene, --transform-a/-b, --json, --threads, --builder, --units, --fail-on,
/// --linear-deflection, --angular-deflection.
void add_two_part_options(CLI::App& command, TwoPartOptions& o);

/// The two parts after the scene file, defaults and checks (files, units, builder).
struct ResolvedParts {
  PartSpec a, b;
  std::string units;
  BvhBuildOptions bvh;
  StepTessellation tessellation;
  /// FE inputs (distance; issue #26, item 5): --part/-a/-b, --disp, --field, --step, --scale...;
  /// null: the defaults (the only body, no displacements).
  std::shared_ptr<const FemFlags> fem;
};
/// `command` is the subcommand (its name and flags, for the STEP tessellation flags).
ResolvedParts resolve_two_parts(const TwoPartOptions& o, const CLI::App& command);

/// Report fields common to the two-part commands: version, command, units, inputs, timings.
nlohmann::json two_part_report(const std::string& command, const std::string& units, const LoadedParts& parts,
                               double query_seconds, double total_seconds);

}  // namespace interfere::cli
