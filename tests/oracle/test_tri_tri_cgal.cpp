// CGAL (Epeck: exact predicates and exact constructions) as an independent oracle for
// core/predicates.h and np/tri_tri.h:
//  (a) tri_tri_exact / tri_tri_exact_intersects == CGAL::do_intersect (degenerate triangles as
//      Segment_3 / Point_3);
//  (b) classification: cross iff non-coplanar, non-degenerate, and CGAL's exact intersection is a
//      segment whose midpoint is strictly inside both triangles;
//  (c) our cross segment's endpoints are within 1e-9 (relative to the scene size) of CGAL's exact
//      ones, as a set, and each endpoint's Feature on A and on B is what CGAL's exact endpoint lies
//      on (corner equality, Segment_3::has_on for edges, else the face).
// Inputs are chosen so that degenerate configurations are frequent: corners on small integer grids
// (coplanar, touching, shared corners/edges, collinear corners), a triangle against rotated and
// translated copies of itself, and corners placed on the other plane up to rounding.
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <sstream>
#include <variant>
#include <vector>

#include "interfere/core/predicates.h"
#include "interfere/np/tri_tri.h"

namespace interfere {
namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using P3 = K::Point_3;
using Tri = std::array<Vec3, 3>;

P3 to_cgal(const Vec3& v) {
  return {v.x, v.y, v.z};
}
Vec3 to_vec(const P3& p) {
  return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
}

std::string describe(const Tri& a, const Tri& b) {
  std::ostringstream s;
  s.precision(17);
  s << "A = ";
  for (const Vec3& v : a) s << "(" << v.x << ", " << v.y << ", " << v.z << ") ";
  s << "\nB = ";
  for (const Vec3& v : b) s << "(" << v.x << ", " << v.y << ", " << v.z << ") ";
  return s.str();
}

using Object = std::variant<K::Triangle_3, K::Segment_3, P3>;

Object as_object(const Tri& t) {
  const P3 p = to_cgal(t[0]), q = to_cgal(t[1]), r = to_cgal(t[2]);
  if (!CGAL::collinear(p, q, r)) return K::Triangle_3(p, q, r);
  if (p == q && q == r) return p;
  P3 lo = p, hi = p;
  for (const P3& x : {q, r}) {
    if (CGAL::compare_xyz(x, lo) == CGAL::SMALLER) lo = x;
    if (CGAL::compare_xyz(hi, x) == CGAL::SMALLER) hi = x;
  }
  return K::Segment_3(lo, hi);
}

bool cgal_do_intersect(const Object& a, const Object& b) {
  return std::visit(
      [](const auto& x, const auto& y) -> bool {
        using X = std::decay_t<decltype(x)>;
        using Y = std::decay_t<decltype(y)>;
        if constexpr (std::is_same_v<X, P3> && std::is_same_v<Y, P3>) {
          return x == y;
        } else if constexpr (std::is_same_v<X, P3>) {
          return y.has_on(x);
        } else if constexpr (std::is_same_v<Y, P3>) {
          return x.has_on(y);
        } else {
          return CGAL::do_intersect(x, y);
        }
      },
      a, b);
}

/// m strictly inside the (non-degenerate) triangle t, m in t's plane.
bool strictly_inside(const K::Triangle_3& t, const P3& m) {
  for (int i = 0; i < 3; ++i)
    if (CGAL::coplanar_orientation(t[i], t[(i + 1) % 3], t[(i + 2) % 3], m) != CGAL::POSITIVE)
      return false;
  return true;
}

/// The feature of triangle t that the exact point x (on t's boundary or inside) lies on.
Feature cgal_feature(const K::Triangle_3& t, const P3& x) {
  for (int i = 0; i < 3; ++i)
    if (t[i] == x) return {Feature::vertex, static_cast<std::uint8_t>(i)};
  for (int i = 0; i < 3; ++i)
    if (K::Segment_3(t[i], t[(i + 1) % 3]).has_on(x))
      return {Feature::edge, static_cast<std::uint8_t>(i)};
  return {Feature::face, 0};
}

std::string feature_name(const Feature& f) {
  const char* names[] = {"vertex", "edge", "face"};
  return std::string(names[f.type]) + " " + std::to_string(f.index);
}

struct Stats {
  int pairs = 0, none = 0, touch = 0, cross = 0, degenerate = 0, coplanar = 0;
  int feature_vertex = 0, feature_edge = 0;
};

/// Checks (a), (b), (c) on one pair; returns false (after reporting) on the first mismatch.
bool check_pair(const Tri& a, const Tri& b, Stats& st) {
  ++st.pairs;
  const Object oa = as_object(a), ob = as_object(b);
  const bool expect_hit = cgal_do_intersect(oa, ob);
  const TriTriResult r = tri_tri_exact(a, b);
  const bool fast = tri_tri_exact_intersects(a, b);
  EXPECT_EQ(r.kind != ContactKind::none, expect_hit) << describe(a, b);
  EXPECT_EQ(fast, expect_hit) << describe(a, b);
  if ((r.kind != ContactKind::none) != expect_hit || fast != expect_hit) return false;
  if (!expect_hit) {
    ++st.none;
    return true;
  }

  // (b) expected classification.
  const auto* ta = std::get_if<K::Triangle_3>(&oa);
  const auto* tb = std::get_if<K::Triangle_3>(&ob);
  bool expect_cross = false;
  std::optional<K::Segment_3> exact_segment;
  if (!ta || !tb) {
    ++st.degenerate;
  } else if (CGAL::coplanar((*ta)[0], (*ta)[1], (*ta)[2], (*tb)[0]) &&
             CGAL::coplanar((*ta)[0], (*ta)[1], (*ta)[2], (*tb)[1]) &&
             CGAL::coplanar((*ta)[0], (*ta)[1], (*ta)[2], (*tb)[2])) {
    ++st.coplanar;
  } else {
    const auto inter = CGAL::intersection(*ta, *tb);
    EXPECT_TRUE(bool(inter)) << describe(a, b);
    if (inter) {
      if (const auto* s = boost::get<K::Segment_3>(&*inter)) {
        const P3 m = CGAL::midpoint(s->source(), s->target());
        expect_cross = strictly_inside(*ta, m) && strictly_inside(*tb, m);
        exact_segment = *s;
      }
    }
  }
  const ContactKind expect_kind = expect_cross ? ContactKind::cross : ContactKind::touch;
  EXPECT_EQ(static_cast<int>(r.kind), static_cast<int>(expect_kind)) << describe(a, b);
  EXPECT_EQ(static_cast<int>(tri_tri_exact_kind(a, b)), static_cast<int>(expect_kind))
      << describe(a, b);
  if (r.kind != expect_kind) return false;
  if (r.kind == ContactKind::touch) {
    ++st.touch;
    return true;
  }
  ++st.cross;

  // (c) endpoints (as a set) and their features.
  double scale = 0;
  for (const Tri* t : {&a, &b})
    for (const Vec3& v : *t)
      scale = std::max({scale, std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  const double tol = 1e-9 * std::max(scale, 1.0);
  const P3 e[2] = {exact_segment->source(), exact_segment->target()};
  const Vec3 ed[2] = {to_vec(e[0]), to_vec(e[1])};
  const bool straight = distance(r.segment[0], ed[0]) + distance(r.segment[1], ed[1]) <=
                        distance(r.segment[0], ed[1]) + distance(r.segment[1], ed[0]);
  bool ok = true;
  for (int k = 0; k < 2; ++k) {
    const int m = straight ? k : 1 - k;
    EXPECT_LT(distance(r.segment[k], ed[m]), tol) << "endpoint " << k << "\n" << describe(a, b);
    const Feature fa = cgal_feature(*ta, e[m]), fb = cgal_feature(*tb, e[m]);
    EXPECT_EQ(r.feature_a[k], fa) << "endpoint " << k << ": ours " << feature_name(r.feature_a[k])
                                  << ", CGAL " << feature_name(fa) << "\n"
                                  << describe(a, b);
    EXPECT_EQ(r.feature_b[k], fb) << "endpoint " << k << ": ours " << feature_name(r.feature_b[k])
                                  << ", CGAL " << feature_name(fb) << "\n"
                                  << describe(a, b);
    ok = ok && distance(r.segment[k], ed[m]) < tol && r.feature_a[k] == fa && r.feature_b[k] == fb;
    for (const Feature& f : {fa, fb}) {
      st.feature_vertex += f.type == Feature::vertex;
      st.feature_edge += f.type == Feature::edge;
    }
  }
  return ok;
}

/// Runs check_pair on a pair and its swapped version; stops a test after a few failures.
class PairChecker {
 public:
  void operator()(const Tri& a, const Tri& b) {
    if (failures_ >= 5) return;
    if (!check_pair(a, b, stats_)) ++failures_;
    if (!check_pair(b, a, stats_)) ++failures_;
  }
  const Stats& stats() const { return stats_; }
  int failures() const { return failures_; }

 private:
  Stats stats_;
  int failures_ = 0;
};

Vec3 grid_point(std::mt19937_64& rng, int n, double step = 1.0, Vec3 offset = {}) {
  std::uniform_int_distribution<int> d(0, n);
  return Vec3{d(rng) * step, d(rng) * step, d(rng) * step} + offset;
}

TEST(TriTriOracle, SmallIntegerGrid) {
  std::mt19937_64 rng(1);
  PairChecker check;
  for (int i = 0; i < 12000; ++i) {
    const int n = i % 3 == 0 ? 2 : 3;
    Tri a{grid_point(rng, n), grid_point(rng, n), grid_point(rng, n)};
    Tri b{grid_point(rng, n), grid_point(rng, n), grid_point(rng, n)};
    check(a, b);
  }
  const Stats& s = check.stats();
  // The generator must actually produce the configurations this test is about.
  EXPECT_GT(s.cross, 500);
  EXPECT_GT(s.touch, 500);
  EXPECT_GT(s.coplanar, 100);
  EXPECT_GT(s.degenerate, 100);
  EXPECT_GT(s.feature_vertex, 100);
  EXPECT_GT(s.feature_edge, 100);
  std::printf("grid: %d pairs, none %d touch %d cross %d (coplanar %d, degenerate %d)\n", s.pairs,
              s.none, s.touch, s.cross, s.coplanar, s.degenerate);
}

TEST(TriTriOracle, CoplanarGrid) {
  // Both triangles in one tilted plane z = kx*x + ky*y (grid points): coplanar overlap, shared
  // edges and corners, collinear (degenerate) triangles, and disjoint coplanar pairs.
  std::mt19937_64 rng(8);
  std::uniform_int_distribution<int> d(0, 3), k(-2, 2);
  PairChecker check;
  for (int i = 0; i < 4000; ++i) {
    const int kx = k(rng), ky = k(rng);
    auto p = [&]() {
      const int x = d(rng), y = d(rng);
      return Vec3{double(x), double(y), double(kx * x + ky * y)};
    };
    check(Tri{p(), p(), p()}, Tri{p(), p(), p()});
  }
  const Stats& s = check.stats();
  EXPECT_GT(s.coplanar, 1000);
  EXPECT_GT(s.none, 300);
  EXPECT_GT(s.degenerate, 300);
  EXPECT_EQ(s.cross, 0);
}

TEST(TriTriOracle, DegenerateTriangles) {
  // Collinear and point triangles on a few shared lines (so collinear overlaps and gaps occur),
  // against each other and against regular grid triangles.
  std::mt19937_64 rng(9);
  std::uniform_int_distribution<int> d(-3, 3), pick(0, 2);
  const Vec3 origins[3] = {{0, 0, 0}, {1, 0, 1}, {0, 2, 1}};
  const Vec3 dirs[3] = {{1, 1, 0}, {1, 0, -1}, {1, 2, 3}};
  auto degenerate = [&]() {
    const Vec3 o = origins[pick(rng)], dir = dirs[pick(rng)];
    if (pick(rng) == 0) {
      const Vec3 p = o + dir * double(d(rng));
      return Tri{p, p, p};
    }
    return Tri{o + dir * double(d(rng)), o + dir * double(d(rng)), o + dir * double(d(rng))};
  };
  PairChecker check;
  for (int i = 0; i < 6000; ++i) {
    const Tri a = degenerate();
    const Tri b =
        i % 2 ? degenerate()
              : Tri{grid_point(rng, 3, 1.0, {-1, -1, -1}), grid_point(rng, 3, 1.0, {-1, -1, -1}),
                    grid_point(rng, 3, 1.0, {-1, -1, -1})};
    check(a, b);
  }
  EXPECT_GT(check.stats().none, 1000);
  EXPECT_GT(check.stats().touch, 1000);
  EXPECT_EQ(check.stats().cross, 0);
}

TEST(TriTriOracle, LargeOffsetDyadicGrid) {
  // 1e6 + k/4: exact doubles whose products need more than 53 bits; differences stay exact.
  std::mt19937_64 rng(2);
  PairChecker check;
  const Vec3 offset{1e6, -3e6, 2.5e6};
  for (int i = 0; i < 4000; ++i) {
    Tri a{grid_point(rng, 3, 0.25, offset), grid_point(rng, 3, 0.25, offset),
          grid_point(rng, 3, 0.25, offset)};
    Tri b{grid_point(rng, 3, 0.25, offset), grid_point(rng, 3, 0.25, offset),
          grid_point(rng, 3, 0.25, offset)};
    check(a, b);
  }
  EXPECT_GT(check.stats().cross, 100);
  EXPECT_GT(check.stats().touch, 100);
}

TEST(TriTriOracle, MeshNeighboursSharingCorners) {
  // Pairs that share one or two corners (as neighbouring mesh faces do), third corners on a grid.
  std::mt19937_64 rng(3);
  PairChecker check;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 p = grid_point(rng, 3), q = grid_point(rng, 3);
    Tri a{p, q, grid_point(rng, 3)};
    Tri b = i % 2 ? Tri{q, p, grid_point(rng, 3)} : Tri{grid_point(rng, 3), p, grid_point(rng, 3)};
    check(a, b);
  }
  EXPECT_GT(check.stats().touch, 1000);
}

/// Rotation by a random unit quaternion, in double.
Vec3 rotate(const Vec3& v, const double q[4]) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return {(1 - 2 * (y * y + z * z)) * v.x + 2 * (x * y - w * z) * v.y + 2 * (x * z + w * y) * v.z,
          2 * (x * y + w * z) * v.x + (1 - 2 * (x * x + z * z)) * v.y + 2 * (y * z - w * x) * v.z,
          2 * (x * z - w * y) * v.x + 2 * (y * z + w * x) * v.y + (1 - 2 * (x * x + y * y)) * v.z};
}

TEST(TriTriOracle, RotatedAndTranslatedCopiesOfItself) {
  std::mt19937_64 rng(4);
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PairChecker check;
  for (int i = 0; i < 3000; ++i) {
    const Tri a{Vec3{u(rng), u(rng), u(rng)}, Vec3{u(rng), u(rng), u(rng)},
                Vec3{u(rng), u(rng), u(rng)}};
    // Small or large rotation about a corner or the centroid, small translation.
    double q[4] = {1.0, 0, 0, 0};
    const double angle = i % 3 == 0 ? 1e-12 * u(rng) : (i % 3 == 1 ? 1e-3 * u(rng) : u(rng));
    Vec3 axis{g(rng), g(rng), g(rng)};
    axis = axis / norm(axis);
    q[0] = std::cos(angle / 2);
    q[1] = std::sin(angle / 2) * axis.x;
    q[2] = std::sin(angle / 2) * axis.y;
    q[3] = std::sin(angle / 2) * axis.z;
    const Vec3 pivot = i % 2 ? a[i % 3] : (a[0] + a[1] + a[2]) / 3.0;
    const Vec3 shift = i % 4 == 0 ? Vec3{} : Vec3{u(rng), u(rng), u(rng)} * 0.1;
    Tri b;
    for (int k = 0; k < 3; ++k) b[k] = rotate(a[k] - pivot, q) + pivot + shift;
    check(a, b);
    check(a, a);  // identical: coplanar overlap
    check(a, Tri{a[1], a[2], a[0]});
    check(a, Tri{a[0], a[2], a[1]});
  }
  EXPECT_GT(check.stats().cross, 300);
}

TEST(TriTriOracle, CornersRoundedOntoTheOtherPlane) {
  // B's corners are affine combinations of A's corners rounded to double: on plane(A) up to an ulp,
  // so the filter fails and the exact sign decides; the exact fallback must be exercised.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0), w(-0.5, 1.5);
  PairChecker check;
  const unsigned long long before = exact_fallback_count();
  for (int i = 0; i < 3000; ++i) {
    const Tri a{Vec3{u(rng), u(rng), u(rng)}, Vec3{u(rng), u(rng), u(rng)},
                Vec3{u(rng), u(rng), u(rng)}};
    auto on_plane = [&]() {
      const double s = w(rng), t = w(rng);
      return a[0] + (a[1] - a[0]) * s + (a[2] - a[0]) * t;
    };
    const Vec3 off{u(rng), u(rng), u(rng)};
    Tri b{on_plane(), on_plane(), i % 2 ? on_plane() : off};
    check(a, b);
  }
  EXPECT_GT(exact_fallback_count(), before);
  EXPECT_GT(check.stats().cross + check.stats().touch, 500);
}

TEST(TriTriOracle, GeneralPositionSegments) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PairChecker check;
  for (int i = 0; i < 4000; ++i) {
    Tri a, b;
    for (Vec3& v : a) v = {u(rng), u(rng), u(rng)};
    for (Vec3& v : b) v = {u(rng), u(rng), u(rng)};
    check(a, b);
  }
  EXPECT_GT(check.stats().cross, 500);
}

