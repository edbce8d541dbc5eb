// The bodies of a glTF 2.0 scene (include/interfere/scene/io.h, read_gltf_bodies): one body per
// node with a mesh, on the walk the flattening mesh reader uses (src/mesh/io/glb.cpp, walk_gltf;
// Khronos glTF 2.0 specification §3.5 "Nodes and hierarchy"): the node's mesh in its own
// coordinates (shared by the nodes that use one glTF mesh), posed by its world transform.
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "../mesh/io/glb.h"
#include "interfere/core/coordinate_range.h"
#include "interfere/scene/io.h"

namespace interfere::scene {

Expected<std::vector<Body>> read_gltf_bodies(const std::string& path, double scale) {
  if (!(scale > 0) || !std::isfinite(scale))
    return Error{.file = path,
                 .reason = "glTF scale " + std::to_string(scale) + ": must be finite and > 0"};
  std::string data;
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) return Error{.file = path, .reason = "cannot open the file"};
    std::ostringstream s;
    s << in.rdbuf();
    data = std::move(s).str();
  }
  if (data.empty()) return Error{.file = path, .reason = "file is empty"};
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  Scene scene;
  // Meshes in the working unit, by glTF mesh: scaled by `scale` times the node's uniform scale
  // (kept in the mesh so that the pose is rigid) and, under a mirroring transform, with their
  // winding reversed (glTF §3.7.2.1: a negative determinant turns the faces clockwise), shared by
  // the nodes that agree on both.
  struct Scaled {
    double factor;
    bool mirrored;
    std::shared_ptr<const TriMesh> mesh;
  };
  std::map<std::size_t, std::vector<Scaled>> meshes;
  const Status walked =
      io_detail::walk_gltf(path, data, dir, [&](const io_detail::GltfMeshNode& n) -> Status {
        if (n.local->triangles.empty()) return {};  // points or lines only: no surface
        const std::string where = "glTF nodes[" + std::to_string(n.node) + "] (" + n.path + ")";
        Transform world;  // in metres
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) world.r[i][j] = n.world[j * 4 + i];
        world.t = Vec3{n.world[12], n.world[13], n.world[14]};
        const int sign = world.determinant_sign();  // exact
        Body b;
        if (sign == 0 || !world.validate()) {
          // A collapsing transform (a zero scale, which hides a node) has no inverse: the node's
          // geometry is placed as the flattening reader places it, at the identity.
          TriMesh placed = *n.local;
          for (Vec3& p : placed.positions) p = world.apply(p) * scale;
          b.mesh = std::make_shared<const TriMesh>(std::move(placed));
        } else {
          // World = c·Q·p + t in metres with Q orthogonal where the node scales uniformly (c = 1
          // otherwise); in the working unit Q·(s·c·p) + s·t.
          const double det =
              world.r[0][0] * (world.r[1][1] * world.r[2][2] - world.r[1][2] * world.r[2][1]) -
              world.r[0][1] * (world.r[1][0] * world.r[2][2] - world.r[1][2] * world.r[2][0]) +
              world.r[0][2] * (world.r[1][0] * world.r[2][1] - world.r[1][1] * world.r[2][0]);
          double c = std::cbrt(std::fabs(det));
          bool orthogonal = c > 0 && std::isfinite(c);
          for (int i = 0; i < 3 && orthogonal; ++i)
            for (int j = 0; j < 3 && orthogonal; ++j) {
              double d = 0;
              for (int k = 0; k < 3; ++k) d += world.r[k][i] * world.r[k][j];
              orthogonal = std::fabs(d / (c * c) - (i == j ? 1 : 0)) <= 1e-9;
            }
          if (!orthogonal) c = 1;
          const bool mirrored = sign < 0;
          std::vector<Scaled>& known = meshes[n.mesh];
          for (const Scaled& k : known)
            if (k.mirrored == mirrored && std::fabs(k.factor - c) <= 1e-12 * c)
              c = k.factor, b.mesh = k.mesh;
          if (!b.mesh) {
            TriMesh m = *n.local;
            for (Vec3& p : m.positions) p = p * (scale * c);
            if (mirrored)
              for (Tri& t : m.triangles) std::swap(t[1], t[2]);
            b.mesh = std::make_shared<const TriMesh>(std::move(m));
            known.push_back({c, mirrored, b.mesh});
          }
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) b.pose.r[i][j] = world.r[i][j] / c;
          b.pose.t = world.t * scale;
        }
        for (std::size_t i = 0; i < b.mesh->positions.size(); ++i)
          if (const Vec3 w = b.pose.apply(b.mesh->positions[i]); !coordinates_in_range(w))
            return Error{.file = path,
                         .reason = where + ": vertex " + std::to_string(i) + " of meshes[" +
                                   std::to_string(n.mesh) +
                                   "], placed: " + coordinate_range_reason(w)};
        b.name = n.name.empty() ? "node" + std::to_string(n.node) : n.name;
        b.path = n.path;
        b.id = make_body_id(n.path);
        b.source = {.kind = SourceKind::gltf_node, .file = path, .detail = n.path};
        b.unit = "m";
        scene.bodies.push_back(std::move(b));
        return {};
      });
  if (!walked) return walked.error();
  if (scene.bodies.empty())
    return Error{
        .file = path,
        .reason = "glTF document: no triangles: the scene has no node with triangle primitives"};
  make_ids_unique(scene);
  return std::move(scene.bodies);
}

}  // namespace interfere::scene
