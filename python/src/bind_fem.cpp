// Python bindings of the FEM module (issue #3): read_fem, the structured mesh generators, surface
// extraction and the clash per load step. Results are dicts of numpy arrays and the module's
// TriMesh / ClashResult classes. See docs/fem.md, "Python".
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <tbb/global_control.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bindings.h"
#include "interfere/fem/deform.h"
#include "interfere/fem/fem_mesh.h"
#include "interfere/fem/generate.h"
#include "interfere/fem/io.h"
#include "interfere/fem/surface.h"

namespace py = pybind11;

namespace interfere::python {
namespace {



py::object points(const std::vector<Vec3>& p) {
  py::array_t<double> a({static_cast<py::ssize_t>(p.size()), py::ssize_t{3}});
  auto r = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < p.size(); ++i) {
    r(i, 0) = p[i].x, r(i, 1) = p[i].y, r(i, 2) = p[i].z;
  }
  return a;
}

template <class T>
py::object ints(const std::vector<T>& v) {
  py::array_t<std::int64_t> a(static_cast<py::ssize_t>(v.size()));
  auto r = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < v.size(); ++i) r(i) = static_cast<std::int64_t>(v[i]);
  return a;
}

std::vector<Vec3> points_in(py::handle obj, const char* what) {
  std::vector<Vec3> out;
  for (py::handle row : obj) {
    py::sequence s = py::reinterpret_borrow<py::sequence>(row);
    if (py::len(s) != 3) throw py::value_error(std::string(what) + ": every row needs 3 numbers");
    out.push_back({s[0].cast<double>(), s[1].cast<double>(), s[2].cast<double>()});
  }
  return out;
}

ElemType type_from(const std::string& name) {
  ElemType t{};
  if (!elem_type_from_name(name, t)) throw py::value_error("unknown element type '" + name + "'");
  return t;
}

PartSplit split_from(const std::string& name) {
  PartSplit s{};
  if (!part_split_from_name(name, s)) throw py::value_error("split: auto, group, connectivity or single");
  return s;
}


py::dict series_dict(const NodalSeries& s) {
  py::dict d;
  d["name"] = s.name;
  d["times"] = s.times;
  py::list values;
  for (const auto& step : s.values) values.append(points(step));
  d["values"] = values;
  return d;
}

// A displacement argument: None, a field name of the mesh, a dict {"values": [...], "times": [...]}
// (as read_displacements_csv returns), or a list of steps of (n, 3) rows.
std::optional<NodalSeries> series_from(py::handle obj, const FemMesh& mesh, const char* what) {
  if (obj.is_none()) return std::nullopt;
  if (py::isinstance<py::str>(obj)) {
    const std::string name = obj.cast<std::string>();
    for (const NodalSeries& f : mesh.fields) {
      if (f.name == name) return f;
    }
    throw py::value_error(std::string(what) + ": the mesh has no field '" + name + "'");
  }
  NodalSeries s;
  s.name = what;
  py::handle values = obj;
  if (py::isinstance<py::dict>(obj)) {
    py::dict d = py::reinterpret_borrow<py::dict>(obj);
    values = d["values"];
    if (d.contains("times")) s.times = d["times"].cast<std::vector<double>>();
  }
  for (py::handle step : values) {
    s.values.push_back(points_in(step, what));
    if (s.values.back().size() != mesh.num_nodes()) {
      throw py::value_error(std::string(what) + ": a step has " + std::to_string(s.values.back().size()) +
                            " rows for " + std::to_string(mesh.num_nodes()) + " nodes");
    }
  }
  if (s.times.empty()) {
    for (std::size_t i = 0; i < s.values.size(); ++i) s.times.push_back(static_cast<double>(i));
  }
  if (s.times.size() != s.values.size()) throw py::value_error(std::string(what) + ": times and values differ in length");
  return s;
}

py::dict part_dict(const SurfacePart& p, const FemMesh& m) {
  py::dict d;
  d["name"] = p.name;
  d["group"] = p.group;
  d["mesh"] = py::cast(p.mesh);
  d["vertex_node"] = ints(p.vertex_node);
  std::vector<std::int64_t> node_ids(p.vertex_node.size()), elem_ids(p.tri_element.size());
  for (std::size_t i = 0; i < p.vertex_node.size(); ++i) node_ids[i] = m.node_ids[p.vertex_node[i]];
  for (std::size_t i = 0; i < p.tri_element.size(); ++i) elem_ids[i] = m.elem_ids[p.tri_element[i]];
  d["vertex_node_id"] = ints(node_ids);
  d["tri_element"] = ints(p.tri_element);
  d["tri_element_id"] = ints(elem_ids);
  d["tri_face"] = ints(p.tri_face);
  d["volume_elements"] = p.volume_elements;
  d["shell_elements"] = p.shell_elements;
  d["components"] = p.components;
  d["open_components"] = p.open_components;
  d["degenerate_components"] = p.degenerate_components;
  d["nonorientable_components"] = p.nonorientable_components;
  d["enclosed_volume"] = p.enclosed_volume;
  return d;
}

