// Scene sources that need only the core library (issue #24, item 1): the JSON scene file, motion
// files, mesh files and glTF scenes. STEP assemblies (cad/assembly_scene.h) and FE models
// (fem/bodies.h) are sources in their own libraries; the CLI and Python combine them.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/scene/clash_test.h"
#include "interfere/scene/scene.h"

namespace interfere::scene {

/// One entry of a scene file's "bodies": a file, or some of the bodies a multi-body file expands
/// to (a STEP assembly's instances, an FE model's bodies, a glTF scene's nodes).
struct BodySpec {
  std::string where;  ///< "scene.json: bodies[3]" (for messages)
  std::string file;   ///< resolved against the scene file's directory
  std::string given;  ///< "file" as the scene file gives it (messages: check_body_file)
  std::string id;     ///< given id (a file that expands to several bodies: a prefix, "ID/child")
  std::string name, path;
  std::string units;  ///< the file's unit; empty: by its format (mm, glTF metres, STEP its own)
  Transform pose;     ///< applied after the file's own placements (translation in the working unit)
  bool pose_given = false;
  std::vector<std::string> tags;
  /// Glob over the names of the bodies the file expands to (FE element sets or "body N", STEP
  /// instance paths, glTF node paths); empty: all.
  std::string select;
};

struct SceneSpec {
  std::string file;             ///< the scene file
  std::string units;            ///< working unit ("units"); empty: not given
  std::vector<BodySpec> bodies;
  std::vector<ClashTest> tests;  ///< "tests" (empty: not given)
  std::string motion;            ///< "motion": a motion file (CSV or JSON), resolved
};

/// Reads a scene file:
///   {"units": "mm",
///    "bodies": [{"file": "bolt.stl", "id": "bolt-1", "name": "Bolt", "path": "/Asm/Bolt",
///                "units": "mm", "transform": [12 numbers] | "12 numbers", "tags": ["fastener"],
///                "select": "glob"}, ...],
///    "tests": [{"name": "hard", "a": ["tag:fastener"], "b": ["tag:plate"], "mode": "hard",
///               "tolerance": 0.01, "clearance": 2,
///               "clearance_overrides": [{"a": [...], "b": [...], "clearance": 1}],
///               "suppress": [{"a": [...], "b": [...], "reason": "..."}],
///               "nominal_fits_are_contacts": true, "id_grid": 1}],
///    "motion": "frames.csv"}
/// The two-part form of `interfere clash --scene` ({"a": {...}, "b": {...}, "units"}) reads as
/// two bodies with ids "a" and "b". Unknown keys, wrong types, missing files and duplicate ids are
/// errors naming the file and the JSON path ("scene.json: bodies[2].transform: ...").
///
/// With `check_body_files` false the entries' files are resolved without asking the file system
/// (the motion file is still checked): a caller checks the entries it reads with check_body_file
/// (interfere-mpi: each rank its share, so that no rank stats every file of a 10^5-body product).
struct SceneFileOptions {
  bool check_body_files = true;
};
Expected<SceneSpec> read_scene_file(const std::string& path, const SceneFileOptions& options = {});

/// read_scene_file's check of an entry's file (it exists and is not a directory), with its message
/// ("scene.json: bodies[3].file: file 'x.stl' not found (looked for /dir/x.stl)"); on success the
/// file's size in bytes.
Expected<std::uintmax_t> check_body_file(const BodySpec& body);

/// Where the clash tests of a scene run come from (`interfere clash --scene`, interfere-mpi).
struct TestSelection {
  std::vector<std::string> texts;     ///< --test texts, in order
  std::string tests_file;             ///< --tests FILE: a scene file holding only "tests"
  std::vector<ClashTest> scene_tests;  ///< the scene file's "tests"
  double clearance = 0;               ///< --clearance of the default test (> 0: clearance mode)
  double tolerance = 0;               ///< --tolerance of the default test
  bool default_options_given = false;  ///< --clearance or --tolerance was on the command line
};

/// The tests of a scene run: the --test texts (several unnamed ones become "test1", "test2", ...),
/// then the tests of the --tests file, else the scene file's tests, else one test "default" from
/// clearance and tolerance. Errors (naming the option or file): a text that does not parse, a
/// tests file with bodies, --clearance/--tolerance beside explicit tests, an invalid test
/// (ClashTest::validate), a duplicate test name.
Expected<std::vector<ClashTest>> select_clash_tests(const TestSelection& selection);

/// Reads motion into `scene` (its bodies must be in place): CSV with the header
/// "frame,body,r00,r01,r02,tx,r10,r11,r12,ty,r20,r21,r22,tz" (optional column "time" after
/// "frame"), one row per body and frame, frames in ascending order (integers, consecutive rows of
/// one frame), `body` a body id; or JSON {"frames": [{"frame": 0, "time": 0.1, "poses": {"ID":
/// [12 numbers]}}]}. Errors name the file and line (or JSON path): unknown body, frame out of
/// order, a body twice in one frame, a row with too few or non-finite numbers, a singular pose.
Status read_motion(const std::string& path, Scene& scene);

/// The bodies of a glTF 2.0 scene (.glb or .gltf), one per node with a mesh (its primitives'
/// triangles, in the node's coordinates), posed by the node's world transform (the product of its
/// ancestors' matrices or TRS), named by the node's name, with path "/parent/.../node" and id the
/// path (made unique); units metres by the specification, scaled by `scale` (metres to the
/// working unit). Source ids: the triangle index within the node's mesh. A uniform scale of the
/// node's transform goes into the mesh (the pose stays rigid); a mirroring node's triangles are
/// reversed (glTF §3.7.2.1).
Expected<std::vector<Body>> read_gltf_bodies(const std::string& path, double scale = 1000.0);

}  // namespace interfere::scene
