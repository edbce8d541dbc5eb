// The paper's comparison methods (Li, Zhou & Zheng 2008, §4): uniform spatial subdivision and a
// distance field, implemented here so that docs/probe.md compares them with the patch hierarchy
// and the BVH in one run. Both feed the same exact cylinder-triangle test.
#include <algorithm>
#include <cmath>
#include <queue>

#include <tbb/parallel_for.h>

#include "interfere/bvh/traverse.h"
#include "interfere/np/distance.h"
#include "interfere/probe/sweep.h"

namespace interfere::probe {

UniformGrid make_uniform_grid(const TriMesh& mesh, double cell) {
  UniformGrid g;
  g.bounds = mesh.bounds();
  g.cell = cell;
  const Vec3 e = g.bounds.extent();
  g.nx = std::max(1, static_cast<int>(std::ceil(e.x / cell)));
  g.ny = std::max(1, static_cast<int>(std::ceil(e.y / cell)));
  g.nz = std::max(1, static_cast<int>(std::ceil(e.z / cell)));
  const std::size_t cells = static_cast<std::size_t>(g.nx) * g.ny * g.nz;
  std::vector<std::uint32_t> count(cells + 1, 0);
  auto range = [&](const Aabb& b, int lo[3], int hi[3]) {
    const int n[3] = {g.nx, g.ny, g.nz};
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::clamp(static_cast<int>(std::floor((b.lo[k] - g.bounds.lo[k]) / cell)), 0, n[k] - 1);
      hi[k] = std::clamp(static_cast<int>(std::floor((b.hi[k] - g.bounds.lo[k]) / cell)), 0, n[k] - 1);
    }
  };
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      for (std::size_t i = 0; i < cells; ++i) count[i + 1] += count[i];
      g.start = count;
      g.items.resize(count[cells]);
    }
    for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
      int lo[3], hi[3];
      range(mesh.triangle_box(t), lo, hi);
      for (int z = lo[2]; z <= hi[2]; ++z) {
        for (int y = lo[1]; y <= hi[1]; ++y) {
          for (int x = lo[0]; x <= hi[0]; ++x) {
            const std::size_t c = (static_cast<std::size_t>(z) * g.ny + y) * g.nx + x;
            if (pass == 0) ++count[c + 1];
            else g.items[count[c]++] = static_cast<std::uint32_t>(t);
          }
        }
      }
    }
  }
  return g;
}

DistanceField make_distance_field(const TriMesh& mesh, const Bvh& bvh, double spacing, double margin) {
  DistanceField f;
  f.spacing = spacing;
  f.bounds = mesh.bounds();
  f.bounds.lo -= Vec3{margin, margin, margin};
  f.bounds.hi += Vec3{margin, margin, margin};
  const Vec3 e = f.bounds.extent();
  f.nx = static_cast<int>(std::ceil(e.x / spacing)) + 1;
  f.ny = static_cast<int>(std::ceil(e.y / spacing)) + 1;
  f.nz = static_cast<int>(std::ceil(e.z / spacing)) + 1;
  f.values.assign(static_cast<std::size_t>(f.nx) * f.ny * f.nz, 0.0f);
  tbb::parallel_for(0, f.nz, [&](int z) {
    for (int y = 0; y < f.ny; ++y) {
      for (int x = 0; x < f.nx; ++x) {
        const Vec3 p = f.bounds.lo + Vec3{x * spacing, y * spacing, z * spacing};
        // Best-first nearest triangle over the BVH.
        double best2 = 1e300;
        using Item = std::pair<double, std::uint32_t>;
        std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
        auto box_d2 = [&](const AabbF& b) {
          double d2 = 0;
          for (int k = 0; k < 3; ++k) {
            const double g = std::max({static_cast<double>(b.lo[k]) - p[k], p[k] - static_cast<double>(b.hi[k]), 0.0});
            d2 += g * g;
          }
          return d2;
        };
        q.push({box_d2(bvh.nodes[0].box), 0});
        while (!q.empty() && q.top().first < best2) {
          const std::uint32_t ni = q.top().second;
          q.pop();
          const BvhNode& nd = bvh.nodes[ni];
          if (nd.is_leaf()) {
            for (std::uint32_t j = nd.first; j < nd.first + nd.count; ++j) {
              const Vec3 c = closest_point_on_triangle(p, mesh.corners(bvh.prims[j]));
              best2 = std::min(best2, squared_norm(c - p));
            }
          } else {
            for (std::uint32_t c = nd.first; c < nd.first + 2; ++c) q.push({box_d2(bvh.nodes[c].box), c});
          }
        }
        // Rounded down (with a relative margin for the double construction): a lower bound.
        f.values[(static_cast<std::size_t>(z) * f.ny + y) * f.nx + x] =
            round_down(std::sqrt(best2) * (1 - 1e-12));
      }
    }
  });
  f.grid = make_uniform_grid(mesh, 2 * spacing);
  return f;
}

}  // namespace interfere::probe
