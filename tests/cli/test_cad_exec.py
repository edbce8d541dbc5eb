#!/usr/bin/env python3
"""End-to-end tests of the hand-over of CAD runs (issue #24, item 8; apps/cli/cad_exec.h): built
with OpenCASCADE, `interfere` links no OCCT and re-executes `interfere-cad` (beside it in the build
tree, in <libexecdir>/interfere once installed) for STEP inputs, `features` and `assembly-clash`,
before it has written anything. Checked: the executable's own dynamic dependencies, STEP runs from
the build tree and from the installed tree, and the error when interfere-cad is missing.

Usage: test_cad_exec.py PATH_TO_INTERFERE WORK_DIR [PATH_TO_INSTALLED_INTERFERE]   (run by ctest).
Standard library only (readelf, when present, for the dependencies).
"""
import json
import os
import shutil
import subprocess
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_common  # noqa: E402
from cli_common import load_json, path, write_text  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
CASING = os.path.join(HERE, "..", "..", "data", "examples", "casing.step")
INSTALLED = os.path.abspath(sys.argv[3]) if len(sys.argv) > 3 else None
NO_CAD = "needs interfere built with OpenCASCADE"


def run_exe(exe, *args, quiet=True):
    p = subprocess.run([exe, *(["--quiet"] if quiet else []), *args], capture_output=True, text=True, timeout=300)
    return p.returncode, p.stdout, p.stderr


def box_obj(name, lo, hi):
    """A closed, outward box [lo, hi] as an OBJ work file (12 triangles)."""
    v = [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    lines = ["v %r %r %r" % p for p in v]
    for a, b, c, d in quads:
        lines.append("f %d %d %d" % (a + 1, b + 1, c + 1))
        lines.append("f %d %d %d" % (a + 1, c + 1, d + 1))
    return write_text(name, "\n".join(lines) + "\n")


class CadExec(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        code, _, err = run_exe(cli_common.EXE, "features", CASING, "--json", path("probe.json"))
        if code == 2 and NO_CAD in err:
            raise unittest.SkipTest("built without OpenCASCADE: one executable, nothing handed over")
        assert code == 0, err

    def test_interfere_links_no_occt(self):
        readelf = shutil.which("readelf")
        if not readelf:
            self.skipTest("no readelf")
        dyn = subprocess.run([readelf, "-d", cli_common.EXE], capture_output=True, text=True, check=True).stdout
        needed = [l.split("[")[1].split("]")[0] for l in dyn.splitlines() if "(NEEDED)" in l]
        self.assertTrue(needed)
        self.assertEqual([n for n in needed if n.startswith("libTK")], [], needed)

    def step_clash(self, exe, tag):
        """A box against the casing (STEP, mm): the same report from either executable."""
        a = box_obj("box.obj", (-1000, -1000, -1000), (1000, 1000, 1000))
        code, out, err = run_exe(exe, "clash", a, CASING, "--json", path(tag + ".json"))
        self.assertIn(code, (0, 1), out + err)
        r = load_json(tag + ".json")
        self.assertEqual(r["inputs"]["b"]["format"], "step")
        return code, r

    def test_step_inputs_run_from_the_build_tree(self):
        code, r = self.step_clash(cli_common.EXE, "build")
        self.assertEqual(code, 1)  # (the casing lies inside the box: containment)
        f = load_json("probe.json")
        self.assertGreater(len(f["parts"]), 0)

    def test_installed_tree_finds_interfere_cad(self):
        if not INSTALLED:
            self.skipTest("no installed tree given")
        self.assertTrue(os.path.isfile(INSTALLED), INSTALLED)
        code_b, build = self.step_clash(cli_common.EXE, "b2")
        code_i, inst = self.step_clash(INSTALLED, "inst")
        self.assertEqual(code_b, code_i)
        for key in ("verdict", "summary", "pairs"):
            if key in build:
                self.assertEqual(build[key], inst[key], key)
        code, out, err = run_exe(INSTALLED, "features", CASING, "--json", path("inst_features.json"))
        self.assertEqual(code, 0, err)
        self.assertEqual(load_json("inst_features.json")["parts"], load_json("probe.json")["parts"])

    def test_missing_interfere_cad_is_an_input_error_before_any_output(self):
        alone = path("alone")
        os.makedirs(alone, exist_ok=True)
        exe = os.path.join(alone, "interfere")
        shutil.copy2(cli_common.EXE, exe)
        a = box_obj("m_a.obj", (0, 0, 0), (1, 1, 1))
        b = box_obj("m_b.obj", (0.5, 0, 0), (1.5, 1, 1))
        # Mesh inputs need no interfere-cad.
        code, out, err = run_exe(exe, "clash", a, b, "--json", path("mesh.json"))
        self.assertEqual(code, 1, err)
        self.assertTrue(os.path.exists(path("mesh.json")))
        for args in (("clash", a, CASING, "--json", path("m1.json")),
                     ("clash", a, b, CASING, "--json", path("m2.json")),  # (a scene)
                     ("features", CASING, "--json", path("m3.json")),
                     ("assembly-clash", CASING, "--json", path("m4.json"))):
            code, out, err = run_exe(exe, *args, quiet=False)
            self.assertEqual(code, 2, args)
            self.assertEqual(out, "", args)
            # The error is the only line: no progress line was written before it.
            self.assertEqual(err.count("\n"), 1, err)
            self.assertTrue(err.startswith("interfere: error: "), err)
            self.assertIn("interfere-cad", err)
            self.assertIn("missing", err)
            self.assertIn(os.path.join(alone, "interfere-cad"), err)
            self.assertFalse(os.path.exists(args[-1]), args)


if __name__ == "__main__":
    cli_common.main()
