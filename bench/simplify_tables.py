#!/usr/bin/env python3
"""Builds and runs interfere_bench_simplify and regenerates docs/simplify.md (+ docs/simplify_bench.json).

    python3 bench/simplify_tables.py              # configure build-bench/, build, run, write the doc
    python3 bench/simplify_tables.py --quick      # 1e5 meshes only (no 1e6 rows)
    python3 bench/simplify_tables.py --no-run     # rewrite the doc from docs/simplify_bench.json
    python3 bench/simplify_tables.py --filter 'Casing|Recognition'   # rerun some rows, merged into the kept results
    python3 bench/simplify_tables.py --exe build/bench/interfere_bench_simplify   # use an existing build
    python3 bench/simplify_tables.py --no-run --check   # exit 1 and a diff when the doc is not what this writes

Everything in docs/simplify.md is written here: the hand-written text (STATIC_HEAD and the paragraphs
around the tables) lives in this script, so edit it here, not only in the doc (--check says when they
differ); the hole truth-set section between its markers is tools/hole_truth/pr_table.py's, kept as it
is. A filtered rerun (--filter) replaces its rows in the tables and keeps the replaced rows of the last
full run in the JSON's "full_run", on which the targets, ratios and the phase table stay judged;
--note TABLE=TEXT (Casing, Recognition) says in the doc what the rerun was.

Issue #6 targets are judged with PASS/MISS verdicts: 1e6 -> 1e4 in <= 0.6 s with symmetric Hausdorff
<= OpenMesh's and feature faces within 1e-6 of the diagonal; the casing case in <= 15 ms; feature
recognition on a 500-face part in <= 50 ms. Real meshes of ../shared/data/mesh (INTERFERE_BENCH_DATA) add rows
when present. Standard library only.
"""
from __future__ import annotations

import argparse
import datetime as _dt
import json
import os
import platform
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BUILD = ROOT / "build-bench"
RAW = ROOT / "docs" / "simplify_bench.json"
DOC = ROOT / "docs" / "simplify.md"


def log(msg):
    print(f"[simplify_tables] {msg}", file=sys.stderr, flush=True)


def build_and_run(quick: bool, bench_filter: str | None = None, exe: str | None = None):
    if exe:
        exe = Path(exe).resolve()
    else:
        # The generator is CMake's default, as bench/run_benchmarks.py configures the same build-bench/
        # (a second generator in one build directory is an error).
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(BUILD), "-DCMAKE_BUILD_TYPE=Release",
                        "-DINTERFERE_BUILD_TESTS=OFF", "-DINTERFERE_BUILD_CLI=OFF", "-DINTERFERE_BUILD_BENCH=ON",
                        "-DINTERFERE_BUILD_PYTHON=OFF"], check=True)
        subprocess.run(["nice", "cmake", "--build", str(BUILD), "-j2", "--target", "interfere_bench_simplify"],
                       check=True)
        exe = BUILD / "bench" / "interfere_bench_simplify"
    env = dict(os.environ)
    if quick:
        env["INTERFERE_BENCH_SIMPLIFY_SIZES"] = "1e5"
    log(f"running {exe}")
    out = RAW if not bench_filter else RAW.with_suffix(".part.json")
    cmd = [str(exe), "--benchmark_format=console", f"--benchmark_out={out}", "--benchmark_out_format=json"]
    if bench_filter:
        cmd.append(f"--benchmark_filter={bench_filter}")
    subprocess.run(cmd, check=True, env=env)
    if bench_filter and RAW.exists():
        kept = json.loads(RAW.read_text())
        new = json.loads(out.read_text())
        names = {b["name"] for b in new["benchmarks"]}
        # The rows of the last full run that a filtered rerun replaces stay in "full_run": the targets,
        # ratios and phase table are judged on the full run, the rerun's tables show the new rows
        # (give --note TABLE=TEXT to say why and how they were run). A full run starts afresh.
        full = {b["name"] for b in kept.get("full_run", [])}
        kept.setdefault("full_run", []).extend(b for b in kept["benchmarks"] if b["name"] in names and b["name"] not in full)
        kept["benchmarks"] = [b for b in kept["benchmarks"] if b["name"] not in names] + new["benchmarks"]
        RAW.write_text(json.dumps(kept, indent=1))
        out.unlink()
    elif bench_filter:
        out.rename(RAW)


def rows(raw, key="benchmarks"):
    out = {}
    for b in raw.get(key, []):
        b = dict(b)
        b["name"] = re.sub(r"(/iterations:\d+)?(/process_time)?$", "", b["name"])
        if b.get("error_occurred"):
            out[b["name"]] = {"error": b.get("error_message", "error")}
            continue
        r = dict(b)
        r["ms"] = b["real_time"] if b.get("time_unit") == "ms" else b["real_time"] / 1e6
        r["cpu_ms"] = b["cpu_time"] if b.get("time_unit") == "ms" else b["cpu_time"] / 1e6
        out[b["name"]] = r
    return out


def fmt(v, spec=".3g"):
    return "—" if v is None else format(v, spec)


def rerun_cell(b):
    """The `guard rerun` column: yes/no for interfere rows, a dash for the peers."""
    return "—" if "guard_rerun" not in b else ("yes" if b["guard_rerun"] else "no")


def rows_of(r, names, line, error_line):
    """One table line per benchmark row: line(name's parts, row), or error_line(parts, error)."""
    out = []
    for name in names:
        b = r[name]
        parts = name.split("/")
        out.append(error_line(parts, b["error"]) if "error" in b else line(parts, b))
    return out


def verdict(ok):
    return "**PASS**" if ok else "**MISS**"


