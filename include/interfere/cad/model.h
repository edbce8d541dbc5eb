// CAD models (issue #6, items 1-2), OCCT-free: a STEP file as parts (one solid or shell each,
// tessellated, every triangle tagged with its B-Rep face id), instances with their placement in
// the product tree (XCAF), and each part's attributed adjacency graph (AAG). Only src/cad/ sees
// OpenCASCADE; these plain structs are what the CLI, the Python module and the tests use.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/core/transform.h"
#include "interfere/mesh/tri_mesh.h"

namespace interfere::cad {

enum class SurfaceType : std::uint8_t { plane, cylinder, cone, sphere, torus, bspline, other };
enum class CurveType : std::uint8_t { line, circle, ellipse, other };
enum class Convexity : std::uint8_t { convex, concave, smooth };
const char* surface_type_name(SurfaceType t);
const char* curve_type_name(CurveType t);
const char* convexity_name(Convexity c);

/// AAG node: one B-Rep face with its surface type and parameters.
struct AagNode {
  std::uint32_t face = 0;       ///< face id (index in the part's face map, TopExp::MapShapes order)
  SurfaceType type = SurfaceType::other;
  bool from_bspline = false;    ///< a B-spline/Bezier/other face recognised as plane/cylinder/...
  Vec3 normal;                  ///< plane: outward unit normal (material side is behind it)
  Vec3 axis_point, axis;        ///< cylinder/cone/sphere/torus: axis (unit direction) and a point
  double radius = 0;            ///< cylinder, sphere, torus (major); cone: radius at axis_point
  double minor_radius = 0;      ///< torus
  double half_angle = 0;        ///< cone, radians
  bool hole = false;            ///< cylinder/cone/sphere: outward normal points to the axis (a bore)
  double area = 0;
  std::uint32_t outer_loops = 0, inner_loops = 0;
  std::uint32_t triangles = 0;  ///< of the tessellation
  /// cylinder/cone (issue #29): the face's angular range about `axis` (right-handed), from the unit
  /// radial direction `arc_start` through `arc_span` radians (2 pi for a face closing the circle),
  /// and its extent along `axis`, [axial_min, axial_max] from `axis_point`.
  Vec3 arc_start;
  double arc_span = 0;
  double axial_min = 0, axial_max = 0;
};

/// AAG arc: one B-Rep edge shared by two different faces.
struct AagArc {
  std::uint32_t a = 0, b = 0;  ///< node (= face) ids, a < b
  std::uint32_t edge = 0;      ///< edge id (TopExp::MapShapes order)
  CurveType curve = CurveType::other;
  Convexity convexity = Convexity::smooth;
  double angle = 0;            ///< angle between the outward normals at the edge's middle, radians
  bool inner_loop_a = false, inner_loop_b = false;  ///< the edge lies on an inner loop of a / b
  double length = 0;
  Vec3 midpoint;               ///< the edge's point at its middle parameter (issue #29)
};

struct Aag {
  std::vector<AagNode> nodes;  ///< nodes[i].face == i
  std::vector<AagArc> arcs;    ///< sorted by (a, b, edge)
};

struct Part {
  std::string name;
  TriMesh mesh;                         ///< part coordinates; vertices duplicated along face boundaries
  std::vector<std::uint32_t> face_ids;  ///< per triangle: its B-Rep face
  Aag aag;
  std::uint32_t solids = 0, shells = 0, faces = 0;
  std::vector<std::uint32_t> untessellated_faces;  ///< faces that failed to tessellate
  /// The linear deflection the part was tessellated with (model units): BRepMesh keeps the
  /// triangles within about this distance of the B-Rep surfaces (0 for a part not from a STEP file).
  double linear_deflection = 0;
  /// With ImportOptions::measure_deviation: the largest distance from the triangles' centroids and
  /// edge midpoints to their faces' surfaces (each sample's an upper estimate: the surface point of
  /// the same (u, v), or a projection's nearest point where that is beyond the linear deflection;
  /// sampled: between samples a triangle may lie farther), measured after BRepMesh; -1 when not
  /// measured (or a face has no UV nodes).
  double tessellation_deviation = -1;
  /// How far the tessellation may lie from the B-Rep: the larger of linear_deflection and the
  /// measured tessellation_deviation (BRepMesh may exceed its tolerance).
  double tessellation_error() const {
    return tessellation_deviation > linear_deflection ? tessellation_deviation : linear_deflection;
  }
  /// The part's colour as the STEP file gives it (XCAF surface or generic colour of its product or
  /// shape; linear RGB in [0, 1]); has_color false where it gives none (issue #29: kept in glTF).
  bool has_color = false;
  float color[3] = {0, 0, 0};
};

struct Instance {
  std::string name;         ///< component or product name
  std::uint32_t part = 0;   ///< index into CadModel::parts
  Transform placement;      ///< part coordinates -> world
  std::string path;         ///< product-tree path, "/"-separated names
};

struct CadModel {
  std::vector<Part> parts;
  std::vector<Instance> instances;
  std::vector<std::string> warnings;
  /// Length unit of every coordinate, radius and distance above: OCCT converts the file's lengths
  /// to millimetres on reading.
  std::string units = "mm";
  /// The length units the file declares (its contexts' units as OCCT names them, e.g. "MM",
  /// "INCH"), each once, in order of appearance.
  std::vector<std::string> file_length_units;
  /// The STEP file it was read from (import_step; empty for a model built in memory).
  std::string file;
};

struct ImportOptions {
  /// BRepMesh_IncrementalMesh linear deflection, model units; 0 = 0.1 % of the bounding-box diagonal;
  /// else at least 1e-7 (Precision::Confusion); other values are errors.
  double linear_deflection = 0;
  double angular_deflection = 0.5;  ///< radians, in [1e-6, pi]
  /// Tolerance (relative to the face's size) of the canonical-surface recognition of B-spline faces.
  double canonical_tolerance = 1e-4;
  /// Measures each part's Part::tessellation_deviation (4 surface evaluations per triangle).
  bool measure_deviation = false;
  /// Triangulates faces with OCCT's Delabella Delaunay (BRepMesh_DelabellaMeshAlgoFactory) instead of
  /// BRepMesh's default algorithm: the same deflections, about a third less time on the casing
  /// (issue #29: its tessellation is most of the whole command), slightly different triangles.
  bool delabella = false;
  /// Meshes a closed surface of revolution with several holes' rims as inner wires as angular
  /// sectors (one rim each, Delabella on surfaces of revolution and cylinders; the triangles keep the face's id): BRepMesh's grid on such a face grows
  /// about quadratically with the rims' nodes (issue #29: the casing's wall, 0.5-0.9 s alone; docs/simplify.md,
  /// "Whole command on the casing", the rule). Off: every face meshed whole, as before.
  bool sector_split = true;
  /// Builds each part's AAG (Part::aag). Callers that need triangles only (clash, distance) turn it
  /// off: the parts' `aag` stay empty.
  bool build_aag = true;
};

/// Reads a STEP file (parts, assemblies, names, instance transforms; XCAF), tessellates every part
/// and builds its AAG. Errors: unreadable or empty file, no solid/shell; faces that fail to
/// tessellate are warnings naming the face.
Expected<CadModel> import_step(const std::filesystem::path& path, const ImportOptions& options = {});

/// All instances' meshes in world coordinates, concatenated; face ids made unique per instance
/// (offset by the running face count) when `face_ids` is given.
TriMesh world_mesh(const CadModel& model, std::vector<std::uint32_t>* face_ids = nullptr);

/// Test and benchmark solids built with OCCT primitives and Booleans, written to STEP
/// (STEPControl_Writer). Sizes in mm.
enum class TestPart {
  box_through_hole,     ///< 40x30x10 box, through hole r=4 along z at the centre
  box_blind_hole,       ///< same box, blind hole r=4 depth 6
  counterbored_plate,   ///< 40x30x10 plate, bore r=3 through, counterbore r=6 depth 4
  countersunk_plate,    ///< 40x30x10 plate, bore r=3 through, 90-degree countersink to r=6
  stepped_shaft,        ///< cylinder r=10 h=30 + cylinder r=6 h=25 on top (shoulder ring)
  slot_block,           ///< 40x30x20 block, through slot 10 wide 8 deep along x
  step_block,           ///< 40x30x20 block, through step 10 x 8 along x
  near_miss_plate,      ///< counterbored_plate with the counterbore 2 mm off the bore axis: no match
  casing,               ///< flanged ring (B-spline wall of revolution), 6 counterbored bolt holes on the lower flange, 6 plain ones on the upper (the paper's casing)
  box_through_hole_nurbs,  ///< box_through_hole with every face converted to B-spline
  perforated_plate,     ///< 400x400x10 plate, 13x13 counterbored holes: 513 faces (recognition timing)
  box_through_hole_split,  ///< box_through_hole with the closed hole face split in two half cylinders
  single_face,          ///< one planar 10 x 10 face, no solid (bad-input test: a warning, not an error)
  countersunk_plate_nurbs,  ///< countersunk_plate with every face converted to B-spline
  // Hole recognition cases (issue #29):
  pocket_block,         ///< 60x40x20 block, blind pocket 30x20x8 with r=4 corner rounds, through slot 8 wide with round ends: no hole
  inclined_entry_block, ///< 40x30x20 block whose top is cut at 30 degrees through (y, z) = (15, 14), through hole r=4 along z entering the inclined face
  shaft_cross_hole,     ///< cylinder r=15 along x, length 60, radial through hole r=3 along z (entry and exit on the curved face)
  blind_split_floor,    ///< box_blind_hole with the wall split in two half cylinders (the floor circle in two edges)
  crossing_holes,       ///< 40x40x20 block, through hole r=4 along x and one r=3 along y crossing it at mid-height
  counterdrilled_plate, ///< 40x30x10 plate, bore r=3 through, counterdrill r=6 from the top to z=6 ending in a 118-degree drill point cone down to r=3
  paper_casing,         ///< He & Xu 2023 §4's casing as the paper describes it: the casing body (bore r=88, B-spline working ring) with end flanges (r=130, 12 thick) holding 6 plain bolt holes r=5 each, and 6 radial counterbored screw holes (bore r=3 through to the inner ring face, counterbore r=6 from the outer wall to r=104) in the working ring at mid-height
  // Floor features with fillets (issue #29, item 1; src/cad/generate_floor_parts.cpp, BRepFilletAPI fillets):
  slot_features_block,  ///< 80x60x30 block, vertical outer edges rounded r=4; through slot along x, y 5..17, floor z=22, floor fillets r=2; blind slot from x=0, y 25..35, floor z=24, round end r=5 about (40, 30); blind slot from x=80 to x=50, y 43..55, floor z=20, square end with corner rounds r=2
  filleted_pocket_block, ///< 70x50x25 block, top outer edges rounded r=1.5; pocket x 15..55, y 10..40, floor z=15, corner rounds r=5, floor fillets r=2
  filleted_step_block,  ///< 60x40x30 block; through step along x at y 0..12, floor z=20, wall y=12, floor fillet r=3, the wall's top edge rounded r=2; plain through step at y 30..40, floor z=22, wall y=30
};
const char* test_part_name(TestPart p);
Status write_test_part(TestPart part, const std::filesystem::path& step_file);
/// The same solid (sizes in mm) written in the length unit `length_unit`, one of OCCT's
/// write.step.unit names ("MM", "M", "INCH", "FT", ...), its coordinates converted to it (a file
/// whose own unit is not mm, as CAD systems write them; issue #23, item 6). Unknown names: an
/// error.
Status write_test_part(TestPart part, const std::filesystem::path& step_file,
                       const std::string& length_unit);
/// The same solid (mm) with its product named `product_name` instead of test_part_name(part): the
/// bundled example data/examples/casing.step is TestPart::paper_casing named "casing"
/// (tools/write_test_part/write_test_part.cpp; issue #29).
Status write_test_part_named(TestPart part, const std::filesystem::path& step_file, const std::string& product_name);

/// An XCAF assembly "assembly" written with STEPCAFControl_Writer (names kept; surface colours: plate
/// (0.8, 0.2, 0.1), shaft (0.1, 0.3, 0.9)): part "plate"
/// (counterbored_plate) as component "plate_1" at the identity and "plate_2" rotated 90 degrees about
/// z then lifted by (0, 0, 20); part "shaft" (stepped_shaft) as "shaft_1" moved by (100, 0, 0).
Status write_test_assembly(const std::filesystem::path& step_file);

/// A bolted joint "joint" with known mates (issue #29): part "plate" (60x40x10, z 0..10) and part
/// "cover" (60x40x6 on the plate, lifted by `cover_gap` mm), one instance each, with through holes
/// r = 4 at (+-15, 0, z); part "bolt" (shank r = 4 from z = -8 through both, head r = 7 h = 5 on the
/// cover) as "bolt_1", "bolt_2" at x = -15, 15; part "nut" (r = 7, h = 6, bore r = 4, under the plate)
/// as "nut_1", "nut_2" on them. Every fit has zero clearance.
Status write_bolted_test_assembly(const std::filesystem::path& step_file, double cover_gap = 0);

/// An AP203 assembly "ASM" (STEP schema CONFIG_CONTROL_DESIGN) as CAD systems write them: product
/// "PLATE" (counterbored_plate) holding its solid as a nameless sub-shape, at the identity; product
/// "ROD" (stepped_shaft) at (100, 0, 0) and at (-100, 0, 0); no instance has a name of its own.
Status write_test_assembly_ap203(const std::filesystem::path& step_file);

}  // namespace interfere::cad
