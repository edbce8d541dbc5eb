// Generated scenes (include/interfere/scene/generate.h; issue #24, item 9): part meshes from two
// constructions, a polygon with holes extruded along z (plates, washers, nuts, the L-bracket) and a
// profile revolved about z (the bolt), laid out in joints on a grid.
#include "interfere/scene/generate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>

namespace interfere::scene {
namespace {

using P2 = std::array<double, 2>;

// cos and sin of 2*pi*j/n for j < n, n a multiple of 8, from the first octant by symmetry, so that
// multiples of 45 degrees come out symmetric (cos = sin at 45, exact 0 and 1 at the axes).
std::vector<P2> unit_circle(int n) {
  std::vector<P2> cs(static_cast<std::size_t>(n));
  const int q = n / 4, o = n / 8;
  for (int j = 0; j <= o; ++j) {
    const double a = 2 * std::numbers::pi * j / n;
    double c = std::cos(a), s = std::sin(a);
    if (j == 0) c = 1, s = 0;
    if (j == o) c = s = std::sqrt(0.5);
    cs[static_cast<std::size_t>(j)] = {c, s};
    cs[static_cast<std::size_t>(q - j)] = {s, c};
  }
  for (int j = 0; j < q; ++j) {
    const P2 p = cs[static_cast<std::size_t>(j)];
    cs[static_cast<std::size_t>(j + q)] = {-p[1], p[0]};
    cs[static_cast<std::size_t>(j + 2 * q)] = {-p[0], -p[1]};
    cs[static_cast<std::size_t>(j + 3 * q)] = {p[1], -p[0]};
  }
  return cs;
}

// A planar region: points and counter-clockwise triangles. Its boundary is where a directed edge
// has no reverse (the region lies to the left of it).
struct Shape2 {
  std::vector<P2> points;
  std::vector<Tri> triangles;
};

// The region extruded from z0 to z1 in `layers` layers: caps (bottom reversed) and a wall along
// every boundary edge. Closed and outward when the region's triangulation is conforming.
TriMesh extrude(const Shape2& s, double z0, double z1, int layers) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;  // directed edge -> count
  for (const Tri& t : s.triangles)
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  std::vector<std::pair<std::uint32_t, std::uint32_t>> boundary;
  for (const auto& [e, n] : edges)
    if (!edges.contains({e.second, e.first})) boundary.push_back(e);

