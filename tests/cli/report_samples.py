"""One JSON report of every kind the CLI writes (issue #30, item 4), from shipped inputs: used by
tests/cli/test_report_schema.py. Standard library only.

make_reports(exe, work) -> {name: path of the report} for: clash of two parts, of two FE bodies, of
a scene (--scene with bodies) and of an FE model's bodies; distance; check of a mesh and of an FE
model; sweep; cell (examples/probe); bearing (simulation and assembly); surface; simplify; and, where the build has
OpenCASCADE, features and assembly-clash (STEP). Each run must exit 0, 1 or 3."""
import json
import os
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.abspath(os.path.join(HERE, "..", ".."))
EX = os.path.join(SOURCE, "data", "examples")
FEM = os.path.join(SOURCE, "tests", "data", "fem")
NO_CAD = "needs interfere built with OpenCASCADE"


def runs(work):
    e, f, w = (lambda n: os.path.join(EX, n)), (lambda n: os.path.join(FEM, n)), (lambda n: os.path.join(work, n))
    scene = w("scene_bodies.json")
    with open(scene, "w") as out:
        json.dump({"bodies": [{"file": e("plate.stl"), "id": "plate"},
                              {"file": e("pin.obj"), "id": "pin",
                               "transform": [1, 0, 0, 30, 0, 1, 0, 30, 0, 0, 1, 5]},
                              {"file": e("pin.obj"), "id": "pin2",
                               "transform": [1, 0, 0, 300, 0, 1, 0, 30, 0, 0, 1, 5]}]}, out)
    return {
        "clash": ["clash", e("plate.stl"), e("pin.obj")],
        "clash_fem": ["clash", f("two_bodies_v41.msh"), f("two_bodies_v41.msh"), "--part-a", "steel", "--part-b", "rubber"],
        "clash_scene": ["clash", "--scene", scene],
        "clash_fem_scene": ["clash", f("two_bodies_v41.msh")],
        "distance": ["distance", e("plate.stl"), e("pin.obj")],
        "check": ["check", e("plate.stl")],
        "check_fem": ["check", f("tets_ascii.vtu")],
        "sweep": ["sweep", "--workpiece", e("plate.stl"), "--robot", e("probe_paper_machine.json"), "--path",
                  e("probe_path.csv"), "--probe-radius", "5", "--probe-length", "40"],
        "bearing": ["bearing", "--params", e("bearing.parameters"), "--frames", "2"],
        "bearing_assembly": ["bearing", "--assembly", e("bearing_axle.json"), "--frames", "1", "--out", w("ba.csv")],
        "surface": ["surface", f("tets_ascii.vtu"), w("surface.stl")],
        "simplify": ["simplify", e("plate.stl"), w("simplified.ply"), "--ratio", "0.5"],
        "cell": ["cell", os.path.join(SOURCE, "examples", "probe", "cell.json")],
        "features": ["features", e("casing.step")],
        "assembly_clash": ["assembly-clash", e("casing.step")],
    }


def make_reports(exe, work):
    reports = {}
    for name, args in runs(work).items():
        out = os.path.join(work, name + ".json")
        p = subprocess.run([exe, "--quiet", *args, "--json", out], capture_output=True, text=True, timeout=300)
        if p.returncode == 2 and NO_CAD in p.stderr:
            continue  # (features, assembly-clash: a build without OpenCASCADE)
        if p.returncode not in (0, 1, 3):
            raise AssertionError("%s: exit %d\n%s" % (" ".join(args), p.returncode, p.stderr))
        reports[name] = out
    return reports
