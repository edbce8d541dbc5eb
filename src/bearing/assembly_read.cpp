// Reading a bearing assembly description (assembly.h; docs/bearing.md, "Bearing assemblies"). Every
// error names the file and the JSON path of the value: unknown keys, wrong types, missing fields.
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "../scene/json_input.h"
#include "interfere/bearing/assembly.h"

namespace interfere::bearing {
namespace {

using nlohmann::json;
using scene::detail::json_key;
using scene::detail::json_type;

struct ReadError {
  Error error;
};

/// One JSON object being read: fields are taken by name, and finish() rejects the keys not taken.
class Obj {
 public:
  Obj(const json& j, std::string path, const std::string& file) : j_(j), path_(std::move(path)), file_(file) {
    if (!j_.is_object()) fail(path_, std::string("expected an object, got ") + json_type(j_));
  }
  [[noreturn]] void fail(const std::string& path, const std::string& reason) const {
    throw ReadError{Error{.file = file_, .reason = (path.empty() ? "" : path + ": ") + reason}};
  }
  std::string at(const std::string& key) const { return json_key(path_, key); }
  const json* get(const std::string& key) {
    taken_.insert(key);
    const auto it = j_.find(key);
    return it == j_.end() ? nullptr : &*it;
  }
  const json& need(const std::string& key) {
    const json* v = get(key);
    if (v == nullptr) fail(at(key), "missing (required)");
    return *v;
  }
  double number(const json& v, const std::string& key) const {
    if (!v.is_number()) fail(at(key), std::string("expected a number, got ") + json_type(v));
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(at(key), "not a finite number");
    return d;
  }
  void num(const std::string& key, double& out, bool required) {
    const json* v = required ? &need(key) : get(key);
    if (v != nullptr) out = number(*v, key);
  }
  void integer(const std::string& key, int& out, bool required) {
    const json* v = required ? &need(key) : get(key);
    if (v == nullptr) return;
    if (!v->is_number_integer()) fail(at(key), std::string("expected an integer, got ") + json_type(*v));
    const auto i = v->get<std::int64_t>();
    if (i < std::numeric_limits<int>::min() || i > std::numeric_limits<int>::max()) fail(at(key), "out of range");
    out = static_cast<int>(i);
  }
  void unsigned_integer(const std::string& key, std::uint64_t& out) {
    const json* v = get(key);
    if (v == nullptr) return;
    if (!v->is_number_unsigned()) fail(at(key), std::string("expected a non-negative integer, got ") + json_type(*v));
    out = v->get<std::uint64_t>();
  }
  void vec3(const std::string& key, Vec3& out, bool required) {
    const json* v = required ? &need(key) : get(key);
    if (v == nullptr) return;
    if (!v->is_array() || v->size() != 3) fail(at(key), "expected an array of 3 numbers");
    double c[3];
    for (int i = 0; i < 3; ++i) c[i] = number((*v)[i], key + "[" + std::to_string(i) + "]");
    out = {c[0], c[1], c[2]};
  }
  void string(const std::string& key, std::string& out, bool required) {
    const json* v = required ? &need(key) : get(key);
    if (v == nullptr) return;
    if (!v->is_string()) fail(at(key), std::string("expected a string, got ") + json_type(*v));
    out = v->get<std::string>();
  }
  Obj child(const std::string& key, bool required) {
    static const json kEmpty = json::object();
    const json* v = required ? &need(key) : get(key);
    return Obj(v == nullptr ? kEmpty : *v, at(key), file_);
  }
  bool has(const std::string& key) const { return j_.contains(key); }
  void finish() const {
    for (auto it = j_.begin(); it != j_.end(); ++it)
      if (!taken_.count(it.key())) fail(at(it.key()), "unknown key");
  }
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  void boolean(const std::string& key, bool& out) {
    const json* v = get(key);
    if (v == nullptr) return;
    if (!v->is_boolean()) fail(at(key), std::string("expected true or false, got ") + json_type(*v));
    out = v->get<bool>();
  }

