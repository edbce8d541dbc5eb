// Reading the JSON inputs of the scene layer (scene files, motion files; scene/io.h): parse errors
// with the byte offset and line, duplicate object keys as errors naming their JSON path (JSON
// parsers keep the last silently), and JSON-path helpers for messages.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "interfere/core/error.h"

namespace interfere::scene::detail {

/// Reads and parses `path` (a UTF-8 byte order mark is skipped). Errors: cannot open, invalid JSON
/// (byte offset and line), a number beyond double, a key twice in one object (its JSON path).
Expected<nlohmann::json> read_json_file(const std::string& path);

/// "bodies[2]" + "transform" -> "bodies[2].transform"; "" + "units" -> "units".
inline std::string json_key(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}
inline std::string json_index(const std::string& path, std::size_t i) {
  return path + "[" + std::to_string(i) + "]";
}
/// The JSON type of `j` for messages ("a string", "an array", ...).
const char* json_type(const nlohmann::json& j);

}  // namespace interfere::scene::detail
