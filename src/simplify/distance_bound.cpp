// Upper bound of the distance from a triangle of one mesh to another mesh (issue #6, item 6: the
// error bound stored with a simplified part, which makes clash checks on it conservative): the
// smaller of a Lipschitz bound over the triangle's samples and a convexity bound over convex
// pieces of it, each with one triangle of the other mesh (see local_bound).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "distance_internal.h"
#include "interfere/np/distance.h"

namespace interfere::detail {
namespace {

// A convex polygon (a triangle of `from` cut by planes). `lost`: a cut had more vertices than fit
// (then the piece is smaller than the cut and must not be used: the bound would miss points).
struct Poly {
  std::array<Vec3, 10> v;
  int n = 0;
  bool lost = false;
};

// The polygon's part on the positive side of the plane n.(x - o) >= 0 (Sutherland-Hodgman).
Poly clip(const Poly& p, const Vec3& n, const Vec3& o) {
  Poly out;
  for (int i = 0; i < p.n; ++i) {
    const Vec3& a = p.v[i];
    const Vec3& b = p.v[(i + 1) % p.n];
    const double da = dot(n, a - o), db = dot(n, b - o);
    if (da >= 0) {
      if (out.n < 10)
        out.v[out.n++] = a;
      else
        out.lost = true;
    }
    if ((da < 0) != (db < 0)) {
      if (out.n < 10)
        out.v[out.n++] = a + (b - a) * (da / (da - db));
      else
        out.lost = true;
    }
  }
  out.lost = out.lost || p.lost;
  return out;
}

// A plane between triangles t1 and t2 of `to` (normal towards t1) with the point x on t2's side,
// cutting across the surface they approximate (N: their mean normal): through their shared edge,
// halving the angle between them; through their shared vertex, between their centroids; else
// between x's closest points on t1 and t2 (x is nearer to t2's); each only if it leaves x on t2's
// side (the cut must make progress).
bool separating_plane(const std::array<Vec3, 3>& t1, const std::array<Vec3, 3>& t2, const Vec3& x,
                      Vec3& n, Vec3& o) {
  const auto accept = [&](const Vec3& nn, const Vec3& oo) {
    if (!(squared_norm(nn) > 0) || !(dot(nn, x - oo) < 0)) return false;
    n = nn, o = oo;
    return true;
  };
  int shared = 0, i1[2], i2[2];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      if (t1[a] == t2[b] && shared < 2) i1[shared] = a, i2[shared] = b, ++shared;
  if (shared == 2) {
    const Vec3 u = t1[i1[0]], e = t1[i1[1]] - u;
    const double ee = dot(e, e);
    const Vec3 w1 = t1[3 - i1[0] - i1[1]] - u, w2 = t2[3 - i2[0] - i2[1]] - u;
    const Vec3 a1 = w1 - e * (dot(w1, e) / ee), a2 = w2 - e * (dot(w2, e) / ee);
    const double l1 = norm(a1), l2 = norm(a2);
    if (ee > 0 && l1 > 0 && l2 > 0 && accept(a1 / l1 - a2 / l2, u)) return true;
  }
  Vec3 mean = cross(t1[1] - t1[0], t1[2] - t1[0]), m2 = cross(t2[1] - t2[0], t2[2] - t2[0]);
  const double ml1 = norm(mean), ml2 = norm(m2);
  mean = ml1 > 0 && ml2 > 0 ? mean / ml1 + m2 / ml2 : Vec3{};
  const double ml = norm(mean);
  const auto across = [&](const Vec3& v) {
    return ml > 0 ? v - mean * (dot(v, mean) / (ml * ml)) : v;
  };
  if (shared == 1) {
    const Vec3 c1 = (t1[0] + t1[1] + t1[2]) / 3.0, c2 = (t2[0] + t2[1] + t2[2]) / 3.0;
    if (accept(across(c1 - c2), t1[i1[0]])) return true;
  }
  const Vec3 q1 = closest_point_on_triangle(x, t1), q2 = closest_point_on_triangle(x, t2);
  return accept(across(q1 - q2), (q1 + q2) * 0.5) || accept(q1 - q2, (q1 + q2) * 0.5);
}

// Upper bound of the distance from the points of polygon p to `to`: the distance to one triangle
// t of `to` is convex, so on p it is largest at a vertex, and the distance to `to` is at most
// that, for each candidate t. Where the best candidate leaves the bound above `floor`, p is cut
// (any partition gives a bound) into the piece over that candidate's triangle and the pieces beyond
// its edges, each bounded with its own best candidate (an input triangle across a fan of output
// triangles), and, if that is still above `floor`, by a plane between that candidate and the one
// nearest to its worst vertex (an input triangle straddling an edge of the output); the smallest
// bound found is kept. `budget` caps the polygons examined (a cut stops when it runs out; the bound
// stays valid, only less tight).
// Works with squared distances (floor2 = floor^2; the square root once, by the callers) on the
// candidates' corners fetched once (cand).
using Corners = std::array<Vec3, 3>;
double d2_to(const Vec3& x, const Corners& t) {
  return squared_norm(closest_point_on_triangle(x, t) - x);
}

double convex_bound2(const Poly& p, const Corners* cand, int nc, double floor2, int depth,
                     int& budget) {
  if (p.n == 0) return 0;
  --budget;
  double best = std::numeric_limits<double>::infinity();
  int bi = -1, worst_v = 0;
  for (int i = 0; i < nc; ++i) {
    double w = 0;
    int wv = 0;
    for (int k = 0; k < p.n && w < best; ++k) {
      const double d = d2_to(p.v[k], cand[i]);
      if (d > w) w = d, wv = k;
    }
    if (w < best) best = w, bi = i, worst_v = wv;
  }
  if (best <= floor2 || depth == 0 || nc < 2 || budget <= 0) return best;
  // Peel the best candidate t's prism: the piece of p over t (inside the three planes through t's
  // edges along its normal) is bounded by t alone; the pieces beyond each edge plane in turn go to
  // the other candidates (an input triangle across a fan of output triangles: one level each).
  {
    const Corners& t = cand[bi];
    const Vec3 nt = cross(t[1] - t[0], t[2] - t[0]);
    if (squared_norm(nt) > 0) {
      Poly rest = p;
      std::array<Poly, 3> out;
      int pieces = 0;
      for (int k = 0; k < 3 && rest.n > 0; ++k) {
        Vec3 m = cross(nt, t[(k + 1) % 3] - t[k]);
        if (dot(m, t[(k + 2) % 3] - t[k]) < 0) m = m * -1.0;  // towards the inside
        out[k] = clip(rest, m * -1.0, t[k]);
        rest = clip(rest, m, t[k]);
        pieces += out[k].n > 0;
      }
      const bool lost = rest.lost || out[0].lost || out[1].lost || out[2].lost;
      if (!lost &&
          (rest.n > 0 || pieces > 1)) {  // progress: p is cut (else the pairwise split below)
        double worst = 0;
        for (int k = 0; k < rest.n && worst < best; ++k)
          worst = std::max(worst, d2_to(rest.v[k], t));
        for (int k = 0; k < 3 && worst < best; ++k)
          if (out[k].n > 0)
            worst = std::max(worst, convex_bound2(out[k], cand, nc, floor2, depth - 1, budget));
        best = std::min(best, worst);
        if (best <= floor2) return best;  // else the pairwise split below may still do better
      }
    }
  }
  const Vec3& x = p.v[worst_v];
  int bj = -1;
  double dj = d2_to(x, cand[bi]);
  for (int i = 0; i < nc; ++i) {
    if (i == bi) continue;
    const double d = d2_to(x, cand[i]);
    if (d < dj) dj = d, bj = i;
  }
  Vec3 n, o;
  if (bj < 0 || !separating_plane(cand[bi], cand[bj], x, n, o)) return best;
  const Poly p1 = clip(p, n, o), p2 = clip(p, n * -1.0, o);
  if (p1.n == 0 || p2.n == 0 || p1.lost || p2.lost) return best;
  const double b1 = convex_bound2(p1, cand, nc, floor2, depth - 1, budget);
  if (b1 >= best) return best;
  return std::min(best, std::max(b1, convex_bound2(p2, cand, nc, floor2, depth - 1, budget)));
}

// Candidates of one convex_bound at most (ring_bound's fans are cut there).
constexpr int kMaxCandidates = 64;

// convex_bound2 of triangle c with the candidates' triangle numbers, as a distance.
double convex_bound(const TriMesh& to, const std::array<Vec3, 3>& c, const std::uint32_t* cand,
                    int nc, double floor, int depth, int budget) {
  std::array<Corners, kMaxCandidates> corners;
  nc = std::min(nc, kMaxCandidates);
  for (int i = 0; i < nc; ++i) corners[i] = to.corners(cand[i]);
  Poly p;
  p.n = 3;
  std::copy(c.begin(), c.end(), p.v.begin());
  return std::sqrt(convex_bound2(p, corners.data(), nc, floor * floor, depth, budget));
}

}  // namespace

// Upper bound of the distance from the points of triangle s.c to `to`, the smaller of two bounds,
// computed lazily down to `floor`:
// - convexity (convex_bound) with the nearest triangles of the samples as candidates (the
//   centroid's first: 0 for a triangle the output kept);
// - Lipschitz: the distance is 1-Lipschitz, and every point of a triangle with longest edge l lies
//   within l / sqrt(3) of a corner (at most the circumradius of an acute triangle, whose largest
//   angle is >= 60 degrees, or half the longest edge of an obtuse one); split at the edge
//   midpoints, the four halves have longest edges <= l/2: max over corners and midpoints + l / (2
//   sqrt 3).
double local_bound(const BoundContext& ctx, const Sampled& s, double floor) {
  double longest = 0;
  for (int k = 0; k < 3; ++k) longest = std::max(longest, norm(s.c[(k + 1) % 3] - s.c[k]));
  const double lips =
      std::max({s.at[0].d, s.at[1].d, s.at[2].d, s.mid[0].d, s.mid[1].d, s.mid[2].d}) +
      longest / (2.0 * std::sqrt(3.0));
  if (lips <= floor) return lips;
  const double b = std::min(lips, region_bound(ctx, s.c, s.at));
  if (b <= floor) return b;
  std::array<std::uint32_t, 7> cand{s.centre.tri, s.at[0].tri,  s.at[1].tri, s.at[2].tri,
                                    s.mid[0].tri, s.mid[1].tri, s.mid[2].tri};
  int nc = 0;
  for (std::size_t i = 0; i < cand.size(); ++i)
    if (std::find(cand.begin(), cand.begin() + nc, cand[i]) == cand.begin() + nc)
      cand[nc++] = cand[i];
  // Polygons examined at most (each cut multiplies them). A triangle left above the floor goes to
  // ring_bound and refined_bound: 64 here gave the same bounds on the bumpy sphere and the shared
  // meshes, 10^6 -> 10^5 in 1.58 s instead of 1.33.
  return std::min(b, convex_bound(ctx.to, s.c, cand.data(), nc, std::max(floor, 0.0), 4, 16));
}

// The region of a corner's own nearest triangle serves it as it is; another region through a
// triangle of it across an edge of that nearest one (a corner on an edge of `to` where the plane
// meets a neighbouring face: either triangle may be reported) or, failing that, around one of
// its vertices (the first 16 of each fan).
double region_bound(const BoundContext& ctx, const std::array<Vec3, 3>& c,
                    const std::array<Near, 3>& at) {
  const ConvexRegions& r = ctx.regions;
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const std::uint32_t id = r.of[at[i].tri];
    if (id == ConvexRegions::kNone || (i > 0 && id == r.of[at[0].tri]) ||
        (i > 1 && id == r.of[at[1].tri]))
      continue;
    double worst = 0;
    for (int k = 0; k < 3 && worst < best; ++k) {
      const std::uint32_t t = at[k].tri;
      if (r.of[t] == id) {
        worst = std::max(worst, at[k].d);
        continue;
      }
      double d2 = std::numeric_limits<double>::infinity();
      for (int e = 0; e < 3; ++e) {
        const std::uint32_t u = r.neighbour[3 * t + e];
        if (u != kNoSeed && r.of[u] == id) d2 = std::min(d2, d2_to(c[k], ctx.to.corners(u)));
      }
      for (std::uint32_t v : ctx.to.triangles[t]) {
        if (std::isfinite(d2)) break;
        const std::uint32_t end = std::min(ctx.fans.start[v + 1], ctx.fans.start[v] + 16);
        for (std::uint32_t j = ctx.fans.start[v]; j < end; ++j)
          if (r.of[ctx.fans.tris[j]] == id)
            d2 = std::min(d2, d2_to(c[k], ctx.to.corners(ctx.fans.tris[j])));
      }
      worst = std::max(worst, std::sqrt(d2));
    }
    best = std::min(best, worst + r.slack[id]);
  }
  return best;
}

