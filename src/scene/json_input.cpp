// JSON inputs of the scene layer (src/scene/json_input.h).
#include "json_input.h"

#include <fstream>
#include <set>
#include <sstream>
#include <vector>

namespace interfere::scene::detail {
namespace {

struct DuplicateKey {
  std::string path;
};

/// Tracks the JSON path of the parser's position through nlohmann's callback events, to name a
/// duplicate key.
struct PathTracker {
  struct Level {
    bool array = false;
    std::size_t next = 0;  ///< arrays: index of the next element
    std::string key;       ///< objects: the key whose value is being read
    std::set<std::string> keys;
    std::string path;
  };
  std::vector<Level> stack;

  void open(bool array) {
    std::string path;
    if (!stack.empty()) {
      Level& parent = stack.back();
      path =
          parent.array ? json_index(parent.path, parent.next++) : json_key(parent.path, parent.key);
    }
    stack.push_back({.array = array, .path = std::move(path)});
  }
  bool operator()(int /*depth*/, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using E = nlohmann::json::parse_event_t;
    switch (event) {
      case E::object_start:
        open(false);
        break;
      case E::array_start:
        open(true);
        break;
      case E::object_end:
      case E::array_end:
        if (!stack.empty()) stack.pop_back();
        break;
      case E::key:
        if (!stack.empty()) {
          Level& top = stack.back();
          top.key = parsed.get<std::string>();
          if (!top.keys.insert(top.key).second) throw DuplicateKey{json_key(top.path, top.key)};
        }
        break;
      case E::value:
        if (!stack.empty() && stack.back().array) ++stack.back().next;
        break;
    }
    return true;
  }
};

/// The same path tracking as a SAX handler (no document built): a second, linear pass after the
/// plain parse. nlohmann's callback parser rescans the enclosing array at every closing object, so
/// a scene file of 10^5 bodies took 3.5 s to read that way (issue #31: every MPI rank reads it).
struct DuplicateKeyCheck {
  using json = nlohmann::json;
  PathTracker t;
  bool scalar() {
    if (!t.stack.empty() && t.stack.back().array) ++t.stack.back().next;
    return true;
  }
  bool null() { return scalar(); }
  bool boolean(bool) { return scalar(); }
  bool number_integer(json::number_integer_t) { return scalar(); }
  bool number_unsigned(json::number_unsigned_t) { return scalar(); }
  bool number_float(json::number_float_t, const json::string_t&) { return scalar(); }
  bool string(json::string_t&) { return scalar(); }
  bool binary(json::binary_t&) { return scalar(); }
  bool start_object(std::size_t) {
    t.open(false);
    return true;
  }
  bool end_object() {
    if (!t.stack.empty()) t.stack.pop_back();
    return true;
  }
  bool start_array(std::size_t) {
    t.open(true);
    return true;
  }
  bool end_array() { return end_object(); }
  bool key(json::string_t& k) {
    if (!t.stack.empty()) {
      PathTracker::Level& top = t.stack.back();
      top.key = k;
      if (!top.keys.insert(top.key).second) throw DuplicateKey{json_key(top.path, top.key)};
    }
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) { throw e; }
};

std::int64_t line_of(const std::string& text, std::size_t byte) {
  std::int64_t line = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) line += text[i] == '\n';
  return line;
}

/// nlohmann's what() without its "[json.exception.parse_error.101] " prefix.
std::string bare(const char* what) {
  std::string s = what;
  if (!s.empty() && s[0] == '[') {
    const std::size_t close = s.find("] ");
    if (close != std::string::npos) s.erase(0, close + 2);
  }
  return s;
}

}  // namespace

Expected<nlohmann::json> read_json_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{.file = path, .reason = "cannot open"};
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  try {
    nlohmann::json j = nlohmann::json::parse(text);  // (syntax errors first, as before)
    DuplicateKeyCheck check;
    nlohmann::json::sax_parse(text, &check);
    return j;
  } catch (const DuplicateKey& d) {
    return Error{.file = path, .reason = d.path + ": key given twice"};
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann counts bytes from 1 (the last byte read); Error::byte is 0-based.
    const std::size_t byte = e.byte > 0 ? e.byte - 1 : 0;
    return Error{.file = path,
                 .line = line_of(text, byte),
                 .byte = static_cast<std::int64_t>(byte),
                 .reason = "invalid JSON: " + bare(e.what())};
  } catch (const nlohmann::json::exception& e) {  // a number beyond double ("1e999")
    return Error{.file = path, .reason = "invalid JSON: " + bare(e.what())};
  }
}

const char* json_type(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::null:
      return "null";
    case nlohmann::json::value_t::object:
      return "an object";
    case nlohmann::json::value_t::array:
      return "an array";
    case nlohmann::json::value_t::string:
      return "a string";
    case nlohmann::json::value_t::boolean:
      return "a boolean";
    case nlohmann::json::value_t::binary:
      return "binary data";
    case nlohmann::json::value_t::discarded:
      return "nothing";
    default:
      return "a number";
  }
}

}  // namespace interfere::scene::detail
