// Fuzz target `simplify` (issue #6, items 5-6): interfere::simplify on small meshes decoded from the
// bytes, every option combination, checked against the guarantees docs/simplify.md states.
//
// Layout: byte 0 = shape (bits 0-1: 0 height field, 1 bumpy sphere with moved vertices, 2 triangle
// soup, 3 height field scaled by 2^(byte 3 - 128) and moved far from the origin) | feature mode
// (bits 2-3: none, weight, last, lock) | sharp-angle regions (bit 4) | guard every collapse (bit 5)
// | no batched passes (bit 6); byte 1: ratio = (byte % 100 + 1) / 100; byte 2: size; the rest feeds
// the shape (heights, moves, coordinates, region ids).
//
// Checks:
//  - simplify() fails only when the ratio leaves no triangle or every triangle is degenerate, with
//    a reason;
//  - the result has finite positions, indices in range, one face id per triangle (ids of the input),
//    and every face whose seams are kept is still there; with max_error, an error bound within it;
//  - no more triangles than the input's non-degenerate ones; `reached` means exactly the budget;
//  - no self-intersection the input did not have: both triangles of every intersecting pair of the
//    result are triangles of the input (same corners);
//  - lock mode: every non-degenerate feature triangle of the input is in the result, corners bit
//    for bit;
//  - 0 <= hausdorff <= error_bound, both finite, and the error bound covers 16 points of the input
//    surface (brute-force distance to every output triangle);
//  - the same result, bit for bit, with one thread.
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "fuzz_common.h"
#include "interfere/mesh/generate.h"
#include "interfere/np/distance.h"
#include "interfere/np/tri_tri.h"
#include "interfere/simplify/hausdorff.h"
#include "interfere/simplify/qem.h"

namespace {

using interfere::SimplifyOptions;
using interfere::SimplifyResult;
using interfere::Tri;
using interfere::TriMesh;
using interfere::Vec3;

struct Reader {
  const std::uint8_t* data;
  std::size_t size, at = 0;
  std::uint8_t next() { return at < size ? data[at++] : 0; }
  bool more() const { return at < size; }
};

bool degenerate(const TriMesh& m, std::size_t t) {
  const auto c = m.corners(t);
  return c[0] == c[1] || c[1] == c[2] || c[0] == c[2];
}

using Key = std::array<double, 9>;
Key key_of(std::array<Vec3, 3> c) {
  std::sort(c.begin(), c.end(), [](const Vec3& a, const Vec3& b) {
    return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.z < b.z)));
  });
  return {c[0].x, c[0].y, c[0].z, c[1].x, c[1].y, c[1].z, c[2].x, c[2].y, c[2].z};
}

