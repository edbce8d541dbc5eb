// Surface extraction on meshes made by the gmsh CLI (box, cylinder, sphere; tet4, tet10, hex8,
// hex20, wedge6, pyramids with tets and hexes), read by read_fem: closed, outward (signed volume =
// volume of the elements), analytic area within the discretisation error. Skipped when `gmsh` is
// not on PATH. The .geo scripts are written here; gmsh runs in a private temporary directory.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "interfere/fem/io.h"
#include "interfere/fem/surface.h"
#include "interfere/mesh/validate.h"

namespace interfere {
namespace {

namespace fs = std::filesystem;

// A private temporary directory, removed at exit.
struct TempDir {
  fs::path path;
  TempDir() {
    std::string t = (fs::temp_directory_path() / "interfere_fem_surface_XXXXXX").string();
    if (!::mkdtemp(t.data())) std::abort();
    path = t;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

const fs::path& work_dir() {
  static TempDir dir;
  return dir.path;
}

bool have_gmsh() { return std::system("gmsh --version > /dev/null 2>&1") == 0; }

fs::path gmsh(const std::string& name, const std::string& geo, const std::string& args) {
  const fs::path g = work_dir() / (name + ".geo"), out = work_dir() / (name + ".msh");
  std::ofstream(g) << geo;
  const std::string cmd = "gmsh " + g.string() + " " + args + " -o " + out.string() + " > " +
                          (work_dir() / (name + ".log")).string() + " 2>&1";
  if (std::system(cmd.c_str()) != 0 || !fs::exists(out)) return {};
  return out;
}

double tet(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return std::fabs(dot(b - a, cross(c - a, d - a))) / 6.0;
}

// Volume of the elements from their corners (tets; hexes, wedges and pyramids with planar faces).
double corner_volume(const FemMesh& m) {
  double s = 0;
  for (std::size_t e = 0; e < m.num_elements(); ++e) {
    const std::uint32_t* v = m.element_nodes(e);
    auto p = [&](int i) { return m.nodes[v[i]]; };
    auto t = [&](int a, int b, int c, int d) { return tet(p(a), p(b), p(c), p(d)); };
    switch (m.elem_types[e]) {
      case ElemType::tet4: case ElemType::tet10: s += t(0, 1, 2, 3); break;
      case ElemType::pyr5: case ElemType::pyr13: s += t(0, 1, 2, 4) + t(0, 2, 3, 4); break;
      case ElemType::wedge6: case ElemType::wedge15: s += t(0, 1, 2, 3) + t(1, 2, 3, 4) + t(2, 3, 4, 5); break;
      case ElemType::hex8: case ElemType::hex20: case ElemType::hex27:
        s += t(0, 1, 2, 6) + t(0, 2, 3, 6) + t(0, 3, 7, 6) + t(0, 7, 4, 6) + t(0, 4, 5, 6) + t(0, 5, 1, 6);
        break;
      default: break;
    }
  }
  return s;
}

struct Measures {
  double volume = 0, area = 0;
  bool closed = false;
  std::size_t components = 0, parts = 0;
};

Measures measure(const fs::path& file, std::size_t* types_seen = nullptr) {
  Measures r;
  auto m = read_fem(file);
  EXPECT_TRUE(m) << m.error().message();
  if (!m) return r;
  if (types_seen) {
    for (ElemType t : m->elem_types) types_seen[static_cast<int>(t)]++;
  }
  // By connectivity: the pyramid case is two glued volumes (two Gmsh entities), one body.
  auto s = extract_surface(*m, {.split = PartSplit::connectivity});
  EXPECT_TRUE(s) << s.error().message();
  if (!s) return r;
  r.parts = s->parts.size();
  EXPECT_EQ(r.parts, 1u);
  if (s->parts.empty()) return r;
  const TriMesh& t = s->parts[0].mesh;
  const MeshStats st = mesh_stats(t);
  r.closed = st.closed();
  r.components = st.components;
  for (std::size_t i = 0; i < t.num_triangles(); ++i) {
    const auto c = t.corners(i);
    r.volume += dot(c[0], cross(c[1], c[2])) / 6.0;
    r.area += norm(cross(c[1] - c[0], c[2] - c[0])) / 2.0;
  }
  EXPECT_EQ(s->inverted_faces, 0u) << file;
  return r;
}

#define REQUIRE_GMSH() \
  if (!have_gmsh()) GTEST_SKIP() << "gmsh not on PATH"

const char* kBox = "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 2, 3};\nMesh.CharacteristicLengthMax = 0.4;\n";
const char* kCylinder =
    "SetFactory(\"OpenCASCADE\");\nCylinder(1) = {0, 0, 0, 0, 0, 2, 1};\nMesh.CharacteristicLengthMax = 0.2;\n";
const char* kSphere = "SetFactory(\"OpenCASCADE\");\nSphere(1) = {0, 0, 0, 1};\nMesh.CharacteristicLengthMax = 0.2;\n";
// All-hex meshes of curved shapes: Gmsh's subdivision of every tet into 4 hexes (and, with
// SecondOrderIncomplete, hex20).
const std::string kHexSubdivision = "Mesh.SubdivisionAlgorithm = 2;\nMesh.SecondOrderIncomplete = 1;\n";
// Structured hexes (extruded, recombined) of the box [0,1]x[0,2]x[0,3]; without the recombination
// of the extruded surface, wedges.
std::string extruded_box(bool hexes) {
  return std::string("Point(1) = {0, 0, 0, 1};\nExtrude {1, 0, 0} {Point{1}; Layers{3};") + (hexes ? " Recombine;" : "") +
         "}\nExtrude {0, 2, 0} {Line{1}; Layers{4};" + (hexes ? " Recombine;" : "") +
         "}\nExtrude {0, 0, 3} {Surface{5}; Layers{5}; Recombine;}\n";
}

TEST(FemSurfaceGmsh, BoxesOfEveryElementTypeAreClosedWithExactVolumeAndArea) {
  REQUIRE_GMSH();
  struct Case {
    const char* name;
    std::string geo, args;
    ElemType expect;
  };
  const Case cases[] = {
      {"box_tet4", kBox, "-3 -format msh41", ElemType::tet4},
      {"box_tet10", kBox, "-3 -order 2 -format msh22", ElemType::tet10},
      {"box_hex8", extruded_box(true), "-3 -format msh41", ElemType::hex8},
      {"box_hex20", extruded_box(true) + "Mesh.SecondOrderIncomplete = 1;\n", "-3 -order 2 -format msh41", ElemType::hex20},
      {"box_hex27", extruded_box(true), "-3 -order 2 -format msh22", ElemType::hex27},
      {"box_wedge6", extruded_box(false), "-3 -format msh41 -bin", ElemType::wedge6},
      {"box_pyr5",
       "SetFactory(\"OpenCASCADE\");\nBox(1) = {0,0,0, 1,2,1.5};\nBox(2) = {0,0,1.5, 1,2,1.5};\n"
       "BooleanFragments{ Volume{1,2}; Delete; }{}\nTransfinite Curve{:} = 4;\nTransfinite Surface{:};\n"
       "Recombine Surface{:};\nTransfinite Volume{1};\n",
       "-3 -format msh22", ElemType::pyr5},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path f = gmsh(c.name, c.geo, c.args);
    ASSERT_FALSE(f.empty()) << "gmsh failed; see " << (work_dir() / (std::string(c.name) + ".log"));
    std::size_t seen[kNumElemTypes] = {};
    const Measures m = measure(f, seen);
    EXPECT_GT(seen[static_cast<int>(c.expect)], 0u) << "gmsh made no " << elem_info(c.expect).name;
    EXPECT_TRUE(m.closed);
    EXPECT_EQ(m.components, 1u);
    EXPECT_NEAR(m.volume, 6.0, 6.0 * 1e-9);
    EXPECT_NEAR(m.area, 22.0, 22.0 * 1e-9);
    auto mesh = read_fem(f);
    ASSERT_TRUE(mesh);
    const double elements = corner_volume(*mesh);
    EXPECT_NEAR(m.volume, elements, 1e-9 * elements);
  }
}

TEST(FemSurfaceGmsh, CylinderAndSphereMatchTheirAnalyticAreaWithinTheDiscretisationError) {
  REQUIRE_GMSH();
  const double pi = std::numbers::pi;
  struct Case {
    const char* name;
    std::string geo;
    const char* args;
    double volume, area, tol;  // relative tolerance: chordal error (h / R)^2 / 8-ish, h = 0.2 R
  };
  const Case cases[] = {
      {"cyl_tet4", kCylinder, "-3 -format msh41", 2 * pi, 6 * pi, 0.02},
      {"cyl_tet10", kCylinder, "-3 -order 2 -format msh41", 2 * pi, 6 * pi, 0.005},
      {"sph_tet4", kSphere, "-3 -format msh41", 4 * pi / 3, 4 * pi, 0.03},
      {"sph_tet10", kSphere, "-3 -order 2 -format msh22", 4 * pi / 3, 4 * pi, 0.005},
      {"cyl_hex8", kCylinder + kHexSubdivision, "-3 -format msh41", 2 * pi, 6 * pi, 0.02},
      {"sph_hex20", kSphere + kHexSubdivision, "-3 -order 2 -format msh41 -bin", 4 * pi / 3, 4 * pi, 0.005},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path f = gmsh(c.name, c.geo, c.args);
    ASSERT_FALSE(f.empty());
    std::size_t seen[kNumElemTypes] = {};
    const Measures m = measure(f, seen);
    if (std::string(c.name).find("hex8") != std::string::npos) EXPECT_GT(seen[static_cast<int>(ElemType::hex8)], 0u);
    if (std::string(c.name).find("hex20") != std::string::npos) EXPECT_GT(seen[static_cast<int>(ElemType::hex20)], 0u);
    EXPECT_TRUE(m.closed);
    EXPECT_EQ(m.components, 1u);
    EXPECT_NEAR(m.volume, c.volume, c.tol * c.volume);
    EXPECT_NEAR(m.area, c.area, c.tol * c.area);
    if (std::string(c.name).find("tet4") != std::string::npos) {  // linear tets: exactly their volume
      auto mesh = read_fem(f);
      ASSERT_TRUE(mesh);
      const double elements = corner_volume(*mesh);
      EXPECT_NEAR(m.volume, elements, 1e-9 * elements);
    }
  }
}

}  // namespace
}  // namespace interfere
