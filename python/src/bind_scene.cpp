// Python bindings of the scene layer (issue #24, item 7; docs/python.md, "Scenes"): Body, Scene,
// ClashTest, Scene.clash -> ClashReport of Clash objects, to_records() (plain dicts for pandas),
// to_json() (the CLI's report schema, scene/report.h) and to_csv(). As everywhere in the module,
// the bindings only convert arguments and results: selection, the engine, ids, baselines and the
// report are the library's (scene/*.h).
//
// Units: a Body keeps its geometry in the unit it was given in (Body.mesh_unit: `unit=`, or the
// file's); Scene.add stores a copy converted to the scene's working unit (Scene.units), as the CLI
// converts every input (issue #23, item 6). Poses are in the working unit (as in scene files).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "bindings.h"
#include "interfere/core/coordinate_range.h"
#include "interfere/core/units.h"
#include "interfere/fem/bodies.h"
#include "interfere/fem/io.h"
#include "interfere/mesh/io.h"
#include "interfere/scene/clash_test.h"
#include "interfere/scene/engine.h"
#include "interfere/scene/io.h"
#include "interfere/scene/load.h"
#include "interfere/scene/report.h"

namespace py = pybind11;

namespace interfere::python {
namespace {

namespace sc = interfere::scene;

// ---------------------------------------------------------------------------------------------
// Helpers (the module's conventions: numpy arrays out, errors as InputError / ValueError)



using interfere::python::raise_input_error;  // (bindings.h; overloaded below)
[[noreturn]] void raise_input_error(const std::string& file, const std::string& reason) {
  raise_input_error(Error{.file = file, .reason = reason});
}


py::object vec_np(const Vec3& v) {
  py::array_t<double> a(3);
  auto r = a.mutable_unchecked<1>();
  r(0) = v.x, r(1) = v.y, r(2) = v.z;
  return a;
}

py::object box_out(const Aabb& b) {
  if (b.empty()) return py::none();
  return py::make_tuple(py::make_tuple(b.lo.x, b.lo.y, b.lo.z),
                        py::make_tuple(b.hi.x, b.hi.y, b.hi.z));
}

template <class T>
py::object ints_np(const std::vector<T>& v, bool unsigned32 = false) {
  if (unsigned32) {
    py::array_t<std::uint32_t> a(static_cast<py::ssize_t>(v.size()));
    auto r = a.mutable_unchecked<1>();
    for (std::size_t i = 0; i < v.size(); ++i)
      r(static_cast<py::ssize_t>(i)) = static_cast<std::uint32_t>(v[i]);
    return a;
  }
  py::array_t<std::int64_t> a(static_cast<py::ssize_t>(v.size()));
  auto r = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < v.size(); ++i)
    r(static_cast<py::ssize_t>(i)) = static_cast<std::int64_t>(v[i]);
  return a;
}

double mm_per(const std::string& unit, const std::string& what) {
  const auto mm = millimetres_per_unit(unit);
  if (!mm) throw py::value_error(what + ": unknown unit '" + unit + "' (" + known_units() + ")");
  return *mm;
}

/// Anything Transform() accepts (12 numbers, 3x4, 4x4, a string, a Transform): the module's own
/// conversion, with its checks and its warning for a non-rigid pose.
Transform transform_from(py::handle obj) {
  if (obj.is_none()) return {};
  if (py::isinstance<Transform>(obj)) return obj.cast<Transform>();
  return py::type::of<Transform>()(obj).cast<Transform>();
}

/// A TriMesh from a TriMesh, or a (vertices, triangles) pair, through the module's TriMesh()
/// (shape, index and coordinate checks).
TriMesh mesh_from(py::handle mesh, py::handle positions, py::handle triangles) {
  if (!mesh.is_none()) {
    if (!positions.is_none() || !triangles.is_none())
      throw py::value_error("Body: give mesh= or positions=/triangles=, not both");
    if (py::isinstance<TriMesh>(mesh)) return mesh.cast<TriMesh>();
    if (py::isinstance<py::str>(mesh) || !PySequence_Check(mesh.ptr()) || py::len(mesh) != 2)
      throw py::type_error(
          "Body: mesh must be a TriMesh or a (vertices (n, 3), triangles (m, 3)) pair");
    py::sequence s = py::reinterpret_borrow<py::sequence>(mesh);
    return py::type::of<TriMesh>()(s[0], s[1]).cast<TriMesh>();
  }
  if (positions.is_none() || triangles.is_none())
    throw py::value_error("Body: a mesh is needed (mesh= or positions= and triangles=)");
  return py::type::of<TriMesh>()(positions, triangles).cast<TriMesh>();
}

std::vector<std::string> strings_from(py::handle obj, const std::string& what) {
  std::vector<std::string> out;
  if (obj.is_none()) return out;
  if (py::isinstance<py::str>(obj)) return {obj.cast<std::string>()};
  for (py::handle h : obj) {
    if (!py::isinstance<py::str>(h)) throw py::type_error(what + ": expected strings");
    out.push_back(h.cast<std::string>());
  }
  return out;
}

/// A selection from "sel1,sel2" or a list of selector strings; ValueError with the library's
/// message.
sc::Selection selection_from(py::handle obj, const std::string& what) {
  sc::Selection out;
  for (const std::string& text : strings_from(obj, what)) {
    const auto s = sc::parse_selection(text);
    if (!s) throw py::value_error(what + ": " + s.error().message());
    out.insert(out.end(), s->begin(), s->end());
  }
  return out;
}

py::list selection_out(const sc::Selection& s) {
  py::list l;
  for (const sc::Selector& x : s) l.append(x.to_string());
  return l;
}

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) raise_input_error(path, "cannot open the file");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string stem(const std::string& file) {
  return std::filesystem::path(file).stem().string();
}

