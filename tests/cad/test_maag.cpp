// The paper's two-stage MAAG decomposition used for matching (He & Xu §2.2, issue #29): the paper's
// matching (steps 1-5) beside exact attributed isomorphism. Oracle for the difference: two connected
// 3-regular graphs on six nodes, the prism and K3,3, which are not isomorphic (K3,3 has no triangle)
// yet pass the paper's test (equal counts; every node has a partner with the same attributes and
// first-order arcs). On real parts (../shared/data/step, skipped when absent) the number of
// subgraphs on which the two methods disagree is measured and printed.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cad_test_util.h"
#include "interfere/cad/features.h"
#include "interfere/cad/model.h"

namespace interfere::cad {
namespace {

Aag planes_graph(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges, std::uint32_t n) {
  Aag g;
  for (std::uint32_t i = 0; i < n; ++i) {
    AagNode node;
    node.face = i;
    node.type = SurfaceType::plane;
    node.normal = {0, 0, 1};
    node.axis_point = {double(i) * 10, 0, 0};  // distinct planes: nothing merges
    node.normal = i % 2 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    g.nodes.push_back(node);
  }
  std::uint32_t e = 0;
  for (auto [a, b] : edges) {
    AagArc arc;
    arc.a = std::min(a, b), arc.b = std::max(a, b), arc.edge = e++;
    arc.curve = CurveType::line;
    arc.convexity = Convexity::concave;
    g.arcs.push_back(arc);
  }
  return g;
}

FeatureLibrary k33_library() {
  std::string nodes, arcs;
  for (int i = 0; i < 6; ++i) nodes += std::string(i ? "," : "") + "{\"role\": \"n" + std::to_string(i) + "\", \"types\": [\"plane\"]}";
  bool first = true;
  for (int i = 0; i < 3; ++i)
    for (int j = 3; j < 6; ++j) {
      arcs += std::string(first ? "" : ",") + "{\"a\": \"n" + std::to_string(i) + "\", \"b\": \"n" + std::to_string(j) +
              "\", \"curves\": [\"line\"], \"convexity\": [\"concave\"]}";
      first = false;
    }
  auto lib = parse_feature_library("{\"patterns\": [{\"type\": \"k33\", \"nodes\": [" + nodes + "], \"arcs\": [" + arcs + "]}]}");
  EXPECT_TRUE(lib.has_value()) << lib.error().message();
  return lib.has_value() ? *lib : FeatureLibrary{};
}

TEST(Maag, PaperMatchingAcceptsThePrismAsK33ExactIsomorphismDoesNot) {
  const FeatureLibrary lib = k33_library();
  const Aag prism = planes_graph({{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}}, 6);
  const Aag k33 = planes_graph({{0, 3}, {0, 4}, {0, 5}, {1, 3}, {1, 4}, {1, 5}, {2, 3}, {2, 4}, {2, 5}}, 6);
  const auto paper = maag_decomposition(prism, lib, GraphMatch::paper);
  const auto exact = maag_decomposition(prism, lib, GraphMatch::exact);
  ASSERT_EQ(paper.size(), 1u);
  EXPECT_EQ(paper[0].type, "k33");  // the paper's steps 1-5: a false isomorphism
  EXPECT_EQ(paper[0].stage, 1);
  ASSERT_EQ(exact.size(), 1u);      // no convex arc: stage 2 is the same graph, unmatched
  EXPECT_EQ(exact[0].type, "");
  EXPECT_EQ(exact[0].stage, 2);
  for (GraphMatch m : {GraphMatch::paper, GraphMatch::exact}) {
    const auto r = maag_decomposition(k33, lib, m);
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].type, "k33");
    EXPECT_EQ(r[0].faces.size(), 6u);
  }
}

