// Encoding of what the ranks exchange (body records binary, findings CBOR) (wire.h; issue #31).
#include "wire.h"

#include <cstring>
#include <stdexcept>

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

// Body metadata: a flat binary record a body (10^5 bodies: CBOR trees cost seconds a rank to
// build and walk, and every rank decodes every body). Little-endian host order: the ranks of one
// job run one binary.
namespace {

struct Writer {
  std::string out;
  template <class T>
  void raw(const T& v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void str(const std::string& v) {
    raw(static_cast<std::uint32_t>(v.size()));
    out += v;
  }
};

struct Reader {
  const std::string& in;
  std::size_t at = 0;
  template <class T>
  T raw() {
    if (at + sizeof(T) > in.size()) throw std::runtime_error("interfere-mpi: truncated body record");
    T v;
    std::memcpy(&v, in.data() + at, sizeof v);
    at += sizeof v;
    return v;
  }
  std::string str() {
    const auto n = raw<std::uint32_t>();
    if (at + n > in.size()) throw std::runtime_error("interfere-mpi: truncated body record");
    std::string v(in.data() + at, n);
    at += n;
    return v;
  }
};

}  // namespace

std::string encode(const std::vector<BodyInfo>& bodies) {
  Writer w;
  w.raw(static_cast<std::uint64_t>(bodies.size()));
  for (const BodyInfo& b : bodies) {
    const scene::Body& m = b.meta;
    w.str(m.id), w.str(m.name), w.str(m.path);
    w.raw(static_cast<std::int32_t>(m.source.kind)), w.str(m.source.file), w.str(m.source.detail), w.str(m.unit);
    w.raw(m.pose.to_row_major());
    w.raw(static_cast<std::uint32_t>(m.tags.size()));
    for (const std::string& t : m.tags) w.str(t);
    w.raw(static_cast<std::int32_t>(m.source_id_kind)), w.raw(m.tessellation_error);
    w.raw(b.triangles), w.raw(b.local_box.lo), w.raw(b.local_box.hi), w.raw(b.spec), w.raw(b.ordinal), w.raw(b.mesh_key), w.raw(b.fit_reach);
  }
  return std::move(w.out);
}

std::vector<BodyInfo> decode_bodies(const std::string& bytes) {
  Reader r{bytes};
  std::vector<BodyInfo> out(r.raw<std::uint64_t>());
  for (BodyInfo& b : out) {
    scene::Body& m = b.meta;
    m.id = r.str(), m.name = r.str(), m.path = r.str();
    m.source.kind = static_cast<scene::SourceKind>(r.raw<std::int32_t>());
    m.source.file = r.str(), m.source.detail = r.str(), m.unit = r.str();
    const auto t = r.raw<std::array<double, 12>>();
    for (int row = 0; row < 3; ++row)
      for (int c = 0; c < 3; ++c) m.pose.r[row][c] = t[4 * row + c];
    m.pose.t = {t[3], t[7], t[11]};
    m.tags.resize(r.raw<std::uint32_t>());
    for (std::string& x : m.tags) x = r.str();
    m.source_id_kind = static_cast<scene::SourceIdKind>(r.raw<std::int32_t>());
    m.tessellation_error = r.raw<double>();
    b.triangles = r.raw<std::uint64_t>(), b.local_box.lo = r.raw<Vec3>(), b.local_box.hi = r.raw<Vec3>();
    b.spec = r.raw<std::uint32_t>(), b.ordinal = r.raw<std::uint32_t>(), b.mesh_key = r.raw<std::uint64_t>();
    b.fit_reach = r.raw<double>();
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
  j["ph"] = r.phases;
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
  r.phases = j["ph"].get<std::vector<std::array<double, 2>>>();
  return r;
}

}  // namespace interfere::mpi
