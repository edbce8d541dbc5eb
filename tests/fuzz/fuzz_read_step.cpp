// Fuzz target `read_step` (issue #6, item 1 and "Bad input"): the bytes as a .step file read with
// interfere::cad::import_step (OpenCASCADE 7.6). Replay only (OCCT is not instrumented for
// libFuzzer); the seeds are the committed STEP test files and broken variants of them (truncated,
// a syntax error, an unresolved reference, a reference cycle, mistyped references), which made
// OCCT crash before src/cad/step_import.cpp guarded it.
//
// Checks: no crash or hang; an error names the file and gives a reason; a model has parts with
// triangles, one face id per triangle below the part's face count, an AAG node per face, finite
// positions and indices in range, a measured tessellation deviation that is -1 or finite, instances
// naming existing parts with finite placements.
#include <cmath>
#include <string>

#include "fuzz_common.h"
#include "interfere/cad/model.h"

namespace {

int entry(const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  const fs::path file = interfere::fuzz::work_dir("read_step") / "input.step";
  interfere::fuzz::put_file(file, data, size);
  const auto m = interfere::cad::import_step(file, {.measure_deviation = true});
  if (!m) {
    FUZZ_CHECK(m.error().file == file.string(), "the error does not name the file: " + m.error().message());
    FUZZ_CHECK(!m.error().reason.empty(), "an error without a reason");
    return 0;
  }
  FUZZ_CHECK(!m->parts.empty(), "a model without parts");
  for (const interfere::cad::Part& p : m->parts) {
    const std::string where = " (part '" + p.name + "')";
    FUZZ_CHECK(p.tessellation_deviation == -1 || (p.tessellation_deviation >= 0 && std::isfinite(p.tessellation_deviation)),
               "a tessellation deviation that is not -1 or a finite distance" + where);
    FUZZ_CHECK(p.face_ids.size() == p.mesh.num_triangles(), "face ids do not match the triangles" + where);
    for (std::uint32_t f : p.face_ids) FUZZ_CHECK(f < p.faces, "a face id beyond the part's faces" + where);
    FUZZ_CHECK(p.aag.nodes.size() == p.faces, "the AAG does not have a node per face" + where);
    for (const interfere::Vec3& v : p.mesh.positions) FUZZ_CHECK(interfere::is_finite(v), "non-finite vertex" + where);
    for (const interfere::Tri& t : p.mesh.triangles)
      for (std::uint32_t v : t) FUZZ_CHECK(v < p.mesh.num_vertices(), "index out of range" + where);
  }
  for (const interfere::cad::Instance& i : m->instances) {
    FUZZ_CHECK(i.part < m->parts.size(), "an instance of a part that does not exist: " + i.name);
    FUZZ_CHECK(interfere::is_finite(i.placement.t), "a non-finite placement: " + i.name);
  }
  return 0;
}

}  // namespace

INTERFERE_FUZZ_TARGET("read_step", entry);
