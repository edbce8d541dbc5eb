// Transform parsing and validation (issue #23, item 8): empty, non-finite and singular transforms
// are errors; non-rigid ones are described. Oracles: closed-form singular values (a diagonal
// matrix, a rotated diagonal, a 2x2 shear block), determinants built to be exactly zero, and a
// signed volume summed here by the divergence theorem.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "interfere/core/transform.h"
#include "interfere/mesh/tri_mesh.h"

using namespace interfere;

namespace {
Transform from_rows(const std::array<std::array<double, 3>, 3>& r, Vec3 t = {}) {
  Transform x;
  x.r = r;
  x.t = t;
  return x;
}
bool mentions(const Error& e, const std::string& what) { return e.message().find(what) != std::string::npos; }

// Signed volume of a closed triangle mesh: sum of det[a, b, c] / 6 (divergence theorem).
double signed_volume(const TriMesh& m) {
  double v = 0;
  for (const Tri& f : m.triangles) {
    const Vec3 a = m.positions[f[0]], b = m.positions[f[1]], c = m.positions[f[2]];
    v += a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) + a.z * (b.x * c.y - b.y * c.x);
  }
  return v / 6;
}

TriMesh unit_cube() {  // outward (counter-clockwise seen from outside)
  TriMesh m;
  for (int i = 0; i < 8; ++i) m.positions.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}
}  // namespace

TEST(Transform, EmptyTextIsAnErrorNotTheIdentity) {
  for (const char* text : {"", " ", " , \t\n"}) {
    const auto t = Transform::parse(text);
    ASSERT_FALSE(t) << "'" << text << "' was taken as a transform";
    EXPECT_TRUE(mentions(t.error(), "empty")) << t.error().message();
  }
}

TEST(Transform, WrongCountAndNonFiniteNameTheValue) {
  const auto eleven = Transform::parse("1 0 0 0 0 1 0 0 0 0 1");
  ASSERT_FALSE(eleven);
  EXPECT_TRUE(mentions(eleven.error(), "got 11")) << eleven.error().message();
  for (const char* bad : {"1 0 0 nan 0 1 0 0 0 0 1 0", "1 0 0 inf 0 1 0 0 0 0 1 0", "1 0 0 1e400 0 1 0 0 0 0 1 0"}) {
    const auto t = Transform::parse(bad);
    ASSERT_FALSE(t) << bad;
    EXPECT_TRUE(mentions(t.error(), "value 4")) << t.error().message();
  }
  Transform x;
  x.t.y = std::nan("");
  const Status s = x.validate();
  ASSERT_FALSE(s);
  EXPECT_TRUE(mentions(s.error(), "value 8")) << s.error().message();
}

TEST(Transform, SingularMatricesAreRejectedExactly) {
  // All zero (B collapsed to a point) and rank 1: rejected, the message quoting the value.
  for (const char* text : {"0 0 0 0 0 0 0 0 0 0 0 0", "1 2 3 0 2 4 6 0 -1 -2 -3 0"}) {
    const auto t = Transform::parse(text);
    ASSERT_FALSE(t) << text;
    EXPECT_TRUE(mentions(t.error(), "singular")) << t.error().message();
    EXPECT_TRUE(mentions(t.error(), text)) << "the message should quote the value: " << t.error().message();
  }
  // Rank 2, the third row exactly the first minus the second (Sterbenz: y/2 <= x <= 2y makes x - y
  // exact), so det R = 0 exactly although the rounded cofactor expansion need not be zero.
  const double a[3] = {0.1, 0.7, 0.3}, b[3] = {0.07, 0.4, 0.2};
  for (int i = 0; i < 3; ++i) ASSERT_EQ((a[i] - b[i]) + b[i], a[i]);
  const Transform r2 = from_rows({{{a[0], a[1], a[2]}, {b[0], b[1], b[2]}, {a[0] - b[0], a[1] - b[1], a[2] - b[2]}}});
  EXPECT_EQ(r2.determinant_sign(), 0);
  EXPECT_FALSE(r2.validate());
  // A tiny but non-zero determinant is not singular: diag(1e-200, 1, 1); a swap of axes mirrors.
  EXPECT_EQ(from_rows({{{1e-200, 0, 0}, {0, 1, 0}, {0, 0, 1}}}).determinant_sign(), 1);
  EXPECT_EQ(from_rows({{{0, 1, 0}, {1, 0, 0}, {0, 0, 1}}}).determinant_sign(), -1);
}

