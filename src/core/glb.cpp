// GLB container (glTF 2.0 §4.4): see core/glb.h.
#include "interfere/core/glb.h"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <limits>

#include "interfere/core/atomic_file.h"

namespace interfere {

void glb_append_aligned(std::string& bin, const void* data, std::size_t bytes) {
  bin.append(static_cast<const char*>(data), bytes);
  while (bin.size() % 4 != 0) bin.push_back('\0');
}

Status write_glb_container(const std::filesystem::path& path, std::string json, std::string bin) {
  while (json.size() % 4 != 0) json.push_back(' ');
  while (bin.size() % 4 != 0) bin.push_back('\0');
  const std::size_t length = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size());
  if (length > std::numeric_limits<std::uint32_t>::max())
    return Error{.file = path.string(), .reason = "glTF: " + std::to_string(length) + " bytes exceed GLB's 4 GiB limit"};
  const auto total = static_cast<std::uint32_t>(length);
  return write_file_atomic(path, [&](std::FILE* f) -> int {
    const std::uint32_t header[3] = {0x46546C67u, 2u, total};  // "glTF", version, length
    const std::uint32_t json_chunk[2] = {static_cast<std::uint32_t>(json.size()), 0x4E4F534Au};  // "JSON"
    const std::uint32_t bin_chunk[2] = {static_cast<std::uint32_t>(bin.size()), 0x004E4942u};    // "BIN\0"
    std::fwrite(header, 4, 3, f);
    std::fwrite(json_chunk, 4, 2, f);
    std::fwrite(json.data(), 1, json.size(), f);
    if (!bin.empty()) {
      std::fwrite(bin_chunk, 4, 2, f);
      std::fwrite(bin.data(), 1, bin.size(), f);
    }
    return std::ferror(f) ? EIO : 0;
  });
}

}  // namespace interfere
