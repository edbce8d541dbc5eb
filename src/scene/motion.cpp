// Motion files (include/interfere/scene/io.h, read_motion; docs/scene.md, "Motion files"; issue
// #24, item 6): per-frame poses of a scene's bodies, as CSV rows or JSON. Every error names the
// file and the line and field (CSV) or the JSON path; the scene is changed only when the whole file
// is good.
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include "interfere/core/text_cells.h"
#include "interfere/scene/io.h"
#include "json_input.h"

namespace interfere::scene {
namespace {

constexpr const char* kPoseColumns[12] = {"r00", "r01", "r02", "tx",  "r10", "r11",
                                          "r12", "ty",  "r20", "r21", "r22", "tz"};

Transform from_row_major(const double (&v)[12]) {
  Transform t;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) t.r[row][col] = v[row * 4 + col];
    t.t[row] = v[row * 4 + 3];
  }
  return t;
}

/// Transform's reasons begin with "transform"; here the field names the value.
std::string pose_reason(const Status& s) {
  std::string r = s.error().reason;
  if (r.rfind("transform: ", 0) == 0) r.erase(0, 11);
  return r;
}

/// Body ids -> indices, and a short list of them for "unknown body" messages.
struct Ids {
  std::unordered_map<std::string_view, std::uint32_t> index;
  std::string some;
  explicit Ids(const Scene& scene) {
    for (std::uint32_t i = 0; i < scene.bodies.size(); ++i) {
      index.emplace(scene.bodies[i].id, i);
      if (i < 8) some += (i ? ", " : "") + scene.bodies[i].id;
    }
    if (scene.bodies.size() > 8)
      some += ", ... (" + std::to_string(scene.bodies.size()) + " bodies)";
    if (scene.bodies.empty()) some = "none: the scene has no bodies";
  }
  std::string unknown(std::string_view id) const {
    return "unknown body '" + std::string(id) + "' (the scene's ids: " + some + ")";
  }
};

/// Adds one frame's poses, checking the order: frames strictly ascending, each frame's entries
/// together, a body at most once per frame. `where` locates the entry for messages.
struct FrameBuilder {
  std::vector<Frame> frames;
  std::vector<std::int64_t> numbers;
  std::unordered_map<std::uint32_t, std::string>
      in_frame;             // body -> where it was given in the current frame
  std::string frame_where;  // where the current frame began

  /// Empty on success, else the reason.
  std::string start(std::int64_t number, double time, const std::string& where) {
    if (!numbers.empty() && number == numbers.back()) {
      if (frames.back().time != time)
        return "time " + short_number(time) + " differs from frame " + std::to_string(number) +
               "'s time " + short_number(frames.back().time) + " (" + frame_where + ")";
      return {};
    }
    if (!numbers.empty() && number < numbers.back())
      return "frame " + std::to_string(number) + " after frame " + std::to_string(numbers.back()) +
             ": frames must be in ascending order, each frame's rows together";
    numbers.push_back(number);
    Frame f;
    f.label = "frame " + std::to_string(number);
    f.time = time;
    frames.push_back(std::move(f));
    in_frame.clear();
    frame_where = where;
    return {};
  }
  std::string add(std::uint32_t body, const std::string& id, const Transform& pose,
                  const std::string& where) {
    if (const auto [it, fresh] = in_frame.emplace(body, where); !fresh)
      return "body '" + id + "' twice in frame " + std::to_string(numbers.back()) + " (also " +
             it->second + ")";
    frames.back().poses.push_back({body, pose});
    return {};
  }
};

Status install(Scene& scene, std::vector<Frame> frames, const std::string& path) {
  if (frames.empty()) return Error{.file = path, .reason = "no frames"};
  scene.frames = std::move(frames);
  return {};
}

// ---- CSV ----


Status read_csv(const std::string& path, const std::string& text, Scene& scene) {
  std::size_t pos = text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;  // UTF-8 byte order mark
  std::int64_t line_no = 0;
  auto fail = [&](const std::string& reason) {
    return Error{.file = path, .line = line_no, .reason = reason};
  };
  const Ids ids(scene);
  FrameBuilder fb;
  bool header = false, has_time = false;
  std::size_t columns = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (trim_blanks(line).empty()) continue;
    const std::vector<std::string_view> f = split_csv_cells(line);
    if (!header) {
      has_time = f.size() > 1 && f[1] == "time";
      std::vector<std::string> want = {"frame"};
      if (has_time) want.push_back("time");
      want.push_back("body");
      for (const char* c : kPoseColumns) want.push_back(c);
      std::string expected;
      for (const std::string& w : want) expected += (expected.empty() ? "" : ",") + w;
      if (f.size() != want.size())
        return fail("header: expected \"" + expected + "\" (" + std::to_string(want.size()) +
                    " columns), got " + std::to_string(f.size()) + " columns");
      for (std::size_t i = 0; i < want.size(); ++i)
        if (f[i] != want[i])
          return fail("header: column " + std::to_string(i + 1) + " is '" + std::string(f[i]) +
                      "', expected '" + want[i] + "' (\"" + expected + "\")");
      header = true;
      columns = want.size();
      continue;
    }
    if (f.size() != columns)
      return fail(std::to_string(f.size()) + " fields, expected " + std::to_string(columns) +
                  " (as the header)");
    std::size_t c = 0;
    std::int64_t number = 0;
    {
      const std::string_view s = f[c++];
      const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), number);
      if (s.empty() || ec != std::errc() || ptr != s.data() + s.size())
        return fail("frame: '" + std::string(s) + "' is not an integer");
    }
    double time = static_cast<double>(number);
    if (has_time) {
      const std::string_view s = f[c++];
      if (!parse_finite_cell(s, time))
        return fail("time: '" + std::string(s) + "' is not a finite number");
    }
    const std::string_view id = f[c++];
    const auto body = ids.index.find(id);
    if (body == ids.index.end()) return fail("body: " + ids.unknown(id));
    double v[12];
    for (int k = 0; k < 12; ++k) {
      const std::string_view s = f[c++];
      if (!parse_finite_cell(s, v[k]))
        return fail(std::string(kPoseColumns[k]) + ": '" + std::string(s) +
                    "' is not a finite number");
    }
    const std::string where = "line " + std::to_string(line_no);
    if (std::string r = fb.start(number, time, where); !r.empty())
      return fail((r.rfind("time ", 0) == 0 ? "time: " : "frame: ") + r);
    const Transform pose = from_row_major(v);
    if (const Status s = pose.validate(); !s)
      return fail("pose of body '" + std::string(id) + "': " + pose_reason(s));
    if (std::string r = fb.add(body->second, std::string(id), pose, where); !r.empty())
      return fail("body: " + r);
  }
  if (!header)
    return Error{.file = path,
                 .reason = "empty (expected the header \"frame,body,r00,...,tz\" and rows)"};
  return install(scene, std::move(fb.frames), path);
}

