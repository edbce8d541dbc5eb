// FE models as scenes (fem/bodies.h, issue #24 item 1): three generated blocks of different element
// types in one mesh, with displacement steps. The oracles are computed here from the element nodes:
// each body's volume from its elements' tetrahedra (and the box's analytic volume), closedness and
// orientation from the triangles' edges, element membership and the face plane of every triangle,
// and the deformed positions from the displacement function.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <tuple>
#include <unordered_map>

#include "fem_io_test_util.h"
#include "interfere/fem/bodies.h"
#include "interfere/fem/generate.h"
#include "interfere/fem/io.h"

namespace interfere {
namespace {

using fem_test::temp_dir;

struct BlockSpec {
  const char* name;
  ElemType type;
  Vec3 lo, hi;
  int nx, ny, nz;
  std::int64_t first_node, first_element;
};

// Blocks with their own nodes (disjoint), ids far from 1 so that indices and ids differ.
const BlockSpec kBlocks[] = {
    {"blk_a", ElemType::hex8, {0, 0, 0}, {2, 1, 1}, 4, 2, 2, 11, 101},
    {"blk_b", ElemType::tet4, {3, 0, 0}, {4, 1, 1.5}, 2, 2, 3, 1001, 5001},
    {"third", ElemType::tet10, {0, 2, 0}, {1, 3, 0.5}, 2, 2, 1, 3001, 9001},
};

FemMesh three_blocks(bool grouped) {
  FemMesh m;
  for (const BlockSpec& s : kBlocks) {
    const GeneratedFem g = make_fem_box({.type = s.type,
                                         .nx = s.nx,
                                         .ny = s.ny,
                                         .nz = s.nz,
                                         .lo = s.lo,
                                         .hi = s.hi,
                                         .first_node_id = s.first_node,
                                         .first_element_id = s.first_element});
    const auto base = static_cast<std::uint32_t>(m.nodes.size());
    m.nodes.insert(m.nodes.end(), g.mesh.nodes.begin(), g.mesh.nodes.end());
    m.node_ids.insert(m.node_ids.end(), g.mesh.node_ids.begin(), g.mesh.node_ids.end());
    const auto group = static_cast<std::int32_t>(m.groups.size());
    if (grouped) m.groups.push_back({.name = s.name, .id = group + 1, .dim = 3});
    for (std::size_t e = 0; e < g.mesh.num_elements(); ++e) {
      std::vector<std::uint32_t> nodes(g.mesh.element_nodes(e),
                                       g.mesh.element_nodes(e) + g.mesh.element_size(e));
      for (std::uint32_t& n : nodes) n += base;
      m.add_element(g.mesh.elem_types[e], g.mesh.elem_ids[e], grouped ? group : -1, nodes.data(),
                    static_cast<int>(nodes.size()));
    }
  }
  EXPECT_TRUE(validate_fem_mesh(m));
  return m;
}

double box_volume(const BlockSpec& s) {
  return (s.hi.x - s.lo.x) * (s.hi.y - s.lo.y) * (s.hi.z - s.lo.z);
}

double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return std::abs(dot(b - a, cross(c - a, d - a))) / 6;
}

// An element's volume from its corners: tets as they are, wedges as 3 tets, hexes as 6 tets
// around the diagonal 0-6 (the blocks' elements are convex with planar faces).
double element_volume(const FemMesh& m, std::size_t e) {
  const std::uint32_t* n = m.element_nodes(e);
  auto p = [&](int k) { return m.nodes[n[k]]; };
  switch (m.elem_types[e]) {
    case ElemType::tet4:
    case ElemType::tet10:
      return tet_volume(p(0), p(1), p(2), p(3));
    case ElemType::hex8: {
      const int t[6][2] = {{1, 2}, {2, 3}, {3, 7}, {7, 4}, {4, 5}, {5, 1}};
      double v = 0;
      for (const auto& k : t) v += tet_volume(p(0), p(k[0]), p(k[1]), p(6));
      return v;
    }
    default:
      ADD_FAILURE() << "unexpected element type";
      return 0;
  }
}

// The divergence theorem: sum of p0 · (p1 × p2) / 6 over the triangles.
double enclosed_volume(const TriMesh& t, const std::vector<Vec3>& pos) {
  double v = 0;
  for (const auto& tri : t.triangles) v += dot(pos[tri[0]], cross(pos[tri[1]], pos[tri[2]])) / 6;
  return v;
}

// Closed and consistently oriented: every directed edge once, and its reverse once.
bool closed_and_consistent(const TriMesh& t) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& tri : t.triangles)
    for (int k = 0; k < 3; ++k) ++edges[{tri[k], tri[(k + 1) % 3]}];
  for (const auto& [e, count] : edges) {
    if (count != 1) return false;
    const auto r = edges.find({e.second, e.first});
    if (r == edges.end() || r->second != 1) return false;
  }
  return true;
}

