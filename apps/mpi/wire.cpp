// Encoding of what the ranks exchange (wire.h; issue #31): flat binary records, no DOM. The
// findings were CBOR (nlohmann::json) until 2026-11-29: building and walking those trees for the
// 10^5-body product's ~14,000 clashes (curves, triangle lists) took most of rank 0's 1.5 s merge.
#include "wire.h"

#include <cstring>
#include <stdexcept>
#include <type_traits>

namespace interfere::mpi {
namespace {

struct Writer {
  std::string out;
  template <class T>
  void raw(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void size(std::uint64_t v) {  // (LEB128: most counts and lengths fit one byte)
    while (v >= 0x80) out += static_cast<char>((v & 0x7f) | 0x80), v >>= 7;
    out += static_cast<char>(v);
  }
  void str(const std::string& v) {
    size(v.size());
    out += v;
  }
  template <class T>
  void vec(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    size(v.size());
    out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
};

struct Reader {
  std::string_view in;
  std::size_t at = 0;
  void need(std::size_t n) const {
    if (n > in.size() - at) throw std::runtime_error("interfere-mpi: truncated record");
  }
  template <class T>
  T raw() {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T));
    T v;
    std::memcpy(&v, in.data() + at, sizeof v);
    at += sizeof v;
    return v;
  }
  template <class T>
  void raw(T& v) {
    v = raw<T>();
  }
  std::uint64_t size() {
    std::uint64_t v = 0;
    for (int shift = 0;; shift += 7) {
      need(1);
      const auto c = static_cast<unsigned char>(in[at++]);
      v |= static_cast<std::uint64_t>(c & 0x7f) << shift;
      if (!(c & 0x80)) return v;
      if (shift >= 63) throw std::runtime_error("interfere-mpi: bad record");
    }
  }
  std::string str() {
    const std::uint64_t n = size();
    need(n);
    std::string v(in.data() + at, n);
    at += n;
    return v;
  }
  template <class T>
  void vec(std::vector<T>& v) {
    const std::uint64_t n = size();
    need(n * sizeof(T));
    v.resize(n);
    std::memcpy(v.data(), in.data() + at, n * sizeof(T));
    at += n * sizeof(T);
  }
};

// Body record flags: what the record leaves out.
enum : std::uint16_t {
  kIdIsEntry = 1,        // id == its entry's "id"
  kNameIsId = 2,         // name == id
  kPathIsSlashName = 4,  // path == "/" + name
  kPathIsName = 8,       // path == name
  kFileIsEntry = 16,     // source.file == the entry's resolved file
  kFileIsGiven = 32,     // source.file == the entry's file as given
  kIdentityPose = 64,    // pose == the identity, bit for bit
  kNoDetail = 128,       // source.detail empty
  kNoTags = 256,
  kNoTessellation = 512,  // tessellation_error == +0
  kNoReach = 1024,        // fit_reach == +0
  kUnitMm = 2048,         // unit == "mm"
};

bool same_bits(double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; }

bool identity_pose(const Transform& t) {
  static const std::array<double, 12> id = Transform{}.to_row_major();
  const std::array<double, 12> m = t.to_row_major();
  return std::memcmp(m.data(), id.data(), sizeof m) == 0;
}

void put(Writer& w, const Vec3& v) { w.raw(v.x), w.raw(v.y), w.raw(v.z); }
Vec3 get_vec3(Reader& r) {
  Vec3 v;
  v.x = r.raw<double>(), v.y = r.raw<double>(), v.z = r.raw<double>();
  return v;
}
void put(Writer& w, const Aabb& b) { put(w, b.lo), put(w, b.hi); }
Aabb get_box(Reader& r) {
  Aabb b;
  b.lo = get_vec3(r), b.hi = get_vec3(r);
  return b;
}
void put(Writer& w, const scene::DeepestPoint& d) {
  w.raw(d.body), w.raw(d.vertex), w.raw(d.node), w.raw(d.element), w.raw(d.depth), put(w, d.point), w.raw(d.frame);
}
scene::DeepestPoint get_deepest(Reader& r) {
  scene::DeepestPoint d;
  r.raw(d.body), r.raw(d.vertex), r.raw(d.node), r.raw(d.element), r.raw(d.depth);
  d.point = get_vec3(r);
  r.raw(d.frame);
  return d;
}

void put(Writer& w, const scene::SceneClash& c) {
  w.str(c.id), w.str(c.test), w.raw(c.a), w.raw(c.b), w.raw(c.verdict), w.str(c.kind);
  w.raw(c.depth), w.raw(c.depth_bound), w.raw(c.distance), put(w, c.point), put(w, c.box), w.raw(c.curve_length);
  w.size(c.curves.size());
  for (const Polyline& p : c.curves) {
    w.size(p.points.size());
    for (const Vec3& v : p.points) put(w, v);
    w.raw(p.closed), w.raw(p.length);
  }
  w.size(c.cross_pairs), w.size(c.touch_pairs);
  w.vec(c.triangles_a), w.vec(c.triangles_b), w.vec(c.source_ids_a), w.vec(c.source_ids_b);
  put(w, c.witness_a), put(w, c.witness_b);
  w.size(c.reasons.size());
  for (const std::string& x : c.reasons) w.str(x);
  w.vec(c.frames);
  w.raw(c.has_deepest), put(w, c.deepest), w.raw(c.designed);
}
scene::SceneClash get_clash(Reader& r) {
  scene::SceneClash c;
  c.id = r.str(), c.test = r.str(), r.raw(c.a), r.raw(c.b), r.raw(c.verdict), c.kind = r.str();
  r.raw(c.depth), r.raw(c.depth_bound), r.raw(c.distance);
  c.point = get_vec3(r), c.box = get_box(r);
  r.raw(c.curve_length);
  c.curves.resize(r.size());
  for (Polyline& p : c.curves) {
    p.points.resize(r.size());
    for (Vec3& v : p.points) v = get_vec3(r);
    r.raw(p.closed), r.raw(p.length);
  }
  c.cross_pairs = r.size(), c.touch_pairs = r.size();
  r.vec(c.triangles_a), r.vec(c.triangles_b), r.vec(c.source_ids_a), r.vec(c.source_ids_b);
  c.witness_a = get_vec3(r), c.witness_b = get_vec3(r);
  c.reasons.resize(r.size());
  for (std::string& x : c.reasons) x = r.str();
  r.vec(c.frames);
  r.raw(c.has_deepest);
  c.deepest = get_deepest(r);
  r.raw(c.designed);
  return c;
}

}  // namespace

std::string encode(const std::vector<BodyInfo>& bodies, const std::vector<scene::BodySpec>& entries) {
  Writer w;
  w.out.reserve(16 + bodies.size() * 96);
  w.raw(static_cast<std::uint64_t>(bodies.size()));
  std::uint32_t last_spec = 0;
  for (const BodyInfo& b : bodies) {
    const scene::Body& m = b.meta;
    const scene::BodySpec& e = entries.at(b.spec);
    const std::array<double, 12> pose = m.pose.to_row_major();
    std::uint16_t flags = 0;
    if (m.id == e.id) flags |= kIdIsEntry;
    if (m.name == m.id) flags |= kNameIsId;
    if (m.path.size() == m.name.size() + 1 && m.path[0] == '/' && m.path.compare(1, std::string::npos, m.name) == 0) flags |= kPathIsSlashName;
    else if (m.path == m.name) flags |= kPathIsName;
    if (m.source.file == e.file) flags |= kFileIsEntry;
    else if (m.source.file == e.given) flags |= kFileIsGiven;
    if (identity_pose(m.pose)) flags |= kIdentityPose;
    if (m.source.detail.empty()) flags |= kNoDetail;
    if (m.tags.empty()) flags |= kNoTags;
    if (same_bits(m.tessellation_error, 0.0)) flags |= kNoTessellation;
    if (same_bits(b.fit_reach, 0.0)) flags |= kNoReach;
    if (m.unit == "mm") flags |= kUnitMm;
    w.raw(flags);
    // (entries in file order: the spec index as a step from the previous body's)
    w.size(b.spec - last_spec), w.size(b.ordinal);
    last_spec = b.spec;
    if (!(flags & kIdIsEntry)) w.str(m.id);
    if (!(flags & kNameIsId)) w.str(m.name);
    if (!(flags & (kPathIsSlashName | kPathIsName))) w.str(m.path);
    w.raw(static_cast<std::uint8_t>(m.source.kind));
    if (!(flags & (kFileIsEntry | kFileIsGiven))) w.str(m.source.file);
    if (!(flags & kNoDetail)) w.str(m.source.detail);
    if (!(flags & kUnitMm)) w.str(m.unit);
    if (!(flags & kIdentityPose)) w.raw(pose);
    if (!(flags & kNoTags)) {
      w.size(m.tags.size());
      for (const std::string& t : m.tags) w.str(t);
    }
    w.raw(static_cast<std::uint8_t>(m.source_id_kind));
    if (!(flags & kNoTessellation)) w.raw(m.tessellation_error);
    w.size(b.triangles), put(w, b.local_box), w.raw(b.mesh_key);
    if (!(flags & kNoReach)) w.raw(b.fit_reach);
  }
  return std::move(w.out);
}

std::size_t count_bodies(std::string_view bytes) {
  Reader r{bytes};
  return r.raw<std::uint64_t>();
}

void decode_bodies(std::string_view bytes, const std::vector<scene::BodySpec>& entries, std::vector<BodyInfo>& out) {
  Reader r{bytes};
  const auto count = r.raw<std::uint64_t>();
  std::uint32_t spec = 0;
  for (std::uint64_t k = 0; k < count; ++k) {
    BodyInfo& b = out.emplace_back();
    scene::Body& m = b.meta;
    const auto flags = r.raw<std::uint16_t>();
    spec += static_cast<std::uint32_t>(r.size());
    b.spec = spec, b.ordinal = static_cast<std::uint32_t>(r.size());
    if (b.spec >= entries.size()) throw std::runtime_error("interfere-mpi: body record of an entry out of range");
    const scene::BodySpec& e = entries[b.spec];
    m.id = flags & kIdIsEntry ? e.id : r.str();
    m.name = flags & kNameIsId ? m.id : r.str();
    if (flags & kPathIsSlashName) m.path.reserve(m.name.size() + 1), m.path += '/', m.path += m.name;
    else m.path = flags & kPathIsName ? m.name : r.str();
    m.source.kind = static_cast<scene::SourceKind>(r.raw<std::uint8_t>());
    m.source.file = flags & kFileIsEntry ? e.file : flags & kFileIsGiven ? e.given : r.str();
    if (!(flags & kNoDetail)) m.source.detail = r.str();
    m.unit = flags & kUnitMm ? std::string("mm") : r.str();
    if (!(flags & kIdentityPose)) {
      const auto t = r.raw<std::array<double, 12>>();
      for (int row = 0; row < 3; ++row)
        for (int c = 0; c < 3; ++c) m.pose.r[row][c] = t[4 * row + c];
      m.pose.t = {t[3], t[7], t[11]};
    }
    if (!(flags & kNoTags)) {
      m.tags.resize(r.size());
      for (std::string& x : m.tags) x = r.str();
    }
    m.source_id_kind = static_cast<scene::SourceIdKind>(r.raw<std::uint8_t>());
    if (!(flags & kNoTessellation)) r.raw(m.tessellation_error);
    b.triangles = r.size(), b.local_box = get_box(r), r.raw(b.mesh_key);
    if (!(flags & kNoReach)) r.raw(b.fit_reach);
  }
}

std::string encode(const RankResult& r) {
  Writer w;
  w.size(r.clashes.size());
  for (const scene::SceneClash& c : r.clashes) put(w, c);
  w.size(r.frames.size());
  for (const scene::FrameRow& f : r.frames) {
    w.raw(f.frame), w.str(f.label), w.raw(f.time), w.size(f.clashes), w.size(f.contacts), w.size(f.clearances);
    w.size(f.undecided), w.raw(f.min_distance), w.raw(f.max_depth), w.raw(f.verdict);
  }
  w.size(r.frame_pairs.size());
  for (const scene::FramePairRow& f : r.frame_pairs) {
    w.raw(f.frame), w.raw(f.test), w.raw(f.a), w.raw(f.b), w.raw(f.verdict), w.size(f.clashes), w.size(f.contacts);
    w.size(f.clearances), w.size(f.undecided), w.raw(f.min_distance), w.raw(f.max_depth), w.raw(f.max_depth_bound);
    w.raw(f.has_deepest), put(w, f.deepest);
  }
  w.size(r.reference_pairs.size());
  for (const scene::ReferencePair& p : r.reference_pairs) w.raw(p.test), w.raw(p.a), w.raw(p.b), w.raw(p.verdict);
  w.size(r.warnings.size());
  for (const std::string& x : r.warnings) w.str(x);
  for (const std::uint64_t n : {std::uint64_t(r.core_runs), std::uint64_t(r.calls), std::uint64_t(r.pairs), std::uint64_t(r.bodies_loaded),
                                r.pair_triangles, r.triangles_loaded, std::uint64_t(r.bodies_used), r.body_triangles})
    w.size(n);
  w.raw(r.reference_checked);
  for (const double t : {r.load_seconds, r.engine_seconds, r.prepare_seconds, r.broad_seconds, r.narrow_seconds, r.peak_rss_mb,
                         r.cpu_seconds, r.load_cpu_seconds, r.engine_cpu_seconds})
    w.raw(t);
  w.size(r.phases.size());
  for (const auto& p : r.phases) w.raw(p);
  return std::move(w.out);
}

RankResult decode_result(std::string_view bytes) {
  Reader in{bytes};
  RankResult r;
  r.clashes.resize(in.size());
  for (scene::SceneClash& c : r.clashes) c = get_clash(in);
  r.frames.resize(in.size());
  for (scene::FrameRow& f : r.frames) {
    in.raw(f.frame), f.label = in.str(), in.raw(f.time), f.clashes = in.size(), f.contacts = in.size(), f.clearances = in.size();
    f.undecided = in.size(), in.raw(f.min_distance), in.raw(f.max_depth), in.raw(f.verdict);
  }
  r.frame_pairs.resize(in.size());
  for (scene::FramePairRow& f : r.frame_pairs) {
    in.raw(f.frame), in.raw(f.test), in.raw(f.a), in.raw(f.b), in.raw(f.verdict), f.clashes = in.size(), f.contacts = in.size();
    f.clearances = in.size(), f.undecided = in.size(), in.raw(f.min_distance), in.raw(f.max_depth), in.raw(f.max_depth_bound);
    in.raw(f.has_deepest), f.deepest = get_deepest(in);
  }
  r.reference_pairs.resize(in.size());
  for (scene::ReferencePair& p : r.reference_pairs) in.raw(p.test), in.raw(p.a), in.raw(p.b), in.raw(p.verdict);
  r.warnings.resize(in.size());
  for (std::string& x : r.warnings) x = in.str();
  r.core_runs = in.size(), r.calls = in.size(), r.pairs = in.size(), r.bodies_loaded = in.size();
  r.pair_triangles = in.size(), r.triangles_loaded = in.size(), r.bodies_used = in.size(), r.body_triangles = in.size();
  in.raw(r.reference_checked);
  for (double* t : {&r.load_seconds, &r.engine_seconds, &r.prepare_seconds, &r.broad_seconds, &r.narrow_seconds, &r.peak_rss_mb,
                    &r.cpu_seconds, &r.load_cpu_seconds, &r.engine_cpu_seconds})
    in.raw(*t);
  r.phases.resize(in.size());
  for (auto& p : r.phases) in.raw(p);
  if (in.at != bytes.size()) throw std::runtime_error("interfere-mpi: findings record of the wrong length");
  return r;
}

}  // namespace interfere::mpi
