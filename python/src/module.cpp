// Python bindings (pybind11) of the interfere engine, module `interfere._interfere`.
//
// ARCHITECTURE.md: the bindings only parse arguments, fill requests, call the engines and convert
// results; there is no geometry here. Conventions of this file:
//  - numpy is required (issue #30): point and index lists are always returned as numpy arrays
//    ((n, 3) float64, (m, 3) uint32, (k,) uint32). Input accepts any array-like (sequences of
//    sequences included). Importing the module without numpy raises ImportError naming numpy.
//  - Every result is a copy owned by Python: no view into C++ memory escapes, so no Python object
//    can dangle or mutate a Model (which is immutable once built, as in C++).
//  - The GIL is released only around work on C++ data that no Python thread can reach: copies, and
//    Models (immutable from Python). `threads` limits oneTBB through a tbb::global_control that
//    lives for the duration of the call (process-wide while it lives: concurrent calls with
//    different limits get the smallest).
//  - Library errors (Error values) become interfere.InputError / interfere.OutputError carrying
//    .file, .line, .byte, .reason; bad arguments raise ValueError / TypeError.
#include "bindings.h"

#include <pybind11/numpy.h>
#include <pybind11/operators.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <tbb/global_control.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bindings.h"
#include "interfere/core/coordinate_range.h"
#include "interfere/core/error.h"
#include "interfere/core/predicates.h"
#include "interfere/core/transform.h"
#include "interfere/mesh/generate.h"
#include "interfere/mesh/io.h"
#include "interfere/mesh/polyline.h"
#include "interfere/mesh/tri_mesh.h"
#include "interfere/mesh/validate.h"
#include "interfere/query/clash.h"
#include "interfere/query/distance.h"
#include "interfere/query/model.h"

namespace py = pybind11;
using namespace interfere;