// Corner nodes of local face f (1-based, the Abaqus numbering documented in fem/surface.h).
std::vector<int> face_corners(ElemType t, int f) {
  static const std::vector<std::vector<int>> tet = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
  static const std::vector<std::vector<int>> hex = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1},
                                                    {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}};
  const auto& table = t == ElemType::hex8 ? hex : tet;
  if (f < 1 || f > static_cast<int>(table.size())) return {};
  return table[static_cast<std::size_t>(f - 1)];
}

using Key = std::tuple<double, double, double>;
Key key(const Vec3& p) {
  return {p.x, p.y, p.z};
}

std::map<Key, std::uint32_t> node_by_position(const FemMesh& m) {
  std::map<Key, std::uint32_t> out;
  for (std::uint32_t i = 0; i < m.num_nodes(); ++i) out.emplace(key(m.nodes[i]), i);
  return out;
}

// The displacement of step s (s = 0: none), a smooth non-rigid field.
Vec3 u_of(const Vec3& p, std::size_t s) {
  const double k = 0.01 * static_cast<double>(s);
  return {k * (p.x + 2 * p.y), -k * p.z * p.z, k * (0.5 * p.x * p.y + 0.25)};
}

NodalSeries series_of(const FemMesh& m, const std::string& name, std::size_t steps) {
  NodalSeries u;
  u.name = name;
  for (std::size_t s = 0; s < steps; ++s) {
    u.times.push_back(0.5 * static_cast<double>(s) + 0.25);
    std::vector<Vec3> v(m.num_nodes());
    for (std::size_t i = 0; i < m.num_nodes(); ++i) v[i] = u_of(m.nodes[i], s);
    u.values.push_back(std::move(v));
  }
  return u;
}

