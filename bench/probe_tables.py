#!/usr/bin/env python3
"""Regenerates the tables of docs/probe.md (issue #5, item 6) on this machine.

Runs build/bench/interfere_bench_probe (Google Benchmark, JSON output), takes the median of the
repetitions, and rewrites the block between the markers
    <!-- BEGIN probe tables (bench/probe_tables.py) -->  ...  <!-- END probe tables -->
with: the generated workpieces and paths, the patch-count table (box / probe volume 8, 33, 100),
the comparison of uniform spatial subdivision, the distance field, the paper's patches and the BVH
(all measured here in one run), the continuous check and clearance costs, the 10^6 / 10^5 scaling
case, and PASS/MISS verdicts for the issue's targets.

Usage: bench/probe_tables.py [--build build] [--doc docs/probe.md] [--repetitions 3] [--json out.json]
Build first:  cmake -B build -DINTERFERE_BUILD_BENCH=ON ... && cmake --build build --target interfere_bench_probe
Standard library only.
"""
import argparse
import datetime
import json
import os
import platform
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BEGIN = "<!-- BEGIN probe tables (bench/probe_tables.py) -->"
END = "<!-- END probe tables -->"
LEVELS_BEGIN = "<!-- BEGIN probe paper levels (bench/probe_tables.py) -->"
LEVELS_END = "<!-- END probe paper levels -->"
CASES = ["sheet", "shell", "saddle"]
HIER = {0: "bvh", 1: "patches", 2: "grid", 3: "distance_field", 4: "brute_force"}
HNAME = {"grid": "uniform spatial subdivision", "distance_field": "distance field",
         "patches": "paper's patches (33x) + boxes", "bvh": "BVH (default)", "brute_force": "all triangles + boxes"}
PAPER_SECONDS = {  # Li, Zhou & Zheng 2008, §4 as quoted by issue #5 (ranges over the three cases)
    "ours": "0.22-1.12 s", "grid": "3.2-11.3 s", "distance_field": "2.4-8.9 s"}


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def google_benchmark(exe, repetitions, out_json, bench_filter=None, env=None, announce=False):
    """exe's Google Benchmark JSON (also left in out_json): `repetitions` runs of each row, only those
    matching bench_filter when given; env: the process environment (None: this one's)."""
    cmd = [exe] + (["--benchmark_filter=" + bench_filter] if bench_filter else []) + [
        "--benchmark_format=json", "--benchmark_out=" + out_json, "--benchmark_out_format=json",
        "--benchmark_repetitions=%d" % repetitions]
    if announce:
        print("running", " ".join(cmd), file=sys.stderr)
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, env=env)
    with open(out_json) as f:
        return json.load(f)


def run_bench(exe, repetitions, out_json):
    return google_benchmark(exe, repetitions, out_json, announce=True)


def collect(data):
    """name -> {'ms': median real time in ms, counters...} over the repetitions (iteration rows)."""
    rows = {}
    for b in data["benchmarks"]:
        if b.get("run_type") == "aggregate":
            continue
        name = b["run_name"] if "run_name" in b else b["name"]
        unit = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b.get("time_unit", "ns")]
        r = rows.setdefault(name, {"times": [], "counters": {}})
        r["times"].append(b["real_time"] * unit)
        for k, v in b.items():
            if isinstance(v, (int, float)) and k not in ("real_time", "cpu_time", "iterations", "repetitions",
                                                         "repetition_index", "threads", "family_index",
                                                         "per_family_instance_index"):
                r["counters"].setdefault(k, []).append(v)
    out = {}
    for name, r in rows.items():
        e = {"ms": statistics.median(r["times"]), "runs": len(r["times"])}
        for k, v in r["counters"].items():
            e[k] = statistics.median(v)
        out[name] = e
    return out


def find(rows, prefix):
    for name, r in rows.items():
        if name.startswith(prefix):
            return r
    raise KeyError(prefix)


def fmt_ms(x):
    return "%.3g" % x if x < 100 else "%.0f" % x


def verdict(ok):
    return "**PASS**" if ok else "**MISS**"


