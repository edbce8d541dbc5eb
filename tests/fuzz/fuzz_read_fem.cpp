// Fuzz target for the FEM readers (fem/io.h): the input bytes are written to a file with each
// extension (.msh .bdf .vtk .vtu .inp .frd, and .fem for detection by content) and read with read_fem.
// (.frd: the CalculiX reader's file path, read_frd_file, issue #26; Exodus .e/.exo is not fed: the
// netCDF/HDF5 libraries it goes through are not ours to fuzz.)
//
// Checked on every read (abort = finding):
//  - no crash, hang, sanitizer report, or allocation out of proportion to the input;
//  - on error: a non-empty reason, never both a line and a byte offset; when the error is about
//    the input file itself (not a file it INCLUDEs), a line within the file's lines / a byte offset
//    within its size; never "out of memory";
//  - on success: validate_fem_mesh passes (ids unique, node indices in range, finite coordinates,
//    fields one value per node), at least one element, one dimension only;
//  - the first mesh read successfully survives write_fem + read_fem through MSH 4.1 binary (when
//    its ids are positive) and VTU appended: same nodes bit for bit, same element types, ids and
//    node lists.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>

#include "fuzz_common.h"
#include "interfere/fem/io.h"

namespace {

namespace fs = std::filesystem;
using interfere::Error;
using interfere::Expected;
using interfere::FemMesh;

const fs::path& fem_work_dir() { return interfere::fuzz::work_dir("fem"); }
void put(const fs::path& p, const std::uint8_t* data, std::size_t size) { interfere::fuzz::put_file(p, data, size); }

void check_error(const Error& e, const fs::path& path, std::int64_t lines, std::size_t size) {
  const std::string at = " [" + path.filename().string() + "]: " + e.message();
  FUZZ_CHECK(!e.reason.empty(), "empty error reason" + at);
  FUZZ_CHECK(!(e.line >= 0 && e.byte >= 0), "error has both a line and a byte offset" + at);
  FUZZ_CHECK(e.reason.rfind("out of memory", 0) != 0, "out of memory on a small input" + at);
  if (e.file != path.string()) return;  // about an INCLUDEd file
  FUZZ_CHECK(e.line == -1 || (e.line >= 1 && e.line <= lines), "error line outside the file's " + std::to_string(lines) + " lines" + at);
  FUZZ_CHECK(e.byte == -1 || static_cast<std::uint64_t>(e.byte) <= size, "error byte offset outside the file's " + std::to_string(size) + " bytes" + at);
}

void check_mesh(const FemMesh& m, const fs::path& path) {
  const std::string at = " [" + path.filename().string() + "]";
  const interfere::Status s = interfere::validate_fem_mesh(m);
  FUZZ_CHECK(s.ok(), "validate_fem_mesh: " + (s.ok() ? std::string() : s.error().reason) + at);
  FUZZ_CHECK(m.num_elements() > 0, "success without elements" + at);
  const int dim = interfere::elem_info(m.elem_types.front()).dim;
  for (interfere::ElemType t : m.elem_types) FUZZ_CHECK(interfere::elem_info(t).dim == dim, "mixed dimensions" + at);
}

void check_round_trip(const FemMesh& m) {
  bool positive = true;
  for (std::int64_t id : m.node_ids) positive &= id > 0 && id < 2147483647;
  for (std::int64_t id : m.elem_ids) positive &= id > 0;
  struct Out {
    const char* file;
    interfere::FemWriteOptions o;
  };
  const Out outs[] = {{"rt.msh", {.binary = true}}, {"rt.vtu", {.vtu_encoding = interfere::VtuEncoding::appended}}};
  for (const Out& o : outs) {
    if (std::string(o.file) == "rt.msh" && !positive) continue;
    const fs::path p = fem_work_dir() / o.file;
    const interfere::Status s = interfere::write_fem(m, p, o.o);
    FUZZ_CHECK(s.ok(), std::string("write_fem ") + o.file + ": " + (s.ok() ? std::string() : s.error().message()));
    Expected<FemMesh> back = interfere::read_fem(p);
    FUZZ_CHECK(back.has_value(), std::string("written mesh does not read back (") + o.file + "): " + (back ? std::string() : back.error().message()));
    FUZZ_CHECK(back->nodes.size() == m.nodes.size() &&
                   (m.nodes.empty() || std::memcmp(back->nodes.data(), m.nodes.data(), m.nodes.size() * sizeof(interfere::Vec3)) == 0),
               std::string("nodes change in the round trip through ") + o.file);
    FUZZ_CHECK(back->node_ids == m.node_ids && back->elem_ids == m.elem_ids && back->elem_types == m.elem_types &&
                   back->elem_nodes == m.elem_nodes,
               std::string("elements change in the round trip through ") + o.file);
  }
}

int entry(const std::uint8_t* data, std::size_t size) {
  if (size > (1u << 20)) return 0;
  std::int64_t lines = 1;
  for (std::size_t i = 0; i < size; ++i) lines += data[i] == '\n';
  bool tripped = false;
  for (const char* name : {"in.msh", "in.bdf", "in.vtk", "in.vtu", "in.inp", "in.frd", "in.fem"}) {
    const fs::path p = fem_work_dir() / name;
    put(p, data, size);
    Expected<FemMesh> m = interfere::read_fem(p);
    if (!m) {
      check_error(m.error(), p, lines, size);
      continue;
    }
    check_mesh(*m, p);
    if (!tripped) {
      tripped = true;
      check_round_trip(*m);
    }
  }
  return 0;
}

}  // namespace

INTERFERE_FUZZ_TARGET("read_fem", entry);
