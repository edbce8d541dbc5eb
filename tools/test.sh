#!/usr/bin/env bash
# Installs dependencies, builds everything (library, CLI, tests, examples, benchmarks) and runs every
# test with ctest. Extended checks on ../shared/data run when that folder exists and skip otherwise.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DINTERFERE_BUILD_TESTS=ON -DINTERFERE_BUILD_CLI=ON \
  -DINTERFERE_BUILD_ORACLE_TESTS=ON -DINTERFERE_BUILD_BENCH=ON -DINTERFERE_WITH_MPI=ON \
  -DPython3_EXECUTABLE=/usr/bin/python3
cmake --build build -j2
ctest --test-dir build --output-on-failure -j2
