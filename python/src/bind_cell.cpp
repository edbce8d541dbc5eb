// Python bindings of the inspection cell (issue #28; robot/cell.h, robot/ik.h): submodule
// `interfere.cell`. A cell file is read once (Cell, immutable from Python); run() checks it along a
// joint path or a pose path (numerical inverse kinematics) and returns per-point verdicts as numpy
// arrays, as `interfere cell` does. No geometry here: the scene engine decides every pair.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>

#include "bindings.h"
#include "interfere/probe/path.h"
#include "interfere/robot/cell.h"
#include "interfere/robot/ik.h"
#include "interfere/scene/engine.h"

namespace py = pybind11;

namespace interfere::python {
namespace {

using namespace interfere::robot;
using CellPtr = std::shared_ptr<Cell>;

py::array_t<double> vec_array(const Vec3& v) {
  py::array_t<double> a(3);
  auto m = a.mutable_unchecked<1>();
  m(0) = v.x, m(1) = v.y, m(2) = v.z;
  return a;
}

py::array_t<double> rows_array(const std::vector<std::vector<double>>& rows, std::size_t cols) {
  py::array_t<double> a({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(cols)});
  auto m = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < cols; ++j) m(i, j) = rows[i][j];
  return a;
}

py::array_t<std::int64_t> int_array(const std::vector<std::int64_t>& v) {
  py::array_t<std::int64_t> a(static_cast<py::ssize_t>(v.size()));
  auto m = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < v.size(); ++i) m(i) = v[i];
  return a;
}

py::object str_array(const std::vector<std::string>& v) {
  py::list l;
  for (const std::string& s : v) l.append(s);
  return py::module_::import("numpy").attr("array")(l, py::arg("dtype") = "U");
}

Vec3 vec3(const py::handle& h, const char* what) {
  const auto a = py::cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(h);
  if (a.ndim() != 1 || a.shape(0) != 3) throw py::value_error(std::string(what) + ": expected 3 numbers");
  const Vec3 v{a.at(0), a.at(1), a.at(2)};
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw py::value_error(std::string(what) + ": numbers must be finite");
  return v;
}

std::vector<double> joint_vector(const Cell& c, const py::handle& h, const char* what) {
  const auto a = py::cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(h);
  if (a.ndim() != 1 || static_cast<std::size_t>(a.shape(0)) != c.robot.dof()) {
    throw py::value_error(std::string(what) + ": expected " + std::to_string(c.robot.dof()) +
                          " joint values (the robot's movable joints in chain order)");
  }
  std::vector<double> q(a.data(), a.data() + a.shape(0));
  for (double v : q)
    if (!std::isfinite(v)) throw py::value_error(std::string(what) + ": values must be finite");
  return q;
}

/// A joint path from an (n, dof) array (lines 1..n) or a CSV file (header = joint names).
JointPath joint_path(const Cell& c, const py::handle& h) {
  if (py::isinstance<py::str>(h) || py::hasattr(h, "__fspath__")) {
    const auto file = py::cast<std::filesystem::path>(h);
    Expected<JointPath> p = read_joint_csv(file, c.robot);
    if (!p) raise_input_error(p.error());
    return std::move(*p);
  }
  const auto a = py::cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(h);
  if (a.ndim() != 2 || static_cast<std::size_t>(a.shape(1)) != c.robot.dof()) {
    throw py::value_error("joints: expected an (n, " + std::to_string(c.robot.dof()) +
                          ") array (the robot's movable joints in chain order) or a CSV file");
  }
  JointPath p;
  const auto m = a.unchecked<2>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    std::vector<double> q(static_cast<std::size_t>(a.shape(1)));
    for (py::ssize_t j = 0; j < a.shape(1); ++j) q[j] = m(i, j);
    for (double v : q)
      if (!std::isfinite(v)) throw py::value_error("joints: row " + std::to_string(i) + ": values must be finite");
    if (Status s = check_limits(c.robot, q); !s)
      throw py::value_error("joints: row " + std::to_string(i) + ": " + s.error().reason);
    p.q.push_back(std::move(q));
    p.lines.push_back(i + 1);
  }
  return p;
}

