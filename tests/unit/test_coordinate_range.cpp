// The supported coordinate range (issue #23, item 7; interfere/core/coordinate_range.h): both sides
// of the boundary. Inside it the predicates are exact, checked against an independent exact
// evaluation in __int128 on dyadic points at the top (|x| up to 2^100) and the bottom (nonzero |x|
// down to 2^-250) of the range; outside it every reader rejects the input with the file, the point
// and the coordinate (today's code read 1e110 and answered wrongly).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>

#include "interfere/core/coordinate_range.h"
#include "interfere/core/predicates.h"
#include "interfere/fem/io.h"
#include "interfere/mesh/io.h"

namespace interfere {
namespace {

namespace fs = std::filesystem;
using i128 = __int128;

TEST(CoordinateRange, BoundsAreInclusiveAndSymmetric) {
  const double top = std::ldexp(1.0, 100), bottom = std::ldexp(1.0, -250);
  EXPECT_TRUE(coordinate_in_range(0.0));
  EXPECT_TRUE(coordinate_in_range(-0.0));
  EXPECT_TRUE(coordinate_in_range(top));
  EXPECT_TRUE(coordinate_in_range(-top));
  EXPECT_TRUE(coordinate_in_range(bottom));
  EXPECT_TRUE(coordinate_in_range(-bottom));
  EXPECT_FALSE(coordinate_in_range(std::nextafter(top, 2 * top)));
  EXPECT_FALSE(coordinate_in_range(-std::nextafter(top, 2 * top)));
  EXPECT_FALSE(coordinate_in_range(std::nextafter(bottom, 0.0)));
  EXPECT_FALSE(coordinate_in_range(1e110));
  EXPECT_FALSE(coordinate_in_range(1e-260));
  EXPECT_TRUE(coordinate_in_range(-1.4997597826618576e-32));  // gmsh's noise for 0
  EXPECT_TRUE(coordinate_in_range(std::numeric_limits<float>::denorm_min()));
  EXPECT_FALSE(coordinate_in_range(std::numeric_limits<double>::denorm_min()));
  EXPECT_FALSE(coordinate_in_range(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_FALSE(coordinate_in_range(-std::numeric_limits<double>::infinity()));
  EXPECT_TRUE(coordinates_in_range(Vec3{1e30, -1e-30, 0}));
  EXPECT_FALSE(coordinates_in_range(Vec3{1, 1e31, 0}));
  const std::vector<Vec3> pts{{0, 0, 0}, {1, 2, 3}, {1, 1e200, 3}, {1e300, 0, 0}};
  EXPECT_EQ(first_out_of_range(pts), 2u);
  const std::string why = coordinate_range_reason(pts[2]);
  EXPECT_NE(why.find("y = 1e+200"), std::string::npos) << why;
  EXPECT_NE(why.find("2^100"), std::string::npos) << why;
  EXPECT_TRUE(coordinate_range_reason(pts[1]).empty());
  const Status st = check_coordinate_range(pts, "f.obj", "vertex", 1);
  ASSERT_FALSE(st);
  EXPECT_EQ(st.error().file, "f.obj");
  EXPECT_EQ(st.error().reason.rfind("vertex 3: y = 1e+200", 0), 0u) << st.error().reason;
}

/// Exact det[a-d, b-d, c-d] for integer points with |coordinate| < 2^40 (no overflow in i128).
i128 det3(const std::int64_t a[3], const std::int64_t b[3], const std::int64_t c[3], const std::int64_t d[3]) {
  const i128 adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  const i128 bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  const i128 cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  return adx * (bdy * cdz - bdz * cdy) - ady * (bdx * cdz - bdz * cdx) + adz * (bdx * cdy - bdy * cdx);
}

int sign(i128 v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

/// Near-coplanar quadruples with integer coordinates X, 2^39 <= |X| < 2^40, placed at 2^shift:
/// x = X 2^shift. shift = 60 puts them at the top of the range (|x| < 2^100), shift = -289 at the
/// bottom (|x| >= 2^-250). d is a rounded point of the plane (a,b,c) or, one case in four, exactly
/// on it, so the determinant is tiny beside its terms: the exact expansion decides many of them.
void check_orient3d_at(int shift, std::uint32_t seed) {
  std::mt19937_64 rng(seed);
  const std::int64_t lo = std::int64_t{1} << 39, hi = (std::int64_t{1} << 40) - 1;
  std::uniform_int_distribution<std::int64_t> coord(lo, hi);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int zeros = 0, nonzeros = 0;
  const unsigned long long fallbacks_before = exact_fallback_count();
  for (int n = 0; n < 4000; ++n) {
    std::int64_t p[4][3];
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) p[i][k] = coord(rng);
    const double s = unit(rng), t = unit(rng) * (1 - s);
    for (int k = 0; k < 3; ++k)  // a convex combination: inside [lo, hi] again
      p[3][k] = std::llround(double(p[0][k]) + s * double(p[1][k] - p[0][k]) + t * double(p[2][k] - p[0][k]));
    if (n % 4 == 3) {  // exactly coplanar: d the midpoint of a and b (b - a made even)
      for (int k = 0; k < 3; ++k) {
        if ((p[1][k] - p[0][k]) % 2 != 0) p[1][k] += p[1][k] < hi ? 1 : -1;
        p[3][k] = p[0][k] + (p[1][k] - p[0][k]) / 2;
      }
    }
    const bool negate = n % 2 == 1;  // both signs
    Vec3 v[4];
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) {
        if (negate) p[i][k] = -p[i][k];
        v[i][static_cast<std::size_t>(k)] = std::ldexp(double(p[i][k]), shift);
        ASSERT_TRUE(coordinate_in_range(v[i][static_cast<std::size_t>(k)]));
      }
    const int want = sign(det3(p[0], p[1], p[2], p[3]));
    (want == 0 ? zeros : nonzeros)++;
    ASSERT_EQ(orient3d(v[0], v[1], v[2], v[3]), want) << "shift " << shift << " case " << n;
    ASSERT_EQ(Orient3dPlane(v[0], v[1], v[2]).side(v[3]), want) << "shift " << shift << " case " << n;
    // orient2d on the xy projection of a, b, d.
    const i128 w2 = i128(p[0][0] - p[3][0]) * (p[1][1] - p[3][1]) - i128(p[0][1] - p[3][1]) * (p[1][0] - p[3][0]);
    ASSERT_EQ(orient2d(v[0].x, v[0].y, v[1].x, v[1].y, v[3].x, v[3].y), sign(w2));
  }
  EXPECT_GT(zeros, 0);  // the sample reaches exact zeros and near misses both
  EXPECT_GT(nonzeros, 0);
  EXPECT_GT(exact_fallback_count(), fallbacks_before);  // the expansions were exercised
}

TEST(CoordinateRange, Orient3dExactAtTheTopOfTheRange) { check_orient3d_at(60, 1); }
TEST(CoordinateRange, Orient3dExactAtTheBottomOfTheRange) { check_orient3d_at(-289, 2); }

/// Tiny and huge coordinates in one determinant: the plane through 2^-250 (1,0,0), (0,1,0),
/// (0,0,1) and points on it, just above and just below it (by 2^-250), 2^100 away.
TEST(CoordinateRange, Orient3dMixedMagnitudesAtBothEnds) {
  const double t = std::ldexp(1.0, -250), h = std::ldexp(1.0, 100);
  const Vec3 a{t, 0, 0}, b{0, t, 0}, c{0, 0, t};
  // The plane x + y + z = t: the determinant det[a-d, b-d, c-d] = t^2 (t - (dx+dy+dz)).
  EXPECT_EQ(orient3d(a, b, c, Vec3{0, 0, 0}), 1);          // t^3 > 0
  EXPECT_EQ(orient3d(a, b, c, Vec3{t, 0, 0}), 0);          // on the plane
  EXPECT_EQ(orient3d(a, b, c, Vec3{h, -h, t}), 0);         // on it, far away
  EXPECT_EQ(orient3d(a, b, c, Vec3{h, -h, 2 * t}), -1);    // just above it, far away
  EXPECT_EQ(orient3d(a, b, c, Vec3{h, -h, 0}), 1);         // just below it, far away
}

class Dir {
 public:
  Dir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / (std::string("interfere_range_") + info->name() + "_" +
                                         std::to_string(reinterpret_cast<std::uintptr_t>(this) & 0xffffff));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~Dir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }
  fs::path write(const std::string& name, const std::string& bytes) const {
    std::ofstream(path_ / name, std::ios::binary) << bytes;
    return path_ / name;
  }

 private:
  fs::path path_;
};

std::string obj_with(const std::string& coordinate) {
  return "v 0 0 0\nv 1 0 0\nv 0 " + coordinate + " 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
}

template <class T>
std::string error_of(const Expected<T>& r) {
  return r ? std::string("(no error)") : r.error().message();
}

TEST(CoordinateRange, ObjReaderAcceptsTheBoundsAndRejectsJustOutside) {
  Dir dir;
  // 2^100 and 2^-250 exactly, and their neighbours outside (shortest round-trip texts).
  EXPECT_TRUE(read_mesh(dir.write("top.obj", obj_with("1.2676506002282294e+30"))));
  EXPECT_TRUE(read_mesh(dir.write("bottom.obj", obj_with("5.527147875260445e-76"))));
  EXPECT_TRUE(read_mesh(dir.write("zero.obj", obj_with("-0"))));
  const auto over = read_mesh(dir.write("over.obj", obj_with("1.2676506002282297e+30")));
  ASSERT_FALSE(over);
  EXPECT_EQ(over.error().line, 3);
  EXPECT_NE(error_of(over).find("y = 1.2676506002282297e+30 is outside the supported coordinate range"),
            std::string::npos)
      << error_of(over);
  const auto under = read_mesh(dir.write("under.obj", obj_with("5.527147875260444e-76")));
  ASSERT_FALSE(under);
  EXPECT_EQ(under.error().line, 3);
  const auto huge = read_mesh(dir.write("huge.obj", obj_with("1e110")));
  ASSERT_FALSE(huge);
  EXPECT_NE(error_of(huge).find("huge.obj:3: vertex 3: y = 1e+110 is outside"), std::string::npos) << error_of(huge);
}

TEST(CoordinateRange, EveryMeshFormatRejectsOutOfRangeCoordinates) {
  Dir dir;
  // ASCII STL: the line.
  const auto stla = read_mesh(dir.write(
      "a.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1e200 0 0\nvertex 0 1 0\n"
               "endloop\nendfacet\nendsolid s\n"));
  ASSERT_FALSE(stla);
  EXPECT_EQ(stla.error().line, 5);
  EXPECT_NE(error_of(stla).find("vertex 1 (0-based): x = 1e+200"), std::string::npos) << error_of(stla);
  // Binary STL (floats): 1e35 > 2^100; the byte of the coordinate.
  std::string b(80, ' ');
  const std::uint32_t one = 1;
  b.append(reinterpret_cast<const char*>(&one), 4);
  const float f[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1e35f, 0};
  b.append(reinterpret_cast<const char*>(f), sizeof f);
  b.append(2, '\0');
  const auto stlb = read_mesh(dir.write("b.stl", b));
  ASSERT_FALSE(stlb);
  EXPECT_EQ(stlb.error().byte, 84 + 12 + 2 * 12 + 4);
  EXPECT_NE(error_of(stlb).find("vertex 2 of triangle 0: y = "), std::string::npos) << error_of(stlb);
  // Every float32 is above 2^-250: a subnormal one is read; 2^100 itself too.
  const float g[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 1e-44f, 0x1p100f, 0};
  std::string b2 = b.substr(0, 84);
  b2.append(reinterpret_cast<const char*>(g), sizeof g);
  b2.append(2, '\0');
  EXPECT_TRUE(read_mesh(dir.write("sub.stl", b2))) << error_of(read_mesh(dir.path() / "sub.stl"));
  // ASCII PLY and OFF: the vertex in file order.
  const auto ply = read_mesh(dir.write(
      "p.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
               "property double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
               "0 0 0\n1 0 0\n0 1 -1e-250\n3 0 1 2\n"));
  ASSERT_FALSE(ply);
  EXPECT_NE(error_of(ply).find("vertex 2"), std::string::npos) << error_of(ply);
  EXPECT_NE(error_of(ply).find("z = -1e-250 is outside"), std::string::npos) << error_of(ply);
  const auto off = read_mesh(dir.write("o.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1e101 0\n3 0 1 2\n"));
  ASSERT_FALSE(off);
  EXPECT_EQ(off.error().line, 5);
}

TEST(CoordinateRange, FemReaderRejectsOutOfRangeNodes) {
  Dir dir;
  const std::string vtk =
      "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
      "0 0 0\n1 0 0\n0 1 0\n0 0 X\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n";
  auto with = [&](const std::string& z) { return vtk.substr(0, vtk.find('X')) + z + vtk.substr(vtk.find('X') + 1); };
  EXPECT_TRUE(read_fem(dir.write("ok.vtk", with("1.2676506002282294e+30")))) << "2^100 is inside";
  const auto r = read_fem(dir.write("bad.vtk", with("1e110")));
  ASSERT_FALSE(r);
  EXPECT_NE(error_of(r).find("bad.vtk"), std::string::npos) << error_of(r);
  EXPECT_NE(error_of(r).find("node "), std::string::npos) << error_of(r);
  EXPECT_NE(error_of(r).find("z = 1e+110 is outside"), std::string::npos) << error_of(r);
}

}  // namespace
}  // namespace interfere