TriMesh height_field(Reader& in, int n, double scale, Vec3 offset, std::vector<std::uint32_t>& face) {
  TriMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      m.positions.push_back({std::ldexp(double(i), int(scale)) + offset.x, std::ldexp(double(j), int(scale)) + offset.y,
                             std::ldexp(double(static_cast<std::int8_t>(in.next())) / 16, int(scale)) + offset.z});
  auto id = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool flip = (in.next() & 1) != 0;  // the diagonal of the quad
      if (flip) {
        m.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        m.triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  for (std::size_t t = 0; t < m.num_triangles(); ++t) face.push_back((in.next() >> 6) & 3u);
  return m;
}

TriMesh decode(Reader& in, int shape, std::vector<std::uint32_t>& face) {
  const int size = in.next();
  switch (shape) {
    case 0: return height_field(in, 2 + size % 12, 0, {}, face);
    case 3: {
      const int e = static_cast<int>(in.next()) - 128;
      const Vec3 off{std::ldexp(3.0, e + 30), std::ldexp(-5.0, e + 28), 0.0};
      return height_field(in, 2 + size % 12, e, off, face);
    }
    case 1: {
      TriMesh m = interfere::make_sphere({.target_triangles = std::size_t(40 + 4 * size), .bump_amplitude = 0.1});
      while (in.more()) {  // move vertices: index, axis, amount
        const std::size_t v = (std::size_t(in.next()) << 8 | in.next()) % m.num_vertices();
        const int axis = in.next() % 3;
        const double d = static_cast<std::int8_t>(in.next()) / 64.0;
        (axis == 0 ? m.positions[v].x : axis == 1 ? m.positions[v].y : m.positions[v].z) += d;
      }
      for (std::size_t t = 0; t < m.num_triangles(); ++t) face.push_back(m.corners(t)[0].z > 0.5 ? 1u : 0u);
      return m;
    }
    default: {
      TriMesh m;
      const std::size_t nv = 4 + size % 60;
      for (std::size_t v = 0; v < nv; ++v)
        m.positions.push_back({static_cast<std::int8_t>(in.next()) / 8.0, static_cast<std::int8_t>(in.next()) / 8.0,
                               static_cast<std::int8_t>(in.next()) / 8.0});
      while (in.more() && m.num_triangles() < 300) {
        const Tri t{std::uint32_t(in.next() % nv), std::uint32_t(in.next() % nv), std::uint32_t(in.next() % nv)};
        m.triangles.push_back(t);
        face.push_back(t[0] % 2);
      }
      return m;
    }
  }
}

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

std::string tag(const SimplifyOptions& o, int shape) {
  return " (shape " + std::to_string(shape) + ", ratio " + std::to_string(o.ratio) + ", features " +
         std::to_string(o.feature_faces.size()) + " mode " + std::to_string(int(o.feature_mode)) +
         (o.inherit_input_contacts ? "" : ", strict guard") + ", seams " + std::to_string(int(o.seams)) + ")";
}

int entry(const std::uint8_t* data, std::size_t size) {
  if (size < 3) return 0;
  Reader in{data, size};
  const std::uint8_t flags = in.next();
  const int shape = flags & 3;
  SimplifyOptions o;
  o.ratio = double(in.next() % 100 + 1) / 100;
  std::vector<std::uint32_t> face;
  const TriMesh mesh = decode(in, shape, face);
  if (mesh.num_triangles() == 0) return 0;
  const int mode = (flags >> 2) & 3;
  if (mode > 0) {
    o.face_ids = face;
    o.feature_faces = {1};
    o.feature_mode = mode == 1 ? interfere::FeatureMode::weight
                     : mode == 2 ? interfere::FeatureMode::last
                                 : interfere::FeatureMode::lock;
  }
  if (flags & 16) o.sharp_angle_deg = 30;
  if (flags & 32) o.guard_every_collapse = true;
  if (flags & 64) o.batched_passes = false;
  if (flags & 128) o.inherit_input_contacts = false;
  o.seams = static_cast<interfere::SeamMode>(data[size - 1] % 4);  // (the last byte: decoding unchanged)
  if ((data[size - 1] >> 2) % 4 == 3) o.max_error = 1e-3 * interfere::norm(mesh.bounds().extent());  // (0 for a point)
  const std::string where = tag(o, shape) + (o.max_error > 0 ? " max_error " + num(o.max_error) : "");

  std::size_t live = 0;
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) live += degenerate(mesh, t) ? 0 : 1;
  const std::size_t target = static_cast<std::size_t>(std::llround(o.ratio * double(mesh.num_triangles())));
  const auto r = interfere::simplify(mesh, o);
  if (!r) {
    FUZZ_CHECK(!r.error().reason.empty(), "an error without a reason" + where);
    FUZZ_CHECK(target == 0 || live == 0, "simplify failed: " + r.error().reason + where);
    return 0;
  }
  FUZZ_CHECK(live > 0 && target > 0, "a result where an error was due" + where);
  const TriMesh& out = r->mesh;
  for (const Vec3& p : out.positions) FUZZ_CHECK(interfere::is_finite(p), "non-finite output position" + where);
  for (const Tri& t : out.triangles)
    for (std::uint32_t v : t) FUZZ_CHECK(v < out.num_vertices(), "output index out of range" + where);
  if (!o.face_ids.empty()) {
    FUZZ_CHECK(r->face_ids.size() == out.num_triangles(), "face ids do not match the triangles" + where);
    for (std::uint32_t f : r->face_ids)
      FUZZ_CHECK(std::find(face.begin(), face.end(), f) != face.end(), "an output face id the input lacks" + where);
    // No face whose seams are kept vanishes: every face (seams all, or auto where every seam
    // held), the feature faces (features, or auto relaxed).
    const bool all_kept = o.seams == interfere::SeamMode::all ||
                          (o.seams == interfere::SeamMode::as_needed && r->seams_relaxed_at == 0);
    const bool features_kept = all_kept || o.seams != interfere::SeamMode::none;
    for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
      const std::uint32_t f = face[t];
      const bool kept = all_kept || (features_kept && f == 1);
      if (!kept || degenerate(mesh, t)) continue;
      FUZZ_CHECK(std::find(r->face_ids.begin(), r->face_ids.end(), f) != r->face_ids.end(),
                 "face " + std::to_string(f) + " vanished" + where);
    }
  }
  FUZZ_CHECK(out.num_triangles() <= live, "more triangles than the input's non-degenerate ones" + where);
  FUZZ_CHECK(!r->reached || out.num_triangles() == target, "reached, yet not the budget" + where);
  // max_error: within it, or the input's own count (its rounding margin alone above it).
  if (o.max_error > 0)
    FUZZ_CHECK(r->error_bound <= o.max_error || r->error_limited_budget >= live,
               "error bound " + num(r->error_bound) + " above max_error" + where);

  // No new self-intersection.
  std::vector<Key> in_keys;
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) in_keys.push_back(key_of(mesh.corners(t)));
  std::sort(in_keys.begin(), in_keys.end());
  const auto is_input = [&](std::uint32_t t) {
    return std::binary_search(in_keys.begin(), in_keys.end(), key_of(out.corners(t)));
  };
  // Inheriting the input's contacts, a moved pair must meet inside the input's contact zone: here
  // by brute force over all the input's pairs (the engine makes the zone near new pairs only, a
  // subset), each pair's box grown by its diagonal holding where the two triangles meet.
  std::vector<interfere::Aabb> zone;
  if (o.inherit_input_contacts)
    for (const auto& [a, b] : interfere::self_intersecting_pairs(mesh)) {
      interfere::Aabb z = mesh.triangle_box(a);
      z.expand(mesh.triangle_box(b));
      const double g = interfere::norm(z.extent());
      zone.push_back({z.lo - Vec3{g, g, g}, z.hi + Vec3{g, g, g}});
    }
  const auto in_zone = [&](std::uint32_t a, std::uint32_t b) {
    const interfere::Aabb ba = out.triangle_box(a), bb = out.triangle_box(b);
    interfere::Aabb meet{max(ba.lo, bb.lo), min(ba.hi, bb.hi)};
    const interfere::TriTriResult c = interfere::tri_tri_exact(out.corners(a), out.corners(b));
    if (c.kind == interfere::ContactKind::cross) {  // the segment, generously padded
      const double pad = 1e-9 * (norm(ba.extent()) + norm(bb.extent()));
      for (int k = 0; k < 3; ++k) {
        meet.lo[k] = std::max(meet.lo[k], std::min(c.segment[0][k], c.segment[1][k]) - pad);
        meet.hi[k] = std::min(meet.hi[k], std::max(c.segment[0][k], c.segment[1][k]) + pad);
      }
    }
    for (const interfere::Aabb& z : zone)
      if (z.contains(meet.lo) && z.contains(meet.hi)) return true;
    return false;
  };
  std::size_t moved = 0;
  for (const auto& [a, b] : interfere::self_intersecting_pairs(out)) {
    if (is_input(a) && is_input(b)) continue;
    ++moved;
    FUZZ_CHECK(in_zone(a, b), "a self-intersection the input did not have: triangles " + std::to_string(a) + ", " +
                                  std::to_string(b) + where);
  }
  FUZZ_CHECK(moved == r->inherited_pairs, "inherited_pairs " + std::to_string(r->inherited_pairs) + ", found " +
                                              std::to_string(moved) + where);

  // Lock mode keeps every feature triangle bit for bit.
  if (o.feature_mode == interfere::FeatureMode::lock && !o.feature_faces.empty()) {
    std::vector<Key> out_keys;
    for (std::size_t t = 0; t < out.num_triangles(); ++t) out_keys.push_back(key_of(out.corners(t)));
    std::sort(out_keys.begin(), out_keys.end());
    for (std::size_t t = 0; t < mesh.num_triangles(); ++t)
      if (face[t] == 1 && !degenerate(mesh, t))
        FUZZ_CHECK(std::binary_search(out_keys.begin(), out_keys.end(), key_of(mesh.corners(t))),
                   "locked feature triangle " + std::to_string(t) + " changed" + where);
  }

  // The error: measured, bounded, and the bound covers points of the input surface.
  FUZZ_CHECK(std::isfinite(r->hausdorff) && r->hausdorff >= 0, "hausdorff not finite" + where);
  FUZZ_CHECK(std::isfinite(r->error_bound) && r->error_bound >= r->hausdorff, "error bound below hausdorff" + where);
  if (out.num_triangles() > 0) {
    for (std::size_t k = 0; k < 16; ++k) {
      const std::size_t t = (k * 7919 + data[k % size]) % mesh.num_triangles();
      const auto c = mesh.corners(t);
      const double u = double((k * 37) % 11) / 10, v = double((k * 53) % 13) / 12 * (1 - u);
      const Vec3 p = c[0] + (c[1] - c[0]) * u + (c[2] - c[0]) * v;
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t s = 0; s < out.num_triangles(); ++s)
        best = std::min(best, interfere::distance(p, interfere::closest_point_on_triangle(p, out.corners(s))));
      // This check's own arithmetic rounds at the coordinates' magnitude (a part far from the
      // origin: a few ulps of its offset).
      const double m = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z), 1e-300});
      const double slack = 8 * std::ldexp(1.0, std::ilogb(m) - 52);
      FUZZ_CHECK(best <= r->error_bound * (1 + 1e-12) + slack,
                 "a point of the input " + num(best) + " from the result, beyond the bound " + num(r->error_bound) +
                     " (hausdorff " + num(r->hausdorff) + ")" + where);
    }
  }

  // One thread: the same result.
  tbb::task_arena one(1);
  const auto r1 = one.execute([&] { return interfere::simplify(mesh, o); });
  FUZZ_CHECK(r1.has_value() && r1->mesh.positions == out.positions && r1->mesh.triangles == out.triangles &&
                 r1->error_bound == r->error_bound,
             "one thread gives another result" + where);
  return 0;
}

}  // namespace

INTERFERE_FUZZ_TARGET("simplify", entry);