// ---- JSON ----

Status read_json(const std::string& path, Scene& scene) {
  using detail::json_index;
  using detail::json_key;
  using detail::json_type;
  using nlohmann::json;
  auto j = detail::read_json_file(path);
  if (!j) return j.error();
  auto fail = [&](const std::string& where, const std::string& reason) {
    return Error{.file = path, .reason = where.empty() ? reason : where + ": " + reason};
  };
  const json& root = *j;
  if (!root.is_object())
    return fail("", std::string("must be an object {\"frames\": [...]}, not ") + json_type(root));
  for (const auto& [k, v] : root.items())
    if (k != "frames") return fail(k, "unknown key (known here: frames)");
  if (!root.contains("frames")) return fail("frames", "missing");
  const json& frames = root["frames"];
  if (!frames.is_array())
    return fail("frames", std::string("must be an array, not ") + json_type(frames));
  const Ids ids(scene);
  FrameBuilder fb;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const std::string p = json_index("frames", i);
    const json& f = frames[i];
    if (!f.is_object()) return fail(p, std::string("must be an object, not ") + json_type(f));
    for (const auto& [k, v] : f.items())
      if (k != "frame" && k != "time" && k != "poses")
        return fail(json_key(p, k), "unknown key (known here: frame, time, poses)");
    if (!f.contains("frame")) return fail(p, "missing \"frame\"");
    if (!f["frame"].is_number_integer())
      return fail(json_key(p, "frame"),
                  std::string("must be an integer, not ") + json_type(f["frame"]));
    const std::int64_t number = f["frame"].get<std::int64_t>();
    double time = static_cast<double>(number);
    if (f.contains("time")) {
      if (!f["time"].is_number())
        return fail(json_key(p, "time"),
                    std::string("must be a number, not ") + json_type(f["time"]));
      time = f["time"].get<double>();
    }
    if (!fb.numbers.empty() && number == fb.numbers.back())
      return fail(json_key(p, "frame"), "frame " + std::to_string(number) +
                                            " again: give each frame once, in ascending order");
    if (std::string r = fb.start(number, time, p); !r.empty()) return fail(json_key(p, "frame"), r);
    if (!f.contains("poses")) return fail(p, "missing \"poses\"");
    const json& poses = f["poses"];
    const std::string pp = json_key(p, "poses");
    if (!poses.is_object())
      return fail(pp,
                  std::string("must be an object {\"ID\": [12 numbers]}, not ") + json_type(poses));
    for (const auto& [id, value] : poses.items()) {
      const std::string q = json_key(pp, id);
      const auto body = ids.index.find(id);
      if (body == ids.index.end()) return fail(q, ids.unknown(id));
      Transform pose;
      if (value.is_string()) {
        auto t = Transform::parse(value.get<std::string>());
        if (!t) return fail(q, pose_reason(Status(t.error())));
        pose = *t;
      } else {
        if (!value.is_array())
          return fail(q, std::string("must be an array of 12 numbers or a string, not ") +
                             json_type(value));
        if (value.size() != 12)
          return fail(q,
                      "expected 12 numbers \"r00 r01 r02 tx r10 r11 r12 ty r20 r21 r22 tz\", got " +
                          std::to_string(value.size()));
        double v[12];
        for (std::size_t k = 0; k < 12; ++k) {
          if (!value[k].is_number())
            return fail(json_index(q, k),
                        std::string("must be a number, not ") + json_type(value[k]));
          v[k] = value[k].get<double>();
        }
        pose = from_row_major(v);
        if (const Status s = pose.validate(); !s) return fail(q, pose_reason(s));
      }
      if (std::string r = fb.add(body->second, id, pose, q); !r.empty()) return fail(q, r);
    }
  }
  return install(scene, std::move(fb.frames), path);
}

bool looks_like_json(const std::string& path, const std::string& text) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".json") return true;
  if (ext == ".csv") return false;
  std::size_t i = text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
  while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
  return i < text.size() && text[i] == '{';
}

}  // namespace

Status read_motion(const std::string& path, Scene& scene) {
  if (!scene.frames.empty())
    return Error{.file = path,
                 .reason = "the scene already has " + std::to_string(scene.frames.size()) +
                           " frames (give one motion)"};
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{.file = path, .reason = "cannot open"};
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  if (looks_like_json(path, text)) return read_json(path, scene);
  return read_csv(path, text, scene);
}

}  // namespace interfere::scene
