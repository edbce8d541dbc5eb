#!/usr/bin/env bash
# Installs dependencies, builds the CLI and clashes the bundled example (data/examples/scene.json):
# a tilted pin through a plate. Writes out/report.json, out/pairs.txt, out/curves.{obj,vtk} and the
# clash regions out/region_{a,b}.stl. Exit status 0 (the example clashes, as expected).
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
set +e
./build/apps/cli/interfere clash --scene data/examples/scene.json --json out/report.json \
  --pairs out/pairs.txt --curves out/curves.obj --curves out/curves.vtk \
  --region-a out/region_a.stl --region-b out/region_b.stl
status=$?
set -e
[ "$status" -eq 1 ] || { echo "unexpected exit status $status (1 = interference expected)"; exit 1; }
echo "report written to out/report.json"
