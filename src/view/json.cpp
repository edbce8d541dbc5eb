// The viewer document as JSON (include/interfere/view/json.h; issue #25, docs/viewer.md).
#include "interfere/view/json.h"

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string_view>
#include <vector>

#include "interfere/core/aabb.h"
#include "interfere/core/base64.h"

namespace interfere::view {
namespace {

using json = nlohmann::ordered_json;

/// A problem found while writing; caught in document_json and returned as an Error.
struct Invalid {
  std::string where, why;
};

std::string at(std::string_view array, std::size_t i) { return std::string(array) + "[" + std::to_string(i) + "]"; }

void expand_box_corners(Aabb& box, const Aabb& local, const Transform& pose) {
  if (local.empty()) return;
  for (int k = 0; k < 8; ++k) {
    const Vec3 c{(k & 1) ? local.hi.x : local.lo.x, (k & 2) ? local.hi.y : local.lo.y, (k & 4) ? local.hi.z : local.lo.z};
    const Vec3 w = pose.apply(c);
    if (is_finite(w)) box.expand(w);
  }
}

void expand_finite(Aabb& box, const Vec3& p) {
  if (is_finite(p)) box.expand(p);
}

/// The bounds of a mesh's finite positions.
Aabb finite_bounds(const TriMesh& m) {
  Aabb b;
  for (const Vec3& p : m.positions) expand_finite(b, p);
  return b;
}

void put_u32(std::string& out, std::size_t at_byte, std::uint32_t v) {
  out[at_byte] = static_cast<char>(v & 0xff);
  out[at_byte + 1] = static_cast<char>((v >> 8) & 0xff);
  out[at_byte + 2] = static_cast<char>((v >> 16) & 0xff);
  out[at_byte + 3] = static_cast<char>((v >> 24) & 0xff);
}

class Writer {
 public:
  Writer(const Document& doc, const Vec3& origin) : doc_(doc), origin_(origin) {}

  json document() {
    const std::size_t frame_count = doc_.frames.labels.size();
    json j;
    j["schema"] = kViewerSchema;
    j["schema_version"] = kViewerSchemaVersion;
    j["title"] = doc_.title;
    j["command"] = doc_.command;
    j["tool_version"] = doc_.tool_version;
    j["units"] = doc_.units;
    j["verdict"] = doc_.verdict;
    j["notes"] = doc_.notes;
    j["error"] = doc_.error;
    j["origin"] = json::array({origin_.x, origin_.y, origin_.z});
    json legend = json::array();
    for (std::size_t i = 0; i < doc_.legend.size(); ++i)
      legend.push_back({{"label", doc_.legend[i].label}, {"color", color(doc_.legend[i].color, at("legend", i) + ".color")}});
    j["legend"] = std::move(legend);

    // Which meshes are in world coordinates (clash regions) and which local (bodies' meshes).
    world_.assign(doc_.meshes.size(), false);
    std::vector<std::int64_t> used_by_body(doc_.meshes.size(), -1);
    for (std::size_t c = 0; c < doc_.clashes.size(); ++c) {
      const std::int64_t m = doc_.clashes[c].region_mesh;
      if (m < 0) continue;
      if (static_cast<std::size_t>(m) >= doc_.meshes.size())
        throw Invalid{at("clashes", c) + ".region_mesh", "mesh " + std::to_string(m) + " out of range (" +
                                                             std::to_string(doc_.meshes.size()) + " meshes)"};
      world_[static_cast<std::size_t>(m)] = true;
    }
    for (std::size_t b = 0; b < doc_.bodies.size(); ++b) {
      const ViewBody& body = doc_.bodies[b];
      check_mesh_index(body.mesh, at("bodies", b) + ".mesh");
      used_by_body[body.mesh] = static_cast<std::int64_t>(b);
      for (std::size_t f = 0; f < body.frame_meshes.size(); ++f) {
        check_mesh_index(body.frame_meshes[f], at(at("bodies", b) + ".frame_meshes", f));
        used_by_body[body.frame_meshes[f]] = static_cast<std::int64_t>(b);
      }
    }
    for (std::size_t m = 0; m < doc_.meshes.size(); ++m)
      if (world_[m] && used_by_body[m] >= 0)
        throw Invalid{at("meshes", m), "used both as a clash region (world coordinates) and by body " +
                                           std::to_string(used_by_body[m]) + " (local coordinates)"};

    json meshes = json::array();
    for (std::size_t m = 0; m < doc_.meshes.size(); ++m) meshes.push_back(mesh(doc_.meshes[m], m));
    j["meshes"] = std::move(meshes);

    json bodies = json::array();
    for (std::size_t b = 0; b < doc_.bodies.size(); ++b) bodies.push_back(body(doc_.bodies[b], b, frame_count));
    j["bodies"] = std::move(bodies);

    json clashes = json::array();
    for (std::size_t c = 0; c < doc_.clashes.size(); ++c) clashes.push_back(clash(doc_.clashes[c], c, frame_count));
    j["clashes"] = std::move(clashes);

    const ViewFrames& fr = doc_.frames;
    if (!fr.times.empty() && fr.times.size() != frame_count)
      throw Invalid{"frames.times", std::to_string(fr.times.size()) + " times for " + std::to_string(frame_count) +
                                        " frame labels (give one per frame, or none)"};
    if (!fr.verdicts.empty() && fr.verdicts.size() != frame_count)
      throw Invalid{"frames.verdicts", std::to_string(fr.verdicts.size()) + " verdicts for " +
                                           std::to_string(frame_count) + " frame labels (give one per frame, or none)"};
    json times = json::array();
    for (std::size_t f = 0; f < fr.times.size(); ++f) times.push_back(number(fr.times[f], at("frames.times", f)));
    j["frames"] = {{"labels", fr.labels}, {"times", std::move(times)}, {"verdicts", fr.verdicts}};
    return j;
  }

