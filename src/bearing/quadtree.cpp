// Vertex quadtree over the unrolled side of a roller (Jia & Zheng 2019, §2.4): scar labels
// propagated to ancestors, virtual (averaged) vertices, calculation layer from Eq. (1) (the paper's
// rule by default, the former "still spanning the window" rule as an option; issue #27); plus, for
// the exact solver, oriented boxes (radial, tangential, axial at the node's middle angle) that
// contain the node's triangles, and binary trees over the end-cap fans; and the exact solvers'
// column-first bound tree of the same boxes (quadtree.h, BoundTree; issue #27).
#include "interfere/bearing/quadtree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace interfere::bearing {
namespace {

struct Builder {
  const Roller& roller;
  RollerQuadtree& tree;

  // Oriented bound of a set of body-frame points in the frame at angle phi (a QuadNode or a BoundNode).
  template <class Node, class Points>
  void bound(Node& node, double phi, Points&& for_points) {
    node.cos_mid = std::cos(phi), node.sin_mid = std::sin(phi);
    const double c = node.cos_mid, s = node.sin_mid;
    double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                    std::numeric_limits<double>::infinity()};
    double hi[3] = {-lo[0], -lo[1], -lo[2]};
    for_points([&](const Vec3& p) {
      const double q[3] = {c * p.x + s * p.y, -s * p.x + c * p.y, p.z};
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
    });
    const double mid[3] = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
    // a relative margin covers the rounding of the projections (the bound must contain the points)
    const double scale = std::max({std::fabs(lo[0]), std::fabs(hi[0]), std::fabs(lo[1]), std::fabs(hi[1]),
                                   std::fabs(lo[2]), std::fabs(hi[2])});
    const double margin = 8 * std::numeric_limits<double>::epsilon() * scale;
    node.half_r = 0.5 * (hi[0] - lo[0]) + margin;
    node.half_t = 0.5 * (hi[1] - lo[1]) + margin;
    node.half_z = 0.5 * (hi[2] - lo[2]) + margin;
    node.box_center = {c * mid[0] - s * mid[1], s * mid[0] + c * mid[1], mid[2]};
  }

  double column_angle(double i) const { return 2.0 * std::numbers::pi * i / roller.n(); }

  // Fills the (already allocated) slot `id`; children get contiguous slots allocated here.
  void side(std::int32_t id, std::int32_t i0, std::int32_t i1, std::int32_t j0, std::int32_t j1, std::int32_t level) {
    tree.depth = std::max(tree.depth, level);
    if (tree.level_max_columns.size() <= static_cast<std::size_t>(level))
      tree.level_max_columns.resize(static_cast<std::size_t>(level) + 1, 0);
    tree.level_max_columns[static_cast<std::size_t>(level)] =
        std::max(tree.level_max_columns[static_cast<std::size_t>(level)], i1 - i0);
    {
      QuadNode& node = tree.nodes[static_cast<std::size_t>(id)];
      node.i0 = i0, node.i1 = i1, node.j0 = j0, node.j1 = j1, node.level = level;
      Vec3 sum;
      int count = 0;
      for (int j = j0; j < j1; ++j)
        for (int i = i0; i < i1; ++i) {
          const std::uint32_t v = roller.side_vertex(i, j);
          sum += roller.mesh.positions[v];
          ++count;
          node.scar |= roller.scar[v];
        }
      node.virtual_vertex = sum / count;
      const int jc1 = std::min(j1, roller.m());  // cells [j0, jc1)
      if (jc1 > j0) {
        bound(node, column_angle(0.5 * (i0 + i1)), [&](auto&& f) {
          for (int j = j0; j <= jc1; ++j)
            for (int i = i0; i <= i1; ++i) f(roller.mesh.positions[roller.side_vertex(i, j)]);
        });
      } else {
        node.half_r = -1;  // no cell (the top ring's leaves)
      }
    }
    if (i1 - i0 == 1 && j1 - j0 == 1) {
      QuadNode& node = tree.nodes[static_cast<std::size_t>(id)];
      if (j0 < roller.m()) node.tri_first = roller.side_triangle(i0, j0), node.tri_count = 2;
      return;
    }
    const std::int32_t im = i1 - i0 > 1 ? (i0 + i1) / 2 : i1;
    const std::int32_t jm = j1 - j0 > 1 ? (j0 + j1) / 2 : j1;
    std::vector<std::array<std::int32_t, 4>> parts;
    for (auto [a0, a1] : {std::pair{i0, im}, std::pair{im, i1}})
      for (auto [b0, b1] : {std::pair{j0, jm}, std::pair{jm, j1}})
        if (a1 > a0 && b1 > b0) parts.push_back({a0, a1, b0, b1});
    // children are contiguous: allocate their slots first, then fill them depth-first
    const auto first = static_cast<std::int32_t>(tree.nodes.size());
    tree.nodes.resize(tree.nodes.size() + parts.size());
    tree.nodes[static_cast<std::size_t>(id)].first_child = first;
    tree.nodes[static_cast<std::size_t>(id)].child_count = static_cast<std::int32_t>(parts.size());
    for (std::size_t k = 0; k < parts.size(); ++k)
      side(first + static_cast<std::int32_t>(k), parts[k][0], parts[k][1], parts[k][2], parts[k][3], level + 1);
  }

