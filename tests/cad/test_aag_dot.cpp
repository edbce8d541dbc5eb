// cad::aag_dot: the AAG as Graphviz DOT (`interfere features --dot`), on a hand-made graph.
#include <gtest/gtest.h>

#include <algorithm>

#include "interfere/cad/aag_dot.h"

namespace interfere::cad {
namespace {

TEST(AagDot, NodesArcsFeaturesAndQuotedNames) {
  Aag g;
  g.nodes.resize(3);
  for (std::uint32_t i = 0; i < 3; ++i) g.nodes[i].face = i;
  g.nodes[0].type = SurfaceType::plane;
  g.nodes[1].type = SurfaceType::cylinder;
  g.nodes[1].radius = 2.5;
  g.nodes[1].hole = true;
  g.nodes[2].type = SurfaceType::plane;
  g.nodes[2].from_bspline = true;
  g.arcs = {{.a = 0, .b = 1, .curve = CurveType::circle, .convexity = Convexity::convex, .inner_loop_a = true},
            {.a = 1, .b = 2, .curve = CurveType::circle, .convexity = Convexity::concave},
            {.a = 0, .b = 2, .curve = CurveType::line, .convexity = Convexity::smooth}};
  Feature hole;
  hole.type = "blind_hole";
  hole.faces = {1, 2};
  const std::string dot = aag_dot({{"odd \"name\"\nhere\\", &g, {hole}, {1}}});
  EXPECT_EQ(dot.rfind("graph aag {\n", 0), 0u);
  EXPECT_NE(dot.find(R"(label="odd \"name\"\nhere\\";)"), std::string::npos) << dot;
  EXPECT_NE(dot.find(R"(p0_0 [label="F0\nplane"];)"), std::string::npos) << dot;
  EXPECT_NE(dot.find(R"(p0_1 [label="F1\ncylinder\nr 2.5 hole", fillcolor=)"), std::string::npos) << dot;
  EXPECT_NE(dot.find(R"(F2\nplane (B-spline))"), std::string::npos) << dot;
  EXPECT_NE(dot.find("color=red"), std::string::npos);
  EXPECT_EQ(dot.find("color=red"), dot.rfind("color=red"));  // face 1 only
  EXPECT_NE(dot.find(R"(p0_0 -- p0_1 [style=solid, label="circle", penwidth=2];)"), std::string::npos) << dot;
  EXPECT_NE(dot.find(R"(p0_1 -- p0_2 [style=dashed, label="circle"];)"), std::string::npos) << dot;
  EXPECT_NE(dot.find(R"(p0_0 -- p0_2 [style=dotted, label="line"];)"), std::string::npos) << dot;
  EXPECT_NE(dot.find(R"(label="blind_hole")"), std::string::npos) << dot;
  // Braces balance; a part without a graph is left out.
  EXPECT_EQ(std::count(dot.begin(), dot.end(), '{'), std::count(dot.begin(), dot.end(), '}'));
  EXPECT_EQ(aag_dot({{"none", nullptr, {}, {}}}), aag_dot({}));
}

}  // namespace
}  // namespace interfere::cad
