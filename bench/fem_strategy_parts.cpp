// FE assembly parts generated with the gmsh SDK (issue #26, item 6): see fem_strategy_parts.h.
#include "fem_strategy_parts.h"

#include <gmsh.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "interfere/fem/io.h"
#include "interfere/fem/surface.h"
#include "interfere/mesh/validate.h"

#ifndef INTERFERE_BINARY_DIR
#define INTERFERE_BINARY_DIR "."
#endif

namespace interfere::bench {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;

// ---- geometry (metres) ----
// Vacuum-vessel sector: torus shell, cross-section an annulus centred at (kR0, 0) in the (R, z)
// plane, revolved over kSector about z (from -kSector/2).
constexpr double kR0 = 6.0, kRi = 2.0, kRo = 2.2, kSector = kPi / 8;
// Port duct: hollow rectangle kW (y) × kH (z), wall kT, from x = kX0 along +x over kLen, its
// cross-section centred at (kYc, kZc), then tilted by kTilt about the y axis through (kCx, 0, 0).
constexpr double kW = 1.6, kH = 2.0, kT = 0.15, kLen = 2.5, kX0 = 7.0, kYc = 0.05, kZc = 0.03;
constexpr double kTilt = 3.0 * kPi / 180, kCx = 8.0;
constexpr int kLayers = 2;  // elements through each wall

/// The grid make(k), k = 1, 2, ..., whose surface triangle count is closest to n.
template <class Make>
auto closest_grid(std::size_t n, Make make) {
  const auto miss = [n](std::size_t t) { return t > n ? t - n : n - t; };
  auto best = make(1);
  for (int k = 2; k < 4000; ++k) {
    const auto g = make(k);
    if (miss(g.triangles()) < miss(best.triangles())) best = g;
    if (g.triangles() > 2 * n) break;
  }
  return best;
}

/// Element counts of the vessel: arcs per quarter of the cross-section, layers of the revolution
/// (spaced as the arcs at mid-wall).
struct VesselGrid {
  int m = 0, p = 0;
  std::size_t triangles() const { return 16u * m * (p + kLayers); }
};
VesselGrid vessel_grid(std::size_t n) {
  return closest_grid(n, [](int m) {
    const double h = 2 * kPi * 0.5 * (kRi + kRo) / (4 * m);
    return VesselGrid{m, std::max(1, static_cast<int>(std::lround(kR0 * kSector / h)))};
  });
}

/// Element counts of the port: segments along the y sides, the z sides, and the axis.
struct PortGrid {
  int kw = 0, kh = 0, nx = 0;
  std::size_t triangles() const { return 8u * (kw + kh) * (nx + kLayers); }
};
PortGrid port_grid(std::size_t n) {
  return closest_grid(n, [](int kh) {
    return PortGrid{std::max(1, static_cast<int>(std::lround(kh * kW / kH))), kh,
                    std::max(1, static_cast<int>(std::lround(kh * kLen / kH)))};
  });
}

/// Tilts a point of the port about the y axis through (kCx, 0, 0).
std::array<double, 3> tilt(double x, double y, double z) {
  const double c = std::cos(kTilt), s = std::sin(kTilt);
  return {kCx + (x - kCx) * c + z * s, y, -(x - kCx) * s + z * c};
}

std::vector<int> volumes_of(const gmsh::vectorpair& dim_tags) {
  std::vector<int> out;
  for (const auto& [dim, tag] : dim_tags) {
    if (dim == 3) out.push_back(tag);
  }
  return out;
}

/// The vessel sector: 4 transfinite quad patches revolved with recombined layers (hex8).
std::vector<int> add_vessel(std::size_t n) {
  namespace geo = gmsh::model::geo;
  const VesselGrid g = vessel_grid(n);
  const double phi = -kSector / 2, cp = std::cos(phi), sp = std::sin(phi);
  auto point = [&](double r_major, double z) { return geo::addPoint(r_major * cp, r_major * sp, z); };
  const int centre = point(kR0, 0);
  int in[4], out[4];
  for (int k = 0; k < 4; ++k) {
    const double a = k * kPi / 2;
    in[k] = point(kR0 + kRi * std::cos(a), kRi * std::sin(a));
    out[k] = point(kR0 + kRo * std::cos(a), kRo * std::sin(a));
  }
  int arc_in[4], arc_out[4], radial[4];
  for (int k = 0; k < 4; ++k) {
    arc_in[k] = geo::addCircleArc(in[k], centre, in[(k + 1) % 4]);
    arc_out[k] = geo::addCircleArc(out[k], centre, out[(k + 1) % 4]);
    radial[k] = geo::addLine(in[k], out[k]);
  }
  gmsh::vectorpair patches;
  for (int k = 0; k < 4; ++k) {
    const int loop =
        geo::addCurveLoop({radial[k], arc_out[k], -radial[(k + 1) % 4], -arc_in[k]});
    const int s = geo::addPlaneSurface({loop});
    geo::mesh::setTransfiniteCurve(arc_in[k], g.m + 1);
    geo::mesh::setTransfiniteCurve(arc_out[k], g.m + 1);
    geo::mesh::setTransfiniteCurve(radial[k], kLayers + 1);
    geo::mesh::setTransfiniteSurface(s);
    geo::mesh::setRecombine(2, s);
    patches.emplace_back(2, s);
  }
  gmsh::vectorpair made;
  geo::revolve(patches, 0, 0, 0, 0, 0, 1, kSector, made, {g.p}, {}, true);
  return volumes_of(made);
}

/// The port duct: 4 transfinite triangle patches extruded without recombination (tet4).
std::vector<int> add_port(std::size_t n) {
  namespace geo = gmsh::model::geo;
  const PortGrid g = port_grid(n);
  const double oy[4] = {-1, 1, 1, -1}, oz[4] = {-1, -1, 1, 1};
  int outer[4], inner[4];
  for (int k = 0; k < 4; ++k) {
    const auto o = tilt(kX0, kYc + oy[k] * kW / 2, kZc + oz[k] * kH / 2);
    const auto i = tilt(kX0, kYc + oy[k] * (kW / 2 - kT), kZc + oz[k] * (kH / 2 - kT));
    outer[k] = geo::addPoint(o[0], o[1], o[2]);
    inner[k] = geo::addPoint(i[0], i[1], i[2]);
  }
  int edge_out[4], edge_in[4], diagonal[4];
  for (int k = 0; k < 4; ++k) {
    edge_out[k] = geo::addLine(outer[k], outer[(k + 1) % 4]);
    edge_in[k] = geo::addLine(inner[k], inner[(k + 1) % 4]);
    diagonal[k] = geo::addLine(inner[k], outer[k]);
  }
  gmsh::vectorpair patches;
  for (int k = 0; k < 4; ++k) {
    const int loop =
        geo::addCurveLoop({diagonal[k], edge_out[k], -diagonal[(k + 1) % 4], -edge_in[k]});
    const int s = geo::addPlaneSurface({loop});
    const int segments = (k % 2 == 0) ? g.kw : g.kh;  // edges 0, 2 run along y
    geo::mesh::setTransfiniteCurve(edge_out[k], segments + 1);
    geo::mesh::setTransfiniteCurve(edge_in[k], segments + 1);
    geo::mesh::setTransfiniteCurve(diagonal[k], kLayers + 1);
    geo::mesh::setTransfiniteSurface(s);
    patches.emplace_back(2, s);
  }
  const auto axis = tilt(kX0 + kLen, 0, 0), base = tilt(kX0, 0, 0);
  gmsh::vectorpair made;
  geo::extrude(patches, axis[0] - base[0], axis[1] - base[1], axis[2] - base[2], made, {g.nx}, {},
               false);
  return volumes_of(made);
}

/// Generates the assembly at scale n into `file` (written under a temporary name, then renamed).
void generate(const fs::path& file, std::size_t n) {
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::model::add("fem_strategy_parts");
  const std::vector<int> vessel = add_vessel(n);
  const std::vector<int> port = add_port(n);
  gmsh::model::geo::synchronize();
  gmsh::model::addPhysicalGroup(3, vessel, 1);
  gmsh::model::setPhysicalName(3, 1, "vacuum_vessel");
  gmsh::model::addPhysicalGroup(3, port, 2);
  gmsh::model::setPhysicalName(3, 2, "port");
  gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
  gmsh::option::setNumber("Mesh.Binary", 1);
  gmsh::option::setNumber("Mesh.SaveAll", 0);
  gmsh::model::mesh::generate(3);
  const fs::path tmp = file.parent_path() /
                       (file.stem().string() + ".tmp" + std::to_string(getpid()) + ".msh");
  gmsh::write(tmp.string());
  gmsh::finalize();
  fs::rename(tmp, file);
}

fs::path cache_dir() {
  const char* env = std::getenv("INTERFERE_BENCH_FEM_CACHE");
  return env && *env ? fs::path(env) : fs::path(INTERFERE_BINARY_DIR) / "bench_cache" / "fem_strategies";
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

[[noreturn]] void fail(const fs::path& file, const std::string& what) {
  throw std::runtime_error(file.string() + ": " + what);
}

/// One closed, outward component whose enclosed volume is within `rel` of `analytic`; returns the
/// surface's statistics.
MeshStats check_part(const fs::path& file, const SurfacePart& part, double analytic, double rel) {
  const MeshStats st = mesh_stats(part.mesh);
  if (part.components != 1 || part.open_components || part.degenerate_components ||
      part.nonorientable_components || !st.closed()) {
    fail(file, "part '" + part.name + "' is not one closed, orientable component (components " +
                   std::to_string(part.components) + ", open " +
                   std::to_string(part.open_components) + ", open edges " +
                   std::to_string(st.open_edges) + ")");
  }
  const double v = part.enclosed_volume;
  if (!(v > 0) || !(std::abs(v - analytic) <= rel * analytic)) {
    fail(file, "part '" + part.name + "' encloses volume " + std::to_string(v) +
                   ", the solid's is " + std::to_string(analytic) + " (relative tolerance " +
                   std::to_string(rel) + ")");
  }
  return st;
}

}  // namespace

FemAssembly load_fem_assembly(const fs::path& file) {
  FemAssembly out;
  out.file = file;
  auto t0 = std::chrono::steady_clock::now();
  Expected<FemMesh> mesh = read_fem(file);
  if (!mesh) fail(file, mesh.error().message());
  out.read_seconds = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  Expected<SurfaceResult> surface =
      extract_surface(*mesh, SurfaceOptions{.split = PartSplit::by_group});
  if (!surface) fail(file, surface.error().message());
  out.extract_seconds = seconds_since(t0);
  out.nodes = mesh->num_nodes();
  for (ElemType t : mesh->elem_types) {
    out.hex_elements += t == ElemType::hex8;
    out.tet_elements += t == ElemType::tet4;
  }
  const SurfacePart* vessel = nullptr;
  const SurfacePart* port = nullptr;
  for (const SurfacePart& p : surface->parts) {
    if (p.name == "vacuum_vessel") vessel = &p;
    if (p.name == "port") port = &p;
  }
  if (!vessel || !port || surface->parts.size() != 2) {
    fail(file, "expected the two parts 'vacuum_vessel' and 'port', got " +
                   std::to_string(surface->parts.size()) + " parts");
  }
  out.vessel_volume_analytic = kPi * (kRo * kRo - kRi * kRi) * kR0 * kSector;  // Pappus
  out.port_volume_analytic = (kW * kH - (kW - 2 * kT) * (kH - 2 * kT)) * kLen;
  // The vessel's cross-section is a polygon inscribed in the circles and its revolution is made of
  // chords: a little less volume, under 0.5% from the smallest scale on. The port is planar.
  out.vessel_stats = check_part(file, *vessel, out.vessel_volume_analytic, 5e-3);
  out.port_stats = check_part(file, *port, out.port_volume_analytic, 1e-9);
  if (vessel->enclosed_volume > out.vessel_volume_analytic) {
    fail(file, "the vessel's polygonal surface encloses more than the torus sector");
  }
  if (out.hex_elements == 0 || out.tet_elements == 0 ||
      out.hex_elements + out.tet_elements != mesh->num_elements()) {
    fail(file, "expected hex8 (vessel) and tet4 (port) elements only");
  }
  out.vessel_volume = vessel->enclosed_volume;
  out.port_volume = port->enclosed_volume;
  out.vessel = vessel->mesh;
  out.port = port->mesh;
  return out;
}

const FemAssembly& fem_assembly(std::size_t n) {
  static std::mutex mutex;
  static std::map<std::size_t, std::unique_ptr<FemAssembly>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[n];
  if (slot) return *slot;
  const fs::path dir = cache_dir();
  fs::create_directories(dir);
  // The name carries the scale and a version of the geometry above (bump it when that changes).
  const fs::path file = dir / ("cfetr_like_parts_v1_n" + std::to_string(n) + ".msh");
  // gmsh's time is kept beside the file, so that a run on cached files still reports it.
  const fs::path timing = fs::path(file).replace_extension(".gmsh-seconds");
  double generate_seconds = 0;
  if (!fs::exists(file)) {
    const auto t0 = std::chrono::steady_clock::now();
    generate(file, n);
    generate_seconds = seconds_since(t0);
    std::ofstream(timing) << generate_seconds << "\n";
  } else {
    std::ifstream(timing) >> generate_seconds;
  }
  slot = std::make_unique<FemAssembly>(load_fem_assembly(file));
  slot->generate_seconds = generate_seconds;
  std::fprintf(stderr,
               "fem parts n=%zu: %s (%zu hex8 + %zu tet4, %zu nodes), surfaces %zu + %zu "
               "triangles; gmsh %.2f s (when written), read_fem %.2f s, extract_surface %.2f s\n",
               n, file.string().c_str(), slot->hex_elements, slot->tet_elements, slot->nodes,
               slot->vessel.num_triangles(), slot->port.num_triangles(), generate_seconds,
               slot->read_seconds, slot->extract_seconds);
  return *slot;
}

}  // namespace interfere::bench
