// Deterministic generated scenes (issue #24, item 9): a bolted assembly of many bodies and a moving
// variant of it, for the scene benchmarks (bench/bench_scene.cpp), tests and Python. Every part is
// a closed, consistently outward triangle mesh shared by all bodies of its type; bodies differ by
// their pose only. All coordinates in mm.
//
// One joint (on a square grid of joints, pitch = plate width + plate_gap):
//   plate   two square plates with a round hole, stacked (bottom z in [0, t], top z in [t, 2t]):
//           their common face is a designed contact (identical triangles, opposite orientation)
//   bolt    a headed shaft through both holes (radial clearance hole - shaft)
//   washer  one under the bolt head on the top plate, one under the bottom plate: face contacts
//   nut     hexagonal, under the bottom washer: face contact (radial clearance to the shaft)
//   bracket an L-bracket standing on the top plate, clear of the washer: face contact
// so a joint has 7 bodies with 6 designed face contacts and only clearance gaps elsewhere. The
// default resolution (48 segments around every circle) makes about 1,000 triangles per body:
// about 10^7 triangles for the default 10,000 bodies.
// Real clashes (AssemblyGenOptions::clashes joints, spread over the grid): in turn a bolt shifted
// sideways by 1 mm into its plates (clashes with both plates, both washers and the nut), a bracket
// sunk 1 mm into its plate, a bracket pushed into the top washer. Clearance gaps
// (AssemblyGenOptions::gaps joints): a bracket lifted by gap_height above its plate.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "interfere/scene/scene.h"