namespace {

// ---------------------------------------------------------------------------------------------
// Exceptions. Types live for the whole process (intentionally never released: a static py::object
// would be decref'd after the interpreter is gone).

PyObject* g_error = nullptr;
PyObject* g_input_error = nullptr;
PyObject* g_output_error = nullptr;

[[noreturn]] void raise_error(PyObject* type, const Error& e) {
  py::object exc = py::reinterpret_borrow<py::object>(type)(e.message());
  exc.attr("file") = e.file.empty() ? py::object(py::none()) : py::object(py::str(e.file));
  exc.attr("line") = e.line >= 0 ? py::object(py::int_(e.line)) : py::object(py::none());
  exc.attr("byte") = e.byte >= 0 ? py::object(py::int_(e.byte)) : py::object(py::none());
  exc.attr("reason") = py::str(e.reason);
  PyErr_SetObject(type, exc.ptr());
  throw py::error_already_set();
}

// ---------------------------------------------------------------------------------------------
// Conversions Python -> C++

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

double to_double(py::handle h, const std::string& what) {
  // PyFloat_AsDouble accepts int, float, numpy scalars (__float__/__index__) and rejects str.
  const double d = PyFloat_AsDouble(h.ptr());
  if (d == -1.0 && PyErr_Occurred()) {
    PyErr_Clear();
    throw py::type_error(what + ": expected a number, got " + std::string(py::str(py::type::of(h))));
  }
  return d;
}

py::sequence to_sequence(py::handle h, const std::string& what) {
  if (!PySequence_Check(h.ptr()) || py::isinstance<py::str>(h) || py::isinstance<py::bytes>(h)) {
    throw py::type_error(what + ": expected a sequence, got " + std::string(py::str(py::type::of(h))));
  }
  return py::reinterpret_borrow<py::sequence>(h);
}

Vec3 to_vec3(py::handle h, const std::string& what) {
  const py::sequence s = to_sequence(h, what);
  if (s.size() != 3) throw py::value_error(what + ": expected 3 numbers, got " + std::to_string(s.size()));
  return {to_double(s[0], what), to_double(s[1], what), to_double(s[2], what)};
}

/// numpy.asarray(obj); checks the dtype kind is one of `kinds` (unless empty) and the shape is (n, 3).
py::array as_rows_of_3(py::handle obj, const std::string& what, const char* kinds) {
  py::array a = py::module_::import("numpy").attr("asarray")(obj);
  if (a.size() == 0) return a;
  const char kind = a.dtype().kind();
  if (std::string(kinds).find(kind) == std::string::npos) {
    throw py::type_error(what + ": unsupported element type " + std::string(py::str(a.dtype())));
  }
  if (a.ndim() != 2 || a.shape(1) != 3) {
    std::string shape = "(";
    for (py::ssize_t k = 0; k < a.ndim(); ++k) {
      if (k) shape += ", ";
      shape += std::to_string(a.shape(k));
    }
    throw py::value_error(what + ": expected shape (n, 3), got " + shape + (a.ndim() == 1 ? ",)" : ")"));
  }
  return a;
}

std::vector<Vec3> points_from(py::handle obj, const std::string& what) {
  std::vector<Vec3> out;
  if (obj.is_none()) return out;
  const py::array raw = as_rows_of_3(obj, what, "fiu");
  if (raw.size() == 0) return out;
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(raw);
  if (!a) throw py::type_error(what + ": cannot convert to float64");
  const auto v = a.unchecked<2>();
  out.resize(static_cast<std::size_t>(v.shape(0)));
  for (py::ssize_t i = 0; i < v.shape(0); ++i) out[static_cast<std::size_t>(i)] = {v(i, 0), v(i, 1), v(i, 2)};
  return out;
}

std::uint32_t to_index(std::int64_t v, const std::string& what) {
  if (v < 0 || v > std::numeric_limits<std::uint32_t>::max()) {
    throw py::value_error(what + ": index " + std::to_string(v) + " is outside [0, 2^32)");
  }
  return static_cast<std::uint32_t>(v);
}

std::int64_t to_int(py::handle h, const std::string& what) {
  // Integers only (int, numpy integers, anything with __index__); floats are rejected.
  if (py::isinstance<py::float_>(h) || !PyIndex_Check(h.ptr())) {
    throw py::type_error(what + ": expected an integer, got " + std::string(py::str(py::type::of(h))));
  }
  const long long v = PyLong_AsLongLong(py::reinterpret_steal<py::object>(PyNumber_Index(h.ptr())).ptr());
  if (v == -1 && PyErr_Occurred()) {
    PyErr_Clear();
    throw py::value_error(what + ": integer out of range");
  }
  return v;
}

std::vector<Tri> triangles_from(py::handle obj, const std::string& what) {
  std::vector<Tri> out;
  if (obj.is_none()) return out;
  const py::array raw = as_rows_of_3(obj, what, "iu");
  if (raw.size() == 0) return out;
  if (raw.dtype().kind() == 'u' && raw.dtype().itemsize() == 8) {
    // uint64 does not fit int64: check the range before converting.
    const auto a = py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>::ensure(raw);
    const auto v = a.unchecked<2>();
    out.resize(static_cast<std::size_t>(v.shape(0)));
    for (py::ssize_t i = 0; i < v.shape(0); ++i) {
      for (int k = 0; k < 3; ++k) {
        if (v(i, k) > std::numeric_limits<std::uint32_t>::max()) {
          throw py::value_error(what + ": index " + std::to_string(v(i, k)) + " is outside [0, 2^32)");
        }
        out[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(v(i, k));
      }
    }
    return out;
  }
  const auto a = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(raw);
  if (!a) throw py::type_error(what + ": cannot convert to int64");
  const auto v = a.unchecked<2>();
  out.resize(static_cast<std::size_t>(v.shape(0)));
  for (py::ssize_t i = 0; i < v.shape(0); ++i) {
    for (int k = 0; k < 3; ++k) out[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] = to_index(v(i, k), what);
  }
  return out;
}

std::vector<std::uint32_t> indices_from(py::handle obj, const std::string& what) {
  std::vector<std::uint32_t> out;
  if (!py::isinstance<py::list>(obj) && !py::isinstance<py::tuple>(obj)) {
    py::array a = py::module_::import("numpy").attr("asarray")(obj);
    if (a.size() == 0) return out;
    if (a.ndim() != 1) throw py::value_error(what + ": expected a 1-D array");
    if (std::string("iu").find(a.dtype().kind()) == std::string::npos) {
      throw py::type_error(what + ": unsupported element type " + std::string(py::str(a.dtype())));
    }
    obj = a.attr("tolist")();  // exact for every integer dtype; ranges checked below
  }
  const py::sequence s = to_sequence(obj, what);
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) out.push_back(to_index(to_int(s[i], what), what));
  return out;
}

/// A singular R collapses the part (ValueError); a scaled, sheared or mirrored one is applied as
/// given, with a UserWarning saying so (issue #23, item 8; docs/robustness.md "Transforms").
Transform checked_transform(const Transform& t) {
  if (const Status ok = t.validate(); !ok) throw py::value_error(ok.error().reason);
  if (const std::string note = t.non_rigid_note(); !note.empty()) {
    if (PyErr_WarnEx(PyExc_UserWarning, note.c_str(), 1) != 0) throw py::error_already_set();
  }
  return t;
}

/// A Transform from a Transform, a string of 12 numbers, 12 numbers, 3 rows of 4, or a 4x4
/// homogeneous matrix whose last row is exactly 0 0 0 1.
Transform transform_from(py::handle obj) {
  if (py::isinstance<Transform>(obj)) return obj.cast<Transform>();
  if (py::isinstance<py::str>(obj)) {
    const auto t = Transform::parse(obj.cast<std::string>());
    if (!t) throw py::value_error(t.error().reason);
    return checked_transform(*t);
  }
  const std::string what = "transform";
  const py::sequence s = to_sequence(obj, what);
  std::vector<double> v;
  if (s.size() == 12) {
    for (std::size_t i = 0; i < 12; ++i) v.push_back(to_double(s[i], what));
  } else if (s.size() == 3 || s.size() == 4) {
    for (std::size_t row = 0; row < s.size(); ++row) {
      if (!PySequence_Check(py::object(s[row]).ptr())) {
        throw py::value_error(what + ": expected 12 numbers, 3 rows of 4 or a 4x4 matrix");
      }
      const py::sequence r = to_sequence(s[row], what + " row " + std::to_string(row));
      if (r.size() != 4) {
        throw py::value_error(what + ": expected rows of 4 numbers, row " + std::to_string(row) + " has " +
                              std::to_string(r.size()));
      }
      for (std::size_t col = 0; col < 4; ++col) v.push_back(to_double(r[col], what));
    }
    if (s.size() == 4) {
      if (!(v[12] == 0 && v[13] == 0 && v[14] == 0 && v[15] == 1)) {
        throw py::value_error(what + ": the last row of a 4x4 matrix must be 0 0 0 1 (affine transforms only)");
      }
      v.resize(12);
    }
  } else {
    throw py::value_error(what + ": expected 12 numbers, 3x4 or 4x4 values, got a sequence of " +
                          std::to_string(s.size()));
  }
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) throw py::value_error(what + ": value " + std::to_string(i + 1) + " is not finite");
  }
  Transform t;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) t.r[row][col] = v[static_cast<std::size_t>(row * 4 + col)];
    t.t[static_cast<std::size_t>(row)] = v[static_cast<std::size_t>(row * 4 + 3)];
  }
  return checked_transform(t);
}

