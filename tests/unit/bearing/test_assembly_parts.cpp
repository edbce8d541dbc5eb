// Bearing assemblies (issue #27): every part's mesh is closed and outward, checked independently
// of the mesher: the signed volume (divergence theorem) is positive and close to the solid's
// analytic volume, and every undirected edge is used by exactly two triangles in opposite
// directions. Also the rest poses: rollers on the pitch circle (tapered: axes through the apex).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

#include "unit/bearing/assembly_fixture.h"
#include "interfere/bearing/assembly.h"

namespace interfere::bearing {
namespace {

constexpr double kPi = std::numbers::pi;

double volume(const TriMesh& m) {
  double v = 0;
  for (const Tri& t : m.triangles) {
    const Vec3 a = m.positions[t[0]], b = m.positions[t[1]], c = m.positions[t[2]];
    v += a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) + a.z * (b.x * c.y - b.y * c.x);
  }
  return v / 6;
}

/// Every directed edge once, its reverse once: closed and consistently oriented (2-manifold edges).
::testing::AssertionResult closed_oriented(const TriMesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const Tri& t : m.triangles)
    for (int i = 0; i < 3; ++i) {
      if (t[i] == t[(i + 1) % 3]) return ::testing::AssertionFailure() << "degenerate triangle";
      ++directed[{t[i], t[(i + 1) % 3]}];
    }
  for (const auto& [e, n] : directed) {
    if (n != 1) return ::testing::AssertionFailure() << "edge " << e.first << "-" << e.second << " used " << n << " times";
    const auto r = directed.find({e.second, e.first});
    if (r == directed.end() || r->second != 1)
      return ::testing::AssertionFailure() << "edge " << e.first << "-" << e.second << " has no opposite";
  }
  return ::testing::AssertionSuccess();
}

Assembly build(const std::string& extra = "") {
  Expected<AssemblySpec> s = parse_assembly(test::assembly_json(extra, test::both_bearings()), "t.json");
  EXPECT_TRUE(s) << s.error().message();
  Expected<Assembly> a = build_assembly(*s);
  EXPECT_TRUE(a) << a.error().message();
  return *a;
}

TEST(BearingAssemblyParts, ClosedAndOutward) {
  const Assembly as = build(R"("scar": {"fraction": 0.5},)");
  ASSERT_EQ(as.parts.size(), 3u + 10u + 3u + 12u);
  int scarred = 0;
  for (const AssemblyPart& p : as.parts) {
    SCOPED_TRACE(p.id);
    EXPECT_TRUE(closed_oriented(*p.mesh));
    EXPECT_GT(volume(*p.mesh), 0);
    scarred += p.scarred;
  }
  EXPECT_EQ(scarred, 5 + 6);  // half of each bearing's rollers: 10 cylindrical, 12 tapered (issue #27)
}

TEST(BearingAssemblyParts, VolumesMatchTheSolids) {
  const Assembly as = build();
  const int n = as.spec.ring_segments;
  // a regular n-gon of radius r has area n r^2 sin(2 pi / n) / 2: the meshes are inscribed
  const double k = n * std::sin(2 * kPi / n) / 2;
  const BearingSpec& c = as.spec.bearings[0];
  const double w = c.inner_width, ri = c.inner_raceway, rb = c.inner_bore, rr = ri + c.rib_height;
  const double inner = k * ((ri * ri - rb * rb) * w + 2 * (rr * rr - ri * ri) * c.rib_width);
  EXPECT_NEAR(volume(*as.parts[0].mesh), inner, 1e-9 * inner);
  const double outer = k * (c.outer_radius * c.outer_radius - c.outer_raceway * c.outer_raceway) * c.outer_width;
  EXPECT_NEAR(volume(*as.parts[1].mesh), outer, 1e-9 * outer);
  // cage webs: convex hexahedra, each volume = integral of its cross-section; check against the
  // tetrahedra of its corners from the centre (independent of the face order)
  const BearingGeometry& g = as.geometry[0];
  double webs = 0;
  for (const CageWeb& web : g.webs) {
    Vec3 centre;
    for (const Vec3& p : web.corners) centre += p;
    centre = centre / 8.0;
    // each face (bit fixed) split into two triangles, tetrahedra to the centre, absolute volumes
    for (int bit = 0; bit < 3; ++bit)
      for (int v = 0; v < 2; ++v) {
        const int o1 = (bit + 1) % 3, o2 = (bit + 2) % 3;
        const auto c4 = [&](int x, int y) { return web.corners[(v << bit) | (x << o1) | (y << o2)]; };
        const auto tet = [&](const Vec3& a, const Vec3& b, const Vec3& d) {
          return std::fabs(dot(a - centre, cross(b - centre, d - centre))) / 6;
        };
        webs += tet(c4(0, 0), c4(1, 0), c4(1, 1)) + tet(c4(0, 0), c4(1, 1), c4(0, 1));
      }
  }
  EXPECT_NEAR(volume(*as.parts[2].mesh), webs, 1e-9 * webs);
  // the webs' radial thickness and axial width as given
  const CageWeb& w0 = g.webs[0];
  const Vec3 m{std::cos(kPi / 10), std::sin(kPi / 10), 0};
  EXPECT_NEAR(dot(w0.corners[2] - w0.corners[0], m), c.cage.web_thickness, 1e-12);
  EXPECT_NEAR(w0.corners[4].z - w0.corners[0].z, c.rollers.length, 1e-12);
}

