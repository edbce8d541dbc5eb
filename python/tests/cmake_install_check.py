#!/usr/bin/env python3
"""ctest python_cmake_install (issue #30, item 6): where `cmake --install` puts the package.

    cmake_install_check.py STAGE RELDIR PREFIX

STAGE is the tree the fixture `installed_package` installed into (cmake --install --prefix STAGE),
RELDIR the configured INTERFERE_PYTHON_INSTALL_DIR, PREFIX the configured CMAKE_INSTALL_PREFIX.
Checks that STAGE/RELDIR/interfere holds the module, the package files, py.typed and the stub, that
it imports from there (outside the source tree) with numpy results, and, when PREFIX is this
interpreter's own install prefix (Debian: /usr/local), that PREFIX/RELDIR is on the interpreter's
sys.path: the installed module is found without PYTHONPATH (Debian's python3 reads
/usr/local/lib/python3.11/dist-packages, not .../site-packages).
"""

import glob
import os
import subprocess
import sys
import sysconfig
import tempfile


def main():
    stage, rel, prefix = sys.argv[1:4]
    pkg = os.path.join(stage, rel, "interfere")
    for name in ("__init__.py", "__main__.py", "py.typed", "_interfere.pyi"):
        if not os.path.isfile(os.path.join(pkg, name)):
            print(f"FAIL: {name} not installed in {pkg}")
            return 1
    if not glob.glob(os.path.join(pkg, "_interfere*.so")):
        print(f"FAIL: no extension module in {pkg}")
        return 1
    env = dict(os.environ, PYTHONPATH=os.path.join(stage, rel))
    code = ("import interfere, numpy; m = interfere.make_box((0, 0, 0), (1, 1, 1)); "
            "assert isinstance(m.positions, numpy.ndarray); print(interfere.__file__)")
    with tempfile.TemporaryDirectory() as cwd:
        r = subprocess.run([sys.executable, "-c", code], env=env, cwd=cwd, capture_output=True, text=True)
    if r.returncode != 0 or not os.path.realpath(r.stdout.strip()).startswith(os.path.realpath(pkg)):
        print(f"FAIL: import from {pkg}: {r.stdout}{r.stderr}")
        return 1
    own_prefix = sysconfig.get_paths()["data"]
    if os.path.realpath(prefix) == os.path.realpath(own_prefix):
        target = os.path.realpath(os.path.join(prefix, rel))
        if target not in [os.path.realpath(p) for p in sys.path if p]:
            print(f"FAIL: {prefix}/{rel} is not on {sys.executable}'s sys.path {sys.path}")
            return 1
        print(f"{prefix}/{rel} is on sys.path")
    else:
        print(f"(prefix {prefix} is not the interpreter's {own_prefix}: sys.path check not applicable)")
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
