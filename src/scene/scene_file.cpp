// The JSON scene file (include/interfere/scene/io.h, read_scene_file; docs/scene.md, "Scene file";
// issue #24, items 1-2): bodies with files, ids, poses, units and tags; clash tests; a motion file.
// Every error names the file and the JSON path of the offending value; nothing is guessed.
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <unordered_map>

#include "interfere/core/units.h"
#include "interfere/scene/io.h"
#include "json_input.h"

namespace interfere::scene {
namespace {

using detail::json_index;
using detail::json_key;
using detail::json_type;
using nlohmann::json;

/// Thrown inside the reader, returned as an Error by read_scene_file.
struct Bad {
  std::string path;  ///< JSON path ("bodies[2].transform"); empty: the document
  std::string reason;
};

[[noreturn]] void bad(const std::string& path, const std::string& reason) {
  throw Bad{path, reason};
}

void check_keys(const json& obj, const std::string& path,
                std::initializer_list<const char*> allowed) {
  for (const auto& [k, v] : obj.items()) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || k == a;
    if (ok) continue;
    std::string list;
    for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    bad(json_key(path, k), "unknown key (known here: " + list + ")");
  }
}

const json& object_at(const json& j, const std::string& path) {
  if (!j.is_object()) bad(path, std::string("must be an object, not ") + json_type(j));
  return j;
}

std::string string_at(const json& j, const std::string& path, bool allow_empty = false) {
  if (!j.is_string()) bad(path, std::string("must be a string, not ") + json_type(j));
  std::string s = j.get<std::string>();
  if (!allow_empty && s.empty()) bad(path, "empty");
  return s;
}

/// string_at(v, path + "." + key), the path built only for the message (10^5 entries: issue #31).
std::string string_key(const json& v, const std::string& path, const char* key) {
  if (v.is_string() && !v.get_ref<const std::string&>().empty()) return v.get<std::string>();
  return string_at(v, json_key(path, key));  // (throws)
}

double number_at(const json& j, const std::string& path) {
  if (!j.is_number()) bad(path, std::string("must be a number, not ") + json_type(j));
  return j.get<double>();  // JSON numbers are finite (a number beyond double fails the parse)
}

std::string unit_at(const json& j, const std::string& path) {
  std::string u = string_at(j, path);
  if (!millimetres_per_unit(u)) bad(path, "unknown unit '" + u + "' (" + known_units() + ")");
  return u;
}

/// A transform: 12 numbers "r00 r01 r02 tx r10 r11 r12 ty r20 r21 r22 tz", as an array or a string.
Transform transform_at(const json& j, const std::string& path) {
  auto strip = [](std::string reason) {  // Transform's reasons begin with "transform: "
    if (reason.rfind("transform: ", 0) == 0) reason.erase(0, 11);
    return reason;
  };
  if (j.is_string()) {
    auto t = Transform::parse(j.get<std::string>());
    if (!t) bad(path, strip(t.error().reason));
    return *t;
  }
  if (!j.is_array())
    bad(path, std::string("must be an array of 12 numbers or a string, not ") + json_type(j));
  if (j.size() != 12)
    bad(path, "expected 12 numbers \"r00 r01 r02 tx r10 r11 r12 ty r20 r21 r22 tz\", got " +
                  std::to_string(j.size()));
  Transform t;
  for (std::size_t i = 0; i < 12; ++i) {
    const double x = number_at(j[i], json_index(path, i));
    if (i % 4 == 3)
      t.t[static_cast<int>(i / 4)] = x;
    else
      t.r[i / 4][i % 4] = x;
  }
  if (const Status s = t.validate(); !s) bad(path, strip(s.error().reason));
  return t;
}

/// A selection: an array of selector strings, or one string of comma-separated selectors.
Selection selection_at(const json& j, const std::string& path) {
  Selection out;
  if (j.is_string()) {
    auto s = parse_selection(j.get<std::string>());
    if (!s) bad(path, s.error().reason);
    return std::move(*s);
  }
  if (!j.is_array())
    bad(path, std::string("must be an array of selectors or a string, not ") + json_type(j));
  if (j.empty()) bad(path, "empty (it would select no body; \"*\" selects every body)");
  for (std::size_t i = 0; i < j.size(); ++i) {
    auto s = parse_selection(string_at(j[i], json_index(path, i)));
    if (!s) bad(json_index(path, i), s.error().reason);
    out.insert(out.end(), s->begin(), s->end());
  }
  return out;
}

/// Why the file `given` (resolved: `full`) cannot be read as an entry's file; empty: it can.
std::string file_problem(const std::string& given, const std::filesystem::path& full) {
  std::error_code ec;
  const auto st = std::filesystem::status(full, ec);
  if (ec || !std::filesystem::exists(st))
    return "file '" + given + "' not found" +
           (std::filesystem::path(given).is_relative() ? " (looked for " + full.string() + ")" : "");
  if (std::filesystem::is_directory(st)) return "'" + full.string() + "' is a directory, not a file";
  return {};
}

/// `file` resolved against `dir` (std::filesystem's `dir / file` on POSIX: a relative file after
/// the directory and one separator, an absolute one as it is; by string, without parsing the
/// path: a 10^5-entry scene file, issue #31); checked (file_problem) when `check`.
std::string resolve(const std::string& dir, const std::string& file, const std::string& path, bool check = true) {
  std::string full = file;
  if (!file.starts_with('/') && !dir.empty()) full = dir.ends_with('/') ? dir + file : dir + '/' + file;
  if (check)
    if (std::string why = file_problem(file, full); !why.empty()) bad(path, why);
  return full;
}

struct Reader {
  std::string file;
  std::string dir;
  std::unordered_map<std::string, std::string> ids;  // given id -> JSON path of the entry that used it first
  bool check_files = true;                  // SceneFileOptions::check_body_files