/// A pose path from a CSV file (sweep's pose header) or an (n, 6) / (n, 9) array (tip, axis[, ref]).
probe::ProbePath pose_path(const py::handle& h, std::string& name) {
  if (py::isinstance<py::str>(h) || py::hasattr(h, "__fspath__")) {
    const auto file = py::cast<std::filesystem::path>(h);
    name = file.string();
    Expected<probe::ProbePath> p = probe::read_path_csv(file, nullptr);
    if (!p) raise_input_error(p.error());
    return std::move(*p);
  }
  name = "<poses>";
  const auto a = py::cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(h);
  if (a.ndim() != 2 || (a.shape(1) != 6 && a.shape(1) != 9))
    throw py::value_error("poses: expected an (n, 6) array (tip, axis) or (n, 9) (tip, axis, ref), or a CSV file");
  probe::ProbePath p;
  p.joint_space = false;
  const auto m = a.unchecked<2>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    probe::ProbePose pose;
    pose.tip = {m(i, 0), m(i, 1), m(i, 2)};
    const Vec3 axis{m(i, 3), m(i, 4), m(i, 5)};
    if (!(norm(axis) > 0) || !std::isfinite(norm(axis)) || !std::isfinite(norm(pose.tip)))
      throw py::value_error("poses: row " + std::to_string(i) + ": finite tip and a non-zero axis needed");
    pose.axis = axis / norm(axis);
    if (a.shape(1) == 9) pose.ref = probe::perpendicular_reference({m(i, 6), m(i, 7), m(i, 8)}, pose.axis);
    p.poses.push_back(pose);
    p.lines.push_back(i + 1);
  }
  return p;
}

IkOptions ik_options(const Cell& c, const py::object& start) {
  IkOptions o;
  if (!start.is_none()) o.start = joint_vector(c, start, "start");
  return o;
}

py::dict ik_dict(const Cell& c, const py::object& poses, const py::object& start, JointPath& out) {
  std::string name;
  const probe::ProbePath p = pose_path(poses, name);
  Expected<PoseIkPath> r = pose_path_to_joints(c.robot, c.base, cell_ik_tool(c), p, name, ik_options(c, start));
  if (!r) raise_input_error(r.error());
  py::dict d;
  d["joints"] = rows_array(r->path.q, c.robot.dof());
  d["lines"] = int_array(r->path.lines);
  d["seed"] = str_array(r->seed);
  d["jump"] = py::array_t<double>(static_cast<py::ssize_t>(r->jump.size()), r->jump.data());
  d["tip_error"] = py::array_t<double>(static_cast<py::ssize_t>(r->position_error.size()), r->position_error.data());
  d["angle_error"] = py::array_t<double>(static_cast<py::ssize_t>(r->angle_error.size()), r->angle_error.data());
  out = std::move(r->path);
  return d;
}