  void cap(std::int32_t id, std::int32_t i0, std::int32_t i1, bool top) {
    const int j = top ? roller.m() : 0;
    const std::size_t center = static_cast<std::size_t>(roller.n()) * (roller.m() + 1) + (top ? 1 : 0);
    {
      QuadNode& node = tree.nodes[static_cast<std::size_t>(id)];
      node.i0 = i0, node.i1 = i1, node.j0 = j, node.j1 = j + 1;
      for (int i = i0; i < i1; ++i) node.scar |= roller.scar[roller.side_vertex(i, j)];
      bound(node, column_angle(0.5 * (i0 + i1)), [&](auto&& f) {
        f(roller.mesh.positions[center]);
        for (int i = i0; i <= i1; ++i) f(roller.mesh.positions[roller.side_vertex(i, j)]);
      });
    }
    if (i1 - i0 <= 2) {
      QuadNode& node = tree.nodes[static_cast<std::size_t>(id)];
      node.tri_first = top ? roller.top_triangle(i0) : roller.bottom_triangle(i0);
      node.tri_count = static_cast<std::uint32_t>(i1 - i0);
      return;
    }
    const std::int32_t im = (i0 + i1) / 2;
    const auto first = static_cast<std::int32_t>(tree.nodes.size());
    tree.nodes.resize(tree.nodes.size() + 2);
    tree.nodes[static_cast<std::size_t>(id)].first_child = first;
    tree.nodes[static_cast<std::size_t>(id)].child_count = 2;
    cap(first, i0, im, top);
    cap(first + 1, im, i1, top);
  }

  std::int32_t root() {
    tree.nodes.emplace_back();
    return static_cast<std::int32_t>(tree.nodes.size() - 1);
  }