  BodySpec body(const json& j, const std::string& path) {
    object_at(j, path);
    check_keys(j, path, {"file", "id", "name", "path", "units", "transform", "tags", "select"});
    BodySpec s;
    s.where = file + ": " + path;
    const auto file_it = j.find("file");
    if (file_it == j.end()) bad(path, "missing \"file\"");
    s.given = string_key(*file_it, path, "file");
    s.file = resolve(dir, s.given, check_files ? json_key(path, "file") : std::string(), check_files);
    if (const auto id = j.find("id"); id != j.end()) {
      s.id = string_key(*id, path, "id");
      if (make_body_id(s.id) != s.id)
        bad(json_key(path, "id"), "id '" + s.id +
                   "' has characters outside [A-Za-z0-9._:/#@+-] (ids appear in selectors, CSV "
                   "cells and file names)");
      if (const auto [it, fresh] = ids.emplace(s.id, path); !fresh)
        bad(json_key(path, "id"), "duplicate id '" + s.id + "' (also " + json_key(it->second, "id") + ")");
    }
    if (const auto name = j.find("name"); name != j.end()) s.name = string_key(*name, path, "name");
    if (const auto p = j.find("path"); p != j.end()) s.path = string_key(*p, path, "path");
    if (j.contains("units")) s.units = unit_at(j["units"], json_key(path, "units"));
    if (j.contains("transform"))
      s.pose = transform_at(j["transform"], json_key(path, "transform")), s.pose_given = true;
    if (j.contains("tags")) {
      const std::string p = json_key(path, "tags");
      const json& t = j["tags"];
      if (!t.is_array()) bad(p, std::string("must be an array of strings, not ") + json_type(t));
      for (std::size_t i = 0; i < t.size(); ++i)
        s.tags.push_back(string_at(t[i], json_index(p, i)));
    }
    if (const auto select = j.find("select"); select != j.end()) s.select = string_key(*select, path, "select");
    return s;
  }