 private:
  double number(double v, const std::string& where) const {
    if (!std::isfinite(v)) throw Invalid{where, std::string("not finite (") + (std::isnan(v) ? "NaN" : "infinite") + ")"};
    return v;
  }
  /// A world point, minus the origin.
  json point(const Vec3& p, const std::string& where) const {
    if (!is_finite(p)) throw Invalid{where, "not finite"};
    const Vec3 q = p - origin_;
    return json::array({number(q.x, where), number(q.y, where), number(q.z, where)});
  }
  /// A number for the nullable fields: < 0 means not known.
  json optional_number(double v, const std::string& where) const {
    number(v, where);
    return v < 0 ? json(nullptr) : json(v);
  }
  json color(const Rgb& c, const std::string& where) const {
    json a = json::array();
    for (float x : c) {
      number(x, where);
      // Rounded to 4 decimals: a float 0.62f would otherwise be written as 0.6200000047683716.
      a.push_back(std::round(static_cast<double>(x) * 1e4) / 1e4);
    }
    return a;
  }
  void check_mesh_index(std::uint32_t m, const std::string& where) const {
    if (m >= doc_.meshes.size())
      throw Invalid{where, "mesh " + std::to_string(m) + " out of range (" + std::to_string(doc_.meshes.size()) + " meshes)"};
  }
  json matrix(const Transform& t, const std::string& where) const {
    for (const auto& row : t.r)
      for (double v : row) number(v, where);
    number(t.t.x, where), number(t.t.y, where), number(t.t.z, where);
    const Vec3 tr = t.t - origin_;
    // Column-major: column k holds R's column k, then the translation column.
    return json::array({t.r[0][0], t.r[1][0], t.r[2][0], 0.0, t.r[0][1], t.r[1][1], t.r[2][1], 0.0, t.r[0][2], t.r[1][2],
                        t.r[2][2], 0.0, number(tr.x, where), number(tr.y, where), number(tr.z, where), 1.0});
  }