TEST(BearingAssemblyParts, RestPoses) {
  const Assembly as = build();
  for (const AssemblyPart& p : as.parts) {
    if (p.kind != PartKind::roller) continue;
    const BearingSpec& b = as.spec.bearings[p.bearing];
    const BearingGeometry& g = as.geometry[p.bearing];
    SCOPED_TRACE(p.id);
    const Vec3 base = p.rest.apply({0, 0, 0}), top = p.rest.apply({0, 0, b.rollers.length});
    const Vec3 mid = (base + top) * 0.5;
    // distance of the mid point from the bearing axis: the pitch radius
    const Vec3 d = mid - b.position;
    const double rho = norm(d - b.axis * dot(d, b.axis));
    EXPECT_NEAR(rho, g.pitch_radius, 1e-9);
    EXPECT_NEAR(dot(d, b.axis), 0, 1e-9);  // on the mid-plane
    if (b.type == BearingType::tapered) {
      // the roller axis meets the bearing axis at the apex, and its cone's apex is there too
      const Vec3 apex = b.position + b.axis * g.apex_z;
      const Vec3 u = (top - base) / norm(top - base);
      EXPECT_NEAR(norm(cross(apex - base, u)), 0, 1e-9);
      const double d_small = norm(base - apex);
      EXPECT_NEAR(b.rollers.radius / d_small, (b.rollers.top_radius - b.rollers.radius) / b.rollers.length, 1e-12);
      // the contact angle: the outer generatrix makes alpha with the bearing axis
      const double lean = std::acos(std::fabs(dot(u, b.axis)));
      const double beta = std::atan((b.rollers.top_radius - b.rollers.radius) / b.rollers.length);
      EXPECT_NEAR((lean + beta) * 180 / kPi, b.contact_angle_deg, 1e-9);
    } else {
      EXPECT_NEAR(std::fabs(dot((top - base) / b.rollers.length, b.axis)), 1, 1e-12);
    }
  }
}

TEST(BearingAssemblyParts, PairList) {
  const Assembly as = build();
  std::map<AssemblyPairKind, int> kinds;
  for (const AssemblyPair& p : as.pairs) ++kinds[p.kind];
  // cylindrical (Z = 10): inner, outer, 2 ribs, 2 webs, 1 neighbour per roller; tapered (Z = 12):
  // cone, cup, 2 webs, 1 neighbour
  EXPECT_EQ(kinds[AssemblyPairKind::roller_inner], 10);
  EXPECT_EQ(kinds[AssemblyPairKind::roller_outer], 10);
  EXPECT_EQ(kinds[AssemblyPairKind::roller_rib], 20);
  EXPECT_EQ(kinds[AssemblyPairKind::roller_cage], 20 + 24);
  EXPECT_EQ(kinds[AssemblyPairKind::roller_roller], 10 + 12);
  EXPECT_EQ(kinds[AssemblyPairKind::roller_cone], 12);
  EXPECT_EQ(kinds[AssemblyPairKind::roller_cup], 12);
  EXPECT_EQ(as.find("tap/roller11"), static_cast<std::int64_t>(as.parts.size() - 1));
  EXPECT_EQ(as.find("cyl/cage"), 2);
  EXPECT_EQ(as.find("nope"), -1);
}

}  // namespace
}  // namespace interfere::bearing

#include "interfere/bearing/assembly_scene.h"
#include "interfere/query/clash.h"
#include "interfere/query/model.h"

namespace interfere::bearing {
namespace {

TEST(BearingAssemblyParts, SceneBodiesAndTheMeshEngine) {
  const Assembly as = build();
  const scene::Scene sc = assembly_scene(as);
  ASSERT_EQ(sc.bodies.size(), as.parts.size());
  EXPECT_NO_THROW(sc.validate());
  EXPECT_EQ(sc.find("cyl/roller4"), as.find("cyl/roller4"));
  EXPECT_EQ(sc.bodies[0].tags, (std::vector<std::string>{"cyl", "inner"}));
  // at rest (zero clearance nowhere: the rollers sit 0.05 from both raceways, the webs 0.25 from the
  // rollers) the mesh engine finds no crossing between any roller and its rings or cage
  for (std::size_t i = 0; i < as.parts.size(); ++i) {
    if (as.parts[i].kind != PartKind::roller || as.parts[i].bearing != 0) continue;
    const Model roller = make_model(transformed(*sc.bodies[i].mesh, sc.bodies[i].pose));
    for (std::size_t j = 0; j < 3; ++j) {
      const Model ring = make_model(transformed(*sc.bodies[j].mesh, sc.bodies[j].pose));
      const ClashResult r = clash(roller, ring);
      EXPECT_EQ(r.verdict, Verdict::clear) << sc.bodies[i].id << " " << sc.bodies[j].id;
    }
  }
}

}  // namespace
}  // namespace interfere::bearing
