// Bearing assemblies (issue #27, item 1; Jia & Zheng 2019, §2.1 Fig. 1 and §4): several bearings of
// an axle, each with its rings, rollers and cage, described in JSON (docs/bearing.md, "Bearing
// assemblies"), meshed as closed outward bodies, and checked pair by pair every frame of a motion
// (generated with a seed, or read from a pose file) by exact solvers.
//
//  * cylindrical: inner ring (raceway cylinder r_i, two ribs of height h and width w at its ends,
//    bore), outer ring (concave raceway bore R_o), Z cylindrical rollers on the pitch circle, a cage
//    of Z webs (convex hexahedra) between the pockets;
//  * tapered: cone (inner raceway, a frustum), cup (outer raceway, a concave cone), Z tapered rollers
//    whose axes and raceways meet at one apex on the bearing axis (§2.1: "axes coplanar or meeting at
//    a point"), the same cage of webs.
//
// Frames: each bearing's local frame has the bearing axis +z through `position`, the mid-plane z = 0.
// Rings and cage have that frame as body frame; a roller's body frame is make_roller's (axis +z from
// its bottom end centre). Poses (motion) map body frames to the world.
//
// Pairs (per bearing; bearings of one assembly must lie apart at rest, checked; the cage-ring and
// bearing-bearing rows bound the rest from below every frame, issue #27 item 2): roller-inner raceway and
// roller-roller (neighbours) by part_pair.h (standard or scarred solver, two-sided), roller-outer
// bore (raceway.h; scarred rollers: the exact vertex maximum, see assembly_pairs.cpp), roller end-rib
// (raceway.h), roller-cage web (exact: min over the web's triangles of the roller's signed distance,
// scarred.h's triangle minimum; tapered or scarred rollers: the mesh engine), tapered: roller-cone
// (cone_pair_distance), roller-cup (roller_cup_distance). Scarred tapered rollers (issue #27;
// assembly_tapered_scars.h): roller-cone and roller-roller by the scarred solver against the intact
// frustum (exact forward value, a two-sided bracket), two scarred neighbours by a lower bound and
// the mesh engine, roller-cup by the exact vertex maximum, roller-cage split into frustum pieces.
// Sign convention of analytic.h: > 0 clearance, < 0 interference depth.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "interfere/bearing/part_pair.h"
#include "interfere/bearing/quadtree.h"
#include "interfere/bearing/raceway_scar.h"
#include "interfere/bearing/roller.h"
#include "interfere/bearing/scar.h"
#include "interfere/core/error.h"
#include "interfere/mesh/tri_mesh.h"
#include "interfere/query/model.h"
#include "interfere/query/verdict.h"