  // The bound tree (quadtree.h, BoundTree): side cells [i0, i1) x [j0, j1) (column i spans vertex
  // columns i .. i+1, wrapping), halved in columns down to one column, then in rows.
  void bound_side(std::int32_t id, std::int32_t i0, std::int32_t i1, std::int32_t j0, std::int32_t j1) {
    auto& nodes = tree.bounds.nodes;
    bound(nodes[static_cast<std::size_t>(id)], column_angle(0.5 * (i0 + i1)), [&](auto&& f) {
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) f(roller.mesh.positions[roller.side_vertex(i, j)]);
    });
    std::int32_t a[2][4];  // the children's (i0, i1, j0, j1)
    if (i1 - i0 > 1) {
      const std::int32_t im = (i0 + i1) / 2;
      a[0][0] = i0, a[0][1] = im, a[1][0] = im, a[1][1] = i1;
      a[0][2] = a[1][2] = j0, a[0][3] = a[1][3] = j1;
    } else if (j1 - j0 > 1) {
      const std::int32_t jm = (j0 + j1) / 2;
      a[0][0] = a[1][0] = i0, a[0][1] = a[1][1] = i1;
      a[0][2] = j0, a[0][3] = jm, a[1][2] = jm, a[1][3] = j1;
    } else {  // one cell: its two triangles
      nodes[static_cast<std::size_t>(id)].tri_first = roller.side_triangle(i0, j0);
      nodes[static_cast<std::size_t>(id)].tri_count = 2;
      return;
    }
    const auto first = static_cast<std::int32_t>(nodes.size());
    nodes.resize(nodes.size() + 2);
    nodes[static_cast<std::size_t>(id)].first_child = first;
    nodes[static_cast<std::size_t>(id)].child_count = 2;
    for (int k = 0; k < 2; ++k) bound_side(first + k, a[k][0], a[k][1], a[k][2], a[k][3]);
  }

  // The bound tree over a cap's fan triangles [i0, i1) (as cap()).
  void bound_cap(std::int32_t id, std::int32_t i0, std::int32_t i1, bool top) {
    auto& nodes = tree.bounds.nodes;
    const int j = top ? roller.m() : 0;
    const std::size_t center = static_cast<std::size_t>(roller.n()) * (roller.m() + 1) + (top ? 1 : 0);
    bound(nodes[static_cast<std::size_t>(id)], column_angle(0.5 * (i0 + i1)), [&](auto&& f) {
      f(roller.mesh.positions[center]);
      for (int i = i0; i <= i1; ++i) f(roller.mesh.positions[roller.side_vertex(i, j)]);
    });
    if (i1 - i0 <= 2) {
      nodes[static_cast<std::size_t>(id)].tri_first = top ? roller.top_triangle(i0) : roller.bottom_triangle(i0);
      nodes[static_cast<std::size_t>(id)].tri_count = static_cast<std::uint32_t>(i1 - i0);
      return;
    }
    const std::int32_t im = (i0 + i1) / 2;
    const auto first = static_cast<std::int32_t>(nodes.size());
    nodes.resize(nodes.size() + 2);
    nodes[static_cast<std::size_t>(id)].first_child = first;
    nodes[static_cast<std::size_t>(id)].child_count = 2;
    bound_cap(first, i0, im, top);
    bound_cap(first + 1, im, i1, top);
  }

  std::int32_t bound_root() {
    tree.bounds.nodes.emplace_back();
    return static_cast<std::int32_t>(tree.bounds.nodes.size() - 1);
  }

  // ---- Coplanar facet strips (quadtree.h, FacetStrips; issue #27) ----
  struct Piece {
    std::int32_t j0, j1;  // cells [j0, j1) of the column
    bool strip;           // a planar run of >= 2 cells (else one cell, its own triangles)
  };
  const Vec3& at(int i, int j) const { return roller.mesh.positions[roller.side_vertex(i, j)]; }
  // Cell (i, j) is a vertical rectangle in the body frame, exactly: both vertex columns keep their
  // (x, y) from row j to row j + 1 and each row has one z (so consecutive such cells of a column
  // share their vertex columns and their union is one planar rectangle)
  bool flat_cell(int i, int j) const {
    const Vec3 &a0 = at(i, j), &a1 = at(i, j + 1), &b0 = at(i + 1, j), &b1 = at(i + 1, j + 1);
    return a0.x == a1.x && a0.y == a1.y && b0.x == b1.x && b0.y == b1.y && a0.z == b0.z && a1.z == b1.z &&
           a0.z < a1.z;
  }
  std::vector<Piece> pieces_of_column(int i) const {
    std::vector<Piece> out;
    const int m = roller.m();
    for (int j = 0; j < m;) {
      int e = j;
      while (e < m && flat_cell(i, e)) ++e;
      if (e - j >= 2) {
        out.push_back({j, e, true});
        j = e;
      } else {
        out.push_back({j, j + 1, false});
        ++j;
      }
    }
    return out;
  }
  std::int32_t strip_node() {
    tree.strips.tree.nodes.emplace_back();
    return static_cast<std::int32_t>(tree.strips.tree.nodes.size() - 1);
  }
  void strip_children(std::int32_t id, std::int32_t& first) {
    auto& nodes = tree.strips.tree.nodes;
    first = static_cast<std::int32_t>(nodes.size());
    nodes.resize(nodes.size() + 2);
    nodes[static_cast<std::size_t>(id)].first_child = first;
    nodes[static_cast<std::size_t>(id)].child_count = 2;
  }
  void add_mesh_triangle(std::int32_t leaf, std::uint32_t t) {
    FacetStrips& fs = tree.strips;
    const Tri& tri = roller.mesh.triangles[t];
    fs.corners.push_back({tri[0], tri[1], tri[2]});
    fs.mesh_triangle.push_back(t);
    fs.strip_cells.push_back({0, 0, 0});
    fs.leaf_of_triangle[t] = leaf;
  }
  // An inner node's entries: its two children's, contiguous (the children are filled one after the
  // other, each appending its entries)
  void entries_below(std::int32_t id, std::int32_t first) {
    auto& nodes = tree.strips.tree.nodes;
    const BoundNode &a = nodes[static_cast<std::size_t>(first)], &b = nodes[static_cast<std::size_t>(first) + 1];
    if (b.tri_first != a.tri_first + a.tri_count) throw std::logic_error("facet strips: entries not contiguous");
    nodes[static_cast<std::size_t>(id)].tri_first = a.tri_first;
    nodes[static_cast<std::size_t>(id)].tri_count = a.tri_count + b.tri_count;
  }
  // The leaf record of node `id` (quadtree.h, StripLeaf): its entries tri_first .. + tri_count - 1
  // (just appended to `corners`), their distinct corners copied in order of first appearance.
  void add_leaf_record(std::int32_t id) {
    FacetStrips& fs = tree.strips;
    BoundNode& node = fs.tree.nodes[static_cast<std::size_t>(id)];
    StripLeaf rec;
    rec.entry = node.tri_first;
    rec.count = static_cast<std::uint8_t>(node.tri_count);
    if (node.tri_count < 1 || node.tri_count > 2) throw std::logic_error("facet strips: a leaf of 1 or 2 entries");
    std::uint32_t ids[4];
    int distinct = 0;
    for (std::uint32_t k = 0; k < node.tri_count; ++k)
      for (int c = 0; c < 3; ++c) {
        const std::uint32_t v = fs.corners[node.tri_first + k][static_cast<std::size_t>(c)];
        int at = 0;
        while (at < distinct && ids[at] != v) ++at;
        if (at == distinct) {
          if (distinct == 4) throw std::logic_error("facet strips: a leaf with more than 4 corners");
          ids[distinct] = v, rec.v[distinct] = roller.mesh.positions[v], ++distinct;
        }
        rec.corner[k][c] = static_cast<std::uint8_t>(at);
      }
    for (std::uint32_t k = 0; k < node.tri_count; ++k) {
      const std::uint32_t e = node.tri_first + k;
      rec.mesh_triangle[k] = fs.mesh_triangle[e];
      if (fs.mesh_triangle[e] == FacetStrips::kStrip)
        for (int c = 0; c < 3; ++c) rec.strip[c] = fs.strip_cells[e][static_cast<std::size_t>(c)];
    }
    rec.vertices = static_cast<std::uint8_t>(distinct);
    const auto record = static_cast<std::int32_t>(fs.leaves.size());
    node.first_child = record;  // (a leaf: child_count stays 0)
    fs.leaves.push_back(rec);
    for (std::uint32_t k = 0; k < node.tri_count; ++k) {
      const std::uint32_t e = node.tri_first + k;
      if (fs.mesh_triangle[e] != FacetStrips::kStrip) {
        fs.leaf_record_of_triangle[fs.mesh_triangle[e]] = record;
      } else {
        const auto [i, j0, j1] = fs.strip_cells[e];
        for (int j = j0; j < j1; ++j) {
          const std::uint32_t t = roller.side_triangle(i, j);
          fs.leaf_record_of_triangle[t] = fs.leaf_record_of_triangle[t + 1] = record;
        }
      }
    }
  }
  // side columns [i0, i1): the same boxes as bound_side's column nodes; one column: its pieces
  void strips_side(std::int32_t id, std::int32_t i0, std::int32_t i1) {
    bound(tree.strips.tree.nodes[static_cast<std::size_t>(id)], column_angle(0.5 * (i0 + i1)), [&](auto&& f) {
      for (int j = 0; j <= roller.m(); ++j)
        for (int i = i0; i <= i1; ++i) f(at(i, j));
    });
    if (i1 - i0 > 1) {
      const std::int32_t im = (i0 + i1) / 2;
      std::int32_t first;
      strip_children(id, first);
      strips_side(first, i0, im);
      strips_side(first + 1, im, i1);
      entries_below(id, first);
      return;
    }
    const std::vector<Piece> pieces = pieces_of_column(i0);
    strips_column(id, i0, pieces, 0, static_cast<std::int32_t>(pieces.size()), true);
  }
  void strips_column(std::int32_t id, std::int32_t i, const std::vector<Piece>& pieces, std::int32_t s0,
                     std::int32_t s1, bool boxed) {
    FacetStrips& fs = tree.strips;
    const std::int32_t ja = pieces[static_cast<std::size_t>(s0)].j0, jb = pieces[static_cast<std::size_t>(s1 - 1)].j1;
    if (!boxed) {
      bound(fs.tree.nodes[static_cast<std::size_t>(id)], column_angle(i + 0.5), [&](auto&& f) {
        for (int j = ja; j <= jb; ++j)
          for (int c = i; c <= i + 1; ++c) f(at(c, j));
      });
    }
    if (s1 - s0 == 1) {
      const Piece& p = pieces[static_cast<std::size_t>(s0)];
      BoundNode& node = fs.tree.nodes[static_cast<std::size_t>(id)];
      node.tri_first = static_cast<std::uint32_t>(fs.corners.size());
      if (p.strip) {
        const std::uint32_t a0 = roller.side_vertex(i, p.j0), b0 = roller.side_vertex(i + 1, p.j0);
        const std::uint32_t a1 = roller.side_vertex(i, p.j1), b1 = roller.side_vertex(i + 1, p.j1);
        fs.corners.push_back({a0, b0, b1});
        fs.corners.push_back({a0, b1, a1});
        for (int k = 0; k < 2; ++k) {
          fs.mesh_triangle.push_back(FacetStrips::kStrip);
          fs.strip_cells.push_back({i, p.j0, p.j1});
        }
        for (int j = p.j0; j < p.j1; ++j) {
          const std::uint32_t t = roller.side_triangle(i, j);
          fs.leaf_of_triangle[t] = fs.leaf_of_triangle[t + 1] = id;
        }
      } else {
        const std::uint32_t t = roller.side_triangle(i, p.j0);
        add_mesh_triangle(id, t);
        add_mesh_triangle(id, t + 1);
      }
      fs.tree.nodes[static_cast<std::size_t>(id)].tri_count = 2;
      (void)node;
      add_leaf_record(id);
      return;
    }
    const std::int32_t sm = (s0 + s1) / 2;
    std::int32_t first;
    strip_children(id, first);
    strips_column(first, i, pieces, s0, sm, false);
    strips_column(first + 1, i, pieces, sm, s1, false);
    entries_below(id, first);
  }
  // the caps: as bound_cap, the fan triangles as entries
  void strips_cap(std::int32_t id, std::int32_t i0, std::int32_t i1, bool top) {
    const int j = top ? roller.m() : 0;
    const std::size_t center = static_cast<std::size_t>(roller.n()) * (roller.m() + 1) + (top ? 1 : 0);
    bound(tree.strips.tree.nodes[static_cast<std::size_t>(id)], column_angle(0.5 * (i0 + i1)), [&](auto&& f) {
      f(roller.mesh.positions[center]);
      for (int i = i0; i <= i1; ++i) f(at(i, j));
    });
    if (i1 - i0 <= 2) {
      const std::uint32_t first_tri = top ? roller.top_triangle(i0) : roller.bottom_triangle(i0);
      tree.strips.tree.nodes[static_cast<std::size_t>(id)].tri_first =
          static_cast<std::uint32_t>(tree.strips.corners.size());
      tree.strips.tree.nodes[static_cast<std::size_t>(id)].tri_count = static_cast<std::uint32_t>(i1 - i0);
      for (int k = 0; k < i1 - i0; ++k) add_mesh_triangle(id, first_tri + static_cast<std::uint32_t>(k));
      add_leaf_record(id);
      return;
    }
    const std::int32_t im = (i0 + i1) / 2;
    std::int32_t first;
    strip_children(id, first);
    strips_cap(first, i0, im, top);
    strips_cap(first + 1, im, i1, top);
    entries_below(id, first);
  }
  void build_strips() {
    FacetStrips& fs = tree.strips;
    fs.leaf_of_triangle.assign(roller.mesh.triangles.size(), -1);
    fs.leaf_record_of_triangle.assign(roller.mesh.triangles.size(), -1);
    fs.tree.nodes.reserve(4 * static_cast<std::size_t>(roller.n()) * 4 + 4 * roller.n());
    fs.tree.side_root = strip_node();
    strips_side(fs.tree.side_root, 0, roller.n());
    fs.tree.bottom_root = strip_node();
    strips_cap(fs.tree.bottom_root, 0, roller.n(), false);
    fs.tree.top_root = strip_node();
    strips_cap(fs.tree.top_root, 0, roller.n(), true);
    fs.leaves.shrink_to_fit();
    // the rims (FacetStrips::rims)
    const int n = roller.n();
    for (int cap = 0; cap < 2; ++cap) {
      const int j = cap ? roller.m() : 0;
      FacetStrips::Rim& rim = fs.rims[static_cast<std::size_t>(cap)];
      const Vec3& v0 = at(0, j);
      rim.radius = std::hypot(v0.x, v0.y), rim.z = v0.z, rim.dev = 0;
      for (int i = 0; i < n; ++i) {
        const double a = 2.0 * std::numbers::pi * i / n;
        const Vec3& v = at(i, j);
        rim.dev = std::max(rim.dev, std::hypot(v.x - rim.radius * std::cos(a), v.y - rim.radius * std::sin(a), v.z - rim.z));
      }
      // (a margin for the rounding of the ideal points, far below any gap the test needs)
      rim.dev = 2 * rim.dev + 64 * std::numeric_limits<double>::epsilon() * (rim.radius + std::fabs(rim.z));
    }
    const double step = 2.0 * std::numbers::pi / n;
    fs.rim_gap = n >= 8 ? (1 - 1e-3) * (std::cos(0.6 * step) - std::cos(1.4 * step)) : 0.0;
    // the ancestors' first_child of every leaf (FacetStrips::leaf_paths)
    std::array<std::uint16_t, 16> none;
    none.fill(0xffff);
    fs.leaf_paths.assign(fs.leaves.size(), none);
    struct Item {
      std::int32_t node;
      std::array<std::uint16_t, 16> path;
      int depth;
    };
    std::vector<Item> stack;
    for (const std::int32_t root : {fs.tree.side_root, fs.tree.bottom_root, fs.tree.top_root}) stack.push_back({root, none, 0});
    while (!stack.empty()) {
      const Item it = stack.back();
      stack.pop_back();
      const BoundNode& node = fs.tree.nodes[static_cast<std::size_t>(it.node)];
      if (node.child_count == 0) {
        fs.leaf_paths[static_cast<std::size_t>(node.first_child)] = it.path;
        continue;
      }
      Item kid = it;
      if (kid.depth < 16 && node.first_child < 0xffff)
        kid.path[static_cast<std::size_t>(kid.depth)] = static_cast<std::uint16_t>(node.first_child);
      ++kid.depth;
      for (std::int32_t k = 0; k < node.child_count; ++k) {
        kid.node = node.first_child + k;
        stack.push_back(kid);
      }
    }
  }
};

}  // namespace