const SurfacePart& pick(const SurfaceResult& s, const std::string& name, const char* what) {
  if (name.empty()) {
    if (s.parts.size() == 1) return s.parts[0];
    throw py::value_error(std::string(what) + ": the mesh has " + std::to_string(s.parts.size()) +
                          " bodies; name one");
  }
  for (const SurfacePart& p : s.parts) {
    if (p.name == name) return p;
  }
  throw py::value_error(std::string(what) + ": no body '" + name + "'");
}

}  // namespace

void bind_fem(py::module_& m) {
  py::class_<FemMesh, std::shared_ptr<FemMesh>>(m, "FemMesh",
                                                "A finite-element mesh (nodes, elements with ids and type, groups, "
                                                "nodal fields) as read by read_fem or made by make_fem_box.")
      .def_property_readonly("file", [](const FemMesh& f) { return f.file; })
      .def_property_readonly("num_nodes", &FemMesh::num_nodes)
      .def_property_readonly("num_elements", &FemMesh::num_elements)
      .def_property_readonly("nodes", [](const FemMesh& f) { return points(f.nodes); }, "(n, 3) reference positions")
      .def_property_readonly("node_ids", [](const FemMesh& f) { return ints(f.node_ids); })
      .def_property_readonly("element_ids", [](const FemMesh& f) { return ints(f.elem_ids); })
      .def_property_readonly("element_types",
                             [](const FemMesh& f) {
                               py::list l;
                               for (ElemType t : f.elem_types) l.append(elem_info(t).name);
                               return l;
                             })
      .def_property_readonly("element_groups", [](const FemMesh& f) { return ints(f.elem_groups); })
      .def_property_readonly("groups",
                             [](const FemMesh& f) {
                               py::list l;
                               for (const FemGroup& g : f.groups) l.append(g.name);
                               return l;
                             })
      .def_property_readonly("fields",
                             [](const FemMesh& f) {
                               py::list l;
                               for (const NodalSeries& s : f.fields) l.append(s.name);
                               return l;
                             })
      .def(
          "field",
          [](const FemMesh& f, const std::string& name) {
            for (const NodalSeries& s : f.fields) {
              if (s.name == name) return series_dict(s);
            }
            throw py::key_error(name);
          },
          py::arg("name"), "A nodal field: {'name', 'times', 'values': [(n, 3) per step]}.")
      .def("__repr__", [](const FemMesh& f) {
        return "<interfere.FemMesh " + std::to_string(f.num_nodes()) + " nodes, " + std::to_string(f.num_elements()) +
               " elements>";
      });

  m.def(
      "read_fem",
      [](const std::filesystem::path& path) {
        Expected<FemMesh> r = Error{};
        {
          py::gil_scoped_release release;
          r = read_fem(path);
        }
        if (!r) raise_input_error(r.error());
        return std::make_shared<FemMesh>(std::move(*r));
      },
      py::arg("path"), "Reads a FEM file (.msh .bdf .nas .dat .vtk .vtu .inp). Raises InputError.");

  m.def(
      "read_displacements_csv",
      [](const std::filesystem::path& path, const FemMesh& mesh) {
        Expected<NodalSeries> r = read_displacements_csv(path, mesh);
        if (!r) raise_input_error(r.error());
        return series_dict(*r);
      },
      py::arg("path"), py::arg("mesh"), "Nodal displacements from CSV: {'name', 'times', 'values'}.");

  auto generated = [](GeneratedFem g) {
    return py::make_tuple(std::make_shared<FemMesh>(std::move(g.mesh)), g.volume, g.area);
  };
  auto box_options = [](const std::string& type, std::array<int, 3> n, int tets_per_cell, const std::string& group) {
    return FemBoxOptions{.type = type_from(type), .nx = n[0], .ny = n[1], .nz = n[2], .tets_per_cell = tets_per_cell,
                         .group = group};
  };
  m.def(
      "make_fem_box",
      [=](const std::string& type, std::array<int, 3> n, std::array<double, 3> lo, std::array<double, 3> hi,
          int tets_per_cell, const std::string& group) {
        FemBoxOptions o = box_options(type, n, tets_per_cell, group);
        o.lo = {lo[0], lo[1], lo[2]};
        o.hi = {hi[0], hi[1], hi[2]};
        try {
          return generated(make_fem_box(o));
        } catch (const std::invalid_argument& e) {
          throw py::value_error(e.what());
        }
      },
      py::arg("type") = "tet4", py::arg("n") = std::array<int, 3>{4, 4, 4},
      py::arg("lo") = std::array<double, 3>{0, 0, 0}, py::arg("hi") = std::array<double, 3>{1, 1, 1},
      py::arg("tets_per_cell") = 6, py::arg("group") = "",
      "Structured box mesh of one element type; returns (FemMesh, exact volume, exact area).");
  m.def(
      "make_fem_cylinder",
      [=](const std::string& type, std::array<int, 3> n, double radius, double height, int tets_per_cell) {
        try {
          return generated(make_fem_cylinder(box_options(type, n, tets_per_cell, ""), radius, height));
        } catch (const std::invalid_argument& e) {
          throw py::value_error(e.what());
        }
      },
      py::arg("type") = "tet4", py::arg("n") = std::array<int, 3>{8, 8, 8}, py::arg("radius") = 1.0,
      py::arg("height") = 1.0, py::arg("tets_per_cell") = 6,
      "Mapped cylinder (axis z from the origin); returns (FemMesh, analytic volume, analytic area).");
  m.def(
      "make_fem_sphere",
      [=](const std::string& type, std::array<int, 3> n, double radius, int tets_per_cell) {
        try {
          return generated(make_fem_sphere(box_options(type, n, tets_per_cell, ""), radius));
        } catch (const std::invalid_argument& e) {
          throw py::value_error(e.what());
        }
      },
      py::arg("type") = "tet4", py::arg("n") = std::array<int, 3>{8, 8, 8}, py::arg("radius") = 1.0,
      py::arg("tets_per_cell") = 6, "Mapped ball; returns (FemMesh, analytic volume, analytic area).");

  m.def(
      "extract_surface",
      [](const FemMesh& mesh, bool linear_faces, const std::string& split, bool drop_boundary_shells, int threads) {
        const SurfaceOptions o{.subdivide_quadratic = !linear_faces, .split = split_from(split),
                               .drop_boundary_shells = drop_boundary_shells};
        Expected<SurfaceResult> r = Error{};
        {
          ThreadLimit limit(threads);
          py::gil_scoped_release release;
          r = extract_surface(mesh, o);
        }
        if (!r) raise_input_error(r.error());
        py::dict d;
        py::list parts;
        for (const SurfacePart& p : r->parts) parts.append(part_dict(p, mesh));
        d["parts"] = parts;
        d["boundary_faces"] = r->boundary_faces;
        d["interior_faces"] = r->interior_faces;
        d["nonmanifold_faces"] = r->nonmanifold_faces;
        d["inverted_faces"] = r->inverted_faces;
        d["degenerate_faces"] = r->degenerate_faces;
        d["tied_faces"] = r->tied_faces;
        d["reoriented_triangles"] = r->reoriented_triangles;
        d["split_faces"] = r->split_faces;
        d["dropped_shells"] = r->dropped_shells;
        d["skipped_elements"] = r->skipped_elements;
        return d;
      },
      py::arg("mesh"), py::arg("linear_faces") = false, py::arg("split") = "auto",
      py::arg("drop_boundary_shells") = true, py::arg("threads") = 0,
      "Boundary surface per body: {'parts': [{'name', 'mesh' (TriMesh), 'vertex_node', 'vertex_node_id', "
      "'tri_element', 'tri_element_id', 'tri_face', ...}], counts}. Releases the GIL.");

  m.def(
      "clash_series",
      [](const FemMesh& mesh_a, const std::string& part_a, py::object disp_a, const FemMesh& mesh_b,
         const std::string& part_b, py::object disp_b, double scale, std::optional<std::vector<std::size_t>> steps,
         bool linear_faces, const std::string& split, int threads, bool depth) {
        const SurfaceOptions so{.subdivide_quadratic = !linear_faces, .split = split_from(split)};
        const std::optional<NodalSeries> ua = series_from(disp_a, mesh_a, "disp_a");
        const std::optional<NodalSeries> ub = series_from(disp_b, mesh_b, "disp_b");
        Expected<SurfaceResult> sa = Error{}, sb = Error{};
        {
          ThreadLimit limit(threads);
          py::gil_scoped_release release;
          sa = extract_surface(mesh_a, so);
          sb = extract_surface(mesh_b, so);
        }
        if (!sa) raise_input_error(sa.error());
        if (!sb) raise_input_error(sb.error());
        const SurfacePart& pa = pick(*sa, part_a, "part_a");
        const SurfacePart& pb = pick(*sb, part_b, "part_b");
        SeriesRequest request{.scale = scale, .depth = depth};
        if (steps) request.steps = *steps;
        Expected<SeriesResult> r = Error{};
        {
          ThreadLimit limit(threads);
          py::gil_scoped_release release;
          r = clash_series({&mesh_a, &pa, ua ? &*ua : nullptr}, {&mesh_b, &pb, ub ? &*ub : nullptr}, request);
        }
        if (!r) throw py::value_error(r.error().message());
        py::dict d;
        d["num_steps"] = r->num_steps;
        d["verdict"] = verdict_name(r->verdict);
        d["first_clash_step"] = r->first_clash_step >= 0 ? py::object(py::int_(r->first_clash_step)) : py::none();
        d["first_contact_step"] =
            r->first_contact_step >= 0 ? py::object(py::int_(r->first_contact_step)) : py::none();
        d["deepest_step"] = r->deepest_step >= 0 ? py::object(py::int_(r->deepest_step)) : py::none();
        py::list table;
        for (const StepSummary& s : r->steps) {
          py::dict row;
          row["step"] = s.step;
          row["time"] = s.time;
          row["interference"] = s.interference;
          row["verdict"] = verdict_name(s.verdict);
          row["pairs"] = s.pairs;
          row["cross_pairs"] = s.cross_pairs;
          row["touch_pairs"] = s.touch_pairs;
          row["regions"] = s.regions;
          row["max_curve_length"] = s.max_curve_length;
          row["curve_length"] = s.total_curve_length;
          row["containment"] = containment_name(s.containment);
          row["refit_seconds"] = s.refit_seconds;
          row["clash_seconds"] = s.clash_seconds;
          // Penetration depth (issue #26, item 3): None where not measured / not bounded / no node inside.
          row["depth"] = s.depth_measured ? py::object(py::float_(s.depth)) : py::none();
          row["depth_bound"] = s.depth_measured && s.depth_bounded ? py::object(py::float_(s.depth_bound)) : py::none();
          if (s.has_deepest) {
            py::dict deep;
            deep["part"] = s.deepest.part == 0 ? "a" : "b";
            deep["node"] = s.deepest.node;
            deep["element"] = s.deepest.element;
            deep["depth"] = s.deepest.depth;
            deep["point"] = py::make_tuple(s.deepest.point.x, s.deepest.point.y, s.deepest.point.z);
            row["deepest"] = deep;
          } else {
            row["deepest"] = py::none();
          }
          row["depth_note"] = s.depth_note.empty() ? py::object(py::none()) : py::object(py::str(s.depth_note));
          table.append(row);
        }
        d["steps"] = table;
        if (r->first_clash_step >= 0) {
          d["first_clash"] = py::cast(r->first_clash);
          py::list regions;
          for (const ClashRegion& g : r->first_clash.regions) {
            const RegionIds ids = region_ids(g, pa, mesh_a, pb, mesh_b);
            py::dict reg;
            reg["elements_a"] = ints(ids.elements_a);
            reg["elements_b"] = ints(ids.elements_b);
            reg["nodes_a"] = ints(ids.nodes_a);
            reg["nodes_b"] = ints(ids.nodes_b);
            regions.append(reg);
          }
          d["first_clash_regions"] = regions;
        } else {
          d["first_clash"] = py::none();
          d["first_clash_regions"] = py::list();
        }
        return d;
      },
      py::arg("mesh_a"), py::arg("part_a") = "", py::arg("disp_a") = py::none(), py::arg("mesh_b"),
      py::arg("part_b") = "", py::arg("disp_b") = py::none(), py::arg("scale") = 1.0, py::arg("steps") = py::none(),
      py::arg("linear_faces") = false, py::arg("split") = "auto", py::arg("threads") = 0, py::arg("depth") = true,
      "Clash of two FEM bodies per load step (trees refitted per step). disp_*: None, a field name, a dict "
      "from read_displacements_csv, or a list of (n, 3) steps. depth: measure the penetration depth of every "
      "clashing step (closed parts; each step's 'depth', 'depth_bound', 'deepest' {part, node, element, depth, "
      "point}, 'depth_note'). Returns {'num_steps', 'first_clash_step', 'deepest_step', 'steps': [...], "
      "'first_clash' (ClashResult), 'first_clash_regions': [{'elements_a', ...}]}.");
}

}  // namespace interfere::python
