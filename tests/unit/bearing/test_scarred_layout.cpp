// The scarred solver's leaf records (quadtree.h, StripLeaf; issue #27, the 1,024-roller frame rate):
// every leaf of the facet-strip tree has a record with copies of its entries' corners (bit for bit
// the mesh positions the entries name), the entries' mesh triangles and strip rows, and every mesh
// triangle maps to the record of the leaf that holds it; inner nodes carry their subtree's entries
// and each record its leaf's path of first_child. Rollers with pits and raised scars, a
// window across angle 0, odd segment counts (a cap leaf of one fan triangle).
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "interfere/bearing/quadtree.h"
#include "interfere/bearing/scar.h"

using namespace interfere;
using namespace interfere::bearing;

namespace {

Roller roller_with(int n, int m, const ScarParams& s) {
  Expected<Roller> r = make_roller({.radius = 10, .height = 38, .radial_segments = n, .height_segments = m});
  EXPECT_TRUE(r.has_value());
  EXPECT_TRUE(apply_scar(*r, s).has_value());
  return std::move(*r);
}

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof(Vec3)) == 0; }

TEST(BearingScarredLayout, LeafRecordsCopyTheEntries) {
  struct Shape {
    int n, m;
    ScarParams scar;
  };
  const Shape shapes[] = {
      {32, 31, {.angle_center_deg = 0, .angle_width_deg = 350, .z_min = 0, .z_max = 38, .depth = 0.05, .seed = 5}},
      {32, 31, {.angle_center_deg = 90, .angle_width_deg = 60, .z_min = 5, .z_max = 20, .depth = 0.04, .border = 2,
                .seed = 7, .raised = true}},
      {33, 20, {.angle_center_deg = 0, .angle_width_deg = 40, .z_min = 0, .z_max = 38, .depth = 0.1, .seed = 3}},
      {7, 5, {.angle_center_deg = 180, .angle_width_deg = 90, .z_min = 10, .z_max = 30, .depth = 0.2, .seed = 11}},
  };
  for (const Shape& s : shapes) {
    const Roller r = roller_with(s.n, s.m, s.scar);
    const RollerQuadtree q = build_quadtree(r);
    const FacetStrips& fs = q.strips;
    ASSERT_FALSE(fs.empty());
    std::vector<int> used(fs.leaves.size(), 0);
    std::vector<std::int32_t> node_of_record(fs.leaves.size(), -1);
    for (std::size_t id = 0; id < fs.tree.nodes.size(); ++id) {
      const BoundNode& node = fs.tree.nodes[id];
      if (node.child_count > 0) continue;
      ASSERT_GE(node.first_child, 0);
      ASSERT_LT(static_cast<std::size_t>(node.first_child), fs.leaves.size());
      const StripLeaf& rec = fs.leaves[static_cast<std::size_t>(node.first_child)];
      ++used[static_cast<std::size_t>(node.first_child)];
      node_of_record[static_cast<std::size_t>(node.first_child)] = static_cast<std::int32_t>(id);
      EXPECT_EQ(rec.entry, node.tri_first);
      EXPECT_EQ(rec.count, node.tri_count);
      ASSERT_LE(rec.vertices, 4);
      for (std::uint32_t k = 0; k < rec.count; ++k) {
        const std::uint32_t e = node.tri_first + k;
        for (int c = 0; c < 3; ++c) {
          ASSERT_LT(rec.corner[k][c], rec.vertices);
          EXPECT_TRUE(same_bits(rec.v[rec.corner[k][c]], r.mesh.positions[fs.corners[e][static_cast<std::size_t>(c)]]));
        }
        EXPECT_EQ(rec.mesh_triangle[k], fs.mesh_triangle[e]);
        if (fs.mesh_triangle[e] == FacetStrips::kStrip)
          for (int c = 0; c < 3; ++c) EXPECT_EQ(rec.strip[c], fs.strip_cells[e][static_cast<std::size_t>(c)]);
      }
    }
    for (const int u : used) EXPECT_EQ(u, 1);  // one record per leaf
    // an inner node's entries are its subtree's (contiguous); a leaf's path lists its ancestors'
    // first_child from its root down
    for (const std::int32_t root : {fs.tree.side_root, fs.tree.bottom_root, fs.tree.top_root}) {
      struct Item {
        std::int32_t node;
        std::vector<std::uint16_t> path;
      };
      std::vector<Item> stack{{root, {}}};
      while (!stack.empty()) {
        const Item it = stack.back();
        stack.pop_back();
        const BoundNode& node = fs.tree.nodes[static_cast<std::size_t>(it.node)];
        if (node.child_count == 0) {
          const auto& path = fs.leaf_paths[static_cast<std::size_t>(node.first_child)];
          for (std::size_t d = 0; d < path.size(); ++d)
            EXPECT_EQ(path[d], d < it.path.size() ? it.path[d] : 0xffff);
          continue;
        }
        ASSERT_EQ(node.child_count, 2);
        const BoundNode& a = fs.tree.nodes[static_cast<std::size_t>(node.first_child)];
        const BoundNode& b = fs.tree.nodes[static_cast<std::size_t>(node.first_child) + 1];
        EXPECT_EQ(a.tri_first, node.tri_first);
        EXPECT_EQ(b.tri_first, a.tri_first + a.tri_count);
        EXPECT_EQ(node.tri_count, a.tri_count + b.tri_count);
        Item kid{0, it.path};
        kid.path.push_back(static_cast<std::uint16_t>(node.first_child));
        for (int k = 0; k < 2; ++k) kid.node = node.first_child + k, stack.push_back(kid);
      }
    }
    ASSERT_EQ(fs.leaf_record_of_triangle.size(), r.mesh.triangles.size());
    for (std::size_t t = 0; t < r.mesh.triangles.size(); ++t) {
      const std::int32_t rec = fs.leaf_record_of_triangle[t];
      ASSERT_GE(rec, 0);
      EXPECT_EQ(node_of_record[static_cast<std::size_t>(rec)], fs.leaf_of_triangle[t]);
    }
  }
}

}  // namespace
