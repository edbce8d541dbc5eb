#!/usr/bin/python3
"""ctest render_labels_generated (issue #29, item 2): tools/hole_truth/render_labels.py on a generated part.

The part is interfere_write_test_part's counterbored_plate (40 x 30 x 10 plate, bore r 3 through along z
at (20, 15), counterbore r 6 from the top down to z = 6: src/cad/generate.cpp), written to STEP and
tessellated by interfere_tessellate_faces (tools/hole_truth/tessellate_faces.cpp). Its label is written
here by hand from that construction, in the truth set's format (tests/data/hole_truth/README.md), beside
a wrong one (a hole of r 5 at another place). Checks:
  - with both labels: the real label matches exactly the two walls (bore and counterbore), the wrong one
    matches no face (and is reported), no concave wall is left unlabelled, and the sheet shows the
    counterbored colour;
  - with no label: the two walls are reported as unlabelled concave surfaces closing 360 degrees and
    the sheet shows the unlabelled colour, not the counterbored one.
usage: check_render_labels.py WRITE_TEST_PART TESSELLATE_FACES WORK_DIR
Exit status 0 pass, 1 fail, 77 skipped (numpy or matplotlib missing).
"""
import json, os, subprocess, sys

try:
    import numpy  # noqa: F401
    import matplotlib  # noqa: F401
    import matplotlib.image
except ImportError as e:
    print("skipped: %s" % e)
    sys.exit(77)

here = os.path.dirname(os.path.abspath(__file__))
tool = os.path.join(here, "..", "..", "tools", "hole_truth", "render_labels.py")
write_part, tessellate, work = sys.argv[1:4]
os.makedirs(work, exist_ok=True)
step = os.path.join(work, "counterbored_plate.step")
subprocess.run([write_part, "counterbored_plate", step], check=True)

real = {"type": "counterbored_hole", "axis_point": [20.0, 15.0, 0.0], "axis": [0.0, 0.0, 1.0], "extent": [0.0, 10.0],
        "ends": ["open", "open"], "max_radius": 6.0,
        "elements": [{"kind": "cylinder", "r0": 3.0, "r1": 3.0, "h0": 0.0, "h1": 6.0, "faces": 1},
                     {"kind": "cylinder", "r0": 6.0, "r1": 6.0, "h0": 6.0, "h1": 10.0, "faces": 1}]}
wrong = {"type": "through_hole", "axis_point": [8.0, 8.0, 0.0], "axis": [0.0, 0.0, 1.0], "extent": [0.0, 10.0],
         "ends": ["open", "open"], "max_radius": 5.0,
         "elements": [{"kind": "cylinder", "r0": 5.0, "r1": 5.0, "h0": 0.0, "h1": 10.0, "faces": 1}]}
failures = []


def run(name, holes):
    labels = os.path.join(work, name + ".json")
    with open(labels, "w") as f:
        json.dump({"file": "counterbored_plate.step", "solids": [{"index": 0, "holes": holes}]}, f)
    png, summary = os.path.join(work, name + ".png"), os.path.join(work, name + "_summary.json")
    r = subprocess.run([sys.executable, tool, "--step", step, "--tessellator", tessellate, png, "--holes", labels,
                        "--summary", summary, "--size", "240"], capture_output=True, text=True)
    if r.returncode != 0:
        failures.append("%s: render_labels.py exit %d: %s" % (name, r.returncode, r.stderr.strip()))
        return None, None, ""
    img = matplotlib.image.imread(png)[:, :, :3]
    return json.load(open(summary)), img, r.stdout


def has_colour(img, rgb):
    """Pixels whose hue matches rgb (shading scales the colour: compare normalised colours)."""
    import numpy as np
    c = np.array(rgb) / max(rgb)
    px = img.reshape(-1, 3)
    m = px.max(axis=1)
    ok = m > 0.15
    n = px[ok] / m[ok, None]
    return int(np.sum(np.all(np.abs(n - c) < 0.08, axis=1)))


s, img, out = run("labelled", [real, wrong])
if s:
    h = s["holes"]
    if sorted(len(x["faces_matched"]) for x in h) != [0, 2]:
        failures.append("labelled: faces matched per label %s, expected the real one 2, the wrong one 0"
                        % [x["faces_matched"] for x in h])
    if "hole 0.1 (through_hole) matched no face" not in out:
        failures.append("labelled: the wrong label was not reported: %r" % out)
    if s["unlabelled_concave"]:
        failures.append("labelled: unlabelled concave walls %s" % s["unlabelled_concave"])
    if has_colour(img, (1.00, 0.55, 0.00)) < 50:
        failures.append("labelled: no counterbored-coloured pixels in the sheet")

s, img, out = run("unlabelled", [])
if s:
    walls = sorted((g["radius"], g["degrees"]) for g in s["unlabelled_concave"])
    if [w[0] for w in walls] != [3.0, 6.0] or any(w[1] < 355 for w in walls):
        failures.append("unlabelled: concave walls %s, expected r 3 and r 6 closing 360 degrees" % walls)
    if has_colour(img, (0.95, 0.90, 0.35)) < 50 or has_colour(img, (1.00, 0.55, 0.00)) > 0:
        failures.append("unlabelled: the sheet should show the unlabelled colour and not the counterbored one")

for f in failures:
    print("FAIL: " + f)
print("render_labels_generated: %s" % ("FAIL" if failures else "pass"))
sys.exit(1 if failures else 0)