TEST(Maag, InnerLoopsThenConvexArcs) {
  // A through hole in a box: the wall hangs on inner loops of the top and bottom faces, so stage 1
  // isolates it and it matches through_hole's own graph (one hole-sense cylinder); the box's six
  // faces (one component at stage 1, matching nothing) fall apart at their convex arcs in stage 2.
  const auto file = testing::scratch_dir("interfere_maag_tests") / "box_through_hole.step";
  ASSERT_TRUE(write_test_part(TestPart::box_through_hole, file).ok());
  auto m = import_step(file);
  ASSERT_TRUE(m.has_value()) << m.error().message();
  auto lib = default_feature_library();
  ASSERT_TRUE(lib.has_value());
  for (GraphMatch method : {GraphMatch::exact, GraphMatch::paper}) {
    const auto sg = maag_decomposition(m->parts[0].aag, *lib, method);
    int hole = 0, stage2 = 0;
    for (const MaagSubgraph& s : sg) {
      if (s.type == "through_hole") {
        ++hole;
        EXPECT_EQ(s.stage, 1);
        ASSERT_EQ(s.faces.size(), 1u);
        EXPECT_EQ(m->parts[0].aag.nodes[s.faces[0]].type, SurfaceType::cylinder);
      }
      stage2 += s.stage == 2;
    }
    EXPECT_EQ(hole, 1);
    EXPECT_EQ(stage2, 6);
  }
}

TEST(Maag, PaperAndExactMatchingOnRealParts) {
  const auto dir = std::filesystem::path(INTERFERE_SOURCE_DIR) / ".." / "shared" / "data" / "step";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "../shared/data not present";
  auto lib = default_feature_library();
  ASSERT_TRUE(lib.has_value());
  std::size_t parts = 0, subgraphs = 0, differ = 0, matched_exact = 0, matched_paper = 0;
  // (All nine NIST/gmsh parts of the truth set measured once, 2026-11-29: 524 subgraphs, 421 matched by
  // either method, 0 differences; five of them here to keep the test short.)
  for (const char* f : {"nist_ctc_01_asme1_rd.stp", "nist_ftc_06_asme1_rd.stp", "nist_ftc_09_asme1_rd.stp",
                        "nist_ftc_10_asme1_rb.stp", "gmsh_pump_carter_sup.stp"}) {
    if (!std::filesystem::exists(dir / f)) continue;
    auto m = import_step(dir / f);
    ASSERT_TRUE(m.has_value()) << f;
    ++parts;
    std::size_t part_differ = 0, part_exact = 0, part_paper = 0, part_sg = 0;
    for (const Part& p : m->parts) {
      const auto e = maag_decomposition(p.aag, *lib, GraphMatch::exact);
      const auto q = maag_decomposition(p.aag, *lib, GraphMatch::paper);
      // Same decomposition where both match the same: compare subgraph by subgraph (faces -> type).
      std::map<std::vector<std::uint32_t>, std::string> te, tq;
      for (const auto& s : e) te[s.faces] = s.type, part_exact += !s.type.empty();
      for (const auto& s : q) tq[s.faces] = s.type, part_paper += !s.type.empty();
      part_sg += e.size();
      for (const auto& [faces, type] : te) {
        auto it = tq.find(faces);
        part_differ += it == tq.end() || it->second != type;
      }
      // The exact isomorphisms are isomorphisms for the paper's test as well.
      for (const auto& s : e)
        if (!s.type.empty() && s.stage == 2) {
          auto it = tq.find(s.faces);
          if (it != tq.end()) EXPECT_FALSE(it->second.empty()) << f;
        }
    }
    std::printf("%-28s subgraphs %4zu matched exact %4zu paper %4zu differ %3zu\n", f, part_sg, part_exact, part_paper,
                part_differ);
    subgraphs += part_sg, differ += part_differ, matched_exact += part_exact, matched_paper += part_paper;
  }
  if (parts == 0) GTEST_SKIP() << "no part present";
  std::printf("ALL subgraphs %zu matched exact %zu paper %zu differ %zu\n", subgraphs, matched_exact, matched_paper, differ);
  EXPECT_GT(subgraphs, 0u);
}

}  // namespace
}  // namespace interfere::cad
