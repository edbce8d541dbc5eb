// The viewer document as JSON (issue #25; contract: docs/viewer.md, schema "interfere.viewer",
// version 1): what the HTML page embeds (view/html.h) and what other tools may read.
//
// World coordinates (body pose translations, clash points, boxes, curves, witnesses and clash region
// meshes) are written relative to "origin", the centre of the box of every world coordinate, so
// that float32 positions and the page's single-precision matrices keep their precision far from
// the world origin; local mesh positions are written as given. Mesh buffers are base64 of little
// endian arrays: positions float32 x 3, indices uint32 x 3, face_colors uint16, clash_flags uint8.
// Pose matrices are column-major 4x4 (three.js Matrix4.fromArray order).
#pragma once
#include <string>

#include "interfere/core/error.h"
#include "interfere/core/vec.h"
#include "interfere/view/document.h"

namespace interfere::view {

/// The centre of the box of every world coordinate of `doc`: the bodies' world boxes (each mesh's
/// local box moved by the body's pose and by every frame pose), clash points, boxes, curves and
/// witnesses, and the clash region meshes. Non-finite values are left out (document_json rejects
/// them); (0, 0, 0) when there is no coordinate at all.
Vec3 document_origin(const Document& doc);

/// The JSON text (compact, one line). Errors name the field ("viewer document: bodies[2].pose:
/// not finite"): a NaN or infinite number anywhere (or a position beyond float32's range), an
/// index out of range (a body's mesh, a clash's bodies or region mesh, a triangle's vertex, a face
/// colour's legend entry, a frame), per-triangle or per-frame arrays of the wrong length, a clash
/// verdict other than clash, contact, clearance or undecided, a mesh used both by a body (local)
/// and as a clash region (world). Strings that are not valid UTF-8 are written with U+FFFD in
/// place of the bad bytes.
Expected<std::string> document_json(const Document& doc);

}  // namespace interfere::view
