// Base64 (RFC 4648 §4, the standard alphabet with '=' padding), for the buffers glTF 2.0 embeds in
// `data:` URIs (Khronos glTF 2.0 specification §3.6.1.1 "Data URI"): the .gltf writer encodes, the
// mesh reader decodes.
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace interfere {

std::string base64_encode(std::string_view bytes);

/// The decoded bytes, or nullopt with `bad_at` set to the offset of the first character that is
/// not base64 (or of the end, when the length or the padding is wrong).
std::optional<std::string> base64_decode(std::string_view text, std::size_t& bad_at);

}  // namespace interfere
