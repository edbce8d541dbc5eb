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

/// The length of the JSON chunk, which starts at byte 20, from the file's first 20 bytes (`head`)
/// and its size: the header and the JSON chunk's header checked as split_glb does, so that the
/// JSON can be read without the rest of the file.
Expected<std::uint32_t> glb_json_length(const std::string& path, std::string_view head, std::uint64_t file_size);

/// True when the bytes start with the GLB magic "glTF".
inline bool is_glb(std::string_view data) { return data.substr(0, 4) == "glTF"; }

}  // namespace interfere::io_detail