BvhBuilder builder_from(const std::string& name) {
  const std::string n = lower(name);
  if (n == "sah" || n == "binned_sah") return BvhBuilder::binned_sah;
  if (n == "median" || n == "median_split") return BvhBuilder::median_split;
  if (n == "insertion") return BvhBuilder::insertion;
  if (n == "lbvh") return BvhBuilder::lbvh;
  if (n == "lbvh_treelet") return BvhBuilder::lbvh_treelet;
  throw py::value_error("builder: unknown builder '" + name + "' (lbvh, lbvh_treelet, sah, median, insertion)");
}

TriTest test_from(const std::string& name) {
  const std::string n = lower(name);
  if (n == "exact") return TriTest::exact;
  if (n == "moller") return TriTest::moller;
  if (n == "gd" || n == "guigue_devillers") return TriTest::guigue_devillers;
  throw py::value_error("test: unknown triangle test '" + name + "' (exact, moller, gd)");
}

Broadphase broadphase_from(const std::string& name) {
  const std::string n = lower(name);
  if (n == "bvh") return Broadphase::bvh;
  if (n == "brute" || n == "brute_force") return Broadphase::brute_force;
  if (n == "box" || n == "box_pretest") return Broadphase::box_pretest;
  throw py::value_error("broadphase: unknown broad phase '" + name + "' (bvh, brute, box)");
}

MeshFormat format_from(const std::string& name) {
  const std::string n = lower(name);
  if (n.empty() || n == "auto") return MeshFormat::automatic;
  const MeshFormat f = mesh_format_from_name(n);
  if (f == MeshFormat::automatic) {
    throw py::value_error("format: unknown mesh format '" + name +
                          "' (auto, stl, stl-ascii, stl-binary, obj, ply, ply-ascii, ply-le, ply-be, off)");
  }
  return f;
}

/// Rejects meshes the engines assume valid (indices in range, finite coordinates).
void check_mesh(const TriMesh& m, const std::string& what) {
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    if (!is_finite(m.positions[i])) {
      throw py::value_error(what + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
    }
    if (!coordinates_in_range(m.positions[i])) {  // issue #23, item 7
      throw py::value_error(what + ": vertex " + std::to_string(i) + ": " +
                            coordinate_range_reason(m.positions[i]));
    }
  }
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    for (std::uint32_t v : m.triangles[t]) {
      if (v >= m.positions.size()) {
        throw py::value_error(what + ": triangle " + std::to_string(t) + " uses vertex " + std::to_string(v) +
                              " but the mesh has " + std::to_string(m.positions.size()) + " vertices");
      }
    }
  }
}


/// A query operand: the caller's Model (borrowed; kept alive by the call's arguments), or a TriMesh
/// copied under the GIL and built into a Model once the GIL is released.
class Part {
 public:
  Part(py::handle h, const std::string& what) {
    if (py::isinstance<Model>(h)) {
      model_ = &h.cast<const Model&>();
    } else if (py::isinstance<TriMesh>(h)) {
      mesh_ = h.cast<TriMesh>();
      check_mesh(*mesh_, what);
    } else {
      throw py::type_error(what + ": expected a Model or a TriMesh, got " + std::string(py::str(py::type::of(h))));
    }
  }
  /// Call without the GIL.
  const Model& get(const BvhBuildOptions& options) {
    if (model_ == nullptr) {
      built_.emplace(make_model(std::move(*mesh_), options, true));
      model_ = &*built_;
    }
    return *model_;
  }

  /// Both operands, built concurrently where both are meshes (call without the GIL).
  friend std::pair<const Model&, const Model&> get_both(Part& a, Part& b, const BvhBuildOptions& options) {
    if (a.model_ == nullptr && b.model_ == nullptr) {
      tbb::parallel_invoke([&] { a.get(options); }, [&] { b.get(options); });
    }
    return {a.get(options), b.get(options)};
  }

 private:
  const Model* model_ = nullptr;
  std::optional<TriMesh> mesh_;
  std::optional<Model> built_;
};

// ---------------------------------------------------------------------------------------------
// Conversions C++ -> Python

py::tuple vec_out(const Vec3& v) { return py::make_tuple(v.x, v.y, v.z); }

py::object points_out(const std::vector<Vec3>& p, bool arrays) {
  if (arrays) {
    py::array_t<double> a({static_cast<py::ssize_t>(p.size()), static_cast<py::ssize_t>(3)});
    auto m = a.mutable_unchecked<2>();
    for (std::size_t i = 0; i < p.size(); ++i) {
      const auto r = static_cast<py::ssize_t>(i);
      m(r, 0) = p[i].x, m(r, 1) = p[i].y, m(r, 2) = p[i].z;
    }
    return a;
  }
  py::list l(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) l[i] = vec_out(p[i]);
  return l;
}

py::object triangles_out(const std::vector<Tri>& t, bool arrays) {
  if (arrays) {
    py::array_t<std::uint32_t> a({static_cast<py::ssize_t>(t.size()), static_cast<py::ssize_t>(3)});
    auto m = a.mutable_unchecked<2>();
    for (std::size_t i = 0; i < t.size(); ++i) {
      for (std::size_t k = 0; k < 3; ++k) m(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(k)) = t[i][k];
    }
    return a;
  }
  py::list l(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) l[i] = py::make_tuple(t[i][0], t[i][1], t[i][2]);
  return l;
}

py::object indices_out(const std::vector<std::uint32_t>& v, bool arrays) {
  if (arrays) {
    py::array_t<std::uint32_t> a(static_cast<py::ssize_t>(v.size()));
    std::copy(v.begin(), v.end(), a.mutable_data());
    return a;
  }
  py::list l(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) l[i] = py::int_(v[i]);
  return l;
}

py::object box_out(const Aabb& b) {
  if (b.empty()) return py::none();
  return py::make_tuple(vec_out(b.lo), vec_out(b.hi));
}

