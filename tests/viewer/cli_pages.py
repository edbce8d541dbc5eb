#!/usr/bin/env python3
"""Pages written by the real command line, checked in headless Chromium (issue #25, item 4: "on
reports generated in the test"). Each command runs with --html (and --json/--csv where it has them);
the expectations come from the command's own report, not from the page: the number of clash rows,
the point where a clash must show red pixels (the report's clash point, minus the page's origin), the
number of frames. tests/viewer/check_page.mjs does the browser part (console errors, ready, rows,
camera flight, red pixels).

Usage: cli_pages.py PATH_TO_INTERFERE WORK_DIR   (ctest, with INTERFERE_VIEWER_NODE_MODULES and
INTERFERE_CHROMIUM in the environment). Standard library only.
"""
import csv
import json
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli"))
import report_schema  # noqa: E402  (the reports against docs/schema, issue #30)

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.join(HERE, "..", "..", "data", "examples")
EXE, WORK = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])


def run(*args, ok=(0, 1)):
    r = subprocess.run([EXE, *args, "-q"], capture_output=True, text=True)
    if r.returncode not in ok:
        sys.exit("FAIL: interfere %s exited %d: %s" % (" ".join(args), r.returncode, r.stderr))
    return r


def page_data(html):
    with open(html, encoding="utf-8") as f:
        m = re.search(r'<script id="interfere-data" type="application/json">(.*?)</script>', f.read(), re.S)
    return json.loads(m.group(1))


def check(name, html, expect):
    exp = os.path.join(WORK, name + ".expect.json")
    with open(exp, "w") as f:
        json.dump(expect, f)
    r = subprocess.run(["node", os.path.join(HERE, "check_page.mjs"), html, exp, "--screenshot",
                        os.path.join(WORK, name + ".png")], capture_output=True, text=True)
    print("%s: %s" % (name, "ok" if r.returncode == 0 else "FAILED"))
    if r.returncode != 0:
        print(r.stdout, r.stderr)
    return r.returncode == 0


def box_obj(name, lo, hi):
    v = [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    p = os.path.join(WORK, name)
    with open(p, "w") as f:
        for q in v:
            f.write("v %r %r %r\n" % q)
        for a, b, c, d in quads:
            f.write("f %d %d %d\nf %d %d %d\n" % (a + 1, b + 1, c + 1, a + 1, c + 1, d + 1))
    return p


def main():
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    ok = True
    # 1. The demo's two-part clash: one row; red where the report's clash point projects.
    html, rep = os.path.join(WORK, "demo.html"), os.path.join(WORK, "demo.json")
    run("clash", "--scene", os.path.join(EXAMPLES, "scene.json"), "--json", rep, "--html", html)
    with open(rep) as f:
        report = json.load(f)
    report_schema.validate(report, rep)
    origin = page_data(html)["origin"]
    point = report["clashes"][0]["point"]
    ok &= check("demo", html, {"rows": len(report["clashes"]), "clickRow": 0,
                               "redAt": [point[k] - origin[k] for k in range(3)]})
    # 2. A scene of three boxes: two clash (one row), one apart.
    a = box_obj("a.obj", (0, 0, 0), (10, 10, 10))
    b = box_obj("b.obj", (8, 2, 2), (18, 8, 8))
    c = box_obj("c.obj", (30, 0, 0), (40, 10, 10))
    html, rep = os.path.join(WORK, "scene.html"), os.path.join(WORK, "scene.json")
    run("clash", a, b, c, "--json", rep, "--html", html)
    with open(rep) as f:
        report = json.load(f)
    report_schema.validate(report, rep)
    origin = page_data(html)["origin"]
    point = report["clashes"][0]["point"]
    ok &= check("scene", html, {"rows": len(report["clashes"]), "bodies": 3, "clickRow": 0,
                                "redAt": [point[k] - origin[k] for k in range(3)]})
    # 3. Bearing frames: 4 pairs x 6 frames with a preload, rows = runs of interfering frames (its CSV).
    html, rows_csv = os.path.join(WORK, "bearing.html"), os.path.join(WORK, "bearing.csv")
    run("bearing", "--pairs", "4", "--frames", "6", "--gap", "-0.2", "--out", rows_csv, "--html", html)
    with open(rows_csv) as f:
        rows = list(csv.DictReader(f))
    runs = 0
    for k in range(4):
        v = [r["verdict"] for r in rows if int(r["pair"]) == k]
        runs += sum(1 for i in range(len(v)) if v[i] != "clear" and (i == 0 or v[i - 1] != v[i]))
    ok &= check("bearing", html, {"rows": runs, "frames": 6, "clickRow": 0, "play": True})
    # 4. A sweep: frames = path points.
    plate = box_obj("plate.obj", (-100, -100, -10), (100, 100, 0))
    path = os.path.join(WORK, "path.csv")
    with open(path, "w") as f:
        f.write("x,y,z,a,b\n0,0,170,0,0\n0,0,148,0,0\n0,0,170,0,0\n")
    html = os.path.join(WORK, "sweep.html")
    run("sweep", "--workpiece", plate, "--robot", os.path.join(EXAMPLES, "probe_5axis.json"), "--path", path,
        "--probe-radius", "5", "--probe-length", "40", "--html", html)
    ok &= check("sweep", html, {"rows": 1, "frames": 3, "clickRow": 0})
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
