// The scene model (include/interfere/scene/scene.h): ids, validation, pose algebra.
#include "interfere/scene/scene.h"

#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

namespace interfere::scene {

const char* source_kind_name(SourceKind k) {
  switch (k) {
    case SourceKind::memory: return "memory";
    case SourceKind::mesh_file: return "mesh_file";
    case SourceKind::fe_body: return "fe_body";
    case SourceKind::step_instance: return "step_instance";
    case SourceKind::gltf_node: return "gltf_node";
    case SourceKind::primitive: return "primitive";
  }
  return "?";
}

const char* source_id_kind_name(SourceIdKind k) {
  switch (k) {
    case SourceIdKind::input_triangle: return "input_triangle";
    case SourceIdKind::fe_element_face: return "fe_element_face";
    case SourceIdKind::brep_face: return "brep_face";
  }
  return "?";
}

std::int64_t Scene::find(std::string_view id) const {
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i].id == id) return static_cast<std::int64_t>(i);
  return -1;
}

void Scene::validate() const {
  std::unordered_set<std::string_view> seen;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    const std::string where = "body " + std::to_string(i) + (b.name.empty() ? "" : " ('" + b.name + "')");
    if (b.id.empty()) throw std::invalid_argument(where + ": empty id");
    if (!seen.insert(b.id).second) throw std::invalid_argument(where + ": duplicate body id '" + b.id + "'");
    if (!b.mesh) throw std::invalid_argument(where + " ('" + b.id + "'): no geometry");
    if (const Status s = b.pose.validate(); !s) throw std::invalid_argument(where + " ('" + b.id + "'): pose: " + s.error().message());
    if (b.source_ids && b.source_ids->size() != b.mesh->num_triangles())
      throw std::invalid_argument(where + " ('" + b.id + "'): " + std::to_string(b.source_ids->size()) +
                                  " source ids for " + std::to_string(b.mesh->num_triangles()) + " triangles");
    if (b.vertex_ids && b.vertex_ids->size() != b.mesh->num_vertices())
      throw std::invalid_argument(where + " ('" + b.id + "'): " + std::to_string(b.vertex_ids->size()) +
                                  " vertex ids for " + std::to_string(b.mesh->num_vertices()) + " vertices");
  }
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const std::string where = "frame " + std::to_string(f) + " ('" + frames[f].label + "')";
    for (const Frame::Pose& p : frames[f].poses) {
      if (p.body >= bodies.size()) throw std::invalid_argument(where + ": body index " + std::to_string(p.body) + " out of range");
      if (const Status s = p.pose.validate(); !s)
        throw std::invalid_argument(where + ": body '" + bodies[p.body].id + "': pose: " + s.error().message());
    }
    for (const Frame::Shape& s : frames[f].shapes) {
      if (s.body >= bodies.size()) throw std::invalid_argument(where + ": body index " + std::to_string(s.body) + " out of range");
      if (!s.positions || s.positions->size() != bodies[s.body].mesh->num_vertices())
        throw std::invalid_argument(where + ": body '" + bodies[s.body].id + "': the deformed shape has " +
                                    std::to_string(s.positions ? s.positions->size() : 0) + " vertices, the body " +
                                    std::to_string(bodies[s.body].mesh->num_vertices()));
    }
  }
}

std::string make_body_id(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' ||
                    c == '_' || c == ':' || c == '/' || c == '#' || c == '@' || c == '+' || c == '-';
    out += ok ? c : '_';
  }
  return out.empty() ? "_" : out;
}

void make_ids_unique(Scene& scene) {
  std::unordered_set<std::string> used;
  for (const Body& b : scene.bodies) used.insert(b.id);
  std::unordered_map<std::string, int> count;
  for (Body& b : scene.bodies) {
    const int n = ++count[b.id];
    if (n == 1) continue;
    for (int k = n;; ++k) {
      std::string candidate = b.id + "#" + std::to_string(k);
      if (used.insert(candidate).second) {
        b.id = std::move(candidate);
        break;
      }
    }
  }
}

Transform compose(const Transform& a, const Transform& b) {
  Transform c;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c.r[i][j] = a.r[i][0] * b.r[0][j] + a.r[i][1] * b.r[1][j] + a.r[i][2] * b.r[2][j];
  c.t = a.apply(b.t);
  return c;
}

Transform inverse(const Transform& t) {
  const auto& m = t.r;
  const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1], c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2],
               c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
  const double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
  Transform inv;
  inv.r[0][0] = c00 / det;
  inv.r[1][0] = c01 / det;
  inv.r[2][0] = c02 / det;
  inv.r[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
  inv.r[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
  inv.r[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
  inv.r[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
  inv.r[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
  inv.r[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
  inv.t = inv.rotate(t.t) * -1.0;
  return inv;
}

}  // namespace interfere::scene
