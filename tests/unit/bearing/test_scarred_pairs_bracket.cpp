// Two scarred rollers that come close (issue #27; src/bearing/scarred_two_sided.h (3)): no exact
// solver, the bracket [L, U*] of S = min(s(A, B), s(B, A)). Neighbours of an assembly with every
// roller scarred (inward and raised scars, cylindrical and tapered), pressed together from 1 mm of
// overlap to a few hundredths of a millimetre apart, scars facing each other (350 degrees wide).
// Independent oracle, written here and in scarred_reference.h (a different method from the
// solvers'): sd_B(p) of a point by every triangle's closest point and ray parity (majority of three
// directions), s(A, B) densely sampled (a 6-step barycentric grid on every triangle of A that a
// Lipschitz bound, sd_B(centroid) - radius, does not rule out), and the brute-force distance of
// every triangle pair. Checked per row:
//   * U* is sd of a point of one surface to the other's closed mesh: its witness lies on that
//     surface and the oracle's sd there is U* (so S <= U*, and U* < -tol certifies a clash);
//   * L <= the dense value (an upper end of S) and U* >= the dense value - its spacing;
//   * exact rows equal the brute-force distance to 1e-9 relative (plus 1e-15 of the scale: rounding);
//   * decided verdicts agree with the mesh engine (query/clash.h) on the two meshes;
//   * decide_part_pair(x, y) and (y, x) give the same value, lower end and verdict bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <string>

#include "interfere/bearing/assembly.h"
#include "interfere/bearing/cylinder.h"
#include "interfere/bearing/part_pair.h"
#include "interfere/query/clash.h"
#include "unit/bearing/scarred_pair_parts.h"
#include "unit/bearing/scarred_reference.h"