TEST(PredicatesOracle, Orient3dMatchesCgalOnNearDegenerateInput) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int disagreements = 0, zeros = 0;
  for (int i = 0; i < 20000; ++i) {
    const double scale = i % 2 ? 1.0 : 1e6;
    const Vec3 a{u(rng) * scale, u(rng), u(rng)}, b{u(rng), u(rng) * scale, u(rng)},
        c{u(rng), u(rng), u(rng)};
    const double s = u(rng) * 2, t = u(rng) * 2;
    Vec3 d = a + (b - a) * s + (c - a) * t;  // on the plane up to rounding
    if (i % 5 == 0) d = a + (b - a) * s;     // on a line through a and b up to rounding
    if (i % 7 == 0) d = b;                   // exactly on the plane
    const int ours = orient3d(a, b, c, d);
    const int theirs =
        -static_cast<int>(CGAL::orientation(to_cgal(a), to_cgal(b), to_cgal(c), to_cgal(d)));
    disagreements += ours != theirs;
    zeros += theirs == 0;
    // orient2d on the xy-projection of the same points
    const int o2 = orient2d(a.x, a.y, b.x, b.y, d.x, d.y);
    const int c2 = static_cast<int>(
        CGAL::orientation(K::Point_2(a.x, a.y), K::Point_2(b.x, b.y), K::Point_2(d.x, d.y)));
    disagreements += o2 != c2;
  }
  EXPECT_EQ(disagreements, 0);
  EXPECT_GT(zeros, 1000);
}

}  // namespace
}  // namespace interfere