  TriMesh m;
  const std::size_t np = s.points.size();
  std::vector<std::int64_t> index(np * static_cast<std::size_t>(layers + 1), -1);
  auto vertex = [&](std::uint32_t p, int level) {
    std::int64_t& i = index[static_cast<std::size_t>(level) * np + p];
    if (i < 0) {
      const double z = level == 0 ? z0 : (level == layers ? z1 : z0 + (z1 - z0) * level / layers);
      i = static_cast<std::int64_t>(m.positions.size());
      m.positions.push_back({s.points[p][0], s.points[p][1], z});
    }
    return static_cast<std::uint32_t>(i);
  };
  for (const Tri& t : s.triangles) {
    m.triangles.push_back({vertex(t[0], layers), vertex(t[1], layers), vertex(t[2], layers)});
    m.triangles.push_back({vertex(t[0], 0), vertex(t[2], 0), vertex(t[1], 0)});
  }
  for (const auto& [p, q] : boundary) {
    for (int l = 0; l < layers; ++l) {
      const std::uint32_t p0 = vertex(p, l), q0 = vertex(q, l), q1 = vertex(q, l + 1),
                          p1 = vertex(p, l + 1);
      m.triangles.push_back({p0, q0, q1});  // normal (dy, -dx, 0)·h: to the right of p->q, outward
      m.triangles.push_back({p0, q1, p1});
    }
  }
  return m;
}

// An annulus between a circle of radius `inner` and the outer boundary point outer(j) on the ray
// of unit_circle()[j], in `rings` rings (the outer points are used as given: exact corners).
template <class Outer>
Shape2 annulus(const std::vector<P2>& cs, double inner, Outer outer, int rings) {
  Shape2 s;
  const auto n = static_cast<std::uint32_t>(cs.size());
  for (int k = 0; k <= rings; ++k) {
    for (std::uint32_t j = 0; j < n; ++j) {
      const P2 a{inner * cs[j][0], inner * cs[j][1]};
      const P2 b = outer(j);
      const double f = static_cast<double>(k) / rings;
      s.points.push_back(
          k == 0 ? a : (k == rings ? b : P2{a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f}));
    }
  }
  auto id = [&](int k, std::uint32_t j) { return static_cast<std::uint32_t>(k) * n + j % n; };
  for (int k = 0; k < rings; ++k) {
    for (std::uint32_t j = 0; j < n; ++j) {  // radial x angular = +z: counter-clockwise
      s.triangles.push_back({id(k, j), id(k + 1, j), id(k + 1, j + 1)});
      s.triangles.push_back({id(k, j), id(k + 1, j + 1), id(k, j + 1)});
    }
  }
  return s;
}

// The profile (r, z) revolved about z: the first and last points lie on the axis (poles). Walking
// the profile, the solid lies to its left in the (r, z) half-plane.
TriMesh revolve(const std::vector<P2>& cs, const std::vector<P2>& profile) {
  TriMesh m;
  const auto n = static_cast<std::uint32_t>(cs.size());
  const std::size_t last = profile.size() - 1;
  m.positions.push_back({0, 0, profile[0][1]});
  for (std::size_t k = 1; k < last; ++k)
    for (std::uint32_t j = 0; j < n; ++j)
      m.positions.push_back({profile[k][0] * cs[j][0], profile[k][0] * cs[j][1], profile[k][1]});
  const auto top = static_cast<std::uint32_t>(m.positions.size());
  m.positions.push_back({0, 0, profile[last][1]});
  auto id = [&](std::size_t k, std::uint32_t j) {
    return k == 0 ? 0u : (k == last ? top : static_cast<std::uint32_t>(1 + (k - 1) * n + j % n));
  };
  // Angle direction x profile direction points out of the solid.
  for (std::size_t k = 0; k < last; ++k) {
    for (std::uint32_t j = 0; j < n; ++j) {
      if (k > 0) m.triangles.push_back({id(k, j), id(k, j + 1), id(k + 1, j + 1)});
      if (k + 1 < last) m.triangles.push_back({id(k, j), id(k + 1, j + 1), id(k + 1, j)});
    }
  }
  return m;
}

// Points a0 + (a1 - a0)·i/k for i = 0..k (the ends exact).
std::vector<double> steps(double a0, double a1, int k) {
  std::vector<double> v;
  for (int i = 0; i <= k; ++i) v.push_back(i == 0 ? a0 : (i == k ? a1 : a0 + (a1 - a0) * i / k));
  return v;
}

// Rectangles given by their grid lines, merged where their points coincide exactly.
struct GridShape {
  Shape2 s;
  std::map<P2, std::uint32_t> index;
  std::uint32_t point(P2 p) {
    const auto [it, inserted] = index.try_emplace(p, static_cast<std::uint32_t>(s.points.size()));
    if (inserted) s.points.push_back(p);
    return it->second;
  }
  void add(const std::vector<double>& xs, const std::vector<double>& ys) {
    for (std::size_t i = 0; i + 1 < xs.size(); ++i)
      for (std::size_t j = 0; j + 1 < ys.size(); ++j) {
        const std::uint32_t a = point({xs[i], ys[j]}), b = point({xs[i + 1], ys[j]}),
                            c = point({xs[i + 1], ys[j + 1]}), d = point({xs[i], ys[j + 1]});
        s.triangles.push_back({a, b, c});
        s.triangles.push_back({a, c, d});
      }
  }
};

int scaled(int segments, int at48) {
  return std::max(1, static_cast<int>(std::lround(at48 * segments / 48.0)));
}

std::shared_ptr<const TriMesh> share(TriMesh m) {
  return std::make_shared<const TriMesh>(std::move(m));
}

// splitmix64 (Steele, Lea & Flood 2014): the same stream on every platform.
struct Rng {
  std::uint64_t s;
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1p-53; }  // [0, 1)
  double symmetric() { return 2 * uniform() - 1; }                          // [-1, 1)
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(next() % n); }
};

Transform translation(const Vec3& t) {
  Transform x;
  x.t = t;
  return x;
}

std::string numbered(const char* prefix, std::size_t i) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%s-%06zu", prefix, i);
  return buf;
}

}  // namespace

