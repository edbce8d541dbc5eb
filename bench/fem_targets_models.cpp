// The models of the FE targets benchmark (issue #26, item 7); see fem_targets_models.h.
#include "fem_targets_models.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "interfere/fem/generate.h"

namespace interfere::bench_fem_targets {
namespace {

struct Range {
  std::size_t begin = 0, end = 0;  // node indices of a body
};

/// Appends `part` as one group `name`; node and element ids continue those of `into` (1-based).
Range append_body(FemMesh& into, const FemMesh& part, const std::string& name) {
  const std::size_t node0 = into.nodes.size();
  const auto g = static_cast<std::int32_t>(into.groups.size());
  into.groups.push_back(FemGroup{.name = name, .id = g + 1, .dim = 3});
  into.nodes.insert(into.nodes.end(), part.nodes.begin(), part.nodes.end());
  for (std::size_t i = 0; i < part.nodes.size(); ++i) into.node_ids.push_back(static_cast<std::int64_t>(node0 + i + 1));
  const std::size_t elems = into.num_elements() + part.num_elements();
  into.elem_types.reserve(elems);
  into.elem_ids.reserve(elems);
  into.elem_groups.reserve(elems);
  into.elem_offsets.reserve(elems + 1);
  into.elem_nodes.reserve(into.elem_nodes.size() + part.elem_nodes.size());
  std::uint32_t v[32];
  for (std::size_t e = 0; e < part.num_elements(); ++e) {
    const int n = part.element_size(e);
    const std::uint32_t* p = part.element_nodes(e);
    for (int q = 0; q < n; ++q) v[q] = p[q] + static_cast<std::uint32_t>(node0);
    into.add_element(part.elem_types[e], static_cast<std::int64_t>(into.num_elements() + 1), g, v, n);
  }
  return {node0, into.nodes.size()};
}

NodalSeries& new_disp(FemMesh& m, int steps) {
  NodalSeries s{.name = "DISP"};
  for (int k = 0; k < steps; ++k) {
    s.times.push_back(0.1 * (k + 1));
    s.values.emplace_back(m.num_nodes(), Vec3{});
  }
  m.fields.push_back(std::move(s));
  return m.fields.back();
}

}  // namespace

int tet_cells_for(std::size_t elements) {
  return std::max(1, static_cast<int>(std::lround(std::cbrt(static_cast<double>(elements) / 6.0))));
}

FemMesh frd_read_model(std::size_t elements, int steps) {
  const int n = std::max(1, static_cast<int>(std::lround(std::cbrt(static_cast<double>(elements) / 8.0))));
  FemMesh m;
  FemBoxOptions o{.type = ElemType::hex8, .nx = 2 * n, .ny = 2 * n, .nz = n, .lo = {0, 0, 0}, .hi = {2, 2, 1}};
  const Range a = append_body(m, make_fem_box(o).mesh, "A");
  o.lo = {2.1, 0, 0}, o.hi = {4.1, 2, 1};
  const Range b = append_body(m, make_fem_box(o).mesh, "B");
  NodalSeries& u = new_disp(m, steps);
  for (int k = 0; k < steps; ++k) {
    std::vector<Vec3>& v = u.values[static_cast<std::size_t>(k)];
    for (std::size_t i = a.begin; i < a.end; ++i) {
      const double x = m.nodes[i].x;
      v[i] = Vec3{0, 0, -0.001 * (k + 1) * x * x};
    }
    for (std::size_t i = b.begin; i < b.end; ++i) v[i] = Vec3{-0.03 * (k + 1), 0, 0};
  }
  return m;
}

FemMesh twenty_body_model(std::size_t total_elements, int steps) {
  const int n = tet_cells_for(total_elements / 20);
  FemMesh m;
  struct Body {
    Range r;
    Vec3 c;
    bool ball;
  };
  std::vector<Body> bodies;
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 5; ++i) {
      const Vec3 c{1.1 * i, 1.1 * j, 0};
      const bool ball = (i + j) % 2 == 1;
      const std::string name = (ball ? "ball " : "box ") + std::to_string(j * 5 + i + 1);
      FemBoxOptions o{.type = ElemType::tet4, .nx = n, .ny = n, .nz = n};
      if (ball) {
        bodies.push_back({append_body(m, make_fem_sphere(o, 0.5, c).mesh, name), c, true});
      } else {
        o.lo = c - Vec3{0.5, 0.5, 0.5}, o.hi = c + Vec3{0.5, 0.5, 0.5};
        bodies.push_back({append_body(m, make_fem_box(o).mesh, name), c, false});
      }
    }
  }
  NodalSeries& u = new_disp(m, steps);
  for (int k = 0; k < steps; ++k) {
    std::vector<Vec3>& v = u.values[static_cast<std::size_t>(k)];
    for (const Body& b : bodies) {
      for (std::size_t i = b.r.begin; i < b.r.end; ++i) {
        const Vec3 d = m.nodes[i] - b.c;
        v[i] = b.ball ? d * (0.06 * k) : Vec3{0, 0, 0.01 * k * d.x};
      }
    }
  }
  return m;
}

FemMesh two_body_series_model(std::size_t elements_per_body, int steps) {
  const int n = tet_cells_for(elements_per_body);
  FemMesh m;
  const FemBoxOptions o{.type = ElemType::tet4, .nx = n, .ny = n, .nz = n};
  const Range a = append_body(m, make_fem_box(o).mesh, "A");
  const Range b = append_body(m, make_fem_sphere(o, 0.5, {1.6, 0.5, 0.5}).mesh, "B");
  NodalSeries& u = new_disp(m, steps);
  for (int k = 0; k < steps; ++k) {
    u.times[static_cast<std::size_t>(k)] = k;
    std::vector<Vec3>& v = u.values[static_cast<std::size_t>(k)];
    for (std::size_t i = a.begin; i < a.end; ++i) v[i] = Vec3{0, 0, -1e-4 * k * m.nodes[i].x * m.nodes[i].x};
    for (std::size_t i = b.begin; i < b.end; ++i) v[i] = Vec3{-0.01 * k, 0, 0};
  }
  return m;
}

}  // namespace interfere::bench_fem_targets
