// Loading one FEM part for the CLI (clash, surface): read_fem, surface extraction, the choice of
// a body (--part), its displacements (--disp CSV or --field in the mesh file) and its pose.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common.h"
#include "interfere/core/transform.h"
#include "interfere/fem/deform.h"
#include "interfere/fem/fem_mesh.h"
#include "interfere/fem/surface.h"

namespace interfere::cli {

/// True for the FEM extensions (.msh .bdf .nas .dat .vtk .vtu .inp .frd .e .exo), case-insensitive.
bool is_fem_file(const std::string& path);

struct FemPartOptions {
  std::string part;          ///< body name; empty: the only body (an error when there are several)
  std::string disp;          ///< displacement CSV (node_id,ux,uy,uz or step,node_id,ux,uy,uz)
  std::string field;         ///< a nodal vector field of the mesh file, by name
  bool linear_faces = false;  ///< corner-only faces
  std::string split = "auto";  ///< auto, group, connectivity, single
  std::string transform;     ///< pose (12 numbers), applied to nodes and displacement vectors
  PartUnit unit{"mm", "default"};  ///< the file's unit (part_unit; issue #23, item 6)
  double unit_scale = 1;     ///< file unit to the working unit: nodes and displacements, before the pose
};

struct FemPart {
  std::string file, label;  ///< label: "A", "B" or "input" (for messages)
  PartUnit unit{"mm", "default"};  ///< of the file's coordinates
  double unit_scale = 1;           ///< to the working unit (applied to nodes and displacements)
  std::string format;       ///< "msh", "vtu", ..., or the mesh format for STL/PLY/OBJ/OFF input
  bool from_triangle_mesh = false;  ///< a triangle mesh file taken as tri3 shells (ids = index + 1)
  std::shared_ptr<FemMesh> mesh;           ///< shared when A and B come from one file
  std::shared_ptr<SurfaceResult> surface_;  ///< every body's surface
  const SurfaceResult& surface() const { return *surface_; }
  std::vector<std::size_t> chosen;  ///< indices into surface.parts
  std::shared_ptr<NodalSeries> csv;  ///< (a pointer: `displacement` may point into it)
  const NodalSeries* displacement = nullptr;  ///< points into csv or mesh->fields; null = none
  std::string displacement_source;            ///< "csv", "field" or ""
  std::string displacement_file;              ///< the CSV's path (source "csv"), else ""
  Transform transform;
  double read_seconds = 0, extract_seconds = 0;
  std::vector<std::string> warnings;  ///< the file's first (file_warnings of them), then the chosen bodies'
  std::size_t file_warnings = 0;

  const SurfacePart& part() const { return surface_->parts[chosen.front()]; }
  SeriesPart series() const { return {mesh.get(), &part(), displacement}; }
  std::size_t num_steps() const { return displacement ? displacement->num_steps() : 0; }
};

/// Reads and prepares a part; throws InputError (file, line/byte, reason). `all_parts_ok`: without
/// --part every body is chosen (surface command); otherwise exactly one body must result.
FemPart load_fem_part(const std::string& file, const FemPartOptions& options, const std::string& label,
                      bool all_parts_ok);

/// Another body of an already loaded file (same displacement, pose and options): shares the mesh,
/// the surfaces and the displacements; throws InputError when `part` is unknown or ambiguous.
FemPart other_part(const FemPart& loaded, const std::string& part, const std::string& label);

/// Input description for the JSON report (docs/report.md, "FEM inputs").
nlohmann::json fem_part_json(const FemPart& p);
/// Region naming by the solver's ids (docs/report.md, "regions[].fem").
nlohmann::json region_ids_json(const RegionIds& ids);

/// 0-based step from --step (checked against the series); throws InputError when out of range.
/// `whose`: the series, for the message ("the displacements of A (field 'disp' of model.msh)");
/// empty: "the series".
std::size_t check_step(long long step, std::size_t num_steps, const std::string& whose = "");

}  // namespace interfere::cli
