// Internal: the GLB container (binary glTF 2.0, Khronos glTF 2.0 specification §4.4 "GLB File
// Format"), shared by the mesh reader (glb.cpp) and read_error_bound (simplify/tagged_io.cpp).
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

#include "interfere/core/error.h"

namespace interfere::io_detail {

struct GlbChunks {
  std::string_view json, bin;           ///< the JSON chunk's text; the BIN chunk (empty if none)
  std::int64_t json_at = 0, bin_at = 0;  ///< their byte offsets in the file
};

/// Checks the 12-byte header ("glTF", version 2, the file's length) and the chunks (a JSON chunk
/// first, then an optional BIN chunk; unknown chunk types after them are skipped, as the
/// specification asks). Errors name the byte offset.
Expected<GlbChunks> split_glb(const std::string& path, std::string_view data);

/// True when the bytes start with the GLB magic "glTF".
inline bool is_glb(std::string_view data) { return data.substr(0, 4) == "glTF"; }

}  // namespace interfere::io_detail
