// CBOR encoding of what the ranks exchange (wire.h; issue #31).
#include "wire.h"

#include <nlohmann/json.hpp>

namespace interfere::mpi {
namespace {

using nlohmann::json;

json v3(const Vec3& v) { return json::array({v.x, v.y, v.z}); }
Vec3 v3(const json& j) { return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()}; }
json box(const Aabb& b) { return json::array({v3(b.lo), v3(b.hi)}); }
Aabb box(const json& j) {
  Aabb b;
  b.lo = v3(j[0]), b.hi = v3(j[1]);
  return b;
}
json pose(const Transform& t) {
  const auto m = t.to_row_major();
  return json(std::vector<double>(m.begin(), m.end()));
}
Transform pose(const json& j) {
  Transform t;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) t.r[r][c] = j[4 * r + c].get<double>();
  }
  t.t = {j[3].get<double>(), j[7].get<double>(), j[11].get<double>()};
  return t;
}
json deepest(const scene::DeepestPoint& d) {
  return json::array({d.body, d.vertex, d.node, d.element, d.depth, v3(d.point), d.frame});
}
scene::DeepestPoint deepest(const json& j) {
  return {.body = j[0].get<std::uint32_t>(), .vertex = j[1].get<std::uint32_t>(), .node = j[2].get<std::int64_t>(),
          .element = j[3].get<std::int64_t>(), .depth = j[4].get<double>(), .point = v3(j[5]), .frame = j[6].get<std::uint32_t>()};
}
template <class E>
int ev(E e) {
  return static_cast<int>(e);
}

json clash(const scene::SceneClash& c) {
  json curves = json::array();
  for (const Polyline& p : c.curves) {
    json pts = json::array();
    for (const Vec3& v : p.points) pts.push_back(v3(v));
    curves.push_back({pts, p.closed, p.length});
  }
  return {{"id", c.id}, {"test", c.test}, {"a", c.a}, {"b", c.b}, {"verdict", ev(c.verdict)}, {"kind", c.kind},
          {"depth", c.depth}, {"bound", c.depth_bound}, {"dist", c.distance}, {"point", v3(c.point)}, {"box", box(c.box)},
          {"len", c.curve_length}, {"curves", curves}, {"cross", c.cross_pairs}, {"touch", c.touch_pairs},
          {"ta", c.triangles_a}, {"tb", c.triangles_b}, {"sa", c.source_ids_a}, {"sb", c.source_ids_b},
          {"wa", v3(c.witness_a)}, {"wb", v3(c.witness_b)}, {"reasons", c.reasons}, {"frames", c.frames},
          {"has_deepest", c.has_deepest}, {"deepest", deepest(c.deepest)}, {"designed", c.designed}};
}
scene::SceneClash clash(const json& j) {
  scene::SceneClash c;
  c.id = j["id"], c.test = j["test"], c.a = j["a"], c.b = j["b"];
  c.verdict = static_cast<Verdict>(j["verdict"].get<int>());
  c.kind = j["kind"], c.depth = j["depth"], c.depth_bound = j["bound"], c.distance = j["dist"];
  c.point = v3(j["point"]), c.box = box(j["box"]), c.curve_length = j["len"];
  for (const json& p : j["curves"]) {
    Polyline l;
    for (const json& v : p[0]) l.points.push_back(v3(v));
    l.closed = p[1], l.length = p[2];
    c.curves.push_back(std::move(l));
  }
  c.cross_pairs = j["cross"], c.touch_pairs = j["touch"];
  c.triangles_a = j["ta"].get<std::vector<std::uint32_t>>(), c.triangles_b = j["tb"].get<std::vector<std::uint32_t>>();
  c.source_ids_a = j["sa"].get<std::vector<std::int64_t>>(), c.source_ids_b = j["sb"].get<std::vector<std::int64_t>>();
  c.witness_a = v3(j["wa"]), c.witness_b = v3(j["wb"]);
  c.reasons = j["reasons"].get<std::vector<std::string>>();
  c.frames = j["frames"].get<std::vector<std::uint32_t>>();
  c.has_deepest = j["has_deepest"], c.deepest = deepest(j["deepest"]), c.designed = j["designed"];
  return c;
}

}  // namespace

std::string encode(const std::vector<BodyInfo>& bodies) {
  json a = json::array();
  for (const BodyInfo& b : bodies) {
    const scene::Body& m = b.meta;
    a.push_back({m.id, m.name, m.path, ev(m.source.kind), m.source.file, m.source.detail, m.unit, pose(m.pose), m.tags,
                 ev(m.source_id_kind), m.tessellation_error, b.triangles, box(b.local_box), b.spec, b.ordinal, b.mesh_key});
  }
  const std::vector<std::uint8_t> v = json::to_cbor(a);
  return {v.begin(), v.end()};
}