const char* kind_name(ContactKind k) {
  switch (k) {
    case ContactKind::touch: return "touch";
    case ContactKind::cross: return "cross";
    case ContactKind::none: break;
  }
  return "none";
}

py::dict stats_dict(const MeshStats& s) {
  py::dict d;
  d["vertices"] = s.vertices;
  d["triangles"] = s.triangles;
  d["degenerate_triangles"] = s.degenerate_triangles;
  d["duplicate_triangles"] = s.duplicate_triangles;
  d["open_edges"] = s.open_edges;
  d["nonmanifold_edges"] = s.nonmanifold_edges;
  d["inconsistent_edges"] = s.inconsistent_edges;
  d["components"] = s.components;
  d["closed"] = s.closed();
  return d;
}

py::dict polyline_dict(const Polyline& p) {
  py::dict d;
  d["points"] = points_out(p.points, false);
  d["closed"] = p.closed;
  d["length"] = p.length;
  return d;
}

py::dict region_dict(const ClashRegion& r) {
  py::dict d;
  d["triangles_a"] = indices_out(r.triangles_a, false);
  d["triangles_b"] = indices_out(r.triangles_b, false);
  d["cross_pairs"] = r.cross_pairs;
  d["touch_pairs"] = r.touch_pairs;
  d["bbox"] = box_out(r.box);
  py::list curves;
  for (const Polyline& c : r.curves) curves.append(polyline_dict(c));
  d["curves"] = curves;
  d["curve_length"] = r.curve_length;
  return d;
}

py::dict clearance_dict(const ClearancePair& c) {
  py::dict d;
  d["a"] = c.a;
  d["b"] = c.b;
  d["distance"] = c.distance;
  d["point_a"] = vec_out(c.point_a);
  d["point_b"] = vec_out(c.point_b);
  return d;
}

py::list pairs_list(const ClashResult& r) {
  py::list l(r.pairs.size());
  for (std::size_t i = 0; i < r.pairs.size(); ++i) {
    const TrianglePair& p = r.pairs[i];
    l[i] = py::make_tuple(p.a, p.b, kind_name(p.kind));
  }
  return l;
}

double total_curve_length(const ClashResult& r) {
  double s = 0;
  for (const ClashRegion& g : r.regions) s += g.curve_length;
  return s;
}

py::dict clash_dict(const ClashResult& r) {
  py::dict d;
  d["verdict"] = verdict_name(r.verdict);
  d["verdict_reasons"] = r.verdict_reasons;
  d["interference"] = r.interference();
  d["containment"] = containment_name(r.containment);
  d["touching_overlap"] = r.touching_overlap;
  d["cross_pairs"] = r.cross_pairs;
  d["touch_pairs"] = r.touch_pairs;
  d["candidate_pairs"] = r.candidate_pairs;
  d["curve_length"] = total_curve_length(r);
  d["pairs"] = pairs_list(r);
  py::list regions, clearance;
  for (const ClashRegion& g : r.regions) regions.append(region_dict(g));
  for (const ClearancePair& c : r.clearance) clearance.append(clearance_dict(c));
  d["regions"] = regions;
  d["clearance"] = clearance;
  d["warnings"] = py::cast(r.warnings);
  return d;
}

py::dict distance_dict(const DistanceResult& r) {
  py::dict d;
  d["intersecting"] = r.intersecting;
  d["distance"] = r.distance;
  d["point_a"] = vec_out(r.point_a);
  d["point_b"] = vec_out(r.point_b);
  d["triangle_a"] = r.triangle_a;
  d["triangle_b"] = r.triangle_b;
  return d;
}

std::string fmt_double(double v) { return py::str(py::float_(v)); }

}  // namespace