py::dict run_cell(const Cell& c, const py::object& joints, const py::object& poses, const py::object& start,
                  std::size_t between, bool continuous, int max_depth, int threads, bool depth) {
  if (!joints.is_none() && !poses.is_none()) throw py::value_error("give joints or poses, not both");
  if (max_depth < 0 || max_depth > 40) throw py::value_error("max_depth must be in 0..40");
  JointPath path;
  py::object ik = py::none();
  if (!poses.is_none()) {
    ik = ik_dict(c, poses, start, path);
  } else if (!joints.is_none()) {
    path = joint_path(c, joints);
  } else {
    if (c.path.empty()) throw py::value_error("no joints or poses given and the cell file names no path");
    Expected<JointPath> p = read_joint_csv(c.path, c.robot);
    if (!p) raise_input_error(p.error());
    path = std::move(*p);
  }
  const std::size_t n = path.size();
  CellScene cs;
  scene::SceneClashResult r;
  std::vector<SegmentResult> segs;
  {
    ThreadLimit limit(threads);
    py::gil_scoped_release release;
    cs = cell_scene(c, path, between);
    scene::SceneClashOptions opt;
    opt.curves = false;
    opt.reference = false;
    opt.depth = depth;
    r = scene::clash_scene(cs.scene, cs.tests, opt);
    if (continuous) {
      BetweenOptions bo;
      bo.max_depth = max_depth;
      segs = check_between_points(c, cs, path, bo);
    }
  }
  // Per point and per sampled segment: the worst frame verdict (as interfere cell reports them).
  std::vector<Verdict> point_v(n, Verdict::clear), seg_v(n ? n - 1 : 0, Verdict::clear);
  for (std::size_t f = 0; f < cs.scene.frames.size() && f < r.frames.size(); ++f) {
    Verdict& t = cs.frame_t[f] == 0 ? point_v[cs.frame_point[f]] : seg_v[cs.frame_point[f]];
    t = worst(t, r.frames[f].verdict);
  }
  std::vector<std::string> pv, sv;
  std::vector<std::int64_t> colliding;
  py::array_t<bool> collides(static_cast<py::ssize_t>(n));
  for (std::size_t i = 0; i < n; ++i) {
    pv.push_back(verdict_name(point_v[i]));
    collides.mutable_at(i) = point_v[i] == Verdict::clash;
    if (point_v[i] == Verdict::clash) colliding.push_back(static_cast<std::int64_t>(i));
  }
  for (Verdict v : seg_v) sv.push_back(verdict_name(v));
  std::vector<std::vector<double>> tips, axes;
  for (std::size_t i = 0; i < n; ++i) {
    const std::vector<Transform> fr = link_frames(c.robot, path.q[i], c.base);
    const ToolCylinders tc = tool_cylinders(c.tool, fr[c.tool_link]);
    const Vec3 ax = (tc.tip - tc.back) / norm(tc.tip - tc.back);
    tips.push_back({tc.tip.x, tc.tip.y, tc.tip.z});
    axes.push_back({ax.x, ax.y, ax.z});
  }
  py::list pairs;
  for (const scene::FramePairRow& row : r.frame_pairs) {
    py::dict e;
    e["point"] = cs.frame_point[row.frame];
    e["t"] = cs.frame_t[row.frame];
    e["test"] = cs.tests[row.test].name;
    e["a"] = cs.scene.bodies[row.a].id;
    e["b"] = cs.scene.bodies[row.b].id;
    e["verdict"] = verdict_name(row.verdict);
    e["min_distance"] = row.min_distance >= 0 ? py::object(py::float_(row.min_distance)) : py::object(py::none());
    if (row.max_depth_bound > 0) e["depth"] = row.max_depth, e["depth_bound"] = row.max_depth_bound;  // depth=True
    pairs.append(e);
  }
  Verdict overall = r.verdict;
  py::dict d;
  d["points"] = n;
  d["lines"] = int_array(path.lines);
  d["joints"] = rows_array(path.q, c.robot.dof());
  d["tip"] = rows_array(tips, 3);
  d["axis"] = rows_array(axes, 3);
  d["verdicts"] = str_array(pv);
  d["collides"] = collides;
  d["colliding_points"] = int_array(colliding);
  d["segment_verdicts"] = str_array(sv);
  d["pairs"] = pairs;
  py::list bodies;
  for (const scene::Body& b : cs.scene.bodies) bodies.append(b.id);
  d["bodies"] = bodies;
  d["candidate_pairs"] = r.candidate_pairs;
  d["suppressed"] = r.suppressed;
  if (continuous) {
    std::vector<std::string> states;
    py::array_t<double> ts(static_cast<py::ssize_t>(segs.size()));
    for (std::size_t k = 0; k < segs.size(); ++k) {
      states.push_back(segment_state_name(segs[k].state));
      ts.mutable_at(k) = segs[k].state == SegmentState::collides ? segs[k].t : std::numeric_limits<double>::quiet_NaN();
      if (segs[k].state == SegmentState::collides) overall = worst(overall, Verdict::clash);
      if (segs[k].state == SegmentState::unresolved) overall = worst(overall, Verdict::undecided);
    }
    d["segment_states"] = str_array(states);
    d["segment_t"] = ts;
  }
  d["verdict"] = verdict_name(overall);
  d["ik"] = ik;
  return d;
}

}  // namespace

