// Python bindings of the probe module (issue #5): submodule `interfere.probe` with the DH robot,
// forward kinematics, the exact cylinder-triangle and box-triangle (box holder) tests and distances,
// the generated panels and paths, and the sweep. Results are plain Python values (tuples, dicts,
// lists); no geometry here.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <tbb/global_control.h>

#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include "bindings.h"
#include "interfere/probe/generate.h"
#include "interfere/probe/paper_machine.h"
#include "interfere/probe/paper_tests.h"
#include "interfere/probe/sweep.h"

namespace py = pybind11;

namespace interfere::python {
namespace {

using namespace interfere::probe;


Vec3 vec(const py::handle& h, const char* what) {
  const auto s = py::cast<std::vector<double>>(h);
  if (s.size() != 3) throw py::value_error(std::string(what) + ": expected 3 numbers");
  return {s[0], s[1], s[2]};
}
py::tuple tup(const Vec3& v) { return py::make_tuple(v.x, v.y, v.z); }

std::array<Vec3, 3> tri(const py::handle& h) {
  const auto rows = py::cast<std::vector<py::object>>(h);
  if (rows.size() != 3) throw py::value_error("triangle: expected 3 points");
  return {vec(rows[0], "triangle[0]"), vec(rows[1], "triangle[1]"), vec(rows[2], "triangle[2]")};
}

OrientedBox oriented_box(const py::handle& centre, const py::handle& axes, const std::array<double, 3>& half) {
  const auto rows = py::cast<std::vector<py::object>>(axes);
  if (rows.size() != 3) throw py::value_error("axes: expected 3 vectors");
  const std::array<Vec3, 3> a{vec(rows[0], "axes[0]"), vec(rows[1], "axes[1]"), vec(rows[2], "axes[2]")};
  for (int i = 0; i < 3; ++i) {
    if (!(half[i] > 0) || !std::isfinite(half[i])) throw py::value_error("half extents must be finite numbers > 0");
    for (int j = 0; j < 3; ++j) {
      if (std::fabs(dot(a[i], a[j]) - (i == j ? 1.0 : 0.0)) > 1e-12) throw py::value_error("axes must be orthonormal");
    }
  }
  return make_box(vec(centre, "centre"), a, half);
}

Cylinder cyl(const py::handle& c0, const py::handle& c1, double r) {
  if (!(r >= 0) || !std::isfinite(r)) throw py::value_error("radius must be a finite number >= 0");
  return {vec(c0, "c0"), vec(c1, "c1"), r};
}

PanelKind panel_from(const std::string& s) {
  if (s == "sheet") return PanelKind::sheet;
  if (s == "shell") return PanelKind::shell;
  if (s == "saddle") return PanelKind::saddle;
  throw py::value_error("kind: 'sheet', 'shell' or 'saddle'");
}

Hierarchy hierarchy_from(const std::string& s) {
  if (s == "bvh") return Hierarchy::bvh;
  if (s == "patches") return Hierarchy::patches;
  if (s == "grid") return Hierarchy::grid;
  if (s == "distance_field" || s == "distance-field") return Hierarchy::distance_field;
  if (s == "brute" || s == "brute_force") return Hierarchy::brute_force;
  throw py::value_error("hierarchy: 'bvh', 'patches', 'grid', 'distance_field' or 'brute'");
}

py::object num(double v) { return std::isfinite(v) ? py::object(py::float_(v)) : py::object(py::none()); }

}  // namespace

void bind_probe(py::module_& m) {
  py::module_ p = m.def_submodule("probe", "Inspection-probe path checking (docs/probe.md).");

  py::class_<Robot>(p, "Robot", "Serial DH chain (standard or modified DH, angles in degrees) with the probe tool frame.")
      .def_readonly("name", &Robot::name)
      .def_property_readonly("convention", [](const Robot& r) { return std::string(dh_convention_name(r.convention)); },
                             "'standard' (distal) or 'modified' (proximal, Craig) Denavit-Hartenberg")
      .def_property_readonly("joint_names",
                             [](const Robot& r) {
                               std::vector<std::string> n;
                               for (const DhJoint& j : r.joints) n.push_back(j.name);
                               return n;
                             })
      .def("to_json", &robot_to_json)
      .def("__repr__", [](const Robot& r) {
        return "Robot(name='" + r.name + "', joints=" + std::to_string(r.joints.size()) + ")";
      });

  p.def(
      "read_robot",
      [](const std::filesystem::path& path) {
        auto r = read_robot_json(path);
        if (!r) raise_input_error(r.error());
        return std::move(r.value());
      },
      py::arg("path"), "Reads a robot JSON file; raises InputError naming file, line and field.");
  p.def(
      "parse_robot",
      [](const std::string& text) {
        auto r = parse_robot_json(text, "<string>");
        if (!r) raise_input_error(r.error());
        return std::move(r.value());
      },
      py::arg("text"));
  p.def("pivot_machine", [](double l) { return pivot_machine(l); }, py::arg("pivot_to_tip") = 150.0,
        "The 5-axis pivot machine (x, y, z, a, b): the project's reconstruction, not the paper's §3.1 machine.");
  p.def("paper_machine", [](double l) { return pivot_machine(l); }, py::arg("pivot_to_tip") = 150.0,
        "Former name of pivot_machine (kept for old scripts): NOT the paper's §3.1 machine.");
  p.def(
      "paper_machine_31",
      [](double d1, double d2, double l) {
        if (!std::isfinite(d1) || !(d2 > 0) || !std::isfinite(d2) || !(l > 0) || !std::isfinite(l))
          throw py::value_error("d1 finite, d2 and probe_length finite and > 0");
        return paper_machine_31({.d1 = d1, .d2 = d2, .probe_length = l});
      },
      py::arg("d1") = 30.0, py::arg("d2") = 120.0, py::arg("probe_length") = 40.0,
      "The paper's 3P+2R machine of §3.1 (joints x, y, z, a, b): rear end circle at (x + d1 cos a + d2 sin a cos b, "
      "y - d1 sin a + d2 cos a cos b, -z + d2 sin b), tip probe_length further along the probe axis.");
  p.def(
      "inverse_kinematics",
      [](const Robot& r, py::handle tip, py::handle axis, std::optional<std::vector<double>> previous) {
        auto q = inverse_kinematics(r, {vec(tip, "tip"), vec(axis, "axis")}, previous ? &*previous : nullptr);
        if (!q) raise_input_error(q.error());
        return std::move(q.value());
      },
      py::arg("robot"), py::arg("tip"), py::arg("axis"), py::arg("previous") = py::none(),
      "Joint values (x, y, z, a, b) of the §3.1 machine putting the tip at `tip` along `axis`, within the limits, "
      "nearest to `previous`; raises InputError naming the violated joint.");
  p.def(
      "pose_path_to_joints",
      [](const ProbePath& path, const Robot& r, const std::string& file) {
        auto j = pose_path_to_joint_path(path, r, file);
        if (!j) raise_input_error(j.error());
        return std::move(j.value());
      },
      py::arg("path"), py::arg("robot"), py::arg("file") = "<path>",
      "A pose path as the machine's joint path (inverse kinematics), so sweep(..., robot) checks the motion between "
      "points along the machine's joints.");
  p.def(
      "forward_kinematics",
      [](const Robot& r, const std::vector<double>& q) {
        if (q.size() != r.joints.size()) {
          throw py::value_error("q: expected " + std::to_string(r.joints.size()) + " joint values");
        }
        const ProbePose pose = forward_kinematics(r, q);
        return py::make_tuple(tup(pose.tip), tup(pose.axis));
      },
      py::arg("robot"), py::arg("q"), "(tip, axis) of the probe at joint values q (degrees for revolute joints).");
  p.def(
      "forward_pose",
      [](const Robot& r, const std::vector<double>& q) {
        if (q.size() != r.joints.size()) {
          throw py::value_error("q: expected " + std::to_string(r.joints.size()) + " joint values");
        }
        const ProbePose pose = forward_kinematics(r, q);
        return py::make_tuple(tup(pose.tip), tup(pose.axis), pose.has_ref() ? py::object(tup(pose.ref)) : py::object(py::none()));
      },
      py::arg("robot"), py::arg("q"),
      "(tip, axis, ref): forward_kinematics plus the holder reference direction (the tool's ref, default the "
      "last frame's x axis, made perpendicular to the axis; None when parallel).");
  p.def(
      "paper_end_circle",
      [](const std::array<double, 5>& q, double l) {
        const ProbePose pose = pivot_end_circle(q, l);
        return py::make_tuple(tup(pose.tip), tup(pose.axis));
      },
      py::arg("xyzab"), py::arg("pivot_to_tip") = 150.0,
      "The pivot machine's closed-form end-circle centre and axis (not §3.1's formula; former name kept).");

  p.def(
      "cylinder_triangle_intersect",
      [](py::handle c0, py::handle c1, double r, py::handle t) { return cylinder_triangle_intersect(cyl(c0, c1, r), tri(t)); },
      py::arg("c0"), py::arg("c1"), py::arg("radius"), py::arg("triangle"),
      "Exact: does the solid cylinder (axis segment c0-c1, radius) touch the triangle ((3, 3) points).");
  p.def(
      "cylinder_triangle_distance",
      [](py::handle c0, py::handle c1, double r, py::handle t) {
        const CylinderTriangleDistance d = cylinder_triangle_distance(cyl(c0, c1, r), tri(t));
        return py::make_tuple(d.distance, tup(d.on_cylinder), tup(d.on_triangle));
      },
      py::arg("c0"), py::arg("c1"), py::arg("radius"), py::arg("triangle"),
      "(distance, point on cylinder, point on triangle); distance 0 exactly when they touch.");
  p.def(
      "three_projection_test",
      [](py::handle c0, py::handle c1, double r, py::handle t, int edge) {
        return three_projection_test(cyl(c0, c1, r), tri(t), edge);
      },
      py::arg("c0"), py::arg("c1"), py::arg("radius"), py::arg("triangle"), py::arg("edge") = 0,
      "The paper's (incomplete) three-projection test as written (§3.4: along the axis, the triangle edge "
      "triangle[edge] -> triangle[edge + 1], a diameter), for comparison.");
  p.def(
      "paper_projections",
      [](py::handle c0, py::handle c1, double r, py::handle t, int edge, std::optional<std::array<double, 3>> d) {
        const PaperProjections x =
            paper_projections(cyl(c0, c1, r), tri(t), edge, d ? Vec3{(*d)[0], (*d)[1], (*d)[2]} : Vec3{});
        return py::make_tuple(x.along_axis, x.along_edge, x.along_diameter);
      },
      py::arg("c0"), py::arg("c1"), py::arg("radius"), py::arg("triangle"), py::arg("edge") = 0,
      py::arg("diameter") = py::none(),
      "(along the axis, along the edge, along the diameter): does each of the paper's §3.4 projections overlap.");
  p.def(
      "frame_projection_test",
      [](py::handle c0, py::handle c1, double r, py::handle t) { return frame_projection_test(cyl(c0, c1, r), tri(t)); },
      py::arg("c0"), py::arg("c1"), py::arg("radius"), py::arg("triangle"),
      "The project's earlier reconstruction (projections on the probe frame's planes; not §3.4), for comparison.");

  p.def(
      "box_triangle_intersect",
      [](py::handle centre, py::handle axes, const std::array<double, 3>& half, py::handle t) {
        return box_triangle_intersect(oriented_box(centre, axes, half), tri(t));
      },
      py::arg("centre"), py::arg("axes"), py::arg("half"), py::arg("triangle"),
      "Exact: does the solid oriented box (centre, 3 orthonormal axes, 3 half extents; the convex hull of its "
      "8 rounded corners) touch the triangle.");
  p.def(
      "box_triangle_distance",
      [](py::handle centre, py::handle axes, const std::array<double, 3>& half, py::handle t) {
        const BoxTriangleDistance d = box_triangle_distance(oriented_box(centre, axes, half), tri(t));
        return py::make_tuple(d.distance, tup(d.on_box), tup(d.on_triangle));
      },
      py::arg("centre"), py::arg("axes"), py::arg("half"), py::arg("triangle"),
      "(distance, point on box, point on triangle); distance 0 exactly when they touch.");
  p.def(
      "holder_box",
      [](py::handle tip, py::handle axis, py::handle ref, double probe_length, double width, double depth,
         double length) {
        const ProbeShape s{.length = probe_length, .holder_box_width = width, .holder_box_depth = depth,
                           .holder_box_length = length};
        if (!(probe_length > 0) || !s.has_holder_box() || !std::isfinite(probe_length + width + depth + length)) {
          throw py::value_error("holder_box: probe_length, width, depth and length must be finite numbers > 0");
        }
        ProbePose pose{vec(tip, "tip"), vec(axis, "axis")};
        if (!(norm(pose.axis) > 0)) throw py::value_error("axis: zero vector");
        pose.axis = pose.axis / norm(pose.axis);
        pose.ref = perpendicular_reference(vec(ref, "ref"), pose.axis);
        if (!pose.has_ref()) throw py::value_error("ref: zero or parallel to the axis");
        const OrientedBox b = probe_holder_box(s, pose);
        py::list corners;
        for (const Vec3& c : b.corners) corners.append(tup(c));
        return corners;
      },
      py::arg("tip"), py::arg("axis"), py::arg("ref"), py::arg("probe_length"), py::arg("width"), py::arg("depth"),
      py::arg("length"),
      "The 8 corners of the holder box (as sweep's holder_box_width/depth/length) behind a probe of "
      "probe_length at the pose (tip, axis, ref); corner i: bit 0 = +width (along ref), bit 1 = +depth "
      "(along axis x ref), bit 2 = front (the probe's back end circle).");

  p.def("make_panel", [](const std::string& kind, int nu, int nv) { return make_panel(panel_from(kind), nu, nv); },
        py::arg("kind"), py::arg("nu"), py::arg("nv"), "Curved panel ('sheet', 'shell', 'saddle'): 2 nu nv triangles.");

  py::class_<ProbePath>(p, "ProbePath", "Path points: joint values or probe poses, with their poses resolved.")
      .def_readonly("joint_space", &ProbePath::joint_space)
      .def_readonly("columns", &ProbePath::columns)
      .def_readonly("joints", &ProbePath::joints)
      .def_property_readonly("poses",
                             [](const ProbePath& path) {
                               py::list l;
                               for (const ProbePose& q : path.poses) l.append(py::make_tuple(tup(q.tip), tup(q.axis)));
                               return l;
                             })
      .def_property_readonly("refs",
                             [](const ProbePath& path) {
                               py::list l;
                               for (const ProbePose& q : path.poses) {
                                 l.append(q.has_ref() ? py::object(tup(q.ref)) : py::object(py::none()));
                               }
                               return l;
                             },
                             "Holder reference direction of every pose (None when unknown).")
      .def("__len__", &ProbePath::size)
      .def("to_csv", &path_to_csv);
  p.def(
      "make_panel_path",
      [](const std::string& kind, int lines, int points_per_line, double standoff, int collide_every) {
        return make_panel_path(panel_from(kind), {.lines = lines,
                                                  .points_per_line = points_per_line,
                                                  .standoff = standoff,
                                                  .collide_every = collide_every});
      },
      py::arg("kind"), py::arg("lines") = 8, py::arg("points_per_line") = 109, py::arg("standoff") = 10.0,
      py::arg("collide_every") = 97, "Raster joint path of the paper machine (pivot_to_tip 150) over a panel.");
  p.def(
      "read_path",
      [](const std::filesystem::path& file, std::optional<Robot> robot) {
        auto r = read_path_csv(file, robot ? &*robot : nullptr);
        if (!r) raise_input_error(r.error());
        if (r->joint_space) resolve_poses(*r, *robot);
        return std::move(r.value());
      },
      py::arg("path"), py::arg("robot") = py::none(), "Reads a path CSV; raises InputError naming file, line and field.");
  p.def(
      "pose_path",
      [](const std::vector<std::vector<std::array<double, 3>>>& poses) {
        ProbePath path;
        path.joint_space = false;
        path.columns = {"px", "py", "pz", "ax", "ay", "az"};
        const bool refs = !poses.empty() && poses[0].size() == 3;
        if (refs) path.columns.insert(path.columns.end(), {"rx", "ry", "rz"});
        std::int64_t line = 2;
        for (const auto& p : poses) {
          if (p.size() != (refs ? 3u : 2u)) {
            throw py::value_error("poses: every pose is (tip, axis) or every pose is (tip, axis, ref)");
          }
          const Vec3 axis{p[1][0], p[1][1], p[1][2]};
          if (!(norm(axis) > 0)) throw py::value_error("zero probe axis");
          ProbePose pose{{p[0][0], p[0][1], p[0][2]}, axis / norm(axis)};
          if (refs) {
            pose.ref = perpendicular_reference({p[2][0], p[2][1], p[2][2]}, pose.axis);
            if (!pose.has_ref()) throw py::value_error("reference direction zero or parallel to the probe axis");
          }
          path.poses.push_back(pose);
          path.lines.push_back(line++);
        }
        return path;
      },
      py::arg("poses"),
      "A pose path from [((px, py, pz), (ax, ay, az)), ...], or with the holder reference direction "
      "[((px, py, pz), (ax, ay, az), (rx, ry, rz)), ...].");

  p.def(
      "sweep",
      [](const TriMesh& mesh, const ProbePath& path, std::optional<Robot> robot, double radius, double length,
         double holder_radius, double holder_length, double box_width, double box_depth, double box_length,
         const std::string& hierarchy, double patch_rule, bool continuous, bool clearance, int depth, int threads) {
        if (!(radius > 0) || !(length > 0)) throw py::value_error("probe radius and length must be > 0");
        if (path.joint_space && !robot) throw py::value_error("a joint path needs a robot");
        const ProbeShape shape{.radius = radius, .length = length, .holder_radius = holder_radius,
                               .holder_length = holder_length, .holder_box_width = box_width,
                               .holder_box_depth = box_depth, .holder_box_length = box_length};
        const bool none = box_width == 0 && box_depth == 0 && box_length == 0;
        if (!none && !shape.has_holder_box()) {
          throw py::value_error("holder_box_width, holder_box_depth, holder_box_length: all > 0 or all 0");
        }
        if (shape.has_holder_box()) {
          if (!(std::isfinite(box_width) && std::isfinite(box_depth) && std::isfinite(box_length))) {
            throw py::value_error("holder box sizes must be finite");
          }
          if (const Status st = check_reference_frames(path, "path"); !st) throw py::value_error(st.error().message());
        }
        std::optional<tbb::global_control> limit;
        if (threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, threads);
        SweepResult r;
        Workpiece w;
        {
          py::gil_scoped_release release;
          w = prepare_workpiece(mesh, shape, {.hierarchy = hierarchy_from(hierarchy), .patch_volume_ratio = patch_rule});
          r = sweep(w, path, robot ? &*robot : nullptr,
                    {.probe = shape, .continuous = continuous, .clearance = clearance, .max_depth = depth});
        }
        py::list points;
        for (const PointResult& q : r.points) {
          py::dict d;
          d["collides"] = q.collides;
          d["inside"] = q.inside;
          d["verdict"] = verdict_name(q.verdict);
          d["holder"] = q.holder;
          d["clearance"] = num(q.clearance);
          d["triangle"] = q.triangle == kNone ? py::object(py::none()) : py::object(py::int_(q.triangle));
          d["patch"] = q.patch == kNone ? py::object(py::none()) : py::object(py::int_(q.patch));
          d["hits"] = q.hits;
          points.append(d);
        }
        py::list segs;
        for (const SegmentResult& s : r.segments) {
          py::dict d;
          d["from"] = s.from;
          d["state"] = segment_state_name(s.state);
          d["verdict"] = verdict_name(s.verdict);
          d["intervals"] = s.intervals;
          d["unresolved"] = s.unresolved;
          d["smallest_gap"] = num(s.smallest_gap);
          d["unresolved_motion"] = s.unresolved_motion;
          d["between_samples"] = s.between_samples;
          d["triangles"] = s.triangles;
          segs.append(d);
        }
        py::dict out;
        out["points"] = points;
        out["segments"] = segs;
        out["colliding_points"] = r.colliding_points;
        out["colliding_segments"] = r.colliding_segments;
        out["between_samples_segments"] = r.between_samples_segments;
        out["unresolved_segments"] = r.unresolved_segments;
        out["undecided_points"] = r.undecided_points;
        out["verdict"] = verdict_name(r.verdict);
        out["warnings"] = w.warnings;
        out["patches"] = w.patches.size();
        out["collision"] = r.any_collision();
        return out;
      },
      py::arg("workpiece"), py::arg("path"), py::arg("robot") = py::none(), py::arg("probe_radius") = 5.0,
      py::arg("probe_length") = 40.0, py::arg("holder_radius") = 0.0, py::arg("holder_length") = 0.0,
      py::arg("holder_box_width") = 0.0, py::arg("holder_box_depth") = 0.0, py::arg("holder_box_length") = 0.0,
      py::arg("hierarchy") = "bvh", py::arg("patch_rule") = 33.0, py::arg("continuous") = true,
      py::arg("clearance") = true, py::arg("depth") = 16, py::arg("threads") = 0,
      "Checks the path against the workpiece mesh; returns a dict (points with verdict; segments that are not clear, "
      "each with state 'collides' or 'unresolved', verdict, intervals, unresolved, smallest_gap; counts; verdict: "
      "the worst, 'undecided' where a segment could not be resolved, never clear; warnings). Releases the GIL.");
}

}  // namespace interfere::python