// Every structural check of a scene made from three_blocks (reference geometry, ids, faces).
void check_bodies(const scene::Scene& sc, const FemMesh& m, double unit_scale = 1) {
  const auto nodes = node_by_position(m);
  std::unordered_map<std::int64_t, std::size_t> element_of_id;
  for (std::size_t e = 0; e < m.num_elements(); ++e) element_of_id[m.elem_ids[e]] = e;
  for (std::size_t b = 0; b < sc.bodies.size(); ++b) {
    const scene::Body& body = sc.bodies[b];
    SCOPED_TRACE(body.name);
    ASSERT_TRUE(body.mesh && body.source_ids && body.source_faces);
    const TriMesh& t = *body.mesh;
    ASSERT_GT(t.num_triangles(), 0u);
    ASSERT_EQ(body.source_ids->size(), t.num_triangles());
    ASSERT_EQ(body.source_faces->size(), t.num_triangles());
    EXPECT_EQ(body.source.kind, scene::SourceKind::fe_body);
    EXPECT_EQ(body.source_id_kind, scene::SourceIdKind::fe_element_face);
    EXPECT_TRUE(closed_and_consistent(t));

    // Which elements the body's triangles claim, and the body's volume from them.
    std::set<std::size_t> elements;
    for (std::size_t i = 0; i < t.num_triangles(); ++i) {
      const auto it = element_of_id.find((*body.source_ids)[i]);
      ASSERT_NE(it, element_of_id.end())
          << "triangle " << i << ": element id " << (*body.source_ids)[i];
      const std::size_t e = it->second;
      elements.insert(e);
      const std::uint32_t* en = m.element_nodes(e);
      const std::set<std::uint32_t> own(en, en + m.element_size(e));
      Vec3 centroid{};
      for (int k = 0; k < elem_info(m.elem_types[e]).corners; ++k)
        centroid = centroid + m.nodes[en[k]];
      centroid = centroid * (1.0 / elem_info(m.elem_types[e]).corners);
      Vec3 p[3];
      for (int k = 0; k < 3; ++k) {
        const Vec3 v = t.positions[t.triangles[i][k]] / unit_scale;
        const auto n = nodes.find(key(v));
        ASSERT_NE(n, nodes.end()) << "triangle " << i << ": vertex is no node";
        EXPECT_TRUE(own.count(n->second)) << "triangle " << i << ": node " << m.node_ids[n->second]
                                          << " not in element " << m.elem_ids[e];
        p[k] = m.nodes[n->second];
      }
      // On its local face's plane (axis-aligned on the blocks' boundaries) and facing away from
      // its element.
      const std::vector<int> fc = face_corners(m.elem_types[e], (*body.source_faces)[i]);
      ASSERT_FALSE(fc.empty()) << "triangle " << i << ": face " << int((*body.source_faces)[i]);
      bool on_plane = false;
      for (int axis = 0; axis < 3; ++axis) {
        const double c = m.nodes[en[fc[0]]][axis];
        bool all = true;
        for (int k : fc) all = all && m.nodes[en[k]][axis] == c;
        for (const Vec3& q : p) all = all && q[axis] == c;
        on_plane = on_plane || all;
      }
      EXPECT_TRUE(on_plane) << "triangle " << i << " is not on face "
                            << int((*body.source_faces)[i]) << " of element " << m.elem_ids[e];
      EXPECT_GT(dot(cross(p[1] - p[0], p[2] - p[0]), (p[0] + p[1] + p[2]) * (1.0 / 3) - centroid),
                0)
          << "triangle " << i << " faces into its element";
    }
    // The body's elements all lie in one block; its volume is the block's.
    const BlockSpec* spec = nullptr;
    for (const BlockSpec& s : kBlocks) {
      const std::int64_t id = m.elem_ids[*elements.begin()];
      if (id >= s.first_element && id < s.first_element + 1000) spec = &s;
    }
    ASSERT_NE(spec, nullptr);
    double element_sum = 0;
    std::size_t in_block = 0;
    for (std::size_t e = 0; e < m.num_elements(); ++e) {
      if (m.elem_ids[e] < spec->first_element || m.elem_ids[e] >= spec->first_element + 1000)
        continue;
      element_sum += element_volume(m, e);
      ++in_block;
    }
    EXPECT_LE(elements.size(), in_block);
    EXPECT_NEAR(element_sum, box_volume(*spec), 1e-12 * box_volume(*spec));
    const double s3 = unit_scale * unit_scale * unit_scale;
    const double enclosed = enclosed_volume(t, t.positions);
    EXPECT_NEAR(enclosed, element_sum * s3, 1e-9 * element_sum * s3);  // positive: outward
  }
}

TEST(FemScene, EveryBodyClosedOutwardWithElementIdsAndFaces) {
  FemMesh m = three_blocks(true);
  auto sc = fem_scene(m, "/data/model.inp", {.steps = false});
  ASSERT_TRUE(sc) << sc.error().message();
  ASSERT_EQ(sc->bodies.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(sc->bodies[i].name, kBlocks[i].name);
    EXPECT_EQ(sc->bodies[i].id, kBlocks[i].name);
    EXPECT_EQ(sc->bodies[i].path, std::string("/model/") + kBlocks[i].name);
    EXPECT_EQ(sc->bodies[i].source.file, "/data/model.inp");
    EXPECT_EQ(sc->bodies[i].source.detail, kBlocks[i].name);
    EXPECT_EQ(sc->bodies[i].unit, "mm");
  }
  EXPECT_EQ(sc->units, "mm");
  EXPECT_TRUE(sc->frames.empty());
  EXPECT_NO_THROW(sc->validate());
  check_bodies(*sc, m);

  // Without groups: bodies by connectivity, named "body N".
  auto conn = fem_scene(three_blocks(false), "model.vtu");
  ASSERT_TRUE(conn) << conn.error().message();
  ASSERT_EQ(conn->bodies.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(conn->bodies[i].name, "body " + std::to_string(i + 1));
    EXPECT_EQ(conn->bodies[i].id, "body_" + std::to_string(i + 1));
  }
  check_bodies(*conn, three_blocks(false));
  // --split single: one body of three closed components.
  auto single = fem_scene(m, "model.vtu", {.split = "single"});
  ASSERT_TRUE(single);
  ASSERT_EQ(single->bodies.size(), 1u);
  EXPECT_EQ(single->bodies[0].name, "all");
  double total = 0;
  for (const BlockSpec& s : kBlocks) total += box_volume(s);
  EXPECT_NEAR(enclosed_volume(*single->bodies[0].mesh, single->bodies[0].mesh->positions), total,
              1e-9 * total);
}

