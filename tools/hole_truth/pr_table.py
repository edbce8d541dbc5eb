#!/usr/bin/env python3
"""Hole recognition precision/recall per part (issue #29, item 2) into docs/simplify.md.

Runs the HoleTruth test (tests/cad/test_hole_truth.cpp) with INTERFERE_HOLE_PR_JSON set and replaces
the section between the markers <!-- hole-truth:begin --> and <!-- hole-truth:end --> of
docs/simplify.md (appended under "## Benchmarks" when absent). tools/hole_truth/pr_before.json is the
same table measured before the recognition of issue #29 (commit before it), shown beside.

usage: pr_table.py [BUILD_DIR]   (default: build)
"""
import json, os, subprocess, sys, tempfile

root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build")
out = tempfile.mktemp(suffix=".json")
env = dict(os.environ, INTERFERE_HOLE_PR_JSON=out)
subprocess.run([os.path.join(build, "tests", "interfere_cad_tests"), "--gtest_filter=HoleTruth.*"], env=env, check=True,
               stdout=subprocess.DEVNULL)
now = json.load(open(out))
before = json.load(open(os.path.join(root, "tools", "hole_truth", "pr_before.json")))
b = {r["file"]: r for r in before["parts"]}

def pr(r):
    return "%.2f / %.2f" % (r["precision"], r["recall"])

def tpr(r):
    return "%.2f / %.2f" % (r["typed_precision"], r["typed_recall"])

lines = ["<!-- hole-truth:begin -->",
         "### Hole recognition on real parts (truth set)",
         "",
         "Truth: `tests/data/hole_truth/` (labeller `tools/hole_truth/label_holes.cpp`: analytic cylinders and cones,",
         "full-circle walls and closed ends decided by point classification against the solid, no AAG). Matching one",
         "to one: coaxial, a common radius, overlapping axial extents. \"typed\": the type must agree too. Written by",
         "`tools/hole_truth/pr_table.py` from the test `HoleTruth.PrecisionAndRecallPerPart`, which requires",
         "precision and recall >= 0.95 per part and per hole type, types included.",
         "",
         "Read with care: the truth's evidence is independent (point classification, not the AAG), but the type",
         "definitions (counterbored = a larger cylinder at an open end, countersunk = a cone narrowing inwards at an",
         "open end, entry chamfers included) are the same specification on both sides. The recognizer",
         "(`src/cad/hole_recognition.cpp`) was developed against the 13 NIST/gmsh parts (two fixes came from their",
         "mismatches: coaxial walls whose extents touch are one hole, gmsh_Kurbelwelle; a planar floor must cover half",
         "the end's disk, gmsh_Block); as1_pe_203 and the three trimesh parts were labelled afterwards, held out.",
         "\"before\" = the pattern matching of commit dc5c7f5 (concave cylinder between two planes).",
         "",
         "| part | truth holes | reported | P / R before | P / R now | typed P / R before | typed P / R now |",
         "|---|---|---|---|---|---|---|"]
for r in now["parts"]:
    o = b.get(r["file"])
    lines.append("| %s | %d | %d | %s | %s | %s | %s |" % (r["file"], r["truth"], r["reported"], pr(o) if o else "-", pr(r),
                                                        tpr(o) if o else "-", tpr(r)))
def tot(t):
    P = t["found"] / t["reported"] if t["reported"] else 1.0
    R = t["found"] / t["truth"] if t["truth"] else 1.0
    tP = t["typed"] / t["reported"] if t["reported"] else 1.0
    tR = t["typed"] / t["truth"] if t["truth"] else 1.0
    return "%.2f / %.2f" % (P, R), "%.2f / %.2f" % (tP, tR)
bt, nt = tot(before["total"]), tot(now["total"])
lines.append("| **all** | %d | %d | %s | %s | %s | %s |" % (now["total"]["truth"], now["total"]["reported"], bt[0], nt[0], bt[1], nt[1]))
lines += ["", "Per hole type (now): truth holes, found (any type), found with their type, reported features of the type:", "",
          "| type | truth | found | typed | reported |", "|---|---|---|---|---|"]
for k, v in sorted(now["types"].items()):
    lines.append("| %s | %d | %d | %d | %d |" % (k, v["truth"], v["found"], v["typed_found"], v["reported"]))
lines.append("<!-- hole-truth:end -->")
section = "\n".join(lines) + "\n"

doc = os.path.join(root, "docs", "simplify.md")
text = open(doc).read()
a, e = "<!-- hole-truth:begin -->", "<!-- hole-truth:end -->"
if a in text:
    i, j = text.index(a), text.index(e) + len(e) + 1
    text = text[:i] + section + text[j:]
else:
    k = text.index("## Benchmarks")
    k = text.index("\n", k) + 1
    text = text[:k] + "\n" + section + "\n" + text[k:]
open(doc, "w").write(text)
os.unlink(out)
print(section)
