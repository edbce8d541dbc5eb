#include "common.h"

#include <cstdio>
#include <fstream>
#include <memory>

#include <tbb/global_control.h>
#include <tbb/info.h>

namespace interfere::cli {

Progress::Progress(std::string what) : what_(std::move(what)), start_(std::chrono::steady_clock::now()) {
  if (!quiet_) std::fprintf(stderr, "[interfere] %s ...\n", what_.c_str());
}
Progress::~Progress() {
  if (!quiet_) std::fprintf(stderr, "[interfere] %s: %.3f s\n", what_.c_str(), seconds());
}
double Progress::seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

LoadedPart load_part(const PartSpec& spec, const std::string& label, const BvhBuildOptions& bvh) {
  LoadedPart p;
  p.file = spec.file;
  if (!spec.transform.empty()) {
    auto t = Transform::parse(spec.transform);
    if (!t) throw InputError("--transform-" + label + ": " + t.error().reason);
    p.transform = *t;
  }
  TriMesh mesh;
  {
    Progress progress("reading " + label + " (" + spec.file + ")");
    MeshReadInfo info;
    auto m = read_mesh(spec.file, {}, &info);
    if (!m) throw InputError(m.error());
    mesh = std::move(*m);
    p.format = info.format;
    p.read_seconds = progress.seconds();
  }
  if (!p.transform.is_identity()) mesh = transformed(mesh, p.transform);
  for (const Vec3& v : mesh.positions) {
    if (!is_finite(v)) throw InputError(spec.file + ": transform produced a non-finite coordinate");
  }
  {
    Progress progress("building tree " + label + " (" + std::to_string(mesh.num_triangles()) + " triangles)");
    p.model = make_model(std::move(mesh), bvh, true);
    p.build_seconds = progress.seconds();
  }
  return p;
}

namespace {
std::string transform_from_json(const nlohmann::json& j, const std::string& where) {
  if (j.is_string()) return j.get<std::string>();
  if (j.is_array()) {
    std::string s;  // JSON's own number text keeps every digit
    for (const auto& x : j) {
      if (!x.is_number()) throw InputError(where + ": transform entries must be numbers");
      s += x.dump() + " ";
    }
    return s;
  }
  throw InputError(where + ": transform must be an array of 12 numbers or a string");
}
}  // namespace

void apply_scene(const std::string& scene_path, PartSpec& a, PartSpec& b, std::string& units) {
  std::ifstream in(scene_path);
  if (!in) throw InputError(scene_path + ": cannot open scene file");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(scene_path + ": byte " + std::to_string(e.byte) + ": invalid JSON: " + e.what());
  }
  if (!j.is_object()) throw InputError(scene_path + ": scene must be a JSON object");
  const std::filesystem::path dir = std::filesystem::path(scene_path).parent_path();
  auto part = [&](const char* key, PartSpec& spec) {
    if (!j.contains(key)) throw InputError(scene_path + ": missing part \"" + key + "\"");
    const auto& p = j[key];
    if (!p.is_object() || !p.contains("file") || !p["file"].is_string()) {
      throw InputError(scene_path + ": part \"" + key + "\" needs a \"file\" string");
    }
    if (spec.file.empty()) {
      std::filesystem::path f = p["file"].get<std::string>();
      spec.file = (f.is_relative() ? dir / f : f).string();
    }
    if (spec.transform.empty() && p.contains("transform")) {
      spec.transform = transform_from_json(p["transform"], scene_path + ": part \"" + key + "\"");
    }
  };
  part("a", a);
  part("b", b);
  if (j.contains("units")) {
    if (!j["units"].is_string()) throw InputError(scene_path + ": \"units\" must be a string");
    if (units.empty()) units = j["units"].get<std::string>();
  }
}

BvhBuilder parse_builder(const std::string& name) {
  if (name == "lbvh") return BvhBuilder::lbvh;
  if (name == "sah" || name == "binned_sah") return BvhBuilder::binned_sah;
  if (name == "median" || name == "median_split") return BvhBuilder::median_split;
  if (name == "insertion") return BvhBuilder::insertion;
  throw InputError("--builder: unknown builder '" + name + "' (lbvh, sah, median, insertion)");
}

void check_units(const std::string& units) {
  for (const char* u : {"mm", "cm", "m", "um", "in", "ft"}) {
    if (units == u) return;
  }
  throw InputError("--units: unknown unit '" + units + "' (mm, cm, m, um, in, ft)");
}

namespace {
std::unique_ptr<tbb::global_control> g_threads;
}

void set_threads(int threads) {
  if (threads < 0) throw InputError("--threads must be >= 0 (0 = all cores)");
  const int n = threads == 0 ? tbb::info::default_concurrency() : threads;
  g_threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, n);
}

int active_threads() {
  return static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

nlohmann::json part_json(const LoadedPart& p) {
  const MeshStats& s = p.model.stats;
  return {{"file", p.file},
          {"format", mesh_format_name(p.format)},
          {"vertices", s.vertices},
          {"triangles", s.triangles},
          {"degenerate_triangles", s.degenerate_triangles},
          {"duplicate_triangles", s.duplicate_triangles},
          {"open_edges", s.open_edges},
          {"nonmanifold_edges", s.nonmanifold_edges},
          {"inconsistent_edges", s.inconsistent_edges},
          {"components", s.components},
          {"closed", s.closed()},
          {"transform", p.transform.to_row_major()},
          {"read_seconds", p.read_seconds},
          {"build_seconds", p.build_seconds}};
}

}  // namespace interfere::cli