Fans fans_of(const TriMesh& m) {
  Fans f;
  f.start.assign(m.num_vertices() + 1, 0);
  for (const Tri& t : m.triangles)
    for (std::uint32_t v : t) ++f.start[v + 1];
  for (std::size_t v = 0; v < m.num_vertices(); ++v) f.start[v + 1] += f.start[v];
  f.tris.resize(f.start.back());
  std::vector<std::uint32_t> fill(f.start.begin(), f.start.end() - 1);
  for (std::uint32_t t = 0; t < m.num_triangles(); ++t)
    for (std::uint32_t v : m.triangles[t]) f.tris[fill[v]++] = t;
  return f;
}

// convex_bound with more candidates: the samples' nearest triangles and every triangle sharing a
// vertex with one of them.
double ring_bound(const BoundContext& ctx, const Sampled& s, double floor) {
  const TriMesh& to = ctx.to;
  const Fans& fans = ctx.fans;
  std::array<std::uint32_t, kMaxCandidates> cand;
  int nc = 0;
  const auto add = [&](std::uint32_t t) {
    if (nc < kMaxCandidates && std::find(cand.begin(), cand.begin() + nc, t) == cand.begin() + nc)
      cand[nc++] = t;
  };
  for (const Near* n : {&s.centre, &s.at[0], &s.at[1], &s.at[2], &s.mid[0], &s.mid[1], &s.mid[2]})
    add(n->tri);
  const int seeds = nc;
  for (int i = 0; i < seeds; ++i)
    for (std::uint32_t v : to.triangles[cand[i]])
      for (std::uint32_t k = fans.start[v]; k < fans.start[v + 1]; ++k) add(fans.tris[k]);
  return convex_bound(to, s.c, cand.data(), nc, floor, 6, 128);
}

// local_bound refined by midpoint subdivision (depth levels) where it exceeds `floor`.
double refined_bound(const BoundContext& ctx, const Sampled& s, double floor, int depth,
                     double stop_d2) {
  const double b = local_bound(ctx, s, floor);
  if (b <= floor || depth == 0) return b;
  const std::array<std::array<Vec3, 3>, 4> sub{{{s.c[0], s.m[0], s.m[2]},
                                                {s.m[0], s.c[1], s.m[1]},
                                                {s.m[2], s.m[1], s.c[2]},
                                                {s.m[0], s.m[1], s.m[2]}}};
  const std::array<std::array<Near, 3>, 4> sub_at{{{s.at[0], s.mid[0], s.mid[2]},
                                                   {s.mid[0], s.at[1], s.mid[1]},
                                                   {s.mid[2], s.mid[1], s.at[2]},
                                                   {s.mid[0], s.mid[1], s.mid[2]}}};
  double r = 0;
  for (int k = 0; k < 4 && r < b; ++k)
    r = std::max(r, refined_bound(ctx, sample(ctx.to, ctx.bvh, sub[k], sub_at[k], nullptr, stop_d2),
                                  floor, depth - 1, stop_d2));
  return std::min(b, r);
}

}  // namespace interfere::detail
