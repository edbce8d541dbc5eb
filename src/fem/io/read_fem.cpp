// read_fem / write_fem: format names, detection by extension then by content, dispatch to the
// per-format files (one format per file in src/fem/io/), atomic writes.
#include <algorithm>

#include "interfere/core/atomic_file.h"
#include "interfere/core/coordinate_range.h"
#include "scan.h"

namespace interfere {

FemFormat fem_format_from_name(const std::string& name) {
  const std::string n = fem_io::to_lower(name);
  if (n == "msh" || n == "gmsh") return FemFormat::msh;
  if (n == "nastran" || n == "bdf" || n == "nas") return FemFormat::nastran;
  if (n == "vtk") return FemFormat::vtk_legacy;
  if (n == "vtu") return FemFormat::vtu;
  if (n == "inp" || n == "abaqus") return FemFormat::abaqus;
  if (n == "frd" || n == "calculix") return FemFormat::frd;
  if (n == "exodus" || n == "exo" || n == "e") return FemFormat::exodus;
  return FemFormat::automatic;
}

const char* fem_format_name(FemFormat f) {
  switch (f) {
    case FemFormat::msh: return "msh";
    case FemFormat::nastran: return "nastran";
    case FemFormat::vtk_legacy: return "vtk";
    case FemFormat::vtu: return "vtu";
    case FemFormat::abaqus: return "inp";
    case FemFormat::frd: return "frd";
    case FemFormat::exodus: return "exodus";
    default: return "auto";
  }
}

FemFormat fem_format_from_path(const std::filesystem::path& path) {
  const std::string ext = fem_io::to_lower(path.extension().string());
  if (ext == ".msh") return FemFormat::msh;
  if (ext == ".bdf" || ext == ".nas" || ext == ".dat" || ext == ".blk") return FemFormat::nastran;
  if (ext == ".vtk") return FemFormat::vtk_legacy;
  if (ext == ".vtu") return FemFormat::vtu;
  if (ext == ".inp") return FemFormat::abaqus;
  if (ext == ".frd") return FemFormat::frd;
  if (ext == ".e" || ext == ".exo") return FemFormat::exodus;
  return FemFormat::automatic;
}

namespace {

/// By content: the first meaningful line.
FemFormat sniff(std::string_view s) {
  using namespace fem_io;
  if (s.substr(0, 3) == "\xEF\xBB\xBF") s = s.substr(3);
  // Exodus II: a netCDF classic/64-bit file or a netCDF-4 (HDF5) file.
  if (s.starts_with(std::string_view("CDF\x01", 4)) || s.starts_with(std::string_view("CDF\x02", 4)) ||
      s.starts_with(std::string_view("CDF\x05", 4)) || s.starts_with("\x89HDF\r\n"))
    return FemFormat::exodus;
  Text t(s);
  std::string_view line;
  int looked = 0;
  while (t.next_line(line) && looked < 200) {
    const std::string_view l = trim(line);
    if (l.empty()) continue;
    ++looked;
    if (l.starts_with("$MeshFormat")) return FemFormat::msh;
    if (l.starts_with("1C") || l.starts_with("2C") || l.starts_with("1UUSER")) return FemFormat::frd;  // CalculiX results
    if (istarts_with(l, "# vtk DataFile")) return FemFormat::vtk_legacy;
    if (l.starts_with("<?xml") || l.starts_with("<VTKFile")) return FemFormat::vtu;
    if (l.starts_with("**")) continue;  // Abaqus comment
    if (l.starts_with("*")) return FemFormat::abaqus;
    if (l.starts_with("$")) continue;  // Nastran comment
    static const char* const kNastran[] = {"GRID", "CTETRA", "CHEXA", "CPENTA", "CPYRA", "CTRIA", "CQUAD", "BEGIN BULK", "SOL ",
                                           "CEND", "INCLUDE", "PSOLID", "PSHELL", "NASTRAN", "ID ", "TIME ", "MAT"};
    for (const char* k : kNastran) {
      if (istarts_with(l, k)) return FemFormat::nastran;
    }
  }
  return FemFormat::automatic;
}

}  // namespace

Expected<FemMesh> read_fem(const std::filesystem::path& path, const FemReadOptions& options) {
  const std::string file = path.string();
  FemFormat f = options.format;
  if (f == FemFormat::automatic) f = fem_format_from_path(path);
  Expected<std::string> bytes = std::string();
  // (the Exodus library reads the file itself; a .frd is mapped by read_frd_file)
  const bool frd_file = f == FemFormat::frd;
  if (f != FemFormat::exodus && !frd_file) {
    bytes = fem_io::read_file_bytes(path);
    if (!bytes) return bytes.error();
  }
  if (f == FemFormat::automatic) f = sniff(*bytes);
  Expected<FemMesh> m = fem_io::file_error(file, "cannot tell the FEM format (not .msh/.bdf/.nas/.dat/.vtk/.vtu/.inp/.frd/.e/.exo and the content is none of them)");
  switch (f) {
    case FemFormat::msh: m = fem_io::read_msh(file, *bytes); break;
    case FemFormat::nastran: m = fem_io::read_nastran(path, *bytes); break;
    case FemFormat::vtk_legacy: m = fem_io::read_vtk_legacy(file, *bytes); break;
    case FemFormat::vtu: m = fem_io::read_vtu(file, *bytes); break;
    case FemFormat::abaqus: m = fem_io::read_abaqus(path, *bytes); break;
    case FemFormat::frd: m = frd_file ? fem_io::read_frd_file(path) : fem_io::read_frd(file, *bytes); break;
    case FemFormat::exodus: m = fem_io::read_exodus(path); break;
    default: break;
  }
  if (!m) return m;
  // The coordinate range of the exact predicates (issue #23, item 7), once for every format.
  if (const std::size_t i = first_out_of_range(m->nodes); i < m->nodes.size()) {
    const std::string id = i < m->node_ids.size() ? std::to_string(m->node_ids[i]) : std::to_string(i);
    return Error{.file = file, .reason = "node " + id + ": " + coordinate_range_reason(m->nodes[i])};
  }
  return m;
}

Status write_fem(const FemMesh& mesh, const std::filesystem::path& path, const FemWriteOptions& options) {
  const std::string file = path.string();
  FemFormat f = options.format;
  if (f == FemFormat::automatic) f = fem_format_from_path(path);
  Status v = validate_fem_mesh(mesh);
  if (!v) return Error{.file = file, .reason = "mesh to write is invalid: " + v.error().reason};
  for (const FemArray& a : options.cell_data) {
    const std::size_t n = a.reals.empty() ? a.ints.size() : a.reals.size();
    if (a.components < 1 || n != mesh.num_elements() * static_cast<std::size_t>(a.components))
      return Error{.file = file, .reason = "cell data '" + a.name + "' has " + std::to_string(n) + " values for " + std::to_string(mesh.num_elements()) + " elements"};
  }
  for (const FemArray& a : options.point_data) {
    const std::size_t n = a.reals.empty() ? a.ints.size() : a.reals.size();
    if (a.components < 1 || n != mesh.num_nodes() * static_cast<std::size_t>(a.components))
      return Error{.file = file, .reason = "point data '" + a.name + "' has " + std::to_string(n) + " values for " + std::to_string(mesh.num_nodes()) + " nodes"};
  }
  std::string out;
  Status st;
  switch (f) {
    case FemFormat::msh: st = fem_io::write_msh(mesh, options, out); break;
    case FemFormat::vtk_legacy: st = fem_io::write_vtk_legacy(mesh, options, out); break;
    case FemFormat::vtu: st = fem_io::write_vtu(mesh, options, out); break;
    case FemFormat::nastran: st = fem_io::write_nastran(mesh, options, out); break;
    case FemFormat::abaqus: st = fem_io::write_abaqus(mesh, options, out); break;
    case FemFormat::frd:
    case FemFormat::exodus: return Error{.file = file, .reason = std::string("no writer for ") + fem_format_name(f) + " files (read only; write .msh, .vtk, .vtu, .bdf or .inp)"};
    default: return Error{.file = file, .reason = "cannot tell the output format from the extension (use .msh, .vtk, .vtu, .bdf or .inp)"};
  }
  if (!st) {
    Error e = st.error();
    e.file = file;
    return e;
  }
  return write_file_atomic(path, out);
}

}  // namespace interfere