  /// The two-part form's "a" or "b": {"file", "transform", "units"}.
  BodySpec part(const json& j, const char* key) {
    const std::string path = key;
    object_at(j, path);
    check_keys(j, path, {"file", "transform", "units"});
    BodySpec s;
    s.where = file + ": " + path;
    s.id = key;
    if (!j.contains("file")) bad(path, "missing \"file\"");
    s.given = string_at(j["file"], json_key(path, "file"));
    s.file = resolve(dir, s.given, json_key(path, "file"), check_files);
    if (j.contains("units")) s.units = unit_at(j["units"], json_key(path, "units"));
    if (j.contains("transform"))
      s.pose = transform_at(j["transform"], json_key(path, "transform")), s.pose_given = true;
    return s;
  }

  /// An entry of "suppress" or "clearance_overrides": "a" required, "b" default every body.
  std::pair<Selection, Selection> rule_pair(const json& j, const std::string& path) {
    if (!j.contains("a")) bad(path, "missing \"a\"");
    Selection a = selection_at(j["a"], json_key(path, "a"));
    Selection b =
        j.contains("b") ? selection_at(j["b"], json_key(path, "b")) : Selection{Selector{}};
    return {std::move(a), std::move(b)};
  }

  ClashTest test(const json& j, const std::string& path, std::size_t index, std::size_t count) {
    object_at(j, path);
    check_keys(j, path,
               {"name", "a", "b", "mode", "tolerance", "clearance", "clearance_overrides",
                "suppress", "nominal_fits_are_contacts", "id_grid"});
    ClashTest t;
    t.name = j.contains("name") ? string_at(j["name"], json_key(path, "name"))
             : count == 1       ? "default"
                                : "test" + std::to_string(index + 1);
    if (j.contains("a")) t.a = selection_at(j["a"], json_key(path, "a"));
    if (j.contains("b")) t.b = selection_at(j["b"], json_key(path, "b"));
    if (j.contains("clearance"))
      t.clearance = number_at(j["clearance"], json_key(path, "clearance"));
    if (j.contains("mode")) {
      auto m = parse_clash_mode(string_at(j["mode"], json_key(path, "mode")));
      if (!m) bad(json_key(path, "mode"), m.error().reason);
      t.mode = *m;
    } else if (j.contains("clearance")) {
      t.mode = ClashMode::clearance;  // a clearance alone means a clearance test
    }
    if (j.contains("tolerance"))
      t.tolerance = number_at(j["tolerance"], json_key(path, "tolerance"));
    if (j.contains("id_grid")) t.id_grid = number_at(j["id_grid"], json_key(path, "id_grid"));
    if (j.contains("nominal_fits_are_contacts")) {
      const json& v = j["nominal_fits_are_contacts"];
      if (!v.is_boolean())
        bad(json_key(path, "nominal_fits_are_contacts"),
            std::string("must be true or false, not ") + json_type(v));
      t.nominal_fits_are_contacts = v.get<bool>();
    }
    if (j.contains("clearance_overrides")) {
      const std::string p = json_key(path, "clearance_overrides");
      const json& list = j["clearance_overrides"];
      if (!list.is_array()) bad(p, std::string("must be an array, not ") + json_type(list));
      for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string q = json_index(p, i);
        object_at(list[i], q);
        check_keys(list[i], q, {"a", "b", "clearance"});
        auto [a, b] = rule_pair(list[i], q);
        if (!list[i].contains("clearance")) bad(q, "missing \"clearance\"");
        const double c = number_at(list[i]["clearance"], json_key(q, "clearance"));
        if (c < 0) bad(json_key(q, "clearance"), "must be >= 0 (got " + short_number(c) + ")");
        t.clearance_overrides.push_back({std::move(a), std::move(b), c});
      }
    }
    if (j.contains("suppress")) {
      const std::string p = json_key(path, "suppress");
      const json& list = j["suppress"];
      if (!list.is_array()) bad(p, std::string("must be an array, not ") + json_type(list));
      for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string q = json_index(p, i);
        object_at(list[i], q);
        check_keys(list[i], q, {"a", "b", "reason"});
        auto [a, b] = rule_pair(list[i], q);
        std::string reason = list[i].contains("reason")
                                 ? string_at(list[i]["reason"], json_key(q, "reason"), true)
                                 : "";
        t.suppressions.push_back({std::move(a), std::move(b), std::move(reason)});
      }
    }
    try {
      t.validate();
    } catch (const std::invalid_argument& e) {
      bad(path, e.what());
    }
    return t;
  }

  SceneSpec read(const json& root) {
    SceneSpec spec;
    spec.file = file;
    object_at(root, "");
    const bool two_part = root.contains("a") || root.contains("b");
    if (two_part) {
      check_keys(root, "", {"a", "b", "units", "tests", "motion"});
      for (const char* key : {"a", "b"})
        if (!root.contains(key))
          bad(key, "missing (the two-part form needs \"a\" and \"b\"; or list \"bodies\")");
      spec.bodies.push_back(part(root["a"], "a"));
      spec.bodies.push_back(part(root["b"], "b"));
    } else {
      check_keys(root, "", {"units", "bodies", "tests", "motion"});
    }
    if (root.contains("units")) spec.units = unit_at(root["units"], "units");
    if (root.contains("bodies")) {
      const json& list = root["bodies"];
      if (!list.is_array()) bad("bodies", std::string("must be an array, not ") + json_type(list));
      spec.bodies.reserve(spec.bodies.size() + list.size());
      ids.reserve(list.size());
      for (std::size_t i = 0; i < list.size(); ++i)
        spec.bodies.push_back(body(list[i], json_index("bodies", i)));
    }
    if (root.contains("tests")) {
      const json& list = root["tests"];
      if (!list.is_array()) bad("tests", std::string("must be an array, not ") + json_type(list));
      std::map<std::string, std::size_t> names;
      for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string p = json_index("tests", i);
        spec.tests.push_back(test(list[i], p, i, list.size()));
        const std::string& name = spec.tests.back().name;
        if (const auto [it, fresh] = names.emplace(name, i); !fresh)
          bad(json_key(p, "name"), "duplicate test name '" + name + "' (also tests[" +
                                       std::to_string(it->second) + "])");
      }
    }
    if (root.contains("motion"))
      spec.motion = resolve(dir, string_at(root["motion"], "motion"), "motion");
    return spec;
  }
};

}  // namespace

