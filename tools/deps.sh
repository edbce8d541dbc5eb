#!/usr/bin/env bash
# Installs the Debian 12 packages interfere needs (build, tests, benchmarks, peers; gmsh makes test meshes and is a reader peer; Graphviz reads the AAG drawings back in a test). Run as root.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
pkgs=(build-essential cmake ninja-build python3 git
      libtbb-dev libeigen3-dev libcli11-dev nlohmann-json3-dev libfmt-dev
      libgtest-dev googletest libbenchmark-dev
      libcgal-dev libgmp-dev libmpfr-dev libfcl-dev
      pybind11-dev python3-dev python3-numpy
      python3-setuptools python3-wheel python3-pip python3-venv  # (issue #30: `pip install --no-build-isolation .` and its ctest, python_pip_install)
      zlib1g-dev gmsh libgmsh-dev
      libpng-dev  # (issue #27: 16-bit grayscale PNG scar height maps, optional in CMake)
      liburdfdom-dev  # (issue #28: URDF robots for the probe cell, optional in CMake)
      libopenmpi-dev openmpi-bin  # (issue #31: interfere-mpi, -DINTERFERE_WITH_MPI=ON, and its mpirun tests)
      libocct-data-exchange-dev libocct-ocaf-dev libocct-modeling-algorithms-dev
      libocct-modeling-data-dev libocct-foundation-dev libocct-visualization-dev
      libmeshoptimizer-dev libopenmesh-dev
      graphviz  # (tests: `interfere features --dot` output is read back by Graphviz)
      calculix-ccx  # (tests, issue #26: the CalculiX solver writes the .frd results the reader is checked on)
      libexodusii-dev  # (issue #26: the Exodus II reader of interfere_fem, optional in CMake)
      netcdf-bin python3-meshio python3-netcdf4  # (tests, issue #26: meshio writes the Exodus test files, ncdump checks them)
      python3-jsonschema python3-paraview  # (tests/view, issue #25: the glTF schema check; issue #30: the report schemas, docs/schema; ParaView reads the .pvd series back)
      chromium)  # (tests/viewer, issue #25: the HTML viewer page in headless Chromium via puppeteer-core; Node.js/npm come with the machine: do not apt-install npm)
missing=()
for p in "${pkgs[@]}"; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
if ((${#missing[@]})); then
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