std::int32_t RollerQuadtree::calculation_layer(double half_width, int radial_segments) const {
  return calculation_layer(half_width, radial_segments, options.layer_rule);
}

std::int32_t RollerQuadtree::calculation_layer(double half_width, int radial_segments,
                                               CalculationLayerRule rule) const {
  const double col = 2.0 * std::numbers::pi / radial_segments;
  if (rule == CalculationLayerRule::paper) {
    // the highest level whose every node's leaves (columns i0 .. i1-1, at angles i * col) span at
    // most the range 2 * half_width; a relative tolerance absorbs the rounding of col
    const double range = 2.0 * half_width * (1 + 1e-12);
    for (std::int32_t level = 0; level < static_cast<std::int32_t>(level_max_columns.size()); ++level)
      if ((level_max_columns[static_cast<std::size_t>(level)] - 1) * col <= range) return level;
    return depth;
  }
  // spanning_window: deepest level whose nodes still span 2*half_width in angle (node width
  // 2*pi/2^level, capped by n)
  std::int32_t level = 0;
  while (level < depth) {
    const double cols = std::max(1.0, std::ceil(radial_segments / std::pow(2.0, level + 1)));
    if (col * cols < 2.0 * half_width) break;
    ++level;
  }
  return level;
}

RollerQuadtree build_quadtree(const Roller& roller, const QuadtreeOptions& options) {
  RollerQuadtree tree;
  tree.options = options;
  tree.nodes.reserve(static_cast<std::size_t>(roller.n()) * (roller.m() + 1) * 2 + 2 * roller.n());
  Builder b{roller, tree};
  tree.side_root = b.root();
  b.side(tree.side_root, 0, roller.n(), 0, roller.m() + 1, 0);
  tree.bottom_root = b.root();
  b.cap(tree.bottom_root, 0, roller.n(), false);
  tree.top_root = b.root();
  b.cap(tree.top_root, 0, roller.n(), true);
  // the exact solvers' bound tree: 2 n m - 1 side nodes, about 2 n per cap
  tree.bounds.nodes.reserve(2 * static_cast<std::size_t>(roller.n()) * roller.m() + 4 * roller.n());
  tree.bounds.side_root = b.bound_root();
  b.bound_side(tree.bounds.side_root, 0, roller.n(), 0, roller.m());
  tree.bounds.bottom_root = b.bound_root();
  b.bound_cap(tree.bounds.bottom_root, 0, roller.n(), false);
  tree.bounds.top_root = b.bound_root();
  b.bound_cap(tree.bounds.top_root, 0, roller.n(), true);
  // the scarred solver's tree of coplanar facet strips (quadtree.h, FacetStrips)
  b.build_strips();
  // (issue #27: the reservations above are upper bounds; a scarred roller keeps its trees for the
  // whole run, 256 of them in the 1,024-roller scene)
  tree.nodes.shrink_to_fit();
  tree.bounds.nodes.shrink_to_fit();
  tree.strips.tree.nodes.shrink_to_fit();
  return tree;
}

}  // namespace interfere::bearing
