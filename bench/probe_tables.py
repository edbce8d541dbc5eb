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


def run_bench(exe, repetitions, out_json):
    cmd = [exe, "--benchmark_format=json", "--benchmark_out=" + out_json, "--benchmark_out_format=json",
           "--benchmark_repetitions=%d" % repetitions]
    print("running", " ".join(cmd), file=sys.stderr)
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(out_json) as f:
        return json.load(f)


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
    ap.add_argument("--levels-only", action="store_true",
                    help="run only the paper's-levels rows and rewrite only their table (issue #28)")
    a = ap.parse_args()
    if a.levels_only:
        exe = os.path.join(a.build, "bench", "interfere_bench_probe")
        out = a.json or os.path.join(a.build, "bench", "probe_levels_bench.json")
        cmd = [exe, "--benchmark_filter=ProbePaperLevels", "--benchmark_format=json", "--benchmark_out=" + out,
               "--benchmark_out_format=json", "--benchmark_repetitions=%d" % a.repetitions]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        with open(out) as f:
            block = levels_table(collect(json.load(f)), a.repetitions)
        with open(a.doc) as f:
            new = replace_block(f.read(), LEVELS_BEGIN, LEVELS_END, block)
        if new is None:
            sys.exit("%s: paper levels markers not found" % a.doc)
        with open(a.doc + ".tmp", "w") as f:
            f.write(new)
        os.replace(a.doc + ".tmp", a.doc)
        print(block)
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
    tmp = a.doc + ".tmp"
    with open(tmp, "w") as f:
        f.write(new)
    os.replace(tmp, a.doc)
    print(block)


if __name__ == "__main__":
    main()