def tables(rows, repetitions):
    L = []
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    L.append("Measured %s on %s, %d logical CPUs (oneTBB default threads), load average %s; median of %d "
             "repetitions; wall time. Regenerate with `bench/probe_tables.py`." %
             (now, cpu_model(), os.cpu_count(), " / ".join("%.1f" % x for x in os.getloadavg()), repetitions))
    L.append("")
    L.append("Probe: radius 5 mm, length 40 mm, holder radius 12 mm, length 30 mm; stand-off 10 mm; every 97th "
             "point has its tip 1 mm below the surface (colliding).")
    L.append("")
    # 1. cases
    L.append("#### Workpieces and paths")
    L.append("")
    L.append("| case | surface | triangles | path points | colliding points | colliding segments | only between samples |")
    L.append("|---|---|---:|---:|---:|---:|---:|")
    surf = {"sheet": "doubly curved sheet", "shell": "cylindrical shell section", "saddle": "saddle"}
    for i, c in enumerate(CASES):
        d = find(rows, "ProbeDiscrete/%d/0/" % i)
        cont = find(rows, "ProbeContinuous/%d/" % i)
        L.append("| %s | %s | %d | %d | %d | %d | %d |" % (c, surf[c], d["triangles"], d["points"], d["colliding_points"],
                                                        cont["colliding_segments"], cont["between_samples"]))
    L.append("")
    # 2. patch count
    L.append("#### Patch count (the paper's hierarchy, box volume = ratio x probe volume)")
    L.append("")
    L.append("| case | ratio 8: patches | tri/patch | ms | ratio 33: patches | tri/patch | ms | ratio 100: patches | tri/patch | ms |")
    L.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for i, c in enumerate(CASES):
        cells = []
        for ratio in (8, 33, 100):
            r = find(rows, "ProbePatches/%d/%d/" % (i, ratio))
            cells += ["%d" % r["patches"], "%.1f" % r["triangles_per_patch"], fmt_ms(r["ms"])]
        L.append("| %s | %s |" % (c, " | ".join(cells)))
    L.append("")
    # 3. comparison
    L.append("#### Comparison of the candidate searches (all path points, decisions only; build time apart)")
    L.append("")
    L.append("| method | " + " | ".join("%s: check ms | build ms" % c for c in CASES) + " | paper (3 cases) |")
    L.append("|---|" + "---:|---:|" * len(CASES) + "---|")
    for h in (2, 3, 1, 0, 4):
        name = HIER[h]
        cells = []
        for i in range(len(CASES)):
            cells.append(fmt_ms(find(rows, "ProbeDiscrete/%d/%d/" % (i, h))["ms"]))
            cells.append(fmt_ms(find(rows, "ProbeBuild/%d/%d/" % (i, h))["ms"]))
        paper = PAPER_SECONDS.get("ours" if name == "patches" else name, "")
        L.append("| %s | %s | %s |" % (HNAME[name], " | ".join(cells), paper))
    L.append("")
    L.append("Every method feeds the same exact cylinder-triangle test and reports the same colliding points "
             "(tests/unit/probe/test_sweep.cpp, HierarchiesAgreeWithBruteForce).")
    L.append("")
    # 4. continuous / clearance
    L.append("#### Continuous check and clearance (BVH)")
    L.append("")
    L.append("| case | discrete ms | + continuous ms | + clearance ms (full report) |")
    L.append("|---|---:|---:|---:|")
    for i, c in enumerate(CASES):
        L.append("| %s | %s | %s | %s |" % (c, fmt_ms(find(rows, "ProbeDiscrete/%d/0/" % i)["ms"]),
                                         fmt_ms(find(rows, "ProbeContinuous/%d/" % i)["ms"]),
                                         fmt_ms(find(rows, "ProbeFull/%d/" % i)["ms"])))
    L.append("")
    # 5. scaling
    s = find(rows, "ProbeScaling")
    L.append("#### Scaling: %d triangles, %d path points (saddle)" % (s["triangles"], s["points"]))
    L.append("")
    L.append("| build ms | discrete ms | continuous ms | total ms | colliding points | colliding segments |")
    L.append("|---:|---:|---:|---:|---:|---:|")
    total = s["ms"]
    L.append("| %s | %s | %s | %s | %d | %d |" % (fmt_ms(1e3 * s["build_seconds"]), fmt_ms(1e3 * s["discrete_seconds"]),
                                                 fmt_ms(1e3 * s["continuous_seconds"]), fmt_ms(total),
                                                 s["colliding_points"], s["colliding_segments"]))
    L.append("")
    # 6. targets
    d2 = find(rows, "ProbeDiscrete/2/0/")["ms"]
    c2 = find(rows, "ProbeContinuous/2/")["ms"]
    L.append("#### Targets (issue #5)")
    L.append("")
    L.append("| target | measured | verdict |")
    L.append("|---|---:|---|")
    L.append("| 2,784 triangles, 2,366 points: all discrete points <= 5 ms (paper: 1.12 s) | %s ms | %s |" %
             (fmt_ms(d2), verdict(d2 <= 5)))
    L.append("| the same including the continuous check <= 50 ms | %s ms | %s |" % (fmt_ms(c2), verdict(c2 <= 50)))
    L.append("| 10^6 triangles, 10^5 points (build + discrete + continuous) <= 2 s on 2 cores | %s ms | %s |" %
             (fmt_ms(total), verdict(total <= 2000 and s["triangles"] >= 9.9e5 and s["points"] >= 1e5)))
    rp = find(rows, "ProbeReplan/2/0/")
    L.append("| re-planning (issue #28): <= 10 ms per colliding point (2,784 triangles, its %d colliding points, tilt "
             "cone 15 degrees, none found: the whole search) | %.3f ms | %s |" %
             (rp["colliding_points"], rp["ms_per_point"], verdict(rp["ms_per_point"] <= 10)))
    return "\n".join(L)