std::vector<AssemblyPart> assembly_parts(const JointDims& d, int segments) {
  if (segments <= 0 || segments % 24 != 0)
    throw std::invalid_argument("assembly_parts: segments must be a positive multiple of 24, got " +
                                std::to_string(segments));
  const std::vector<P2> cs = unit_circle(segments);
  const double pi = std::numbers::pi;
  std::vector<AssemblyPart> parts;

  // Plate: a square (half width h) around the hole; the square's points on the rays, corners exact.
  const double h = d.plate_width / 2;
  auto square = [&](std::uint32_t j) {
    const double c = cs[j][0], s = cs[j][1];
    if (std::fabs(c) == std::fabs(s)) return P2{std::copysign(h, c), std::copysign(h, s)};
    if (std::fabs(c) > std::fabs(s)) return P2{std::copysign(h, c), h * s / std::fabs(c)};
    return P2{h * c / std::fabs(s), std::copysign(h, s)};
  };
  parts.push_back(
      {"plate",
       share(extrude(annulus(cs, d.hole_radius, square, scaled(segments, 6)), 0, d.plate_thickness,
                     scaled(segments, 2))),
       (d.plate_width * d.plate_width - pi * d.hole_radius * d.hole_radius) * d.plate_thickness});

  // Bolt: shaft from z = 0 through nut, washers and plates, head on top.
  const double shaft =
      d.shaft_protrusion + d.nut_thickness + 2 * d.washer_thickness + 2 * d.plate_thickness;
  {
    std::vector<P2> profile{{0, 0}};
    for (double z : steps(0, shaft, scaled(segments, 8))) profile.push_back({d.shaft_radius, z});
    for (double r : steps(d.shaft_radius, d.head_radius, 2)) profile.push_back({r, shaft});
    for (double z : steps(shaft, shaft + d.head_height, 2)) profile.push_back({d.head_radius, z});
    profile.push_back({d.head_radius / 2, shaft + d.head_height});
    profile.push_back({0, shaft + d.head_height});
    // Repeated corner points (one per run of steps) would make degenerate bands: drop them.
    profile.erase(std::unique(profile.begin(), profile.end()), profile.end());
    parts.push_back({"bolt", share(revolve(cs, profile)),
                     pi * d.shaft_radius * d.shaft_radius * shaft +
                         pi * d.head_radius * d.head_radius * d.head_height});
  }

  // Nut: hexagon of apothem a with corners on the rays at multiples of 60 degrees.
  {
    const int sixth = segments / 6;
    const double a = d.nut_apothem;
    auto hexagon = [&](std::uint32_t j) {
      // The side between corners k·60° and (k+1)·60°: its normal at (k + 1/2)·60°.
      const std::uint32_t k = j / static_cast<std::uint32_t>(sixth);
      const double nx = std::cos(pi / 3 * (k + 0.5)), ny = std::sin(pi / 3 * (k + 0.5));
      const double c = cs[j][0], s = cs[j][1];
      const double t = a / (c * nx + s * ny);
      return P2{t * c, t * s};
    };
    parts.push_back(
        {"nut",
         share(extrude(annulus(cs, d.nut_inner, hexagon, scaled(segments, 2)), 0, d.nut_thickness,
                       scaled(segments, 2))),
         (2 * std::sqrt(3.0) * a * a - pi * d.nut_inner * d.nut_inner) * d.nut_thickness});
  }

  // Washer: a flat ring.
  parts.push_back(
      {"washer",
       share(extrude(annulus(
                         cs, d.washer_inner,
                         [&](std::uint32_t j) {
                           return P2{d.washer_outer * cs[j][0], d.washer_outer * cs[j][1]};
                         },
                         scaled(segments, 2)),
                     0, d.washer_thickness, 1)),
       pi * (d.washer_outer * d.washer_outer - d.washer_inner * d.washer_inner) *
           d.washer_thickness});

  // L-bracket: profile in (u, v) = base leg [0, w] x [0, t] and vertical leg [0, t] x [t, H],
  // extruded along w in [0, L], then mapped (u, v, w) -> (u, L - w, v) (a proper rotation).
  {
    const double w = d.bracket_width, t = d.bracket_thickness, H = d.bracket_height,
                 L = d.bracket_length;
    GridShape g;
    std::vector<double> xs = steps(0, t, scaled(segments, 2));
    const std::vector<double> rest = steps(t, w, scaled(segments, 10));
    xs.insert(xs.end(), rest.begin() + 1, rest.end());
    g.add(xs, steps(0, t, scaled(segments, 2)));
    g.add(steps(0, t, scaled(segments, 2)), steps(t, H, scaled(segments, 8)));
    TriMesh m = extrude(g.s, 0, L, scaled(segments, 8));
    for (Vec3& p : m.positions) p = Vec3{p.x, p.z == 0 ? L : (p.z == L ? 0 : L - p.z), p.y};
    parts.push_back({"bracket", share(std::move(m)), (w * t + t * (H - t)) * L});
  }
  return parts;
}

