// Deterministic test/benchmark geometry: closed, welded, outward-oriented triangle meshes.
#pragma once
#include <cstddef>
#include <cstdint>

#include "interfere/mesh/tri_mesh.h"

namespace interfere {

struct SphereOptions {
  std::size_t target_triangles = 20000;  ///< actual count is the nearest UV-sphere size (2·lon·(lat-1))
  double radius = 1.0;
  Vec3 center{};
  double bump_amplitude = 0.0;  ///< relative radial bump: r = R·(1 + a·sin(kθ)·sin(kφ))
  int bump_frequency = 7;       ///< k
  double twist = 0.0;           ///< longitude offset in radians (lets two spheres' grids differ)
};

/// A UV sphere, optionally bumpy. Closed 2-manifold, genus 0, outward (counter-clockwise) faces.
TriMesh make_sphere(const SphereOptions& options);

/// Axis-aligned box [lo, hi] with `n` subdivisions per edge (12·n² triangles), closed, outward.
TriMesh make_box(const Vec3& lo, const Vec3& hi, int n = 1);

/// A prism of height h over a regular n-gon of radius r (z from 0 to h) whose caps are fans from
/// one centre vertex: 4n triangles, 2n side slivers and 2n spokes, closed, outward. The sliver case
/// of the error measurement (issue #23, item 12: a "cylinder with fan caps", a thick polygon).
TriMesh make_fan_prism(int n, double r, double h);

/// The benchmark pair of issue #2: two bumpy spheres of ~`triangles_per_part` triangles each, radius 1,
/// centres 1.96 apart on x, so that about 1 % of each part's surface lies inside the other.
struct SpherePair {
  TriMesh a, b;
};
SpherePair make_overlapping_spheres(std::size_t triangles_per_part);

}  // namespace interfere
