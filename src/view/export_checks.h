// The checks the file exports of a viewer document (view/gltf.h, view/pvd.h; issue #25) run before
// writing anything: every index in range, every per-triangle, per-vertex and per-frame array of the
// right length, every coordinate finite and within float32 (both formats store float positions).
#pragma once
#include <cstddef>
#include <string>

#include "interfere/view/document.h"

namespace interfere::view::detail {

/// The number of frames (frames.labels.size(); 0: a static document).
inline std::size_t frame_count(const Document& doc) { return doc.frames.labels.size(); }

/// Empty when `doc` can be exported; otherwise "viewer document: <field>: <reason>" naming the first
/// bad field ("viewer document: bodies[2].mesh: mesh 7 out of range (3 meshes)"). A document with
/// `error` set is refused with that text ("the report could not be shown: ...").
std::string check_for_export(const Document& doc);

/// sRGB (0..1, as the page and the document give colours) to linear light (glTF's colour factors).
float srgb_to_linear(float c);

}  // namespace interfere::view::detail