Scene generate_assembly(const AssemblyGenOptions& o, AssemblyInfo* info) {
  const JointDims& d = o.dims;
  const std::vector<AssemblyPart> parts = assembly_parts(d, o.segments);
  auto mesh_of = [&](const char* type) {
    for (const AssemblyPart& p : parts)
      if (p.type == type) return p.mesh;
    throw std::logic_error("assembly part missing");
  };
  const auto plate = mesh_of("plate"), bolt = mesh_of("bolt"), nut = mesh_of("nut"),
             washer = mesh_of("washer"), bracket = mesh_of("bracket");

  const std::size_t joints = (o.bodies + 6) / 7;
  const auto side = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(joints))));
  const double pitch = d.plate_width + d.plate_gap;

  // Which joints clash (kind = rank % 3) and which have a lifted bracket: a seeded permutation.
  std::vector<std::size_t> order(joints);
  for (std::size_t i = 0; i < joints; ++i) order[i] = i;
  Rng rng{o.seed};
  for (std::size_t i = joints; i > 1; --i) std::swap(order[i - 1], order[rng.below(i)]);
  std::vector<int> special(joints,
                           -1);  // 0 bolt shifted, 1 bracket sunk, 2 bracket into washer, 3 gap
  const std::size_t nc = std::min(o.clashes, joints), ng = std::min(o.gaps, joints - nc);
  for (std::size_t r = 0; r < nc; ++r) special[order[r]] = static_cast<int>(r % 3);
  for (std::size_t r = nc; r < nc + ng; ++r) special[order[r]] = 3;

  Scene scene;
  scene.units = "mm";
  AssemblyInfo local;
  AssemblyInfo& gt = info ? *info : local;
  gt = {};
  gt.joints = joints;
  std::size_t counts[5] = {0, 0, 0, 0, 0};  // plate, bolt, washer, nut, bracket
  const char* type_names[5] = {"plate", "bolt", "washer", "nut", "bracket"};
  const std::shared_ptr<const TriMesh> meshes[5] = {plate, bolt, washer, nut, bracket};
  char detail[64];
  std::snprintf(detail, sizeof detail, "segments=%d", o.segments);

  for (std::size_t jn = 0; jn < joints && scene.bodies.size() < o.bodies; ++jn) {
    const Vec3 c{static_cast<double>(jn % side) * pitch, static_cast<double>(jn / side) * pitch, 0};
    const int kind = special[jn];
    Vec3 bolt_shift{};
    if (kind == 0) {
      static constexpr double dirs[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
      const std::size_t k = rng.below(4);
      bolt_shift = {dirs[k][0], dirs[k][1], 0};
    }
    Vec3 bracket_shift{};
    if (kind == 1) bracket_shift = {0, 0, -1};
    if (kind == 2)
      bracket_shift = {0, -2.5,
                       0};  // corner 8.5 from the axis: into the washer, 0.5 clear of the head
    if (kind == 3) bracket_shift = {0, 0, o.gap_height};
    const double t = d.plate_thickness, tw = d.washer_thickness;
    const struct {
      int type;
      Vec3 at;
    } placed[7] = {
        {0, {0, 0, 0}},  // plate, bottom
        {0, {0, 0, t}},  // plate, top
        {1, bolt_shift + Vec3{0, 0, -(tw + d.nut_thickness + d.shaft_protrusion)}},  // bolt
        {2, {0, 0, 2 * t}},                                                          // washer, top
        {2, {0, 0, -tw}},                         // washer, bottom
        {3, {0, 0, -(tw + d.nut_thickness)}},     // nut
        {4, bracket_shift + Vec3{4, 10, 2 * t}},  // bracket
    };
    std::string ids[7];
    for (int k = 0; k < 7 && scene.bodies.size() < o.bodies; ++k) {
      const int ty = placed[k].type;
      Body b;
      b.id = numbered(type_names[ty], counts[ty]++);
      b.name = b.id;
      b.path = "/assembly/" + numbered("joint", jn) + "/" + b.id;
      b.source.kind = SourceKind::primitive;
      b.source.detail = std::string(type_names[ty]) + " " + detail;
      b.mesh = meshes[ty];
      b.pose = translation(c + placed[k].at);
      b.tags = {type_names[ty]};
      gt.triangles += b.mesh->num_triangles();
      ids[k] = b.id;
      scene.bodies.push_back(std::move(b));
    }
    auto add = [&](std::vector<std::pair<std::string, std::string>>& v, int x, int y) {
      if (ids[x].empty() || ids[y].empty()) return;  // cut short
      v.push_back(std::minmax(ids[x], ids[y]));
    };
    // Designed contacts: plates, washers on plates, head on washer, nut on washer, bracket on
    // plate.
    add(gt.contact_pairs, 0, 1);
    add(gt.contact_pairs, 1, 3);
    add(gt.contact_pairs, 0, 4);
    add(gt.contact_pairs, 4, 5);
    if (kind == 0) {
      for (int k : {0, 1, 3, 4, 5}) add(gt.clash_pairs, 2, k);
    } else {
      add(gt.contact_pairs, 2, 3);
    }
    if (kind == 1)
      add(gt.clash_pairs, 1, 6);
    else if (kind == 3)
      add(gt.gap_pairs, 1, 6);
    else
      add(gt.contact_pairs, 1, 6);
    if (kind == 2) add(gt.clash_pairs, 3, 6);
  }
  for (auto* v : {&gt.clash_pairs, &gt.contact_pairs, &gt.gap_pairs})
    std::sort(v->begin(), v->end());
  return scene;
}

