// Options of `interfere clash` (cmd_clash.cpp), shared with its FEM path (clash_fem.cpp).
#pragma once
#include <string>
#include <vector>

#include "common.h"
#include "view_output.h"
#include "interfere/query/clash.h"

namespace interfere::cli {

struct ClashOptions : TwoPartOptions {
  std::string pairs, region_a, region_b, test = "exact", broadphase = "bvh";
  std::vector<std::string> curves;
  double clearance = 0;
  bool no_containment = false;
  bool depth = false;  ///< two-part clash: measure depths (scenes always do)
  /// Simplified inputs (interfere simplify): their stored error bounds widen the clearance, and any
  /// pair within them counts as a possible clash of the original parts.
  bool conservative = false;
  std::size_t max_clearance_pairs = 100000;
  ViewOutputs views;  ///< --html, --glb, --pvd (issue #25)

  // Scenes (issue #24; cmd_clash_scene.cpp).
  std::vector<std::string> more;       ///< inputs after A and B
  std::vector<std::string> test_args;  ///< --test: clash tests (exact/moller/gd: the triangle test, as before)
  bool reference = true;  // FE steps: check the undeformed model too (designed contacts)
  std::string tests_file, baseline, csv, frames_csv, frame_pairs_csv, group_by = "pair", motion;
  double group_distance = 0, tolerance = 0;

  // FEM inputs (docs/fem.md, "CLI"): a flag without -a/-b applies to both parts.
  std::string part, part_a, part_b, disp, disp_a, disp_b, field, field_a, field_b, split = "auto";
  std::string regions_vtu;
  double scale = 1.0;
  long long step = -1;  ///< -1: every step
  bool linear_faces = false;
  bool fem_requested() const {
    return !part.empty() || !part_a.empty() || !part_b.empty() || !disp.empty() || !disp_a.empty() ||
           !disp_b.empty() || !field.empty() || !field_a.empty() || !field_b.empty() || !regions_vtu.empty() ||
           step >= 0 || linear_faces || split != "auto" || scale != 1.0;
  }
};

/// Registers --part/-a/-b, --disp/-a/-b, --field/-a/-b, --scale, --step, --linear-faces, --split,
/// --regions-vtu.
void add_fem_clash_options(CLI::App& command, ClashOptions& o);

/// `interfere clash` on a scene: bodies from every input, clash tests, baseline, motion.
int run_scene_clash(const ClashOptions& o, const CLI::App& command, const std::vector<std::string>& clash_tests);

/// The clash of FEM parts (either input a FEM file, or a FEM flag given): per step or per series.
int run_fem_clash(const ClashOptions& o, const ResolvedParts& parts, const ClashRequest& request);

}  // namespace interfere::cli