TEST(FemScene, SelectAndDuplicateIdsAndErrors) {
  FemMesh m = three_blocks(true);
  auto sel = fem_scene(m, "m.msh", {.select = "blk*"});
  ASSERT_TRUE(sel);
  ASSERT_EQ(sel->bodies.size(), 2u);
  EXPECT_EQ(sel->bodies[0].name, "blk_a");
  EXPECT_EQ(sel->bodies[1].name, "blk_b");

  // Names that map to one id get suffixes.
  m.groups[0].name = "a b";
  m.groups[1].name = "a_b";
  auto dup = fem_scene(m, "m.msh");
  ASSERT_TRUE(dup);
  EXPECT_NE(dup->bodies[0].id, dup->bodies[1].id);
  EXPECT_NO_THROW(dup->validate());

  auto bad_split = fem_scene(m, "m.msh", {.split = "bogus"});
  ASSERT_FALSE(bad_split);
  EXPECT_NE(bad_split.error().reason.find("bogus"), std::string::npos);
  auto none = fem_scene(m, "m.msh", {.select = "zzz*"});
  ASSERT_FALSE(none);
  EXPECT_NE(none.error().reason.find("'third'"), std::string::npos)
      << none.error().reason;  // lists the bodies
  auto unit = fem_scene(m, "m.msh", {.unit_scale = 10, .unit = "cm"});
  EXPECT_FALSE(unit);  // no working unit
  m.fields.push_back(series_of(m, "displacement", 2));
  m.fields.push_back(series_of(m, "DISPL", 2));
  auto two = fem_scene(m, "m.msh");
  ASSERT_FALSE(two);  // which one?
  EXPECT_NE(two.error().reason.find("DISPL"), std::string::npos);
  auto unknown = fem_scene(m, "m.msh", {.field = "velocity"});
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.error().reason.find("'displacement'"), std::string::npos);
  auto both = fem_scene(m, "m.msh", {.displacement_csv = "x.csv", .field = "DISPL"});
  EXPECT_FALSE(both);
  auto named = fem_scene(m, "m.msh", {.field = "DISPL"});
  ASSERT_TRUE(named);
  EXPECT_EQ(named->frames.size(), 2u);
  // Only a field not named like a displacement: no frames, a warning.
  m.fields = {series_of(m, "velocity", 2)};
  auto vel = fem_scene(m, "m.msh");
  ASSERT_TRUE(vel);
  EXPECT_TRUE(vel->frames.empty());
  bool warned = false;
  for (const std::string& w : vel->warnings)
    warned = warned || w.find("'velocity'") != std::string::npos;
  EXPECT_TRUE(warned);
  // A displacement that leaves the coordinate range.
  m.fields = {series_of(m, "u", 2)};
  std::size_t corner = 0;  // a node on the surface: the first block's corner lo
  while (!(m.nodes[corner] == kBlocks[0].lo)) ++corner;
  m.fields[0].values[1][corner] = {1e200, 0, 0};
  auto far = fem_scene(m, "m.msh");
  ASSERT_FALSE(far);
  EXPECT_NE(far.error().reason.find("step 1, node " + std::to_string(m.node_ids[corner])),
            std::string::npos)
      << far.error().reason;
}

