// The models of the FE targets benchmark (issue #26, item 7; bench/fem_targets.cpp,
// bench/fem_targets_tables.py -> docs/fem-benchmarks.md), generated in memory from
// fem/generate.h, each body one group, its displacement steps the mesh's field "DISP":
//
//  (a) frd_read_model: two hex8 (C3D8) boxes of 2n × 2n × n cells, 8n³ elements in all (n = 50:
//      10^6), A = [0,2]×[0,2]×[0,1], B the same shifted by 2.1 in x; step k (0-based) moves B
//      by -0.03(k+1) in x (the 0.1 gap closes between steps 2 and 3) and sags A by
//      -0.001(k+1)x² in z. Written as .frd (frd_bench_writer.h) and read back.
//  (b) twenty_body_model: 20 tet4 bodies on a 5 × 4 grid of pitch 1.1 (a checkerboard of unit
//      boxes and balls of radius 0.5: neighbours 0.1 apart), n³ cells × 6 tets each; step k grows
//      every ball about its centre by 6k % (its radius reaches 0.5 + 0.03k: it crosses its 2-4 box
//      neighbours from k = 4 on, never the diagonal balls up to k = 9) and shears every box by
//      0.01k (z += 0.01k(x - cx)).
//  (c) two_body_series_model: the pair of BM_FemSeriesStep (bench_fem.cpp): A a tet4 unit box,
//      B a tet4 ball of radius 0.5 at (1.6, 0.5, 0.5), n³ cells × 6 tets each, B moved by -0.01k
//      in x at step k (touching A at k = 10, 0.9 deep at k = 99), A sagging by -1e-4·k·x² in z (so
//      that both bodies change at every step and both are refitted, as in a real analysis).
#pragma once
#include <cstddef>

#include "interfere/fem/fem_mesh.h"

namespace interfere::bench_fem_targets {

/// Cells per axis of a tet4 (6 per cell) body of about `elements` elements.
int tet_cells_for(std::size_t elements);

FemMesh frd_read_model(std::size_t elements, int steps);
FemMesh twenty_body_model(std::size_t total_elements, int steps);
FemMesh two_body_series_model(std::size_t elements_per_body, int steps);

}  // namespace interfere::bench_fem_targets
