// Python bindings of the bearing module (issue #4): rollers and scars, the analytic cylinder pair
// distance, Eq. (1), the exact surface reference and the dynamic simulation. Submodule
// `interfere.bearing`. Points are (x, y, z) tuples; bad parameters raise ValueError naming them.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "bindings.h"
#include "interfere/bearing/analytic.h"
#include "interfere/bearing/assembly.h"
#include "interfere/bearing/scar_import.h"
#include "interfere/bearing/scarred.h"
#include "interfere/bearing/simulation.h"
#include "interfere/bearing/window.h"

namespace py = pybind11;

namespace interfere::python {
namespace {
using namespace interfere::bearing;
using P3 = std::array<double, 3>;
P3 tup(const Vec3& v) { return {v.x, v.y, v.z}; }
Vec3 vec(const P3& p) { return {p[0], p[1], p[2]}; }
void check(const Status& s) {
  if (!s) throw py::value_error(s.error().message());
}
constexpr double kDeg = std::numbers::pi / 180.0;
}  // namespace

void bind_bearing(py::module_& parent) {
  py::module_ m = parent.def_submodule("bearing", "Dynamic interference of cylindrical roller bearings with scars");

  py::class_<RollerParams>(m, "RollerParams")
      .def(py::init([](double radius, double top_radius, double height, int radial_segments, int height_segments) {
             return RollerParams{radius, top_radius, height, radial_segments, height_segments};
           }),
           py::arg("radius") = 10.0, py::arg("top_radius") = -1.0, py::arg("height") = 40.0,
           py::arg("radial_segments") = 64, py::arg("height_segments") = 63)
      .def_readwrite("radius", &RollerParams::radius)
      .def_readwrite("top_radius", &RollerParams::top_radius)
      .def_readwrite("height", &RollerParams::height)
      .def_readwrite("radial_segments", &RollerParams::radial_segments)
      .def_readwrite("height_segments", &RollerParams::height_segments);

  py::class_<ScarParams>(m, "ScarParams")
      .def(py::init([](double c, double w, double z0, double z1, double depth, double roughness, int border,
                       std::uint64_t seed, bool raised) {
             return ScarParams{c, w, z0, z1, depth, roughness, border, seed, raised};
           }),
           py::arg("angle_center_deg") = 0.0, py::arg("angle_width_deg") = 40.0, py::arg("z_min") = 10.0,
           py::arg("z_max") = 30.0, py::arg("depth") = 0.05, py::arg("roughness") = 0.6, py::arg("border") = 2,
           py::arg("seed") = 1, py::arg("raised") = false)
      .def_readwrite("angle_center_deg", &ScarParams::angle_center_deg)
      .def_readwrite("angle_width_deg", &ScarParams::angle_width_deg)
      .def_readwrite("z_min", &ScarParams::z_min)
      .def_readwrite("z_max", &ScarParams::z_max)
      .def_readwrite("depth", &ScarParams::depth)
      .def_readwrite("roughness", &ScarParams::roughness)
      .def_readwrite("border", &ScarParams::border)
      .def_readwrite("seed", &ScarParams::seed)
      .def_readwrite("raised", &ScarParams::raised);  // outward scar (issue #27)

  py::class_<Roller>(m, "Roller", "A meshed roller (body frame: axis +z from the bottom end centre)")
      .def_readonly("params", &Roller::params)
      .def_readonly("mesh", &Roller::mesh)
      .def_readonly("displacement", &Roller::displacement)
      .def_readonly("scar", &Roller::scar)
      .def_readonly("has_scar", &Roller::has_scar)
      .def_readonly("max_raise", &Roller::raise);  // largest outward displacement (issue #27; `raise` is a Python keyword)

  m.def(
      "make_roller",
      [](const RollerParams& p, std::optional<ScarParams> scar) {
        Expected<Roller> r = make_roller(p);
        if (!r) throw py::value_error(r.error().message());
        if (scar) {
          Expected<int> k = apply_scar(*r, *scar);
          if (!k) throw py::value_error(k.error().message());
        }
        return std::move(*r);
      },
      py::arg("params") = RollerParams{}, py::arg("scar") = std::nullopt,
      "Mesh a roller (cylinder or tapered), optionally with a diamond-square scar.");

  // Imported scars (issue #27; scar_import.h, docs/bearing.md "Scars: raised and imported"): a measured
  // height map (CSV grid over angle x z, or a 16-bit PNG placed on a window) or a point cloud / scanned
  // mesh of the worn surface, resampled onto a roller's vertex grid. Heights in mm, positive outward.
  py::class_<HeightMap>(m, "HeightMap", "A measured scar height map: columns angle_deg, rows z, height row-major")
      .def_readonly("angle_deg", &HeightMap::angle_deg)
      .def_readonly("z", &HeightMap::z)
      .def_readonly("height", &HeightMap::height)
      .def_readonly("source", &HeightMap::source)
      .def_property_readonly("rows", &HeightMap::rows)
      .def_property_readonly("cols", &HeightMap::cols)
      .def_property_readonly("wraps", &HeightMap::wraps);
  py::class_<VertexHeights>(m, "VertexHeights", "Heights on a roller's vertex grid (n columns x m + 1 rows)")
      .def_readonly("n", &VertexHeights::n)
      .def_readonly("m", &VertexHeights::m)
      .def_readonly("height", &VertexHeights::height)
      .def_property_readonly("covered", [](const VertexHeights& v) { return std::vector<bool>(v.covered.begin(), v.covered.end()); })
      .def_readonly("source", &VertexHeights::source)
      .def_property_readonly("covered_count", &VertexHeights::covered_count);
  const auto value = [](auto&& e) {
    if (!e) throw py::value_error(e.error().message());
    return std::move(*e);
  };
  m.def("read_scar_csv", [value](const std::string& path) { return value(read_scar_csv(path)); }, py::arg("path"),
        "Read a CSV height map (header: a label, then the column angles in degrees; then z, heights per line). "
        "Errors (ValueError) name the file, line and field.");
  m.def(
      "parse_scar_csv",
      [value](const std::string& text, const std::string& source) { return value(parse_scar_csv(text, source)); },
      py::arg("text"), py::arg("source") = "scar.csv", "The same from text (source names it in errors).");
  m.def("scar_png_supported", &scar_png_supported, "Whether this build reads 16-bit PNG height maps (libpng).");
  m.def(
      "read_scar_png",
      [value](const std::string& path, double scale, double offset, double angle_min_deg, double angle_max_deg,
              double z_min, double z_max) {
        return value(read_scar_png(path, scale, offset, MapPlacement{angle_min_deg, angle_max_deg, z_min, z_max}));
      },
      py::arg("path"), py::arg("scale"), py::arg("offset") = 0.0, py::arg("angle_min_deg") = -20.0,
      py::arg("angle_max_deg") = 20.0, py::arg("z_min") = 10.0, py::arg("z_max") = 30.0,
      "A 16-bit grayscale PNG: height = scale * pixel + offset (mm), placed on the angle and z window "
      "(the image seen from outside, +z up).");
  m.def(
      "read_scar_points",
      [value](const std::string& path) {
        std::vector<P3> out;
        for (const Vec3& p : value(read_scar_points(path))) out.push_back(tup(p));
        return out;
      },
      py::arg("path"),
      "Points of the worn surface (roller body frame): an 'x y z' text file, or the vertices of a .stl .ply .obj "
      ".off mesh (a scanned STL of the worn region).");
  m.def(
      "resample_height_map",
      [value](const HeightMap& map, const RollerParams& roller) { return value(resample_height_map(map, roller)); },
      py::arg("map"), py::arg("roller"), "Bilinear resampling of a height map onto the roller's vertex grid.");
  m.def(
      "scar_from_points",
      [value](const std::vector<P3>& points, const RollerParams& roller, double window, const std::string& source) {
        std::vector<Vec3> pts;
        for (const P3& p : points) pts.push_back(vec(p));
        return value(scar_from_points(pts, roller, PointScarOptions{window}, source));
      },
      py::arg("points"), py::arg("roller"), py::arg("window") = 0.0, py::arg("source") = "points",
      "Inverse-distance-weighted heights per vertex from the points within `window` mm (0: one grid cell).");
  m.def(
      "make_roller_with_scar",
      [value](const RollerParams& p, const VertexHeights& heights, int border) {
        Roller r = value(make_roller(p));
        value(apply_vertex_heights(r, heights, border));
        return r;
      },
      py::arg("params"), py::arg("heights"), py::arg("border") = 0,
      "Mesh a roller carrying an imported scar (heights from resample_height_map or scar_from_points; "
      "border > 0: the generated scars' median filter over the covered region's border band).");
  m.def(
      "covered_window",
      [](const VertexHeights& h, const RollerParams& roller) { return covered_window(h, roller); }, py::arg("heights"),
      py::arg("roller"), "The smallest scar window holding every covered vertex (the range test's window).");

  py::class_<Cylinder>(m, "Cylinder")
      .def(py::init([](P3 base, P3 axis, double height, double radius, double top_radius) {
             const Vec3 a = vec(axis);
             const double l = norm(a);
             if (!(l > 0) || !std::isfinite(l)) throw py::value_error("axis must be a finite nonzero vector");
             if (!(height > 0) || !(radius > 0)) throw py::value_error("height and radius must be > 0");
             return Cylinder{vec(base), a / l, height, radius, top_radius};
           }),
           py::arg("base") = P3{0, 0, 0}, py::arg("axis") = P3{0, 0, 1}, py::arg("height") = 1.0,
           py::arg("radius") = 1.0, py::arg("top_radius") = -1.0)
      .def_property_readonly("base", [](const Cylinder& c) { return tup(c.base); })
      .def_property_readonly("axis", [](const Cylinder& c) { return tup(c.axis); })
      .def_readonly("height", &Cylinder::height)
      .def_readonly("radius", &Cylinder::radius)
      .def_property_readonly("top_radius", &Cylinder::top);

  py::class_<PairDistance>(m, "PairDistance")
      .def_readonly("distance", &PairDistance::distance)
      .def_property_readonly("point_a", [](const PairDistance& d) { return tup(d.point_a); })
      .def_property_readonly("point_b", [](const PairDistance& d) { return tup(d.point_b); })
      .def_property_readonly("path", [](const PairDistance& d) { return analytic_path_name(d.path); })
      .def_property_readonly("interference", [](const PairDistance& d) { return d.distance < 0 ? -d.distance : 0.0; });

  m.def("max_interference_distance", &cylinder_pair_distance, py::arg("a"), py::arg("b"),
        "Signed distance s(A, B) = min over solid A of sd_B (> 0 clearance, < 0: -s is the maximum interference "
        "distance), with the point pair. Exact to rounding (standard solver).");
  m.def("point_signed_distance", [](const Cylinder& c, P3 p) { return point_signed_distance(c, vec(p)); });
  m.def("barbier_galin_signed_distance", [](const Cylinder& c, P3 p) { return barbier_galin_signed_distance(c, vec(p)); });
  // Eq. (1) of Jia & Zheng 2019, §2.3 (issue #27): window.h
  const auto window_params = [](double r, double R, double hb, double max_tilt_deg) {
    const WindowParams w{r, R, hb, max_tilt_deg * kDeg};
    check(validate(w));
    return w;
  };
  m.def(
      "ideal_interference_range",
      [window_params](double r, double R, double hb, double max_tilt_deg) {
        return ideal_interference_range(window_params(r, R, hb, max_tilt_deg)) / kDeg;
      },
      py::arg("roller_radius"), py::arg("partner_radius"), py::arg("height"), py::arg("max_tilt_deg"),
      "theta of Eq. (1) in degrees, the full angle MCN: 2 acos((r^2 + d^2 - R^2) / (2 r d)), "
      "d = R + r - h_b tan(alpha); tilts must be in [0, atan(2 min(r, R) / h_b)).");
  m.def(
      "interference_window",
      [window_params](double r, double R, double hb, double max_tilt_deg) {
        return interference_window(window_params(r, R, hb, max_tilt_deg)) / kDeg;
      },
      py::arg("roller_radius"), py::arg("partner_radius"), py::arg("height"), py::arg("max_tilt_deg"),
      "The search window's half-width in degrees: theta / 2 of Eq. (1) (ideal_interference_range).");
  m.def(
      "contact_turn_bound",
      [window_params](double r, double R, double hb, double max_tilt_deg) {
        return contact_turn_bound(window_params(r, R, hb, max_tilt_deg)) / kDeg;
      },
      py::arg("roller_radius"), py::arg("partner_radius"), py::arg("height"), py::arg("max_tilt_deg"),
      "The former window, asin(h_b sin(alpha) / (R + r)) in degrees: a bound on the turn of the "
      "maximum-interference point (not the paper's range).");
  m.def(
      "roller_pose",
      [](P3 pivot, double tilt_deg, double azimuth_deg, double spin_deg) {
        return roller_pose(vec(pivot), tilt_deg * kDeg, azimuth_deg * kDeg, spin_deg * kDeg);
      },
      py::arg("pivot"), py::arg("tilt_deg") = 0.0, py::arg("azimuth_deg") = 0.0, py::arg("spin_deg") = 0.0);
  m.def(
      "posed_cylinder",
      [](const RollerParams& p, const Transform& pose) { return posed_cylinder(p.radius, p.top_radius, p.height, pose); },
      py::arg("params"), py::arg("pose"));

  py::class_<MeshPairResult>(m, "MeshPairResult")
      .def_readonly("distance", &MeshPairResult::distance)
      .def_property_readonly("point_a", [](const MeshPairResult& d) { return tup(d.point_a); })
      .def_property_readonly("point_b", [](const MeshPairResult& d) { return tup(d.point_b); })
      .def_readonly("triangle", &MeshPairResult::triangle)
      .def_readonly("evaluated", &MeshPairResult::evaluated);
  m.def("surface_reference", &surface_reference, py::arg("roller"), py::arg("pose"), py::arg("partner"),
        "Exact minimum of the partner's signed distance over the roller's (scarred) triangle surface.");
  m.def(
      "scarred_distance",
      [](const Roller& roller, const Transform& pose, const Cylinder& b) {
        const RollerQuadtree tree = build_quadtree(roller);
        ScarredSolver s(&roller, &tree);
        return s.solve(pose, b);
      },
      py::arg("roller"), py::arg("pose"), py::arg("partner"), "The quadtree branch-and-bound solver (one frame).");

  py::class_<PairFrame>(m, "PairFrame")
      .def_readonly("frame", &PairFrame::frame)
      .def_readonly("pair", &PairFrame::pair)
      .def_readonly("distance", &PairFrame::distance)
      .def_property_readonly("point_a", [](const PairFrame& r) { return tup(r.point_a); })
      .def_property_readonly("point_b", [](const PairFrame& r) { return tup(r.point_b); })
      .def_property_readonly("solver", [](const PairFrame& r) { return r.solver == 1 ? "scarred" : "standard"; })
      .def_readonly("scar_in_range", &PairFrame::scar_in_range)
      .def_readonly("tilt_deg", &PairFrame::tilt_deg)
      .def_property_readonly("verdict", [](const PairFrame& r) { return verdict_name(r.verdict); });
  py::class_<CrossPair>(m, "CrossPair", "A pair of parts of different bearing pairs (part 2k: roller k, 2k + 1: its partner)")
      .def_readonly("frame", &CrossPair::frame)
      .def_readonly("part_a", &CrossPair::part_a)
      .def_readonly("part_b", &CrossPair::part_b)
      .def_readonly("distance", &CrossPair::distance)
      .def_property_readonly("point_a", [](const CrossPair& c) { return tup(c.point_a); })
      .def_property_readonly("point_b", [](const CrossPair& c) { return tup(c.point_b); })
      .def_property_readonly("solver", [](const CrossPair& c) { return part_pair_solver_name(c.solver); })
      .def_property_readonly("verdict", [](const CrossPair& c) { return verdict_name(c.verdict); });
  py::class_<SimulationResult>(m, "SimulationResult")
      .def_readonly("rows", &SimulationResult::rows)
      .def_readonly("min_distance", &SimulationResult::min_distance)
      .def_readonly("interfering_rows", &SimulationResult::interfering_rows)
      .def_readonly("scarred_solves", &SimulationResult::scarred_solves)
      .def_readonly("scarred_rollers", &SimulationResult::scarred_rollers)
      .def_readonly("cross_pairs", &SimulationResult::cross_pairs)
      .def_readonly("cross_results", &SimulationResult::cross_results)
      .def_property_readonly("verdict", [](const SimulationResult& r) { return verdict_name(r.verdict); })
      .def_readonly("undecided_reasons", &SimulationResult::undecided_reasons)
      .def_property_readonly("theta_deg", [](const SimulationResult& r) { return r.theta / kDeg; })
      .def_readonly("frames_per_second", &SimulationResult::frames_per_second);
  m.def(
      "simulate",
      [](int pairs, int frames, const RollerParams& roller, double partner_radius, double partner_height, double gap,
         double max_tilt_deg, double spin_deg_per_frame, double scar_fraction, const ScarParams& scar,
         std::uint64_t seed, const std::string& broad_phase, double spacing, double clearance,
         std::optional<VertexHeights> imported_scar) {
        SceneParams p;
        if (imported_scar) p.imported_scar = std::move(*imported_scar);
        p.pairs = pairs, p.frames = frames, p.roller = roller, p.partner_radius = partner_radius;
        p.partner_height = partner_height, p.gap = gap, p.max_tilt_deg = max_tilt_deg;
        p.spin_deg_per_frame = spin_deg_per_frame, p.scar_fraction = scar_fraction, p.scar = scar, p.seed = seed;
        p.spacing = spacing, p.clearance = clearance;
        if (!parse_broad_phase(broad_phase, p.broad_phase))
          throw py::value_error("broad_phase must be one of brute, sap, octree, bvh");
        Expected<SimulationResult> r = Error{};
        {
          py::gil_scoped_release release;
          r = simulate(p);
        }
        if (!r) throw py::value_error(r.error().message());
        return std::move(*r);
      },
      py::arg("pairs") = 4, py::arg("frames") = 10, py::arg("roller") = RollerParams{}, py::arg("partner_radius") = 30.0,
      py::arg("partner_height") = 60.0, py::arg("gap") = 0.0, py::arg("max_tilt_deg") = 1.0,
      py::arg("spin_deg_per_frame") = 3.0, py::arg("scar_fraction") = 0.25, py::arg("scar") = ScarParams{},
      py::arg("seed") = 1, py::arg("broad_phase") = "sap", py::arg("spacing") = 0.0, py::arg("clearance") = 0.0,
      py::arg("imported_scar") = std::nullopt,
      "Run the dynamic simulation (interfere bearing; imported_scar: VertexHeights that every scarred roller carries, issue #27) and return every pair's per-frame result, the non-clear "
      "pairs of parts of different pairs (cross_results) and the verdict ('clash', 'contact', 'clearance', "
      "'clear', 'undecided').");

  // Bearing assemblies (issue #27): a JSON description run over generated or file motion; the rows
  // as parallel lists (one entry per frame and pair, frame-major), like the CLI's CSV.
  m.def(
      "run_assembly",
      [](const std::string& path, int frames, py::object seed, const std::string& motion_file) {
        Expected<AssemblySpec> spec = read_assembly_file(path);
        if (!spec) throw py::value_error(spec.error().message());
        Expected<Assembly> as = build_assembly(*spec);
        if (!as) throw py::value_error(as.error().message());
        AssemblyMotion motion;
        if (!motion_file.empty()) {
          Expected<AssemblyMotion> mm = read_assembly_motion(*as, motion_file);
          if (!mm) throw py::value_error(mm.error().message());
          motion = std::move(*mm);
        } else {
          if (frames < 1) throw py::value_error("frames must be >= 1");
          motion = generate_motion(*as, frames, seed.is_none() ? spec->seed : seed.cast<std::uint64_t>());
        }
        AssemblyResult r;
        {
          py::gil_scoped_release release;
          r = run_assembly(*as, motion);
        }
        py::list frame, kind, a, b, distance, pa, pb, solver, scar, exact, two_sided, verdict, scar_part;
        for (const AssemblyRow& row : r.rows) {
          const AssemblyPair& p = as->pairs[row.pair];
          const AssemblyPairResult& x = row.result;
          frame.append(row.frame), kind.append(assembly_pair_kind_name(p.kind));
          a.append(as->parts[p.a].id), b.append(as->parts[p.b].id);
          distance.append(x.distance), pa.append(tup(x.point_a)), pb.append(tup(x.point_b));
          solver.append(assembly_solver_name(x.solver)), scar.append(x.scar), exact.append(x.exact);
          two_sided.append(x.two_sided), verdict.append(verdict_name(x.verdict));
          // the part whose scar the row measured (issue #27: a scarred roller or a scarred raceway's ring)
          if (x.scar_part == 1) scar_part.append(as->parts[p.a].id);
          else if (x.scar_part == 2) scar_part.append(as->parts[p.b].id);
          else scar_part.append(py::none());
        }
        py::dict out;
        out["frames"] = r.frames, out["pairs_per_frame"] = as->pairs.size(), out["frame"] = frame;
        out["kind"] = kind, out["a"] = a, out["b"] = b, out["distance"] = distance, out["point_a"] = pa;
        out["point_b"] = pb, out["solver"] = solver, out["scar"] = scar, out["exact"] = exact;
        out["two_sided"] = two_sided, out["verdict"] = verdict_name(r.verdict), out["scar_part"] = scar_part;
        out["row_verdict"] = verdict, out["worst"] = r.rows.empty() ? -1 : static_cast<long>(r.worst);
        out["motion"] = motion.source;
        return out;
      },
      py::arg("path"), py::arg("frames") = 1, py::arg("seed") = py::none(), py::arg("motion_file") = "",
      "Run a bearing assembly (JSON description, docs/bearing.md) over generated motion (frames, seed; the "
      "description's seed by default) or a motion file, and return every row as parallel lists: frame, kind, "
      "a, b, distance (> 0 clearance, < 0 minus the depth), point_a, point_b, solver, scar, exact, two_sided, "
      "row_verdict, scar_part (the id of the part whose scar the row measured, or None; raceway scars: "
      "bearings[i].scars); with frames, pairs_per_frame, worst (the row of the smallest distance), the verdict and "
      "the motion's source.");
}

}  // namespace interfere::python
