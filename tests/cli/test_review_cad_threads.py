#!/usr/bin/env python3
"""Adversarial review (issue #29) of the casing's whole-command speed-ups: 3ebe716 (both Hausdorff
directions at once, tbb::parallel_invoke), 4c1da1d (the AAG built in a task while the triangles are
collected) and 021efbb (the launcher gives interfere-cad glibc malloc settings through
GLIBC_TUNABLES unless the user set it).

Checked on data/examples/casing.step: `interfere simplify --ratio 0.1` and `interfere features --aag`
give the same output bytes (the .ply) and the same JSON but its timings on one CPU and on two
(taskset: TBB follows the affinity mask), and with GLIBC_TUNABLES unset, empty, malformed, naming
unknown tunables or a bad value (glibc ignores what it cannot parse; the launcher leaves any value
alone).

Usage: test_review_cad_threads.py PATH_TO_INTERFERE WORK_DIR   (run by ctest). Standard library only.
"""
import json
import os
import shutil
import subprocess
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
CASING = os.path.join(HERE, "..", "..", "data", "examples", "casing.step")
EXE = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else "interfere"
WORK = os.path.abspath(sys.argv[2]) if len(sys.argv) > 2 else "/tmp/review_cad_threads"
TIMING = ("seconds", "timings_s", "time", "wall", "cpu")


def strip_timings(x):
    if isinstance(x, dict):
        return {k: strip_timings(v) for k, v in x.items() if not any(t in k for t in TIMING)}
    if isinstance(x, list):
        return [strip_timings(v) for v in x]
    return x


def run(args, cpus=None, tunables=None):
    env = dict(os.environ)
    env.pop("GLIBC_TUNABLES", None)
    if tunables is not None:
        env["GLIBC_TUNABLES"] = tunables
    cmd = [EXE, "--quiet", *args]
    if cpus is not None:
        cmd = ["taskset", "-c", cpus, *cmd]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=600, env=env)
    return p.returncode, p.stderr


def cad_available():
    rc, err = run(["features", CASING, "--json", os.path.join(WORK, "probe.json")])
    return rc == 0


class ReviewCadThreads(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        os.makedirs(WORK, exist_ok=True)
        if not cad_available():
            raise unittest.SkipTest("needs interfere built with OpenCASCADE")

    def simplify(self, tag, **kw):
        ply, js = os.path.join(WORK, "s.ply"), os.path.join(WORK, "s.json")  # one name: the JSON names its files
        rc, err = run(["simplify", CASING, ply, "--ratio", "0.1", "--json", js], **kw)
        self.assertEqual(rc, 0, err)
        with open(ply, "rb") as f, open(js) as g:
            return f.read(), strip_timings(json.load(g))

    def features(self, tag, **kw):
        js = os.path.join(WORK, "f.json")
        rc, err = run(["features", CASING, "--aag", "--json", js], **kw)
        self.assertEqual(rc, 0, err)
        with open(js) as g:
            return strip_timings(json.load(g))

    @unittest.skipUnless(shutil.which("taskset") and (os.cpu_count() or 1) >= 2, "needs taskset and 2 CPUs")
    def test_one_and_two_cpus_same_outputs(self):
        ply1, js1 = self.simplify("cpu1", cpus="0")
        for k in range(2):
            ply2, js2 = self.simplify(f"cpu2_{k}", cpus="0,1")
            self.assertEqual(ply1, ply2, "simplify .ply differs between 1 and 2 CPUs")
            self.assertEqual(js1, js2, "simplify JSON differs between 1 and 2 CPUs")
        self.assertGreater(js1.get("hausdorff", 0), 0)
        self.assertLessEqual(js1["hausdorff"], js1["error_bound"])
        aag1 = self.features("cpu1", cpus="0")
        for k in range(2):
            self.assertEqual(aag1, self.features(f"cpu2_{k}", cpus="0,1"), "features --aag differs between 1 and 2 CPUs")

    def test_glibc_tunables_do_not_change_outputs(self):
        ref_ply, ref_js = self.simplify("unset")
        for k, t in enumerate(["", "===:::", "glibc.malloc.garbage=1", "glibc.malloc.mmap_threshold=abc",
                               "glibc.malloc.arena_max=1:glibc.malloc.hugetlb=0", "glibc.malloc.check=3"]):
            ply, js = self.simplify(f"tunables{k}", tunables=t)
            self.assertEqual(ref_ply, ply, f"GLIBC_TUNABLES={t!r} changed the .ply")
            self.assertEqual(ref_js, js, f"GLIBC_TUNABLES={t!r} changed the JSON")


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