namespace {

// A random small rigid motion about `centre` (local coordinates): a rotation by an angle up to
// max_angle about a random unit axis (rejection from the cube; Rodrigues' formula), then a
// translation up to max_translation per axis.
Transform small_motion(Rng& rng, const Vec3& centre, double max_angle, double max_translation) {
  Vec3 axis;
  double len2 = 0;
  do {
    axis = {rng.symmetric(), rng.symmetric(), rng.symmetric()};
    len2 = squared_norm(axis);
  } while (len2 > 1 || len2 < 1e-6);
  axis = axis / std::sqrt(len2);
  const double angle = max_angle * rng.symmetric();
  const double co = std::cos(angle), si = std::sin(angle), v = 1 - co;
  Transform r;
  const double x = axis.x, y = axis.y, z = axis.z;
  r.r = {{{co + x * x * v, x * y * v - z * si, x * z * v + y * si},
          {y * x * v + z * si, co + y * y * v, y * z * v - x * si},
          {z * x * v - y * si, z * y * v + x * si, co + z * z * v}}};
  const Vec3 shift{max_translation * rng.symmetric(), max_translation * rng.symmetric(),
                   max_translation * rng.symmetric()};
  // translate(centre + shift) ∘ R ∘ translate(-centre)
  return compose(translation(centre + shift), compose(r, translation(Vec3{} - centre)));
}

// MovingLayout::cell (generate.h): one body per grid cell, near pairs sharing a cell.
Scene cell_scene(const MovingSceneGenOptions& o,
                 std::vector<std::pair<std::string, std::string>>& near) {
  const std::vector<AssemblyPart> parts = assembly_parts(JointDims{}, o.segments);
  // Part order of assembly_parts: find by type.
  auto part = [&](const char* type) -> const AssemblyPart& {
    for (const AssemblyPart& p : parts)
      if (p.type == type) return p;
    throw std::logic_error("assembly part missing");
  };
  const char* cycle[5] = {"plate", "bolt", "washer", "nut", "bracket"};
  const char* on_plate[4] = {"plate", "washer", "nut", "bracket"};
  double footprint = 0;  // the largest x or y extent of a part (the plate's width)
  for (const AssemblyPart& p : parts) {
    const Aabb b = p.mesh->bounds();
    footprint = std::max({footprint, b.hi.x - b.lo.x, b.hi.y - b.lo.y});
  }
  const double pitch = footprint + o.clearance;
  const std::size_t pairs =
      std::min(o.bodies / 2, static_cast<std::size_t>(std::llround(o.near_fraction * static_cast<double>(o.bodies) / 2)));
  const std::size_t cells = o.bodies - pairs;
  const auto side = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(cells))));
  // Which cells hold a near pair: a seeded permutation.
  std::vector<std::size_t> order(cells);
  for (std::size_t i = 0; i < cells; ++i) order[i] = i;
  Rng rng{o.seed};
  for (std::size_t i = cells; i > 1; --i) std::swap(order[i - 1], order[rng.below(i)]);
  std::vector<int> pair_kind(cells, -1);  // 0-3: a plate, washer, nut or bracket on a plate; 4: a fit
  for (std::size_t r = 0; r < pairs; ++r) pair_kind[order[r]] = r % 2 == 0 ? 4 : static_cast<int>((r / 2) % 4);
  // The bolt's head: its lowest vertex off the shaft (the bolt's axis is z, at x = y = 0).
  const JointDims dims;
  double head_bottom = std::numeric_limits<double>::infinity();
  for (const Vec3& v : part("bolt").mesh->positions)
    if (v.x * v.x + v.y * v.y > (dims.shaft_radius + 0.5) * (dims.shaft_radius + 0.5)) head_bottom = std::min(head_bottom, v.z);

  Scene scene;
  scene.units = "mm";
  std::map<std::string, std::size_t> counts;
  char detail[64];
  std::snprintf(detail, sizeof detail, "segments=%d", o.segments);
  auto add = [&](const AssemblyPart& p, const Vec3& at, std::size_t cell) {
    Body b;
    b.id = numbered(p.type.c_str(), counts[p.type]++);
    b.name = b.id;
    b.path = "/cell/" + numbered("cell", cell) + "/" + b.id;
    b.source.kind = SourceKind::primitive;
    b.source.detail = p.type + " " + detail;
    b.mesh = p.mesh;
    b.pose = translation(at);
    b.tags = {p.type};
    scene.bodies.push_back(std::move(b));
    return scene.bodies.back().id;
  };
  for (std::size_t c = 0; c < cells; ++c) {
    const Vec3 centre{(static_cast<double>(c % side) + 0.5) * pitch, (static_cast<double>(c / side) + 0.5) * pitch, 0};
    // A part standing on z = 0, its box centred on the cell's centre in x and y.
    auto standing = [&](const AssemblyPart& p, double z) {
      const Aabb b = p.mesh->bounds();
      return Vec3{centre.x - 0.5 * (b.lo.x + b.hi.x), centre.y - 0.5 * (b.lo.y + b.hi.y), z - b.lo.z};
    };
    if (pair_kind[c] < 0) {
      const AssemblyPart& p = part(cycle[c % 5]);
      add(p, standing(p, 0), c);
    } else {
      const AssemblyPart& plate = part("plate");
      const Aabb pb = plate.mesh->bounds();
      const std::string a = add(plate, standing(plate, 0), c);
      std::string b;
      if (pair_kind[c] == 4) {  // a bolt through the plate's hole, its head fit_gap above the plate
        const AssemblyPart& bolt = part("bolt");
        const Vec3 at = standing(bolt, 0);
        b = add(bolt, Vec3{at.x, at.y, pb.hi.z - pb.lo.z + o.fit_gap - head_bottom}, c);
      } else {
        const AssemblyPart& top = part(on_plate[pair_kind[c]]);
        b = add(top, standing(top, pb.hi.z - pb.lo.z + o.near_gap), c);
      }
      near.push_back(std::minmax(a, b));
    }
  }
  std::sort(near.begin(), near.end());
  return scene;
}

}  // namespace