TEST(Transform, RigidPosesHaveNoNote) {
  const double c = std::cos(0.3), s = std::sin(0.3);
  const Transform rot = from_rows({{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}}, {10, -2, 3});
  EXPECT_TRUE(rot.is_rigid());
  EXPECT_EQ(rot.non_rigid_note(), "");
  EXPECT_TRUE(Transform::identity().is_rigid());
  const auto parsed = Transform::parse("1 0 0 5, 0 1 0 6, 0 0 1 7");
  ASSERT_TRUE(parsed);
  EXPECT_EQ(parsed->non_rigid_note(), "");
}

TEST(Transform, StretchRangeMatchesClosedForms) {
  auto near = [](double x, double want) { return std::fabs(x - want) <= 1e-12 * std::max(1.0, std::fabs(want)); };
  // diag(2, 3, 0.5): singular values 0.5 and 3.
  auto r = from_rows({{{2, 0, 0}, {0, 3, 0}, {0, 0, 0.5}}}).stretch_range();
  EXPECT_TRUE(near(r[0], 0.5) && near(r[1], 3)) << r[0] << " " << r[1];
  // Rotation about z times diag(4, 1, 1): singular values 1 and 4.
  const double c = std::cos(0.7), s = std::sin(0.7);
  r = from_rows({{{4 * c, -s, 0}, {4 * s, c, 0}, {0, 0, 1}}}).stretch_range();
  EXPECT_TRUE(near(r[0], 1) && near(r[1], 4)) << r[0] << " " << r[1];
  // Shear [[1, k], [0, 1]] in x-y: singular values (sqrt(k^2 + 4) +- k) / 2 (their product is 1).
  const double k = 1.5;
  r = from_rows({{{1, k, 0}, {0, 1, 0}, {0, 0, 1}}}).stretch_range();
  EXPECT_TRUE(near(r[0], (std::sqrt(k * k + 4) - k) / 2)) << r[0];
  EXPECT_TRUE(near(r[1], (std::sqrt(k * k + 4) + k) / 2)) << r[1];
}

TEST(Transform, NonRigidNoteSaysWhatHappens) {
  const Transform scaled = from_rows({{{2, 0, 0}, {0, 2, 0}, {0, 0, 2}}});
  EXPECT_FALSE(scaled.is_rigid());
  const std::string n = scaled.non_rigid_note();
  EXPECT_NE(n.find("between 2 and 2"), std::string::npos) << n;
  EXPECT_NE(n.find("transformed space"), std::string::npos) << n;
  const Transform sheared = from_rows({{{1, 1, 0}, {0, 1, 0}, {0, 0, 1}}});
  EXPECT_NE(sheared.non_rigid_note().find("sheared"), std::string::npos) << sheared.non_rigid_note();
  const Transform mirror = from_rows({{{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}}});
  EXPECT_FALSE(mirror.is_rigid());
  const std::string m = mirror.non_rigid_note();
  EXPECT_NE(m.find("mirrors"), std::string::npos) << m;
  EXPECT_EQ(m.find("scales"), std::string::npos) << m;  // lengths are kept
}

TEST(Transform, MirroredMeshStaysOutward) {
  const TriMesh cube = unit_cube();
  ASSERT_NEAR(signed_volume(cube), 1.0, 1e-15);  // the fixture is outward
  const TriMesh mirrored = transformed(cube, from_rows({{{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}, {5, 0, 0}));
  EXPECT_NEAR(signed_volume(mirrored), 1.0, 1e-15);
  const TriMesh scaled = transformed(cube, from_rows({{{2, 0, 0}, {0, 3, 0}, {0, 0, 1}}}));
  EXPECT_NEAR(signed_volume(scaled), 6.0, 1e-14);  // det R = 6, orientation kept
}
