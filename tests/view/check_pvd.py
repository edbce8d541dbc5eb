#!/usr/bin/env python3
"""ParaView time series export (issue #25, item 3), read back by ParaView.

Runs interfere_view_samples (tests/view/write_view_samples.cpp) into WORKDIR; checks each .pvd's
collection (ElementTree: every listed file exists, one bodies part per step, times as the document
gives them) and loads it with ParaView's Python (tests/view/pvd_summary.py under pvpython, or under a
python3 that imports paraview.simple), comparing what ParaView read at every time step with the
document facts in expect.json: time step values and count, per body (cell array `body`) its triangle
count, world box, clash-flagged cells, source ids and penetration depth range; per clash present at
the step its region triangles, curve and witness polylines, verdict code and clash flags; the
field data naming bodies and clashes.
Exit status 0: passed; 1: a check failed; 77: no ParaView Python (python3-paraview) found.

Usage: check_pvd.py SAMPLES_EXE WORKDIR
"""
import json
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

VERDICT_CODE = {"undecided": 0, "clash": 1, "contact": 2, "clearance": 3}


def paraview_python():
    """A command that runs a script with paraview.simple importable, or None."""
    if shutil.which("pvpython"):
        return ["pvpython"]
    for py in dict.fromkeys([sys.executable, "/usr/bin/python3"]):
        if py and os.path.exists(py) and subprocess.run([py, "-c", "import paraview.simple"], capture_output=True).returncode == 0:
            return [py]
    return None


def close(a, b, tol=1e-9):
    return abs(a - b) <= tol * max(1.0, abs(b))


def close_box(got, want):
    return all(close(g, w) for gs, ws in zip(got, want) for g, w in zip(gs, ws))


