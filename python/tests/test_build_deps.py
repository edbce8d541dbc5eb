"""`pip install .` without a compiler or without the Debian build dependencies stops at once with a
message naming the missing packages (issue #30, "Bad input"; python/tools/build_deps.py, setup.py).
"""

import os
import shutil
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "python", "tools"))
import build_deps  # noqa: E402


class BuildDeps(unittest.TestCase):
    def test_this_machine_has_what_the_module_was_built_with(self):
        # (the module under test was built here, so nothing it needed can be missing)
        self.assertEqual(build_deps.missing(), [])

    def test_each_missing_package_is_named(self):
        with tempfile.TemporaryDirectory() as empty:
            found = build_deps.missing(env={"PATH": empty}, include=[empty], python_include=empty)
        names = [p for p, _ in found]
        for p in ("cmake", "g++", "libtbb-dev", "libeigen3-dev", "nlohmann-json3-dev", "zlib1g-dev", "python3-dev"):
            self.assertIn(p, names)
        text = build_deps.message(found)
        self.assertIn("apt-get install cmake g++ libtbb-dev libeigen3-dev", text)
        self.assertIn("no eigen3/Eigen/Core or Eigen/Core under " + empty, text)

    def test_cxx_counts_as_the_compiler(self):
        gxx = shutil.which("g++") or shutil.which("c++")
        if gxx is None:
            self.skipTest("no compiler here")
        with tempfile.TemporaryDirectory() as empty:
            found = dict(build_deps.missing(env={"PATH": empty, "CXX": gxx + " -O2"}))
        self.assertNotIn("g++", found)

    def test_setup_without_a_compiler_names_gxx(self):
        # setup.py's build as pip runs it, with only python3 and cmake on PATH: it stops before
        # CMake runs, naming g++ and the apt-get line.
        cmake = shutil.which("cmake")
        if cmake is None:
            self.skipTest("no cmake here")
        with tempfile.TemporaryDirectory() as bin_dir:
            os.symlink(sys.executable, os.path.join(bin_dir, "python3"))
            os.symlink(cmake, os.path.join(bin_dir, "cmake"))
            env = {"PATH": bin_dir, "HOME": bin_dir}
            p = subprocess.run([os.path.join(bin_dir, "python3"), "setup.py", "-q", "build_ext"], cwd=ROOT, env=env,
                               capture_output=True, text=True, timeout=300)
        self.assertNotEqual(p.returncode, 0)
        self.assertIn("interfere setup.py: error: missing build dependencies: g++", p.stderr)
        self.assertIn("apt-get install g++", p.stderr)


if __name__ == "__main__":
    unittest.main()