Scene generate_moving_scene(const MovingSceneGenOptions& o,
                            std::vector<std::pair<std::string, std::string>>* near_pairs) {
  std::vector<std::pair<std::string, std::string>> local;
  std::vector<std::pair<std::string, std::string>>& near = near_pairs ? *near_pairs : local;
  near.clear();
  Scene scene;
  if (o.layout == MovingLayout::cell) {
    scene = cell_scene(o, near);
  } else {
    AssemblyGenOptions a;
    a.bodies = o.bodies, a.segments = o.segments, a.clashes = o.clashes, a.gaps = o.gaps,
    a.seed = o.seed;
    scene = generate_assembly(a);
  }
  Rng rng{o.seed ^ 0x6D6F76696E67ull};  // "moving"
  const double max_angle = o.max_rotation_deg * std::numbers::pi / 180;
  std::map<const TriMesh*, Vec3> centres;
  for (const Body& b : scene.bodies)
    if (!centres.contains(b.mesh.get())) centres[b.mesh.get()] = b.mesh->bounds().center();
  scene.frames.resize(o.frames);
  for (std::size_t f = 0; f < o.frames; ++f) {
    Frame& fr = scene.frames[f];
    fr.label = "frame " + std::to_string(f);
    fr.time = static_cast<double>(f);
    fr.poses.reserve(scene.bodies.size());
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const Body& b = scene.bodies[i];
      // local -> world: home pose ∘ the frame's motion about the part's centre.
      const Transform about = small_motion(rng, centres[b.mesh.get()], max_angle, o.max_translation);
      fr.poses.push_back({static_cast<std::uint32_t>(i), compose(b.pose, about)});
    }
  }
  return scene;
}

}  // namespace interfere::scene
