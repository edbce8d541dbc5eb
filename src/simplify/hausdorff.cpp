// Sampled Hausdorff distance between two meshes (issue #6, item 5) with the engine's BVH
// (bvh/bvh.h) and its nearest-triangle search (query/distance.h, nearest_triangle_d2); and the
// upper bound of the input's distance to the result (item 6, distance_bound.cpp).
#include "interfere/simplify/hausdorff.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "distance_internal.h"
#include "interfere/np/distance.h"

namespace interfere {
namespace detail {

Near nearest(const TriMesh& to, const PieceBvh& bvh, const Vec3& p, double stop_d2,
             std::uint32_t seed) {
  Near n;
  n.d = std::sqrt(nearest_triangle_d2(to, bvh.bvh, p, &n.tri, stop_d2, seed, bvh.owners()));
  return n;
}

Sampled sample(const TriMesh& to, const PieceBvh& bvh, const std::array<Vec3, 3>& c,
               const std::array<Near, 3>& at, const std::array<Near, 3>* mid, double stop_d2) {
  Sampled s{c, {}, at, {}, {}};
  for (int k = 0; k < 3; ++k) {
    s.m[k] = (c[k] + c[(k + 1) % 3]) * 0.5;
    s.mid[k] =
        mid ? (*mid)[k] : nearest(to, bvh, s.m[k], stop_d2, nearer(at[k], at[(k + 1) % 3]).tri);
  }
  s.centre = nearest(to, bvh, (c[0] + c[1] + c[2]) / 3.0, stop_d2,
                     nearer(nearer(at[0], at[1]), at[2]).tri);
  return s;
}

double Sampled::max_sample() const {
  return std::max({at[0].d, at[1].d, at[2].d, mid[0].d, mid[1].d, mid[2].d, centre.d});
}

}  // namespace detail

using detail::BoundContext;
using detail::convex_planar_regions;
using detail::ConvexRegions;
using detail::Fans;
using detail::fans_of;
using detail::local_bound;
using detail::Near;
using detail::nearer;
using detail::nearest;
using detail::piece_bvh;
using detail::PieceBvh;
using detail::refined_bound;
using detail::ring_bound;
using detail::sample;
using detail::Sampled;

// Samples: every vertex used by a triangle (an unused vertex is no point of the surface: an OBJ
// with stray vertices measured their distance), then per triangle its 3 edge midpoints and its
// centroid. The bound: per triangle local_bound, computed in the sampling pass down to 1.25x
// the vertices' largest distance (usually the largest of all: QEM errs most at vertices); the
// triangles still above 1.25x the largest sampled distance get more candidates (ring_bound), then
// midpoint subdivision (refined_bound, 2 levels).
OneSidedDistance one_sided(const TriMesh& from, const TriMesh& to, bool with_bound) {
  OneSidedDistance out;
  const std::size_t nv = from.num_vertices(), nt = from.num_triangles();
  std::vector<std::uint8_t> used(nv, 0);
  for (const Tri& t : from.triangles)
    for (std::uint32_t v : t) used[v] = 1;
  out.samples = static_cast<std::size_t>(std::count(used.begin(), used.end(), 1)) + 4 * nt;
  if (out.samples == 0) return out;
  if (to.num_triangles() == 0) {
    out.sampled = out.bound = std::numeric_limits<double>::infinity();
    return out;
  }
  constexpr double kSlack = 1.25;
  // The search tree: pieces of the slivers of `to` (piece_bvh.cpp), at most as many as there are
  // samples to measure: 80,000-triangle 20,000-gon prism to its tenth, 1.8 -> 1.0 s. (Until issue
  // #29 also up to 4 per triangle of `to`: the result's few samples on the input paid for a tree
  // of up to 4 times the input's triangles. The paper's casing, its 5,200 triangles' 23,000 samples
  // on the 35,552 of the input: 123,000 pieces, that direction 0.12 -> 0.025 s CPU with the plain
  // tree, the whole error measurement 0.25 -> 0.17 s; `fan_cylinder` to 10 %: 0.063 -> 0.034 s.
  // The distances are the same bits: the tree only changes the order of the search.)
  const PieceBvh bvh = piece_bvh(to, out.samples);
  // Early exit (Taha & Hanbury, "An Efficient Algorithm for Calculating the Exact Hausdorff
  // Distance", IEEE TPAMI 37(11), 2015): only the largest distance is wanted, so a sample's search
  // may stop at the first triangle within a distance the maximum is known to reach: every 64th
  // vertex, measured exactly first, gives one for the other vertices; the vertices' maximum for the
  // edge midpoints and centroids. A sample farther than that is measured exactly, any other
  // reports at most that: the maximum is the same, bit for bit, and the search order is fixed
  // (thread-independent). With the leaves' per-triangle box test: 10^6 -> 10^4 triangles, input to
  // result 720 -> 480 ms, 10^6 -> 10^5 910 -> 610 ms (2 cores). The edge midpoints and centroids
  // start from the triangle of their nearer corner (a seed: within the stop distance it ends the
  // search at once, else it prunes it; the exact distances do not change): 10^6 -> 10^4 500 -> 175
  // ms, 10^6 -> 10^5 640 -> 345 ms. (Seeding the vertices from the first pass's vertex before them
  // gained 5 % and loosened the bound: their triangles are its candidates.) The bound takes the
  // reported distances and triangles as they are (each at least the nearest's: it stays an upper
  // bound); triangles it refines are measured again exactly.
  constexpr std::size_t kFirst = 64;
  // The largest squared distance whose square root is at most d: a search stopped at it reports
  // no more than d.
  const auto stop_at = [](double d) {
    double s = d * d;
    while (s > 0 && std::sqrt(s) > d) s = std::nextafter(s, 0.0);
    return s;
  };
  std::vector<Near> vn(nv);
  const auto max_of = [&](std::size_t step, double stop_d2) {
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, nv, 1024), 0.0,
        [&](const tbb::blocked_range<std::size_t>& r, double m) {
          for (std::size_t v = r.begin(); v < r.end(); ++v) {
            if (!used[v] || (v % kFirst == 0) != (step == kFirst)) continue;
            vn[v] = nearest(to, bvh, from.positions[v], stop_d2);
            m = std::max(m, vn[v].d);
          }
          return m;
        },
        [](double x, double y) { return std::max(x, y); });
  };
  const double first_max = max_of(kFirst, -1);
  const double vertex_max = std::max(first_max, max_of(1, stop_at(first_max)));
  const double sample_stop = stop_at(vertex_max);
  const auto corners_of = [&](std::size_t t) {
    const Tri& tr = from.triangles[t];
    return std::array<Near, 3>{vn[tr[0]], vn[tr[1]], vn[tr[2]]};
  };
  // Edge midpoints: an edge two triangles share (by vertex number: welded meshes, as the readers
  // give them) is measured once, by the triangle where it runs from its lower to its higher vertex
  // number; the other takes that result, the same bits ((p + q) / 2 = (q + p) / 2, the same
  // query): a third of the queries fewer, nothing changes (10^6 -> 10^4: 4.5 -> 3 million).
  std::vector<Near> mid(3 * nt);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, nt, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t t = r.begin(); t < r.end(); ++t) {
          const Tri& tr = from.triangles[t];
          for (int k = 0; k < 3; ++k)
            if (tr[k] < tr[(k + 1) % 3])
              mid[3 * t + k] =
                  nearest(to, bvh, (from.positions[tr[k]] + from.positions[tr[(k + 1) % 3]]) * 0.5,
                          sample_stop, nearer(vn[tr[k]], vn[tr[(k + 1) % 3]]).tri);
        }
      });
  const Fans from_fans = fans_of(from);
  // The midpoints of triangle t: its own or, for an edge running downwards, the twin's (the first
  // triangle, by number, where it runs upwards: looked up in the smaller fan of its two ends, both
  // in triangle order, so the same twin either way; the lower end's fan alone cost O(n^2) on a fan
  // hub numbered before its rim, as STL welding numbers it: 20,000-gon prism 0.50 -> 0.15 s), else
  // measured here.
  const auto mids_of = [&](std::size_t t) {
    const Tri& tr = from.triangles[t];
    std::array<Near, 3> m;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = tr[k], b = tr[(k + 1) % 3];
      if (a < b) {
        m[k] = mid[3 * t + k];
        continue;
      }
      bool found = false;
      const std::uint32_t v = from_fans.start[a + 1] - from_fans.start[a] <
                                      from_fans.start[b + 1] - from_fans.start[b]
                                  ? a
                                  : b;
      for (std::uint32_t i = from_fans.start[v]; i < from_fans.start[v + 1] && !found; ++i) {
        const std::uint32_t u = from_fans.tris[i];
        const Tri& q = from.triangles[u];
        for (int j = 0; j < 3; ++j)
          if (u != t && q[j] == b && q[(j + 1) % 3] == a) {
            m[k] = mid[3 * u + j];
            found = true;
            break;
          }
      }
      if (!found)
        m[k] = nearest(to, bvh, (from.positions[a] + from.positions[b]) * 0.5, sample_stop,
                       nearer(vn[a], vn[b]).tri);
    }
    return m;
  };
  const Fans to_fans = with_bound ? fans_of(to) : Fans{};
  const ConvexRegions regions = with_bound ? convex_planar_regions(to) : ConvexRegions{};
  const BoundContext ctx{to, bvh, to_fans, regions};
  std::vector<double> local(with_bound ? nt : 0);
  struct Max {
    double sampled = 0, local = 0;
  };
  const Max m = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, nt, 256), Max{},
      [&](const tbb::blocked_range<std::size_t>& r, Max m) {
        for (std::size_t t = r.begin(); t < r.end(); ++t) {
          const std::array<Near, 3> mt = mids_of(t);
          const Sampled s = sample(to, bvh, from.corners(t), corners_of(t), &mt, sample_stop);
          m.sampled = std::max(m.sampled, s.max_sample());
          if (!with_bound) continue;
          local[t] = local_bound(ctx, s, kSlack * vertex_max);
          m.local = std::max(m.local, local[t]);
        }
        return m;
      },
      [](Max x, Max y) {
        return Max{std::max(x.sampled, y.sampled), std::max(x.local, y.local)};
      });
  out.sampled = std::max(vertex_max, m.sampled);
  const double floor = kSlack * out.sampled;
  double bound = m.local;
  if (with_bound && bound > floor) {
    // Refinement (issue #23, item 12), worst first: the triangles above the floor in order of their
    // local bound (ties by number), in batches of kBatch (parallel within, a fixed partition: the
    // result is thread-independent); it stops when the next triangle's local bound is within what
    // the refined ones reached (nothing left can raise or lower the maximum: early exit as in Taha
    // & Hanbury 2015) or the floor, or after kRefineBudget + nt / 16 triangles: the bound is then
    // the larger of the refined maximum and the next local bound, which bounds every triangle not
    // refined (valid, only looser). Each refinement costs a bounded number of searches and
    // polygons, so the bound costs O(n) searches whatever the triangles' shapes.
    constexpr std::size_t kBatch = 256, kRefineBudget = 2048;
    std::vector<std::uint32_t> over;
    double below = 0;  // the largest local bound at or under the floor
    for (std::uint32_t t = 0; t < nt; ++t) {
      if (local[t] > floor)
        over.push_back(t);
      else
        below = std::max(below, local[t]);
    }
    std::sort(over.begin(), over.end(), [&](std::uint32_t x, std::uint32_t y) {
      return local[x] != local[y] ? local[x] > local[y] : x < y;
    });
    const std::size_t budget = std::min(over.size(), kRefineBudget + nt / 16);
    // New searches may stop at half the floor: any triangle that near serves the bound as well.
    const double refine_stop = stop_at(0.5 * floor);
    double done = 0;
    std::size_t i = 0;
    while (i < budget && local[over[i]] > std::max(done, floor)) {
      const std::size_t end = std::min(budget, i + kBatch);
      done = std::max(done, tbb::parallel_reduce(
                                tbb::blocked_range<std::size_t>(i, end, 8), 0.0,
                                [&](const tbb::blocked_range<std::size_t>& r, double b) {
                                  for (std::size_t j = r.begin(); j < r.end(); ++j) {
                                    const std::uint32_t t = over[j];
                                    const std::array<Vec3, 3> c = from.corners(t);
                                    const Tri& tr = from.triangles[t];
                                    const std::array<Near, 3> at{
                                        nearest(to, bvh, c[0], refine_stop, vn[tr[0]].tri),
                                        nearest(to, bvh, c[1], refine_stop, vn[tr[1]].tri),
                                        nearest(to, bvh, c[2], refine_stop, vn[tr[2]].tri)};
                                    const Sampled s = sample(to, bvh, c, at, nullptr, refine_stop);
                                    double x = std::min(local[t], ring_bound(ctx, s, floor));
                                    if (x > floor)
                                      x = std::min(x, refined_bound(ctx, s, floor, 2, refine_stop));
                                    b = std::max(b, x);
                                  }
                                  return b;
                                },
                                [](double x, double y) { return std::max(x, y); }));
      i = end;
    }
    bound = std::max({done, below, i < over.size() ? local[over[i]] : 0.0});
  }
  // Rounding of the closest-point computations (relative 1e-11 seen on CAD slivers): a margin of
  // 1e-9 of the two meshes' joint extent.
  Aabb box = from.bounds();
  box.expand(to.bounds());
  out.bound = with_bound ? std::max(bound, out.sampled) + 1e-9 * norm(box.extent())
                         : std::numeric_limits<double>::infinity();
  return out;
}

double one_sided_distance(const TriMesh& from, const TriMesh& to, std::size_t* samples) {
  const OneSidedDistance d = one_sided(from, to, false);
  if (samples) *samples = d.samples;
  return d.sampled;
}

HausdorffResult hausdorff(const TriMesh& a, const TriMesh& b, bool with_bound) {
  HausdorffResult r;
  // The two directions at once (issue #29): each has serial steps (its tree, the fans, the convex
  // regions, the refinement's sort) that the other's parallel loops fill. The casing's error
  // measurement 0.081 -> 0.074 s wall on 2 cores (medians of 16, P1/P2, interfere-cad under
  // SCHED_RR: docs/simplify.md); the same bits (each direction is computed as before).
  OneSidedDistance ab, ba;
  tbb::parallel_invoke([&] { ab = one_sided(a, b, with_bound); }, [&] { ba = one_sided(b, a, false); });
  r.a_to_b = ab.sampled, r.b_to_a = ba.sampled;
  r.a_to_b_bound = ab.bound;
  r.samples = ab.samples + ba.samples;
  return r;
}

}  // namespace interfere