void bind_cell(py::module_& m) {
  py::module_ c = m.def_submodule("cell", "The whole inspection cell along a path (docs/probe.md, \"The whole cell\").");
  py::class_<Cell, CellPtr>(c, "Cell", "An inspection cell read from its JSON file (immutable).")
      .def_property_readonly("file", [](const Cell& x) { return x.file; })
      .def_property_readonly("urdf", [](const Cell& x) { return x.robot_format == "urdf" ? x.robot_file : std::string(); },
                             "the URDF file read ('' for a DH robot)")
      .def_property_readonly("robot_file", [](const Cell& x) { return x.robot_file; },
                             "the robot description read (URDF or DH robot JSON)")
      .def_property_readonly("robot_format", [](const Cell& x) { return x.robot_format; }, "'urdf' or 'dh'")
      .def_property_readonly("robot_name", [](const Cell& x) { return x.robot.name; })
      .def_property_readonly("dof", [](const Cell& x) { return x.robot.dof(); })
      .def_property_readonly("joint_names",
                             [](const Cell& x) {
                               std::vector<std::string> v;
                               for (std::size_t j : x.robot.movable) v.push_back(x.robot.joints[j].name);
                               return v;
                             },
                             "Movable joints in chain order (the columns of every joint array).")
      .def_property_readonly("limits",
                             [](const Cell& x) {
                               std::vector<std::vector<double>> v;
                               for (std::size_t j : x.robot.movable)
                                 v.push_back({x.robot.joints[j].lower, x.robot.joints[j].upper});
                               return rows_array(v, 2);
                             },
                             "(dof, 2) lower and upper limits (degrees, mm; continuous joints +-1e300).")
      .def_property_readonly("tool_link", [](const Cell& x) { return x.tool.link; })
      .def_property_readonly("path",
                             [](const Cell& x) { return x.path.empty() ? py::object(py::none()) : py::object(py::str(x.path)); },
                             "The joint path file the cell names (resolved), or None.")
      .def(
          "forward",
          [](const Cell& x, const py::object& q) {
            const std::vector<double> v = joint_vector(x, q, "q");
            const probe::ProbePose p = robot::tool_pose(x.robot, x.base, cell_ik_tool(x), v);
            return py::make_tuple(vec_array(p.tip), vec_array(p.axis));
          },
          py::arg("q"), "Probe tip and direction (world, mm) at joint values q (degrees, mm).")
      .def(
          "link_poses",
          [](const Cell& x, const py::object& q) {
            const std::vector<Transform> f = link_frames(x.robot, joint_vector(x, q, "q"), x.base);
            py::dict d;
            for (std::size_t k = 0; k < f.size(); ++k) {
              py::array_t<double> a({py::ssize_t{3}, py::ssize_t{4}});
              auto mm = a.mutable_unchecked<2>();
              const auto rows = f[k].to_rows();
              for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 4; ++j) mm(i, j) = rows[i][j];
              d[py::str(x.robot.links[k].name)] = a;
            }
            return d;
          },
          py::arg("q"), "Every link's pose (world <- link) as a (3, 4) array [R|t], by link name.")
      .def(
          "inverse_kinematics",
          [](const Cell& x, const py::object& tip, const py::object& axis, const py::object& ref,
             const py::object& previous, const py::object& start) {
            probe::ProbePose p;
            p.tip = vec3(tip, "tip");
            const Vec3 a = vec3(axis, "axis");
            if (!(norm(a) > 0)) throw py::value_error("axis: must not be zero");
            p.axis = a / norm(a);
            if (!ref.is_none()) p.ref = probe::perpendicular_reference(vec3(ref, "ref"), p.axis);
            std::optional<std::vector<double>> prev;
            if (!previous.is_none()) prev = joint_vector(x, previous, "previous");
            const IkOptions o = ik_options(x, start);
            IkSolution s;
            {
              py::gil_scoped_release release;
              s = solve_ik(x.robot, x.base, cell_ik_tool(x), p, prev ? &*prev : nullptr, o);
            }
            if (!s.ok) raise_input_error(Error{.file = x.file, .reason = "not reachable by robot '" + x.robot.name + "': " + s.reason});
            return py::array_t<double>(static_cast<py::ssize_t>(s.q.size()), s.q.data());
          },
          py::arg("tip"), py::arg("axis"), py::arg("ref") = py::none(), py::arg("previous") = py::none(),
          py::arg("start") = py::none(),
          "Joint values (degrees, mm) putting the probe tip at `tip` pointing along `axis` (and the tool "
          "link's x axis along `ref` when given), by damped least squares from `previous`, `start`, home and "
          "pseudo-random seeds (robot/ik.h). InputError when no seed reaches it (the reason says whether "
          "only outside the joint limits).")
      .def(
          "pose_path_to_joints",
          [](const Cell& x, const py::object& poses, const py::object& start) {
            JointPath p;
            return ik_dict(x, poses, start, p);
          },
          py::arg("poses"), py::arg("start") = py::none(),
          "A pose path (CSV file with sweep's pose header, or an (n, 6) / (n, 9) array: tip, axis[, ref]) "
          "as joints, each point from the previous one's solution: dict joints (n, dof), lines, seed, jump, "
          "tip_error, angle_error. InputError naming the line of an unreachable point.")
      .def(
          "read_joint_path",
          [](const Cell& x, const std::filesystem::path& file) {
            Expected<JointPath> p = read_joint_csv(file, x.robot);
            if (!p) raise_input_error(p.error());
            return py::make_tuple(rows_array(p->q, x.robot.dof()), int_array(p->lines));
          },
          py::arg("file"), "A joint path CSV (header = joint names, any order) as ((n, dof) array, lines).")
      .def(
          "run",
          [](const Cell& x, const py::object& joints, const py::object& poses, const py::object& start,
             std::size_t between, bool continuous, int max_depth, int threads, bool depth) {
            return run_cell(x, joints, poses, start, between, continuous, max_depth, threads, depth);
          },
          py::arg("joints") = py::none(), py::kw_only(), py::arg("poses") = py::none(), py::arg("start") = py::none(),
          py::arg("between") = 0, py::arg("continuous") = false, py::arg("max_depth") = 12, py::arg("threads") = 0,
          py::arg("depth") = false,
          "Checks the cell along a path, as `interfere cell`: `joints` an (n, dof) array or a joint CSV file, "
          "or `poses` (CSV file or (n, 6)/(n, 9) array; inverse kinematics, `start` picks the first point's "
          "branch), or neither (the cell's own path). Returns a dict: verdict, points, lines, joints (n, dof), "
          "tip and axis (n, 3), verdicts (n,) str, collides (n,) bool, colliding_points, segment_verdicts "
          "(sampled frames, `between` per segment), pairs (one dict per finding: point, t, test, a, b, "
          "verdict, min_distance; with `depth=True` depth and depth_bound of clashes, as `--depth`), bodies, candidate_pairs, suppressed, ik (pose paths), and with "
          "`continuous=True` segment_states (clear / collides / unresolved) and segment_t. Releases the GIL.");
  c.def(
      "read_cell",
      [](const std::filesystem::path& file) {
        Expected<Cell> x = read_cell_json(file);
        if (!x) raise_input_error(x.error());
        return std::make_shared<Cell>(std::move(*x));
      },
      py::arg("file"), "Reads a cell file (robot URDF, tool, workpiece, fixtures; docs/probe.md, \"Cell file\").");
  c.def("has_urdf_reader", &has_urdf_reader, "Whether this build reads URDF (urdfdom).");
}

}  // namespace interfere::python
