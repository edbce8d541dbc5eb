"""Builds the Python package `interfere` with CMake (issue #30; docs/python.md, "Install").

    pip install --no-build-isolation .      # offline, with Debian's python3-setuptools/-wheel/-numpy

`build_ext` configures this repository's CMakeLists.txt with the Python module on and the tests,
benchmarks and CLI off, builds the target `_interfere` (which also writes the type stubs,
python/tools/stubgen.py) and copies the extension and `_interfere.pyi` into the wheel; the pure
Python files and `py.typed` come from python/interfere/.

Environment:
  INTERFERE_CMAKE_BUILD_DIR   an already configured CMake build tree to reuse: no configure, only
                              an incremental `cmake --build DIR --target _interfere` (tests, developers)
  INTERFERE_CMAKE_ARGS        extra configure arguments (split on spaces), e.g. -DINTERFERE_WITH_OCCT=OFF
  CMAKE_BUILD_PARALLEL_LEVEL  build jobs (default: the number of CPUs)
Without INTERFERE_CMAKE_BUILD_DIR the CMake tree is build-pip/cmake (kept, so a second
`pip install .` is incremental) and setuptools' files go to build-pip/; with it, to DIR/python/setuptools.
"""

import glob
import os
import re
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))
# The Debian packages a clean build needs (README "Install"); named when a step fails. Before the
# first configure, python/tools/build_deps.py names the ones this machine lacks (issue #30, "Bad
# input"; INTERFERE_SKIP_DEPS_CHECK=1 skips that check, e.g. for dependencies outside the system
# include directories that CMake is told about with INTERFERE_CMAKE_ARGS).
sys.path.insert(0, os.path.join(ROOT, "python", "tools"))
import build_deps  # noqa: E402

# The wheel carries the command-line tool (interfere/bin/interfere, and interfere-cad when
# OpenCASCADE is found), so that `python -m interfere` works after `pip install .` alone;
# INTERFERE_PIP_CLI=0 builds the module only (fewer dependencies, a shorter build).
WITH_CLI = os.environ.get("INTERFERE_PIP_CLI", "1") not in ("0", "OFF", "off", "no")
DEBIAN_BUILD_DEPS = " ".join(build_deps.PACKAGES[:2] + ["ninja-build"] + build_deps.PACKAGES[2:] +
                             (build_deps.CLI_PACKAGES if WITH_CLI else []) + ["python3-setuptools", "python3-wheel"])


def cache_on(build_dir, name):
    """Whether the CMake cache of `build_dir` has the option `name` ON."""
    try:
        with open(os.path.join(build_dir, "CMakeCache.txt")) as f:
            return re.search(r"^%s:BOOL=(ON|TRUE|1|YES)$" % re.escape(name), f.read(), re.M | re.I) is not None
    except OSError:
        return False


def project_version():
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        m = re.search(r"project\(\s*interfere\s+VERSION\s+([0-9.]+)", f.read())
    if not m:
        raise RuntimeError("setup.py: no `project(interfere VERSION x.y.z)` in CMakeLists.txt")
    return m.group(1)