def levels_table(rows, repetitions):
    """The paper's Table 1 levels timed one at a time (ProbePaperLevels rows; issue #28)."""
    L = []
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    L.append("Measured %s on %s, %d logical CPUs, load average %s; median of %d repetitions; one thread; "
             "wall time. Regenerate with `bench/probe_tables.py` (all tables) or `bench/probe_tables.py "
             "--levels-only` (this one)." %
             (now, cpu_model(), os.cpu_count(), " / ".join("%.1f" % x for x in os.getloadavg()), repetitions))
    L.append("")
    L.append("The probe alone (radius 5 mm, length 40 mm; the paper has no holder), patches of box volume 8, 33 "
             "and 100 x the probe volume (Table 1's ratios). Each level runs on what the previous one passed, over all path points: §3.2 the probe's "
             "box against every patch box (an edge of either box meeting a face of the other), §3.3 the "
             "passing patches' triangles against the probe box, §3.4 the three projections (axis, edge 0, a "
             "fixed diameter) of the triangles that passed §3.3; beside it, the exact cylinder-triangle test "
             "on those same triangles. Paths: *standard* = the tables' paths above (stand-off 10 mm = 2 "
             "probe radii, few points get past §3.3), *near* = the same raster at 1 mm stand-off with the "
             "probe tilted 30 degrees about its tip (every point reaches §3.4; most touch the surface). "
             "Counts: tests run / passed.")
    L.append("")
    L.append("| case | path | ratio | patches | points | points reaching §3.4 | §3.2 box ms | tests / passed | §3.3 tri/box ms | "
             "tests / passed | §3.4 projections ms | tests / passed | exact test ms | same triangles / touching |")
    L.append("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for i, c in enumerate(CASES):
        for near, pname in ((0, "standard"), (1, "near")):
            for ratio in (8, 33, 100):
                cells = []
                r1 = find(rows, "ProbePaperLevels/%d/1/%d/%d/" % (i, near, ratio))
                for level in (1, 2, 3, 0):
                    r = find(rows, "ProbePaperLevels/%d/%d/%d/%d/" % (i, level, near, ratio))
                    cells += [fmt_ms(r["ms"]), "%d / %d" % (r["tests"], r["passed"])]
                L.append("| %s | %s | %d | %d | %d | %d | %s |" % (c, pname, ratio, r1["patches"], r1["points"],
                                                                  r1["points_reaching_3"], " | ".join(cells)))
    L.append("")
    return "\n".join(L)


NEAR_BEGIN = "<!-- BEGIN probe near-surface tables (bench/probe_tables.py) -->"
NEAR_END = "<!-- END probe near-surface tables -->"
PAPER_T2 = {"sheet": (576, 31, 872, 0.22), "shell": (1152, 35, 1430, 0.67), "saddle": (2784, 32, 2366, 1.12)}
PAPER_T3 = {"sheet": (0.22, 3.2, 2.4), "shell": (0.67, 5.6, 4.5), "saddle": (1.12, 11.3, 8.9)}


def near_tables(rows, repetitions):
    """Tables 2 and 3 of the paper on near-surface paths, and the issue #28 probe target (ProbeNear*)."""
    L = []
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    L.append("Measured %s on %s, %d logical CPUs (oneTBB default threads), load average %s%s; median of %d repetitions. *wall* = elapsed time per run (includes waiting for a core "
             "on this shared machine), *CPU* = CPU time of the whole process (all threads) per run. Regenerate "
             "with `bench/probe_tables.py`." %
             (now, cpu_model(), os.cpu_count(), " / ".join("%.1f" % x for x in os.getloadavg()),
              " (other builds running)" if os.getloadavg()[0] > 2 else "", repetitions))
    L.append("")
    L.append("Near-surface paths: the rasters of the tables above with the probe tip 2 mm from the surface "
             "(0.4 probe radius; the colliding points keep their tip 1 mm below it) and the axis tilted 20 "
             "degrees about the tip, so the end circle's rim passes ~0.3 mm above a flat surface; probe "
             "(r 5, l 40) and holder (r 12, l 30); pose paths (straight pose interpolation between points). "
             "*Points reaching the exact level*: points with a triangle whose box meets the probe's or the "
             "holder's box (any candidate search must run an exact test there); *exact tests*: the "
             "cylinder-triangle tests the method ran over the path.")
    L.append("")
    L.append("#### Table 2 on near-surface paths (the paper's patches at its ratios)")
    L.append("")
    L.append("| case | triangles | ratio (paper) | patches | tri/patch | points (paper) | points reaching the exact level "
             "| exact tests | colliding points | wall ms | CPU ms | paper |")
    L.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for i, c in enumerate(CASES):
        r = find(rows, "ProbeNear/%d/1/" % i)
        pt = PAPER_T2[c]
        L.append("| %s | %d | %d (%d) | %d | %.1f | %d (%d) | %d | %d | %d | %s | %s | %.2f s |" % (
            c, r["triangles"], r["ratio"], pt[1], r["patches"], r["triangles_per_patch"], r["points"], pt[2],
            r["reaching_exact"], r["candidate_tests"], r["colliding_points"], fmt_ms(r["ms"]),
            fmt_ms(r["process_cpu_ms"]), pt[3]))
    L.append("")
    L.append("#### Table 3 on near-surface paths: the candidate searches compared")
    L.append("")
    L.append("| method | " + " | ".join("%s: wall ms | CPU ms | exact tests | build ms" % c for c in CASES) +
             " | paper (s) |")
    L.append("|---|" + "---:|---:|---:|---:|" * len(CASES) + "---|")
    paper_col = {"patches": 0, "grid": 1, "distance_field": 2}
    for h in (1, 2, 3, 0, 4):
        name = HIER[h]
        cells = []
        for i in range(len(CASES)):
            r = find(rows, "ProbeNear/%d/%d/" % (i, h))
            b = find(rows, "ProbeNearBuild/%d/%d/" % (i, h))
            cells += [fmt_ms(r["ms"]), fmt_ms(r["process_cpu_ms"]), "%d" % r["candidate_tests"], fmt_ms(b["ms"])]
        paper = " / ".join("%.2f" % PAPER_T3[c][paper_col[name]] for c in CASES) if name in paper_col else ""
        label = HNAME[name].replace("(33x)", "(paper ratios)")
        L.append("| %s | %s | %s |" % (label, " | ".join(cells), paper))
    L.append("")
    L.append("| case | uniform subdivision / patches: ours (wall, CPU) | paper | distance field / patches: ours "
             "(wall, CPU; build apart) | paper |")
    L.append("|---|---:|---:|---:|---:|")
    for i, c in enumerate(CASES):
        p = find(rows, "ProbeNear/%d/1/" % i)
        g = find(rows, "ProbeNear/%d/2/" % i)
        d = find(rows, "ProbeNear/%d/3/" % i)
        t3 = PAPER_T3[c]
        L.append("| %s | %.2f, %.2f | %.1f | %.2f, %.2f | %.1f |" % (
            c, g["ms"] / p["ms"], g["process_cpu_ms"] / p["process_cpu_ms"], t3[1] / t3[0],
            d["ms"] / p["ms"], d["process_cpu_ms"] / p["process_cpu_ms"], t3[2] / t3[0]))
    L.append("")
    L.append("#### Target (issue #28): the 2,784-triangle workpiece, 2,366 points within 2 probe radii")
    L.append("")
    L.append("| target | wall | CPU (all threads) | verdict |")
    L.append("|---|---:|---:|---|")
    d = find(rows, "ProbeNear/2/0/")
    cc = find(rows, "ProbeNearContinuous/2/")
    for what, r, limit in (("probe + holder, all discrete points <= 5 ms (BVH)", d, 5),
                           ("the same including the check between points <= 50 ms (%d colliding segments, %d "
                            "unresolved)" % (cc["colliding_segments"], cc["unresolved_segments"]), cc, 50)):
        wall_ok, cpu_ok = r["ms"] <= limit, r["process_cpu_ms"] <= limit
        v = verdict(wall_ok) if wall_ok == cpu_ok else (
            "**PASS** in CPU time, **MISS** in wall time under this load" if cpu_ok else "**MISS**")
        L.append("| %s | %s ms | %s ms | %s |" % (what, fmt_ms(r["ms"]), fmt_ms(r["process_cpu_ms"]), v))
    L.append("")
    return "\n".join(L)


CELL_BEGIN = "<!-- BEGIN probe full cell (bench/probe_tables.py) -->"
CELL_END = "<!-- END probe full cell -->"


def run_cell_bench(build, points, out_json, repetitions=3):
    exe = os.path.join(build, "bench", "interfere_bench_cell")
    if not os.path.exists(exe):
        return None
    return google_benchmark(exe, repetitions, out_json, env=dict(os.environ, INTERFERE_CELL_POINTS=str(points)))


def cell_table(data):
    """The full-cell target of issue #28 (interfere_bench_cell: CellFull rows, medians of the repetitions)."""
    rows = collect(data)
    d = find(rows, "BM_CellFull/0")
    c = find(rows, "BM_CellFull/1")
    L = []
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    L.append("Measured %s on %s, %d logical CPUs (oneTBB default threads), load average %s%s; median of %d runs. Regenerate with `bench/probe_tables.py --cell-only --cell-points N`." %
             (now, cpu_model(), os.cpu_count(), " / ".join("%.1f" % x for x in os.getloadavg()),
              " (other builds running)" if os.getloadavg()[0] > 2 else "", c["runs"]))
    L.append("")
    L.append("The cell: %d bodies, %d triangles (7 link meshes, %d triangles together; workpiece %d; the clamp "
             "and two posts), %d path points (raster lines of 1,000 points, x = 350..700 mm, at y = -150..150 mm; "
             "one line at y = 0 below 2,000 points; joints by the numerical inverse kinematics, untimed)." % (
                 c["bodies"], c["triangles"], c["link_triangles"], c["workpiece_triangles"], c["points"]))
    L.append("")
    L.append("| run | scene build s | at the points s | between points s | total wall s | process CPU s | colliding "
             "points | colliding / unresolved segments | middles checked between points (of which by the scene engine) |")
    L.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, r in (("points only", d), ("points + between points (conservative)", c)):
        L.append("| %s | %.3g | %.3g | %.3g | %.3g | %.3g | %d | %d / %d | %d (%d) |" % (
            name, r["scene_seconds"], r["discrete_seconds"], r["between_seconds"], r["ms"] / 1e3,
            r["process_cpu_seconds"], r["colliding_points"], r["colliding_segments"], r["unresolved_segments"],
            r["between_frames"], r.get("between_engine_frames", 0)))
    L.append("")
    if "certificates" in c:
        L.append("Both rows use `check_cell_path` (robot/cell.h): certified distances carried across path points; "
                 "%d certificates (%d of them BVH distance queries, the others bounding spheres), %d (pair, point) "
                 "decisions left to the scene engine, %d of %d segments proven clear by the points' certificates "
                 "alone (no middle); certificates took %.3g s of the points' time." % (
                     c["certificates"], c["bvh_queries"], c["engine_pair_frames"], c["certified_segments"],
                     c["points"] - 1, c["certify_seconds"]))
        L.append("")
    scale = 1e5 / c["points"]
    total = c["ms"] / 1e3 * scale
    L.append("| target | measured | verdict |")
    L.append("|---|---:|---|")
    if c["points"] == 100000:
        measured = "%.3g s for 10^5 points (%.2fx the target; median of %d runs, wall clock)" % (
            total, total / 5, c["runs"])
    else:
        measured = ("%.3g s for %d points: %.3g s for 10^5 at this rate (linear extrapolation; %.2fx "
                    "the target)" % (c["ms"] / 1e3, c["points"], total, total / 5))
    L.append("| 6R arm, 7 link meshes of ~5k triangles, fixtures, a 10^6-triangle workpiece, 10^5 points "
             "including between points <= 5 s | %s | %s |" % (measured, verdict(total <= 5)))
    L.append("")
    return "\n".join(L)


def replace_block(doc, begin, end, block):
    if begin not in doc or end not in doc:
        return None
    head, rest = doc.split(begin, 1)
    _, tail = rest.split(end, 1)
    return head + begin + "\n" + block + "\n" + end + tail


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--doc", default=os.path.join(ROOT, "docs", "probe.md"))
    ap.add_argument("--repetitions", type=int, default=3)
    ap.add_argument("--json", default=None, help="keep the raw benchmark JSON here")
    ap.add_argument("--from-json", default=None, help="do not run: use this raw benchmark JSON")
    ap.add_argument("--cell-points", type=int, default=1000,
                    help="path points of the full-cell benchmark (interfere_bench_cell; 10^5 is the target's size)")
    ap.add_argument("--cell-only", action="store_true", help="run only the full-cell benchmark and rewrite its block")
    ap.add_argument("--near-only", action="store_true",
                    help="run only the near-surface rows (Tables 2-3, issue #28) and rewrite only their block")
    ap.add_argument("--levels-only", action="store_true",
                    help="run only the paper's-levels rows and rewrite only their table (issue #28)")
    a = ap.parse_args()
    def probe_rows(bench_filter, default_json):
        """interfere_bench_probe's rows matching bench_filter (medians over the repetitions)."""
        out = a.json or os.path.join(a.build, "bench", default_json)
        return collect(google_benchmark(os.path.join(a.build, "bench", "interfere_bench_probe"), a.repetitions, out,
                                        bench_filter))

    def rewrite_block(begin, end, block, what):
        """Replaces the doc's block between the markers (written to a temporary file, then moved)."""
        with open(a.doc) as f:
            new = replace_block(f.read(), begin, end, block)
        if new is None:
            sys.exit("%s: %s markers not found" % (a.doc, what))
        with open(a.doc + ".tmp", "w") as f:
            f.write(new)
        os.replace(a.doc + ".tmp", a.doc)
        print(block)

    if a.levels_only:
        rewrite_block(LEVELS_BEGIN, LEVELS_END,
                      levels_table(probe_rows("ProbePaperLevels", "probe_levels_bench.json"), a.repetitions),
                      "paper levels")
        return
    if a.cell_only:
        data = run_cell_bench(a.build, a.cell_points, os.path.join(a.build, "bench", "probe_cell_bench.json"),
                              a.repetitions)
        if data is None:
            sys.exit("missing interfere_bench_cell (needs urdfdom)")
        rewrite_block(CELL_BEGIN, CELL_END, cell_table(data), "full cell")
        return
    if a.near_only:
        rewrite_block(NEAR_BEGIN, NEAR_END,
                      near_tables(probe_rows("ProbeNear", "probe_near_bench.json"), a.repetitions), "near-surface")
        return
    if a.from_json:
        with open(a.from_json) as f:
            data = json.load(f)
    else:
        exe = os.path.join(a.build, "bench", "interfere_bench_probe")
        if not os.path.exists(exe):
            sys.exit("missing %s: configure with -DINTERFERE_BUILD_BENCH=ON and build interfere_bench_probe" % exe)
        out = a.json or os.path.join(a.build, "bench", "probe_bench.json")
        data = run_bench(exe, a.repetitions, out)
    block = tables(collect(data), a.repetitions)
    with open(a.doc) as f:
        doc = f.read()
    if BEGIN not in doc or END not in doc:
        sys.exit("%s: markers not found" % a.doc)
    head, rest = doc.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    new = head + BEGIN + "\n" + block + "\n" + END + tail
    rows = collect(data)
    if any(k.startswith("ProbePaperLevels/") for k in rows):
        new = replace_block(new, LEVELS_BEGIN, LEVELS_END, levels_table(rows, a.repetitions)) or new
    if any(k.startswith("ProbeNear/") for k in rows):
        near = near_tables(rows, a.repetitions)
        new2 = replace_block(new, NEAR_BEGIN, NEAR_END, near)
        if new2 is None:
            sys.exit("%s: near-surface markers not found" % a.doc)
        new = new2
        print(near)
    tmp = a.doc + ".tmp"
    with open(tmp, "w") as f:
        f.write(new)
    os.replace(tmp, a.doc)
    print(block)


if __name__ == "__main__":
    main()
