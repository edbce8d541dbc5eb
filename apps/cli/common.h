// Shared CLI plumbing: loading posed parts, scene files, progress lines, exit codes.
#pragma once
#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "interfere/core/error.h"
#include "interfere/core/transform.h"
#include "interfere/mesh/io.h"
#include "interfere/query/model.h"

namespace CLI {
class App;
}

namespace interfere::cli {

/// Exit status (documented in the README): 0 no interference, 1 interference, 2 usage/input error.
enum ExitCode : int { kClear = 0, kInterference = 1, kInputError = 2 };

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
/// printed and kept). Throws InputError naming the file.
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
/// STEP files are read in millimetres (OCCT converts the file's units): throws InputError naming
/// the file when one is among `files` and `units` is not "mm".
void check_step_units(const std::vector<std::string>& files, const std::string& units);
PartMesh read_part_mesh(const std::string& file, const StepTessellation& tessellation = {});
bool is_step_file(const std::string& file);

struct PartSpec {
  std::string file;
  std::string transform;  ///< 12 numbers, empty = identity
};

struct LoadedPart {
  std::string file;
  std::string format;  ///< mesh_format_name, or "step"
  Transform transform;
  Model model;
  double linear_deflection = 0;         ///< PartMesh::linear_deflection (STEP inputs)
  double tessellation_deviation = -1;   ///< PartMesh::tessellation_deviation (STEP inputs, when measured)
  double read_seconds = 0, build_seconds = 0;
  std::vector<std::string> warnings;  ///< degenerate/duplicate triangles, open or non-manifold edges
};

struct ResolvedParts;

struct LoadedParts {
  LoadedPart a, b;
  double build_seconds = 0;  ///< wall time of building both models (they are built concurrently)
};

/// Reads, validates and poses (p' = R·p + t in double) both parts, A first, then builds their
/// models concurrently and collects the input warnings.
LoadedParts load_parts(const ResolvedParts& parts);

/// Fills part specs from a scene JSON file: {"a": {"file": ..., "transform": [12] | "..."}, "b": ...,
/// "units": "mm"}. Files are relative to the scene's directory. Command-line values win.
void apply_scene(const std::string& scene_path, PartSpec& a, PartSpec& b, std::string& units);

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

void check_output(const std::string& path, const std::vector<std::string>& extensions, const char* flag);
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

/// Sets the oneTBB thread count for the rest of the process (0 = all cores).
void set_threads(int threads);
int active_threads();

nlohmann::json part_json(const LoadedPart& p);
nlohmann::json stats_json(const MeshStats& s);

/// Options shared by the two-part commands (clash, distance).
struct TwoPartOptions {
  PartSpec a, b;
  std::string scene, units, json, builder = "lbvh";
  int threads = 0;
  StepTessellation tessellation;
};
/// Registers A, B, --scene, --transform-a/-b, --json, --threads, --builder, --units,
/// --linear-deflection, --angular-deflection.
void add_two_part_options(CLI::App& command, TwoPartOptions& o);

/// The two parts after the scene file, defaults and checks (files, units, builder).
struct ResolvedParts {
  PartSpec a, b;
  std::string units;
  BvhBuildOptions bvh;
  StepTessellation tessellation;
};
/// `command` is the subcommand (its name and flags, for the STEP tessellation flags).
ResolvedParts resolve_two_parts(const TwoPartOptions& o, const CLI::App& command);

/// Report fields common to the two-part commands: version, command, units, inputs, timings.
nlohmann::json two_part_report(const std::string& command, const std::string& units, const LoadedParts& parts,
                               double query_seconds, double total_seconds);

}  // namespace interfere::cli