def fail(message):
    sys.stderr.write(f"\ninterfere setup.py: error: {message}\n")
    raise SystemExit(1)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        cmake = shutil.which("cmake")
        if cmake is None:
            fail("cmake was not found on PATH (Debian: apt-get install cmake). Build dependencies: " +
                 DEBIAN_BUILD_DEPS)
        reuse = os.environ.get("INTERFERE_CMAKE_BUILD_DIR")
        if reuse:
            build_dir = os.path.abspath(reuse)
            if not os.path.isfile(os.path.join(build_dir, "CMakeCache.txt")):
                fail(f"INTERFERE_CMAKE_BUILD_DIR={reuse} is not a configured CMake build tree (no CMakeCache.txt)")
        else:
            build_dir = os.path.join(ROOT, "build-pip", "cmake")
            if not os.environ.get("INTERFERE_SKIP_DEPS_CHECK"):
                lacking = build_deps.missing(cli=WITH_CLI)
                if lacking:
                    fail(build_deps.message(lacking))
            self.configure(cmake, build_dir)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        targets = ["_interfere"]
        cli = WITH_CLI and cache_on(build_dir, "INTERFERE_BUILD_CLI")
        if cli:
            targets.append("interfere")
            if cache_on(build_dir, "INTERFERE_WITH_OCCT"):
                targets.append("interfere-cad")
        self.run_step([cmake, "--build", build_dir, "--target", *targets, "-j", jobs], "build")

        package_dir = os.path.join(build_dir, "python", "interfere")
        built = sorted(glob.glob(os.path.join(package_dir, "_interfere*.so")) +
                       glob.glob(os.path.join(package_dir, "_interfere*.pyd")))
        if not built:
            fail(f"the build left no _interfere extension in {package_dir} (is INTERFERE_BUILD_PYTHON on there?)")
        suffix = sysconfig.get_config_var("EXT_SUFFIX") or ".so"
        if not built[-1].endswith(suffix):
            fail(f"{built[-1]} was built for another Python (this one, {sys.executable}, needs *{suffix}); "
                 "reconfigure that tree with -DPython3_EXECUTABLE=" + sys.executable + " or build without "
                 "INTERFERE_CMAKE_BUILD_DIR")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built[-1], target)
        stub = os.path.join(package_dir, "_interfere.pyi")
        if not os.path.isfile(stub):
            fail(f"the build left no type stubs {stub} (python/tools/stubgen.py)")
        shutil.copyfile(stub, os.path.join(os.path.dirname(target), "_interfere.pyi"))
        # The CLI next to the package (python -m interfere runs interfere/bin/interfere first).
        bin_dir = os.path.join(os.path.dirname(target), "bin")
        shutil.rmtree(bin_dir, ignore_errors=True)
        for name in targets[1:]:
            exe = os.path.join(build_dir, "apps", "cli", name)
            if not os.path.isfile(exe):
                fail(f"the build left no {exe}")
            os.makedirs(bin_dir, exist_ok=True)
            shutil.copy2(exe, os.path.join(bin_dir, name))  # (copy2: the executable bit too)

    def configure(self, cmake, build_dir):
        args = [cmake, "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release",
                "-DINTERFERE_BUILD_PYTHON=ON", "-DINTERFERE_BUILD_TESTS=OFF", "-DINTERFERE_BUILD_ORACLE_TESTS=OFF",
                "-DINTERFERE_BUILD_BENCH=OFF", "-DINTERFERE_BUILD_CLI=" + ("ON" if WITH_CLI else "OFF"),
                f"-DPython3_EXECUTABLE={sys.executable}"]
        if not os.path.isfile(os.path.join(build_dir, "CMakeCache.txt")) and shutil.which("ninja"):
            args += ["-G", "Ninja"]
        args += os.environ.get("INTERFERE_CMAKE_ARGS", "").split()
        self.run_step(args, "configure")

    def run_step(self, args, what):
        print(" ".join(args), flush=True)
        try:
            subprocess.run(args, check=True)
        except subprocess.CalledProcessError as e:
            fail(f"CMake {what} failed (exit {e.returncode}); its output above names what is missing. "
                 f"On Debian 12 the build needs: apt-get install {DEBIAN_BUILD_DEPS}")


# setuptools' own files (build/lib.*, bdist.*, egg-info): not its default build/, the CMake tree's
# usual name; inside the reused CMake tree when there is one, so the source tree stays untouched.
if os.environ.get("INTERFERE_CMAKE_BUILD_DIR"):
    _reuse = os.path.abspath(os.environ["INTERFERE_CMAKE_BUILD_DIR"])
    if not os.path.isfile(os.path.join(_reuse, "CMakeCache.txt")):
        fail(f"INTERFERE_CMAKE_BUILD_DIR={os.environ['INTERFERE_CMAKE_BUILD_DIR']} is not a configured CMake "
             "build tree (no CMakeCache.txt)")
    BUILD_BASE = os.path.join(_reuse, "python", "setuptools")
else:
    BUILD_BASE = os.path.join(ROOT, "build-pip")
os.makedirs(BUILD_BASE, exist_ok=True)

setup(
    version=project_version(),
    packages=["interfere"],
    package_dir={"": "python"},
    package_data={"interfere": ["py.typed", "*.pyi"]},
    ext_modules=[CMakeExtension("interfere._interfere")],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": BUILD_BASE}, "egg_info": {"egg_base": BUILD_BASE}},
    zip_safe=False,
)
