// The paper's three levels as written (Li, Zhou & Zheng 2008, §3.2-3.4; issue #28, deliverable 3),
// kept beside the project's exact cylinder-triangle test (cylinder.h), which stays the default.
// All in double precision, as the paper's; docs/probe.md "The paper's three levels, as written"
// says where each is incomplete:
//
//  - §3.2 box test: two boxes intersect when one box's 12 edges meet the other's 6 faces (line-plane
//    intersection, the point in the face by the area method, on the edge by the length method).
//    Misses a box inside the other (no edge meets a face) and, with one direction only, boxes
//    whose edges cross only the other way: a FALSE NEGATIVE (a possible contact dropped).
//  - §3.3 triangle/box test: the triangle's 3 edges against the box's 6 faces. Misses a triangle
//    inside the box and a box piercing the triangle's interior: FALSE NEGATIVES.
//  - §3.4 three projections: the cylinder and the triangle overlap when their projections overlap
//    along (1) the cylinder axis, (2) one edge of the triangle, (3) a diameter of the end circle.
//    Projections of intersecting sets always overlap, so it never misses a contact, but three
//    directions do not decide every configuration: FALSE POSITIVES (clear pairs called overlapping;
//    tests/unit/probe/test_paper_tests.cpp searches for them).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "interfere/core/aabb.h"
#include "interfere/core/vec.h"
#include "interfere/probe/cylinder.h"
#include "interfere/probe/sweep.h"

namespace interfere::probe {

/// §3.2: does the closed segment [p, q] meet the closed planar quadrilateral `face` (corners in
/// order)? Line-plane intersection as in the paper (a segment parallel to the face's plane never
/// meets it, even when lying in it), the intersection point in the face when the four triangle
/// areas it makes with the sides add up to the face's area, on the segment when PA + PB = AB; both
/// equalities within a relative 1e-9 (our addition: exact equality fails on rounding).
bool paper_segment_meets_face(const Vec3& p, const Vec3& q, const std::array<Vec3, 4>& face);

/// §3.2 as written: one box's 12 edges (`edges_of`) against the other's 6 faces (`faces_of`).
bool paper_box_test(const Aabb& edges_of, const Aabb& faces_of);

/// §3.1's probe box: built from the two end-circle centres and the diameter (centres -/+ radius
/// in every coordinate; contains the cylinder).
Aabb paper_cylinder_box(const Cylinder& c);

/// §3.3 as written: the triangle's 3 edges against the box's 6 faces.
bool paper_triangle_box_test(const std::array<Vec3, 3>& t, const Aabb& box);

/// §3.4: the outcome of each of the three projections (true = the projections overlap).
struct PaperProjections {
  bool along_axis = false;      ///< §3.4.1: ellipse (the end circle) vs triangle
  bool along_edge = false;      ///< §3.4.2: ellipses O1, O2 and rectangle vs the segment the triangle becomes
  bool along_diameter = false;  ///< §3.4.3: rectangle vs triangle
  bool all() const { return along_axis && along_edge && along_diameter; }
};

/// §3.4's three projections of cylinder `c` and triangle `t`: along the axis, along the edge
/// t[edge] -> t[(edge + 1) % 3] (edge in 0..2), and along the diameter of the end circle in the
/// direction of the component of `diameter` perpendicular to the axis (the paper leaves both
/// choices open: "any edge", "any diameter"; a zero `diameter`, or one along the axis, picks a
/// fixed one). A degenerate edge (zero length) counts as overlapping (no direction to project on).
PaperProjections paper_projections(const Cylinder& c, const std::array<Vec3, 3>& t, int edge = 0,
                                   const Vec3& diameter = {});

/// The paper's hierarchy at one path point, beside the exact test (issue #28; `interfere sweep
/// --paper-levels`): §3.2 the probe's box (paper_cylinder_box) against each workpiece patch box
/// (an edge of either box meeting a face of the other), §3.3 the triangles of the patches that pass
/// against the probe box, §3.4 the three projections (edge `edge`, the fixed diameter) for the
/// triangles that pass. The probe cylinder only (the paper has no holder). `exact` is the project's
/// exact test over every triangle (no paper level in front of it), so `collides != exact` is the
/// paper's error at this point: a false positive (collides, not exact) or a false negative.
struct PaperPointCheck {
  bool collides = false;                 ///< some triangle passed all three levels
  bool exact = false;                    ///< the exact cylinder-triangle test: some triangle touches
  std::uint32_t patches_passed = 0;      ///< patch boxes passing §3.2
  std::uint32_t triangles_passed = 0;    ///< triangles passing §3.3
  std::uint32_t projections_passed = 0;  ///< triangles passing §3.4
  std::vector<std::uint32_t> hits;       ///< triangles passing all three levels, sorted
  bool false_positive() const { return collides && !exact; }
  bool false_negative() const { return !collides && exact; }
};
PaperPointCheck paper_point_check(const Workpiece& workpiece, const ProbeShape& shape, const ProbePose& pose,
                                  int edge = 0);

}  // namespace interfere::probe