TEST(FemScene, SurfaceAndBodyWarnings) {
  FemMesh m = three_blocks(true);
  // "fan": three tets on one triangle (a face of three elements, left out of the surface);
  // "flat": a tet of four coplanar nodes (a closed surface enclosing no volume).
  const auto base = static_cast<std::uint32_t>(m.nodes.size());
  for (const Vec3& p :
       {Vec3{10, 0, 0}, Vec3{11, 0, 0}, Vec3{10, 1, 0}, Vec3{10.2, 0.2, 1}, Vec3{10.2, 0.2, -1},
        Vec3{10.3, 0.3, 2}, Vec3{20, 0, 0}, Vec3{21, 0, 0}, Vec3{20, 1, 0}, Vec3{20.25, 0.25, 0}}) {
    m.nodes.push_back(p);
    m.node_ids.push_back(static_cast<std::int64_t>(90000 + m.nodes.size() - base));
  }
  m.groups.push_back({.name = "fan", .id = 9, .dim = 3});
  m.groups.push_back({.name = "flat", .id = 10, .dim = 3});
  const auto g = static_cast<std::int32_t>(m.groups.size() - 2);
  const std::uint32_t t0[4] = {base, base + 1, base + 2, base + 3},
                      t1[4] = {base, base + 2, base + 1, base + 4},
                      t2[4] = {base, base + 1, base + 2, base + 5},
                      t3[4] = {base + 6, base + 7, base + 8, base + 9};
  m.add_element(ElemType::tet4, 77701, g, t0, 4);
  m.add_element(ElemType::tet4, 77702, g, t1, 4);
  m.add_element(ElemType::tet4, 77703, g, t2, 4);
  m.add_element(ElemType::tet4, 77801, g + 1, t3, 4);
  ASSERT_TRUE(validate_fem_mesh(m));
  auto sc = fem_scene(m, "fan.inp");
  ASSERT_TRUE(sc) << sc.error().message();
  ASSERT_EQ(sc->bodies.size(), 5u);
  EXPECT_EQ(sc->bodies[3].name, "fan");
  EXPECT_EQ(sc->bodies[3].mesh->num_triangles(), 9u);  // 3 x 3 side faces
  for (std::size_t t = 0; t < 9; ++t) {
    const std::int64_t id = (*sc->bodies[3].source_ids)[t];
    EXPECT_TRUE(id >= 77701 && id <= 77703) << id;
  }
  EXPECT_EQ(sc->bodies[4].name, "flat");
  bool flat = false, shared = false;
  std::string all;
  for (const std::string& w : sc->warnings) {
    all += w + "\n";
    flat = flat || w == "fan.inp, body 'flat': 1 closed surface components enclose no volume "
                        "(degenerate; oriented by "
                        "the faces' votes)";
    shared = shared ||
             w == "fan.inp: 1 faces shared by more than two elements (left out of the surface)";
  }
  EXPECT_TRUE(flat) << all;
  EXPECT_TRUE(shared) << all;
  for (const std::string& w : sc->warnings) EXPECT_EQ(w.find("blk_"), std::string::npos) << w;
}

// Frame positions against node + u computed here; unchanged bodies share their shape.
void check_frames(const scene::Scene& sc, const FemMesh& m, std::size_t steps, double unit_scale,
                  double scale, bool exact) {
  const auto nodes = node_by_position(m);
  ASSERT_EQ(sc.frames.size(), steps);
  for (std::size_t s = 0; s < steps; ++s) {
    const scene::Frame& f = sc.frames[s];
    ASSERT_EQ(f.shapes.size(), sc.bodies.size());
    for (std::size_t b = 0; b < sc.bodies.size(); ++b) {
      ASSERT_EQ(f.shapes[b].body, b);
      const std::vector<Vec3>& ref = sc.bodies[b].mesh->positions;
      const std::vector<Vec3>& pos = *f.shapes[b].positions;
      ASSERT_EQ(pos.size(), ref.size());
      for (std::size_t v = 0; v < ref.size(); ++v) {
        const Vec3 node = ref[v] / unit_scale;
        ASSERT_TRUE(nodes.count(key(node)));
        const Vec3 want = (node + u_of(node, s) * scale) * unit_scale;
        if (exact) {
          ASSERT_EQ(pos[v], want) << "step " << s << ", body " << b << ", vertex " << v;
        } else {
          ASSERT_LT(norm(pos[v] - want), 1e-12 * unit_scale * 10)
              << "step " << s << ", body " << b << ", vertex " << v;
        }
      }
    }
  }
}

