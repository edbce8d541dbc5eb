// The scene model (issue #24, item 1; ../shared/ARCHITECTURE.md, "Scenes"): the bodies a user checks
// together — an assembly's instances, an FE model's bodies, a glTF scene's nodes, mesh files — with
// where each came from, its unit, pose and tags, plus optional motion (per-frame poses, per-step
// deformations). Every source (scene/io.h, cad/assembly_scene.h, fem bodies) makes a Scene; the
// clash engine (scene/engine.h) checks one.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "interfere/core/transform.h"
#include "interfere/mesh/tri_mesh.h"
#include "interfere/query/model.h"

namespace interfere::scene {

/// Where a body comes from.
enum class SourceKind : std::uint8_t {
  memory,         ///< built by the caller
  mesh_file,      ///< a mesh file (STL, OBJ, PLY, OFF, glTF flattened)
  fe_body,        ///< one body of an FE model (element set, property, physical group or connectivity)
  step_instance,  ///< one instance of a STEP assembly's product tree
  gltf_node,      ///< one node of a glTF scene
  primitive,      ///< an analytic primitive (cylinder, cone, roller), tessellated for the mesh engine
};
const char* source_kind_name(SourceKind k);

/// What Body::source_ids number.
enum class SourceIdKind : std::uint8_t {
  input_triangle,   ///< the triangle's index in its file (mesh files; also the default)
  fe_element_face,  ///< the solver's element id, with the element's local face in source_faces
  brep_face,        ///< the B-Rep face id (STEP, 1-based within the part)
};
const char* source_id_kind_name(SourceIdKind k);

struct BodySource {
  SourceKind kind = SourceKind::memory;
  std::string file;    ///< the input file (empty for bodies built in memory)
  std::string detail;  ///< FE: element set or "body N"; STEP: instance label; glTF: node path; primitive: its parameters
};

struct Body {
  /// Stable and unique within the scene: the user's (scene file), or derived from the source
  /// (file name, product path, node path) so that it survives reordering the inputs. Clash ids
  /// (engine.h) are built from it.
  std::string id;
  std::string name;
  /// Path in the product tree ("/Assembly/Sub-assembly/Instance"); the name when there is none.
  std::string path;
  BodySource source;
  std::string unit = "mm";  ///< the unit of the source's coordinates (geometry is in the scene's unit)
  /// Local geometry, in the scene's working unit (shared between instances of one part). Closed,
  /// consistently outward triangles are what containment needs; open bodies are allowed (their
  /// verdicts say undecided where inside/outside matters).
  std::shared_ptr<const TriMesh> mesh;
  Transform pose;  ///< local -> world (scene's working unit)
  std::vector<std::string> tags;
  SourceIdKind source_id_kind = SourceIdKind::input_triangle;
  /// Per triangle of `mesh`: what it came from (source_id_kind); empty: the triangle index.
  std::shared_ptr<const std::vector<std::int64_t>> source_ids;
  /// Per triangle, fe_element_face only: the element's local face (1-based, fem/surface.h's
  /// Abaqus numbering S1..S6; 1 for shells); else empty.
  std::shared_ptr<const std::vector<std::int8_t>> source_faces;
  /// Per vertex of `mesh`: the source's id of it (FE bodies: the solver's node id; issue #26,
  /// item 3); empty: the vertex index.
  std::shared_ptr<const std::vector<std::int64_t>> vertex_ids;
  /// The chordal error of the tessellation against its source surfaces (STEP bodies; 0 for
  /// meshes, which are exact as given). Crossings within it may be a nominal fit (engine.h).
  double tessellation_error = 0;

  /// Optional: the body's world model, already built by the caller (mesh posed, BVH, statistics
  /// when computed: MeshStats::triangles > 0). The engine then uses it as is instead of moving
  /// `mesh` by `pose` (which must still describe it); frames that move or deform the body do not.
  std::shared_ptr<const Model> world_model;

  std::int64_t source_id(std::uint32_t triangle) const {
    return source_ids && triangle < source_ids->size() ? (*source_ids)[triangle] : triangle;
  }
  std::int64_t vertex_id(std::uint32_t vertex) const {
    return vertex_ids && vertex < vertex_ids->size() ? (*vertex_ids)[vertex] : vertex;
  }
};

/// One frame (or load step) of a motion: new poses and shapes of some bodies. A body a frame does
/// not list keeps its pose and shape from the previous frame (initially the scene's).
struct Frame {
  std::string label;  ///< "frame 3", "step 2 (time 0.5)"
  double time = 0;
  struct Pose {
    std::uint32_t body = 0;  ///< index into Scene::bodies
    Transform pose;          ///< local -> world
  };
  struct Shape {
    std::uint32_t body = 0;
    /// New local positions (same triangles as the body's mesh: a deformation, refitted, not rebuilt).
    std::shared_ptr<const std::vector<Vec3>> positions;
  };
  std::vector<Pose> poses;
  std::vector<Shape> shapes;
};

struct Scene {
  std::string units = "mm";  ///< the working unit of every body's geometry and pose
  std::vector<Body> bodies;
  std::vector<Frame> frames;  ///< empty: static
  std::vector<std::string> warnings;

  /// Index of the body with this id, or -1.
  std::int64_t find(std::string_view id) const;
  /// Throws std::invalid_argument naming the first problem: an empty or duplicate body id, a body
  /// without geometry, a frame naming a body out of range, a shape whose vertex count differs
  /// from its body's mesh.
  void validate() const;
};

/// A body id from free text: characters outside [A-Za-z0-9._:/#@+-] become '_' (ids appear in
/// file names, CSV cells and selectors).
std::string make_body_id(std::string_view text);

/// Gives duplicate ids in `scene` a suffix "#2", "#3", ... in body order (sources that derive ids
/// from names: two instances of one product named alike).
void make_ids_unique(Scene& scene);

/// The composition a∘b (apply b, then a).
Transform compose(const Transform& a, const Transform& b);
/// The inverse of an invertible affine transform (the caller validated it).
Transform inverse(const Transform& t);

}  // namespace interfere::scene
