// The GLB container of glTF 2.0 (Khronos glTF 2.0 specification §4.4 "GLB File Format"), shared by
// the simplifier's part export (simplify/gltf_io.h, issue #6) and the viewer's scene export
// (view/gltf.h, issue #25): a 12-byte header, a JSON chunk padded with spaces and a BIN chunk
// padded with zeros, every buffer view starting at a multiple of 4 bytes (§3.6.2.4 "Data Alignment").
#pragma once
#include <cstddef>
#include <filesystem>
#include <string>

#include "interfere/core/error.h"

namespace interfere {

/// Appends `bytes` bytes at `data` to the BIN chunk `bin` and pads it with zeros to a multiple of
/// 4, so that the next buffer view (which starts at bin.size()) is aligned for any component type.
void glb_append_aligned(std::string& bin, const void* data, std::size_t bytes);

/// Writes `path` atomically (core/atomic_file.h) as a GLB: the header, `json` as the JSON chunk
/// (padded with spaces) and `bin` as the BIN chunk (zero-padded; no BIN chunk when `bin` is empty).
/// Error (naming `path`) above GLB's 4 GiB limit, or when the write fails.
Status write_glb_container(const std::filesystem::path& path, std::string json, std::string bin);

}  // namespace interfere