 private:
  const json& j_;
  std::string path_;
  const std::string& file_;
  std::set<std::string> taken_;
};

void read_rollers(Obj o, BearingSpec& b) {
  RollerSetSpec& r = b.rollers;
  o.integer("count", r.count, true);
  o.num("radius", r.radius, true);
  o.num("length", r.length, true);
  if (b.type == BearingType::tapered) {
    o.num("top_radius", r.top_radius, true);
  } else {
    o.num("pitch_radius", r.pitch_radius, true);
  }
  o.integer("radial_segments", r.radial_segments, false);
  o.integer("height_segments", r.height_segments, false);
  o.finish();
}

void read_cage(Obj o, CageSpec& c) {
  o.num("pocket_clearance", c.pocket_clearance, true);
  o.num("web_thickness", c.web_thickness, true);
  o.num("width", c.width, false);
  o.finish();
}

/// bearings[i].scars[k] (issue #27; raceway_scar.h): a generated or imported raceway scar.
RacewayScarSpec read_raceway_scar(Obj o, const BearingSpec& b) {
  RacewayScarSpec s;
  s.where = o.path();
  s.scar.z_min = s.scar.z_max = -1;  // defaults: the middle half of the raceway's width
  std::string part;
  o.string("part", part, true);
  const bool cyl = b.type == BearingType::cylindrical;
  if (cyl && part == "inner") s.part = RacewaySurface::inner;
  else if (cyl && part == "outer") s.part = RacewaySurface::outer;
  else if (!cyl && part == "cone") s.part = RacewaySurface::cone;
  else if (!cyl && part == "cup") s.part = RacewaySurface::cup;
  else
    o.fail(o.at("part"), std::string("expected ") + (cyl ? "\"inner\" or \"outer\"" : "\"cone\" or \"cup\"") +
                             " (a " + bearing_type_name(b.type) + " bearing's raceways), got \"" + part + "\"");
  o.string("map", s.map, false);
  o.string("png", s.png, false);
  o.string("points", s.points, false);
  if (int(!s.map.empty()) + int(!s.png.empty()) + int(!s.points.empty()) > 1)
    o.fail(o.path(), "map, png and points exclude each other (one imported scar per entry)");
  o.num("angle_center_deg", s.scar.angle_center_deg, false);
  o.num("angle_width_deg", s.scar.angle_width_deg, false);
  o.num("z_min", s.scar.z_min, false);
  o.num("z_max", s.scar.z_max, false);
  if (s.imported()) {
    for (const char* only : {"depth", "roughness", "seed", "raised"})
      if (o.has(only)) o.fail(o.at(only), "only for a generated scar (not with map, png or points)");
    o.integer("border", s.border, false);
  } else {
    o.num("depth", s.scar.depth, false);
    o.num("roughness", s.scar.roughness, false);
    o.integer("border", s.scar.border, false);
    o.unsigned_integer("seed", s.scar.seed);
    o.boolean("raised", s.scar.raised);
  }
  if (!s.png.empty()) {
    o.num("scale", s.png_scale, true);
    o.num("offset", s.png_offset, false);
  }
  if (!s.points.empty()) o.num("window", s.points_window, false);
  o.integer("radial_segments", s.grid.radial_segments, false);
  o.integer("height_segments", s.grid.height_segments, false);
  o.finish();
  return s;
}

BearingSpec read_bearing(Obj o, std::size_t index) {
  BearingSpec b;
  b.where = o.path();
  b.id = "b" + std::to_string(index);
  o.string("id", b.id, false);
  std::string type;
  o.string("type", type, true);
  if (type == "cylindrical") b.type = BearingType::cylindrical;
  else if (type == "tapered") b.type = BearingType::tapered;
  else o.fail(o.at("type"), "expected \"cylindrical\" or \"tapered\", got \"" + type + "\"");
  o.vec3("position", b.position, false);
  o.vec3("axis", b.axis, false);
  const double n = norm(b.axis);
  if (!(n > 0) || !std::isfinite(n)) o.fail(o.at("axis"), "must be a non-zero finite vector");
  b.axis = b.axis / n;
  read_rollers(o.child("rollers", true), b);
  read_cage(o.child("cage", true), b.cage);
  if (b.type == BearingType::cylindrical) {
    Obj in = o.child("inner_ring", true);
    in.num("bore_radius", b.inner_bore, true);
    in.num("raceway_radius", b.inner_raceway, true);
    in.num("width", b.inner_width, true);
    Obj rib = in.child("rib", true);
    rib.num("height", b.rib_height, true);
    rib.num("width", b.rib_width, true);
    rib.finish();
    in.finish();
    Obj out = o.child("outer_ring", true);
    out.num("raceway_radius", b.outer_raceway, true);
    out.num("outer_radius", b.outer_radius, true);
    out.num("width", b.outer_width, true);
    out.finish();
  } else {
    o.num("contact_angle_deg", b.contact_angle_deg, true);
    Obj cone = o.child("cone", true);
    cone.num("bore_radius", b.cone_bore, true);
    cone.num("clearance", b.cone_clearance, false);
    cone.finish();
    Obj cup = o.child("cup", true);
    cup.num("outer_radius", b.cup_outer, true);
    cup.num("clearance", b.cup_clearance, false);
    cup.finish();
  }
  if (const json* scars = o.get("scars"); scars != nullptr) {
    if (!scars->is_array()) o.fail(o.at("scars"), std::string("expected an array, got ") + json_type(*scars));
    for (std::size_t k = 0; k < scars->size(); ++k)
      b.scars.push_back(read_raceway_scar(Obj((*scars)[k], o.at("scars") + "[" + std::to_string(k) + "]", o.file()), b));
  }
  o.finish();
  return b;
}

AssemblySpec read_root(const json& root, const std::string& file) {
  AssemblySpec s;
  s.file = file;
  s.scar.z_min = s.scar.z_max = -1;  // relative defaults (validate/build)
  Obj o(root, "", file);
  o.integer("frames", s.frames, false);
  o.unsigned_integer("seed", s.seed);
  o.num("clearance", s.clearance, false);
  o.integer("ring_segments", s.ring_segments, false);
  if (o.has("motion")) {
    Obj m = o.child("motion", false);
    AssemblyMotionSpec& mo = s.motion;
    m.num("inner_deg_per_frame", mo.inner_deg_per_frame, false);
    m.num("max_tilt_deg", mo.max_tilt_deg, false);
    m.num("pocket_play", mo.pocket_play, false);
    m.num("axial_play", mo.axial_play, false);
    if (m.has("load")) {
      Obj l = m.child("load", false);
      l.num("direction_deg", mo.load_direction_deg, false);
      l.num("displacement", mo.load_displacement, true);
      l.finish();
    }
    m.finish();
  }
  if (o.has("scar")) {
    const json* v = o.get("scar");
    if (!v->is_null()) {
      Obj sc(*v, "scar", file);
      sc.num("fraction", s.scar_fraction, true);
      sc.num("angle_center_deg", s.scar.angle_center_deg, false);
      sc.num("angle_width_deg", s.scar.angle_width_deg, false);
      sc.num("z_min", s.scar.z_min, false);
      sc.num("z_max", s.scar.z_max, false);
      // an imported roller scar (issue #27): the keys of the raceway scars' imports
      RollerScarImport& im = s.scar_import;
      sc.string("map", im.map, false);
      sc.string("png", im.png, false);
      sc.string("points", im.points, false);
      if (int(!im.map.empty()) + int(!im.png.empty()) + int(!im.points.empty()) > 1)
        sc.fail("scar", "map, png and points exclude each other (one imported scar)");
      if (im.any()) {
        for (const char* only : {"depth", "roughness", "seed", "raised"})
          if (sc.has(only)) sc.fail(sc.at(only), "only for a generated scar (not with map, png or points)");
        sc.integer("border", im.border, false);
        if (!im.png.empty()) {
          sc.num("scale", im.png_scale, true);
          sc.num("offset", im.png_offset, false);
        }
        if (!im.points.empty()) sc.num("window", im.points_window, false);
      } else {
        sc.num("depth", s.scar.depth, false);
        sc.num("roughness", s.scar.roughness, false);
        sc.integer("border", s.scar.border, false);
        sc.unsigned_integer("seed", s.scar.seed);
        sc.boolean("raised", s.scar.raised);  // a raised (outward) roller scar (issue #27)
      }
      sc.finish();
    }
  }
  const json& bearings = o.need("bearings");
  if (!bearings.is_array()) o.fail("bearings", std::string("expected an array, got ") + json_type(bearings));
  if (bearings.empty()) o.fail("bearings", "no bearings (at least one)");
  for (std::size_t i = 0; i < bearings.size(); ++i)
    s.bearings.push_back(read_bearing(Obj(bearings[i], "bearings[" + std::to_string(i) + "]", file), i));
  o.finish();
  return s;
}

Expected<AssemblySpec> finish(const json& root, const std::string& file) {
  AssemblySpec s;
  try {
    s = read_root(root, file);
  } catch (const ReadError& e) {
    return e.error;
  }
  if (Status st = validate_assembly(s); !st) {
    Error e = st.error();
    if (e.file.empty()) e.file = file;
    return e;
  }
  return s;
}

}  // namespace

const char* bearing_type_name(BearingType t) {
  return t == BearingType::tapered ? "tapered" : "cylindrical";
}

Expected<AssemblySpec> read_assembly_file(const std::string& path) {
  Expected<json> j = scene::detail::read_json_file(path);
  if (!j) return j.error();
  return finish(*j, path);
}

Expected<AssemblySpec> parse_assembly(const std::string& text, const std::string& file) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    return Error{.file = file, .byte = static_cast<std::int64_t>(e.byte), .reason = "invalid JSON"};
  } catch (const json::exception& e) {
    return Error{.file = file, .reason = std::string("invalid JSON: ") + e.what()};
  }
  return finish(j, file);
}

}  // namespace interfere::bearing