namespace interfere::scene {

/// The dimensions of one joint (mm). Defaults: M10-like bolt in 5 mm plates.
struct JointDims {
  double plate_width = 40, plate_thickness = 5, hole_radius = 5.5;
  double shaft_radius = 5, head_radius = 8, head_height = 5, shaft_protrusion = 2;
  double washer_inner = 5.3, washer_outer = 9, washer_thickness = 2;
  double nut_inner = 5.2, nut_apothem = 8,
         nut_thickness = 6;  ///< apothem: half the width across flats
  /// L-bracket: a base leg (bracket_width x bracket_thickness) and a vertical leg
  /// (bracket_thickness x bracket_height) in its profile, extruded by bracket_length; placed at x
  /// in [4, 16] and y in [10, 18] of the joint (clear of the washer and the bolt head).
  double bracket_width = 12, bracket_thickness = 2, bracket_height = 10, bracket_length = 8;
  double plate_gap = 1;  ///< between neighbouring joints' plates
};

struct AssemblyGenOptions {
  std::size_t bodies = 10000;  ///< the last joint is cut short when not a multiple of 7
  /// Segments around every circle (a multiple of 24, so that the square plate's and the hexagonal
  /// nut's corners are vertices); also sets the radial and axial subdivisions. 48 gives about
  /// 1,000 triangles per body.
  int segments = 48;
  std::size_t clashes = 300;  ///< joints given a real clash (at most one per joint)
  std::size_t gaps = 100;  ///< joints whose bracket is lifted by gap_height (a clearance violation)
  double gap_height = 0.05;  ///< below every designed clearance (>= 0.19 mm at 48 segments)
  std::uint64_t seed = 1;    ///< which joints get clashes and gaps, shift directions
  JointDims dims;
};

/// The ground truth of a generated assembly, by construction (independent of any clash query).
struct AssemblyInfo {
  std::size_t joints = 0;
  std::size_t triangles = 0;
  /// Body id pairs (first < second) whose solids overlap: the real clashes.
  std::vector<std::pair<std::string, std::string>> clash_pairs;
  /// Body id pairs in face contact (touching, interiors apart).
  std::vector<std::pair<std::string, std::string>> contact_pairs;
  /// Body id pairs apart by exactly gap_height (the lifted brackets and their plates).
  std::vector<std::pair<std::string, std::string>> gap_pairs;
};

/// One part type's shared mesh and its analytic volume (of the smooth part, mm^3).
struct AssemblyPart {
  std::string type;  ///< "bolt", "nut", "washer", "plate", "bracket"
  std::shared_ptr<const TriMesh> mesh;
  double analytic_volume = 0;
};

/// The five part meshes at `segments` (throws std::invalid_argument unless a positive multiple of
/// 24).
std::vector<AssemblyPart> assembly_parts(const JointDims& dims = {}, int segments = 48);

/// The generated assembly: bodies in joint order (plate bottom, plate top, bolt, washer top, washer
/// bottom, nut, bracket), ids "<type>-<6-digit index within its type>" (e.g. "bolt-000123"),
/// name = id, path "/assembly/joint-<6 digits>/<id>", tag = the type, source primitive.
/// Deterministic: the same options give the same scene on every platform.
Scene generate_assembly(const AssemblyGenOptions& options = {}, AssemblyInfo* info = nullptr);

/// The layouts of the moving scene.
enum class MovingLayout {
  /// A moving scene as one is met in use (a robot cell, a mechanism, parts handled in fixtures):
  /// bodies stand apart with clearances between them, and only a few are near another at a time.
  /// The five part types in turn, one body per cell of a square grid in x and y (pitch: the
  /// plate's width + `clearance`), each standing on z = 0 at its cell's centre, so that two
  /// bodies of different cells stay more than `clearance` - 2 x (their motion's reach) apart in
  /// every frame: the broad phase never pairs them. Near pairs (`near_fraction` of the bodies, two
  /// bodies sharing a cell), of two kinds in turn: a fit, a bolt through a plate's hole (radial
  /// clearance 0.5 mm) with its head `fit_gap` above the plate, near in every frame (the boxes
  /// overlap) and never touching; and a stack, a plate with a part standing on it (a plate,
  /// washer, nut or bracket in turn), the part's bottom face `near_gap` above the plate's top face
  /// in their home poses: as both move, the pair is clear in most frames and clashes (or
  /// touches) in some.
  cell,
  /// The bolted assembly of generate_assembly with every body moving (the first version of this
  /// benchmark): about 680 of its designed face contacts (1,000 bodies) become shallow clashes in
  /// every frame, each decided with regions, curves and a depth bound.
  assembly,
};

struct MovingSceneGenOptions {
  std::size_t bodies = 1000;
  std::size_t frames = 100;
  std::uint64_t seed = 1;
  MovingLayout layout = MovingLayout::cell;
  /// Every body, every frame: its home pose composed with a rotation about its part's centre by
  /// an angle up to max_rotation_deg about a random axis and a translation up to max_translation
  /// per axis (fresh each frame, not cumulative: random small rigid motions about the home pose).
  double max_translation = 0.05, max_rotation_deg = 0.1;
  int segments = 48;
  /// MovingLayout::cell: the gap between neighbouring cells (mm), the share of bodies in near
  /// pairs (4 % of 1,000 bodies: 20 pairs, 10 fits and 10 stacks), the gap of a stack and the gap
  /// under a fit's bolt head in their home poses.
  double clearance = 2, near_fraction = 0.04, near_gap = 0.06, fit_gap = 1;
  std::size_t clashes = 30;  ///< MovingLayout::assembly: of the underlying assembly
  std::size_t gaps = 10;     ///< MovingLayout::assembly
};

/// The moving scene: `bodies` bodies with `frames` frames of random small rigid motions
/// (Scene::frames, every body in every frame). `near_pairs`, when given, receives the body id
/// pairs (first < second) of the near pairs (MovingLayout::cell; empty for the assembly): by
/// construction the only body pairs that can come within `clearance` - 2 x reach of each other.
Scene generate_moving_scene(const MovingSceneGenOptions& options,
                            std::vector<std::pair<std::string, std::string>>* near_pairs = nullptr);
inline Scene generate_moving_scene(std::size_t bodies = 1000, std::size_t frames = 100,
                                   std::uint64_t seed = 1) {
  MovingSceneGenOptions o;
  o.bodies = bodies, o.frames = frames, o.seed = seed;
  return generate_moving_scene(o);
}

}  // namespace interfere::scene
