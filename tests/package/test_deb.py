#!/usr/bin/env python3
"""The Debian package of the CLI and the C++ library (issue #30, item 3; cmake/packaging.cmake).

Builds the .deb from the existing build tree with cpack (it installs the built files; with Ninja
nothing is rebuilt), checks its control fields and contents, installs it with `dpkg -i` into a
temporary root whose dpkg database is a copy of this machine's (so dpkg checks the computed
Depends against the packages installed here, as `apt install ./interfere_*.deb` would, and touches
nothing outside the root), then runs the installed tree: `interfere --version`, a mesh clash, a
STEP clash and `features` (handed to the packaged libexec/interfere/interfere-cad), and checks that
interfere-cad reads the packaged feature data, not the configured prefix's or the source tree's;
builds tests/consumer with find_package(interfere) from the unpacked package.
Also checks that `cmake --install` (the installed_package fixture's tree) has LICENSE and NOTICE.

Usage: test_deb.py BUILD_DIR WORK_DIR [STAGE_DIR]   (ctest package_deb). Exits 77 (skipped)
without dpkg-deb, dpkg-shlibdeps or cpack. Standard library only.
"""
import json
import os
import shutil
import subprocess
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli"))
import report_schema  # noqa: E402  (the packaged CLI's reports against docs/schema, issue #30)

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.abspath(os.path.join(HERE, "..", ".."))
CASING = os.path.join(SOURCE, "data", "examples", "casing.step")
BUILD = WORK = STAGE = None
DEB = ROOT = None


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=600, **kw)