STATIC_HEAD = """# Simplification and CAD features (issue #6)

`interfere simplify` reduces a mesh — or a STEP part, tessellated by OpenCASCADE — to a triangle budget with
quadric-error-metric edge collapses while the faces that take part in the current assembly step keep their shape;
`interfere features` recognises machining features on the B-Rep. This page is regenerated by
`python3 bench/simplify_tables.py` (the benchmark section from its run; the rest is kept in that script).

## Pipeline and method

1. **STEP import** (`interfere::cad`, OCCT 7.6 only inside `src/cad/`): `STEPCAFControl_Reader` into an XCAF
   document gives parts, names, the product tree and instance placements; every part is tessellated with
   `BRepMesh_IncrementalMesh` (linear deflection, default 0.1 % of the part's diagonal; angular deflection,
   default 0.5 rad); every triangle keeps its B-Rep face id (index in `TopExp::MapShapes(shape, FACE)`), vertices
   are duplicated along face boundaries so faces stay separable. Faces that fail to tessellate are warnings
   naming the face; unreadable/empty files and files without solids or shells are errors. Malformed files are
   errors naming the line or entity — syntax errors and truncation (the parser's own messages, which OCCT would
   print to stdout, with their line numbers), unresolved references, reference cycles (found before OCCT's
   entity checks, which follow them until the stack overflows) — never crashes: signals inside OCCT become
   exceptions during the import (`OSD::SetSignal`, `OCC_CATCH_SIGNALS`; the host's handlers are restored).
   Instances are named by their own names, else by their products' (OCCT's made-up names — `=>[0:1:1:3]`,
   `SOLID`, `COMPOUND`, NAUO ids — are not names; an AP203 product's nameless solid is the product, see
   [scenes](scene.md#bodies-a-file-expands-to)); two unnamed instances of one product in one assembly get
   paths ending `#2`, `#3`.
   Schema check failures of single entities, common in files from CAD systems (NIST test parts), and entities
   that fail to translate are warnings (`tests/cad/test_cad_malformed.cpp`; 240 mutated files in a manual fuzz
   run: every one a clean error or a warned result).
2. **Attributed adjacency graph** (Joshi & Chang 1988, as used by He & Xu 2023 §2.1): a node per face with its
   surface type (plane, cylinder, cone, sphere, torus, B-spline/other) and parameters (outward normal; axis,
   radius, half angle; `hole` = outward normal towards the axis), area and loop counts; an arc per edge shared by
   two faces with curve type (line, circle, ellipse, other), the angle between the outward normals at the edge's
   middle and the convexity: with T the edge tangent oriented as the edge runs in face A, the edge is convex
   when (n_A × n_B) · T > 0, concave when < 0, smooth when the normals agree within 1e-3 rad. Arcs record
   whether the edge lies on an inner loop of either face. B-spline (and other free-form) faces are tested for
   being planes (PCA of 81 sampled points), cylinders (axis from the PCA of the normals, Kåsa circle fit
   across it) or cones (axis from the PCA of the centred normals, its point where the normal lines meet,
   radius linear in height: half angle, hole sense; so a countersink exported as a B-spline still makes a
   `countersunk_hole`) within 1e-4 of the face's size, since exported files often carry analytic faces as
   B-splines.
   Checked on the public STEP files of `../shared/data/step` when present (`tests/cad/test_cad_shared_data.cpp`):
   face counts and surface types against a text scan of each file (21 files, including NIST test parts), the
   CAx-IF AS1 assembly exported with its 28 cylinders as B-splines recognised exactly like its analytic (inch)
   export, and every part simplified with its bolt features locked.
3. **Feature recognition** (He & Xu §2.2): `minimal_subgraphs` splits the AAG at inner loops and then at convex
   arcs; the library (`data/features/library.json`) holds attributed patterns matched by backtracking subgraph
   isomorphism (node surface type and hole/boss sense, arc curve type and convexity, exact concave/convex arc
   counts) followed by geometric checks (coaxial axes, radius order, a plane perpendicular to an axis,
   opposite/perpendicular planes). Patterns are tried by decreasing priority and each match claims its own
   (non-shared) faces, so a counterbore's bore is not also reported as a through hole. Shipped patterns:
   `counterbored_hole`, `counterdrilled_hole`, `countersunk_hole`, `slot`, `blind_slot`, `blind_hole`, `through_step`,
   `pocket`, `ring_face` (shoulder), `through_hole`, `boss` (outer cylinder closing the full circle). **Holes** (issue #29) are not matched as patterns ("a concave
   cylinder between two planes" took pocket corner rounds and slot ends for holes and missed split floors and
   curved entries on real parts) but recognised from their walls and ends (`src/cad/hole_recognition.cpp`):
   hole-sense cylinder and cone faces on one surface (coaxial, same radius or cone, touching extents) form a
   wall when their angular ranges close the circle, across split faces and edges (fillets and corner rounds
   never do); coaxial walls joined by an arc or touching extents (a seat has no height) form a hole; an end is closed
   by a floor plane at the end's height facing into the hole (split floors summed, at least half the end's
   disk), a drill-point apex, a coaxial sphere or a floor fillet, and open on any other face (planar, inclined,
   curved, another hole); from an open end: counterdrilled (a larger cylinder, then a cone narrowing to the
   bore: a drill point's seat; roles `counterdrill`, `cone`, `bore`; the `screw` rule takes it like a
   counterbore), counterbored (a larger cylinder first), countersunk (a cone
   narrowing inwards, entry chamfers included), stepped, blind, through. Roles: `wall`/`counterbore`/
   `countersink`/`bore`/`seat`, `top` (the entry faces), `bottom` (the exit faces or the floor).
   **Pockets, slots, blind slots and steps** (issue #29; `src/cad/pocket_recognition.cpp`) are recognised in
   code too, since patterns of fixed size cannot state "walls all round" or "any number of fillets". The
   paper's library shows only the through step (§2.2, Fig. 4: two planes meeting at one concave arc); the
   others follow the same AAG reading (Joshi & Chang 1988; ISO 10303-224's closed pocket, slot and step): a
   planar **floor** whose outer-loop arcs are concave to **walls** standing on it (planes perpendicular to it,
   cylinders about its normal: corner rounds, a slot's round end), smooth to **floor fillets** (concave
   cylinders parallel to the floor one radius above it, tori about its normal whose tube centre lies one minor
   radius above it, concave spheres: corner blends; fillets meeting at a mitred corner count too), which lead
   smoothly or at a concave arc to walls, or convex (an **open side**, where the floor meets the outside; a
   smooth arc to a convex round too: a boss-sense cylinder or sphere, a torus below the floor); any other arc (an inclined wall, a tangent continuation) means no
   floor. Inner loops (islands, holes through the floor) take no part. Types, from the walls joined by their
   arcs: `pocket` (no open side, at least three walls in a ring), `blind_slot` (open; two facing planar
   sides joined by an end: one plane perpendicular to them and/or rounds: a slot closed at one end), `slot`
   (open; two facing planar walls, nothing else: a through slot), `through_step` (open; one planar wall whose
   only wall, taken as a floor, is this floor: the paper's two planes at one concave arc, so a face standing
   on a base plate among others is no step). A floor belongs to one feature and is no other feature's face:
   pockets first, then blind slots, slots, steps (a slot's wall is also "a floor with one wall"), larger floors
   first (a step's floor and wall, a blind slot's floor and end, read either way); features may share walls
   and fillets (the gaps above and below one cooling fin), but not all their walls when of one type (a
   rectangular window read as a slot from either end is one slot). Roles: `floor`, `wall` (pocket, step) or `wall1`,
   `wall2` (the sides) and `end` (blind slot), `fillet` (the floor fillets). Fillets and corner rounds are never
   a feature of their own: not floors, walls, holes (hole walls close the circle) or bosses (the boss pattern
   checks `full_circle`). Tested on generated parts with OCCT rolling-ball fillets
   (`tests/cad/test_floor_cases.cpp`: `slot_features_block`: a through slot with floor fillets, a blind slot
   with a round end, one with a square end and corner rounds, the block's outer corners rounded;
   `filleted_pocket_block`: a pocket with corner rounds and floor fillets and corner blends, rounded top
   edges; `filleted_step_block`: a step with a floor fillet and a rounded top edge, a plain step; and the
   earlier slot, step and pocket blocks): each feature's faces are exactly the faces inside its cutting tool's
   region (found by their triangles), no other feature is reported. On real parts: the floor-feature truth
   set below (independent labeller). The library's
   hole patterns only name the roles. Precision and recall on real parts: the truth-set table below.
   **MAAG matching** (§2.2, issue #29): `maag_decomposition(aag, library, GraphMatch)` runs the paper's
   two stages as matching (split at inner loops into SG1, match each subgraph as it is, split the unmatched at
   convex arcs into SG2, match again) against each pattern's own graph (its non-shared roles, attributes only,
   no geometric checks), with exact attributed isomorphism (`GraphMatch::exact`) or the paper's steps 1-5
   (`GraphMatch::paper`: equal counts, and every node of either graph has a partner with equal attributes and
   first-order arcs). The paper's test accepts non-isomorphic graphs (unit test: the prism graph passes as
   K3,3); on nine NIST/gmsh parts (524 subgraphs, 421 matched) the two never differ, because real minimal
   AAGs have one to three nodes. Graph matching alone is not recognition (an isolated plane matches the ring
   face's one-node graph, a hole wall the through hole's): `recognize_features` keeps whole-graph matching with
   geometric checks, and holes as above.
   **Mates from geometry** (issue #29 item 4): `infer_mates(model, library)` (`cad/mates.h`) finds
   insertions (a boss-sense cylinder of one instance coaxial with a recognised hole of another, of one of its
   radii, overlapping along the axis: a bolt or rod in a hole, a nut on a bolt; the hole's type gives the
   constraint: through/stepped → `bolt`, blind → `pin`, counterbored → `screw`, countersunk →
   `countersunk_screw`) and planar contacts (planes back to back whose faces' regions overlap with a positive area: their
   triangles, exact 2D orientation tests; overlapping boxes are not enough, test Mates.PlanarContactNeedsOverlappingRegions). On AS1 (both
   exports, the same answer): 22 insertions (bolt in bracket, plate and nut 6 each; rod in bracket and nut 2
   each) and 16 planar contacts. **Without a process file** (`PipelineOptions::mates`, `interfere simplify
   --mates auto`, the default for a STEP input without `--process`) the mates pick the assembly features
   (`select_mate_features`): each insertion's hole by the rule of its constraint applied to that hole alone
   (a bolt in a through hole: its wall and the clamped TopFace/BottomFace annuli; a rule that keeps nothing of
   it, or skips it for want of a clamped face, leaves the hole's own faces), the inserted cylinder (a bolt's
   shank, a rod), and of a planar contact the side whose contact faces are smaller (a nut's or a head's seat,
   a bracket's foot; both when equal: the larger face around a hole is covered by the hole's annulus, not kept
   whole). A part's selection is the union over its instances' mates; instances in no mate are simplified
   without features (`<part> [mates]` beside `<part>` where only some take part). Report: `cad.features_from`
   (`mates`, `process`, `none`) and `cad.mates` [{`kind`, `a_path`, `b_path`, `feature_type`, `constraint`,
   `faces_a`, `faces_b`}]; a part alone or parts apart have no mates and keep nothing; a process overrides
   the mates. Tested on a generated bolted joint (plate, cover, two bolts and nuts: the 11 mates of its
   construction, the kept faces found by their own geometry, kept triangle for triangle when locked) and on
   AS1 (every instance in a mate, every part with its holes' walls or shank kept).
   **Zero-clearance fits** (issue #29 item 4): `assembly_clash` also classifies from the B-Rep pairs whose
   tessellations neither cross nor touch, or come only within the clearance: coincident faces back to back
   (`coincide`, as for nominal fits) whose triangles come within 1e-7 of the parts' diagonals make a contact
   (`zero_clearance_fit`). One classification for both commands: the scene engine's hook
   `SceneClashOptions::zero_clearance_fits`, given by `cad::zero_clearance_fit_check` (assembly_scene.h) to
   `assembly-clash` and, for STEP assemblies in a scene, to `interfere clash --scene` (contacts of kind
   `zero_clearance_fit`; before, the scene path showed such pairs apart or as clearances). AS1's AP203 export places a bracket 1.3e-12 mm above the plate, 31 contacts
   before, 32 now: every fit of AS1 is a contact in both exports at linear deflections 0 (default) and 1 mm,
   with or without a clearance, and the bolted joint's 9 meeting pairs at four tessellations, its cover
   lifted 1e-6 mm or not (lifted 0.01 mm it is a gap).
4. **Assembly semantics** (He & Xu §3): rules (`data/features/semantics.json`) map a constraint type to the
   feature types and roles whose faces take part, and the faces the paper's rules add (§3: "If feature Is Type
   (Circular Through Hole), Then feature.Add(TopFace and BottomFace)"; `"add": ["TopFace", "BottomFace"]`):
   `bolt` → through hole (wall) + TopFace and BottomFace; `gear_shaft` → ring (shoulder) face + the shaft
   cylinder it meets; `screw` → counterbored or countersunk hole (bore, counterbore or countersink, seat) +
   BottomFace (§4's FeatureE = {CounterboredHole, BottomFace}); plus `countersunk_screw`, `key`, `pin`,
   `locate`. TopFace is the hole's `top` role, BottomFace its `bottom` role, else the AAG neighbours of its
   innermost bore that are not its own faces (where the bore leaves the part). **Clamped annulus** (issue #29):
   the added faces are kept only within `clamp_radius_factor` (default 2, ISO 7089 washers are about 2 d across)
   times the hole's radius of its axis (TopFace: the largest radius, the counterbore's; BottomFace: the bore's),
   not whole: a triangle of such a face is a feature triangle when its three corners lie within that distance of
   the axis line (`annulus_triangles`, `SimplifyOptions::feature_triangles`; `0` keeps whole faces; reports:
   `assembly_feature_annuli` [{`face`, `radius`, `axis`}], and in `cad.parts[]` of `simplify` also
   `assembly_feature_annulus_triangles`). BRepMesh puts no vertex inside a planar face, so on planar faces the
   triangles fan the hole's rim out to the face's far border and few lie inside (the rim is kept by the hole's
   wall, whose triangles share its vertices; the AS1 plate's feature triangles fall from 868 of 876, its whole
   top and bottom faces, to its hole walls' 420): the annulus takes triangles on curved and finely meshed faces. A hole whose planar
   TopFace or BottomFace has less than half the annulus' area, π((k r)² − r²)/2, holds no washer or head and is
   skipped by the rule with a warning naming it (the casing's Ø176 main bore, a through hole of the flange
   ring: 28,000 mm² against 36,500; a nut's face is about 0.6 of it and stays). **The paper's casing**
   (§4, issue #29 item 4; `TestPart::paper_casing`): the working ring carries 6 radial counterbored screw
   holes (bore r 3 out of the inner ring face, counterbore r 6), each end flange 6 plain bolt holes r 5.
   P1 (`screw`) keeps the counterbored holes and, as BottomFace, the casing's inner ring face (the paper's
   node 344) as an annulus of radius 6 around each hole; P2 (`bolt`) keeps the 12 flange holes with the
   annuli of the flanges' top and bottom faces (24), none of the ring's holes, and skips the main bore
   (`FeatureCases.PaperCasingStepsKeepThePapersFeatures`, faces found by their own geometry). The bundled
   example `data/examples/casing.step` is this part (product `casing`, written by `tools/write_test_part`;
   35,556 triangles at linear deflection 0.01696, the paper's 35,548; 35,552 at 0.0205 until its working-ring
   wall was meshed as angular sectors, "Whole command on the casing"; issue #29). The simplification
   benchmark's casing (`TestPart::casing`, `bench/bench_simplify.cpp`) keeps the older geometry
   (counterbored holes on the lower flange, whose BottomFace is the flange's underside) so that its tables
   stay comparable; the benchmark is not moved to the paper's geometry. A process description lists the steps
   (`{"steps": [{"id": "P1", "parts": ["casing"], "constraint": "screw"}, ...]}`, `"*"` = every part; ids unique,
   not empty, not `all`, and for `--step all` distinct as file names; no `parts`: every part, an empty list is an
   error); the faces of
   step P_i are selected automatically. A step names parts or component instances: a part used several times
   of which the step names only some instances is simplified twice, `<part> [<step>]` with the step's
   features for those instances and `<part>` without for the others (a step that mounts one of six
   identical bolts keeps that bolt's features only; report `cad.instances[].in_step`, `simplified_part`). A
   name the model does not have is a warning listing the parts there are. A rule that names a feature type
   missing from the library is an error naming the rule and the type, and so is a role none of the type's
   patterns has (naming the roles there are); a step whose constraint no rule knows
   (a misspelt `gear_on_shaft` for `gear_shaft`) is an error naming the step, the constraint and the
   constraints the rules know, reported before the STEP file is read (`load_semantics`), never an empty
   selection that would leave the step's features unprotected. `--library`/`--rules` (both commands, and
   `library=`/`rules=` in Python) read the user's JSON instead of the installed files.
5. **Feature-preserving QEM** (Garland & Heckbert 1997): area-weighted plane quadrics, penalty planes through
   constrained edges (weight 10·|e|²), a min-heap of candidate collapses (a radix heap, with a binary heap for the keys below the last
   one taken, so the order is the exact cost order; equal costs first in, first out, which spreads the collapses
   of a flat region instead of piling them on one vertex: unit test `Simplify.FlatRegionsDoNotPileCollapsesOnOneVertex`)
   invalidated lazily by per-vertex stamps,
   optimal placement by the 3×3 system (cofactor inverse, relative determinant test) with fallback to the
   endpoints and the midpoint; the link condition keeps the mesh manifold; a collapse is refused when a moved
   triangle's normal turns by more than acos(0.2) or degenerates. **Large meshes** (≥ 20,000 input triangles,
   `batched_min_triangles`; `batched_passes = false` turns it off): the heap is preceded by batched passes, the
   scheme of meshoptimizer's simplifier (Kapoulkine, `meshopt_simplify`: sorted collapses, an error limit of 1.5×
   the cost at half the pass's goal, each vertex in at most one collapse per pass) and of independent-set
   decimation (Franc & Skala 2001; Papageorgiou & Platis 2015): each pass sorts the candidates (one per edge) by
   the heap's key with a stable parallel radix sort and walks them from the cheapest, selecting a candidate when
   neither end was used by an earlier selection of the pass (the sort key drops the 10 lowest mantissa bits of
   the cost: two 11-bit radix passes; ties keep their order); the selected collapses are sorted by vertex, checked
   (link condition, flips, against the current mesh, on one snapshot of both fans) and applied in up to 16
   contiguous ranges of about 1,024 collapses in parallel (an even number of equal ranges, so that two threads
   share them evenly: the casing's apply phase 3.7 → 3.2 ms) — a collapse whose triangles hold an end of another range's collapse is deferred to a serial
   sweep afterwards, so the ranges touch disjoint triangles and the result does not depend on the thread count;
   where more than 2 % of the edges join vertices far apart in number (CAD tessellations number each B-Rep face on
   its own), the ranges are cut along a Morton curve of the kept ends instead, vertex order within each (casing:
   deferred collapses of the first pass 2,488 → 339) — and the candidates of the changed vertices are dropped and
   their edges evaluated again (in parallel); the others keep their cost. On meshes of 2^18 triangles and more,
   once half the triangles are dead the live vertices and triangles are renumbered densely, in order, between
   passes (`compact_min_triangles`; the late passes otherwise miss the caches: a collapse of pass 10 on the 10^6
   sphere cost 4.5× one of pass 1; the result is bit-identical, unit test
   `Simplify.CompactionBetweenPassesChangesNothing`). Below about budget + max(budget / 2, 1024) triangles the
   heap finishes with the exact budget. The setup is parallel with oneTBB (weld: the mesh module's
   hash-partitioned `weld_exact`; per-vertex quadrics summed in fan order; seam detection; initial candidates
   written straight into the list at fixed vertex-block offsets) and every result is bit-identical for 1 and N
   threads (unit tests `Simplify.OneAndManyThreadsGiveBitIdenticalResults`,
   `Simplify.ScrambledVertexNumbersGiveThreadIndependentResults`). Large arrays are never zero-filled when the
   next step writes them anyway and are first touched by the parallel loops that fill them: on this project's
   VMs a fresh 4 KiB page costs about 2 µs to fault in, which made page faults a sixth of a 10^6-triangle run. **No self-intersections**: by default the result
   is checked for intersecting non-adjacent triangle pairs with the engine's BVH traversed against itself and
   the exact triangle test of `np/tri_tri.h` (the decision of the engine's clash query; pairs sharing a vertex
   position are skipped before the exact test, which made `clash(m, m)` slow here; unit test
   `Hausdorff.SelfIntersectionCountMatchesBruteForceAndTheEngineClash`); a pair of triangles both left exactly
   as in the input (same corner positions) is not tested, its intersection being the input's own (unit test
   `Simplify.StrictGuardKeepsTheInputsIntersectionsButAddsNone`: two interpenetrating spheres). Where the input
   has such contacts, no collapse next to them can leave their triangles unchanged: by default
   (`inherit_input_contacts`) a pair whose intersection lies inside the input's **contact zone** (each of the
   input's own pairs' boxes grown by its diagonal; the intersection is the segment of the exact test, padded by
   10^-12 of the triangles' size, or the two boxes' overlap for a touch) is the input's contact moved, inherited
   and allowed (`inherited_pairs` counts them); every other new pair is refused as before, so the guarantee is: no
   intersection outside the neighbourhood of the input's own. The zone is made only where the plain result has
   new pairs (from the input's triangles near where each meets: the box of its segment grown by its own
   diagonal; about 5 ms at 10^6 triangles instead of the input's whole self-clash, 145 ms; the casing's 307
   folds of `--feature-mode last`: 1,737 of its 35,516 triangles, 0.5 ms), grown when a rerun finds a pair
   outside it; unit
   tests `Simplify.InheritedIntersectionsStayNearTheInputsCrossingCurve` (every inherited crossing within 0.3 of
   the two spheres' exact crossing circle), `Simplify.TheInputsOwnContactsAreInheritedAndNoOtherIntersectionIsAdded`,
   `ContactZone.*`; CGAL oracle `SimplifyOracle.*`: every intersecting pair of the results, found by brute force
   with Epeck's exact test, is the engine's, and is either left as in the input or meets, by CGAL's exact
   intersection, inside the input's own pairs' zone). `--strict-intersection-guard` (`inherit_input_contacts = false`) refuses every pair of
   triangles not both as in the input. Only if plain QEM created
   an intersection is the run repeated with a guard that refuses collapses whose moved triangles would meet a
   non-adjacent triangle (exact test of `np/tri_tri.h` against a hash grid, scanned once per collapse over the
   cells of all its moved triangles, cells shedding dead and repeated entries as they are scanned, rebuilt
   whenever the live triangle count halves or re-inserted entries pile up): first in the heap phase only (the
   rerun repeats the plain run's batched passes, which make the same collapses — inputs of 2^18 triangles and
   more instead start from the copy of its state the plain run kept where the passes handed over to the heap:
   about 15 ms to copy at 10^6 → 10 %, 2 ms at 1 %, where repeating the passes took 300 ms; unit test
   `Simplify.IntersectionsOfThePlainRunAreRepairedByGuardedReruns` checks both give the same result — checks
   the mesh they leave, and if it has no new intersection guards the heap's collapses, where the coarsest,
   last collapses are: first only those near the new pairs, then, should pairs remain, every one; else it
   stops there), then only near the intersecting
   pairs found (each pair's box grown by its diagonal; the grid
   then holds only that neighbourhood's triangles, guarded collapses are applied in the serial sweep of the
   batched passes, and one reaching beyond the neighbourhood is refused), up to 3 such reruns with the region
   growing, then, as a last resort, on every collapse (about 10× slower); so the result never has a
   self-intersection the input did not have (`guard_rerun`, `guard_reruns` say which run was used; unit test
   `Simplify.IntersectionsOfThePlainRunAreRepairedByGuardedReruns`). The input is welded by exact position;
   seams (edges between different face ids), open boundaries and non-manifold edges are constrained: a vertex on
   two of them (a seam vertex) is only removed along one of them onto the other end, which stays put, so seams
   stay shared and are simplified as polylines through original vertices; a vertex on one or three or more
   (a corner) is never removed. **No face whose seams are kept vanishes**: a collapse that would remove the
   last triangle of such a face (every face with `--seams all`, the feature faces with `features`) is refused
   (`rejected.last_face_triangle`), so a small face (the half cones at the tip of a drilled hole, a narrow
   fillet) may shrink to one triangle but its id and seams stay in the output (before 2026-11-26, 148 of the
   664 faces of `nist_ctc_02` vanished at 10 %, 13 of 33 of `eight_cyl` at 3 %; an inner edge of a face never
   removes its last triangle, so only seam collapses are checked: in the heap exactly, in the batched passes by
   sending those next to a face of fewer than 32 triangles at the pass's start to the serial sweep, the same
   for any thread count; unit test `Simplify.NoFaceWhoseSeamsAreKeptVanishes`). A CAD part of many small
   faces (fillets, chamfers, the NIST test parts) has so many corners that a low budget cannot be met with
   every seam kept (`gmsh_Block.stp` of `../shared/data`,
   533 faces: 12,070 → 2,726 triangles at most for a budget of 1,207, Hausdorff 12 % of the diagonal as the
   last seam collapses cut across curved borders); `--seams features` (`SimplifyOptions::seams`) keeps only the
   borders of assembly-feature faces and lets the others' seams go (1,206 triangles, Hausdorff 1.9 %;
   `nist_ftc_08`: 7,102 → 710 instead of 1,102 at most), `--seams auto` keeps every seam when the budget can be
   met so and else makes the run again with `features` (`seams_relaxed_at`: the fewest triangles every seam
   allowed; a warning says so; the error is measured once; the default since issue #29, item 7, so a requested
   ratio is met on such parts: `nist_ctc_01` at 10 %, 2,828 → 282 for a budget of 283 instead of 614, the
   generated test assembly 800 → 80 instead of 112; `--seams all` keeps the old behaviour and its warning
   names what holds the rest), `--seams none` keeps none; each output triangle
   still carries its input triangle's face id. The warning of a budget held by corners says so (unit test
   `Simplify.SeamsOfNonFeatureFacesCanGoWhereTheirCornersHoldTheBudget`). **Assembly features** follow the paper's rule: the cost of every edge touching a
   feature face is raised by the maximum unmodified (initial) edge cost, so those edges go last
   (`FeatureMode::weight`, default). Since costs grow as quadrics accumulate, late non-feature collapses can
   cost more than that offset, and then feature edges go before them; `--feature-mode last` orders every feature
   edge strictly after all other candidates (an infinite offset: the top bit of the heap key), and `--lock`
   freezes every vertex of a feature face, which keeps the feature triangles bit-identical. Plain meshes use a per-triangle region file (`--regions`) or a dihedral-angle
   mask (`--sharp-angle DEG`: regions split at edges sharper than DEG, their borders kept like seams).
6. **Error bound**: the symmetric Hausdorff distance between input and output, sampled at every vertex used by a triangle, edge
   midpoint (once per edge two triangles share) and centroid and measured with the engine's BVH and closest-point queries, overall and on the feature
   faces (`hausdorff`, `hausdorff_features`: measurements, lower bounds of the true distances). Only the largest
   sample matters, so a sample's search stops at the first triangle within a distance the maximum is known to
   reach (every 64th vertex measured first, then the vertices' maximum for the midpoints and centroids; Taha &
   Hanbury, IEEE TPAMI 2015): the maximum is exact, bit for bit (unit test
   `Hausdorff.EarlyStoppedSearchesKeepTheMaximumExact`: the maximum at a vertex, an edge midpoint, a centroid;
   brute force), and with a box test per leaf triangle the input-to-result pass at 10^6 → 1 % takes 0.48 s
   instead of 0.72. `error_bound` is an
   upper bound of the distance from every point of the input's surface to the output (`OneSidedDistance::bound`
   in `simplify/hausdorff.h`), at least `hausdorff`: per input triangle the smaller of a Lipschitz bound (largest
   corner or edge-midpoint distance + longest edge / (2√3): the distance is 1-Lipschitz and every point of the
   four midpoint halves lies within that of a sample) and a convexity bound (the distance to one output triangle
   is convex, so on an input triangle, or a convex piece of it, it is largest at a corner; the input triangle is
   cut into the piece over the best output triangle and the pieces beyond its edges, or along the plane between
   two output triangles, each piece bounded with its own output triangle: 0 for triangles the output kept), refined by subdivision where it exceeds 1.25× the sampled distance; plus 10⁻⁹ of
   the extent for rounding (unit tests `Hausdorff.BoundCoversThePointsBetweenTheSamples`,
   `Simplify.ErrorBoundBoundsTheDistanceOfEveryInputPointToTheResult`: random surface points, brute force). It
   is written into PLY/OBJ outputs (`comment error_bound` / `# error_bound`) and `interfere clash --conservative
   A' B'` reads it back: two touching original parts have points of their simplified versions within the sum of
   the bounds, so the clearance is widened by it and any pair within it is a possible clash (exit status 1);
   a 0 exit means the originals do not clash. On the bumpy sphere the bound is 1.25× the sampled distance at
   10^6 → 1 %, 1.6× at 10^6 → 10 % (input triangles large against an error of 3·10⁻⁴), 1.2× on the test
   assembly's shaft (a fan of long triangles across its end face), 1.2–1.3× on every mesh of
   `../shared/data/mesh` at 5 %; computing it adds about 0.06 s to the measurement at 10^6 → 1 % and 0.7 s at
   10^6 → 10 % (`interfere_error` rows below).

**Sliver meshes** (issue #23, item 12). A prism over a regular n-gon whose caps are fans from one centre vertex
(every spoke a sliver 10 long and 10/n wide) made the error measurement's cost grow with the slivers' aspect
ratio, not with the mesh: the result's cap is fanned differently (from a rim vertex), so every input spoke
crosses hundreds of output triangles. The convexity bound with one output triangle failed there, the
refinement (more candidates, subdivision) ran its whole budget on every spoke and ended at the Lipschitz term
(0.72 on a 10-radius cap: 7,000× the sampled distance), and every search near a fan visited a third of its
triangles, whose boxes all contain the point. Now, each valid as an upper bound and exact where it was:
- **Convex planar regions** of the result (`src/simplify/planar_regions.cpp`): edge-connected, consistently
  oriented triangles in one plane (grown within 10⁻⁶ of the extent, the deviation then measured) whose union is
  one convex polygon, decided by exact predicates on the coordinates that drop the normal's largest axis: all
  triangles turn alike, the boundary of their sum is one cycle, it never turns back and goes round once (then
  the degree argument: the union is that polygon). Small dents of the border (up to 10⁻⁴ of the extent, summed)
  are filled and added to the region's slack. The distance to a convex set is convex, so a triangle (or piece)
  whose corners' nearest triangles lie in one region is bounded by its largest corner distance plus the slack
  (twice the deviation plus the dents, lifted back to the plane): a spoke across 400 output triangles in one
  test. Planar faces that are not convex (an L, a hole) are no region.
- **Refinement worst first** (`hausdorff.cpp`): the triangles above 1.25× the sampled distance are refined in
  order of their local bound, in fixed batches of 256 (thread-independent), until the next one's local bound is
  within what the refined ones reached or the floor (nothing left can change the maximum), or after
  2,048 + n/16 triangles: the bound is then the larger of the refined maximum and that next local bound, which
  bounds every triangle not refined (looser, never lower). The refinement's searches stop at half the floor.
- **Searches over pieces of slivers** (`src/simplify/piece_bvh.cpp`): the nearest-triangle search
  (`nearest_triangle_d2`, one search for `surface_distance` and this measure) runs on a BVH over strips cut
  across each sliver's length (up to 16, as many pieces in all as there are samples, boxes padded over the
  cut points' rounding), measuring whole triangles through an owner map: the same distances, bit for bit, with
  boxes about as wide as long.
- Clipped polygons of the convexity bound that would exceed their 10 vertices are no longer used (they lost a
  vertex, and with it points of the triangle).

Unit tests (`HausdorffSlivers.*`): fan-capped prisms (512 and 1,024 segments) against a dense oracle of its
own (a grid over every input triangle, distances by projection and edge segments, brute force, covering radius
accounted): the bound covers every point and stays within twice the truth (before: 0.073 on the thin one, far
above); an
L-shaped and a holed face are no region and a sliver over the notch is still covered; a fan with a reflex vertex
or winding twice is none; a dent's depth goes into the slack and covers a point the samples miss; the piece
tree covers every triangle and searches exactly. `interfere simplify IN OUT --ratio 0.1` on this VM
(2026-11-28, 2 threads, wall time, median of 3; STL files of float coordinates, radius 10; before = the
measurement code of commit 583eaf1 linked into the same CLI; after → now: commit 60b18a3 against commits
bd4c6f0 and 74a2db3 (twin lookup, parallel piece tree: below), run alternately in the same minute, later that day under a load of
about 3 on the 2 cores, so both slower than an idle machine):

| mesh | triangles | before | after → now | `--no-error` | error_bound before → after (= now) | hausdorff |
|---|---:|---:|---:|---:|---:|---:|
| fan-capped cylinder, 8,192 segments, height 20 | 32,768 | 8.87 s | 0.55 → 0.44 s | 0.20 s | 0.722 → 0.0102 | 9.7·10⁻⁵ |
| prism over a 10,000-gon, height 1 | 40,000 | 15.6 s | 0.70 → 0.51 s | 0.28 s | 0.722 → 0.00285 | 6.5·10⁻⁵ |
| prism over a 20,000-gon, height 1 | 80,000 | 30.8 s | 1.68 → 1.01 s | 0.45 s | 0.722 → 0.00131 | 1.8·10⁻⁵ |
| flat 10,000-gon, one fan | 10,000 | 4.4 s | 0.33 → 0.30 s | 0.19 s | 0.722 → 0.000142 | 1.4·10⁻⁴ |

(The issue measured 21.5 s, 43 s and over 120 s on its machine and meshes.) Two costs were not the searches:
an edge midpoint shared with a twin triangle looked the twin up in the fan of the edge's lower vertex, O(n²)
on a fan hub numbered before its rim (as STL welding numbers it: 0.3 s of the 20,000-gon's measurement); it now
looks in the smaller fan of the two ends (both in triangle order: the same twin, the same bits). And the piece
tree is filled and boxed in parallel at prefix-sum offsets (0.16 → 0.10 s). The 20,000-gon's measurement now
takes about 0.6 s in process against its simplification's 0.2–0.27 s: 0.4 s for input to result (360,000
searches of about 25 closest points each: the boxes of the result's fan strips near a point) and 0.23 s for
result to input (24,000 searches of 300–700 closest points on the plain tree: cutting the input's 40,000 cap
spokes into strips needs over a million pieces, whose tree costs more than it saves, measured). The rows
`Slivers/*` of the benchmark below time the same shapes in process.

**Local frame.** QEM costs grow as the fourth power of the size and are ranked as floats, which overflow above
sizes of about 10^10 and underflow below 10^-9 (every cost inf or 0: collapses in arbitrary order, 15× the
error), and quadrics lose their precision to cancellation far from the origin (a part 10^6 of its sizes away:
twice the error; 10^8: garbage). So a mesh whose centre lies beyond 256 sizes from the origin or whose size is
outside [2^-20, 2^20] is simplified in a local frame p' = (p − c)·2^k, c the centre rounded to a multiple of a
power of two near the size, used only where both steps are exact for every coordinate (checked; else the mesh
is simplified as it is): the result is that of the same mesh at the origin and of unit size, mapped back —
bit for bit for power-of-two scales, kept vertices bit-identical, the error bound grown by the rounding of
the moved vertices, and (translated frames) the mapped result checked again for self-intersections (unit
tests `LocalFrame.*`; phase `local frame`).

**Bad input and fuzzing.** An all-degenerate mesh is an error; degenerate triangles are dropped with a warning
(`degenerate_triangles`); unused vertices are not sampled by the error measurement; a sliver spanning more than
512 cells of the guard's grid (one vertex far out beside tiny triangles) goes to a list every check scans. The
fuzz targets `simplify` and `read_step` (`tests/fuzz/`, replayed by ctest over their seed corpora; `simplify`
also under libFuzzer with ASan/UBSan) check the guarantees above on decoded meshes with every option, and that
malformed STEP files give errors naming the file.

**STEP input** is simplified part by part (an assembly's touching parts are contacts, not self-intersections
of one mesh): each part prototype gets its share of the total budget from the formula below (instances counted,
the step's feature triangles reserved), is simplified in part coordinates, and its instances are placed in the
output; the error bound is the largest part's (rigid placements keep distances).

**Scale.** `interfere simplify` on a bumpy sphere of 9,991,920 triangles (binary PLY, 250 MB) to 1 %, on this
2-core VM (2026-11-26, later that day): 14.2 s in all, reading 1.3 s, simplification about 7.2 s (its weld took
0.4 to 1.1 s between runs), the report's error measurement 4.6 s (10.2 s before the midpoints' and centroids'
searches were seeded, see hausdorff.cpp) (`--no-error`: 8.5 s in all); peak resident memory 2.55 GB, about
250 bytes per input triangle, so 10^8
triangles need a machine of about 32 GB. The simplification itself peaks at about 206 bytes per triangle
beyond the input's 24 (2.2 GB at 10^7, 2 threads), nearly independent of the thread count: each thread's
scratch holds marks over every vertex (12 bytes per vertex, the fastest) only up to 3 threads or 2^18
vertices, else a small hash map of the vertices one collapse touches (`src/simplify/vertex_map.h`; until
2026-11-26 the marks always, about 100 bytes per triangle more on 16 threads; the map costs about 10 % of
the batched passes' apply phase, the same collapses bit for bit).

**Budget.** A collapse removes the two triangles of an inner edge or the one of a boundary edge, so the budget is
met exactly whenever it is reachable; on a closed mesh (even triangle count) an odd budget ends one below
(never above; the result of the even budget below, bit for bit: unit test
`Simplify.OddBudgetOnAClosedMeshStopsOneShortOnAnOpenMeshIsExact`), and locks or constraints can stop earlier
(`reached: false` plus a warning). Where the self-intersection guard stopped it, the warning says how many
collapses it refused and how many intersecting or touching pairs the input has of its own, and how to lift it.
CAD exports with cracks (T-junctions: the two sides of a face border tessellated apart, meeting or overlapping
by rounding) stalled a strict guard there (`trimesh_featuretype.STL` of `../shared/data`: 1,216 such pairs,
3,476 → 1,306 triangles at most with `--strict-intersection-guard`); inheriting the input's contacts (the
default) the budget is met, 174 triangles, the result's 91 intersecting pairs all inside the cracks' zone (unit
test `Simplify.AStrictGuardStoppedByTheInputsOwnContactsSaysSoAndHowToLiftIt` and the one after it). When the
budget is met but the guard refused collapses next to such pairs, a warning says the error can be larger than
without it (the Newell teapot, whose spout and handle cross its body, 161 pairs: 6,320 → 316 triangles,
Hausdorff 5.3 % of the diagonal with the strict guard, 1.5 % inheriting, the same as unchecked and
meshoptimizer's).

**Error limit.** A budget alone can cost any error (a CAD part of many small faces, a budget below what its
corners allow); `--max-error E` (`--max-error-rel R`: of the diagonal; `SimplifyOptions::max_error`) makes the
budget a target that gives way where its error bound would exceed E: budgets that should hold the error if
it fell as 1/N are tried until one does (the input's own count does, up to its 1e-9 rounding margin), then
the bracket between the last budget that did not and the first that did is narrowed to 2 % of the
triangles, alternately by log-log interpolation and by halving; the run with the fewest triangles within E
is returned with a warning, `error_limited_budget` its budget and `max_error_runs` the runs made (the bumpy
sphere of 19,880 triangles to 200: half its error bound holds at 282 triangles, found in 8 runs; of 199,808
to 2,000: a tenth of it at 38,162 triangles, 9 runs, 3.1 s). The error bound does not fall strictly with the
budget (it steps where one local feature dominates: 0.00122 at 37,726 triangles of that sphere, 0.00088 at
38,162 and 39,646), so a lower budget outside the bracket may hold as well: the search finds one within E,
near the fewest, not provably the fewest; unit test
`Simplify.MaxErrorStopsAboveTheBudgetWhereTheErrorBoundWouldExceedIt`, where the budget found gives the same
result again on its own). The limit applies to `error_bound`, an upper bound of the distance from every point
of the input's surface to the result (and at least the sampled Hausdorff distance both ways), not only to the
samples.

### Triangle budget per part (renderer share)

For process step P with parts j having T_j triangles, F_j of them on the step's assembly-feature faces
(F_j = 0 for parts not in the step), and the renderer's maximum N_max:

- if Σ T_j ≤ N_max: N_i = T_i (nothing to simplify);
- else every part has a floor, half its proportional share (the paper's N = N_max · N2 / N1, §3.3):
  L_i = min(T_i, ⌊N_max · T_i / (2 Σ_j T_j)⌋), and protects P_i = max(F_i, L_i);
- if Σ P_j ≤ N_max: R = N_max − Σ P_j and N_i = P_i + ⌊R · (T_i − P_i) / Σ_j (T_j − P_j)⌋;
- else (the step's features exceed what the cap leaves: `features_exceed_budget`, a warning naming the parts and
  their feature triangles): S = N_max − Σ L_j (at least N_max / 2) and N_i = L_i + ⌊S · (P_i − L_i) / Σ_j (P_j − L_j)⌋,
  so the features are simplified too, in proportion, and no part goes below its floor;
- in each case the remaining triangles are handed out by largest remainder (ties: lower index), so that
  Σ N_i = N_max exactly: the cap is never exceeded by the shares and no part is starved.

Until issue #29 the features were reserved first and, when they alone exceeded the cap, every part got N_i = F_i:
above the cap, and parts without features nothing (CAx-IF AS1, bolt step on every part, `--renderer-max 1500`:
3,570 triangles, the bolts at 10 and the rod at 2, Hausdorff 23.5 mm on the 200 mm rod). Now: 1,500 triangles, the
bolts 40 each (Hausdorff 5.5 % of the bolt's diagonal), the rod 18 (0.9 %), the nuts 66, the brackets 204, the
plate 306 (tests `Budget.*`, `AssemblyBudget.*`: the cap on a generated assembly and on AS1 when
`../shared/data` is there, every part within 8 % (AS1: 6 %) of its size).

`triangle_budgets()` in `simplify/budget.h`; `interfere simplify --renderer-max N` applies it to one part.

The renderer's maximum is a cap, so a STEP input whose parts stop above their N_i (seams, corners, locks, the
guard: the part's report shows `output_triangles` > `target_triangles`) has them keep what they reached, and
the other parts share what is left by the same formula (`rebalanced_budgets()`, Python
`interfere.rebalanced_budgets`) and are simplified again; up to 4 rounds, each fixing at least one more part
(report `budget_rounds`). The rebalanced parts are kept only if the total budget is then met: when the stopped
parts alone fill it, or the others stop too, the formula's shares stand (no part loses its shape for a cap
missed anyway) and a warning gives the total (test assembly of `tests/cli/data`, 800 triangles: 15 % → 120
exactly, the plate stopping at 42 of its 39 and the shaft taking 36 instead of 42; 10 %: 112 for 80). What the
budget has left at the end — a closed part (even triangle count) ends one below an odd N_i, shares are rounded
down per instance — goes to the parts that met theirs, two triangles each, in part order, while the total allows,
so an assembly of closed parts meets an even budget exactly and an odd one less one (`eight_cyl.stp`, 1,312 → 394:
394, 388 before; `as1-oc-214.stp` → 1,675: 1,674, 1,658 before); parts that ended one below are counted in one
warning.

### Whole command on the casing (issue #29 target: ≤ 0.5 s including the STEP import)

`interfere simplify data/examples/casing.step c.glb --linear-deflection 0.0205 --target 5200 --step P1
--process data/examples/casing_process.json --json c.json` on the paper's casing (`TestPart::paper_casing`,
35,552 → 5,200 triangles, the paper's 35,548 case; P2 alike), 2026-11-29 13:33 UTC on this project's 2-core VM
under a load average of 3.4–4.1 (other agents building), 7 interleaved runs each, medians:

| what | before (12:53 build) | after (this change) | `--mesher delabella` |
|---|---:|---:|---:|
| whole command, wall (`interfere`, which hands STEP input to `interfere-cad`) | 2.02 s | 1.80 s | 1.57 s |
| CPU time of the process (all threads) | 1.27 s | 1.23 s | 1.02 s |
| the report's `timings_s.total` (in process) | 1.78 s | 1.63 s | 1.31 s |
| of it: STEP import (read, transfer, tessellation, deviation, AAG) | 1.48 s | 1.33 s | 0.94 s |
| of it: simplification with the error measurement | 0.29 s | 0.28 s | 0.33 s |
| of that: the error measurement | 0.24 s | 0.24 s | 0.28 s |
| writing the glTF | 0.009 s | 0.009 s | 0.009 s |

The runs' wall times spread from 1.2 to 3.2 s with the load, so before and after differ within the noise;
results are identical (output PLY byte for byte and the JSON report but timings, P1 and P2). Where the time goes
(`perf record -g` of the whole command, and a standalone OCCT loop of the import's steps, same load): process
start 0.19 s wall (0.14 s CPU: the dynamic loader resolving 70 shared libraries, OCCT's built `BIND_NOW`;
`TKXCAF` pulls in the visualisation libraries); reading and transferring the STEP file 0.19–0.25 s; BRepMesh
1.0–1.15 s with faces in parallel (`InParallel`, already the default), of which the working-ring wall (a
surface of revolution of a B-spline meridian) alone, one face holding 27,843 of the 35,552 triangles and
meshed on one thread (BRepMesh does not split a face), 0.68–0.90 s: more than the whole target by itself (`BRepMesh_CircleInspector`, Delaunay edge maps, page
faults of its work arrays); the tessellation deviation, AAG and feature recognition together under 0.05 s;
the error measurement 0.24 s against the simplification's 0.04. Changed: the tessellation deviation of a face
is measured in parallel over ranges of triangles (`tessellation_deviation.cpp`; the maximum is the same bit
for bit: checked on the casing and two NIST parts). Tried and not kept (measured no faster here): glibc
`mallopt` trim threshold and top pad for `interfere-cad` (page faults unchanged, 17,000: they are first touches
of BRepMesh's arrays, not memory handed back), both Hausdorff directions and the feature faces' distance at
once (`tbb::parallel_invoke`: error phase 0.19 → 0.25 s, the concurrent tree builds' page faults).

Second round (issue #29, 16:07 UTC, the same command; `old` the build before it, `new` with it, both
`interfere-cad` run directly, `launcher` the `interfere` command as written; 7 interleaved runs of each for P1
and P2, medians of the 14, under a load average of 6.3–7.0: other agents building and rendering):

| what | old | new | launcher |
|---|---:|---:|---:|
| whole command, wall | 2.37 s | 2.40 s | 2.44 s |
| CPU time of the process (all threads) | 1.19 s | 1.16 s | 1.16 s |
| the report's `timings_s.total` | 2.09 s | 2.13 s | 2.12 s |
| of it: STEP import (total less simplification) | 1.80 s | 1.84 s | 1.82 s |
| of it: simplification with the error measurement | 0.32 s | 0.30 s | 0.30 s |
| of that: the error measurement | 0.27 s | 0.25 s | 0.25 s |

Changed: the error measurement's search tree of the measured-to mesh holds at most as many sliver pieces as
there are samples (`hausdorff.cpp`): the 5,200-triangle result's 23,000 samples on the 35,552-triangle input
built a tree of 123,000 pieces, and now the plain tree. In isolation (the two meshes read back, 9 interleaved
runs in one process, load 5.5) that direction takes 0.12 → 0.025 s CPU and the whole measurement 0.25 →
0.17 s CPU; in the command the gain shrinks to the 0.02 s above, within the noise (its memory comes from
the heap BRepMesh handed back, already mapped). Distances and bounds are the same bits (casing P1/P2 output
PLY byte for byte as before; `fan_cylinder`, `polygon_10k`, `polygon_20k` to 10 %). What is left of it is
the 160,000 samples of the input and their bound (0.11 s CPU: `nearest_triangle_d2`, closest points).

Tried this round and not kept (measured, `/tmp` harnesses on the same OCCT 7.6.3):
- BRepMesh parameters on the wall face: `ControlSurfaceDeflection` off, 20,233 triangles (27,843 before),
  deviation 0.037 > 0.0205, no faster (its initial grid, `BRepMesh_BoundaryParamsRangeSplitter`, takes a
  grid line at every boundary node's parameter, the six counterbore rims' included); `AllowQualityDecrease`,
  `AdjustMinSize`, `AngleInterior` 1: the same mesh, no faster; `MinSize` 0.05 / 0.2: 33,686 / 38,520
  triangles, deviation 0.0205 / 0.0204; `DeflectionInterior` 0.04: 28,526, deviation 0.040;
  `InternalVerticesMode` off: other faces 11.8 off their surfaces.
- A mesher of our own for surfaces of revolution (an `IMeshTools_MeshAlgoFactory` giving the wall a grid of
  nodes from the deflection: angle steps from the largest radius, meridian steps by
  `GCPnts_TangentialDeflection`): with BRepMesh's Delaunay the node insertion itself is the cost (5,802
  nodes 0.37–0.46 s; more cells for its circle filter is slower still: 60 × 60 cells 5.5 s); with OCCT's
  Delabella and the nodes registered first, 0.09 s for 10,773 triangles but up to 0.041 off the surface (where on
  the face not located), and with deflection control (0.0204) 0.17 s for 11,661; at the paper's count it is no faster
  per triangle than the default, and its count jumps with the deflection (0.0135: 26,836; 0.014: 43,074).
- Process start (item c): `interfere-cad --version` costs 115 ms CPU, 75 % of it the dynamic loader binding
  ~95,000 relocations (OCCT built `BIND_NOW`); about a quarter are the visualisation and image libraries
  that `TKXCAF` needs (`TKVCAF` → `TKV3d`, `TKService`, FreeImage, OpenEXR, ...); ordering the lookup scope
  (libc, libstdc++, `TKernel`, `TKMath` first) changes nothing; the `interfere` launcher's own start is
  about 10 ms CPU. Avoiding it means reading STEP without XCAF (names, colours, assembly structure by hand).
- STEP read and transfer options (item d): `STEPCAFControl_Reader` with layers, properties, GD&T, materials
  and views off: the same 0.07 + 0.03 s (warm; 0.12 + 0.08 s the first time in a process).
- OCCT's allocator (`MMGT_OPT=1`: 1.6 s more system time), `MMGT_CLEAR=0`, the TBB malloc proxy: within
  the noise or slower.

Third round (issue #29, 19:20–19:40 UTC): **the working-ring wall meshed as angular sectors, the sectors
triangulated by Delabella** (`src/cad/sector_split.cpp`, `ImportOptions::sector_split`, on by default).
BRepMesh meshes a face on one thread, and its initial grid (`BRepMesh_BoundaryParamsRangeSplitter`) takes a
line at the parameter of every boundary node of the face, its holes' rims included, so on the wall (5
counterbore rims as inner wires, the sixth crossing the seam and part of the outer wire) the grid and the
Delaunay insertion into it grow about quadratically with the rims' nodes. The importer now divides such a
face before meshing, at isoparametric lines of the angle in the middle of the gaps between its rims, one rim
per sector, and gives the sectors' triangles the face's id; the AAG, feature recognition, face ids and seams
stay on the B-Rep as read. The rule: a face whose surface is a surface of revolution, cylinder, cone or
torus, periodic in the angle, covering the whole turn, without a degenerated edge (a pole or an apex), with at
least 3 inner wires in at least 3 angular groups (rims overlapping in angle form one group); a split line is placed only in a gap wider than 0.1 % of
the turn and farther than a tenth of the gap from every vertex of the face. The division is
`ShapeUpgrade_FaceDivide` with a `ShapeBuild_ReShape` context applied to the whole part, so the two circle
edges each line crosses are split for the neighbouring faces too and every shared edge is discretised once
(the meshes weld); a failed or unexpected division (not the sectors asked for, a face of the result not
traced to one face of the part) meshes the part unsplit. The sectors of surfaces of revolution and cylinders
are triangulated by OCCT's Delabella (`BRepMesh_DelabellaMeshAlgoFactory`, the same deflection control)
through a per-face algorithm factory; every other face of every part, cones' and tori's sectors included,
keeps BRepMesh's default algorithm. Why those limits (a `/tmp` harness on generated solids with 3, 4 and 7
radial holes at deflections 0, 0.05 and 0.01, each import welded by exact coordinates): a sphere split
through its poles left 10–26 more unwelded edges there (spheres and faces with degenerated edges are not
split: identical to before); a cone's sectors by Delabella measured up to 0.076 off at 0.05 (by the default
algorithm 0.056–0.059, unsplit 0.049–0.056: BRepMesh overshoots on cones either way); tubes with holes in
line and staggered: closed, within the deflection as unsplit. Measured first with BRepMesh alone (`/tmp`
harnesses, one thread): 0.43–0.60 s for the part unsplit → 0.21 s with 5 sectors (0.25 s with 3, two rims
each; load 2.5–3); then at 0.01694, load 6: sectors 0.49–0.53 s CPU → 0.26–0.28 s with Delabella on them
(with `InParallel`, as the importer runs it: 0.64–0.71 → 0.37–0.46 s CPU).

What it changes in the tessellations: the sectors need fewer triangles at the same deflection (the unsplit
face's grid was over-dense), stay within the deflection as measured (`tessellation_deviation.cpp`) and closed:

| casing (`data/examples/casing.step`) | unsplit | sectors |
|---|---:|---:|
| at 0.0205: triangles (the wall's) | 35,552 (27,843) | 29,926 (22,201) |
| at 0.0205: measured deviation | 0.02044 | 0.02045 |
| at 0.01696: triangles (the wall's) | 40,430 (31,998) | 35,556 (27,118) |
| at 0.01696: measured deviation | 0.01693 | 0.01694 |

The other faces that change are the inner ring face (a cylinder with the 6 screw bores: also split, 735 →
737 triangles at 0.01696) and four planar flange faces (1–3 triangles each: the split circle edges, the
vertices ShapeUpgrade copies). The paper's 35,548 case is therefore now `--linear-deflection 0.01696` (35,556
triangles; the closest on a grid 0.0160–0.0180 by 0.00005 refined by 0.00001; `data/examples/README.md`,
`ExampleFiles.CasingIsThePaperCasing`). Of the 24 generated test parts, the 4 files of `tests/cli/data` and
the 21 of `shared/data/step` (NIST CTC/FTC, gmsh, AS1, ...) at their default deflections only `paper_casing`
changes (4,842 → 4,618 triangles, measured deviation 0.3654 → 0.371); the benchmark's `TestPart::casing`
does not. Checked by `SectorSplit.*` (tests/cad/test_sector_split.cpp): the mesh welded by exact coordinates
has every edge in two triangles, once each way, and the unsplit mesh's Euler characteristic; each face's
triangle area within 0.5 % of its B-Rep area; one thread and many give the same triangles bit for bit; five
other test parts identical with and without. The simplification: P1 35,556 → 5,200, Hausdorff 0.202 (error
bound 0.251; before 0.235 and 0.293), P2 0.235 (0.272; before 0.284 and 0.309), no self-intersections, the
welded input closed (17,742 vertices, genus 19 as before); `--threads 1` and the default give the same PLY.

The whole command, `python3 bench/casing_whole_command.py --runs 9 --variant head=HEAD_INTERFERE_CAD:0.0205
--variant new=build/apps/cli/interfere-cad --variant launcher=build/apps/cli/interfere` (`head`: the build
before this change, `interfere-cad` with the HEAD `step_import.cpp` linked in, at the old case's 0.0205;
`new`: with it, at 0.01696; `launcher`: the `interfere` command; both cases 35,55x → 5,200; 9 interleaved
runs of each for P1 and P2, medians of the 18; 19:38 UTC, load average 4.4 before, 7.6 after):

| what | head (0.0205) | new (0.01696) | launcher (0.01696) |
|---|---:|---:|---:|
| whole command, wall | 2.55 s | 1.79 s | 2.13 s |
| CPU time of the process (all threads) | 1.26 s | 0.97 s | 1.01 s |
| the report's `timings_s.total` | 2.29 s | 1.53 s | 1.83 s |
| of it: STEP import (total less simplification) | 1.99 s | 1.17 s | 1.36 s |
| of it: simplification with the error measurement | 0.30 s | 0.43 s | 0.44 s |
| of that: the error measurement | 0.24 s | 0.31 s | 0.33 s |

Under this load the wall times spread from 1.1 to 3.7 s and the error measurement of one binary from 0.13 to
0.34 s over three runs; the CPU time is the steadier measure. The same at a lower load (19:51 UTC, the final
build of this round, `--runs 7`, load average 2.7 before, 3.0 after; medians of 14):

| what | head (0.0205) | new (0.01696) |
|---|---:|---:|
| whole command, wall (range) | 1.19 s (0.86–2.13) | 0.94 s (0.61–1.45) |
| CPU time of the process (all threads) | 1.16 s | 0.92 s |
| the report's `timings_s.total` | 1.05 s | 0.77 s |
| of it: STEP import (total less simplification) | 0.89 s | 0.58 s |
| of it: simplification with the error measurement | 0.17 s | 0.19 s |
| of that: the error measurement | 0.14 s | 0.15 s |

A `perf record` of one such run (new): BRepMesh (`TKMesh`) 21 % of the samples (the circle filter of its
Delaunay still the largest part), the kernel 19 % (page faults, the VM's interrupt handling), the error
measurement about 13 % (`nearest_triangle_d2`, `closest_point_on_triangle`, the bound's clipping), the
dynamic loader 9 %, `TKMath`/`TKernel` 12 % (surface evaluation: a surface of revolution builds a rotation,
`gp_Mat::SetRotation` and `sincos`, at every point), the STEP parser (`TKXSBase`) 4 %. (Sectors without Delabella, 19:20 UTC, load
4.5–7.1, 35,576 triangles at 0.01694: wall 2.17 → 1.86 s, CPU 1.27 → 1.06 s.) Where the import's time goes now
(stages of the same calls in one process, sectors with the default algorithm, load 5): read 0.06 s CPU and
transfer 0.04–0.06 s CPU (0.11–0.23 s and 0.07–0.23 s wall), the division 0.01 s, BRepMesh 0.5 s on one thread
(the wall's five sectors 0.04–0.10 s each, the flange faces 0.015 s each; with Delabella on the sectors about
half), deviation and AAG 0.02 s each. Tried and not kept: also splitting the sectors along the meridian above
and below the rims (15 pieces, default algorithm): 32,046 triangles at 0.01694 (another count for the paper's
case), 0.35–0.46 s against 0.43–0.71 s for the 5 sectors under load 5, within the noise.

**On a quiet machine** (the lead, 2026-11-29 20:28 UTC, every helper stopped, load average 1.2 before and
after, `python3 bench/casing_whole_command.py --runs 9`, the build of this round; 9 interleaved runs for P1 and
P2, medians of the 18):

| what | interfere (d = 0.01696) |
|---|---:|
| whole command, wall | 0.586 s (range 0.54–0.75) |
| CPU time of the process (all threads) | 0.860 s |
| the report's `timings_s.total` | 0.482 s |
| of it: STEP import (total less simplification) | 0.361 s |
| of it: simplification with the error measurement | 0.120 s |
| of that: the error measurement | 0.082 s |
| triangles | 35,556 → 5,200 |

So the whole command was **0.586 s against the target's 0.5 s: MISS by about 17 %** on a quiet machine (was
1.6–1.8 s under load before this round); the process starts (the `interfere` launcher and `interfere-cad`,
about 0.10 s between the wall time and the report's total) and the STEP import (0.36 s) are most of it.

The simplification's own part of the target is untouched by this: ≤ 15 ms, **PASS** in the Targets table
below (the benchmark's rows, default weighting). The whole command's ≤ 0.5 s was **MISS** (0.586 s quiet, above; since the fourth round: **0.455 s quiet, PASS** by 7–9 %, confirmed below); under load: 0.94 s wall
median (0.61 s the fastest run; 0.92 s CPU) under a load of 2.7–3.0, 1.8–2.1 s under 4.4–7.6, on this 2-core
VM (before this round 1.19 and 2.55 s under the same loads), to be re-measured on a quiet machine with the
command above. Left: BRepMesh (about 0.25 s on one thread, the sectors in parallel with `InParallel`), the
process start (0.12 s CPU, the dynamic loader; `TKXCAF` pulls in the visualisation libraries) and the XCAF read
and transfer (0.1–0.2 s), the error measurement (0.2–0.3 s: 160,000 samples of the input, already in parallel).
Not tried: a tessellation (or the whole imported model) cached between runs, a coarser deflection on faces that
are no features (it changes the paper's input count), a structured mesher of our own for the wall (grid cells
inside the face as two triangles each, a constrained triangulation only along the rims), fewer error samples
with a certified bound.

The error measurement alone (issue #29, 2026-11-29 20:00–20:15 UTC; the two meshes of the P1 case written by
the command, 35,556 and 5,200 triangles, read back in a `/tmp` harness; load average 2.5–3.9): `hausdorff(input,
result)` with the bound takes 0.12–0.13 s CPU on one thread (median of 15 runs; 0.13–0.17 s wall on two threads
under that load: the second core is mostly someone else's), the same values as in the command (Hausdorff
0.2016, bound 0.25146). Where it goes (callgrind, one thread): the tree searches (`nearest_triangle_d2`) 36 % of
the instructions, `closest_point_on_triangle` 33 % (about three quarters of that for the bound's convexity
candidates, `convex_bound2`, the rest in the searches), the bound's clipping and candidates (`clip`,
`convex_bound2`) 17 %, tree builds 3 %. The searches, input → result: 17,742 vertices (4.9 closest points and 33
tree nodes per query: no seed), 53,334 edge midpoints (1.9 and 9), 35,556 centroids (2.2 and 12), the
refinement of the triangles above 1.25× the sampled maximum 17,478 (2.4 and 13); result → input 15,564.
Tried and reverted (c14aaec, d5e4245, reverted in 873655d; each the same bits, casing P1/P2 output byte for
byte): the leaves as one array in leaf order with the corners and `closest_point_on_triangle`'s sliver test
precomputed (the search's own copy of the traversal, box distances kept on the stack), the convexity
candidates' sliver tests computed once, no zero fill of the clipping polygons: 18 % fewer instructions
(1.94 → 1.60 · 10^9 for the harness) but no less CPU time (0.119–0.130 s before, 0.125–0.139 s after; with
per-triangle sliver flags instead of the leaf array 0.127–0.140 s): the sliver test is off the critical path,
and the leaf array (104 bytes an entry, a sliver's corners copied for each of its pieces) outgrows the caches.
What is left for this part is therefore fewer queries, not cheaper ones: seeds for the vertex searches (each
from a neighbour's triangle; it changes which triangle a stopped search reports, hence the bound's bits,
which must then be re-certified), fewer convexity candidates where the Lipschitz or region bound already
covers a triangle, and the 35,556 centroid queries, which only matter where they raise the sampled maximum or
serve the bound.

**Fourth round** (issue #29, 2026-11-29 21:56–22:40 UTC): three changes, none changing the output (casing P1
and P2: `.ply` and `.glb` byte for byte, the JSON reports equal but their timings; `interfere features --aag`
reports equal on the casing, `nist_ctc_01`, `as1-oc-214` and `as1_pe_203`):

1. **glibc malloc settings for `interfere-cad`** (`apps/cli/cad_exec.cpp`): the `interfere` launcher execs it
   with `GLIBC_TUNABLES=glibc.malloc.hugetlb=1:glibc.malloc.mmap_threshold=33554432:glibc.malloc.top_pad=67108864:glibc.malloc.trim_threshold=1073741824`
   in its environment, unless the user set `GLIBC_TUNABLES`. By default every array above glibc's dynamic
   mmap threshold (BRepMesh's, the importer's, the simplifier's: many of up to a few MB) is a fresh `mmap`
   whose 4 KiB pages each fault in, and memory freed at the heap's top is handed back and faulted in again;
   now they come from the heap (mmap threshold 32 MiB), which grows 64 MiB at a time and is not trimmed
   (the process is short-lived; its peak is unchanged), in transparent huge pages where the kernel gives them
   to madvised memory (`hugetlb=1`; this VM: THP `madvise`). Casing P1/P2, `interfere-cad` with and without,
   9 interleaved runs each, load 6.1–6.7: minor page faults 13,300 → 1,900, CPU time 0.90 → 0.71 s (user
   0.75 → 0.63, system 0.15 → 0.08); the three thresholds without huge pages 6,900 faults and 0.78 s;
   `glibc.malloc.arena_max=1` on top no change. (The second round's `mallopt` trim threshold and top pad
   changed nothing because the mmap threshold, which sends those arrays to `mmap`, stayed.) `interfere-cad`
   run directly does not get them: give it the same `GLIBC_TUNABLES` to time it as the launcher runs it.
   The price is memory: the casing's peak resident set 63 → 73 MB; other STEP inputs simplified to
   `--ratio 0.1` (one run each under `chrt -r 10`, the launcher before and after): `nist_ctc_02` 1.53 → 1.21 s
   wall (86 → 97 MB), `gmsh_Zylkopf` 0.42 → 0.38 s (55 → 68 MB), `as1-oc-214` 0.36 → 0.31 s (55 → 63 MB).
2. **Both Hausdorff directions at once** (`hausdorff.cpp`, `tbb::parallel_invoke`; each computed as before,
   the same bits): each direction has serial steps (its tree, the fans, the convex regions, the refinement's
   sort) that the other's parallel loops fill. Error phase 0.081 → 0.074–0.076 s (medians of 10 and 16
   interleaved runs). The second round measured this with the feature faces' distance as well and found it
   slower (the concurrent tree builds' page faults, which item 1 removes); the feature faces' distance
   beside the pair (`qem.cpp`) measured 0.0629 → 0.0624 s and was not kept.
3. **The AAG built while the triangles are collected** (`step_import.cpp`, `tbb::task_group`; after BRepMesh
   both only read the B-Rep; OCCT failures and signals in the task are caught there and rethrown): import
   0.249 → 0.241 s (median of 20 interleaved runs).

The machine was loaded by the other helpers' builds and tests all through this round (load average 6–10), so
the runs were made under `chrt -r 10` (SCHED_RR, as root: they preempt the other work; the `before` column
reproduces the quiet 0.586 s above). `chrt -r 10 python3 bench/casing_whole_command.py --runs 9 --variant
before=OLD/interfere --variant after=build/apps/cli/interfere` (`before`: the launcher and `interfere-cad` of
3b81db2, copied to `OLD/`; `after`: this round's; 9 interleaved runs for P1 and P2, medians of the 18),
22:33 UTC, load average 7.8 before, 9.4 after:

| what | before | after |
|---|---:|---:|
| whole command, wall | 0.599 s | 0.486 s |
| CPU time of the process (all threads) | 0.853 s | 0.656 s |
| the report's `timings_s.total` | 0.470 s | 0.349 s |
| of it: STEP import (total less simplification) | 0.354 s | 0.258 s |
| of it: simplification with the error measurement | 0.116 s | 0.082 s |
| of that: the error measurement | 0.082 s | 0.066 s |
| wall, range | 0.58–0.68 s | 0.43–0.54 s |
| triangles | 35,556 → 5,200 | 35,556 → 5,200 |

Repeated at 22:35 UTC (load 9.3–9.8, where SCHED_RR no longer kept the runs apart: both slower): 0.829 →
0.635 s wall, CPU 1.093 → 0.856 s, import 0.492 → 0.344 s, error 0.095 → 0.076 s (after/before 0.77; in the
first run 0.81); and at 22:50 UTC with the final build (load 3.7–5.1, the machine in a slow phase: both
slower again): 0.801 → 0.588 s wall (0.73), CPU 1.079 → 0.815 s, import 0.469 → 0.327 s, error 0.091 → 0.072
s. Only the ratio carries over between such runs: applied to the quiet 0.586 s it gives 0.43–0.47 s. Where the time goes, by stage (a build with timers between the importer's steps, not
committed; both columns with items 2 and 3, `before` without the malloc settings; 12 interleaved runs each
under `chrt -r 10`, load 8.2–9.7, medians; wall 0.756 → 0.614 s):

| stage | before | after |
|---|---:|---:|
| process start to the import (`interfere`, its exec of `interfere-cad`, the dynamic loader, options, JSON files) | 0.150 s | 0.147 s |
| STEP read (XCAF application and reader set-up, parse) | 0.086 s | 0.062 s |
| entity checks (reference cycles, the session's check list) | 0.019 s | 0.019 s |
| transfer to the XCAF document | 0.054 s | 0.054 s |
| sector division | 0.012 s | 0.012 s |
| BRepMesh | 0.215 s | 0.151 s |
| triangles collected, deviation measured (the AAG beside) | 0.032 s | 0.032 s |
| simplification without the error measurement | 0.048 s | 0.023 s |
| error measurement | 0.078 s | 0.072 s |
| features, writing the glTF and JSON, exit | 0.039 s | 0.025 s |

So the whole command now measures **0.486 s against the target's 0.5 s (PASS by about 3 %)** in the runs
that reproduce the quiet machine's 0.586 s for the code before; confirmed on a quiet machine (the lead, 2026-11-29 23:22 UTC, load average 1.0 before and 1.2 after, no
other work running) with `python3 bench/casing_whole_command.py --runs 9` (the `interfere` launcher, as users run
it; 9 runs each of P1 and P2, medians of the 18), twice: **0.455 s** (range 0.44–0.48 s; CPU 0.663 s, the report's
total 0.351 s, import 0.259 s, simplification with the error 0.090 s, the error 0.069 s) and **0.465 s** (range
0.41–0.49 s): **PASS** by about 8 %, every one of the 36 runs under 0.5 s. Tried this
round and not kept: the feature faces' distance beside the Hausdorff pair (above); `arena_max=1` (above).
Looked at and left: the start — `interfere-cad --version` 70–80 ms wall when quiet, most of it the dynamic
loader binding OCCT's ~95,000 relocations (`BIND_NOW`), a third of them in the visualisation libraries
(`TKV3d` 10,100, `TKBO` 6,500, `TKService` 3,700, `TKHLR` 2,500, OpenEXR 3,500, ...) that `TKXDESTEP` →
`TKXCAF` → `TKVCAF` pull in: only a reader without XCAF would drop them; the launcher's own start and exec
about 10 ms; oneTBB loads `libiomp5.so` at its start. The meshing stays as it is (its parameters or
algorithm would change the paper's 35,556 triangles); its faces are balanced on the two threads (the five
sectors first, each thread busy for the same time within 10 %) after about 35 ms of serial edge
discretisation and model building. Left for margin: fewer error queries with a re-certified bound (below),
a reader without XCAF.

## CLI

```text synopsis
interfere simplify IN OUT (--target N | --ratio R | --renderer-max N) [--step P --process process.json]
                   [--regions FILE] [--features IDS] [--lock | --feature-mode weight|last|lock] [--sharp-angle DEG]
                   [--seams all|auto|features|none]
                   [--linear-deflection D] [--angular-deflection A] [--parts-dir DIR] [--format F]
                   [--crease-angle DEG] [--check-self-intersections] [--no-intersection-guard | --strict-intersection-guard]
                   [--no-error | --max-error E | --max-error-rel R] [--json REPORT] [--threads N]
interfere features PART.step [--json REPORT] [--aag] [--dot GRAPH.dot] [--library lib.json] [--rules rules.json]
                   [--process process.json --step P] [--linear-deflection D] [--angular-deflection A]
```

| flag | meaning |
|---|---|
| `IN` | mesh (STL/OBJ/PLY/OFF/GLB/glTF) or, built with OCCT, STEP (`.step`/`.stp`) |
| `OUT` | `.ply`: face property `uint face_id` + `uchar feature`; `.obj`: `g face_<id>` / `g feature_face_<id>` groups; `.stl` (binary): face id in each facet's attribute word (ids < 65535); `.off`: no ids; `.glb` (binary glTF 2.0, for renderers; `.gltf`: the same as JSON with the buffer a base64 `data:` URI, one file): one mesh per part and one node per instance with its placement (a part used N times is stored once), STEP instances under group nodes that follow their product paths (one per path level, no transform; the leaf's `extras.path` is the full path: the product tree, not flattened; issue #29), each mesh with two primitives on the same vertices, material `part` (grey; a part with a colour in the STEP file, its product's or shape's surface or generic colour, gets a material of that colour named after it) and material `assembly feature` (orange: the step's feature faces and clamped annuli, visible in any viewer; checked with three.js's GLTFLoader in `tests/cli/test_simplify.py`), per-vertex `NORMAL` (area-weighted, smooth within a B-Rep face so a decimated cylinder still shades round, sharp across face borders; a plain mesh's across its edges sharper than 40°), `_FACE_ID` and `_FEATURE` attributes (vertices split along faces), a root node scaling millimetres to metres for STEP input, `extras.error_bound` per mesh and on the scene (checked with the Khronos glTF validator 2.0.0-dev.3.10 from npm, 2026-11-26, on the casing's two steps, an AP214 assembly, a plain STL and the bunny: no errors, warnings or infos; the `.gltf` of the casing's step P2 and of a plain mesh alike) |
| `--lod R1,R2,...` | glTF output: coarser levels of detail in the same file, each the same simplification to a fraction of the budget (decreasing, in (0, 1)), written as `MSFT_lod` levels of every instance node (one node per level outside the scene tree, same placement, meshes `<part> LOD<k>`; `extras.MSFT_screencoverage` 0.5, 0.25, …, 0); report `lods` [{`fraction`, `target_triangles`, `output_triangles`, `error_bound`}] (issue #29: a digital twin's LOD chain in one run; AS1 at 1,500 with `--lod 0.5,0.1`: 748 and 454 triangles, the last held by the parts' corners). Renderers without the extension show the finest level |
| `--target N` | triangle budget (> 0, ≤ the input's count) |
| `--ratio R` | budget as a fraction in (0, 1] |
| `--renderer-max N` | budget from the formula above (one part: its feature triangles reserved) |
| `--step P --process F` | STEP input: features of step P's constraint type (rules: installed `semantics.json`) are kept; `--step all`: every step of F in order, the STEP file imported once (`prepare_for_simplify(model, options)`), a library, rules or process error (any step's) stopping it before the import and the first output, outputs `OUT_<step>.ext`, reports `JSON_<step>.json`, parts `DIR/<step>/` (a digital twin's model for each assembly state) |
| `--library F`, `--rules F` | STEP input: the feature library and the assembly-semantics rules (JSON, formats below) instead of the installed `data/features/library.json` and `semantics.json`; rules need a process |
| `--regions FILE` | plain mesh: one unsigned region id per triangle (whitespace separated, `#` comments) |
| `--features IDS` | comma-separated face/region ids kept in addition to the step's: region ids of `--regions` or `--sharp-angle` (one no triangle has is an error; `--sharp-angle`'s regions are numbered in order of their first triangle, and the output's face ids show them); for STEP input face ids as the output numbers them (a part's face id plus its instance's `cad.instances[].face_id_offset`; one part: the ids `interfere features` lists), each kept on every instance of its part (`add_feature_faces`; an id on no part is an error). Until 2026-11-26 a STEP input's `--features` were reported and tagged but not kept |
| `--lock` | hard locks instead of the paper's cost weighting (= `--feature-mode lock`) |
| `--feature-mode M` | `weight` (paper, default), `last` (feature edges strictly last), `lock` |
| `--seams S` | face seams kept: `auto` (default since issue #29: all if the budget can be met so, else as `features`, with a warning giving the count every seam allowed), `all` (every seam, even where its corners hold the part above the budget: `nist_ctc_01` at 10 % stops at 614 for 283), `features` (the borders of assembly-feature faces only), `none` (face ids as tags only) |
| `--sharp-angle DEG` | plain mesh without regions: split it into regions at edges sharper than DEG (in (0, 180)), whose borders are kept like seams and whose ids the output carries as face ids (with `--regions`, or on a STEP input, whose regions are its faces, an error) |
| `--linear-deflection`, `--angular-deflection` | STEP tessellation (0 = 0.1 % of the diagonal; radians) |
| `--parts-dir DIR` | STEP input: also write each simplified part once, in part coordinates, as `DIR/<part>_<name>.<OUT's extension>` with its own face ids, feature tags and error bound; the report's `cad.instances[].placement` places them (a renderer instances them instead of loading the merged OUT) |
| `--format F` | output format (stl, stl-ascii, obj, ply, ply-ascii, off, glb, gltf), whatever OUT's extension |
| `--crease-angle DEG` | glTF output of a mesh without faces or regions: `NORMAL` smooth across edges up to DEG degrees, split across sharper ones (default 40; in (0, 180)); an error for other outputs and where faces or regions (STEP, `--regions`, `--sharp-angle`) set the normals |
| `--check-self-intersections` | count self-intersections of the result (engine clash), reported |
| `--no-intersection-guard` | plain QEM: no self-intersection check of the result, no guarded rerun |
| `--strict-intersection-guard` | refuse every new intersecting pair, also where the input's own contacts move (default: those inside the input's contact zone are inherited) |
| `--no-error` | skip the Hausdorff measurement |
| `--max-error E`, `--max-error-rel R` | largest error bound allowed, in model units or as a fraction of the input's bounding-box diagonal (an assembly's parts share one limit): where the budget's error bound would exceed it, the fewest triangles that keep it within are returned instead, a warning says so (`SimplifyOptions::max_error`: a search over the budget to 2 % of the triangles, each step a full run with the error measured: several times the time of one run; report `max_error`, `max_error_runs`, `error_limited_budget`) |
| `--json FILE` | JSON report |

On a terminal the share of the collapses done is shown while it runs (`SimplifyOptions::progress`).
Exit status 0 on success, 2 on a usage or input error (the message names the file, line or entity); outputs are
written atomically and only after every input was validated.

**`simplify` report**: the keys every report has (docs/report.md), `input`, `output`, `units` and `units_source` (the working unit and where it came from), `input_triangles`, `target_triangles`, `output_triangles`, `output_vertices`, `reached`,
`one_below` (ended one triangle below an odd budget, as a closed mesh loses triangles in pairs; a warning says so; STEP input: per part, the report's warnings count the parts),
`collapses`, `rejected` {`link_condition`, `flipped_normal`, `self_intersection`, `last_face_triangle` (collapses refused as they would remove a face's last triangle)}, `guard_rerun`, `guard_reruns`, `input_contact_pairs` (the input's own intersecting or touching pairs: all of them where the guard refused collapses, else those near the plain result's new pairs; 0 when none were looked for), `inherited_pairs` (intersecting pairs of the result inside the input's contact zone, not both as in the input), `degenerate_triangles` (input triangles with two corners at one position, dropped with a warning; all degenerate is an error), `vertices` {`welded_input`,
`seam`, `corner`, `locked`}, `feature_mode`, `feature_faces`, `sharp_angle` (null without), `regions` (distinct face or region ids of the input: B-Rep faces, `--regions`, `--sharp-angle`; 0 for none), `feature_triangles` {`input`, `output`},
`seams`, `seams_relaxed_at` (`--seams auto`: the fewest triangles every seam allowed, when that was above the budget; 0 otherwise; STEP input: summed over the parts × instances), `max_error` (the limit in model units, null without one), `max_error_runs` (runs made for it; summed over the parts), `error_limited_budget` (the budget of the run returned where the limit raised it, else 0; STEP input: per part), `max_unmodified_cost`, `bbox_diagonal`, `hausdorff`, `hausdorff_features` (null without features), `error_bound`,
`self_intersections` (with the flag), `timings_s` {`simplify`, `total`, `phases` [{`phase`, `seconds`}] (wall time
of simplify()'s phases, in order; summed over the parts of a STEP input)}, `warnings`; for STEP input `cad` {`parts`
[{`name`, `faces`, `triangles`, `features`, `assembly_feature_faces`}], `instances` [{`name`, `part`, `path`,
`face_id_offset`, `placement` (3×4 [R|t], part → world), `in_step`, `simplified_part`}], `step`, `units`, `file_length_units`, `warnings`}, `budget_rounds`, `tessellation_error` (the largest part's) and `parts_simplified` [{`part`, `model_part`, `name`, `file` (with `--parts-dir`), `instances`, `input_triangles`,
`target_triangles`, `output_triangles`, `one_below`, `feature_triangles`, `hausdorff`, `error_bound`, `hausdorff_features`, `guard_rerun`, `guard_reruns`, `input_contact_pairs`, `inherited_pairs`, `seams_relaxed_at`, `max_error_runs`, `error_limited_budget`,
`self_intersections` (with the flag; for STEP input the report's count is the sum over parts × instances), `tessellation_error`}].
`error_bound` (also the bound stored in the output files) measures the result against the tessellation it was
simplified from; `tessellation_error` is how far that tessellation may lie from the B-Rep: the larger of the
linear deflection and the deviation measured after BRepMesh (sampled at the triangles' centroids and edge
midpoints, as `interfere check` reports it; BRepMesh exceeds its tolerance on some faces). Against the B-Rep
parts, add the two. Face
ids of a multi-instance STEP are offset per instance.

**`features --dot FILE`**: the attributed adjacency graph of every part as Graphviz DOT (`cad::aag_dot`; render
with `dot -Tsvg FILE -o aag.svg`): a cluster per part, a node per face (`F<id>`, surface type, radius and
`hole` for rotational faces), faces filled in one colour per recognised feature (a legend note per feature),
the step's assembly-feature faces (`--step P`) outlined red; arcs convex solid, concave dashed, smooth dotted,
labelled with the curve type, bold on inner loops (where the minimal subgraphs are split first).

**`features` report**: `parts` [{`name`, `solids`, `faces`, `triangles`, `untessellated_faces`, `features`
[{`type`, `faces`, `roles` {role: face}, `radii`, `axis` {`point`, `direction`}}], `assembly_feature_faces`,
`semantics_warnings` (with `--step all`: `steps` {step: {`assembly_feature_faces`, `semantics_warnings`}}), with `--aag`: `aag` {`nodes` [{`face`, `type`, `from_bspline`, `area`, `outer_loops`,
`inner_loops`, `triangles`, `normal` | `axis`, `radius`, `hole`, `half_angle`, `minor_radius`}], `arcs` [{`faces`,
`edge`, `curve`, `convexity`, `angle`, `length`, `inner_loop`}], `minimal_subgraphs`}}], `instances` [{`name`,
`part`, `path`, `placement` (3×4)}], `units` (always `mm`: OCCT converts the file's lengths to millimetres;
every coordinate, radius, area and distance of both reports is in it), `file_length_units` (the length units
the file declares, e.g. `["INCH"]`), `warnings`, `timings_s` {`recognition`, `total`}, and the keys every report has (docs/report.md: `seconds` is the process's wall time).

## Feature library and rules (JSON)

Pattern: `{"type", "priority", "nodes": [{"role", "types": [...], "hole": bool, "concave_arcs": n,
"convex_arcs": n, "min_convex_arcs": n, "shared": bool}], "arcs": [{"a", "b", "curves": [...], "convexity":
[...]}], "checks": [{"kind": "coaxial" | "radius_less" | "perpendicular_to_axis" | "parallel_planes" |
"opposite_normals" | "perpendicular_planes" | "full_circle" (the role's faces' angular spans sum to the full
circle: the boss pattern's, so convex fillets and outer corner rounds are no bosses), "roles": [...]}]}`. Rule: `{"name", "constraint", "features":
[{"type", "roles": [...]}]}` (empty roles = every face of the feature). Both files are installed to
`share/interfere/features/` (`INTERFERE_DATA_DIR` overrides).

## C++ and Python API

C++: `interfere/simplify/qem.h` (`simplify`, `SimplifyOptions`, `SimplifyResult`, `sharp_edge_regions`,
`weld_positions`, `split_by_face`), `simplify/hausdorff.h` (`hausdorff`, `one_sided` (sampled distance and bound), `one_sided_distance`,
`count_self_intersections`), `simplify/budget.h`, `simplify/tagged_io.h` (`write_tagged_mesh`, `read_error_bound`), `simplify/gltf_io.h` (`write_glb`); with OCCT (`interfere::cad`):
`cad/model.h` (`import_step`, `world_mesh`, `write_test_part`), `cad/features.h`, `cad/semantics.h`,
`cad/pipeline.h` (`prepare_for_simplify`, `add_feature_faces`), `cad/aag_dot.h` (`aag_dot`: the graph as DOT), `cad/assembly_simplify.h` (`simplify_assembly`:
a prepared model part by part to one total, as the CLI does; per-part results and budgets, the merged world
result). Python: `interfere.simplify(mesh, target=0, ratio=0, face_ids=[], feature_faces=[],
lock=False, sharp_angle=0, prevent_self_intersections=True, measure_error=True, feature_mode="weight",
inherit_input_contacts=True, seams="auto", max_error=0)` → `SimplifyResult` (`.mesh`, `.face_ids`, `.hausdorff`, `.hausdorff_features`,
`.error_bound`, `.guard_rerun`, `.guard_reruns`, `.input_contact_pairs`, `.inherited_pairs`, `.seams_relaxed_at`,
`.one_below`, `.max_error_runs`, `.error_limited_budget`, `.phases`
[(phase, seconds)], counters), `interfere.hausdorff(a, b)` (sampled a→b, b→a), `interfere.distance_bound(a, b)`,
`interfere.write_tagged_mesh(path, mesh, face_ids=[], feature_faces=[], error_bound=-1)`,
`interfere.read_error_bound(path)`, `interfere.write_glb(path, [(name, mesh, face_ids, feature_faces,
error_bound)], [(name, part, Transform)], units="mm")`, `interfere.count_self_intersections(mesh)`, `interfere.triangle_budgets([(T, F), ...], renderer_max)`; when
`interfere.HAVE_CAD`: `interfere.import_step(path, linear_deflection=0, angular_deflection=0.5)` (instances with
their `placement`), `interfere.step_features(path, process="", step="", library="", rules="")` (per part `features`, `dot`, with a step `assembly_feature_faces`) and `interfere.prepare_step(path,
process="", step="", linear_deflection=0, angular_deflection=0.5, library="", rules="", mates=True,
mesher="default")`, the CLI's STEP pipeline (`mates=True` without a process: the mates' features, as `--mates auto`;
`mesher="delabella"` as `--mesher`)
up to the simplification: `parts` ready for `simplify` (`name`, `mesh` in part coordinates, `face_ids`,
`feature_faces` of the step, `faces`, `instances`, `model_part`; `<part> [<step>]` variants as in the CLI),
`instances` (`name`, `part`, `placement`, `face_offset`), `warnings` and `report` (the CLI report's `cad` object);
and `interfere.simplify_step(path, target=0, ratio=0, renderer_max=0, process="", step="", lock=False,
feature_mode="weight", seams="auto", prevent_self_intersections=True, measure_error=True, max_error=0,
linear_deflection=0, angular_deflection=0.5, library="", rules="", mates=True, mesher="default")`, the CLI's STEP
simplification whole (`cad::simplify_assembly`; `mates` and `mesher` with the CLI's defaults: the mates' features
without a process, as `--mates auto`, `mates=False` as `--mates off`, ignored with a process): `result` (every instance placed), `parts` [{`name`, `result`, `budget`, `instances`,
`feature_faces`, `model_part`}], `instances`, `budget_rounds`, `features_exceed_budget`, `feature_faces`,
`warnings`, `report`. By hand, part by part:

```python
import interfere as itf
prep = itf.prepare_step("data/examples/casing.step", process="data/examples/casing_process.json", step="P1")
parts = [(p["name"], itf.simplify(p["mesh"], ratio=0.1, face_ids=p["face_ids"], feature_faces=p["feature_faces"]))
         for p in prep["parts"]]
itf.write_glb("line.glb", [(n, r.mesh, r.face_ids, p["feature_faces"], r.error_bound)
                           for (n, r), p in zip(parts, prep["parts"])],
              [(i["name"], i["part"], i["placement"]) for i in prep["instances"]])
```
"""