namespace interfere::bearing {
namespace {

using test::meshes_clash;
using test::scene_part;

/// A posed closed mesh and its triangles' bounding spheres (centroid, largest corner distance).
struct Posed {
  const TriMesh* mesh;
  std::vector<Vec3> pos;
  std::vector<Vec3> centre;
  std::vector<double> radius;
  Posed(const TriMesh& m, const Transform& pose) : mesh(&m), pos(test::posed_positions(m, pose)) {
    for (const Tri& t : m.triangles) {
      const Vec3 c = (pos[t[0]] + pos[t[1]] + pos[t[2]]) / 3.0;
      centre.push_back(c);
      radius.push_back(std::max({norm(pos[t[0]] - c), norm(pos[t[1]] - c), norm(pos[t[2]] - c)}));
    }
  }
};

/// The oracle's signed distance from p to a posed closed mesh: the closest point of every triangle
/// (scarred_reference.h; a triangle whose sphere lies farther than the best found is skipped, a
/// valid bound), the sign by ray parity in three directions (majority: a ray through an edge
/// miscounts at most one of them).
double ref_sd(const Vec3& p, const Posed& m) {
  double best2 = std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t < m.mesh->triangles.size(); ++t) {
    const double lb = norm(p - m.centre[t]) - m.radius[t];
    if (lb > 0 && lb * lb > best2) continue;
    const Tri& tr = m.mesh->triangles[t];
    const Vec3 c = test::ref_closest_on_triangle(p, m.pos[tr[0]], m.pos[tr[1]], m.pos[tr[2]]);
    best2 = std::min(best2, dot(c - p, c - p));
  }
  const double d = std::sqrt(best2);
  const int in = test::ref_inside(p, m.pos, *m.mesh) + test::ref_inside(p, m.pos, *m.mesh, {-0.31, 0.72, 0.62}) +
                 test::ref_inside(p, m.pos, *m.mesh, {0.83, -0.22, 0.51});
  return in >= 2 ? -d : d;
}

/// s(A, B) densely: the minimum of ref_sd over a k-step barycentric grid of every triangle of A not
/// ruled out by a bound of sd_B over it (sd_B is 1-Lipschitz: a value at the centroid less the
/// largest corner distance), first max(rho - R, -z, z - h) at the centroid in the frame of `bc`, a
/// cylinder holding B's solid (sd_B is at least its signed distance, which is at least that), then
/// ref_sd at the centroid; `spacing`: the largest sampled triangle's longest edge / k (every point
/// of a sampled triangle lies that close to a sample), so s(A, B) >= value - spacing.
struct Dense {
  double value = std::numeric_limits<double>::infinity();
  double spacing = 0;
};
Dense dense_min(const Posed& a, const Posed& b, const Cylinder& bc, int k) {
  struct Cand {
    double bound;
    std::size_t t;
  };
  std::vector<Cand> cand;
  for (std::size_t t = 0; t < a.mesh->triangles.size(); ++t) {
    const Vec3 c = a.centre[t];
    const double z = dot(c - bc.base, bc.axis), rho = norm(cross(c - bc.base, bc.axis));
    cand.push_back({std::max({rho - bc.radius, -z, z - bc.height}) - a.radius[t], t});
  }
  std::sort(cand.begin(), cand.end(), [](const Cand& x, const Cand& y) { return x.bound < y.bound; });
  Dense out;
  for (const Cand& c : cand) {
    if (c.bound > out.value) break;
    if (ref_sd(a.centre[c.t], b) - a.radius[c.t] > out.value) continue;
    const Tri& tr = a.mesh->triangles[c.t];
    const Vec3 p = a.pos[tr[0]], q = a.pos[tr[1]], r = a.pos[tr[2]];
    out.spacing = std::max(out.spacing, std::max({norm(p - q), norm(q - r), norm(r - p)}) / k);
    for (int i = 0; i <= k; ++i)
      for (int j = 0; i + j <= k; ++j) {
        const double u = static_cast<double>(i) / k, v = static_cast<double>(j) / k;
        out.value = std::min(out.value, ref_sd(p * (1 - u - v) + q * u + r * v, b));
      }
  }
  return out;
}

struct Stats {
  std::map<std::string, int> rows;
  double worst_exact = 0, worst_witness = 0, worst_upper_gap = 0, worst_lower_gap = 0;
};

/// One pressed pair: part `a` at `pa`, part `b` at `pb`.
void check_pair(const Assembly& as, const AssemblyPair& pair, const std::vector<Transform>& poses, Stats& st) {
  const ScenePart x = scene_part(as, pair.a, poses[pair.a]), y = scene_part(as, pair.b, poses[pair.b]);
  const double clearance = as.spec.clearance;
  const PartPairResult r = decide_part_pair(x, y, clearance), q = decide_part_pair(y, x, clearance);
  // s(A, B) = s(B, A): the same computation in both orders
  EXPECT_EQ(r.distance, q.distance);
  EXPECT_EQ(r.distance_lower, q.distance_lower);
  EXPECT_EQ(r.verdict, q.verdict);
  EXPECT_EQ(r.two_sided_exact, q.two_sided_exact);
  EXPECT_LE(r.distance_lower, r.distance);
  const double tol = touch_tolerance(x.cylinder, y.cylinder);
  const double scale = norm(poses[pair.a].t) + norm(poses[pair.b].t) + 100;
  const Posed pa(*as.parts[pair.a].mesh, poses[pair.a]), pb(*as.parts[pair.b].mesh, poses[pair.b]);
  // roles: r.point_a on the part decide_part_pair took as A (x unless swapped)
  const Posed& A = r.swapped ? pb : pa;
  const Posed& B = r.swapped ? pa : pb;
  const bool engine = meshes_clash(*pa.mesh, poses[pair.a], *pb.mesh, poses[pair.b]);
  const char* verdict = verdict_name(r.verdict);
  if (r.two_sided_exact) {
    st.rows[std::string("exact ") + verdict] += 1;
    // (1e-9 relative; a few hundredths of a micrometre apart, the posed coordinates' rounding, 1e-15
    // of the scale, is the larger)
    const double ref = test::ref_mesh_distance(*pa.mesh, pa.pos, *pb.mesh, pb.pos);
    const double diff = std::fabs(ref - r.distance);
    st.worst_exact = std::max(st.worst_exact, diff / std::max(std::fabs(ref), 1e-3 * scale));
    EXPECT_LE(diff, 1e-9 * std::fabs(ref) + 1e-15 * scale) << "row " << r.distance << " brute force " << ref;
    if (r.distance > tol) EXPECT_FALSE(engine);
    return;
  }
  if (r.distance_lower > tol) {  // (L clear and the meshes' distance not found: not seen)
    st.rows[std::string("bound ") + verdict] += 1;
    EXPECT_EQ(r.verdict, Verdict::clear);
    return;
  }
  st.rows[std::string("bracket ") + verdict] += 1;
  EXPECT_EQ(r.solver, PartPairSolver::bound);
  // U* is sd of a point of one surface to the other's mesh
  const Vec3 on = r.reverse ? r.point_b : r.point_a;
  const Posed& own = r.reverse ? B : A;
  const Posed& other = r.reverse ? A : B;
  EXPECT_LE(test::ref_point_mesh_distance(on, own.pos, *own.mesh), 1e-9 * scale) << "the witness lies on its surface";
  const double sd = ref_sd(on, other);
  const double diff = std::fabs(sd - r.distance);
  st.worst_witness = std::max(st.worst_witness, diff / scale);
  EXPECT_LE(diff, 1e-9 * scale) << "U* " << r.distance << " oracle sd at its witness " << sd;
  // the dense oracle: S <= min of the two dense values; S >= that - spacing
  // cylinders holding each solid: the intact one's largest radius grown by the raise
  const auto holder = [](const ScenePart& p) {
    Cylinder c = p.cylinder;
    c.radius = c.max_radius() + std::max(p.mesh->raise, 0.0), c.top_radius = -1;
    return c;
  };
  const Cylinder hb = holder(r.swapped ? x : y), ha = holder(r.swapped ? y : x);
  const Dense ab = dense_min(A, B, hb, 6), ba = dense_min(B, A, ha, 6);
  const double dense = std::min(ab.value, ba.value), spacing = std::max(ab.spacing, ba.spacing);
  EXPECT_LE(r.distance_lower, dense + 1e-9 * scale) << "L above the dense value";
  EXPECT_GE(r.distance, dense - spacing - 1e-9 * scale) << "U* below the dense value less its spacing";
  st.worst_upper_gap = std::max(st.worst_upper_gap, r.distance - dense);
  st.worst_lower_gap = std::max(st.worst_lower_gap, dense - r.distance_lower);
  if (r.verdict == Verdict::clash) EXPECT_TRUE(engine);
  if (r.verdict == Verdict::clash) EXPECT_LT(sd, -tol);
  if (r.verdict == Verdict::undecided) EXPECT_FALSE(r.reason.empty());
}

/// Every neighbouring pair of an assembly with every roller scarred, the second roller moved toward
/// the first: `place(poses, pair, step)` sets the step's pose.
template <class Place>
void run(const std::string& bearing, int steps, const Place& place, Stats& st) {
  for (const bool raised : {false, true}) {
    const Assembly as = test::scarred_assembly(bearing, raised);
    test::SplitMix rng{raised ? 17u : 13u};
    const std::vector<Transform> base = test::random_poses(as, rng, 0.5, -0.02, 0.02, 0.3, 0.0);
    int pairs = 0;
    for (const AssemblyPair& pair : as.pairs) {
      if (pair.kind != AssemblyPairKind::roller_roller) continue;
      if (++pairs > 2) break;  // (two neighbours of each: the oracle is slow)
      for (int step = 0; step < steps; ++step) {
        std::vector<Transform> poses = base;
        place(as, poses, pair, step);
        SCOPED_TRACE(std::string(raised ? "raised " : "inward ") + as.parts[pair.a].id + " / " + as.parts[pair.b].id +
                     " step " + std::to_string(step));
        check_pair(as, pair, poses, st);
      }
    }
  }
}

void report(const char* what, const Stats& st) {
  for (const auto& [k, n] : st.rows) std::printf("[ %s ] %s: %d rows\n", what, k.c_str(), n);
  std::printf("[ %s ] exact rows vs brute force %.3g of max(distance, scale / 1000); U* vs oracle sd at its witness %.3g of the scale;\n"
              "  U* - dense value up to %.4g, dense value - L up to %.4g\n",
              what, st.worst_exact, st.worst_witness, st.worst_upper_gap, st.worst_lower_gap);
}

// intact gaps between the two cylinders (mm): deep, shallow (about the scar depth 0.08 and the
// facets' sagitta, 10 (1 - cos 7.5 deg) = 0.086), touching, just apart
constexpr double kGaps[] = {-1.0, -0.2, -0.09, -0.06, -0.03, -0.01, 0.0, 0.02};

TEST(BearingScarredPairsBracket, CylindricalNeighboursPressedTogether) {
  Stats st;
  // B keeps its (random) orientation; its centre moves along the line of centres (across A's axis)
  // to 2 R + gap from A's
  run(test::kCylindricalBearing, static_cast<int>(std::size(kGaps)),
      [](const Assembly& as, std::vector<Transform>& poses, const AssemblyPair& pair, int step) {
        const double h = as.spec.bearings[0].rollers.length, R = as.spec.bearings[0].rollers.radius;
        const Vec3 ma = poses[pair.a].apply({0, 0, 0.5 * h}), mb = poses[pair.b].apply({0, 0, 0.5 * h});
        const Vec3 ua = poses[pair.a].rotate({0, 0, 1});
        Vec3 d = mb - ma;
        d = d - ua * dot(d, ua);
        d = d / norm(d);
        poses[pair.b].t = poses[pair.b].t + (ma + d * (2 * R + kGaps[step]) - mb);
      },
      st);
  report("cylindrical pressed", st);
  EXPECT_GE(st.rows["bracket clash"], 10);  // (before: every one of these was undecided)
  EXPECT_GT(st.rows["exact clear"] + st.rows["exact clearance"] + st.rows["exact contact"], 0);
}

TEST(BearingScarredPairsBracket, TaperedNeighboursPressedTogether) {
  Stats st;
  // B a parallel copy of A shifted toward B's place (the frustums' radii 8 to 9.5: the large ends
  // touch at a shift of 19), as BearingAssemblyTaperedScars.TwoScarredNeighboursPressedTogether
  constexpr double shifts[] = {17.0, 18.5, 18.9, 18.97, 19.0, 19.03, 19.1};
  run(test::kTaperedBearing, static_cast<int>(std::size(shifts)),
      [&](const Assembly&, std::vector<Transform>& poses, const AssemblyPair& pair, int step) {
        Transform moved = poses[pair.a];
        const Vec3 d = poses[pair.b].t - poses[pair.a].t;
        moved.t = poses[pair.a].t + d * (shifts[step] / norm(d));
        poses[pair.b] = moved;
      },
      st);
  report("tapered pressed", st);
  EXPECT_GE(st.rows["bracket clash"], 8);
}

TEST(BearingScarredPairsBracket, AssemblyRowsTakeTheBracket) {
  // the assemblies' rows of two scarred neighbours: cylindrical from decide_part_pair (solver bound,
  // distance U*), tapered the same bracket where it decides, else the mesh engine's verdict
  for (const char* bearing : {test::kCylindricalBearing, test::kTaperedBearing}) {
    const Assembly as = test::scarred_assembly(bearing, false);
    const bool tapered = as.spec.bearings[0].type == BearingType::tapered;
    int decided = 0, engine = 0;
    for (const AssemblyPair& pair : as.pairs) {
      if (pair.kind != AssemblyPairKind::roller_roller) continue;
      std::vector<Transform> poses;
      for (const AssemblyPart& p : as.parts) poses.push_back(p.rest);
      const Vec3 d = poses[pair.b].t - poses[pair.a].t;
      Transform moved = poses[pair.a];
      moved.t = poses[pair.a].t + d * ((tapered ? 17.0 : 19.0) / norm(d));  // 1 mm of overlap (2 at the small ends)
      poses[pair.b] = moved;
      const AssemblyPairResult row = solve_pair(as, pair, poses, as.spec.clearance);
      const PartPairResult pp = decide_part_pair(scene_part(as, pair.a, poses[pair.a]),
                                                 scene_part(as, pair.b, poses[pair.b]), as.spec.clearance);
      EXPECT_FALSE(row.exact);
      EXPECT_FALSE(row.two_sided);
      if (row.solver == AssemblySolver::bound) {
        ++decided;
        EXPECT_EQ(row.verdict, pp.verdict);
        EXPECT_EQ(row.verdict, Verdict::clash);
        EXPECT_NEAR(row.distance, pp.distance, 1e-12 * (norm(poses[pair.a].t) + 100));  // (roles may differ)
      } else {
        ++engine;
        EXPECT_TRUE(tapered);
        EXPECT_EQ(row.solver, AssemblySolver::mesh);
        EXPECT_EQ(pp.verdict, Verdict::undecided);
      }
    }
    std::printf("[ assembly rows ] %s: %d decided by the bracket, %d by the mesh engine\n",
                tapered ? "tapered" : "cylindrical", decided, engine);
    EXPECT_GT(decided, 0);
  }
}

}  // namespace
}  // namespace interfere::bearing