std::vector<BodyInfo> decode_bodies(const std::string& bytes) {
  const json a = json::from_cbor(bytes);
  std::vector<BodyInfo> out;
  for (const json& j : a) {
    BodyInfo b;
    scene::Body& m = b.meta;
    m.id = j[0], m.name = j[1], m.path = j[2];
    m.source.kind = static_cast<scene::SourceKind>(j[3].get<int>());
    m.source.file = j[4], m.source.detail = j[5], m.unit = j[6], m.pose = pose(j[7]);
    m.tags = j[8].get<std::vector<std::string>>();
    m.source_id_kind = static_cast<scene::SourceIdKind>(j[9].get<int>());
    m.tessellation_error = j[10];
    b.triangles = j[11], b.local_box = box(j[12]), b.spec = j[13], b.ordinal = j[14], b.mesh_key = j[15];
    out.push_back(std::move(b));
  }
  return out;
}

std::string encode(const RankResult& r) {
  json j;
  j["clashes"] = json::array();
  for (const scene::SceneClash& c : r.clashes) j["clashes"].push_back(clash(c));
  j["frames"] = json::array();
  for (const scene::FrameRow& f : r.frames)
    j["frames"].push_back({f.frame, f.label, f.time, f.clashes, f.contacts, f.clearances, f.undecided, f.min_distance,
                           f.max_depth, ev(f.verdict)});
  j["frame_pairs"] = json::array();
  for (const scene::FramePairRow& f : r.frame_pairs)
    j["frame_pairs"].push_back({f.frame, f.test, f.a, f.b, ev(f.verdict), f.clashes, f.contacts, f.clearances, f.undecided,
                                f.min_distance, f.max_depth, f.max_depth_bound, f.has_deepest, deepest(f.deepest)});
  j["reference_pairs"] = json::array();
  for (const scene::ReferencePair& p : r.reference_pairs) j["reference_pairs"].push_back({p.test, p.a, p.b, ev(p.verdict)});
  j["warnings"] = r.warnings;
  j["n"] = {r.core_runs, r.calls, r.pairs, r.bodies_loaded, r.pair_triangles, r.triangles_loaded, r.bodies_used, r.body_triangles};
  j["reference_checked"] = r.reference_checked;
  j["t"] = {r.load_seconds, r.engine_seconds, r.prepare_seconds, r.broad_seconds, r.narrow_seconds, r.peak_rss_mb, r.cpu_seconds, r.load_cpu_seconds, r.engine_cpu_seconds};
  const std::vector<std::uint8_t> v = json::to_cbor(j);
  return {v.begin(), v.end()};
}

RankResult decode_result(const std::string& bytes) {
  const json j = json::from_cbor(bytes);
  RankResult r;
  for (const json& c : j["clashes"]) r.clashes.push_back(clash(c));
  for (const json& f : j["frames"])
    r.frames.push_back({.frame = f[0], .label = f[1], .time = f[2], .clashes = f[3], .contacts = f[4], .clearances = f[5],
                        .undecided = f[6], .min_distance = f[7], .max_depth = f[8], .verdict = static_cast<Verdict>(f[9].get<int>())});
  for (const json& f : j["frame_pairs"])
    r.frame_pairs.push_back({.frame = f[0], .test = f[1], .a = f[2], .b = f[3], .verdict = static_cast<Verdict>(f[4].get<int>()),
                             .clashes = f[5], .contacts = f[6], .clearances = f[7], .undecided = f[8], .min_distance = f[9],
                             .max_depth = f[10], .max_depth_bound = f[11], .has_deepest = f[12], .deepest = deepest(f[13])});
  for (const json& p : j["reference_pairs"])
    r.reference_pairs.push_back({.test = p[0], .a = p[1], .b = p[2], .verdict = static_cast<Verdict>(p[3].get<int>())});
  r.warnings = j["warnings"].get<std::vector<std::string>>();
  r.core_runs = j["n"][0], r.calls = j["n"][1], r.pairs = j["n"][2], r.bodies_loaded = j["n"][3];
  r.pair_triangles = j["n"][4], r.triangles_loaded = j["n"][5];
  r.bodies_used = j["n"][6], r.body_triangles = j["n"][7];
  r.reference_checked = j["reference_checked"];
  r.load_seconds = j["t"][0], r.engine_seconds = j["t"][1], r.prepare_seconds = j["t"][2], r.broad_seconds = j["t"][3];
  r.narrow_seconds = j["t"][4], r.peak_rss_mb = j["t"][5], r.cpu_seconds = j["t"][6];
  r.load_cpu_seconds = j["t"][7], r.engine_cpu_seconds = j["t"][8];
  return r;
}

}  // namespace interfere::mpi