Expected<SceneSpec> read_scene_file(const std::string& path, const SceneFileOptions& options) {
  auto j = detail::read_json_file(path);
  if (!j) return j.error();
  Reader r{.file = path, .dir = std::filesystem::path(path).parent_path().string(), .ids = {},
           .check_files = options.check_body_files};
  try {
    return r.read(*j);
  } catch (const Bad& b) {
    return Error{.file = path, .reason = b.path.empty() ? b.reason : b.path + ": " + b.reason};
  }
}

Expected<std::uintmax_t> check_body_file(const BodySpec& body) {
  // (one system call in the common case, a file that is there: interfere-mpi's ranks check 10^5
  // entries between them; the size as std::filesystem::file_size gives it, 0 for other than a
  // regular file)
  struct stat st {};
  if (::stat(body.file.c_str(), &st) == 0 && !S_ISDIR(st.st_mode))
    return S_ISREG(st.st_mode) ? static_cast<std::uintmax_t>(st.st_size) : std::uintmax_t{0};
  // (read_scene_file's message: where + ".file: " + why; the resolved file is body.file)
  if (std::string why = file_problem(body.given.empty() ? body.file : body.given, body.file); !why.empty())
    return Error{.reason = body.where + ".file: " + why};
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(body.file, ec);
  return ec ? std::uintmax_t{0} : size;
}

}  // namespace interfere::scene
