// Graphviz DOT of the attributed adjacency graph (issue #6, item 2; include/interfere/cad/aag_dot.h).
#include "interfere/cad/aag_dot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace interfere::cad {
namespace {

// A DOT string literal: quotes and backslashes escaped, line breaks as DOT's \n, other control
// characters dropped.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) >= 0x20) out += c;
  }
  return out + "\"";
}

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

// Fill colours of the features, in order (a Brewer qualitative set; cycled).
constexpr const char* kFill[] = {"#8dd3c7", "#ffffb3", "#bebada", "#fb8072", "#80b1d3",
                                 "#fdb462", "#b3de69", "#fccde5", "#d9d9d9", "#bc80bd"};

std::string node_label(const AagNode& n) {
  std::string label = "F" + std::to_string(n.face) + "\n" + surface_type_name(n.type);
  if (n.from_bspline) label += " (B-spline)";
  if (n.type == SurfaceType::cylinder || n.type == SurfaceType::cone || n.type == SurfaceType::sphere ||
      n.type == SurfaceType::torus) {
    label += "\nr " + number(n.radius);
    if (n.hole) label += " hole";
  }
  return label;
}

}  // namespace

std::string aag_dot(const std::vector<DotPart>& parts) {
  std::string out = "graph aag {\n  node [shape=box, style=\"rounded,filled\", fillcolor=white, fontsize=10];\n"
                    "  edge [fontsize=8];\n";
  for (std::size_t pi = 0; pi < parts.size(); ++pi) {
    const DotPart& part = parts[pi];
    if (!part.aag) continue;
    const std::string id = "p" + std::to_string(pi) + "_";
    out += "  subgraph cluster_" + std::to_string(pi) + " {\n    label=" + quoted(part.name) + ";\n";
    // Each face's feature (the first that has it) and the legend.
    std::map<std::uint32_t, std::size_t> feature_of;
    for (std::size_t k = 0; k < part.features.size(); ++k)
      for (std::uint32_t f : part.features[k].faces) feature_of.emplace(f, k);
    std::vector<std::uint32_t> assembly = part.assembly_faces;
    std::sort(assembly.begin(), assembly.end());
    for (const AagNode& n : part.aag->nodes) {
      std::string attrs = "label=" + quoted(node_label(n));
      if (const auto it = feature_of.find(n.face); it != feature_of.end())
        attrs += std::string(", fillcolor=\"") + kFill[it->second % std::size(kFill)] + "\", tooltip=" +
                 quoted(part.features[it->second].type + " " + std::to_string(it->second));
      if (std::binary_search(assembly.begin(), assembly.end(), n.face)) attrs += ", color=red, penwidth=2.5";
      out += "    " + id + std::to_string(n.face) + " [" + attrs + "];\n";
    }
    for (const AagArc& a : part.aag->arcs) {
      const char* style = a.convexity == Convexity::convex ? "solid" : a.convexity == Convexity::concave ? "dashed" : "dotted";
      std::string attrs = std::string("style=") + style + ", label=" + quoted(curve_type_name(a.curve));
      if (a.inner_loop_a || a.inner_loop_b) attrs += ", penwidth=2";
      out += "    " + id + std::to_string(a.a) + " -- " + id + std::to_string(a.b) + " [" + attrs + "];\n";
    }
    for (std::size_t k = 0; k < part.features.size(); ++k)  // legend: one entry per feature
      out += "    " + id + "feature" + std::to_string(k) + " [shape=note, fillcolor=\"" + kFill[k % std::size(kFill)] +
             "\", label=" + quoted(part.features[k].type) + "];\n";
    out += "  }\n";
  }
  return out + "}\n";
}

}  // namespace interfere::cad
