#!/usr/bin/env bash
# Installs dependencies, builds the CLI and clashes the bundled example (data/examples/scene.json):
# a tilted pin through a plate. Writes out/report.json, out/pairs.txt, out/curves.{obj,vtk} and the
# clash regions out/region_{a,b}.stl, the viewer page out/report.html and the glTF scene out/report.glb; then, built with OpenCASCADE, the features of the bundled casing
# (out/features.json) and its simplification for process step P2 (out/casing_P2.ply, out/simplify.json).
# Exit status 0 (the example clashes, as expected).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/deps.sh
# A fresh build directory is configured without the tests (faster); one that tools/test.sh
# configured keeps its options, so its test targets stay (ctest would otherwise run stale ones).
if [ -f build/CMakeCache.txt ]; then
  cmake -S . -B build
else
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DINTERFERE_BUILD_TESTS=OFF
fi
cmake --build build -j2 --target interfere
mkdir -p out
# The HTML viewer is built where Node.js and npm are (the machine's own; cmake/viewer.cmake).
view=()
if command -v npm > /dev/null; then view=(--html out/report.html); fi
set +e
./build/apps/cli/interfere clash --scene data/examples/scene.json --json out/report.json \
  --pairs out/pairs.txt --curves out/curves.obj --curves out/curves.vtk \
  --region-a out/region_a.stl --region-b out/region_b.stl --glb out/report.glb "${view[@]}"
status=$?
set -e
[ "$status" -eq 1 ] || { echo "unexpected exit status $status (1 = interference expected)"; exit 1; }
echo "report written to out/report.json; open out/report.html in a browser to see the clash"
# The CAD pipeline (issue #6) on the bundled casing, the paper's case (He & Xu §4): 35,552 triangles at
# this deflection, simplified to 5,200 keeping the bolting features of process step P2.
if ./build/apps/cli/interfere features --help >/dev/null 2>&1; then
  ./build/apps/cli/interfere features data/examples/casing.step --json out/features.json \
    --process data/examples/casing_process.json --step P2 --dot out/casing_aag.dot
  ./build/apps/cli/interfere simplify data/examples/casing.step out/casing_P2.ply --linear-deflection 0.0205 \
    --target 5200 --step P2 --process data/examples/casing_process.json --json out/simplify.json
  echo "reports written to out/features.json and out/simplify.json (AAG drawing: out/casing_aag.dot)"
fi
# A scene (issue #24): every instance pair of a STEP assembly checked at once, with a 15 mm clearance
# test; each clash with a stable id (rerun with --baseline out/scene.json to see new/active/resolved).
if ./build/apps/cli/interfere features --help >/dev/null 2>&1; then
  ./build/apps/cli/interfere clash tests/cli/data/assembly.step --clearance 15 \
    --json out/scene.json --csv out/scene.csv
  echo "scene report written to out/scene.json and out/scene.csv"
fi