def render_doc(raw, old: str | None):
    """The page: STATIC_HEAD, the hole truth-set section kept from `old` (the current page), the tables."""
    r = rows(raw)
    # Rows of the last full run that filtered reruns replaced (build_and_run): the targets, ratios,
    # locked-feature lines and the phase table are judged on them; notes say what the reruns were.
    full = rows(raw, "full_run")
    notes = raw.get("notes", {})

    def judged(name):
        return full.get(name) or r.get(name)

    ctx = raw.get("context", {})
    lines = [STATIC_HEAD, "## Benchmarks", ""]
    # The truth-set sections (issue #29) are written by tools/hole_truth/pr_table.py and
    # tools/floor_truth/pr_table.py: kept as they are.
    if old is not None:
        for name in ("hole-truth", "floor-truth"):
            a, e = f"<!-- {name}:begin -->", f"<!-- {name}:end -->"
            if a in old and e in old:
                if name == "floor-truth" and lines[-1] == "":
                    lines.pop()  # one blank line between the two sections, as the page has
                lines += [old[old.index(a):old.index(e) + len(e)], "", ""]
    when = ctx.get("date") or _dt.datetime.now(_dt.timezone.utc).strftime('%Y-%m-%d %H:%M UTC')  # the run's own date
    lines.append(f"Run {when} on {platform.node()} "
                 f"({ctx.get('num_cpus', '?')} CPUs, load average {ctx.get('load_avg', '?')}), "
                 "`bench/bench_simplify.cpp`, wall time per run: the mean of 3 runs (1e6) or 5 (1e5) for interfere and meshoptimizer after one untimed warm-up call each (the steady state of a process that simplifies repeatedly; a process's first call is about 10 % slower: thread pool start, heap growth), one for OpenMesh, 20 for the casing rows. Meshes: `make_sphere` with 5 % "
                 "bumps; the equatorial patch x > 0.98, |z| < 0.05 (about 0.25 % of the triangles) is the feature region "
                 "(weighted by interfere, unknown to the peers). "
                 "`hausdorff_rel`: symmetric sampled Hausdorff / bounding-box diagonal; `feature_err_rel`: largest "
                 "distance from the original feature faces' samples to the result / diagonal; `self_x`: pairs of "
                 "non-adjacent intersecting triangles. `interfere`: default options (features weighted, result "
                 "checked for self-intersections and rerun with the per-collapse guard if needed, `guard_rerun`) "
                 "except the Hausdorff report (`measure_error = false`, as the peers report no error either); "
                 "`interfere_error`: the same plus the report's sampled Hausdorff measurement (what `interfere "
                 "simplify` does without `--no-error`); `interfere_unchecked`: without the self-intersection check; "
                 "`interfere_plain`: no feature region. Every interfere row times the whole `simplify()` call: "
                 "welding, setup, collapses, the check, output. The 0.6 s target is judged on the `interfere` row "
                 "(checked, no error report): the check is a guarantee of the result, the Hausdorff report is a "
                 "measurement that meshoptimizer does not make; `interfere_error` shows its cost. `cpu` is the "
                 "process's CPU time (all threads). OpenMesh's half-edge construction is not timed.")
    lines.append("")
    lines.append("| case | tool | time (ms) | cpu (ms) | triangles out | hausdorff_rel | feature_err_rel | self_x | guard rerun |")
    lines.append("|---|---|---:|---:|---:|---:|---:|---:|---:|")
    for name, b in r.items():
        if not name.startswith("Simplify/"):
            continue
        _, tool, size, pct = name.split("/")[:4]
        case = f"{size} → {pct.replace('pct', ' %')}"
        if "error" in b:
            lines.append(f"| {case} | {tool} | error: {b['error']} | | | | | | |")
            continue
        rerun = rerun_cell(b)
        lines.append(f"| {case} | {tool} | {b['ms']:.1f} | {b['cpu_ms']:.1f} | {int(b['tri_out'])} | {fmt(b['hausdorff_rel'])} | "
                     f"{fmt(b['feature_err_rel'])} | {int(b['self_x'])} | {rerun} |")
    lines.append("")
    lines.append("`guard rerun` yes: the plain result had a self-intersection (10^6 → 10 %: a few pairs), so the "
                 "time includes a guarded rerun of the heap phase, started from the copy of the state the plain run "
                 "kept where its batched passes handed over (see the casing note below); `interfere_unchecked` shows "
                 "the plain run alone.")
    lines.append("")
    lines.append("Casing (generated with OCCT: flanged ring whose wall is a surface of revolution with a B-spline "
                 "bulge, 6 counterbored bolt holes on the lower flange, 6 plain bolt holes on the upper one; linear deflection chosen so the tessellation is closest to the "
                 "paper's 35,548 triangles) simplified to 5,200 triangles with the assembly features of two steps "
                 "weighted, in the paper's order (He & Xu §4; issue #29): P1 screw tightening (counterbored holes + "
                 "seats + the BottomFace within 2 r of each bore), P2 bolt connection (through holes + TopFace and "
                 "BottomFace within 2 r; the main bore skipped: no washer fits its flange). `interfere`: the paper's weighting; `interfere_last`: feature edges strictly last; "
                 "`interfere_lock`: hard locks; `meshoptimizer`: the peer on the welded part, knowing neither faces nor "
                 "features (its time is the reference for the casing target on this machine and load); `openmesh`: "
                 "the OpenMesh Decimater (ModQuadric) on the welded part, 3 runs; `openmesh_lock`: the same with "
                 "every vertex of the step's feature faces locked, the Decimater's own region protection (it keeps "
                 "the feature triangles as they are, like `interfere_lock`, but knows no seams and checks no "
                 "intersections)." + (f" ({notes['Casing']})" if notes.get("Casing") else ""))
    lines.append("")
    lines.append("| case | time (ms) | cpu (ms) | triangles in → out | feature faces | hausdorff_rel | feature_err_rel | self_x | guard rerun |")
    lines.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, b in r.items():
        if not name.startswith("Casing/"):
            continue
        if "error" in b:
            lines.append(f"| {name} | error: {b['error']} | | | | | | | |")
            continue
        rerun = rerun_cell(b)
        lines.append(f"| {name} | {b['ms']:.2f} | {b['cpu_ms']:.2f} | {int(b['tri_in'])} → {int(b['tri_out'])} | "
                     f"{int(b['feature_faces'])} | {fmt(b['hausdorff_rel'])} | {fmt(b['feature_err_rel'])} | "
                     f"{int(b['self_x'])} | {rerun} |")
    lines.append("")
    lines.append("`guard rerun`: plain QEM left a self-intersection and the run was repeated with the guard. With "
                 "P1's features kept strictly (`last`, `lock`) the flange faces and bolt holes keep most of the 5,200 "
                 "triangles and the rest of the casing is cut down to a few hundred, whose triangles span most of "
                 "the part and cut through it (about 50 new pairs locked, 300 strictly last), all in the heap phase: the rerun repeats the "
                 "batched passes (the same collapses), finds the mesh they leave clean and guards the heap's "
                 "collapses near the pairs, whose neighbourhoods here cover the whole part (about 1,800, from "
                 "about 8,800 triangles to 5,200, each one scan of the guard's hash grid over the cells of its "
                 "moved triangles). Before 2026-11-26 the rerun guarded the pairs' neighbourhoods, which here cover the "
                 "whole part, with the batched passes again: about 100 ms (250 ms before 2026-11-24). Since "
                 "2026-11-26 the new pairs first make the input's contact zone where they meet (the casing has no "
                 "contacts of its own: a self-clash of the 1,737 of its 35,516 triangles near them finds none, "
                 "about 1 ms). Where the time goes (2026-11-26, about 56 ms in all): the guard about 13 ms (some "
                 "1,500 scans of its hash grid, each over about 28 cells and 420 entries: 120 distinct live "
                 "triangles, half of them overlapping the moved triangles' box, and about 57 exact triangle tests), "
                 "the rest of the guarded heap 6 ms, the repeated passes and setup 11 ms, the checks 8 ms (the plain "
                 "result, the handoff mesh, the final result), the plain run 14 ms. Keeping the handoff copy for "
                 "small inputs too saves about 5 ms here and costs about 1 ms on every other run (measured, not "
                 "adopted). The uniform grid is a poor fit for these mixed sizes (tiny kept feature triangles "
                 "beside huge ones); a hierarchy there is open work. The 1e6 → 10 % rerun also takes the "
                 "heap-guarded path: the plain run's heap "
                 "left one fold (6 pairs around one vertex near a pole of the sphere); the rerun starts from the "
                 "state the plain run kept at the handoff and guards the heap's collapses near that fold only. "
                 "Until 2026-11-26 it repeated the passes and guarded every heap collapse (about 30,000): about "
                 "1.2 s in all instead of about 0.6 s.")
    lines.append("")
    real = [n for n in r if n.startswith("Real/")]
    if real:
        lines.append("Real meshes (public models of `../shared/data/mesh`, see its `SOURCES.md`; rows only when "
                     "present), welded, each to 5 % of its triangles, no features; 5 runs (OpenMesh 1). `self_x`: "
                     "intersecting pairs of the result, `own`: of the input (cracks of CAD exports, bodies crossing "
                     "each other), which a result may keep; interfere's default (`interfere`) adds none outside "
                     "the input's contact zone (pairs inside it are the input's contacts, moved), "
                     "`interfere_strict` (`--strict-intersection-guard`, meshes with contacts of their own only) "
                     "none but the input's unchanged pairs, `interfere_unchecked` is the plain run.")
        lines.append("")
        lines.append("| mesh | tool | time (ms) | triangles in → out | hausdorff_rel | self_x (own) | guard rerun |")
        lines.append("|---|---|---:|---:|---:|---:|---:|")
        lines += rows_of(
            r, real,
            lambda p, b: (f"| {p[2]} | {p[1]} | {b['ms']:.2f} | {int(b['tri_in'])} → {int(b['tri_out'])} | "
                          f"{fmt(b['hausdorff_rel'])} | {int(b['self_x'])} ({int(b['self_x_in'])}) | {rerun_cell(b)} |"),
            lambda p, e: f"| {p[2]} | {p[1]} | error: {e} | | | | |")
        lines.append("")
        lines.append("Where a mesh has intersections of its own, the strict guard refuses collapses next to them "
                     "and makes more elsewhere (the Newell teapot: a larger error than unchecked; "
                     "`trimesh_featuretype`, a CAD export with cracks: it stops above the budget, with a warning "
                     "naming both and how to lift it); the default inherits them (the teapot's and "
                     "`trimesh_featuretype`'s plain results have new pairs only inside the contact zone: no rerun, "
                     "the unchecked result). Where the plain run adds intersections elsewhere the "
                     "guarded rerun costs time: `vtkdata_gears` (gears whose teeth touch, faces meshed as fans of "
                     "slivers from the hub) makes about 100 exact triangle tests per guarded collapse, as the "
                     "slivers' boxes overlap; the same error as unchecked, 34 pairs (the input's contacts, moved) "
                     "instead of 210. Below 20,000 triangles there are no batched passes, and the heap alone handles fandisk's "
                     "flat faces (every cost 0) in about 8 ms since equal costs are taken first in, first out (42 ms "
                     "before, last in, first out).")
        lines.append("")
    seams = [n for n in r if n.startswith("Seams/")]
    if seams:
        lines.append("CAD parts of many small faces (STEP parts of `../shared/data/step`, rows only when present), "
                     "tessellated with the default deflection, each to 10 % of its triangles, no features, 5 runs: "
                     "`all` keeps every face seam, `auto` (the default since issue #29) keeps them when the budget can be met so and "
                     "else runs again as `features` (`relaxed at`: the fewest triangles every seam allowed), "
                     "`features` keeps only the feature faces' borders (here none).")
        lines.append("")
        lines.append("| part | faces | seams | time (ms) | triangles in → out (budget) | hausdorff_rel | relaxed at | guard rerun |")
        lines.append("|---|---:|---|---:|---:|---:|---:|---:|")
        lines += rows_of(
            r, seams,
            lambda p, b: (f"| {p[2]} | {int(b['faces'])} | {p[1]} | {b['ms']:.2f} | {int(b['tri_in'])} → "
                          f"{int(b['tri_out'])} ({int(b['target'])}) | {fmt(b['hausdorff_rel'])} | "
                          f"{int(b.get('seams_relaxed_at', 0)) or '—'} | {rerun_cell(b)} |"),
            lambda p, e: f"| {p[2]} | | {p[1]} | error: {e} | | | | |")
        lines.append("")
        lines.append("With every seam kept, a part's corners (where three faces meet) and its seams, simplified as "
                     "polylines through their own vertices, hold it far above a low budget, and the last collapses "
                     "along curved borders cost the most error (and often a guarded rerun): `auto` decides on its "
                     "first, plain run (no check or rerun of it when it falls short; `relaxed at` is its count) and "
                     "gives the result of `features`.")
        lines.append("")
    slivers = [n for n in r if n.startswith("Slivers/interfere/")]
    if slivers:
        lines.append("Sliver meshes (issue #23, item 12): prisms over a regular n-gon of radius 10, caps fanned "
                     "from their centres (4n triangles, every spoke a sliver): `fan_cylinder` n = 8,192, height 20; "
                     "`polygon_10k` / `polygon_20k` n = 10,000 / 20,000, height 1; each to 10 %, 3 runs (run 2026-11-28 alone, `--filter Slivers`). `plain`: "
                     "simplify() without the error measurement; `with error`: with it (what `interfere simplify` "
                     "does without `--no-error`), `error` its phase alone; `hausdorff` (sampled) and `error_bound` "
                     "absolute.")
        lines.append("")
        lines.append("| mesh | triangles in → out | plain (ms) | with error (ms) | error (ms) | hausdorff | error_bound |")
        lines.append("|---|---:|---:|---:|---:|---:|---:|")
        for name in slivers:
            b, e = r[name], r.get(name.replace("/interfere/", "/interfere_error/"), {"error": "missing"})
            mesh = name.split("/")[2]
            if "error" in b or "error" in e:
                lines.append(f"| {mesh} | error: {b.get('error') or e.get('error')} | | | | | |")
                continue
            lines.append(f"| {mesh} | {int(b['tri_in'])} → {int(b['tri_out'])} | {b['ms']:.1f} | {e['ms']:.1f} | "
                         f"{fmt(e.get('phase:error'), '.1f')} | {fmt(e.get('hausdorff'))} | {fmt(e.get('error_bound'))} |")
        lines.append("")
    rec = judged("Recognition/perforated_plate")
    if rec and "error" not in rec:
        lines.append(f"Feature recognition on the perforated plate ({int(rec['faces'])} faces, "
                     f"{int(rec['features'])} features): {rec['ms']:.2f} ms.")
        parts = []
        for f in ("nist_ctc_02_asme1_rc.stp", "nist_ftc_10_asme1_rb.stp"):
            rf = r.get("Recognition/" + f)
            if rf and "error" not in rf:
                parts.append(f"{f} ({int(rf['faces'])} faces, {int(rf['features'])} features): {rf['ms']:.2f} ms")
        if parts:
            rerun = r.get("Recognition/perforated_plate")
            note = ""
            if notes.get("Recognition") and rerun is not rec and rerun and "error" not in rerun:
                note = (f" (these two and the plate at {rerun['ms']:.2f} ms with the hole recognition of issue #29: "
                        f"{notes['Recognition']})")
            elif notes.get("Recognition"):
                note = f" ({notes['Recognition']})"
            lines.append("On " + "; ".join(parts) + note + ".")
        lines.append("")
    # Verdicts.
    lines.append("### Targets")
    lines.append("")
    lines.append("| target | measured | verdict |")
    lines.append("|---|---|---|")
    ours = judged("Simplify/interfere/1e6/1pct")
    ours_ng = judged("Simplify/interfere_unchecked/1e6/1pct")
    om = judged("Simplify/openmesh/1e6/1pct")
    if ours and "error" not in ours:
        lines.append(f"| 1e6 → 1e4 in ≤ 0.6 s (default, checked) | {ours['ms']/1000:.2f} s | {verdict(ours['ms'] <= 600)} |")
        if ours_ng and "error" not in ours_ng:
            lines.append(f"| 1e6 → 1e4 in ≤ 0.6 s (unchecked) | {ours_ng['ms']/1000:.2f} s | "
                         f"{verdict(ours_ng['ms'] <= 600)} |")
        if om and "error" not in om:
            lines.append(f"| Hausdorff ≤ OpenMesh's (1e6 → 1e4) | {ours['hausdorff']:.3g} vs {om['hausdorff']:.3g} | "
                         f"{verdict(ours['hausdorff'] <= om['hausdorff'])} |")
        lines.append(f"| feature faces within 1e-6 of the diagonal | {ours['feature_err_rel']:.3g} | "
                     f"{verdict(ours['feature_err_rel'] <= 1e-6)} |")
    else:
        lines.append("| 1e6 → 1e4 | not run (--quick) | — |")
    for step in ("P1", "P2"):
        for variant in ("interfere", "interfere_last"):
            c = judged(f"Casing/{variant}/{step}")
            if c and "error" not in c:
                mode = ("the paper's weighting, default" if variant == "interfere" else
                        "stricter than the paper: feature edges strictly last")
                lines.append(f"| casing {int(c['tri_in'])} → {int(c['tri_out'])} ({step}, {variant}: {mode}) in ≤ 15 ms | "
                             f"{c['ms']:.2f} ms | {verdict(c['ms'] <= 15)} |")
    # Recognition targets on the latest rows (the recogniser changes, so the current code's time; the
    # full run's rows are history): a filtered rerun of Recognition updates them.
    rec = r.get("Recognition/perforated_plate") or rec
    if rec and "error" not in rec:
        lines.append(f"| feature recognition, {int(rec['faces'])}-face part, ≤ 50 ms | {rec['ms']:.2f} ms | "
                     f"{verdict(rec['ms'] <= 50)} |")
    ctc2 = r.get("Recognition/nist_ctc_02_asme1_rc.stp") or judged("Recognition/nist_ctc_02_asme1_rc.stp")
    if ctc2 and "error" not in ctc2:
        lines.append(f"| feature recognition, NIST CTC-02 ({int(ctc2['faces'])} faces), ≤ 100 ms | {ctc2['ms']:.2f} ms | "
                     f"{verdict(ctc2['ms'] <= 100)} |")
    lines.append("")
    mo = judged("Simplify/meshoptimizer/1e6/1pct")
    if ours and mo and "error" not in ours and "error" not in mo:
        lines.append(f"Same run, same load: interfere {ours['ms']/1000:.2f} s vs meshoptimizer {mo['ms']/1000:.2f} s "
                     f"(ratio {ours['ms']/mo['ms']:.2f}); the issue's 0.6 s is meshoptimizer's time on a quiet machine.")
        lines.append("")
    cmo = judged("Casing/meshoptimizer/P1")
    cours = judged("Casing/interfere/P1")
    if cmo and cours and "error" not in cmo and "error" not in cours:
        lines.append(f"Casing, same run: interfere (P1) {cours['ms']:.2f} ms vs meshoptimizer {cmo['ms']:.2f} ms "
                     f"(ratio {cours['ms']/cmo['ms']:.2f}); meshoptimizer keeps no faces or features and checks no "
                     "self-intersections.")
        lines.append("")
    for step in ("P1", "P2"):
        ol = judged(f"Casing/openmesh_lock/{step}")
        il = judged(f"Casing/interfere_lock/{step}")
        if ol and il and "error" not in ol and "error" not in il:
            lines.append(f"Feature faces locked, {step}: interfere {il['ms']:.1f} ms, {int(il['tri_out'])} triangles, "
                         f"Hausdorff {fmt(il['hausdorff_rel'])}, {int(il['self_x'])} self-intersections; OpenMesh "
                         f"{ol['ms']:.0f} ms, {int(ol['tri_out'])} triangles, Hausdorff {fmt(ol['hausdorff_rel'])}, "
                         f"{int(ol['self_x'])} self-intersections.")
            lines.append("")
    lines.append("Verdicts use wall time. Timings come from a shared 2-core machine (see the load average above; "
                 "`cpu` is the process's CPU time, all threads); rerun `python3 bench/simplify_tables.py` on a quiet "
                 "machine for reference numbers. The issue's casing target is the paper's method (`interfere`, "
                 "weighted features); the `interfere_last` rows are judged too, and P1 misses there for the reason "
                 "given under the casing table. The machines these pages were made on differ and go through slow "
                 "phases: on 2026-11-24 (another VM of the same kind) meshoptimizer took from 0.56 to 0.98 s on the "
                 "same 1e6 input and 12.2 ms on the casing, where interfere P1 took 16.3 ms (a MISS then; the check "
                 "has since become 0.2 ms faster); the two-threaded interfere suffers more in slow phases (one "
                 "filtered run in such a phase: 1e6 → 1e4 0.67 s vs meshoptimizer 0.91 s, casing P1 23.8 ms vs "
                 "12.9 ms). On 2026-11-26 the casing P1 took 14.9 to 15.5 ms in the day's first runs (1.65× "
                 "meshoptimizer: at the target's edge); the batched passes' ranges made even and equal (the late "
                 "passes ran on one thread), smaller evaluation chunks and a faster self-intersection check (its "
                 "leaf tests four boxes at a time, adjacency without branches) brought it to about 1.5× (P1's "
                 "Hausdorff 0.000522 → 0.000554 of the diagonal from the changed ranges, the spheres' unchanged). "
                 "Compare rows of one run only.")
    lines.append("")
    # Where the time goes: simplify()'s own phase timers (SimplifyResult::phases, the report's
    # timings_s.phases), recorded by the benchmark as phase:<name> counters.
    ph = {n: judged(n) for n in ("Simplify/interfere/1e6/1pct", "Casing/interfere/P1")}
    ph_rows = [n for n, b in ph.items() if b and "error" not in b]
    if ph_rows:
        order = ["weld", "setup", "seams", "initial candidates", "passes: sort", "passes: select", "passes: apply",
                 "passes: filter", "passes: evaluate", "passes: compact", "handoff copy", "heap", "output", "check",
                 "split", "error"]
        names = [p for p in order if any("phase:" + p in ph[n] for n in ph_rows)]
        for n in ph_rows:  # phases this list does not know yet, after it
            for k in sorted(ph[n]):
                if k.startswith("phase:") and k[6:] not in names:
                    names.append(k[6:])
        lines.append("Where the time goes (ms, wall; `timings_s.phases` of the report, same run):")
        lines.append("")
        lines.append("| phase | " + " | ".join(ph_rows) + " |")
        lines.append("|---|" + "---:|" * len(ph_rows))
        for name in names:
            lines.append(f"| {name} | " + " | ".join(fmt(ph[n].get('phase:' + name), '.2f') for n in ph_rows) + " |")
        lines.append("")
        lines.append("`weld`: exact-position welding (the mesh module's hash-partitioned `weld_exact`); `setup`: fans, quadrics, feature marks; "
                     "`seams`: constrained edges and their penalty planes; `initial candidates`: one evaluated "
                     "collapse per edge; `passes: *`: the batched passes (radix sort, selection walk, checks and "
                     "collapses in parallel vertex ranges, dropping candidates of changed vertices, re-evaluation of "
                     "the changed vertices' edges, dense renumbering of large meshes); `handoff copy`: the state kept for a "
                     "guarded rerun (inputs of 2^18 triangles and more); `heap`: the min-heap to the exact budget; `output`, `check` "
                     "(the result's self-intersection count and the checks of reruns), `split` (faces made separable again).")
    return "\n".join(lines) + "\n"