def box_obj(name, lo, hi):
    """A closed, outward box [lo, hi] as OBJ (12 triangles); returns its path."""
    v = [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    lines = ["v %r %r %r" % p for p in v]
    for a, b, c, d in quads:
        lines += ["f %d %d %d" % (a + 1, b + 1, c + 1), "f %d %d %d" % (a + 1, c + 1, d + 1)]
    p = os.path.join(WORK, name)
    with open(p, "w") as f:
        f.write("\n".join(lines) + "\n")
    return p


def control(field):
    return run(["dpkg-deb", "-f", DEB, field], check=True).stdout.strip()


def installed_version(package):
    """This machine's installed version of `package`, or None."""
    p = run(["dpkg-query", "-W", "-f=${Status}\t${Version}\n", package])
    for line in p.stdout.splitlines():
        status, _, version = line.partition("\t")
        if status.endswith(" installed"):
            return version
    return None


def setUpModule():
    global DEB, ROOT
    # No environment of the build's tests leaks into the installed tree's runs.
    os.environ.pop("INTERFERE_DATA_DIR", None)
    out = os.path.join(WORK, "cpack")
    os.makedirs(out)
    p = run(["cpack", "--config", os.path.join(BUILD, "CPackConfig.cmake"), "-G", "DEB", "-B", out])
    assert p.returncode == 0, p.stdout + p.stderr
    debs = [f for f in os.listdir(out) if f.endswith(".deb")]
    assert len(debs) == 1, (debs, p.stdout)
    DEB = os.path.join(out, debs[0])
    # dpkg -i into ROOT: its own database, a copy of this machine's installed-package list.
    ROOT = os.path.join(WORK, "root")
    admin = os.path.join(ROOT, "var", "lib", "dpkg")
    for d in ("info", "updates"):
        os.makedirs(os.path.join(admin, d))
    shutil.copyfile("/var/lib/dpkg/status", os.path.join(admin, "status"))
    p = run(["dpkg", "--root=" + ROOT, "--force-not-root", "--log=/dev/null", "-i", DEB])
    assert p.returncode == 0, "dpkg -i failed (Depends not satisfied here?):\n" + p.stdout + p.stderr


class Package(unittest.TestCase):
    def exe(self):
        return os.path.join(ROOT, "usr", "bin", "interfere")

    def test_control_fields(self):
        self.assertEqual(control("Package"), "interfere")
        with open(os.path.join(SOURCE, "CMakeLists.txt")) as f:
            version = f.read().split("project(interfere VERSION ", 1)[1].split()[0]
        self.assertEqual(control("Version"), version)
        depends = [d.strip() for d in control("Depends").split(",")]
        names = [d.split()[0] for d in depends]
        # computed by dpkg-shlibdeps from the executables (not a hand-written list)
        for lib in ("libc6", "libstdc++6", "libtbb12"):
            self.assertIn(lib, names, depends)
        self.assertFalse([n for n in names if "mpi" in n], depends)
        if os.path.exists(os.path.join(ROOT, "usr", "libexec", "interfere", "interfere-cad")):
            self.assertTrue(any(n.startswith("libocct-") for n in names), depends)
        for d in depends:  # each satisfied by this machine's packages (dpkg -i above checked it too)
            name, _, rest = d.partition(" ")
            have = installed_version(name)
            self.assertIsNotNone(have, d)
            if rest:
                op, want = rest.strip("()").split()
                self.assertEqual(run(["dpkg", "--compare-versions", have, op, want]).returncode, 0, (d, have))

    def test_contents(self):
        listing = run(["dpkg", "--root=" + ROOT, "-L", "interfere"], check=True).stdout.split()
        for f in ("/usr/bin/interfere", "/usr/share/doc/interfere/LICENSE", "/usr/share/doc/interfere/NOTICE",
                  "/usr/lib/cmake/interfere/interfereConfig.cmake", "/usr/lib/cmake/interfere/interfereTargets.cmake",
                  "/usr/lib/libinterfere.a", "/usr/include/interfere/query/clash.h",
                  "/usr/share/bash-completion/completions/interfere"):
            self.assertIn(f, listing)
            self.assertTrue(os.path.isfile(ROOT + f), f)
        # the Python module is not in it (pip install ., README), nor interfere-mpi (OpenMPI)
        self.assertEqual([f for f in listing if "python" in f or f.endswith(".py") or "mpi" in f], [])
        with open(os.path.join(ROOT, "usr", "share", "doc", "interfere", "LICENSE")) as f:
            self.assertIn("Apache License", f.read())

    def test_version(self):
        p = run([self.exe(), "--version"])
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(p.stdout.strip(), control("Version"))

    def test_mesh_clash(self):
        a = box_obj("a.obj", (0, 0, 0), (2, 2, 2))
        b = box_obj("b.obj", (1, 1, 1), (3, 3, 3))
        c = box_obj("c.obj", (5, 0, 0), (6, 1, 1))
        report = os.path.join(WORK, "mesh.json")
        p = run([self.exe(), "--quiet", "clash", a, b, "--json", report])
        self.assertEqual(p.returncode, 1, p.stdout + p.stderr)
        with open(report) as f:
            r = json.load(f)
        report_schema.validate(r, report)
        self.assertEqual(r["summary"]["clashes"], 1)
        p = run([self.exe(), "--quiet", "clash", a, c])
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)

    def cad(self):
        return os.path.exists(os.path.join(ROOT, "usr", "libexec", "interfere", "interfere-cad"))

    def test_step_clash_through_interfere_cad(self):
        if not self.cad():
            self.skipTest("built without OpenCASCADE: no interfere-cad")
        a = box_obj("big.obj", (-1000, -1000, -1000), (1000, 1000, 1000))
        report = os.path.join(WORK, "step.json")
        # (the installed interfere finds interfere-cad only in ../libexec/interfere: the packaged one)
        p = run([self.exe(), "--quiet", "clash", a, CASING, "--json", report])
        self.assertEqual(p.returncode, 1, p.stdout + p.stderr)  # the casing lies inside the box
        with open(report) as f:
            r = json.load(f)
        report_schema.validate(r, report)
        self.assertEqual(r["inputs"]["b"]["format"], "step")

    def test_features_read_the_packaged_data(self):
        if not self.cad():
            self.skipTest("built without OpenCASCADE: no interfere-cad")
        p = run([self.exe(), "--quiet", "features", CASING, "--json", os.path.join(WORK, "features.json")])
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        report_schema.validate_outputs(["--json", os.path.join(WORK, "features.json")])
        # A broken packaged feature library: the error names the packaged file, so that is the one read.
        library = os.path.join(ROOT, "usr", "share", "interfere", "features", "library.json")
        shutil.copyfile(library, library + ".good")
        try:
            with open(library, "w") as f:
                f.write("{ not json")
            p = run([self.exe(), "--quiet", "features", CASING])
            self.assertEqual(p.returncode, 2, p.stdout + p.stderr)
            self.assertIn(library, p.stderr)
        finally:
            os.replace(library + ".good", library)

    def test_find_package_from_the_package(self):
        # tests/consumer (as package_consumer builds it against `cmake --install`), against the
        # unpacked package's /usr: its CMake files locate everything relative to themselves.
        build = os.path.join(WORK, "consumer")
        gen = ["-G", "Ninja"] if shutil.which("ninja") else []
        p = run(["cmake", "-S", os.path.join(SOURCE, "tests", "consumer"), "-B", build, *gen,
                 "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_PREFIX_PATH=" + os.path.join(ROOT, "usr")])
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        with open(os.path.join(build, "CMakeCache.txt")) as f:
            self.assertIn("interfere_DIR:PATH=" + os.path.join(ROOT, "usr", "lib", "cmake", "interfere"), f.read())
        p = run(["cmake", "--build", build, "-j2"])
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        env = dict(os.environ, INTERFERE_DATA_DIR=os.path.join(ROOT, "usr", "share", "interfere"))
        p = run([os.path.join(build, "consumer")], cwd=build, env=env)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)

    def test_cmake_install_has_license_and_notice(self):
        if not STAGE:
            self.skipTest("no cmake --install tree given")
        for name in ("LICENSE", "NOTICE"):
            self.assertTrue(os.path.isfile(os.path.join(STAGE, "share", "doc", "interfere", name)), name)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    BUILD, WORK = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    STAGE = os.path.abspath(sys.argv[3]) if len(sys.argv) > 3 else None
    for tool in ("cpack", "dpkg", "dpkg-deb", "dpkg-shlibdeps"):
        if not shutil.which(tool):
            print("skipped: %s not found (Debian: dpkg-dev, cmake)" % tool)
            sys.exit(77)
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    sys.exit(0 if unittest.main(argv=sys.argv[:1], exit=False, verbosity=2).result.wasSuccessful() else 1)
