"""The type stubs and the package files next to the built module (issue #30): `_interfere.pyi`
(written by python/tools/stubgen.py after every build) declares every public name, `py.typed` marks
the package as typed, and `python -m interfere` finds the CLI or says how to get it.
"""

import os
import subprocess
import sys
import tempfile
import unittest

import interfere as itf
import interfere._interfere as ext
from stub_check import check_stub_file, missing_names, stub_path


class Stubs(unittest.TestCase):
    def test_stub_declares_every_public_name(self):
        check_stub_file(stub_path(ext), ext)

    def setUp(self):
        if not os.path.isfile(stub_path(ext)):
            self.skipTest("built with -DINTERFERE_PYTHON_STUBS=OFF")

    def test_checker_sees_a_missing_name(self):
        # The check itself: a stub without `clash` (or without a method of a class) is caught.
        with open(stub_path(ext)) as f:
            text = f.read()
        self.assertIn("clash", missing_names(text.replace("def clash(", "def clash_renamed("), ext))
        self.assertIn("TriMesh.bounds", missing_names(text.replace("def bounds(", "def bounds_renamed("), ext))

    def test_signatures_are_typed(self):
        with open(stub_path(ext)) as f:
            text = f.read()
        self.assertIn("def make_model(mesh: TriMesh", text)
        self.assertIn("class InputError(Error):", text)
        self.assertIn("class bearing:", text)
        self.assertRegex(text, r"def clash\(a: Any, b: Any, .*\) -> ClashResult:")

    def test_package_is_marked_typed(self):
        self.assertTrue(os.path.isfile(os.path.join(os.path.dirname(itf.__file__), "py.typed")))


class RunModule(unittest.TestCase):
    def run_module(self, env, *args):
        with tempfile.TemporaryDirectory() as cwd:
            return subprocess.run([sys.executable, "-m", "interfere", *args], cwd=cwd, env=env,
                                  capture_output=True, text=True, timeout=120)

    def test_without_cli_says_how_to_get_it(self):
        env = dict(os.environ, PATH="/nonexistent")
        env.pop("INTERFERE_CLI", None)
        r = self.run_module(env, "--version")
        self.assertEqual(r.returncode, 2)
        self.assertIn("interfere: error: the `interfere` executable was not found", r.stderr)
        env["INTERFERE_CLI"] = "/nonexistent/interfere"
        r = self.run_module(env, "--version")
        self.assertEqual(r.returncode, 2)
        self.assertIn("INTERFERE_CLI=/nonexistent/interfere is not an executable file", r.stderr)

    def test_runs_the_cli_with_its_exit_code(self):
        with tempfile.TemporaryDirectory() as d:
            fake = os.path.join(d, "interfere")
            with open(fake, "w") as f:
                f.write('#!/bin/sh\necho "fake $*"\nexit 3\n')
            os.chmod(fake, 0o755)
            env = dict(os.environ, PATH=d + os.pathsep + "/usr/bin:/bin")
            env.pop("INTERFERE_CLI", None)
            r = self.run_module(env, "clash", "a b.stl")
            self.assertEqual((r.returncode, r.stdout), (3, "fake clash a b.stl\n"))


if __name__ == "__main__":
    unittest.main()