namespace interfere::bearing {

// ---------------------------------------------------------------------------------------------
// Description (assembly_read.cpp, assembly_validate.cpp)

enum class BearingType : std::uint8_t { cylindrical, tapered };
const char* bearing_type_name(BearingType t);

struct RollerSetSpec {
  int count = 0;              ///< Z >= 3
  double radius = 0;          ///< cylindrical: the radius; tapered: the small-end radius
  double top_radius = -1;     ///< tapered: the large-end radius (> radius)
  double length = 0;          ///< > 0
  double pitch_radius = 0;    ///< cylindrical: radius of the circle of the roller axes (tapered: derived)
  int radial_segments = 32;   ///< mesh (>= 3)
  int height_segments = 31;   ///< mesh (>= 1)
};

struct CageSpec {
  double pocket_clearance = 0;  ///< tangential play per side between roller and pocket face (>= 0)
  double web_thickness = 0;     ///< radial thickness of the webs, centred on the pitch line (< 2 x min roller radius)
  double width = 0;             ///< axial length of the webs along the roller axis; 0: the roller length
};

/// A scar on one of the bearing's raceways (issue #27; raceway_scar.h): `bearings[i].scars[k]`.
/// Generated (the window keys) or imported (`map`: a CSV grid, `png`, `points`: a point cloud or a
/// registered STL in the bearing's frame); docs/bearing.md, "Scars on raceways".
struct RacewayScarSpec {
  std::string where;  ///< "bearings[0].scars[1]" (messages)
  RacewaySurface part = RacewaySurface::inner;  ///< inner, outer (cylindrical); cone, cup (tapered)
  ScarParams scar;    ///< generated: window (angles in the bearing frame, z from the raceway's start), depth, ...
  std::string map, png, points;  ///< imported (at most one; paths as given, relative to the JSON file)
  double png_scale = 0, png_offset = 0;  ///< png: height = scale * pixel + offset (scale required)
  double points_window = 0;              ///< points: PointScarOptions::window (0: automatic)
  int border = 0;                        ///< imported: median filter band (generated: scar.border)
  RacewayGrid grid;                      ///< the raceway grid (radial_segments, height_segments)
  bool imported() const { return !map.empty() || !png.empty() || !points.empty(); }
};

struct BearingSpec {
  std::string id;  ///< unique; part ids are "<id>/inner", "<id>/outer", "<id>/cage", "<id>/roller<k>"
  std::string where;  ///< "bearings[2]" (messages)
  BearingType type = BearingType::cylindrical;
  Vec3 position;
  Vec3 axis{0, 0, 1};  ///< normalised by the reader
  RollerSetSpec rollers;
  CageSpec cage;
  // cylindrical
  double inner_bore = 0, inner_raceway = 0, inner_width = 0;  ///< inner ring radii, axial width
  double rib_height = 0, rib_width = 0;                       ///< the two ribs of the inner ring
  double outer_raceway = 0, outer_radius = 0, outer_width = 0;  ///< outer ring: bore R_o, outside, width
  // tapered
  double contact_angle_deg = 0;  ///< cup half-angle alpha
  double cone_bore = 0, cone_clearance = 0;   ///< cone's bore radius; raceway offset inwards (normal)
  double cup_outer = 0, cup_clearance = 0;    ///< cup's outside radius; raceway offset outwards (normal)
  std::vector<RacewayScarSpec> scars;  ///< raceway scars (issue #27), at most one per raceway
};

/// An imported roller scar (issue #27, deliverable 2: scars on any part, generated or imported):
/// the top-level `scar` with `map` (a CSV grid over angle x axial position), `png` (a 16-bit
/// grayscale PNG, placed on the scar window, `scale` required) or `points` (an x y z text file, or
/// a scanned .stl/.ply/.obj/.off whose vertices are the points) in the roller's body frame
/// (scar_import.h), resolved against the assembly file's folder. Every scarred roller (scar.fraction)
/// carries it, resampled onto its bearing's roller grid; docs/bearing.md, "Imported roller scars".
struct RollerScarImport {
  std::string map, png, points;          ///< at most one; paths as given
  double png_scale = 0, png_offset = 0;  ///< png: height = scale * pixel + offset (scale required)
  double points_window = 0;              ///< points: PointScarOptions::window (0: automatic)
  int border = 0;                        ///< median filter band over the covered region's border
  bool any() const { return !map.empty() || !png.empty() || !points.empty(); }
};

struct AssemblyMotionSpec {
  double inner_deg_per_frame = 5;  ///< inner ring rotation per frame (outer ring fixed)
  double max_tilt_deg = 0.05;      ///< roller tilt perturbation in its axial plane, |tilt| <= this; Eq. (1) valid
  double load_direction_deg = 270; ///< direction of the inner ring's radial displacement (bearing frame, from +x)
  double load_displacement = 0;    ///< radial displacement of the inner ring (>= 0)
  double pocket_play = 1.0;        ///< tangential roller shift, fraction of the pocket clearance ([0, 4])
  double axial_play = 1.0;         ///< axial roller shift, fraction of the free axial play between the ribs ([0, 4])
};

struct AssemblySpec {
  std::string file;
  int frames = 10;
  std::uint64_t seed = 1;
  double clearance = 0;          ///< >= 0: the clearance verdict below it
  int ring_segments = 96;        ///< segments around the rings' meshes (>= 8)
  double scar_fraction = 0;      ///< of each bearing's rollers (cylindrical and tapered), in [0, 1]
  ScarParams scar;               ///< window; z_min/z_max < 0: 25 % / 75 % of the roller length
  RollerScarImport scar_import;  ///< imported roller scar (scar.map / png / points), else generated
  AssemblyMotionSpec motion;
  std::vector<BearingSpec> bearings;
};

/// Reads the JSON description. Errors name the file and the JSON path ("axle.json: bearings[1].
/// rollers.count: expected an integer, got a string"): unknown keys, wrong types, missing fields.
/// The result is validated (validate_assembly).
Expected<AssemblySpec> read_assembly_file(const std::string& path);
/// The same from text (`file` names it in messages).
Expected<AssemblySpec> parse_assembly(const std::string& text, const std::string& file);

/// Every geometric condition, the error naming the parameter ("bearings[0].rollers.pitch_radius"):
/// non-finite numbers, rollers that do not fit between their rings (radially, axially between the
/// ribs), neighbours overlapping (Z too large for the pitch circle), a cage pocket smaller than its
/// roller, webs that vanish, tilts outside Eq. (1)'s validity range (window.h), bearings that overlap.
Status validate_assembly(const AssemblySpec& spec);

// ---------------------------------------------------------------------------------------------
// Parts (assembly_parts.cpp)

enum class PartKind : std::uint8_t { inner, outer, cage, roller };
const char* part_kind_name(PartKind k);

/// A convex hexahedral cage web, body (bearing) frame: 8 corners, 6 outward planes n.x <= d.
struct CageWeb {
  std::array<Vec3, 8> corners;
  std::array<Vec3, 6> normals;
  std::array<double, 6> offsets;
};

/// Derived geometry of one bearing (bearing frame).
struct BearingGeometry {
  Transform frame;          ///< bearing frame -> world (rotation z -> axis, translation position)
  double pitch_radius = 0;  ///< of the roller mid points
  double roller_z = 0;      ///< axial position of the roller mid points
  double roller_lean = 0;   ///< angle of the roller axes to the bearing axis (tapered: gamma), radians
  double apex_z = 0;        ///< tapered: the apex on the axis
  double cone_half_angle = 0, cup_half_angle = 0;
  double ring_lo = 0, ring_hi = 0;  ///< tapered: axial span of cone and cup
  Cylinder raceway;         ///< inner raceway (cylindrical: r_i over the inner width; tapered: the cone frustum)
  double free_axial_play = 0;  ///< cylindrical: (inner width - 2 rib widths - roller length) / 2
  std::vector<CageWeb> webs;   ///< web k lies between roller k and roller k + 1
};
Expected<BearingGeometry> bearing_geometry(const BearingSpec& b);

/// A part's bounding sphere in its body frame, grown by its meshes' faceting (the true surface lies
/// within the sagitta of the inscribed facets) and a scar's outward raise: every point of the part.
/// Also its enclosing cylinder about the body frame's z axis (radius, z_lo..z_hi), grown the same way.
struct PartSphere {
  Vec3 centre;
  double radius = 0;
  double cylinder_radius = 0, z_lo = 0, z_hi = 0;
};

struct AssemblyPart {
  std::string id;
  PartKind kind = PartKind::roller;
  int bearing = 0, index = 0;          ///< index: the roller's k (else 0)
  std::shared_ptr<const TriMesh> mesh; ///< body frame, closed and outward
  std::shared_ptr<const Roller> roller;        ///< rollers: the meshed (scarred) roller
  std::shared_ptr<const RollerQuadtree> tree;  ///< scarred rollers
  std::shared_ptr<const Model> solid;          ///< scarred rollers: body-frame model (containment)
  bool scarred = false;
  /// Scarred rollers: max(roller->raise, the largest |displacement|), set once by build_assembly
  /// (the raceway-scar rows' check, assembly_pairs.cpp; issue #27: it looped over the roller's
  /// displacements per row). 0 otherwise.
  double scar_height = 0;
  Transform rest;  ///< nominal pose (no motion)
  PartSphere sphere;  ///< (bearing_bearing bound)
  /// Rings: the scar on its raceway (issue #27; raceway_scar.h), else null. The ring's `mesh` then
  /// shows it (scarred_ring_mesh; display only: no row uses ring meshes); roller-raceway rows in
  /// range of it use raceway_scar_solver.h.
  std::shared_ptr<const RacewayScar> raceway_scar;
};

/// Meshes of the parts of one bearing (for views and the mesh engine).
TriMesh inner_ring_mesh(const BearingSpec& b, const BearingGeometry& g, int segments);
TriMesh outer_ring_mesh(const BearingSpec& b, const BearingGeometry& g, int segments);
/// The ring whose raceway carries `scar` (issue #27): the ring's profile revolved with the scar
/// grid's angular segments, its raceway edge through the grid's rows with the scarred surface's
/// vertices (the edge's ends, at the ribs or faces, intact): closed and outward, for views.
TriMesh scarred_ring_mesh(const BearingSpec& b, const BearingGeometry& g, const RacewayScar& scar);
TriMesh cage_mesh(const BearingGeometry& g);  ///< the Z webs, 12 triangles each
TriMesh web_mesh(const CageWeb& w);

/// The roller pose in the bearing frame: orbit angle phi, tilt in the axial plane (about the
/// tangential direction through the roller's mid point), axial shift, spin about its own axis.
Transform roller_local_pose(const BearingSpec& b, const BearingGeometry& g, double phi, double tilt,
                            double axial_shift, double spin);

// ---------------------------------------------------------------------------------------------
// Pairs (assembly_pairs.cpp)

enum class AssemblyPairKind : std::uint8_t {
  roller_inner,  ///< cylindrical roller - inner raceway cylinder (convex-convex)
  roller_outer,  ///< roller - concave outer raceway bore
  roller_roller, ///< neighbours
  roller_cage,   ///< roller - the cage web next to it
  roller_rib,    ///< roller end - rib face of the inner ring
  roller_cone,   ///< tapered roller - cone raceway
  roller_cup,    ///< tapered roller - cup raceway
  // issue #27, item 2: pairs that can touch only under large displacements; a conservative lower
  // bound of their distance every frame (clear above the clearance, else undecided: never a wrong clear)
  cage_inner,       ///< the cage's webs - the inner ring (its envelope: raceway and ribs; tapered: the cone)
  cage_outer,       ///< the cage's webs - the outer ring (bore; tapered: the cup)
  bearing_bearing,  ///< two bearings of the assembly (a, b: their outer rings stand for every part)
};
const char* assembly_pair_kind_name(AssemblyPairKind k);

struct AssemblyPair {
  AssemblyPairKind kind = AssemblyPairKind::roller_inner;
  std::uint32_t a = 0, b = 0;  ///< part indices (a: the roller)
  int feature = 0;             ///< roller_cage: the web index; roller_rib: 0 (z < 0 side) or 1
};


struct Assembly {
  AssemblySpec spec;
  std::vector<BearingGeometry> geometry;
  std::vector<AssemblyPart> parts;
  std::vector<AssemblyPair> pairs;
  std::vector<Model> webs;  ///< per bearing, per web: body-frame models (mesh engine), flattened
  std::vector<std::uint32_t> web_offset;  ///< per bearing: first web model
  std::int64_t find(const std::string& id) const;
};

/// Builds geometry, meshes (scars applied), and the pair list. Errors: validate_assembly.
Expected<Assembly> build_assembly(const AssemblySpec& spec);

enum class AssemblySolver : std::uint8_t {
  standard,  ///< analytic.h (two-sided)
  scarred,   ///< scarred.h on the roller's triangle surface
  raceway,   ///< raceway.h (bore, rib, cone, cup)
  vertex,    ///< scarred roller in the bore: maximum over its vertices (exact for the mesh)
  web,       ///< min over the web's triangles of the roller's signed distance (exact)
  mesh,      ///< the mesh engine (query/distance.h, clash.h) on the two meshes
  bound,     ///< only a bound (see part_pair.h)
};
const char* assembly_solver_name(AssemblySolver s);

struct AssemblyPairResult {
  double distance = 0;        ///< > 0 clearance, < 0 interference depth
  Vec3 point_a, point_b;      ///< world frame
  AssemblySolver solver = AssemblySolver::standard;
  AnalyticPath path = AnalyticPath::side;  ///< the analytic solver's path (standard, raceway)
  bool scar = false;          ///< a scarred surface was the one measured
  bool exact = true;          ///< false: distance is a bound (the verdict says what is decided)
  /// true: the value is two-sided, S = min(s(A, B), s(B, A)) (roller-inner, roller-roller,
  /// roller-cone; the ring and web rows of intact rollers, ring_two_sided.h), or a clearance that is
  /// the Euclidean distance (symmetric); a scarred roller's bore, cup, rib and web rows where
  /// certified (src/bearing/scarred_two_sided.h, scarred_rib_two_sided.h, scarred_web_two_sided.h).
  /// false: one direction only (a scarred roller's depth in the outer ring, cup or rib, or the web's
  /// deepest point in it, where not certified), and clearances that are not certified as the
  /// Euclidean distance (cup: to the cone line; rib: over the annulus).
  bool two_sided = true;
  Verdict verdict = Verdict::clear;
  /// Which part carries the scar that `scar` reports: 0 none, 1 part a (the roller), 2 part b (the
  /// other roller, or the ring whose raceway is scarred; issue #27).
  std::uint8_t scar_part = 0;
};

/// One pair at the given poses (world, per part).
AssemblyPairResult solve_pair(const Assembly& as, const AssemblyPair& pair, const std::vector<Transform>& poses,
                              double clearance);

// ---------------------------------------------------------------------------------------------
// Motion (assembly_motion.cpp)

/// Per frame, per part: body -> world.
struct AssemblyMotion {
  std::vector<std::vector<Transform>> poses;
  std::string source;  ///< "generated (seed S)" or the file
};

/// The paper's motion (§4; docs/bearing.md): inner ring rotation, cage and rollers orbiting at the
/// cage speed, roller spin, seeded tilt perturbations in the axial plane (|tilt| <= max_tilt), pocket
/// and axial play, the load's radial displacement of the inner ring. Frame f depends only on
/// (seed, f): deterministic.
AssemblyMotion generate_motion(const Assembly& as, int frames, std::uint64_t seed);

/// Per-frame poses from a motion file (scene/io.h's read_motion: CSV frame,body,12 numbers, or
/// JSON); a part a frame does not list keeps its previous pose (initially the rest pose). Errors
/// name the file and line (unknown part ids, ...), or the frame and part for a non-rigid pose.
Expected<AssemblyMotion> read_assembly_motion(const Assembly& as, const std::string& path);

// ---------------------------------------------------------------------------------------------
// Per frame (assembly_run.cpp)

struct AssemblyRow {
  std::int32_t frame = 0;
  std::uint32_t pair = 0;  ///< index into Assembly::pairs
  AssemblyPairResult result;
};

struct AssemblyResult {
  int frames = 0;
  std::vector<AssemblyRow> rows;             ///< frame-major, then pair
  std::vector<std::uint32_t> worst_per_frame;  ///< row index of each frame's smallest distance (first on ties)
  std::uint32_t worst = 0;                   ///< row index of the smallest distance overall
  std::array<std::uint64_t, 5> verdicts{};   ///< rows per Verdict
  Verdict verdict = Verdict::clear;
  std::uint64_t interfering_rows = 0, scar_rows = 0, inexact_rows = 0;
  double seconds = 0;
};

/// Every pair of every frame, in parallel over pairs (oneTBB), identical for any thread count.
/// `progress`, when set, is called with (frames done, frame count) as frames finish, from worker
/// threads, possibly at once (it must be thread-safe; the CLI's progress bar is). (Today: from the
/// calling thread after each block of frames, increasing, the last call with the frame count;
/// the blocks and the order within them: src/bearing/assembly_schedule.h, issue #27.)
AssemblyResult run_assembly(const Assembly& as, const AssemblyMotion& motion,
                            const std::function<void(std::size_t, std::size_t)>& progress = {});

/// The summaries of `out` (frames, worst_per_frame, worst, verdicts, verdict, the row counts) from
/// its rows alone (frame-major, `pairs_per_frame` rows a frame), as run_assembly computes them:
/// interfere-mpi (issue #31) merges the ranks' blocks of frames into one row list and calls it.
void summarize_assembly(AssemblyResult& out, std::size_t pairs_per_frame);

}  // namespace interfere::bearing