  json mesh(const ViewMesh& vm, std::size_t m) const {
    const std::string where = at("meshes", m);
    const TriMesh& tm = vm.mesh;
    const std::size_t nv = tm.num_vertices(), nt = tm.num_triangles();
    if (nv > std::numeric_limits<std::uint32_t>::max())
      throw Invalid{where, std::to_string(nv) + " vertices: more than uint32 indices can address"};
    const bool world = world_[m];
    std::string pos(nv * 12, '\0');
    for (std::size_t v = 0; v < nv; ++v) {
      Vec3 p = tm.positions[v];
      if (!is_finite(p)) throw Invalid{at(where + ".positions", v), "not finite"};
      if (world) p = p - origin_;
      for (int k = 0; k < 3; ++k) {
        const float f = static_cast<float>(p[k]);
        if (!std::isfinite(f))
          throw Invalid{at(where + ".positions", v), "beyond the range of float32 (" + short_number(p[k]) + ")"};
        std::uint32_t bits;
        std::memcpy(&bits, &f, 4);
        put_u32(pos, v * 12 + 4 * static_cast<std::size_t>(k), bits);
      }
    }
    std::string idx(nt * 12, '\0');
    for (std::size_t t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t i = tm.triangles[t][static_cast<std::size_t>(k)];
        if (i >= nv)
          throw Invalid{at(where + ".triangles", t), "vertex " + std::to_string(i) + " out of range (" +
                                                         std::to_string(nv) + " vertices)"};
        put_u32(idx, t * 12 + 4 * static_cast<std::size_t>(k), i);
      }
    json j;
    j["vertices"] = nv;
    j["triangles"] = nt;
    j["positions"] = base64_encode(pos);
    j["indices"] = base64_encode(idx);
    if (!vm.face_colors.empty()) {
      if (vm.face_colors.size() != nt)
        throw Invalid{where + ".face_colors", std::to_string(vm.face_colors.size()) + " values for " + std::to_string(nt) +
                                                  " triangles"};
      std::string fc(nt * 2, '\0');
      for (std::size_t t = 0; t < nt; ++t) {
        const std::uint32_t c = vm.face_colors[t];
        if (c >= doc_.legend.size() || c > 0xffff)
          throw Invalid{at(where + ".face_colors", t), "legend entry " + std::to_string(c) + " out of range (" +
                                                           std::to_string(doc_.legend.size()) + " legend entries)"};
        fc[2 * t] = static_cast<char>(c & 0xff);
        fc[2 * t + 1] = static_cast<char>(c >> 8);
      }
      j["face_colors"] = base64_encode(fc);
    }
    if (!vm.clash_flags.empty()) {
      if (vm.clash_flags.size() != nt)
        throw Invalid{where + ".clash_flags", std::to_string(vm.clash_flags.size()) + " values for " + std::to_string(nt) +
                                                  " triangles"};
      j["clash_flags"] = base64_encode(
          std::string_view(reinterpret_cast<const char*>(vm.clash_flags.data()), vm.clash_flags.size()));
    }
    j["source_triangles"] = vm.source_triangles > 0 ? vm.source_triangles : nt;
    j["decimation_error"] = number(vm.decimation_error, where + ".decimation_error");
    return j;
  }

  json body(const ViewBody& b, std::size_t i, std::size_t frame_count) const {
    const std::string where = at("bodies", i);
    json j;
    j["id"] = b.id;
    j["name"] = b.name;
    j["path"] = b.path;
    j["mesh"] = b.mesh;
    j["role"] = b.role;
    j["visible"] = b.visible;
    j["tags"] = b.tags;
    j["color"] = color(b.color, where + ".color");
    j["pose"] = matrix(b.pose, where + ".pose");
    if (!b.frame_poses.empty()) {
      if (b.frame_poses.size() != frame_count)
        throw Invalid{where + ".frame_poses", std::to_string(b.frame_poses.size()) + " poses for " +
                                                  std::to_string(frame_count) + " frames"};
      json poses = json::array();
      for (std::size_t f = 0; f < b.frame_poses.size(); ++f) poses.push_back(matrix(b.frame_poses[f], at(where + ".frame_poses", f)));
      j["frame_poses"] = std::move(poses);
    }
    if (!b.frame_meshes.empty()) {
      if (b.frame_meshes.size() != frame_count)
        throw Invalid{where + ".frame_meshes", std::to_string(b.frame_meshes.size()) + " meshes for " +
                                                   std::to_string(frame_count) + " frames"};
      j["frame_meshes"] = b.frame_meshes;
    }
    return j;
  }

