// What the rows of one frame share (issue #27, the 1,024-roller frame rate): run_assembly
// (assembly_run.cpp) computes it once per frame and passes it to the rows, where solve_pair computes
// it per row; the same operations on the same poses, so every row is the same bit for bit.
#pragma once
#include <cstdint>
#include <vector>

#include "interfere/bearing/assembly.h"

namespace interfere::bearing::detail {

/// A bearing's bounding sphere at a frame: about its outer ring's posed sphere centre, holding every
/// part's posed sphere (assembly.h PartSphere); the bearing-bearing rows' first test
/// (assembly_pairs.cpp, solve_structural).
struct BearingSphere {
  Vec3 centre;
  double radius = 0;
};

/// The sphere of the bearing whose outer ring is part `outer`, at `poses`.
BearingSphere bearing_sphere(const Assembly& as, std::uint32_t outer, const std::vector<Transform>& poses);

/// solve_pair, with the frame's bearing spheres indexed by bearing (bearing_sphere at these poses),
/// or nullptr (then computed per row, as solve_pair does).
AssemblyPairResult solve_pair_in_frame(const Assembly& as, const AssemblyPair& pair, const std::vector<Transform>& poses,
                                       double clearance, const BearingSphere* spheres);

}  // namespace interfere::bearing::detail
