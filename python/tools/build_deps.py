"""The build dependencies of `pip install .` (setup.py, issue #30 "Bad input"): which Debian 12
packages a clean build of the module needs, and which of them this machine lacks, each found by
what it provides (a compiler on PATH, a header, a Python package), so that the install stops at
once with a message naming the missing packages instead of a compiler or CMake error later on.

Standard library only (setup.py imports it before anything is built)."""
import importlib.util
import os
import shutil
import sys
import sysconfig

# (Debian package, how it is found): ("cmd", names...) a program on PATH; ("header", paths...) one
# of the headers under the include directories; ("python", module) an importable module;
# ("python_h",) the interpreter's Python.h.
CHECKS = [
    ("cmake", ("cmd", "cmake")),
    ("g++", ("cmd", "$CXX", "c++", "g++", "clang++")),
    ("libtbb-dev", ("header", "oneapi/tbb.h", "tbb/tbb.h")),
    ("libeigen3-dev", ("header", "eigen3/Eigen/Core", "Eigen/Core")),
    ("nlohmann-json3-dev", ("header", "nlohmann/json.hpp")),
    ("zlib1g-dev", ("header", "zlib.h")),
    ("pybind11-dev", ("header", "pybind11/pybind11.h")),
    ("python3-dev", ("python_h",)),
    ("python3-numpy", ("python", "numpy")),
]
# The command-line tool, which the wheel carries too (setup.py, INTERFERE_PIP_CLI).
CLI_CHECKS = [
    ("libcli11-dev", ("header", "CLI/CLI.hpp")),
    ("libfmt-dev", ("header", "fmt/format.h")),
]
PACKAGES = [p for p, _ in CHECKS]
CLI_PACKAGES = [p for p, _ in CLI_CHECKS]


def include_dirs(env=None):
    """Where the compiler looks for headers by default, and CPATH / CPLUS_INCLUDE_PATH."""
    env = os.environ if env is None else env
    dirs = []
    for var in ("CPATH", "CPLUS_INCLUDE_PATH"):
        dirs += [d for d in env.get(var, "").split(os.pathsep) if d]
    multiarch = sysconfig.get_config_var("MULTIARCH") or ""
    dirs += ["/usr/local/include", "/usr/include"] + (["/usr/include/" + multiarch] if multiarch else [])
    return dirs


def missing(env=None, include=None, python_include=None, cli=False):
    """[(Debian package, what was not found)] for every check that fails (empty: nothing missing).
    `env` (PATH, CXX, CPATH), `include` (header directories) and `python_include` (the directory
    of Python.h) default to this process's; `cli`: also what the command-line tool needs."""
    env = os.environ if env is None else env
    include = include_dirs(env) if include is None else include
    python_include = sysconfig.get_paths()["include"] if python_include is None else python_include
    path = env.get("PATH", "")
    out = []
    for package, (kind, *what) in CHECKS + (CLI_CHECKS if cli else []):
        if kind == "cmd":
            names = []
            for w in what:
                if w == "$CXX":
                    if env.get("CXX"):
                        names.append(env["CXX"].split()[0])
                else:
                    names.append(w)
            if not any(shutil.which(n, path=path) or (os.path.isabs(n) and os.access(n, os.X_OK)) for n in names):
                out.append((package, "no %s on PATH" % " or ".join(names)))
        elif kind == "header":
            found = any(os.path.isfile(os.path.join(d, h)) for d in include for h in what)
            if not found and package == "pybind11-dev" and importlib.util.find_spec("pybind11") is not None:
                found = True  # (pybind11 from PyPI brings its headers and CMake package)
            if not found:
                out.append((package, "no %s under %s" % (" or ".join(what), ", ".join(include))))
        elif kind == "python_h":
            if not os.path.isfile(os.path.join(python_include, "Python.h")):
                out.append((package, "no Python.h in %s (the headers of %s)" % (python_include, sys.executable)))
        elif kind == "python":
            if importlib.util.find_spec(what[0]) is None:
                out.append((package, "%s cannot import %s" % (sys.executable, what[0])))
    return out


def message(found):
    """The error text for the list `missing()` returned."""
    names = " ".join(p for p, _ in found)
    return ("missing build dependencies: %s (%s). On Debian 12: apt-get install %s" %
            (names, "; ".join("%s: %s" % f for f in found), names))
