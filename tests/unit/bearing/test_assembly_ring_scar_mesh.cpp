// Raceway scars drawn (issue #27): a ring whose raceway carries a scar gets a mesh through the
// scarred raceway surface (scarred_ring_mesh: the profile revolved with the scar grid's segments,
// the raceway edge through the grid's rows), used by the viewer document, the scene bodies and the
// .pvd series. Checked: closed and outward (every directed edge once, its reverse once; positive
// volume), the raceway vertices are the scar surface's vertices (ring frame), some lie off the
// intact raceway (the scar shows), the volume stays within the scar's depth band of the intact
// ring's; rings without a scar keep the intact mesh.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <utility>

#include "assembly_fixture.h"
#include "interfere/bearing/assembly.h"

using namespace interfere;
using namespace interfere::bearing;
using namespace interfere::bearing::test;

namespace {

bool closed_outward(const TriMesh& m, double& volume) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  volume = 0;
  for (const Tri& t : m.triangles) {
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
    volume += dot(m.positions[t[0]], cross(m.positions[t[1]], m.positions[t[2]])) / 6;
  }
  for (const auto& [e, n] : edges) {
    if (n != 1) return false;
    const auto it = edges.find({e.second, e.first});
    if (it == edges.end() || it->second != 1) return false;
  }
  return volume > 0;
}

std::string with_scars(const char* bearing, const std::string& scars) {
  std::string b = bearing;
  b.insert(b.rfind('}'), ", \"scars\": [" + scars + "]");
  return b;
}

}  // namespace

TEST(BearingAssemblyRingScarMesh, ScarredRacewaysAreDrawn) {
  const std::string bearings =
      with_scars(kCylindricalBearing,
                 R"({"part": "inner", "angle_center_deg": 30, "angle_width_deg": 80, "depth": 0.05, "raised": true, "seed": 3,
                     "radial_segments": 256, "height_segments": 31},
                    {"part": "outer", "angle_center_deg": 200, "angle_width_deg": 60, "depth": 0.04, "seed": 4})") +
      "," + with_scars(kTaperedBearing, R"({"part": "cone", "depth": 0.03, "seed": 5}, {"part": "cup", "depth": 0.03, "raised": true, "seed": 6})");
  const Expected<AssemblySpec> spec = parse_assembly(assembly_json("", bearings), "a.json");
  ASSERT_TRUE(spec) << spec.error().message();
  const Expected<Assembly> as = build_assembly(*spec);
  ASSERT_TRUE(as) << as.error().message();
  int drawn = 0;
  for (const AssemblyPart& p : as->parts) {
    if (p.kind != PartKind::inner && p.kind != PartKind::outer) continue;
    SCOPED_TRACE(p.id);
    ASSERT_TRUE(p.raceway_scar);  // every ring of this description carries one
    const BearingSpec& b = as->spec.bearings[static_cast<std::size_t>(p.bearing)];
    const BearingGeometry& g = as->geometry[static_cast<std::size_t>(p.bearing)];
    const RacewayScar& scar = *p.raceway_scar;
    double v = 0, v0 = 0;
    EXPECT_TRUE(closed_outward(*p.mesh, v));
    // the intact ring with the same segments: the scar moves the raceway by at most its depth
    const TriMesh intact = p.kind == PartKind::inner ? inner_ring_mesh(b, g, scar.surface.n())
                                                     : outer_ring_mesh(b, g, scar.surface.n());
    ASSERT_TRUE(closed_outward(intact, v0));
    const double area = 2 * std::numbers::pi * std::max(scar.geometry.radius, scar.geometry.top_radius) * scar.geometry.width;
    EXPECT_NE(v, v0);
    EXPECT_LE(std::fabs(v - v0), 1.01 * scar.window.depth * area);
    // every scar surface vertex within the ring's raceway edge is a vertex of the mesh
    std::map<std::array<double, 3>, int> at;
    for (const Vec3& q : p.mesh->positions) ++at[{q.x, q.y, q.z}];
    int shown = 0, off = 0;
    for (int j = 0; j <= scar.surface.m(); ++j)
      for (int i = 0; i < scar.surface.n(); ++i) {
        const std::uint32_t vi = scar.surface.side_vertex(i, j);
        const Vec3 q = scar.to_ring.apply(scar.surface.mesh.positions[vi]);
        if (at.count({q.x, q.y, q.z})) {
          ++shown;
          off += scar.surface.scar[vi] && scar.surface.displacement[vi] != 0;
        }
      }
    EXPECT_GT(shown, scar.surface.n() * (scar.surface.m() / 2));  // (cylindrical inner: the rows between the ribs)
    EXPECT_GT(off, 0);
    ++drawn;
  }
  EXPECT_EQ(drawn, 4);
  // no scar: the intact ring mesh of ring_segments
  const Expected<Assembly> plain = build_assembly(*parse_assembly(assembly_json("", both_bearings()), "a.json"));
  ASSERT_TRUE(plain);
  const BearingSpec& b0 = plain->spec.bearings[0];
  EXPECT_EQ(plain->parts[0].mesh->positions.size(),
            inner_ring_mesh(b0, plain->geometry[0], plain->spec.ring_segments).positions.size());
}

TEST(RacewayScarIntactRoller, ApartRowsAreTwoSidedOverlappingOnesSaySo) {
  // an intact roller in range of a raceway scar: apart surfaces (T_r > 0) are the Euclidean distance,
  // symmetric, so the row is S (two_sided 1); overlapping rows are T_r alone (two_sided 0): the
  // roller's depth in the scarred ring is not computed (docs/bearing.md, "Scars on raceways")
  const std::string bearings =
      with_scars(kCylindricalBearing,
                 R"({"part": "inner", "angle_center_deg": 270, "angle_width_deg": 120, "depth": 0.03, "seed": 3,
                     "radial_segments": 256, "height_segments": 31},
                    {"part": "outer", "angle_center_deg": 90, "angle_width_deg": 120, "depth": 0.03, "raised": true, "seed": 4,
                     "radial_segments": 256, "height_segments": 31})") +
      "," + with_scars(kTaperedBearing, R"({"part": "cone", "angle_center_deg": 270, "angle_width_deg": 120, "depth": 0.03, "seed": 5,
                                          "radial_segments": 256, "height_segments": 31})");
  const Expected<AssemblySpec> spec = parse_assembly(
      assembly_json(R"("frames": 3, "seed": 3, "motion": {"inner_deg_per_frame": 7, "max_tilt_deg": 0.1,
                      "load": {"direction_deg": 270, "displacement": 0.08}},)", bearings), "a.json");
  ASSERT_TRUE(spec) << spec.error().message();
  const Expected<Assembly> as = build_assembly(*spec);
  ASSERT_TRUE(as) << as.error().message();
  const AssemblyResult res = run_assembly(*as, generate_motion(*as, 3, as->spec.seed));
  int apart = 0, overlapping = 0;
  for (const AssemblyRow& row : res.rows) {
    const AssemblyPair& pair = as->pairs[row.pair];
    const AssemblyPairResult& r = row.result;
    if (!as->parts[pair.b].raceway_scar || r.solver != AssemblySolver::scarred || as->parts[pair.a].scarred) continue;
    EXPECT_EQ(r.two_sided, r.distance > 0) << assembly_pair_kind_name(pair.kind);
    (r.distance > 0 ? apart : overlapping) += 1;
  }
  EXPECT_GT(apart, 0);
  EXPECT_GT(overlapping, 0);
}