  json clash(const ViewClash& c, std::size_t i, std::size_t frame_count) const {
    const std::string where = at("clashes", i);
    if (c.verdict != "clash" && c.verdict != "contact" && c.verdict != "clearance" && c.verdict != "undecided")
      throw Invalid{where + ".verdict", "\"" + c.verdict + "\" (expected clash, contact, clearance or undecided)"};
    for (const std::uint32_t b : {c.body_a, c.body_b})
      if (b >= doc_.bodies.size())
        throw Invalid{where + ".bodies", "body " + std::to_string(b) + " out of range (" + std::to_string(doc_.bodies.size()) +
                                             " bodies)"};
    json j;
    j["id"] = c.id;
    j["verdict"] = c.verdict;
    j["status"] = c.status;
    j["kind"] = c.kind;
    j["bodies"] = json::array({c.body_a, c.body_b});
    j["depth"] = optional_number(c.depth, where + ".depth");
    j["depth_bound"] = optional_number(c.depth_bound, where + ".depth_bound");
    j["distance"] = optional_number(c.distance, where + ".distance");
    j["point"] = point(c.point, where + ".point");
    j["box"] = json::array({point(c.box_min, where + ".box"), point(c.box_max, where + ".box")});
    json curves = json::array();
    for (std::size_t k = 0; k < c.curves.size(); ++k) {
      json flat = json::array();
      for (const Vec3& p : c.curves[k]) {
        const json q = point(p, at(where + ".curves", k));
        flat.push_back(q[0]), flat.push_back(q[1]), flat.push_back(q[2]);
      }
      curves.push_back(std::move(flat));
    }
    j["curves"] = std::move(curves);
    j["region_mesh"] = c.region_mesh < 0 ? json(nullptr) : json(c.region_mesh);
    j["witness"] = c.has_witness
                       ? json::array({point(c.witness_a, where + ".witness"), point(c.witness_b, where + ".witness")})
                       : json(nullptr);
    for (std::size_t k = 0; k < c.frames.size(); ++k)
      if (c.frames[k] >= frame_count)
        throw Invalid{at(where + ".frames", k), "frame " + std::to_string(c.frames[k]) + " out of range (" +
                                                    std::to_string(frame_count) + " frames)"};
    j["frames"] = c.frames;
    j["note"] = c.note;
    return j;
  }

  const Document& doc_;
  Vec3 origin_;
  std::vector<bool> world_;
};

}  // namespace

Vec3 document_origin(const Document& doc) {
  Aabb box;
  std::vector<Aabb> local(doc.meshes.size());
  std::vector<bool> known(doc.meshes.size(), false);
  const auto bounds = [&](std::uint32_t m) -> const Aabb& {
    if (!known[m]) local[m] = finite_bounds(doc.meshes[m].mesh), known[m] = true;
    return local[m];
  };
  for (const ViewBody& b : doc.bodies) {
    if (b.mesh < doc.meshes.size()) expand_box_corners(box, bounds(b.mesh), b.pose);
    for (std::size_t f = 0; f < b.frame_poses.size(); ++f) {
      const std::uint32_t m = f < b.frame_meshes.size() ? b.frame_meshes[f] : b.mesh;
      if (m < doc.meshes.size()) expand_box_corners(box, bounds(m), b.frame_poses[f]);
    }
    if (b.frame_poses.empty())
      for (const std::uint32_t m : b.frame_meshes)
        if (m < doc.meshes.size()) expand_box_corners(box, bounds(m), b.pose);
  }
  for (const ViewClash& c : doc.clashes) {
    expand_finite(box, c.point);
    if (is_finite(c.box_min) && is_finite(c.box_max)) expand_finite(box, c.box_min), expand_finite(box, c.box_max);
    for (const auto& curve : c.curves)
      for (const Vec3& p : curve) expand_finite(box, p);
    if (c.has_witness) expand_finite(box, c.witness_a), expand_finite(box, c.witness_b);
    if (c.region_mesh >= 0 && static_cast<std::size_t>(c.region_mesh) < doc.meshes.size())
      box.expand(bounds(static_cast<std::uint32_t>(c.region_mesh)));
  }
  if (box.empty()) return {};
  const Vec3 o = box.center();
  return is_finite(o) ? o : Vec3{};
}

Expected<std::string> document_json(const Document& doc) {
  const Vec3 origin = document_origin(doc);
  try {
    Writer w(doc, origin);
    return w.document().dump(-1, ' ', false, json::error_handler_t::replace);
  } catch (const Invalid& e) {
    return Error{.reason = "viewer document: " + e.where + ": " + e.why};
  }
}

}  // namespace interfere::view