PYBIND11_MODULE(_interfere, m) {
  m.doc() = "Exact, parallel clash detection for triangle meshes (bindings of the C++ library).";
  m.attr("__version__") = INTERFERE_VERSION;

  // numpy is required: every point and index list comes back as an array (issue #30).
  try {
    py::module_::import("numpy");
  } catch (const py::error_already_set& e) {
    throw py::import_error(std::string("interfere needs numpy, which could not be imported (") + e.what() +
                           "); install it: apt-get install python3-numpy, or pip install numpy");
  }
  m.attr("HAVE_NUMPY") = true;  // always True since numpy became required; kept for old scripts
  m.attr("KIND_TOUCH") = static_cast<int>(ContactKind::touch);
  m.attr("KIND_CROSS") = static_cast<int>(ContactKind::cross);

  // ---- exceptions ----
  g_error = PyErr_NewExceptionWithDoc(
      "interfere.Error", "Base class of the errors reported by the library (attributes file, line, byte, reason).",
      PyExc_Exception, nullptr);
  g_input_error = PyErr_NewExceptionWithDoc(
      "interfere.InputError",
      "A file could not be read: .file, .line (1-based, text formats) or .byte (0-based, binary formats) "
      "say where, .reason says why; line/byte are None when not applicable.",
      g_error, nullptr);
  g_output_error = PyErr_NewExceptionWithDoc(
      "interfere.OutputError", "A file could not be written (same attributes as InputError).", g_error, nullptr);
  if (g_error == nullptr || g_input_error == nullptr || g_output_error == nullptr) throw py::error_already_set();
  for (const char* a : {"file", "line", "byte", "reason"}) {
    py::handle(g_error).attr(a) = py::none();
  }
  m.attr("Error") = py::handle(g_error);
  m.attr("InputError") = py::handle(g_input_error);
  m.attr("OutputError") = py::handle(g_output_error);

  // ---- Transform ----
  py::class_<Transform>(m, "Transform",
                        "Affine part pose p' = R·p + t (row-major [R|t]), evaluated in double.")
      .def(py::init<>(), "The identity.")
      .def(py::init([](py::handle values) { return transform_from(values); }), py::arg("values"),
           "From 12 numbers r00 r01 r02 tx r10 r11 r12 ty r20 r21 r22 tz, 3 rows of 4, a 4x4 matrix with last "
           "row 0 0 0 1, a string of 12 numbers, or another Transform.")
      .def_static("parse", [](const std::string& s) { return transform_from(py::str(s)); }, py::arg("text"),
                  "Parses 12 numbers separated by spaces and/or commas (ValueError on error).")
      .def_static(
          "translation", [](py::handle t) { Transform x; x.t = to_vec3(t, "translation"); return x; },
          py::arg("t"), "A pure translation by (tx, ty, tz).")
      .def_property_readonly("r",
                             [](const Transform& t) {
                               return py::make_tuple(py::make_tuple(t.r[0][0], t.r[0][1], t.r[0][2]),
                                                     py::make_tuple(t.r[1][0], t.r[1][1], t.r[1][2]),
                                                     py::make_tuple(t.r[2][0], t.r[2][1], t.r[2][2]));
                             },
                             "The 3x3 linear part as a tuple of rows.")
      .def_property_readonly("t", [](const Transform& t) { return vec_out(t.t); }, "The translation.")
      .def("to_row_major", [](const Transform& t) { return py::cast(t.to_row_major()); },
           "The 12 numbers, row-major (a list).")
      .def("matrix",
           [](const Transform& t) {
             const auto v = t.to_row_major();
             py::array_t<double> a({static_cast<py::ssize_t>(3), static_cast<py::ssize_t>(4)});
             std::copy(v.begin(), v.end(), a.mutable_data());
             return a;
           },
           "The 3x4 matrix [R|t] as a (3, 4) float64 numpy array.")
      .def("apply", [](const Transform& t, py::handle p) { return vec_out(t.apply(to_vec3(p, "point"))); },
           py::arg("point"), "R·p + t for one point.")
      .def("is_identity", &Transform::is_identity)
      .def(py::self == py::self)  // NOLINT(misc-redundant-expression)
      .def("__repr__",
           [](const Transform& t) {
             std::string s = "Transform([";
             const auto v = t.to_row_major();
             for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + fmt_double(v[i]);
             return s + "])";
           })
      .def(py::pickle([](const Transform& t) { return py::object(py::cast(t.to_row_major())); },
                      [](const py::object& v) { return transform_from(v); }));

  // ---- TriMesh ----
  py::class_<TriMesh>(m, "TriMesh",
                      "Triangle mesh: positions (n, 3) float64 and triangles (m, 3) uint32 (indices into "
                      "positions). Triangle i is input triangle i: every index a query reports refers to it.")
      .def(py::init([](py::handle positions, py::handle triangles) {
             TriMesh t;
             t.positions = points_from(positions, "positions");
             t.triangles = triangles_from(triangles, "triangles");
             check_mesh(t, "TriMesh");
             return t;
           }),
           py::arg("positions") = py::none(), py::arg("triangles") = py::none())
      .def_property(
          "positions", [](const TriMesh& t) { return points_out(t.positions, true); },
          [](TriMesh& t, py::handle v) { t.positions = points_from(v, "positions"); },
          "Vertex positions (a copy: assign the attribute to change it).")
      .def_property(
          "triangles", [](const TriMesh& t) { return triangles_out(t.triangles, true); },
          [](TriMesh& t, py::handle v) { t.triangles = triangles_from(v, "triangles"); },
          "Vertex indices per triangle (a copy: assign the attribute to change it).")
      .def_property_readonly("num_vertices", &TriMesh::num_vertices)
      .def_property_readonly("num_triangles", &TriMesh::num_triangles)
      .def("bounds", [](const TriMesh& t) { return box_out(t.bounds()); },
           "((xmin, ymin, zmin), (xmax, ymax, zmax)) of the positions, None when there are none.")
      .def("copy", [](const TriMesh& t) { return TriMesh(t); })
      .def("__copy__", [](const TriMesh& t) { return TriMesh(t); })
      .def("__deepcopy__", [](const TriMesh& t, py::handle) { return TriMesh(t); }, py::arg("memo"))
      .def("__repr__",
           [](const TriMesh& t) {
             return "TriMesh(vertices=" + std::to_string(t.num_vertices()) +
                    ", triangles=" + std::to_string(t.num_triangles()) + ")";
           })
      .def(py::pickle(
          [](const TriMesh& t) { return py::make_tuple(points_out(t.positions, false), triangles_out(t.triangles, false)); },
          [](const py::tuple& s) {
            if (s.size() != 2) throw std::runtime_error("TriMesh: invalid pickle state");
            TriMesh t;
            t.positions = points_from(s[0], "positions");
            t.triangles = triangles_from(s[1], "triangles");
            return t;
          }));

  // ---- MeshStats ----
  py::class_<MeshStats>(m, "MeshStats", "Validation statistics of a mesh (see mesh_stats).")
      .def_readonly("vertices", &MeshStats::vertices)
      .def_readonly("triangles", &MeshStats::triangles)
      .def_readonly("degenerate_triangles", &MeshStats::degenerate_triangles,
                    "Repeated corner index or three collinear corners (exact test).")
      .def_readonly("duplicate_triangles", &MeshStats::duplicate_triangles,
                    "Same vertex set as an earlier triangle (any orientation).")
      .def_readonly("open_edges", &MeshStats::open_edges, "Edges used by exactly one triangle.")
      .def_readonly("nonmanifold_edges", &MeshStats::nonmanifold_edges, "Edges used by more than two triangles.")
      .def_readonly("inconsistent_edges", &MeshStats::inconsistent_edges,
                    "Manifold edges whose two triangles do not orient them oppositely.")
      .def_readonly("components", &MeshStats::components, "Connected components (by shared vertices).")
      .def_property_readonly("closed", &MeshStats::closed,
                             "No open or non-manifold edge and consistent orientation (needed for containment).")
      .def("to_dict", &stats_dict)
      .def("__repr__", [](const MeshStats& s) { return "MeshStats(" + std::string(py::str(stats_dict(s))) + ")"; });

  // ---- Model ----
  py::class_<Model>(m, "Model", "A mesh with its BVH and statistics; immutable (build with make_model).")
      .def_property_readonly("mesh", [](const Model& x) { return TriMesh(x.mesh); }, "A copy of the mesh.")
      .def_property_readonly("stats", [](const Model& x) { return x.stats; })
      .def_property_readonly("num_vertices", [](const Model& x) { return x.mesh.num_vertices(); })
      .def_property_readonly("num_triangles", [](const Model& x) { return x.mesh.num_triangles(); })
      .def_property_readonly("bvh_nodes", [](const Model& x) { return x.bvh.nodes.size(); })
      .def("bounds", [](const Model& x) { return box_out(x.mesh.bounds()); })
      .def("__repr__", [](const Model& x) {
        return "Model(vertices=" + std::to_string(x.mesh.num_vertices()) +
               ", triangles=" + std::to_string(x.mesh.num_triangles()) +
               ", bvh_nodes=" + std::to_string(x.bvh.nodes.size()) + ")";
      });

  // ---- Polyline ----
  py::class_<Polyline>(m, "Polyline", "An intersection curve: points, closed flag, length.")
      .def(py::init([](py::handle points, bool closed) {
             Polyline p;
             p.points = points_from(points, "points");
             p.closed = closed;
             for (std::size_t i = 1; i < p.points.size(); ++i) p.length += distance(p.points[i - 1], p.points[i]);
             if (closed && p.points.size() > 1) p.length += distance(p.points.back(), p.points.front());
             return p;
           }),
           py::arg("points"), py::arg("closed") = false)
      .def_property_readonly("points", [](const Polyline& p) { return points_out(p.points, true); })
      .def_readonly("closed", &Polyline::closed, "The last point joins the first.")
      .def_readonly("length", &Polyline::length)
      .def("__len__", [](const Polyline& p) { return p.points.size(); })
      .def("to_dict", &polyline_dict)
      .def("__repr__", [](const Polyline& p) {
        return "Polyline(points=" + std::to_string(p.points.size()) + ", closed=" + (p.closed ? "True" : "False") +
               ", length=" + fmt_double(p.length) + ")";
      });

  // ---- clash results ----
  py::class_<ClashRegion>(m, "ClashRegion", "Connected group of intersecting pairs with its curves.")
      .def_property_readonly("triangles_a", [](const ClashRegion& r) { return indices_out(r.triangles_a, true); },
                             "Sorted triangle indices of A.")
      .def_property_readonly("triangles_b", [](const ClashRegion& r) { return indices_out(r.triangles_b, true); },
                             "Sorted triangle indices of B.")
      .def_readonly("cross_pairs", &ClashRegion::cross_pairs)
      .def_readonly("touch_pairs", &ClashRegion::touch_pairs)
      .def_property_readonly("bbox", [](const ClashRegion& r) { return box_out(r.box); },
                             "((xmin, ymin, zmin), (xmax, ymax, zmax)) of the region's triangles on both parts.")
      .def_readonly("curves", &ClashRegion::curves, "Intersection curves (list of Polyline).")
      .def_readonly("curve_length", &ClashRegion::curve_length)
      .def("to_dict", &region_dict)
      .def("__repr__", [](const ClashRegion& r) {
        return "ClashRegion(triangles_a=" + std::to_string(r.triangles_a.size()) +
               ", triangles_b=" + std::to_string(r.triangles_b.size()) + ", cross_pairs=" +
               std::to_string(r.cross_pairs) + ", touch_pairs=" + std::to_string(r.touch_pairs) +
               ", curves=" + std::to_string(r.curves.size()) + ")";
      });

  py::class_<ClearancePair>(m, "ClearancePair", "A non-intersecting pair closer than the clearance.")
      .def_readonly("a", &ClearancePair::a)
      .def_readonly("b", &ClearancePair::b)
      .def_readonly("distance", &ClearancePair::distance)
      .def_property_readonly("point_a", [](const ClearancePair& c) { return vec_out(c.point_a); })
      .def_property_readonly("point_b", [](const ClearancePair& c) { return vec_out(c.point_b); })
      .def("to_dict", &clearance_dict)
      .def("__repr__", [](const ClearancePair& c) {
        return "ClearancePair(a=" + std::to_string(c.a) + ", b=" + std::to_string(c.b) +
               ", distance=" + fmt_double(c.distance) + ")";
      });

  py::class_<ClashResult>(m, "ClashResult", "Result of clash(); every list is sorted (independent of threads).")
      .def_property_readonly("pairs", &pairs_list,
                             "Intersecting pairs as (triangle_a, triangle_b, 'cross' | 'touch'), sorted by (a, b).")
      .def(
          "pair_array",
          [](const ClashResult& r) {
            py::array_t<std::uint32_t> a({static_cast<py::ssize_t>(r.pairs.size()), static_cast<py::ssize_t>(3)});
            auto v = a.mutable_unchecked<2>();
            for (std::size_t i = 0; i < r.pairs.size(); ++i) {
              const auto k = static_cast<py::ssize_t>(i);
              v(k, 0) = r.pairs[i].a, v(k, 1) = r.pairs[i].b, v(k, 2) = static_cast<std::uint32_t>(r.pairs[i].kind);
            }
            return a;
          },
          "Pairs as an (n, 3) uint32 array [a, b, kind] with kind KIND_TOUCH (1) or KIND_CROSS (2).")
      .def_readonly("regions", &ClashResult::regions, "List of ClashRegion.")
      .def_readonly("clearance", &ClashResult::clearance, "List of ClearancePair, sorted by (a, b).")
      .def_property_readonly("containment", [](const ClashResult& r) { return containment_name(r.containment); },
                             "'none', 'a_inside_b', 'b_inside_a' or 'not_checked'.")
      .def_readonly("cross_pairs", &ClashResult::cross_pairs)
      .def_readonly("touch_pairs", &ClashResult::touch_pairs)
      .def_readonly("touching_overlap", &ClashResult::touching_overlap,
                    "Only touching pairs, both parts closed, yet the solids overlap (coincident faces).")
      .def_readonly("candidate_pairs", &ClashResult::candidate_pairs,
                    "Box-overlapping pairs handed to the triangle test.")
      .def_readonly("warnings", &ClashResult::warnings)
      .def_property_readonly("interference", &ClashResult::interference,
                             "Any intersecting pair, or one part inside the other.")
      .def_property_readonly("curve_length", &total_curve_length, "Sum of the regions' curve lengths.")
      .def_property_readonly(
          "verdict", [](const ClashResult& r) { return verdict_name(r.verdict); },
          "'clash' (interiors overlap), 'contact' (touching only), 'clearance', 'clear' or 'undecided' "
          "(inside/outside could not be decided, e.g. an open part: never clear); docs/robustness.md")
      .def_readonly("verdict_reasons", &ClashResult::verdict_reasons, "Why the verdict is undecided.")
      .def("to_dict", &clash_dict, "Plain lists/dicts (JSON-serialisable).")
      .def("__repr__", [](const ClashResult& r) {
        return "ClashResult(verdict='" + std::string(verdict_name(r.verdict)) + "', interference=" +
               std::string(r.interference() ? "True" : "False") +
               ", pairs=" + std::to_string(r.pairs.size()) + " (" + std::to_string(r.cross_pairs) + " cross, " +
               std::to_string(r.touch_pairs) + " touch), regions=" + std::to_string(r.regions.size()) +
               ", containment='" + containment_name(r.containment) + "')";
      });

  py::class_<DistanceResult>(m, "DistanceResult", "Result of distance().")
      .def_readonly("intersecting", &DistanceResult::intersecting, "Surfaces intersect (exact); distance is 0.")
      .def_readonly("distance", &DistanceResult::distance,
                    "Minimum distance (inf when upper_bound > 0 and nothing is closer).")
      .def_property_readonly("point_a", [](const DistanceResult& r) { return vec_out(r.point_a); })
      .def_property_readonly("point_b", [](const DistanceResult& r) { return vec_out(r.point_b); })
      .def_readonly("triangle_a", &DistanceResult::triangle_a)
      .def_readonly("triangle_b", &DistanceResult::triangle_b)
      .def("to_dict", &distance_dict)
      .def("__repr__", [](const DistanceResult& r) {
        return "DistanceResult(distance=" + fmt_double(r.distance) +
               ", intersecting=" + (r.intersecting ? "True" : "False") + ", triangles=(" +
               std::to_string(r.triangle_a) + ", " + std::to_string(r.triangle_b) + "))";
      });

  // ---- input / output ----
  m.def(
      "read_mesh",
      [](const std::filesystem::path& path, const std::string& format, bool weld, bool return_info) -> py::object {
        const ReadOptions options{.format = format_from(format), .weld = weld};
        MeshReadInfo info;
        std::optional<Expected<TriMesh>> r;
        {
          py::gil_scoped_release release;
          r.emplace(read_mesh(path, options, &info));
        }
        if (!*r) raise_error(g_input_error, r->error());
        py::object mesh = py::cast(std::move(r->value()));
        if (!return_info) return mesh;
        py::dict d;
        d["format"] = mesh_format_name(info.format);
        d["polygons_split"] = info.polygons_split;
        d["vertices_before_weld"] = info.vertices_before_weld;
        return py::make_tuple(mesh, d);
      },
      py::arg("path"), py::arg("format") = "auto", py::arg("weld") = true, py::arg("return_info") = false,
      "Reads STL (ASCII/binary), OBJ, PLY or OFF. Raises InputError (file, line or byte, reason) on any error. "
      "With return_info=True returns (mesh, {'format', 'polygons_split', 'vertices_before_weld'}).");

  m.def(
      "write_mesh",
      [](const std::filesystem::path& path, const TriMesh& mesh, const std::string& format, bool ply_float) {
        const Status s = write_mesh(path, mesh, {.format = format_from(format), .ply_float = ply_float});
        if (!s) raise_error(g_output_error, s.error());
      },
      py::arg("path"), py::arg("mesh"), py::arg("format") = "auto", py::arg("ply_float") = false,
      "Writes atomically (format by extension unless given). Raises OutputError.");

  m.def(
      "write_polylines",
      [](const std::filesystem::path& path, const std::vector<Polyline>& curves) {
        const Status s = write_polylines(path, curves);
        if (!s) raise_error(g_output_error, s.error());
      },
      py::arg("path"), py::arg("curves"), "Writes curves to .obj (l lines) or .vtk (POLYDATA). Raises OutputError.");

  // ---- mesh utilities ----
  m.def(
      "mesh_stats",
      [](const TriMesh& mesh) {
        check_mesh(mesh, "mesh");
        return mesh_stats(mesh);
      },
      py::arg("mesh"), "Vertices, triangles, degenerate/duplicate triangles, open/non-manifold/inconsistent "
                       "edges, components, closed.");
  m.def(
      "weld_exact", [](TriMesh& mesh) { return weld_exact(mesh); }, py::arg("mesh"),
      "Merges bit-identical vertices in place; returns the number removed.");
  m.def(
      "submesh",
      [](const TriMesh& mesh, py::handle triangles) {
        check_mesh(mesh, "mesh");
        const std::vector<std::uint32_t> t = indices_from(triangles, "triangles");
        for (std::uint32_t i : t) {
          if (i >= mesh.num_triangles()) {
            throw py::value_error("triangles: index " + std::to_string(i) + " but the mesh has " +
                                  std::to_string(mesh.num_triangles()) + " triangles");
          }
        }
        return submesh(mesh, t);
      },
      py::arg("mesh"), py::arg("triangles"), "The given triangles (in that order) with only the vertices they use.");
  m.def(
      "transformed",
      [](const TriMesh& mesh, py::handle transform) {
        const Transform t = transform_from(transform);
        TriMesh out = transformed(mesh, t);
        check_mesh(out, "transformed mesh");
        return out;
      },
      py::arg("mesh"), py::arg("transform"), "A copy with every position mapped by the transform (in double).");

  // ---- generators ----
  m.def(
      "make_sphere",
      [](std::size_t triangles, double radius, py::handle center, double bump_amplitude, int bump_frequency,
         double twist) {
        return make_sphere({.target_triangles = triangles,
                            .radius = radius,
                            .center = to_vec3(center, "center"),
                            .bump_amplitude = bump_amplitude,
                            .bump_frequency = bump_frequency,
                            .twist = twist});
      },
      py::arg("triangles") = 20000, py::arg("radius") = 1.0, py::arg("center") = py::make_tuple(0.0, 0.0, 0.0),
      py::arg("bump_amplitude") = 0.0, py::arg("bump_frequency") = 7, py::arg("twist") = 0.0,
      "UV sphere (closed, outward) of about `triangles` triangles, optionally bumpy: r = R·(1 + a·sin(kθ)·sin(kφ)).");
  m.def(
      "make_box",
      [](py::handle lo, py::handle hi, int n) { return make_box(to_vec3(lo, "lo"), to_vec3(hi, "hi"), n); },
      py::arg("lo"), py::arg("hi"), py::arg("n") = 1, "Axis-aligned box with n subdivisions per edge (12·n² triangles).");
  m.def(
      "make_overlapping_spheres",
      [](std::size_t triangles_per_part) {
        SpherePair p = make_overlapping_spheres(triangles_per_part);
        return py::make_tuple(std::move(p.a), std::move(p.b));
      },
      py::arg("triangles_per_part") = 20000,
      "The benchmark pair: two bumpy unit spheres 1.96 apart on x; returns (a, b).");

  // ---- engines ----
  m.def(
      "make_model",
      [](const TriMesh& mesh, const std::string& builder, std::uint32_t max_leaf_size, bool stats, int threads) {
        const BvhBuildOptions options{.builder = builder_from(builder), .max_leaf_size = std::max(1u, max_leaf_size)};
        TriMesh copy = mesh;
        check_mesh(copy, "mesh");
        interfere::python::ThreadLimit limit(threads);
        py::gil_scoped_release release;
        return make_model(std::move(copy), options, stats);
      },
      py::arg("mesh"), py::arg("builder") = "lbvh", py::arg("max_leaf_size") = 4, py::arg("stats") = true,
      py::arg("threads") = 0,
      "Builds the BVH (builder 'lbvh' (default), 'lbvh_treelet', 'sah', 'median' or 'insertion') and the statistics. Releases the GIL.");

  m.def(
      "clash",
      [](py::handle a, py::handle b, const std::string& test, const std::string& broadphase, double clearance,
         bool regions, bool containment, int threads, const std::string& builder) {
        if (!(clearance >= 0) || !std::isfinite(clearance)) {
          throw py::value_error("clearance must be a finite number >= 0");
        }
        const ClashRequest request{.test = test_from(test),
                                   .broadphase = broadphase_from(broadphase),
                                   .parallel = true,
                                   .clearance = clearance,
                                   .regions = regions,
                                   .containment = containment};
        const BvhBuildOptions options{.builder = builder_from(builder)};
        Part pa(a, "a"), pb(b, "b");
        interfere::python::ThreadLimit limit(threads);
        py::gil_scoped_release release;
        const auto [ma, mb] = get_both(pa, pb, options);
        return clash(ma, mb, request);
      },
      py::arg("a"), py::arg("b"), py::arg("test") = "exact", py::arg("broadphase") = "bvh",
      py::arg("clearance") = 0.0, py::arg("regions") = true, py::arg("containment") = true, py::arg("threads") = 0,
      py::arg("builder") = "lbvh",
      "Every intersecting triangle pair of a and b (Models, or TriMeshes built with `builder`), regions with "
      "curves, containment and clearance pairs. threads=0 uses all cores. Releases the GIL.");

  m.def(
      "distance",
      [](py::handle a, py::handle b, double upper_bound, int threads, const std::string& builder) {
        if (!(upper_bound >= 0)) throw py::value_error("upper_bound must be >= 0 (0 = no bound)");
        const BvhBuildOptions options{.builder = builder_from(builder)};
        Part pa(a, "a"), pb(b, "b");
        interfere::python::ThreadLimit limit(threads);
        py::gil_scoped_release release;
        const auto [ma, mb] = get_both(pa, pb, options);
        return distance(ma, mb, DistanceRequest{.upper_bound = upper_bound});
      },
      py::arg("a"), py::arg("b"), py::arg("upper_bound") = 0.0, py::arg("threads") = 0, py::arg("builder") = "lbvh",
      "Minimum distance with witness points and triangles. Releases the GIL.");

  m.def("exact_fallback_count", &exact_fallback_count,
        "Exact-arithmetic fallbacks taken by the predicates since the process started.");
  interfere::python::bind_probe(m);
  interfere::python::bind_cell(m);
  interfere::python::bind_bearing(m);

  interfere::python::bind_fem(m);
  interfere::python::bind_simplify(m);
  interfere::python::bind_scene(m);
}