std::string lower_ext(const std::string& file) {
  std::string e = std::filesystem::path(file).extension().string();
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

// ---------------------------------------------------------------------------------------------
// Body, Scene

/// A body as Python holds it: the library's Body with its geometry in `mesh_unit`.
struct PyBody {
  sc::Body body;
  std::string mesh_unit = "mm";
};

using NominalFit = std::function<bool(std::uint32_t, std::uint32_t, const Model&, const Model&,
                                      const ClashResult&, double)>;

struct PyScene {
  sc::Scene scene;
  std::vector<sc::ClashTest> tests;  ///< from a scene file's "tests"; clash()'s default when set
  std::vector<std::string> files;    ///< the files read (reported as the report's inputs)
  /// The nominal-fit check of the STEP assemblies read (scene/load.h), and what it refers to.
  NominalFit nominal_fit;
  /// Their zero-clearance fits (scene/load.h; issue #29: as assembly-clash classifies them).
  sc::SceneClashOptions::ZeroClearanceFits zero_clearance_fits;
  std::shared_ptr<void> keep_alive;
};

/// Every posed vertex within the supported coordinate range (issue #23, item 7).
void check_posed(const sc::Body& b) {
  std::vector<Vec3> w(b.mesh->positions.size());
  for (std::size_t i = 0; i < w.size(); ++i) w[i] = b.pose.apply(b.mesh->positions[i]);
  if (const std::size_t i = first_out_of_range(w); i < w.size())
    throw py::value_error("body '" + b.id + "': vertex " + std::to_string(i) +
                          " once converted and posed: " + coordinate_range_reason(w[i]));
}

/// Adds `b` (geometry in `mesh_unit`) to the scene, converted to the scene's unit.
void add_body(PyScene& s, sc::Body b, const std::string& mesh_unit) {
  if (b.id.empty()) throw py::value_error("Scene.add: a body needs a non-empty id");
  if (s.scene.find(b.id) >= 0) throw py::value_error("Scene.add: duplicate body id '" + b.id + "'");
  if (!b.mesh || b.mesh->num_triangles() == 0)
    throw py::value_error("Scene.add: body '" + b.id + "' has no triangles");
  const double scale =
      mm_per(mesh_unit, "body '" + b.id + "' unit") / mm_per(s.scene.units, "scene units");
  if (scale != 1) {
    TriMesh m = *b.mesh;
    for (Vec3& v : m.positions) v = v * scale;
    b.mesh = std::make_shared<const TriMesh>(std::move(m));
  }
  check_posed(b);
  s.scene.bodies.push_back(std::move(b));
}

PyBody body_from_file(const std::string& path, const std::string& id, const std::string& units) {
  const std::string ext = lower_ext(path);
  const std::string unit = !units.empty() ? units : (ext == ".glb" || ext == ".gltf") ? "m" : "mm";
  mm_per(unit, "units");
  std::optional<Expected<TriMesh>> r;
  {
    py::gil_scoped_release release;
    r.emplace(read_mesh(path, ReadOptions{.weld = true}));
  }
  if (!*r) raise_input_error(r->error());
  PyBody p;
  p.mesh_unit = unit;
  sc::Body& b = p.body;
  b.id = id.empty() ? sc::make_body_id(stem(path)) : id;
  b.name = stem(path);
  b.path = "/" + b.name;
  b.source = {sc::SourceKind::mesh_file, path, ""};
  b.unit = unit;
  b.mesh = std::make_shared<const TriMesh>(std::move(r->value()));
  return p;
}

PyScene scene_from_file(const std::string& path, const std::string& units_arg) {
  const auto spec = sc::read_scene_file(path);
  if (!spec) raise_input_error(spec.error());
  PyScene s;
  s.scene.units = !units_arg.empty() ? units_arg : !spec->units.empty() ? spec->units : "mm";
  mm_per(s.scene.units, "units");
  s.files.push_back(path);
  {  // every entry through the library's loader (scene/load.h), as the CLI reads them
    std::optional<Expected<sc::LoadedScene>> r;
    {
      py::gil_scoped_release release;
      r.emplace(sc::load_scene(spec->bodies, sc::LoadOptions{.units = s.scene.units}));
    }
    if (!*r) raise_input_error(r->error());
    sc::LoadedScene& l = r->value();
    s.scene = std::move(l.scene);
    s.files.insert(s.files.end(), l.files.begin(), l.files.end());
    s.nominal_fit = std::move(l.nominal_fit);
    s.zero_clearance_fits = std::move(l.zero_clearance_fits);
    s.keep_alive = std::move(l.keep_alive);
  }
  s.tests = spec->tests;
  if (!spec->motion.empty()) {
    if (!s.scene.frames.empty())
      raise_input_error(path, "motion: the scene already has steps from an FE input");
    if (const Status st = sc::read_motion(spec->motion, s.scene); !st)
      raise_input_error(st.error());
    s.files.push_back(spec->motion);
  }
  return s;
}

// ---------------------------------------------------------------------------------------------
// ClashTest

sc::ClashMode mode_from(const std::string& text) {
  const auto m = sc::parse_clash_mode(text);
  if (!m) throw py::value_error("mode: " + m.error().message());
  return *m;
}

sc::ClashTest make_test(const std::string& name, py::handle a, py::handle b,
                        const std::string& mode, double tolerance, double clearance,
                        py::handle suppress, py::handle overrides, double id_grid, bool nominal) {
  sc::ClashTest t;
  t.name = name;
  t.a = selection_from(a, "a");
  t.b = selection_from(b, "b");
  t.mode = mode_from(mode);
  t.tolerance = tolerance;
  t.clearance = clearance;
  t.id_grid = id_grid;
  t.nominal_fits_are_contacts = nominal;
  if (!suppress.is_none()) {
    std::size_t k = 0;
    for (py::handle h : suppress) {
      const std::string w = "suppress[" + std::to_string(k++) + "]";
      if (py::isinstance<py::str>(h) || !PySequence_Check(h.ptr()) || py::len(h) < 2 ||
          py::len(h) > 3)
        throw py::value_error(w + ": expected (selection_a, selection_b[, reason])");
      py::sequence s = py::reinterpret_borrow<py::sequence>(h);
      sc::Suppression x{selection_from(s[0], w + " a"), selection_from(s[1], w + " b"),
                        py::len(s) == 3 ? py::str(s[2]).cast<std::string>() : std::string()};
      t.suppressions.push_back(std::move(x));
    }
  }
  if (!overrides.is_none()) {
    std::size_t k = 0;
    for (py::handle h : overrides) {
      const std::string w = "clearance_overrides[" + std::to_string(k++) + "]";
      if (py::isinstance<py::str>(h) || !PySequence_Check(h.ptr()) || py::len(h) != 3)
        throw py::value_error(w + ": expected (selection_a, selection_b, clearance)");
      py::sequence s = py::reinterpret_borrow<py::sequence>(h);
      const double d = s[2].cast<double>();
      if (!(d >= 0) || !std::isfinite(d))
        throw py::value_error(w + ": the clearance must be a finite number >= 0");
      t.clearance_overrides.push_back(
          {selection_from(s[0], w + " a"), selection_from(s[1], w + " b"), d});
    }
  }
  t.validate();  // std::invalid_argument -> ValueError
  return t;
}

sc::ClashTest parse_test(const std::string& text) {
  const auto t = sc::parse_clash_test(text);
  if (!t) throw py::value_error(t.error().message());
  t->validate();
  return *t;
}

std::vector<sc::ClashTest> tests_from(py::handle obj, const PyScene& s) {
  std::vector<sc::ClashTest> out;
  if (obj.is_none()) {
    if (!s.tests.empty()) return s.tests;
    return {sc::ClashTest{}};
  }
  const auto one = [&](py::handle h) {
    if (py::isinstance<sc::ClashTest>(h)) return h.cast<sc::ClashTest>();
    if (py::isinstance<py::str>(h)) return parse_test(h.cast<std::string>());
    throw py::type_error("tests: expected ClashTest objects or test strings");
  };
  if (py::isinstance<sc::ClashTest>(obj) || py::isinstance<py::str>(obj)) return {one(obj)};
  for (py::handle h : obj) out.push_back(one(h));
  if (out.empty())
    throw py::value_error("tests: an empty list (None runs the default all-pairs hard test)");
  return out;
}

// ---------------------------------------------------------------------------------------------
// Results

struct ReportData {
  sc::Scene scene;
  std::vector<sc::ClashTest> tests;
  sc::SceneClashResult result;
  std::vector<std::string> inputs;
  int threads = 0;
  double seconds = 0;
};

struct PyReport {
  std::shared_ptr<const ReportData> d;
};

/// One clash of a report (resolved: one of the baseline's clashes no longer found).
struct PyClash {
  std::shared_ptr<const ReportData> d;
  std::size_t index = 0;
  bool resolved = false;
  const sc::SceneClash& c() const {
    return resolved ? d->result.resolved[index] : d->result.clashes[index];
  }
};

py::object json_loads(const std::string& text) {
  return py::module_::import("json").attr("loads")(text);
}

py::dict user_fields(const sc::SceneClash& c) {
  py::dict u;
  for (const auto& [k, v] : c.user_fields) u[py::str(k)] = json_loads(v);
  return u;
}

/// A resolved clash's field from its baseline JSON (None when absent).
py::object baseline_field(const PyClash& x, const char* key) {
  py::dict j = json_loads(x.c().baseline_json);
  return j.contains(key) ? py::object(j[key]) : py::object(py::none());
}

py::object baseline_body(const PyClash& x, const char* body, const char* key) {
  py::object b = baseline_field(x, body);
  if (!py::isinstance<py::dict>(b)) return py::none();
  py::dict d = b;
  return d.contains(key) ? py::object(d[key]) : py::object(py::none());
}

std::string user_status_or(const sc::SceneClash& c, const std::string& run) {
  const auto it = c.user_fields.find("status");
  if (it == c.user_fields.end()) return run;
  py::object v = json_loads(it->second);
  return py::isinstance<py::str>(v) ? v.cast<std::string>() : std::string(py::str(v));
}

py::object body_field(const PyClash& x, bool a, const char* key) {
  if (x.resolved) return baseline_body(x, a ? "body_a" : "body_b", key);
  const sc::Body& b = x.d->scene.bodies[a ? x.c().a : x.c().b];
  const std::string k = key;
  return py::str(k == "id" ? b.id : k == "name" ? b.name : b.path);
}

py::object num_field(const PyClash& x, const char* key, double v) {
  if (!x.resolved) return py::float_(v);
  return baseline_field(x, key);
}

/// The flat record of one clash (to_records): scalars only.
py::dict record(const PyClash& x) {
  const sc::SceneClash& c = x.c();
  py::dict r;
  r["id"] = c.id;
  r["test"] = c.test;
  const std::string run = sc::clash_status_name(c.status);
  r["status"] = user_status_or(c, run);
  r["run_status"] = run;
  r["verdict"] =
      x.resolved ? baseline_field(x, "verdict") : py::object(py::str(verdict_name(c.verdict)));
  r["kind"] = c.kind;
  for (const bool a : {true, false}) {
    const std::string s = a ? "a" : "b";
    r[py::str("body_" + s)] = body_field(x, a, "id");
    r[py::str("name_" + s)] = body_field(x, a, "name");
    r[py::str("path_" + s)] = body_field(x, a, "path");
  }
  r["depth"] = num_field(x, "depth", c.depth);
  r["depth_bound"] = num_field(x, "depth_bound", c.depth_bound);
  r["distance"] = num_field(x, "distance", c.distance);
  if (x.resolved) {
    py::object p = baseline_field(x, "point");
    const bool ok = py::isinstance<py::list>(p) && py::len(p) == 3;
    r["x"] = ok ? py::object(p[py::int_(0)]) : py::object(py::none());
    r["y"] = ok ? py::object(p[py::int_(1)]) : py::object(py::none());
    r["z"] = ok ? py::object(p[py::int_(2)]) : py::object(py::none());
  } else {
    r["x"] = c.point.x, r["y"] = c.point.y, r["z"] = c.point.z;
  }
  const char* box_keys[2][3] = {{"box_min_x", "box_min_y", "box_min_z"},
                                {"box_max_x", "box_max_y", "box_max_z"}};
  for (int e = 0; e < 2; ++e) {
    const Vec3& p = e == 0 ? c.box.lo : c.box.hi;
    for (int k = 0; k < 3; ++k)
      r[box_keys[e][k]] =
          x.resolved || c.box.empty() ? py::object(py::none()) : py::object(py::float_(p[k]));
  }
  r["curve_length"] = num_field(x, "curve_length", c.curve_length);
  r["cross_pairs"] =
      x.resolved ? baseline_field(x, "cross_pairs") : py::object(py::int_(c.cross_pairs));
  r["touch_pairs"] =
      x.resolved ? baseline_field(x, "touch_pairs") : py::object(py::int_(c.touch_pairs));
  r["triangles_a"] = x.resolved ? baseline_field(x, "triangle_count_a")
                                : py::object(py::int_(c.triangles_a.size()));
  r["triangles_b"] = x.resolved ? baseline_field(x, "triangle_count_b")
                                : py::object(py::int_(c.triangles_b.size()));
  r["first_frame"] =
      c.frames.empty() ? py::object(py::none()) : py::object(py::int_(c.frames.front()));
  r["frames"] = c.frames.size();
  for (const auto& [k, v] : c.user_fields)
    if (k != "status" && !r.contains(k)) r[py::str(k)] = json_loads(v);
  return r;
}

py::dict summary(const sc::SceneClashResult& r) {
  py::dict d;
  d["verdict"] = verdict_name(r.verdict);
  d["bodies"] = r.bodies;
  d["triangles"] = r.triangles;
  d["candidate_pairs"] = r.candidate_pairs;
  d["suppressed"] = r.suppressed;
  d["core_runs"] = r.core_runs;
  d["clashes"] = r.clash_count;
  d["contacts"] = r.contact_count;
  d["clearances"] = r.clearance_count;
  d["undecided"] = r.undecided_count;
  d["resolved"] = r.resolved.size();
  d["frames"] = r.frames.size();
  return d;
}

sc::ReportContext context(const ReportData& d) {
  sc::ReportContext ctx;
  ctx.command = "clash";  // (the CLI clash report, docs/schema/clash.schema.json)
  ctx.tool_version = INTERFERE_VERSION;
  ctx.inputs = d.inputs;
  ctx.threads = d.threads;
  ctx.total_seconds = d.seconds;
  ctx.exit_status = verdict_exit_status(d.result.verdict);
  return ctx;
}

/// Baseline argument: None, a dict (an earlier report as json.loads gives it), a ClashReport, JSON
/// text (starting with '{'), or a path.
std::optional<std::pair<std::string, std::string>> baseline_from(py::handle obj) {
  if (obj.is_none()) return std::nullopt;
  if (py::isinstance<PyReport>(obj)) {
    const PyReport& r = obj.cast<const PyReport&>();
    return std::make_pair(sc::report_json(r.d->scene, r.d->tests, r.d->result, context(*r.d)),
                          std::string("<baseline report>"));
  }
  if (py::isinstance<py::dict>(obj))
    return std::make_pair(py::module_::import("json").attr("dumps")(obj).cast<std::string>(),
                          std::string("<baseline dict>"));
  if (py::isinstance<py::str>(obj)) {
    const std::string s = obj.cast<std::string>();
    const auto first = s.find_first_not_of(" \t\r\n");
    if (first != std::string::npos && s[first] == '{')
      return std::make_pair(s, std::string("<baseline text>"));
    return std::make_pair(read_text_file(s), s);
  }
  if (py::hasattr(obj, "__fspath__")) {
    const std::string p = py::module_::import("os").attr("fspath")(obj).cast<std::string>();
    return std::make_pair(read_text_file(p), p);
  }
  throw py::type_error("baseline: expected None, a path, JSON text, a dict or a ClashReport");
}

sc::GroupBy group_from(py::handle obj) {
  if (obj.is_none()) return sc::GroupBy::none;
  const std::string g = obj.cast<std::string>();
  if (g == "pair") return sc::GroupBy::pair;
  if (g == "location") return sc::GroupBy::location;
  if (g == "none") return sc::GroupBy::none;
  throw py::value_error("group_by: '" + g + "' (pair, location or None)");
}

PyReport run_clash(const PyScene& s, py::handle tests_arg, py::handle baseline_arg,
                   py::handle group_by, double group_distance, py::handle threads_arg, bool depth,
                   bool curves) {
  auto d = std::make_shared<ReportData>();
  d->tests = tests_from(tests_arg, s);
  d->scene = s.scene;  // a snapshot: bodies share their meshes
  d->inputs = s.files;
  const auto baseline = baseline_from(baseline_arg);
  sc::SceneClashOptions o;
  o.group_by = group_from(group_by);
  if (!(group_distance >= 0) || !std::isfinite(group_distance))
    throw py::value_error("group_distance must be a finite number >= 0");
  o.group_distance = group_distance;
  o.depth = depth;
  o.curves = curves;
  o.nominal_fit = s.nominal_fit;
  o.zero_clearance_fits = s.zero_clearance_fits;
  const int threads = threads_arg.is_none() ? 0 : threads_arg.cast<int>();
  d->threads = threads;
  ThreadLimit limit(threads, "0 or None = all cores");
  Status st;
  {
    py::gil_scoped_release release;
    const auto t0 = std::chrono::steady_clock::now();
    d->result = sc::clash_scene(d->scene, d->tests, o);  // std::invalid_argument -> ValueError
    if (baseline) st = sc::apply_baseline(d->result, baseline->first, baseline->second);
    d->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  if (!st) raise_input_error(st.error());
  return PyReport{std::move(d)};
}

py::list clash_list(const PyReport& r, bool resolved) {
  py::list l;
  const std::size_t n = resolved ? r.d->result.resolved.size() : r.d->result.clashes.size();
  for (std::size_t i = 0; i < n; ++i) l.append(py::cast(PyClash{r.d, i, resolved}));
  return l;
}

py::object body_out(const sc::Body& b, const std::string& mesh_unit) {
  return py::cast(PyBody{b, mesh_unit});
}

}  // namespace

void bind_scene(py::module_& m) {
  // ---- Body ----
  py::class_<PyBody>(
      m, "Body",
      "One body of a scene: a stable id, name, product path, source, unit, pose, tags and its "
      "triangles (with per-triangle source ids). Geometry is in `mesh_unit`; Scene.add converts "
      "a copy to the scene's unit.")
      .def(py::init([](const std::string& id, py::handle mesh, py::handle positions,
                       py::handle triangles, const std::string& name, const std::string& path,
                       py::handle pose, py::handle tags, const std::string& unit,
                       py::handle source_ids) {
             PyBody p;
             mm_per(unit, "unit");
             p.mesh_unit = unit;
             sc::Body& b = p.body;
             b.id = id;
             if (id.empty()) throw py::value_error("Body: the id must not be empty");
             b.name = name.empty() ? id : name;
             b.path = path.empty() ? "/" + b.name : path;
             b.unit = unit;
             b.mesh = std::make_shared<const TriMesh>(mesh_from(mesh, positions, triangles));
             b.pose = transform_from(pose);
             b.tags = strings_from(tags, "tags");
             if (!source_ids.is_none()) {
               std::vector<std::int64_t> ids;
               for (py::handle h : py::iter(source_ids)) ids.push_back(h.cast<std::int64_t>());
               if (ids.size() != b.mesh->num_triangles())
                 throw py::value_error("Body: source_ids needs one id per triangle (" +
                                       std::to_string(b.mesh->num_triangles()) + "), got " +
                                       std::to_string(ids.size()));
               b.source_ids = std::make_shared<const std::vector<std::int64_t>>(std::move(ids));
             }
             return p;
           }),
           py::arg("id"), py::arg("mesh") = py::none(), py::kw_only(),
           py::arg("positions") = py::none(), py::arg("triangles") = py::none(),
           py::arg("name") = "", py::arg("path") = "", py::arg("pose") = py::none(),
           py::arg("tags") = py::none(), py::arg("unit") = "mm", py::arg("source_ids") = py::none(),
           "Body(id, mesh=TriMesh | (vertices (n, 3), triangles (m, 3)), *, positions=, "
           "triangles=, name=id, "
           "path='/'+name, pose=None (anything Transform() takes), tags=[], unit='mm', "
           "source_ids=None).")
      .def_static(
          "from_file",
          [](const std::filesystem::path& path, const std::optional<std::string>& id,
             const std::optional<std::string>& units) {
            return body_from_file(path.string(), id.value_or(""), units.value_or(""));
          },
          py::arg("path"), py::arg("id") = py::none(), py::arg("units") = py::none(),
          "Reads a mesh file (read_mesh: STL, OBJ, PLY, OFF, glTF flattened; welded). id: the "
          "file's stem by "
          "default; units: the file's unit (default mm, glTF m). Raises InputError.")
      .def_property(
          "id", [](const PyBody& p) { return p.body.id; },
          [](PyBody& p, const std::string& v) { p.body.id = v; })
      .def_property(
          "name", [](const PyBody& p) { return p.body.name; },
          [](PyBody& p, const std::string& v) { p.body.name = v; })
      .def_property(
          "path", [](const PyBody& p) { return p.body.path; },
          [](PyBody& p, const std::string& v) { p.body.path = v; })
      .def_property(
          "tags", [](const PyBody& p) { return p.body.tags; },
          [](PyBody& p, py::handle v) { p.body.tags = strings_from(v, "tags"); })
      .def_property(
          "pose", [](const PyBody& p) { return p.body.pose; },
          [](PyBody& p, py::handle v) { p.body.pose = transform_from(v); },
          "Local -> world (a Transform).")
      .def_property_readonly(
          "unit", [](const PyBody& p) { return p.body.unit; }, "The source's unit.")
      .def_property_readonly(
          "mesh_unit", [](const PyBody& p) { return p.mesh_unit; },
          "The unit the body's geometry is in now (the scene's once added).")
      .def_property_readonly(
          "mesh", [](const PyBody& p) { return TriMesh(*p.body.mesh); },
          "A copy (local coordinates).")
      .def_property_readonly("num_triangles",
                             [](const PyBody& p) { return p.body.mesh->num_triangles(); })
      .def_property_readonly("num_vertices",
                             [](const PyBody& p) { return p.body.mesh->num_vertices(); })
      .def_property_readonly(
          "source_kind", [](const PyBody& p) { return sc::source_kind_name(p.body.source.kind); })
      .def_property_readonly("source_file", [](const PyBody& p) { return p.body.source.file; })
      .def_property_readonly("source_detail", [](const PyBody& p) { return p.body.source.detail; })
      .def_property_readonly(
          "source_id_kind",
          [](const PyBody& p) { return sc::source_id_kind_name(p.body.source_id_kind); })
      .def_property_readonly(
          "source_ids",
          [](const PyBody& p) {
            std::vector<std::int64_t> v(p.body.mesh->num_triangles());
            for (std::size_t i = 0; i < v.size(); ++i)
              v[i] = p.body.source_id(static_cast<std::uint32_t>(i));
            return ints_np(v);
          },
          "Per triangle: what it came from (input triangle, FE element, B-Rep face), int64.")
      .def_property_readonly("tessellation_error",
                             [](const PyBody& p) { return p.body.tessellation_error; })
      .def("__repr__", [](const PyBody& p) {
        return "Body(id='" + p.body.id +
               "', triangles=" + std::to_string(p.body.mesh->num_triangles()) + ", unit='" +
               p.mesh_unit + "')";
      });

  // ---- ClashTest ----
  py::class_<sc::ClashTest>(
      m, "ClashTest",
      "A clash test: selection a against selection b (or all pairs within a), mode hard "
      "(penetration tolerance), clearance or duplicates, suppression rules, clearance "
      "overrides. Selectors: 'kind:glob' with kind id, name, path, tag, file, source; a bare "
      "glob is a name; '*' or 'all' selects every body.")
      .def(py::init(&make_test), py::arg("name") = "default", py::arg("a") = "*",
           py::arg("b") = py::none(), py::arg("mode") = "hard", py::arg("tolerance") = 0.0,
           py::arg("clearance") = 0.0, py::arg("suppress") = py::none(),
           py::arg("clearance_overrides") = py::none(), py::arg("id_grid") = 0.0,
           py::arg("nominal_fits_are_contacts") = true,
           "a, b: a selection string ('tag:bolt,name:Plate*') or a list of selectors; b=None: all "
           "pairs within a. "
           "suppress: [(sel_a, sel_b, reason)], clearance_overrides: [(sel_a, sel_b, clearance)]. "
           "ValueError on bad "
           "selectors, modes or values.")
      .def_static("parse", &parse_test, py::arg("text"),
                  "The CLI's --test text: 'NAME: SEL_A [vs SEL_B] [hard|clearance D|duplicates] "
                  "[tolerance T]'.")
      .def_readonly("name", &sc::ClashTest::name)
      .def_property_readonly("a", [](const sc::ClashTest& t) { return selection_out(t.a); })
      .def_property_readonly("b", [](const sc::ClashTest& t) { return selection_out(t.b); })
      .def_property_readonly("mode",
                             [](const sc::ClashTest& t) { return sc::clash_mode_name(t.mode); })
      .def_readonly("tolerance", &sc::ClashTest::tolerance)
      .def_readonly("clearance", &sc::ClashTest::clearance)
      .def_readonly("id_grid", &sc::ClashTest::id_grid)
      .def_readonly("nominal_fits_are_contacts", &sc::ClashTest::nominal_fits_are_contacts)
      .def_property_readonly(
          "suppress",
          [](const sc::ClashTest& t) {
            py::list l;
            for (const auto& s : t.suppressions)
              l.append(py::make_tuple(selection_out(s.a), selection_out(s.b), s.reason));
            return l;
          })
      .def_property_readonly(
          "clearance_overrides",
          [](const sc::ClashTest& t) {
            py::list l;
            for (const auto& o : t.clearance_overrides)
              l.append(py::make_tuple(selection_out(o.a), selection_out(o.b), o.clearance));
            return l;
          })
      .def("__repr__", [](const sc::ClashTest& t) {
        std::string s =
            "ClashTest(name='" + t.name + "', a=" + std::string(py::repr(selection_out(t.a)));
        if (!t.b.empty()) s += ", b=" + std::string(py::repr(selection_out(t.b)));
        s += ", mode='" + std::string(sc::clash_mode_name(t.mode)) + "'";
        if (t.tolerance > 0) s += ", tolerance=" + std::string(py::repr(py::float_(t.tolerance)));
        if (t.mode == sc::ClashMode::clearance)
          s += ", clearance=" + std::string(py::repr(py::float_(t.clearance)));
        return s + ")";
      });

  // ---- Clash ----
  py::class_<PyClash>(
      m, "Clash",
      "One clash of a ClashReport (a connected clash region of a body pair, a body inside "
      "another, a clearance violation or a duplicate), or a resolved baseline clash.")
      .def_property_readonly(
          "id", [](const PyClash& x) { return x.c().id; }, "Stable id (survives reordering).")
      .def_property_readonly("test", [](const PyClash& x) { return x.c().test; })
      .def_property_readonly(
          "status",
          [](const PyClash& x) {
            return user_status_or(x.c(), sc::clash_status_name(x.c().status));
          },
          "The user's status carried from the baseline ('approved', ...) when set, else "
          "run_status.")
      .def_property_readonly(
          "run_status", [](const PyClash& x) { return sc::clash_status_name(x.c().status); },
          "'new', 'active' or 'resolved' against the baseline.")
      .def_property_readonly("verdict",
                             [](const PyClash& x) {
                               return x.resolved ? baseline_field(x, "verdict")
                                                 : py::object(py::str(verdict_name(x.c().verdict)));
                             })
      .def_property_readonly("kind", [](const PyClash& x) { return x.c().kind; })
      .def_property_readonly("body_a", [](const PyClash& x) { return body_field(x, true, "id"); })
      .def_property_readonly("body_b", [](const PyClash& x) { return body_field(x, false, "id"); })
      .def_property_readonly("name_a", [](const PyClash& x) { return body_field(x, true, "name"); })
      .def_property_readonly("name_b",
                             [](const PyClash& x) { return body_field(x, false, "name"); })
      .def_property_readonly("path_a", [](const PyClash& x) { return body_field(x, true, "path"); })
      .def_property_readonly("path_b",
                             [](const PyClash& x) { return body_field(x, false, "path"); })
      .def_property_readonly(
          "depth", [](const PyClash& x) { return num_field(x, "depth", x.c().depth); },
          "Sampled depth (a lower bound) of crossing bodies.")
      .def_property_readonly(
          "depth_bound",
          [](const PyClash& x) { return num_field(x, "depth_bound", x.c().depth_bound); },
          "Proven upper bound of the depth.")
      .def_property_readonly(
          "distance", [](const PyClash& x) { return num_field(x, "distance", x.c().distance); },
          "Clearance: the smallest distance; 0 when the bodies meet.")
      .def_property_readonly(
          "point",
          [](const PyClash& x) {
            if (x.resolved) return baseline_field(x, "point");
            return vec_np(x.c().point);
          },
          "A representative point (world), numpy (3,) float64.")
      .def_property_readonly(
          "box",
          [](const PyClash& x) { return x.resolved ? py::object(py::none()) : box_out(x.c().box); },
          "((xmin, ymin, zmin), (xmax, ymax, zmax)) of the curves and contact region.")
      .def_property_readonly(
          "curve_length",
          [](const PyClash& x) { return num_field(x, "curve_length", x.c().curve_length); })
      .def_property_readonly(
          "curves", [](const PyClash& x) { return x.c().curves; }, "Intersection curves (world).")
      .def_property_readonly("cross_pairs", [](const PyClash& x) { return x.c().cross_pairs; })
      .def_property_readonly("touch_pairs", [](const PyClash& x) { return x.c().touch_pairs; })
      .def_property_readonly("triangles_a",
                             [](const PyClash& x) { return ints_np(x.c().triangles_a, true); })
      .def_property_readonly("triangles_b",
                             [](const PyClash& x) { return ints_np(x.c().triangles_b, true); })
      .def_property_readonly("source_ids_a",
                             [](const PyClash& x) { return ints_np(x.c().source_ids_a); })
      .def_property_readonly("source_ids_b",
                             [](const PyClash& x) { return ints_np(x.c().source_ids_b); })
      .def_property_readonly("witness_a", [](const PyClash& x) { return vec_np(x.c().witness_a); })
      .def_property_readonly("witness_b", [](const PyClash& x) { return vec_np(x.c().witness_b); })
      .def_property_readonly("reasons", [](const PyClash& x) { return x.c().reasons; })
      .def_property_readonly(
          "frames", [](const PyClash& x) { return x.c().frames; },
          "The frames it is present in (motion); empty when static.")
      .def_property_readonly(
          "user_fields", [](const PyClash& x) { return user_fields(x.c()); },
          "The user's fields carried from the baseline (status, assignee, comment, ...).")
      .def_property_readonly(
          "baseline",
          [](const PyClash& x) {
            return x.c().baseline_json.empty() ? py::object(py::none())
                                               : json_loads(x.c().baseline_json);
          },
          "Resolved clashes: the clash as the baseline reported it (a dict); else None.")
      .def("to_record", &record, "The flat dict of to_records().")
      .def("__repr__", [](const PyClash& x) {
        const py::dict r = record(x);
        return "Clash(id='" + x.c().id + "', verdict=" + std::string(py::repr(r["verdict"])) +
               ", kind='" + x.c().kind + "', bodies=(" + std::string(py::repr(r["body_a"])) + ", " +
               std::string(py::repr(r["body_b"])) + "), status='" +
               r["status"].cast<std::string>() + "')";
      });

  // ---- ClashReport ----
  py::class_<PyReport>(m, "ClashReport",
                       "The result of Scene.clash: clashes, pairs, groups, frames, verdict.")
      .def_property_readonly(
          "clashes", [](const PyReport& r) { return clash_list(r, false); },
          "Clash objects, sorted by (test, body a id, body b id, id).")
      .def_property_readonly(
          "resolved", [](const PyReport& r) { return clash_list(r, true); },
          "Baseline clashes not found now (run_status 'resolved'), listed once.")
      .def_property_readonly("verdict",
                             [](const PyReport& r) { return verdict_name(r.d->result.verdict); })
      .def_property_readonly("summary", [](const PyReport& r) { return summary(r.d->result); })
      .def_property_readonly("warnings", [](const PyReport& r) { return r.d->result.warnings; })
      .def_property_readonly("tests", [](const PyReport& r) { return r.d->tests; })
      .def_property_readonly(
          "pairs",
          [](const PyReport& r) {
            py::list l;
            for (const sc::PairSummary& p : r.d->result.pairs) {
              py::dict d;
              d["test"] = p.test;
              d["body_a"] = r.d->scene.bodies[p.a].id;
              d["body_b"] = r.d->scene.bodies[p.b].id;
              d["verdict"] = verdict_name(p.verdict);
              py::list ids;
              for (std::uint32_t i : p.clashes) ids.append(r.d->result.clashes[i].id);
              d["clashes"] = ids;
              d["depth"] = p.depth;
              d["depth_bound"] = p.depth_bound;
              d["min_distance"] = p.min_distance < 0 ? py::object(py::none())
                                                     : py::object(py::float_(p.min_distance));
              l.append(d);
            }
            return l;
          },
          "Per body pair with clashes: test, body_a, body_b, verdict (the worst), clashes (ids), "
          "depth, depth_bound, min_distance.")
      .def_property_readonly(
          "groups",
          [](const PyReport& r) {
            py::list l;
            for (const sc::ClashGroup& g : r.d->result.groups) {
              py::dict d;
              d["id"] = g.id;
              py::list ids;
              for (std::uint32_t i : g.clashes) ids.append(r.d->result.clashes[i].id);
              d["clashes"] = ids;
              d["box"] = box_out(g.box);
              d["verdict"] = verdict_name(g.verdict);
              l.append(d);
            }
            return l;
          },
          "Groups by group_by: id, clashes (ids), box, verdict.")
      .def_property_readonly(
          "frames",
          [](const PyReport& r) {
            py::list l;
            for (const sc::FrameRow& f : r.d->result.frames) {
              py::dict d;
              d["frame"] = f.frame;
              d["label"] = f.label;
              d["time"] = f.time;
              d["clashes"] = f.clashes;
              d["contacts"] = f.contacts;
              d["clearances"] = f.clearances;
              d["undecided"] = f.undecided;
              d["min_distance"] = f.min_distance < 0 ? py::object(py::none())
                                                     : py::object(py::float_(f.min_distance));
              d["max_depth"] = f.max_depth;
              d["verdict"] = verdict_name(f.verdict);
              l.append(d);
            }
            return l;
          },
          "Motion: one dict per frame (frame, label, time, clashes, contacts, clearances, "
          "undecided, min_distance, max_depth, verdict).")
      .def(
          "to_records",
          [](const PyReport& r, bool resolved) {
            py::list l;
            for (std::size_t i = 0; i < r.d->result.clashes.size(); ++i)
              l.append(record(PyClash{r.d, i, false}));
            if (resolved)
              for (std::size_t i = 0; i < r.d->result.resolved.size(); ++i)
                l.append(record(PyClash{r.d, i, true}));
            return l;
          },
          py::arg("resolved") = true,
          "One flat dict per clash (and per resolved baseline clash): id, test, status, "
          "run_status, verdict, kind, "
          "body_a, name_a, path_a, body_b, name_b, path_b, depth, depth_bound, distance, x, y, z, "
          "box_min_x..box_max_z, "
          "curve_length, cross_pairs, touch_pairs, triangles_a, triangles_b, first_frame, frames, "
          "and the user's "
          "fields. pandas.DataFrame(report.to_records()).")
      .def(
          "to_json",
          [](const PyReport& r) {
            return sc::report_json(r.d->scene, r.d->tests, r.d->result, context(*r.d));
          },
          "The JSON report (schema interfere.scene-clash, as the CLI writes it; docs/report.md).")
      .def(
          "to_csv", [](const PyReport& r) { return sc::clash_table_csv(r.d->scene, r.d->result); },
          "The CSV clash table (as the CLI's --csv).")
      .def(
          "frames_csv", [](const PyReport& r) { return sc::frames_table_csv(r.d->result); },
          "The frames table (motion) as CSV.")
      .def(
          "exit_status",
          [](const PyReport& r, const std::string& fail_on) {
            const auto f = parse_fail_on(fail_on);
            if (!f)
              throw py::value_error("fail_on: '" + fail_on +
                                    "' (clash, contact, clearance or a list of them)");
            return verdict_exit_status(r.d->result.verdict, *f);
          },
          py::arg("fail_on") = "clash",
          "The CLI's exit status for this verdict: 1 clash, 3 undecided, 0 otherwise.")
      .def("__len__", [](const PyReport& r) { return r.d->result.clashes.size(); })
      .def("__iter__", [](const PyReport& r) { return py::iter(clash_list(r, false)); })
      .def("__repr__", [](const PyReport& r) {
        const auto& x = r.d->result;
        return "ClashReport(verdict='" + std::string(verdict_name(x.verdict)) +
               "', clashes=" + std::to_string(x.clash_count) +
               ", contacts=" + std::to_string(x.contact_count) +
               ", clearances=" + std::to_string(x.clearance_count) +
               ", undecided=" + std::to_string(x.undecided_count) +
               ", resolved=" + std::to_string(x.resolved.size()) + ")";
      });

  // ---- Scene ----
  py::class_<PyScene>(
      m, "Scene",
      "Bodies checked together (with optional motion) in one working unit, and the clash "
      "tests of a scene file.")
      .def(py::init([](const std::string& units) {
             mm_per(units, "units");
             PyScene s;
             s.scene.units = units;
             return s;
           }),
           py::arg("units") = "mm")
      .def_static(
          "from_file",
          [](const std::filesystem::path& path, const std::optional<std::string>& units) {
            return scene_from_file(path.string(), units.value_or(""));
          },
          py::arg("path"), py::arg("units") = py::none(),
          "Reads a JSON scene file (scene/io.h read_scene_file): its bodies (mesh files; glTF "
          "scenes and FE models "
          "expand to their bodies, ids '<id>/<child>'), tests and motion. units overrides the "
          "file's. STEP "
          "assemblies are an error here (the CLI reads them). Raises InputError naming file and "
          "JSON path.")
      .def_static(
          "from_gltf",
          [](const std::filesystem::path& path, const std::string& units,
             const std::string& file_units) {
            PyScene s;
            s.scene.units = units;
            const double scale = mm_per(file_units, "file_units") / mm_per(units, "units");
            std::optional<Expected<std::vector<sc::Body>>> r;
            {
              py::gil_scoped_release release;
              r.emplace(sc::read_gltf_bodies(path.string(), scale));
            }
            if (!*r) raise_input_error(r->error());
            s.files.push_back(path.string());
            for (sc::Body& b : r->value()) add_body(s, std::move(b), units);
            return s;
          },
          py::arg("path"), py::arg("units") = "mm", py::arg("file_units") = "m",
          "One body per node with a mesh of a glTF 2.0 scene (.glb/.gltf), posed by the node's "
          "world transform; "
          "id = the node path. file_units: the file's (glTF: metres).")
      .def_property_readonly("units", [](const PyScene& s) { return s.scene.units; })
      .def(
          "add", [](PyScene& s, const PyBody& b) { add_body(s, b.body, b.mesh_unit); },
          py::arg("body"),
          "Adds a copy of the body, its geometry converted to the scene's unit. ValueError for an "
          "empty or "
          "duplicate id, no triangles, or coordinates out of range once posed.")
      .def_property_readonly(
          "bodies",
          [](const PyScene& s) {
            py::list l;
            for (const sc::Body& b : s.scene.bodies) l.append(body_out(b, s.scene.units));
            return l;
          },
          "Copies of the bodies (geometry in the scene's unit).")
      .def("__len__", [](const PyScene& s) { return s.scene.bodies.size(); })
      .def("__contains__",
           [](const PyScene& s, const std::string& id) { return s.scene.find(id) >= 0; })
      .def("__getitem__",
           [](const PyScene& s, py::handle key) {
             if (py::isinstance<py::str>(key)) {
               const std::int64_t i = s.scene.find(key.cast<std::string>());
               if (i < 0) throw py::key_error("no body with id '" + key.cast<std::string>() + "'");
               return body_out(s.scene.bodies[static_cast<std::size_t>(i)], s.scene.units);
             }
             auto i = key.cast<std::int64_t>();
             const auto n = static_cast<std::int64_t>(s.scene.bodies.size());
             if (i < 0) i += n;
             if (i < 0 || i >= n) throw py::index_error("body index out of range");
             return body_out(s.scene.bodies[static_cast<std::size_t>(i)], s.scene.units);
           })
      .def_property(
          "tests", [](const PyScene& s) { return s.tests; },
          [](PyScene& s, const std::vector<sc::ClashTest>& t) { s.tests = t; },
          "The default tests of clash() (a scene file's \"tests\"); empty: one all-pairs hard "
          "test.")
      .def_property_readonly("warnings", [](const PyScene& s) { return s.scene.warnings; })
      .def_property_readonly("files", [](const PyScene& s) { return s.files; })
      .def_property_readonly("num_frames", [](const PyScene& s) { return s.scene.frames.size(); })
      .def(
          "add_frame",
          [](PyScene& s, const std::string& label, double time, py::handle poses,
             py::handle shapes) {
            sc::Frame f;
            f.label = label.empty() ? "frame " + std::to_string(s.scene.frames.size()) : label;
            f.time = time;
            const auto index = [&](py::handle key) {
              const std::string id = py::str(key).cast<std::string>();
              const std::int64_t i = s.scene.find(id);
              if (i < 0) throw py::value_error("add_frame: no body with id '" + id + "'");
              return static_cast<std::uint32_t>(i);
            };
            if (!poses.is_none()) {
              for (auto [k, v] : poses.cast<py::dict>()) {
                const Transform t = transform_from(v);
                if (const Status st = t.validate(); !st)
                  throw py::value_error("add_frame: pose of '" + py::str(k).cast<std::string>() +
                                        "': " + st.error().reason);
                f.poses.push_back({index(k), t});
              }
            }
            if (!shapes.is_none()) {
              for (auto [k, v] : shapes.cast<py::dict>()) {
                const std::uint32_t i = index(k);
                const sc::Body& b = s.scene.bodies[i];
                TriMesh tmp = py::type::of<TriMesh>()(v, py::none()).cast<TriMesh>();
                if (tmp.positions.size() != b.mesh->positions.size())
                  throw py::value_error("add_frame: shape of '" + b.id + "' has " +
                                        std::to_string(tmp.positions.size()) +
                                        " vertices; the body has " +
                                        std::to_string(b.mesh->positions.size()));
                f.shapes.push_back(
                    {i, std::make_shared<const std::vector<Vec3>>(std::move(tmp.positions))});
              }
            }
            s.scene.frames.push_back(std::move(f));
          },
          py::arg("label") = "", py::arg("time") = 0.0, py::arg("poses") = py::none(),
          py::arg("shapes") = py::none(),
          "Appends a frame: poses {id: pose} (world, scene unit), shapes {id: new local positions "
          "(n, 3)}. Bodies a "
          "frame does not list keep their previous pose and shape.")
      .def(
          "read_motion",
          [](PyScene& s, const std::filesystem::path& path) {
            if (const Status st = sc::read_motion(path.string(), s.scene); !st)
              raise_input_error(st.error());
            s.files.push_back(path.string());
          },
          py::arg("path"),
          "Reads frames from a motion file (CSV or JSON, scene/io.h). Raises InputError.")
      .def("clash", &run_clash, py::arg("tests") = py::none(), py::arg("baseline") = py::none(),
           py::arg("group_by") = "pair", py::arg("group_distance") = 0.0,
           py::arg("threads") = py::none(), py::arg("depth") = true, py::arg("curves") = true,
           "Runs the clash tests (None: the scene file's, else one all-pairs hard test; a "
           "ClashTest, a test string, "
           "or a list of them) on every body (and frame). baseline: an earlier report (path, JSON "
           "text, dict or "
           "ClashReport) for new/active/resolved status and the user's fields. Releases the GIL. "
           "Returns a "
           "ClashReport.")
      .def("__repr__", [](const PyScene& s) {
        return "Scene(units='" + s.scene.units +
               "', bodies=" + std::to_string(s.scene.bodies.size()) +
               ", frames=" + std::to_string(s.scene.frames.size()) + ")";
      });
}

}  // namespace interfere::python