def write_doc(raw, check=False):
    """Writes docs/simplify.md; with `check`, only compares (exit status 1 and a diff when it differs)."""
    old = DOC.read_text() if DOC.exists() else None
    text = render_doc(raw, old)
    if check:
        if text == old:
            log(f"{DOC} is what this script writes")
            return 0
        import difflib
        sys.stdout.writelines(difflib.unified_diff((old or "").splitlines(True), text.splitlines(True),
                                                   str(DOC), "regenerated"))
        return 1
    DOC.write_text(text)
    log(f"wrote {DOC}")
    return 0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--no-run", action="store_true")
    ap.add_argument("--filter", default=None)
    ap.add_argument("--exe", default=None, help="run this interfere_bench_simplify instead of building build-bench/")
    ap.add_argument("--note", action="append", default=[], metavar="TABLE=TEXT",
                    help="a note on a filtered rerun, printed with its table (Casing, Recognition); kept in the JSON")
    ap.add_argument("--check", action="store_true",
                    help="with --no-run: write nothing, exit 1 with a diff when docs/simplify.md is not what the script writes")
    a = ap.parse_args()
    if a.check and not a.no_run:
        ap.error("--check needs --no-run")
    if not a.no_run:
        build_and_run(a.quick, a.filter, a.exe)
    raw = json.loads(RAW.read_text())
    if a.note:
        for n in a.note:
            table, _, text = n.partition("=")
            raw.setdefault("notes", {})[table] = text
        RAW.write_text(json.dumps(raw, indent=1))
    sys.exit(write_doc(raw, a.check))


if __name__ == "__main__":
    main()
