// Fuzz target for the exact triangle–triangle test (np/tri_tri.h): tri_tri_exact,
// tri_tri_exact_intersects and tri_tri_exact_kind must agree, and the answer must not change under
// any relabelling or exact transformation of the input. The non-robust double tests are run for
// memory/UB checking only (their answers are not checked).
//
// Input layout: byte 0 selects the decoding (bits 0-1) and a parameter (bits 2-7); the rest gives
// the 18 coordinates A0 A1 A2 B0 B1 B2 (x, y, z each), missing bytes read as zero:
//   mode 0  raw:    18 little-endian IEEE doubles (144 bytes).
//   mode 1  grid:   18 bytes, coordinate = (byte % 17 - 8) * 2^(param % 16 - 8): tiny integer
//                   grids, so coplanar, collinear, touching and repeated corners are frequent.
//   mode 2  jitter: like mode 1 with step 1 plus an offset (param % 4 selects 0, 1024, 2^20,
//                   3·2^40), then each coordinate moved by (int8)b >> 4 ulps (18 more bytes; a
//                   zero moves by steps of 2^-60): nearly degenerate input, where the
//                   predicates' floating-point filters fail.
//   mode 3  int16:  36 bytes, coordinate = int16 * 2^-(param % 32): general position with some
//                   exact degeneracies.
// Inputs with a non-finite coordinate, or with |x| > 1e30 or 0 < |x| < 1e-30, are skipped: the
// predicates' documented domain (core/predicates.h) is coordinates and nonzero differences between
// ~1e-80 and ~1e80, which these bounds keep also after the scalings below (2^±20).
//
// Checked on every input (abort = finding):
//  - tri_tri_exact(a, b).kind == tri_tri_exact_kind(a, b), and != none iff
//  tri_tri_exact_intersects;
//  - a degenerate (collinear, exactly) triangle never gives `cross`;
//  - on integer grids (modes 1 and 3), the kind equals that of an independent brute-force oracle in
//    128-bit integer arithmetic (edges against triangles; `cross` from exact rational intervals);
//  - the kind and, for `cross`, the endpoint features are identical for all 6 x 6 corner
//    permutations of A and B (3 rotations x 2 orientations) and with A and B swapped, and under the
//    exact transformations x -> -x, (x,y,z) -> (y,z,x), x <-> y, scaling by 2^-20 / 2^20, and a
//    translation when it is exact (checked with TwoSum); the segment ends then match the mapped
//    ends (in the order the documented direction nA x nB implies) up to a small tolerance;
//  - `cross` segment ends are finite, lie in both triangles' boxes (padded) and on both triangles
//    (up to rounding), a vertex-feature end is that corner bit for bit, an edge-feature end lies on
//    that edge, and no end is `face` on both triangles;
//  - np/distance.h: closest_point_on_triangle, from each corner to the other triangle and from each
//    `cross` end to both triangles, is finite, no farther than the nearest corner, and not grossly
//    farther than an independent reference distance.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "fuzz_common.h"
#include "interfere/core/predicates.h"
#include "interfere/np/distance.h"
#include "interfere/np/tri_tri.h"

