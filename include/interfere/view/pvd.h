// ParaView time series of a viewer document (issue #25, item 3): a `.pvd` collection (VTK File
// Formats, "ParaView Data (PVD)") of per-frame VTK XML PolyData files, for frames and load steps
// (bearing frames, probe poses, FE load steps); a static document is one step at time 0.
//
// Files: `<dir>/<stem>.pvd` and, in the folder `<dir>/<stem>_files/`, per step k (0-based, four or
// more digits) `bodies_<k>.vtp` and, when the document has clashes, `clashes_<k>.vtp`; the
// collection lists them as part 0 ("bodies") and part 1 ("clashes") at the step's time:
// frames.times when strictly increasing, the frame index otherwise.
//
// bodies_<k>.vtp: every body in world coordinates at step k (its frame pose, else `pose`; its
// frame mesh, else `mesh`), triangles as polygons, points Float64. Cell data: `body` (Int32, the
// body's index; field data `body_names` and `body_ids` name them), `clash` (UInt8,
// ViewMesh::clash_flags, 0 where absent), `clash_region` (Int32, ViewMesh::clash_region: the clash
// index of the clashes files, or an FE series step's region number; -1 where none; in every file when
// any mesh of the document has it), `source_id` (Int64, ViewMesh::source_ids: FE element ids,
// B-Rep faces; -1 where absent; only when some body has them). Point data: `penetration_depth`
// (Float64, ViewMesh::point_depth; NaN where a body has none; in every file of a series when any
// mesh of the document has it).
//
// clashes_<k>.vtp: the clashes present at step k (ViewClash::frames empty or holding k), world
// coordinates: intersection curves and clearance witness segments as polylines, then the clash and
// contact region triangles as polygons. Cell data: `clash_index` (Int32, index into the document's
// clashes; field data `clash_ids`), `verdict` (UInt8: 0 undecided, 1 clash, 2 contact, 3 clearance;
// field data `verdict_names`), `geometry` (UInt8: 0 region triangle, 1 intersection curve, 2
// clearance witness), `clash` (UInt8: 1 on the region triangles of a clash, 0 otherwise).
//
// Arrays are zlib-compressed base64 (vtkZLibDataCompressor, header_type UInt64), which ParaView and
// VTK read; the name arrays are ASCII VTK string arrays. Every file is written atomically
// (core/atomic_file.h), the .pvd last; files of an earlier, longer series with these names are
// removed from the folder afterwards.
#pragma once
#include <filesystem>

#include "interfere/core/error.h"
#include "interfere/view/document.h"

namespace interfere::view {

/// The folder the step files go to: `<pvd's directory>/<pvd's stem>_files`.
std::filesystem::path pvd_files_folder(const std::filesystem::path& pvd);

/// Writes the series (see above). Errors naming the file and field: a document with `error` set,
/// an index out of range, arrays of the wrong length, a coordinate not finite, a folder that
/// cannot be made, a failed write.
Status write_pvd(const std::filesystem::path& pvd, const Document& doc);

}  // namespace interfere::view
