#!/usr/bin/env python3
"""ctest python_pip_install (issue #30): `pip install .` into a fresh venv, then use the package.

    pip_install_check.py --source REPO --build CMAKE_BUILD_DIR --work DIR

1. `python3 -m venv --system-site-packages DIR/venv` (numpy and setuptools from Debian);
2. `DIR/venv/bin/pip install --no-build-isolation --no-deps REPO` with
   INTERFERE_CMAKE_BUILD_DIR=CMAKE_BUILD_DIR, so setup.py reuses this build tree (an incremental
   build of `_interfere`, no second configure);
3. from a directory outside the source tree, with the venv's python: `import interfere` comes from
   the venv, a small clash returns numpy arrays, `py.typed` and `_interfere.pyi` are installed and
   the stub declares every public name (stub_check.py), importing without numpy fails with an
   ImportError naming numpy, and `python -m interfere --version` prints the CLI's version from
   the CLI the wheel carries (interfere/bin/interfere; no INTERFERE_CLI, none on PATH) when this
   build tree has the CLI, else from INTERFERE_CLI / PATH.
Exits 77 (skipped) when the interpreter has no venv/ensurepip or the venv no pip.
"""

import argparse
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))

CHECK = r'''
import os, sys
import numpy as np
import interfere as itf
from stub_check import check_stub_file, stub_path
venv = sys.argv[1]
assert os.path.realpath(itf.__file__).startswith(os.path.realpath(venv)), itf.__file__
a, b = itf.make_overlapping_spheres(2000)
r = itf.clash(itf.make_model(a), itf.make_model(b))
assert r.interference and r.verdict == "clash", r
assert isinstance(r.pair_array(), np.ndarray) and r.pair_array().shape == (len(r.pairs), 3)
assert isinstance(r.regions[0].triangles_a, np.ndarray) and r.regions[0].triangles_a.dtype == np.uint32
assert isinstance(a.positions, np.ndarray) and a.positions.dtype == np.float64
pkg = os.path.dirname(itf.__file__)
assert os.path.isfile(os.path.join(pkg, "py.typed")), pkg
print("stubs:", check_stub_file(stub_path(itf._interfere), itf._interfere))
print("ok", itf.__version__, itf.__file__)
'''

NO_NUMPY = r'''
import sys
sys.modules["numpy"] = None  # as if numpy were not installed
try:
    import interfere
except ImportError as e:
    assert "numpy" in str(e) and "python3-numpy" in str(e), str(e)
    print("ImportError:", e)
else:
    raise SystemExit("import interfere succeeded without numpy")
'''


def run(args, **kw):
    print("+", " ".join(args), flush=True)
    r = subprocess.run(args, text=True, capture_output=True, **kw)
    sys.stdout.write(r.stdout)
    sys.stdout.write(r.stderr)
    return r


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True)
    ap.add_argument("--build", required=True)
    ap.add_argument("--work", required=True)
    o = ap.parse_args()

    shutil.rmtree(o.work, ignore_errors=True)
    os.makedirs(o.work)
    venv = os.path.join(o.work, "venv")
    r = run([sys.executable, "-m", "venv", "--system-site-packages", venv])
    if r.returncode != 0:
        print("SKIP: cannot create a venv (Debian: apt-get install python3-venv)")
        return 77
    py, pip = os.path.join(venv, "bin", "python"), os.path.join(venv, "bin", "pip")
    if not os.path.exists(pip):
        print("SKIP: the venv has no pip (Debian: apt-get install python3-venv python3-pip)")
        return 77

    env = dict(os.environ, INTERFERE_CMAKE_BUILD_DIR=os.path.abspath(o.build), PIP_NO_INDEX="1",
               PIP_DISABLE_PIP_VERSION_CHECK="1")
    env.pop("PYTHONPATH", None)  # the venv's package, not the build tree's
    r = run([pip, "install", "--no-build-isolation", "--no-deps", o.source], env=env, cwd=o.work)
    if r.returncode != 0:
        print("FAIL: pip install")
        return 1

    outside = tempfile.mkdtemp(dir=o.work)  # outside the source tree: no ./python/interfere to shadow
    env = dict(os.environ, PYTHONPATH=HERE)  # stub_check.py only; interfere itself from the venv
    r = run([py, "-c", CHECK, venv], env=env, cwd=outside)
    if r.returncode != 0 or "ok " not in r.stdout:
        print("FAIL: using the installed package")
        return 1
    r = run([py, "-c", NO_NUMPY], env=env, cwd=outside)
    if r.returncode != 0:
        print("FAIL: import without numpy")
        return 1

    cli = os.environ.get("INTERFERE_CLI") or shutil.which("interfere")
    if not cli:
        print("FAIL: no interfere CLI to run (INTERFERE_CLI unset and none on PATH)")
        return 1
    env = dict(os.environ)
    env.pop("INTERFERE_CLI", None)
    r = run([py, "-c", "import interfere, os; print(os.path.dirname(interfere.__file__))"], env=env, cwd=outside)
    bundled = os.path.join(r.stdout.strip(), "bin", "interfere")
    with open(os.path.join(o.build, "CMakeCache.txt")) as f:
        has_cli = "INTERFERE_BUILD_CLI:BOOL=ON" in f.read()
    if has_cli:  # the wheel carries the CLI: python -m interfere must find it with nothing on PATH
        if not os.access(bundled, os.X_OK):
            print(f"FAIL: the wheel has no executable {bundled}")
            return 1
        env["PATH"] = os.path.dirname(sys.executable)  # (no interfere there)
    else:
        env["PATH"] = os.path.dirname(os.path.abspath(cli)) + os.pathsep + env.get("PATH", "")
    r = run([py, "-m", "interfere", "--version"], env=env, cwd=outside)
    version = run([cli, "--version"]).stdout.strip()
    if r.returncode != 0 or not version or r.stdout.strip() != version:
        print(f"FAIL: python -m interfere --version printed {r.stdout!r}, the CLI {version!r}")
        return 1
    examples = os.path.join(o.source, "data", "examples")
    r = run([py, "-m", "interfere", "-q", "clash", os.path.join(examples, "plate.stl"), os.path.join(examples, "pin.obj")],
            env=env, cwd=outside)
    if r.returncode != 1 or "CLASH" not in r.stdout:
        print(f"FAIL: python -m interfere clash exited {r.returncode} (want 1, a clash)")
        return 1
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