namespace {

using interfere::ContactKind;
using interfere::Feature;
using interfere::TriTriResult;
using interfere::Vec3;
using Tri = std::array<Vec3, 3>;

std::string describe(const Tri& a, const Tri& b) {
  std::string s;
  char buf[128];
  for (const Tri* t : {&a, &b}) {
    s += t == &a ? " A:" : " B:";
    for (const Vec3& v : *t) {
      std::snprintf(buf, sizeof buf, " (%a %a %a)", v.x, v.y, v.z);
      s += buf;
    }
  }
  return s;
}

const char* kind_name(ContactKind k) {
  return k == ContactKind::none ? "none" : (k == ContactKind::touch ? "touch" : "cross");
}

/// Decodes the input; `step` is set to the grid step when every coordinate is an integer multiple
/// of it (modes 1 and 3), else to 0.
bool decode(const std::uint8_t* data, std::size_t size, Tri& a, Tri& b, double& step) {
  step = 0;
  if (size == 0) return false;
  const int mode = data[0] & 3;
  const int param = data[0] >> 2;
  const std::uint8_t* p = data + 1;
  const std::size_t n = size - 1;
  auto byte = [&](std::size_t i) -> std::uint8_t { return i < n ? p[i] : 0; };
  double c[18];
  switch (mode) {
    case 0: {
      std::uint8_t raw[144] = {};
      std::memcpy(raw, p, std::min<std::size_t>(n, sizeof raw));
      for (int i = 0; i < 18; ++i) {
        std::uint64_t bits = 0;
        for (int k = 0; k < 8; ++k) bits |= std::uint64_t{raw[8 * i + k]} << (8 * k);
        std::memcpy(&c[i], &bits, 8);
      }
      break;
    }
    case 1: {
      step = std::ldexp(1.0, param % 16 - 8);
      for (int i = 0; i < 18; ++i) c[i] = (byte(static_cast<std::size_t>(i)) % 17 - 8) * step;
      break;
    }
    case 2: {
      static constexpr double kOffset[4] = {0.0, 1024.0, 1048576.0, 3.0 * 1099511627776.0};
      const double offset = kOffset[param % 4];
      for (int i = 0; i < 18; ++i) {
        double v = offset + (byte(static_cast<std::size_t>(i)) % 17 - 8);
        const int ulps = static_cast<std::int8_t>(byte(18 + static_cast<std::size_t>(i))) >> 4;
        if (v == 0) {  // the ulps of zero are subnormal (outside the domain): use steps of 2^-60
          c[i] = std::ldexp(ulps, -60);
          continue;
        }
        for (int k = 0; k < ulps; ++k)
          v = std::nextafter(v, std::numeric_limits<double>::infinity());
        for (int k = 0; k > ulps; --k)
          v = std::nextafter(v, -std::numeric_limits<double>::infinity());
        c[i] = v;
      }
      break;
    }
    default: {
      step = std::ldexp(1.0, -(param % 32));
      for (int i = 0; i < 18; ++i) {
        const auto lo = byte(2 * static_cast<std::size_t>(i));
        const auto hi = byte(2 * static_cast<std::size_t>(i) + 1);
        c[i] = static_cast<std::int16_t>(static_cast<std::uint16_t>(lo | (hi << 8))) * step;
      }
      break;
    }
  }
  for (double v : c) {
    if (!std::isfinite(v)) return false;
    const double m = std::fabs(v);
    if (m > 1e30 || (m != 0 && m < 1e-30)) return false;
  }
  for (int i = 0; i < 3; ++i) {
    a[static_cast<std::size_t>(i)] = {c[3 * i], c[3 * i + 1], c[3 * i + 2]};
    b[static_cast<std::size_t>(i)] = {c[9 + 3 * i], c[9 + 3 * i + 1], c[9 + 3 * i + 2]};
  }
  return true;
}

/// Corner permutations: new corner i is old corner kPerms[p][i]; p < 3 keep the orientation.
constexpr int kPerms[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};

Tri permute(const Tri& t, const int* perm) {
  return {t[static_cast<std::size_t>(perm[0])], t[static_cast<std::size_t>(perm[1])],
          t[static_cast<std::size_t>(perm[2])]};
}

/// A feature as the set of original corners it spans (bit mask; face = all three).
unsigned corner_set(const Feature& f, const int* perm) {
  switch (f.type) {
    case Feature::vertex:
      return 1u << perm[f.index];
    case Feature::edge:
      return (1u << perm[f.index]) | (1u << perm[(f.index + 1) % 3]);
    default:
      return 7u;
  }
}

constexpr int kIdentity[3] = {0, 1, 2};

/// Ends of a cross result in a canonical frame: features as original corner sets of the
/// original A and B, segment ends mapped back, in the original order.
struct Ends {
  unsigned fa[2], fb[2];
  Vec3 p[2];
};

Ends canonical(const TriTriResult& r, const int* perm_a, const int* perm_b, bool swapped,
               bool reversed) {
  Ends e{};
  for (int k = 0; k < 2; ++k) {
    const int slot = reversed ? 1 - k : k;
    const Feature& f1 = swapped ? r.feature_b[k] : r.feature_a[k];
    const Feature& f2 = swapped ? r.feature_a[k] : r.feature_b[k];
    e.fa[slot] = corner_set(f1, perm_a);
    e.fb[slot] = corner_set(f2, perm_b);
    e.p[slot] = r.segment[k];
  }
  return e;
}

Vec3 box_lo(const Tri& t) {
  return interfere::min(interfere::min(t[0], t[1]), t[2]);
}
Vec3 box_hi(const Tri& t) {
  return interfere::max(interfere::max(t[0], t[1]), t[2]);
}

double max_abs(const Tri& a, const Tri& b) {
  double m = 0;
  for (const Tri* t : {&a, &b})
    for (const Vec3& v : *t) m = std::max({m, std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  return m;
}

double extent(const Tri& a, const Tri& b) {
  const Vec3 lo = interfere::min(box_lo(a), box_lo(b)), hi = interfere::max(box_hi(a), box_hi(b));
  return std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
}

/// Rounding allowance for constructed points: relative to the pair's extent, plus a few ulps of
/// the largest coordinate (a far-from-origin pair cannot be located more finely).
double tolerance(const Tri& a, const Tri& b) {
  return 1e-9 * extent(a, b) + 16 * std::numeric_limits<double>::epsilon() * max_abs(a, b);
}

double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double den = interfere::dot(ab, ab);
  const double t = den > 0 ? std::clamp(interfere::dot(p - a, ab) / den, 0.0, 1.0) : 0.0;
  return interfere::distance(p, a + ab * t);
}

/// Reference distances from p to triangle t for the checks, independent of np/distance.h: the
/// distance to the nearest edge, or the plane distance where p projects inside t.
///  - lenient: the projection counts as inside when the double side tests say so. Never much above
///    the true distance (a side test can only be wrong where its value is rounding noise, i.e. next
///    to an edge, or on a needle, whose interior is close to its edges); it may be below it.
///  - upper: the projection counts as inside only when the side tests are certain (each above a
///    bound on its rounding error), and the plane distance carries its error bound; never below the
///    true distance (up to a few ulps).
struct RefDistance {
  double lenient, upper;
};
RefDistance distance_to_triangle(const Vec3& p, const Tri& t) {
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  double edges = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < 3; ++i)
    edges = std::min(edges, point_segment_distance(p, t[i], t[(i + 1) % 3]));
  const Vec3 e1 = t[1] - t[0], e2 = t[2] - t[0];
  const Vec3 n = interfere::cross(e1, e2);
  const double nn = interfere::norm(n);
  RefDistance r{edges, edges};
  if (!(nn > 0)) return r;
  bool inside = true, certain = true;
  const double scale = interfere::norm(e1) * interfere::norm(e2);
  for (std::size_t i = 0; i < 3; ++i) {
    const Vec3 e = t[(i + 1) % 3] - t[i], w = p - t[i];
    const double side = interfere::dot(interfere::cross(e, w), n);
    inside &= side >= 0;
    certain &= side > 16 * kEps * interfere::norm(e) * interfere::norm(w) * scale;
  }
  const Vec3 w0 = p - t[0];
  const double plane = std::fabs(interfere::dot(n, w0)) / nn;
  if (inside) r.lenient = std::min(edges, plane);
  if (certain) r.upper = std::min(edges, plane + 8 * kEps * scale / nn * interfere::norm(w0));
  return r;
}

double tri_extent(const Tri& t) {
  const Vec3 e = box_hi(t) - box_lo(t);
  return std::max({e.x, e.y, e.z});
}

/// np/distance.h: closest_point_on_triangle(p, t) is a finite point no farther from p than any
/// corner of t, and not grossly farther than the reference distance (1e-5 relative: the method
/// loses digits on needles, by design up to about eps / sin^2 of its sliver threshold).
void check_closest_point(const Vec3& p, const Tri& t, const char* which, const Tri& a,
                         const Tri& b) {
  const Vec3 c = interfere::closest_point_on_triangle(p, t);
  static const bool ignore_nan = interfere::fuzz::ignored("closest_point_nan");
  if (ignore_nan && !interfere::is_finite(c)) return;
  char buf[96];
  std::snprintf(buf, sizeof buf, " (p = (%a %a %a), triangle %s)", p.x, p.y, p.z, which);
  FUZZ_CHECK(interfere::is_finite(c), "closest_point_on_triangle returns a non-finite point" +
                                          std::string(buf) + describe(a, b));
  static const bool ignore_accuracy = interfere::fuzz::ignored("closest_point_accuracy");
  if (ignore_accuracy) return;
  const double tol =
      tolerance(a, b) + 16 * std::numeric_limits<double>::epsilon() * interfere::norm(p);
  const double d = interfere::distance(p, c);
  for (const Vec3& v : t) {
    FUZZ_CHECK(
        d <= interfere::distance(p, v) + tol,
        "closest_point_on_triangle is farther than a corner" + std::string(buf) + describe(a, b));
  }
  const double want = distance_to_triangle(p, t).upper;
  char dist[96];
  std::snprintf(dist, sizeof dist, "closest_point_on_triangle is %.3g away, the triangle %.3g", d,
                want);
  FUZZ_CHECK(d <= want + 1e-5 * (tri_extent(t) + want) + tol,
             dist + std::string(buf) + describe(a, b));
}

bool degenerate(const Tri& t) {
  return interfere::collinear(t[0], t[1], t[2]);
}

std::string feature_str(const Feature& f) {
  const char* n[] = {"v", "e", "f"};
  return std::string(f.type <= 2 ? n[f.type] : "?") + std::to_string(f.index);
}

/// Contract of one result (kinds agree, cross ends valid).
void check_single(const Tri& a, const Tri& b, const TriTriResult& r) {
  const ContactKind kind = interfere::tri_tri_exact_kind(a, b);
  const bool hit = interfere::tri_tri_exact_intersects(a, b);
  FUZZ_CHECK(kind == r.kind, std::string("tri_tri_exact_kind ") + kind_name(kind) +
                                 " != tri_tri_exact " + kind_name(r.kind) + describe(a, b));
  FUZZ_CHECK(hit == (r.kind != ContactKind::none),
             std::string("tri_tri_exact_intersects ") + (hit ? "true" : "false") +
                 " but tri_tri_exact " + kind_name(r.kind) + describe(a, b));
  if (r.kind != ContactKind::cross) return;
  FUZZ_CHECK(!degenerate(a) && !degenerate(b),
             "degenerate triangle classified cross" + describe(a, b));
  const double tol = tolerance(a, b);
  const Vec3 lo = interfere::max(box_lo(a), box_lo(b)), hi = interfere::min(box_hi(a), box_hi(b));
  for (int k = 0; k < 2; ++k) {
    const Vec3& p = r.segment[static_cast<std::size_t>(k)];
    const Feature fa = r.feature_a[static_cast<std::size_t>(k)],
                  fb = r.feature_b[static_cast<std::size_t>(k)];
    const std::string where = " (end " + std::to_string(k) + ", features " + feature_str(fa) + "/" +
                              feature_str(fb) + ")" + describe(a, b);
    FUZZ_CHECK(interfere::is_finite(p), "non-finite cross segment end" + where);
    FUZZ_CHECK(fa.type <= Feature::face && fb.type <= Feature::face && fa.index < 3 && fb.index < 3,
               "invalid feature" + where);
    FUZZ_CHECK(fa.type != Feature::face || fb.type != Feature::face,
               "segment end interior to both triangles" + where);
    for (int ax = 0; ax < 3; ++ax) {
      FUZZ_CHECK(p[static_cast<std::size_t>(ax)] >= lo[static_cast<std::size_t>(ax)] - tol &&
                     p[static_cast<std::size_t>(ax)] <= hi[static_cast<std::size_t>(ax)] + tol,
                 "cross segment end outside the boxes of the triangles" + where);
    }
    check_closest_point(p, a, "A", a, b);
    check_closest_point(p, b, "B", a, b);
    FUZZ_CHECK(distance_to_triangle(p, a).lenient <= tol,
               "cross segment end off triangle A" + where);
    FUZZ_CHECK(distance_to_triangle(p, b).lenient <= tol,
               "cross segment end off triangle B" + where);
    for (const auto& [f, t] : {std::pair{fa, &a}, std::pair{fb, &b}}) {
      if (f.type == Feature::vertex) {
        FUZZ_CHECK(p == (*t)[f.index], "vertex-feature end is not that corner" + where);
      } else if (f.type == Feature::edge) {
        const auto c =
            interfere::segment_segment_closest(p, p, (*t)[f.index], (*t)[(f.index + 1u) % 3]);
        FUZZ_CHECK(c.distance <= tol, "edge-feature end is off that edge" + where);
      }
    }
  }
}

/// Compares a variant's result with the reference (ends already mapped to the original frame).
void check_same(const TriTriResult& ref, const Ends& want, const TriTriResult& got,
                const Ends& have, const Tri& a, const Tri& b, double tol,
                const std::string& variant) {
  static const bool ignore_segment = interfere::fuzz::ignored("segment_accuracy");
  FUZZ_CHECK(got.kind == ref.kind, std::string("kind ") + kind_name(ref.kind) + " becomes " +
                                       kind_name(got.kind) + " under " + variant + describe(a, b));
  if (ref.kind != ContactKind::cross) return;
  for (int k = 0; k < 2; ++k) {
    FUZZ_CHECK(want.fa[k] == have.fa[k] && want.fb[k] == have.fb[k],
               "endpoint features change under " + variant + " (end " + std::to_string(k) + ")" +
                   describe(a, b));
    if (!ignore_segment) {
      FUZZ_CHECK(interfere::distance(want.p[k], have.p[k]) <= tol,
                 "segment end moves under " + variant + " (end " + std::to_string(k) + ")" +
                     describe(a, b));
    }
  }
}

/// True when x + t is exact for every coordinate (TwoSum error term zero).
bool exact_translation(const Tri& a, const Tri& b, const Vec3& t) {
  for (const Tri* tri : {&a, &b}) {
    for (const Vec3& v : *tri) {
      for (std::size_t i = 0; i < 3; ++i) {
        const double x = v[i], y = t[i];
        const double s = x + y, bb = s - x, err = (x - (s - bb)) + (y - bb);
        if (err != 0 || !std::isfinite(s)) return false;
      }
    }
  }
  return true;
}

// ---- Independent oracle for integer-grid input (modes 1 and 3), exact in 128-bit integers ----
// Brute force, unrelated to the library's method: two closed triangles (points and segments when
// degenerate) meet iff an edge of one meets the other; `cross` iff both are proper triangles, each
// strictly split by the other's plane, and the two open intervals they cut on the planes' common
// line overlap (compared as exact rationals). Valid for |coordinate / step| <= 2^15 (intersection)
// and <= 255 (cross; the rational comparison then stays below 2^112).
__extension__ typedef __int128 I128;
struct IV {
  I128 x, y, z;
};
IV operator-(const IV& a, const IV& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
IV operator*(const IV& a, I128 s) {
  return {a.x * s, a.y * s, a.z * s};
}
bool operator==(const IV& a, const IV& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}
I128 idot(const IV& a, const IV& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
IV icross(const IV& a, const IV& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
int isign(I128 v) {
  return (v > 0) - (v < 0);
}
/// Sign of det[b-a, c-a, d-a] (height of d over the plane of a, b, c along (b-a)x(c-a)).
int iorient(const IV& a, const IV& b, const IV& c, const IV& d) {
  return isign(idot(icross(b - a, c - a), d - a));
}
bool icollinear(const IV& a, const IV& b, const IV& c) {
  return icross(b - a, c - a) == IV{0, 0, 0};
}

bool point_on_segment(const IV& p, const IV& a, const IV& b) {
  return icollinear(a, b, p) && idot(p - a, p - b) <= 0;
}

/// Closed segments, either possibly a point.
bool iseg_seg(const IV& a, const IV& b, const IV& c, const IV& d) {
  if (a == b) return point_on_segment(a, c, d);
  if (c == d) return point_on_segment(c, a, b);
  if (iorient(a, b, c, d) != 0) return false;  // not coplanar
  const IV n = icross(b - a, d - c);
  if (n == IV{0, 0, 0}) {  // parallel
    if (!icollinear(a, b, c)) return false;
    return point_on_segment(c, a, b) || point_on_segment(d, a, b) || point_on_segment(a, c, d) ||
           point_on_segment(b, c, d);
  }
  const int sc = isign(idot(icross(b - a, c - a), n)), sd = isign(idot(icross(b - a, d - a), n));
  if (sc * sd > 0) return false;
  const int sa = isign(idot(icross(d - c, a - c), n)), sb = isign(idot(icross(d - c, b - c), n));
  return sa * sb <= 0;
}

/// Point in closed proper triangle t.
bool ipoint_in_tri(const IV& p, const std::array<IV, 3>& t) {
  if (iorient(t[0], t[1], t[2], p) != 0) return false;
  const IV n = icross(t[1] - t[0], t[2] - t[0]);
  for (int i = 0; i < 3; ++i) {
    const IV& u = t[static_cast<std::size_t>(i)];
    const IV& v = t[static_cast<std::size_t>((i + 1) % 3)];
    if (idot(icross(v - u, p - u), n) < 0) return false;
  }
  return true;
}

/// Closed segment (possibly a point) vs closed proper triangle.
bool iseg_tri(const IV& a, const IV& b, const std::array<IV, 3>& t) {
  if (a == b) return ipoint_in_tri(a, t);
  const int sa = iorient(t[0], t[1], t[2], a), sb = iorient(t[0], t[1], t[2], b);
  if (sa * sb > 0) return false;
  if (sa == 0 && sb == 0) {
    return ipoint_in_tri(a, t) || ipoint_in_tri(b, t) || iseg_seg(a, b, t[0], t[1]) ||
           iseg_seg(a, b, t[1], t[2]) || iseg_seg(a, b, t[2], t[0]);
  }
  // One point of the line ab is on the plane and within the segment: it is in t iff the line
  // passes on the same side of (or through) all three edges.
  const int e0 = iorient(a, b, t[0], t[1]), e1 = iorient(a, b, t[1], t[2]),
            e2 = iorient(a, b, t[2], t[0]);
  return !((e0 > 0 || e1 > 0 || e2 > 0) && (e0 < 0 || e1 < 0 || e2 < 0));
}

/// A triangle as a point (all corners equal), a segment (collinear; its two farthest corners) or a
/// proper triangle.
struct Prim {
  int dim;
  std::array<IV, 3> p;
};
Prim prim(const std::array<IV, 3>& t) {
  if (!icollinear(t[0], t[1], t[2])) return {2, t};
  std::size_t bi = 0, bj = 0;
  I128 best = -1;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = i + 1; j < 3; ++j) {
      const IV d = t[i] - t[j];
      if (idot(d, d) > best) best = idot(d, d), bi = i, bj = j;
    }
  return {best == 0 ? 0 : 1, {t[bi], t[bj], t[bj]}};
}

bool iintersects(const Prim& a, const Prim& b) {
  if (a.dim < 2 && b.dim < 2) return iseg_seg(a.p[0], a.p[1], b.p[0], b.p[1]);
  if (a.dim < 2) return iseg_tri(a.p[0], a.p[1], b.p);
  if (b.dim < 2) return iseg_tri(b.p[0], b.p[1], a.p);
  for (int i = 0; i < 3; ++i) {
    if (iseg_tri(a.p[static_cast<std::size_t>(i)], a.p[static_cast<std::size_t>((i + 1) % 3)], b.p))
      return true;
    if (iseg_tri(b.p[static_cast<std::size_t>(i)], b.p[static_cast<std::size_t>((i + 1) % 3)], a.p))
      return true;
  }
  return false;
}

/// A rational t = num / den along the common line (den > 0).
struct Rat {
  I128 num, den;
};
bool operator<(const Rat& x, const Rat& y) {
  return x.num * y.den < y.num * x.den;
}

/// The interval that proper triangle t, strictly split by plane(u), cuts on the line with
/// direction d: its ends are corners on the plane and edge crossings.
std::pair<Rat, Rat> interval(const std::array<IV, 3>& t, const std::array<IV, 3>& u, const IV& d) {
  const IV n = icross(u[1] - u[0], u[2] - u[0]);
  I128 h[3];
  for (std::size_t i = 0; i < 3; ++i) h[i] = idot(n, t[i] - u[0]);
  std::vector<Rat> ts;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t j = (i + 1) % 3;
    if (h[i] == 0) ts.push_back({idot(d, t[i]), 1});
    if ((h[i] > 0 && h[j] < 0) || (h[i] < 0 && h[j] > 0)) {
      // X = (h_i t_j - h_j t_i) / (h_i - h_j)
      I128 den = h[i] - h[j];
      I128 num = idot(d, t[j] * h[i] - t[i] * h[j]);
      if (den < 0) den = -den, num = -num;
      ts.push_back({num, den});
    }
  }
  Rat lo = ts[0], hi = ts[0];
  for (const Rat& r : ts) {
    if (r < lo) lo = r;
    if (hi < r) hi = r;
  }
  return {lo, hi};
}

/// none / touch / cross by the oracle; `cross_known` is false when the coordinates are too large
/// for the rational comparison.
ContactKind oracle_kind(const std::array<IV, 3>& a, const std::array<IV, 3>& b, bool cross_valid) {
  const Prim pa = prim(a), pb = prim(b);
  if (!iintersects(pa, pb)) return ContactKind::none;
  if (!cross_valid || pa.dim < 2 || pb.dim < 2) return ContactKind::touch;
  auto split = [](const std::array<IV, 3>& t, const std::array<IV, 3>& u) {
    bool pos = false, neg = false;
    for (const IV& v : t) {
      const int s = iorient(u[0], u[1], u[2], v);
      pos |= s > 0, neg |= s < 0;
    }
    return pos && neg;
  };
  if (!split(a, b) || !split(b, a)) return ContactKind::touch;
  const IV d = icross(icross(a[1] - a[0], a[2] - a[0]), icross(b[1] - b[0], b[2] - b[0]));
  const auto [alo, ahi] = interval(a, b, d);
  const auto [blo, bhi] = interval(b, a, d);
  const Rat lo = alo < blo ? blo : alo, hi = ahi < bhi ? ahi : bhi;
  return lo < hi ? ContactKind::cross : ContactKind::touch;
}

/// Checks tri_tri_exact's kind against the oracle when the input is on an integer grid.
void check_oracle(const Tri& a, const Tri& b, double step, ContactKind kind) {
  if (step == 0) return;
  std::array<IV, 3> ia, ib;
  double biggest = 0;
  for (int k = 0; k < 2; ++k) {
    const Tri& t = k == 0 ? a : b;
    std::array<IV, 3>& it = k == 0 ? ia : ib;
    for (std::size_t i = 0; i < 3; ++i) {
      double c[3];
      for (std::size_t ax = 0; ax < 3; ++ax) {
        c[ax] = t[i][ax] / step;  // exact: step is a power of two
        if (c[ax] != std::trunc(c[ax]) || std::fabs(c[ax]) > 32768) return;
        biggest = std::max(biggest, std::fabs(c[ax]));
      }
      it[i] = {static_cast<I128>(c[0]), static_cast<I128>(c[1]), static_cast<I128>(c[2])};
    }
  }
  const bool cross_valid = biggest <= 255;
  const ContactKind want = oracle_kind(ia, ib, cross_valid);
  static const bool verbose = std::getenv("INTERFERE_FUZZ_VERBOSE") != nullptr;
  if (verbose)
    std::fprintf(stderr, "  oracle: %s%s\n", kind_name(want),
                 cross_valid ? "" : " (intersection only)");
  const bool agree =
      cross_valid ? want == kind : (want == ContactKind::none) == (kind == ContactKind::none);
  FUZZ_CHECK(agree, std::string("tri_tri_exact says ") + kind_name(kind) + ", the integer oracle " +
                        kind_name(want) + (cross_valid ? "" : " (intersection only)") +
                        describe(a, b));
}

int entry(const std::uint8_t* data, std::size_t size) {
  Tri a, b;
  double step;
  if (!decode(data, size, a, b, step)) return 0;

  // Memory/UB coverage of the double reference tests; their answers are not robust.
  (void)interfere::tri_tri_moller(a, b);
  (void)interfere::tri_tri_guigue_devillers(a, b);

  const TriTriResult ref = interfere::tri_tri_exact(a, b);
  static const bool verbose = std::getenv("INTERFERE_FUZZ_VERBOSE") != nullptr;
  if (verbose) std::fprintf(stderr, "  %s:%s\n", kind_name(ref.kind), describe(a, b).c_str());
  check_single(a, b, ref);
  check_oracle(a, b, step, ref.kind);
  for (std::size_t i = 0; i < 3; ++i) {
    check_closest_point(a[i], b, "B", a, b);
    check_closest_point(b[i], a, "A", a, b);
  }
  const Ends want =
      ref.kind == ContactKind::cross ? canonical(ref, kIdentity, kIdentity, false, false) : Ends{};
  const double tol = tolerance(a, b);

  // Corner permutations of either triangle, and the swap.
  for (int pa = 0; pa < 6; ++pa) {
    for (int pb = 0; pb < 6; ++pb) {
      const Tri a2 = permute(a, kPerms[pa]), b2 = permute(b, kPerms[pb]);
      for (int swap = 0; swap < 2; ++swap) {
        if (pa == 0 && pb == 0 && swap == 0) continue;
        const TriTriResult r =
            swap ? interfere::tri_tri_exact(b2, a2) : interfere::tri_tri_exact(a2, b2);
        const bool reversed = ((pa >= 3) != (pb >= 3)) != (swap == 1);
        const std::string variant = "corner permutation A" + std::to_string(pa) + " B" +
                                    std::to_string(pb) + (swap ? " with A and B swapped" : "");
        if (swap) {
          check_single(b2, a2, r);
        } else {
          check_single(a2, b2, r);
        }
        const Ends have = r.kind == ContactKind::cross
                              ? canonical(r, kPerms[pa], kPerms[pb], swap == 1, reversed)
                              : Ends{};
        check_same(ref, want, r, have, a, b, tol, variant);
      }
    }
  }

  // Exact linear maps of space: M maps points; `flip` when det(M) < 0 (the direction nA x nB then
  // maps to -M d, so the ends come in the opposite order).
  struct Map {
    const char* name;
    Vec3 (*apply)(const Vec3&);
    Vec3 (*inverse)(const Vec3&);
    bool flip;
  };
  static const Map kMaps[] = {
      {"x -> -x",
       [](const Vec3& v) {
         return Vec3{-v.x, v.y, v.z};
       },
       [](const Vec3& v) {
         return Vec3{-v.x, v.y, v.z};
       },
       true},
      {"(x,y,z) -> (y,z,x)",
       [](const Vec3& v) {
         return Vec3{v.y, v.z, v.x};
       },
       [](const Vec3& v) {
         return Vec3{v.z, v.x, v.y};
       },
       false},
      {"x <-> y",
       [](const Vec3& v) {
         return Vec3{v.y, v.x, v.z};
       },
       [](const Vec3& v) {
         return Vec3{v.y, v.x, v.z};
       },
       true},
      {"scale 2^-20", [](const Vec3& v) { return v * 0x1p-20; },
       [](const Vec3& v) { return v * 0x1p20; }, false},
      {"scale 2^20", [](const Vec3& v) { return v * 0x1p20; },
       [](const Vec3& v) { return v * 0x1p-20; }, false},
  };
  for (const Map& m : kMaps) {
    const Tri a2{m.apply(a[0]), m.apply(a[1]), m.apply(a[2])};
    const Tri b2{m.apply(b[0]), m.apply(b[1]), m.apply(b[2])};
    const TriTriResult r = interfere::tri_tri_exact(a2, b2);
    check_single(a2, b2, r);
    Ends have{};
    if (r.kind == ContactKind::cross) {
      have = canonical(r, kIdentity, kIdentity, false, m.flip);
      for (Vec3& p : have.p) p = m.inverse(p);
    }
    check_same(ref, want, r, have, a, b, tol, m.name);
  }

  // Translations, when exact: by a power of two near the pair's extent and by a small integer
  // vector (exact on integer grids).
  const double e = extent(a, b);
  const double pow2 = e > 0 ? std::ldexp(1.0, std::ilogb(e) + 1) : 1.0;
  for (const Vec3& t : {Vec3{pow2, -pow2, 2 * pow2}, Vec3{3, -5, 7}}) {
    if (!exact_translation(a, b, t)) continue;
    const Tri a2{a[0] + t, a[1] + t, a[2] + t}, b2{b[0] + t, b[1] + t, b[2] + t};
    const TriTriResult r = interfere::tri_tri_exact(a2, b2);
    check_single(a2, b2, r);
    Ends have{};
    if (r.kind == ContactKind::cross) {
      have = canonical(r, kIdentity, kIdentity, false, false);
      for (Vec3& p : have.p) p = p - t;
    }
    check_same(ref, want, r, have, a, b, tol + tolerance(a2, b2), "an exact translation");
  }
  return 0;
}

}  // namespace

INTERFERE_FUZZ_TARGET("tri_tri", entry);
