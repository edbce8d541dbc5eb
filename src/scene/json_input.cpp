// JSON inputs of the scene layer (src/scene/json_input.h).
#include "json_input.h"

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

namespace interfere::scene::detail {
namespace {

struct DuplicateKey {
  std::string path;
};

/// Finds a key given twice in one object, naming its JSON path, in one SAX pass (no document
/// built), after the plain parse. nlohmann's callback parser rescans the enclosing array at every
/// closing object, so a scene file of 10^5 bodies took 3.5 s to read that way (issue #31: every
/// MPI rank reads it). The path is built only for the message: per level the array index or the
/// current key, and the keys seen so far (few per object: a list; many: a set).
struct DuplicateKeyCheck {
  using json = nlohmann::json;
  struct Level {
    bool array = false;
    std::size_t next = 0;  ///< arrays: index of the next element
    std::vector<std::string> keys;  ///< objects: the keys so far (the last one is being read)
    std::set<std::string> many;     ///< (every key, once an object has more than 16)
  };
  std::vector<Level> stack;
  std::size_t depth = 0;  ///< levels in use (stack keeps its buffers for the next objects)

  std::string path_of(std::size_t levels) const {
    std::string path;
    for (std::size_t d = 0; d + 1 < levels; ++d) {
      const Level& l = stack[d];
      path = l.array ? json_index(path, l.next - 1) : json_key(path, l.keys.back());
    }
    return path;
  }
  void open(bool array) {
    if (depth > 0 && stack[depth - 1].array) ++stack[depth - 1].next;
    if (stack.size() == depth) stack.emplace_back();
    Level& l = stack[depth++];
    l.array = array, l.next = 0, l.keys.clear(), l.many.clear();
  }
  bool scalar() {
    if (depth > 0 && stack[depth - 1].array) ++stack[depth - 1].next;
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
    open(false);
    return true;
  }
  bool end_object() {
    if (depth > 0) --depth;
    return true;
  }
  bool start_array(std::size_t) {
    open(true);
    return true;
  }
  bool end_array() { return end_object(); }
  bool key(json::string_t& k) {
    if (depth == 0) return true;
    Level& top = stack[depth - 1];
    bool twice = false;
    if (top.keys.size() < 16) {
      twice = std::find(top.keys.begin(), top.keys.end(), k) != top.keys.end();
      if (!twice && top.keys.size() == 15) top.many.insert(top.keys.begin(), top.keys.end()), top.many.insert(k);
    } else {
      twice = !top.many.insert(k).second;
    }
    if (twice) throw DuplicateKey{json_key(path_of(depth), k)};
    top.keys.push_back(k);
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