def check_series(pvd, expect, runner, problems):
    name = os.path.basename(pvd)

    def check(ok, what):
        if not ok:
            problems.append(f"{name}: {what}")
        return ok

    # The collection itself.
    root = ET.parse(pvd).getroot()
    check(root.tag == "VTKFile" and root.get("type") == "Collection", "not a VTK Collection")
    sets = root.findall("./Collection/DataSet")
    steps = len(expect["steps"])
    want_times = expect["times"] if expect["frame_count"] and expect["times"] else list(range(steps))
    for ds in sets:
        check(os.path.isfile(os.path.join(os.path.dirname(pvd), ds.get("file"))), f"listed file {ds.get('file')} missing")
    bodies_sets = [ds for ds in sets if ds.get("part") == "0"]
    check(len(bodies_sets) == steps, f"{len(bodies_sets)} bodies data sets for {steps} steps")
    check([float(ds.get("timestep")) for ds in bodies_sets] == [float(t) for t in want_times], "collection time steps")

    run = subprocess.run(runner + [os.path.join(os.path.dirname(os.path.abspath(__file__)), "pvd_summary.py"), pvd],
                         capture_output=True, text=True, timeout=300)
    lines = [l for l in run.stdout.splitlines() if l.startswith("PVD_SUMMARY ")]
    if not check(run.returncode == 0 and lines, f"ParaView could not read it: {run.stderr.strip()[-2000:]}"):
        return
    s = json.loads(lines[-1][len("PVD_SUMMARY "):])
    check(len(s["times"]) == steps or (steps == 1 and len(s["times"]) <= 1), f"ParaView sees {len(s['times'])} time steps, expected {steps}")
    if steps > 1:
        check(all(close(a, b) for a, b in zip(s["times"], want_times)), f"time values {s['times']} != {want_times}")
    for k, (got, want) in enumerate(zip(s["steps"], expect["steps"])):
        at = f"step {k}"
        bodies = got.get("bodies")
        if not check(bodies is not None, f"{at}: no bodies block"):
            continue
        check(bodies["body_ids"] == [b["id"] for b in expect["bodies"]], f"{at}: body_ids {bodies['body_ids']}")
        check(bodies["body_names"] == [b["name"] for b in expect["bodies"]], f"{at}: body_names {bodies['body_names']}")
        check(bodies["cells"] == sum(b["triangles"] for b in want["bodies"]), f"{at}: {bodies['cells']} cells")
        has_source = any(b["source_ids"] for b in want["bodies"])
        check(("source_id" in bodies["cell_arrays"]) == has_source, f"{at}: source_id array {'missing' if has_source else 'unexpected'}")
        step_depth = any(b["depth_range"] is not None for b in want["bodies"])
        # (in every step's file when any step has depths: ParaView colours a series by one array)
        doc_depth = any(b["depth_range"] is not None for st in expect["steps"] for b in st["bodies"])
        check(("penetration_depth" in bodies["point_arrays"]) == doc_depth, f"{at}: penetration_depth array")
        for bi, wb in enumerate(want["bodies"]):
            gb = bodies["per_body"].get(str(bi))
            where = f"{at}: body {expect['bodies'][bi]['id']}"
            if not check(gb is not None, f"{where}: no cells"):
                continue
            check(gb["cells"] == wb["triangles"] and gb["cell_types"] == [5], f"{where}: {gb['cells']} cells of types {gb['cell_types']}")
            check(close_box(gb["box"], wb["world_box"]), f"{where}: box {gb['box']} != {wb['world_box']}")
            check(gb["clash_flagged"] == wb["clash_flagged"], f"{where}: {gb['clash_flagged']} clash-flagged cells, expected {wb['clash_flagged']}")
            if has_source:
                want_ids = wb["source_ids"] or [-1] * wb["triangles"]
                check(gb["source_ids"] == want_ids, f"{where}: source ids {gb['source_ids'][:8]}...")
            if wb["depth_range"] is not None:
                check(gb["depth_range"] is not None and all(close(a, b) for a, b in zip(gb["depth_range"], wb["depth_range"])),
                      f"{where}: depth range {gb['depth_range']} != {wb['depth_range']}")
            elif step_depth:
                check(gb["depth_range"] is None, f"{where}: depths where the body has none")
        if not expect["clashes"]:
            continue
        clashes = got.get("clashes")
        if not check(clashes is not None, f"{at}: no clashes block"):
            continue
        check(clashes["clash_ids"] == [c["id"] for c in expect["clashes"]], f"{at}: clash_ids")
        check(clashes["verdict_names"] == ["undecided", "clash", "contact", "clearance"], f"{at}: verdict_names")
        present = {expect["clashes"][int(i)]["id"] for i in clashes["per_clash"]}
        check(present == set(want["clashes"]), f"{at}: clashes {sorted(present)}, expected {sorted(want['clashes'])}")
        for ci, cl in enumerate(expect["clashes"]):
            gc = clashes["per_clash"].get(str(ci))
            if gc is None:
                continue
            where = f"{at}: clash {cl['id']}"
            check(gc["region_triangles"] == cl["region_triangles"], f"{where}: {gc['region_triangles']} region triangles")
            check(gc["curve_points"] == [n for n in cl["curve_points"] if n >= 2], f"{where}: curves {gc['curve_points']}")
            check(gc["witness_points"] == ([2] if cl["witness"] else []), f"{where}: witness {gc['witness_points']}")
            check(gc["verdicts"] == [VERDICT_CODE[cl["verdict"]]], f"{where}: verdict codes {gc['verdicts']}")
            check(gc["clash_flagged"] == (cl["region_triangles"] if cl["verdict"] == "clash" else 0), f"{where}: clash flags")


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    samples, work = sys.argv[1:]
    shutil.rmtree(work, ignore_errors=True)
    subprocess.run([samples, work], check=True)
    expect = json.load(open(os.path.join(work, "expect.json")))
    runner = paraview_python()
    if runner is None:
        print("SKIPPED: no ParaView Python (pvpython or python3-paraview): apt-get install python3-paraview (tools/deps.sh)")
        return 77
    problems = []
    for name in ("static", "frames"):
        before = len(problems)
        check_series(os.path.join(work, name + ".pvd"), expect[name], runner, problems)
        print(f"{name}.pvd: {len(problems) - before} problems")
    for p in problems:
        print("FAIL", p)
    if problems:
        return 1
    print("ParaView series checks passed (" + " ".join(runner) + ")")
    return 0


if __name__ == "__main__":
    sys.exit(main())
