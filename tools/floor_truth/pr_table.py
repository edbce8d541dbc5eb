#!/usr/bin/env python3
"""Floor-feature recognition (pockets, slots, blind slots, steps) precision/recall per part (issue #29,
item 2) into docs/simplify.md.

Runs the FloorTruth test (tests/cad/test_floor_truth.cpp) with INTERFERE_FLOOR_PR_JSON set and replaces
the section between the markers <!-- floor-truth:begin --> and <!-- floor-truth:end --> of
docs/simplify.md (put after the hole truth section when absent).

usage: pr_table.py [BUILD_DIR]   (default: build)
"""
import os, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "truth_common"))
from pr_common import ROOT as root, replace_section, run_truth_test, total_ratios, type_table

build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build")
now = run_truth_test(build, "INTERFERE_FLOOR_PR_JSON", "FloorTruth.*")

def counts(d):
    return ", ".join("%s %d" % (k, v) for k, v in sorted(d.items())) or "-"

lines = ["<!-- floor-truth:begin -->",
         "### Pockets, slots and steps on real parts (truth set)",
         "",
         "Truth: `tests/data/floor_truth/` (labeller `tools/floor_truth/label_floors.cpp`, no AAG: for every planar",
         "face, rays cast just above it across its outer boundary against the solid decide where material rises to a",
         "face standing on it (walled) and where the floor meets the outside (open); all walled: pocket, one straight",
         "walled run: step (mutual: its wall, as a floor, has this floor as its one wall), two facing straight runs:",
         "slot, one run turning half a turn: blind slot). A truth feature matches a recognised one (one to one, typed",
         "first) when one of its floor points and at least 80 % of its walled boundary points lie on the feature's",
         "triangles. Written by `tools/floor_truth/pr_table.py` from the test `FloorTruth.PrecisionAndRecallPerPart`",
         "(which requires the totals' typed precision and recall to stay >= 0.85). The type definitions are the same",
         "specification on both sides (the paper's library gives only the through step, Fig. 4; slot, blind slot and",
         "pocket as in docs/simplify.md's feature list); the evidence is not: rays against the solid there, AAG arcs",
         "(convexity, surface types) here. The labeller was written after the recognizer and the mutual-step rule was",
         "added to both after the first comparison (CTC-01 and FTC-10 mismatches: faces standing on a base plate).",
         "The parts and the 17 labels are the hole truth set's; the STEP files stay in `../shared/data/step` (skipped",
         "when absent). Checked by rendering (2026-11-29, `tools/hole_truth/render_labels.py --floors`: floors in the",
         "type's colour, walls lighter; 12 of the 13 parts with features looked at, not trimesh_box_sides' 98). What",
         "they show: AS1's steps are its L-brackets' inner corners, trimesh_base_interface's slots its two edge notches;",
         "gmsh_Angled's",
         "pockets are its hex nut traps; FTC-10's pocket, slots and steps, featuretype's pockets (one with an island)",
         "and blind slots are what one sees; engraved NIST letters are pockets (two letters each on CTC-01, CTC-02,",
         "FTC-06, FTC-09); CTC-01's three slots are a rectangular through window and edge notches read from an end",
         "face (which face is the floor is arbitrary: its mismatch); FTC-09's steps are the L-corners of its window",
         "and corner notches; FTC-08's octagonal pocket is the cover's underside cavity, a pocket by eye; FTC-06's two",
         "slots (small faces in its V-notches) were not made out at this size. Two",
         "labeller errors were found and fixed: gmsh_Zylkopf's two \"pockets\" were bolt-head seats open to the outside",
         "through a notch (the first ray, 1e-4 of the diagonal above the floor, was below the file's 4.4e-3 mm edge",
         "tolerance and grazed the outer wall: h is now at least 4 edge tolerances; the other two identical seats",
         "had been dropped as sharing that wall), and gmsh_Block's cooling-fin gaps were labelled one in two (a",
         "candidate sharing any face with a taken feature was dropped, so the gaps above and below one fin",
         "excluded each other; now only a shared floor drops one): 25 -> 52 features there, its precision 0.71 ->",
         "0.96 and recall 0.68 -> 0.44, all parts 0.88 / 0.92 -> 0.92 / 0.83 with the same recognizer. The other 15",
         "parts' labels are unchanged byte for byte. The recognizer had the same rule (a candidate owning any face",
         "of a taken feature was dropped); it now drops a candidate only when its floor is a face of a taken",
         "feature, a taken floor is one of its faces, or a taken feature of its type has the same walls (a",
         "rectangular window read as a slot from either end): gmsh_Block 0.96 / 0.44 -> 0.93 / 0.71, no other part",
         "changed, all parts 0.92 / 0.83 -> 0.91 / 0.90; hole results unchanged (1.00 / 1.00). Known mismatches:",
         "gmsh_Block's blind slots beside the ribs and some fin-gap slots (labelled, not recognised; not",
         "investigated); FTC-08's octagonal pocket (its walls are not",
         "perpendicular to the floor as the recognizer requires; the labeller's rays meet a standing face within",
         "its 10 % reach), whose adjacent walls, joined by corner rounds, are then reported as 4 steps (each wall",
         "reads the other through the round as a step with a floor fillet: the extra steps); trimesh_box_sides'",
         "0.05 mm-wide faces (7 extra steps); CTC-01's slot is recognised with another of its faces as the floor",
         "than the label's and fails the 80 % rule. The issue's 0.95 targets are hole targets; here P and R >= 0.95",
         "hold on 13 of 17 parts (5 of them with no feature labelled or reported). A smooth arc to a convex round",
         "(boss-sense cylinder, a torus whose tube centre lies below the floor) is an open side since the second",
         "comparison (FTC-10's steps, rounded outlines: recall 0.71 -> 1.00), which made FTC-08's walls steps",
         "(precision 1.00 -> 0.56 there; all parts 0.90 / 0.91 -> 0.88 / 0.92).",
         "",
         "| part | truth | reported | P / R | typed P / R | truth types | reported types |",
         "|---|---|---|---|---|---|---|"]
for r in now["parts"]:
    lines.append("| %s | %d | %d | %.2f / %.2f | %.2f / %.2f | %s | %s |" % (
        r["file"], r["truth"], r["reported"], r["precision"], r["recall"], r["typed_precision"], r["typed_recall"],
        counts(r["truth_types"]), counts(r["reported_types"])))
t = now["total"]
lines.append("| **all** | %d | %d | %.2f / %.2f | %.2f / %.2f | | |" % ((t["truth"], t["reported"]) + total_ratios(t)))
lines += ["", "Per type: truth features, found (any type), found with their type, reported features of the type:", ""]
lines += type_table(now["types"])
lines += ["", "![gmsh_Block's floor labels after the fixes: every cooling-fin gap a slot (red), blind slots beside the ribs "
          "(blue), walls lighter](images/floor_truth_block.png)"]
lines.append("<!-- floor-truth:end -->")
section = "\n".join(lines) + "\n"


def after_hole_truth(text):
    k = text.index("<!-- hole-truth:end -->")
    k = text.index("\n", k) + 1
    return text[:k] + "\n" + section + text[k:]


replace_section("floor-truth", section, after_hole_truth)
print(section)