TEST(FemScene, DisplacementStepsBecomeFrames) {
  FemMesh m = three_blocks(true);
  m.fields.push_back(series_of(m, "U", 3));
  // The third body does not move from step 1 to step 2: its shape is shared.
  const std::int64_t third_first = kBlocks[2].first_node;
  for (std::size_t i = 0; i < m.num_nodes(); ++i)
    if (m.node_ids[i] >= third_first) m.fields[0].values[2][i] = m.fields[0].values[1][i];
  auto sc = fem_scene(m, "model.vtu");
  ASSERT_TRUE(sc) << sc.error().message();
  EXPECT_NO_THROW(sc->validate());
  ASSERT_EQ(sc->frames.size(), 3u);
  EXPECT_EQ(sc->frames[1].label, "step 1 (time 0.75)");
  EXPECT_EQ(sc->frames[2].time, 1.25);
  EXPECT_EQ(sc->frames[2].shapes[2].positions, sc->frames[1].shapes[2].positions);
  EXPECT_NE(sc->frames[2].shapes[0].positions, sc->frames[1].shapes[0].positions);
  // Steps 0 and 1 against the field; step 2 against it too, except the third body (its step 1).
  scene::Scene first_two = *sc;
  first_two.frames.resize(2);
  check_frames(first_two, m, 2, 1, 1, true);
  for (std::size_t v = 0; v < sc->bodies[2].mesh->num_vertices(); ++v) {
    const Vec3 node = sc->bodies[2].mesh->positions[v];
    ASSERT_EQ((*sc->frames[2].shapes[2].positions)[v], node + u_of(node, 1));
  }
  for (std::size_t b = 0; b < 2; ++b)
    for (std::size_t v = 0; v < sc->bodies[b].mesh->num_vertices(); ++v) {
      const Vec3 node = sc->bodies[b].mesh->positions[v];
      ASSERT_EQ((*sc->frames[2].shapes[b].positions)[v], node + u_of(node, 2));
    }

  // Units and scale: positions = unit_scale · (node + scale · u).
  m.fields[0] = series_of(m, "U", 3);
  auto cm = fem_scene(m, "model.vtu",
                      {.unit_scale = 10,
                       .unit = "cm",
                       .working_unit = "mm",
                       .displacement_scale = 2,
                       .parallel = false});
  ASSERT_TRUE(cm) << cm.error().message();
  EXPECT_EQ(cm->units, "mm");
  EXPECT_EQ(cm->bodies[0].unit, "cm");
  check_bodies(*cm, m, 10);
  check_frames(*cm, m, 3, 10, 2, false);
}

TEST(FemScene, StepsFromAnMshFileAndFromCsv) {
  FemMesh m = three_blocks(true);
  m.fields.push_back(series_of(m, "displacement", 3));
  const std::string msh = (temp_dir() / "three_blocks.msh").string();
  ASSERT_TRUE(write_fem(m, msh));
  auto sc = read_fem_scene(msh);
  ASSERT_TRUE(sc) << sc.error().message();
  ASSERT_EQ(sc->bodies.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(sc->bodies[i].name, kBlocks[i].name);
    EXPECT_EQ(sc->bodies[i].path, std::string("/three_blocks/") + kBlocks[i].name);
  }
  check_bodies(*sc, m);
  check_frames(*sc, m, 3, 1, 1, true);
  EXPECT_EQ(sc->frames[2].time, 1.25);

  // CSV (step,node_id,ux,uy,uz) for the mesh without fields: two steps.
  FemMesh bare = three_blocks(true);
  const std::string csv = (temp_dir() / "three_blocks_u.csv").string();
  {
    std::ofstream f(csv);
    f.precision(17);
    f << "step,node_id,ux,uy,uz\n";
    for (std::size_t s = 0; s < 2; ++s)
      for (std::size_t i = 0; i < bare.num_nodes(); ++i) {
        const Vec3 u = u_of(bare.nodes[i], s);
        f << s << "," << bare.node_ids[i] << "," << u.x << "," << u.y << "," << u.z << "\n";
      }
  }
  auto fromcsv = fem_scene(bare, "three_blocks.inp", {.displacement_csv = csv});
  ASSERT_TRUE(fromcsv) << fromcsv.error().message();
  check_frames(*fromcsv, bare, 2, 1, 1, true);
  auto missing = fem_scene(bare, "three_blocks.inp", {.displacement_csv = csv + ".nope"});
  EXPECT_FALSE(missing);
}

}  // namespace
}  // namespace interfere
