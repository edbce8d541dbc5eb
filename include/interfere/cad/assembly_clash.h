// Interference of every pair of instances of a CAD assembly, as a CAD package's clash module checks
// an assembly (the mission's "static clash" of paper 1 on the parts of a STEP product tree): each
// instance's tessellation placed in the world, candidate pairs by their boxes (grown by the
// clearance), then the engine's exact clash (query/clash.h) of each candidate. OCCT-free: works on
// a CadModel from import_step or built by hand.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "interfere/cad/model.h"
#include "interfere/query/clash.h"

namespace interfere::cad {

struct AssemblyClashOptions {
  double clearance = 0;  ///< > 0: also report pairs of instances closer than this (model units)
  /// Keep each clashing pair's geometry (InstancePairResult::curves, region_triangles_a/b): the
  /// clash regions and intersection curves a CAD package's clash module shows (paper 1's exported
  /// clash regions).
  bool geometry = false;
  /// Splits per direction of a clashing pair for InstancePairResult::depth_bound (about 4 µs each;
  /// more: a tighter bound); 0: no bound.
  std::size_t depth_bound_splits = 5000;
  /// Progress (done, count) as instance pairs are decided, from worker threads (thread-safe
  /// callers only; scene::SceneClashOptions::pair_progress).
  std::function<void(std::size_t, std::size_t)> progress;
};

/// How two instances meet: `clash` (their surfaces cross, one lies inside the other, or their
/// surfaces only touch while the solids overlap: ClashResult::touching_overlap, e.g. an instance
/// placed twice), `contact` (they touch only: faces, edges or points in common, as mating parts
/// do; or their tessellations cross only where their B-Rep faces coincide: a nominal fit, see
/// InstancePairResult::nominal_fit), `clearance` (apart, but closer than the clearance),
/// `undecided` (an instance is open where inside/outside decides: touching surfaces or nested
/// boxes; the clash engine's Verdict::undecided, InstancePairResult::verdict_reasons says why).
/// The names are the verdict model's (query/verdict.h).
enum class InstanceMeeting : std::uint8_t { clash, contact, clearance, undecided };
const char* instance_meeting_name(InstanceMeeting m);

struct InstancePairResult {
  std::uint32_t a = 0, b = 0;  ///< instance indices, a < b
  InstanceMeeting meeting = InstanceMeeting::contact;
  std::size_t cross_pairs = 0, touch_pairs = 0;  ///< intersecting triangle pairs (query/clash.h)
  std::size_t clearance_pairs = 0;               ///< triangle pairs apart but within the clearance
  double min_clearance = 0;                      ///< the smallest of their distances (0 without)
  Containment containment = Containment::not_checked;
  bool touching_overlap = false;  ///< touching surfaces of overlapping solids (ClashResult)
  /// Clashes with crossing surfaces: the largest distance to the other surface of the vertices of
  /// either part that lie inside the other solid (exact ray parity; the vertices of the crossing
  /// triangles and of the other triangles inside): a sampled lower bound of how deep the surfaces
  /// reach into each other, 0 when no vertex lies inside. `tessellation_error`: the sum over the two
  /// parts of the larger of Part::linear_deflection and Part::tessellation_deviation (when
  /// measured: BRepMesh may exceed its tolerance), the chordal error by which tessellations of
  /// B-Rep faces in contact may cross (0 for parts not from STEP). A depth within it suggests a
  /// nominal fit.
  double depth = 0, tessellation_error = 0;
  /// Clashes with crossing surfaces (not nominal fits): an upper bound of that depth over every
  /// point of either surface inside the other solid, not samples (branch and bound on pieces of the
  /// triangles that may lie inside, the distance being 1-Lipschitz; within 10 % of `depth`, or
  /// looser after AssemblyClashOptions::depth_bound_splits per direction); 0 otherwise (or with no
  /// splits allowed). depth <= true depth <= depth_bound.
  double depth_bound = 0;
  /// The surfaces cross only where B-Rep faces coincide (coaxial cylinders of one radius, as a bolt
  /// in a hole of its own diameter or a nut's bore in line with a plate's; two planes back to back;
  /// a sphere in a spherical seat; a face crossing the other part may coincide with one it does not
  /// meet, as a seat a hair inside a plate's face): every crossing pair has a face of such a
  /// coincident pair (the bolt's cylinder also crosses the plate's faces at the rim of the hole),
  /// and the sampled depth is within the tessellation error. Their tessellations cross only by
  /// their chordal errors, so the instances are a contact. Geometry compared within kFitTolerance
  /// (the faces' parameters, placed by the instances' transforms; B-spline faces by their
  /// recognised cylinder, plane or sphere).
  bool nominal_fit = false;
  /// A contact classified from the B-Rep (issue #29, item 4): the tessellations neither cross nor
  /// touch (apart by `min_clearance`, rounding of the placements, e.g. 1.3e-12 mm in the AS1 AP203
  /// export) or lie only within the clearance, but B-Rep faces of the two coincide back to back (as
  /// for nominal_fit) and their triangles come within kFitTolerance of the parts' diagonals.
  bool zero_clearance_fit = false;
  std::size_t regions = 0;
  double curve_length = 0;  ///< of the intersection curves
  std::vector<std::string> verdict_reasons;  ///< for `undecided`: what could not be decided
  /// With AssemblyClashOptions::geometry, for pairs that clash: the intersection curves (world
  /// coordinates) and each instance's triangles in the clash regions (sorted indices into its
  /// part's mesh, Part::mesh: its triangles in the same order; all of an instance that lies inside
  /// the other), empty otherwise.
  std::vector<Polyline> curves;
  std::vector<std::uint32_t> region_triangles_a, region_triangles_b;
};

/// Relative tolerance (of the two parts' bounding-box diagonals, and in radians for directions)
/// within which two placed B-Rep faces count as the same surface for InstancePairResult::nominal_fit:
/// far above the rounding of placements, below the interference of a press fit.
inline constexpr double kFitTolerance = 1e-7;

struct AssemblyClashResult {
  /// The meeting pairs, by (a, b); pairs that neither meet nor come within the clearance are left out.
  std::vector<InstancePairResult> pairs;
  std::size_t candidate_pairs = 0;  ///< instance pairs whose boxes (grown by the clearance) overlap
  std::size_t clashes = 0, contacts = 0, within_clearance = 0, undecided = 0;
  /// The worst pair's (query/verdict.h): clash, undecided, contact, clearance or clear.
  Verdict verdict = Verdict::clear;
  std::vector<std::string> warnings;  ///< open instances (containment not checked), ...
};

/// Every pair of model.instances. Deterministic (results do not depend on the thread count).
AssemblyClashResult assembly_clash(const CadModel& model, const AssemblyClashOptions& options = {});

}  // namespace interfere::cad
