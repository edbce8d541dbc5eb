#!/usr/bin/env python3
"""Regenerates the tables of docs/scene-benchmarks.md (issue #24, items 8 and 9) on this machine.

    python3 bench/scene_tables.py                  # build, run everything (several minutes), write the doc
    python3 bench/scene_tables.py --no-build       # use the existing build-bench/ and build/ executables
    python3 bench/scene_tables.py --quick          # 1,000-body assembly, 1 frame, 1 repetition: a smoke run
    python3 bench/scene_tables.py --report-only    # rewrite the doc from docs/scene-benchmarks.json

Runs, all on this machine in one session so that the peers and the engine share its state:
  1. interfere_bench_scene (Google Benchmark, bench/bench_scene.cpp + bench/peer_fcl_scene.cpp): the
     generated 10,000-body assembly (all pairs hard, and hard + clearance 0.1 mm) from meshes in memory,
     FCL 0.7's DynamicAABBTreeCollisionManager + collide() on the same bodies, the 1,000-body moving scene;
     --repetitions runs each, the tables give medians.
  2. interfere_scene_run assembly: the same assembly in a process of its own, for its peak resident set.
  3. Whole process: interfere_scene_run spheres writes two 1M-triangle binary STL files (bumpy spheres
     overlapping about 1 % of their triangles); then `interfere clash A.stl B.stl --json out.json`,
     interfere_peer_process_cgal and interfere_peer_process_fcl, each timed as a separate process
     (wall clock from here, --process-repetitions times, interleaved, after one untimed warm-up each).
Writes docs/scene-benchmarks.json (raw) and the block between the markers of docs/scene-benchmarks.md
(the text outside the markers is kept). Standard library only.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(Path(__file__).resolve().parent))
from gbench_json import google_benchmark_json  # noqa: E402
from run_benchmarks import machine_description  # noqa: E402

DOC = ROOT / "docs" / "scene-benchmarks.md"
RAW = ROOT / "docs" / "scene-benchmarks.json"
BEGIN = "<!-- BEGIN scene tables (bench/scene_tables.py) -->"
END = "<!-- END scene tables -->"
GB = 1e9

# The targets (issue #24, item 9; "on 2 cores").
TARGET_ASSEMBLY_S = 1.0
TARGET_FCL_RATIO = 10.0
TARGET_FPS = 200.0
TARGET_PROCESS_S = 0.150
TARGET_PEAK_BYTES = 3 * GB


def log(msg: str) -> None:
    print(f"[scene_tables] {msg}", file=sys.stderr, flush=True)


def run(cmd, **kw) -> subprocess.CompletedProcess:
    log("$ " + " ".join(str(c) for c in cmd))
    return subprocess.run([str(c) for c in cmd], cwd=ROOT, **kw)


# ----------------------------------------------------------------------------- build
def build(build_dir: Path, cli_build: Path, jobs: int) -> None:
    # The generator is CMake's default, as bench/run_benchmarks.py configures the same build-bench/.
    run(["cmake", "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release", "-DINTERFERE_BUILD_BENCH=ON",
         "-DINTERFERE_BUILD_TESTS=OFF", "-DINTERFERE_BUILD_CLI=OFF", "-DINTERFERE_BUILD_PYTHON=OFF"], check=True)
    run(["nice", "cmake", "--build", build_dir, "-j", str(jobs), "--target", "interfere_bench_scene",
         "interfere_scene_run", "interfere_peer_process_fcl", "interfere_peer_process_cgal"], check=True)
    if (cli_build / "CMakeCache.txt").exists():  # the CLI of the whole-process run: the main build
        if run(["nice", "cmake", "--build", cli_build, "-j", str(jobs), "--target", "interfere"]).returncode:
            log("the interfere CLI did not build: the whole-process row of interfere is left out")


# ----------------------------------------------------------------------------- runs
def run_google_benchmark(exe: Path, repetitions: int, env: dict, bench_filter: str | None) -> dict:
    return google_benchmark_json(run, exe, repetitions, env, bench_filter)


def medians(data: dict) -> dict:
    """run_name -> {'ms': median real time, 'reps': n, counters: median} over the iteration rows."""
    rows: dict[str, list[dict]] = {}
    for b in data.get("benchmarks", []):
        if b.get("run_type") == "aggregate":
            continue
        name = re.sub(r"/(iterations:\d+|repeats:\d+|real_time)", "", b.get("run_name", b["name"]))
        rows.setdefault(name, []).append(b)
    out = {}
    skip = {"name", "run_name", "run_type", "family_index", "per_family_instance_index", "repetitions",
            "repetition_index", "threads", "iterations", "real_time", "cpu_time", "time_unit", "label",
            "error_occurred", "error_message", "aggregate_name", "aggregate_unit"}
    for name, bs in rows.items():
        errors = [b.get("error_message", "error") for b in bs if b.get("error_occurred")]
        bs = [b for b in bs if not b.get("error_occurred")]
        if not bs:
            out[name] = {"error": errors[0] if errors else "no result"}
            continue
        scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[bs[0].get("time_unit", "ns")]
        r = {"ms": statistics.median(b["real_time"] * scale for b in bs),
             "ms_min": min(b["real_time"] * scale for b in bs), "ms_max": max(b["real_time"] * scale for b in bs),
             "reps": len(bs)}
        for k in bs[0]:
            if k not in skip and isinstance(bs[0][k], (int, float)):
                r[k] = statistics.median(b.get(k, 0) for b in bs)
        out[name] = r
    return out


def run_json(cmd, env=None) -> dict:
    p = run(cmd, check=True, env=env, stdout=subprocess.PIPE, text=True)
    return json.loads(p.stdout)


def whole_process(build_dir: Path, cli: Path, reps: int, peer_reps: int, triangles: str) -> dict:
    res: dict = {"triangles_per_part": triangles, "repetitions": reps, "peer_repetitions": peer_reps,
                 "programs": {}}
    with tempfile.TemporaryDirectory(prefix="interfere_scene_") as tmp:
        files = run_json([build_dir / "bench" / "interfere_scene_run", "spheres", tmp, triangles])
        res["files"] = {k: files[k] for k in ("tris_a", "tris_b")}
        a, b = files["a"], files["b"]
        res["file_bytes"] = os.path.getsize(a) + os.path.getsize(b)
        report = Path(tmp) / "out.json"
        programs = {
            "interfere": [cli, "clash", a, b, "--json", report],
            "cgal": [build_dir / "bench" / "interfere_peer_process_cgal", a, b],
            "fcl": [build_dir / "bench" / "interfere_peer_process_fcl", a, b],
        }
        programs = {k: v for k, v in programs.items() if Path(v[0]).exists()}
        for name in programs:
            res["programs"][name] = {"command": " ".join(Path(str(c)).name if i == 0 else
                                                          (Path(str(c)).name if str(c).startswith(tmp) else str(c))
                                                          for i, c in enumerate(programs[name])),
                                     "wall_s": [], "reports": []}
        # Round 0 warms the page cache and the loader for interfere (not counted); the peers take
        # seconds, where a cold start is noise, and run peer_reps times.
        for rep in range(reps + 1):
            for name, cmd in programs.items():
                if name != "interfere" and not 1 <= rep <= peer_reps:
                    continue
                if report.exists():
                    report.unlink()
                t0 = time.perf_counter()
                p = subprocess.run([str(c) for c in cmd], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                   text=True)
                wall = time.perf_counter() - t0
                ok = p.returncode in (0, 1) if name == "interfere" else p.returncode == 0
                entry = res["programs"][name]
                if not ok:
                    entry["error"] = f"exit status {p.returncode}: {p.stderr.strip()[-400:]}"
                    log(f"{name} failed: {entry['error']}")
                    continue
                if rep == 0:
                    continue
                entry["wall_s"].append(wall)
                if name == "interfere":
                    try:
                        j = json.loads(report.read_text())
                        res_ = j.get("result") if isinstance(j.get("result"), dict) else {}
                        pairs = res_.get("pairs")
                        if isinstance(pairs, list):
                            pairs = len(pairs)
                        if not isinstance(pairs, (int, float)):
                            pairs = (res_.get("cross_pairs") or 0) + (res_.get("touch_pairs") or 0) or None
                        entry["reports"].append({"timings_s": j.get("timings_s"), "verdict": j.get("verdict"),
                                                 "pairs": pairs})
                    except (OSError, ValueError) as e:
                        entry["reports"].append({"error": str(e)})
                else:
                    entry["reports"].append(json.loads(p.stdout))
        for entry in res["programs"].values():
            if entry["wall_s"]:
                entry["median_s"] = statistics.median(entry["wall_s"])
    return res


def scene_file_process(build_dir: Path, cli: Path, reps: int, bodies: str) -> dict:
    """`interfere clash --scene scene.json` on the generated assembly written as users give it (five
    binary STL part files, a scene file of every body), timed as a fresh process, its pair counts
    checked against the construction's."""
    res: dict = {"repetitions": reps, "wall_s": [], "reports": []}
    with tempfile.TemporaryDirectory(prefix="interfere_scene_file_") as tmp:
        info = run_json([build_dir / "bench" / "interfere_scene_run", "scene-file", tmp, bodies])
        res["construction"] = info
        report = Path(tmp) / "out.json"
        cmd = [str(cli), "clash", "--scene", info["scene"], "--json", str(report)]
        res["command"] = f"interfere clash --scene scene.json --json out.json"
        for rep in range(reps + 1):  # round 0 warms the page cache (not counted)
            if report.exists():
                report.unlink()
            t0 = time.perf_counter()
            p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            wall = time.perf_counter() - t0
            if p.returncode not in (0, 1):
                res["error"] = f"exit status {p.returncode}: {p.stderr.strip()[-400:]}"
                log(f"scene file run failed: {res['error']}")
                return res
            if rep == 0:
                continue
            res["wall_s"].append(wall)
            j = json.loads(report.read_text())
            count = lambda test, v: sum(1 for q in j.get("pairs", []) if q.get("test") == test and q.get("verdict") == v)
            res["reports"].append({"timings_s": j.get("timings_s"), "summary": j.get("summary"),
                                   "clash_pairs": count("hard", "clash"), "contact_pairs": count("hard", "contact"),
                                   "gap_pairs": count("clearance", "clearance")})
        res["median_s"] = statistics.median(res["wall_s"])
    return res


# ----------------------------------------------------------------------------- report
def verdict(ok) -> str:
    return "—" if ok is None else ("**PASS**" if ok else "**MISS**")


def ms(v) -> str:
    if v is None:
        return "—"
    return f"{v / 1000:.2f} s" if v >= 10000 else (f"{v:.0f} ms" if v >= 100 else f"{v:.1f} ms")


def secs(v) -> str:
    return "—" if v is None else ms(v * 1000)


def n(v) -> str:
    return "—" if v is None else f"{int(round(v)):,}"


def median_split(reports: list, key: str):
    vals = [r["timings_s"][key] for r in reports if isinstance(r.get("timings_s"), dict) and key in r["timings_s"]
            and isinstance(r["timings_s"][key], (int, float))]
    return statistics.median(vals) if vals else None


def make_block(raw: dict) -> tuple[str, list]:
    m, gb, run_ = raw["machine"], raw["google_benchmark"], raw.get("assembly_process")
    wp = raw.get("whole_process") or {}
    L: list[str] = []
    targets: list = []
    thr = raw["settings"]["threads"]
    hard = gb.get(f"Scene/assembly/interfere/hard/threads:{thr}")
    both = gb.get(f"Scene/assembly/interfere/hard+clearance/threads:{thr}")
    fcl = gb.get("Scene/assembly/fcl/collide_all")
    mov = gb.get(f"Scene/moving/interfere/hard/threads:{thr}")
    mov_asm = gb.get(f"Scene/moving_assembly/interfere/hard/threads:{thr}")

    def ok_row(b):
        return b is not None and "error" not in b

    L.append(f"Measured {m['date_utc']} on {m.get('cpu_model', '?')}, {m.get('nproc', '?')} logical CPUs "
             f"(interfere on {thr} threads, the peers single-threaded as they are), load average "
             f"{m.get('loadavg_at_start', '?')} at the start; medians of {raw['settings']['repetitions']} "
             f"repetition(s) (Google Benchmark rows) and of {wp.get('repetitions', '—')} runs (whole process); wall "
             f"time. Regenerate with `python3 bench/scene_tables.py`"
             + (" (this run: `--quick`, a smaller scene: the targets are not judged on it)" if raw["settings"].get("quick") else "")
             + ". Timings on this shared 2-core virtual machine vary by ±10–30 % between runs; "
               "compare rows of one run only.")
    parts = raw.get("parts") or {}
    if len({p.get("date_utc") for p in parts.values()}) > 1:  # parts from different runs
        names = {"bench": "Google Benchmark rows", "memory": "peak memory", "process": "whole process",
                 "scenefile": "scene file process"}
        L.append("")
        L.append("Parts measured in different runs: " + "; ".join(
            f"{names.get(k, k)} {v.get('date_utc')} (load average {v.get('loadavg')})" for k, v in sorted(parts.items())) + ".")
    L.append("")

    # ---- targets
    L.append("### Targets")
    L.append("")
    L.append("| Target (issue #24, item 9) | Measured | Verdict |")
    L.append("|---|---|---|")
    full = not raw["settings"].get("quick")

    def target(text, measured, ok):
        ok = ok if full else None
        targets.append({"target": text, "measured": measured, "pass": ok})
        L.append(f"| {text} | {measured} | {verdict(ok)} |")

    bodies = n(both.get("bodies")) if ok_row(both) else "—"
    tris = n(both.get("triangles")) if ok_row(both) else "—"
    t_both = both["ms"] / 1000 if ok_row(both) else None
    target(f"{bodies}-body assembly ({tris} triangles), all pairs hard + clearance 0.1 mm, from meshes in memory: "
           f"≤ {TARGET_ASSEMBLY_S:g} s", secs(t_both), None if t_both is None else t_both <= TARGET_ASSEMBLY_S)
    ratio = fcl["ms"] / both["ms"] if ok_row(fcl) and ok_row(both) else None
    target("FCL 0.7 `DynamicAABBTreeCollisionManager` + `collide` (all contacts) on the same bodies: interfere "
           f"≥ {TARGET_FCL_RATIO:g}× faster",
           "—" if ratio is None else f"{ratio:.2f}× (FCL {ms(fcl['ms'])}, interfere {ms(both['ms'])})",
           None if ratio is None else ratio >= TARGET_FCL_RATIO)
    fps = mov.get("frames_per_second") if ok_row(mov) else None
    target(f"{n(mov.get('bodies')) if ok_row(mov) else '—'} moving bodies (random small rigid motions every frame; "
           "apart by clearances, a few near pairs touching or clashing in some frames): "
           f"≥ {TARGET_FPS:g} frames/s", "—" if fps is None else f"{fps:.3g} frames/s",
           None if fps is None else fps >= TARGET_FPS)
    ip = (wp.get("programs") or {}).get("interfere", {})
    t_proc = ip.get("median_s")
    target("Whole process, `interfere clash A.stl B.stl --json out.json` on two 1M-triangle binary STL files: "
           f"≤ {TARGET_PROCESS_S * 1000:g} ms", secs(t_proc) + (f" ({ip['error']})" if ip.get("error") else ""),
           None if t_proc is None else t_proc <= TARGET_PROCESS_S)
    peak = run_.get("peak_rss_bytes") if run_ and "error" not in run_ else None
    target(f"Peak memory of the {n(run_.get('triangles')) if run_ else '—'}-triangle scene (own process): ≤ 3 GB",
           "—" if peak is None else f"{peak / GB:.2f} GB", None if peak is None else peak <= TARGET_PEAK_BYTES)
    L.append("")

    # ---- assembly
    L.append("### The assembly (all pairs)")
    L.append("")
    L.append("| Run | Time (median) | min–max | Candidate pairs | Core runs | Clashing body pairs | Contact body pairs | "
             "Clearance items | Undecided | prepare / broad / narrow |")
    L.append("|---|---|---|---|---|---|---|---|---|---|")
    for label, b in ((f"interfere, hard ({thr} threads)", hard), (f"interfere, hard + clearance 0.1 mm ({thr} threads)", both)):
        if not ok_row(b):
            L.append(f"| {label} | {b.get('error') if b else 'not run'} | | | | | | | | |")
            continue
        L.append(f"| {label} | {ms(b['ms'])} | {ms(b['ms_min'])}–{ms(b['ms_max'])} | {n(b.get('candidate_pairs'))} | "
                 f"{n(b.get('core_runs'))} | "
                 f"{n(b.get('clash_pairs'))} | {n(b.get('contact_pairs'))} | {n(b.get('clearances'))} | "
                 f"{n(b.get('undecided'))} | {secs(b.get('prepare_s'))} / {secs(b.get('broad_s'))} / "
                 f"{secs(b.get('narrow_s'))} |")
    if ok_row(fcl):
        L.append(f"| FCL 0.7, DynamicAABBTree + collide (1 thread) | {ms(fcl['ms'])} | {ms(fcl['ms_min'])}–"
                 f"{ms(fcl['ms_max'])} | {n(fcl.get('fcl_candidates'))} | {n(fcl.get('fcl_candidates'))} | "
                 f"{n(fcl.get('fcl_pairs'))} (colliding) | — | — | — | — |")
    elif fcl:
        L.append(f"| FCL 0.7 | {fcl.get('error')} | | | | | | | | |")
    L.append("")
    if ok_row(both):
        L.append("Exactness against the assembly's construction (scene/generate.h knows which body pairs it made "
                 "overlap, touch and stand apart by 0.05 mm): ")
        L.append(f"clashing pairs missing {n(both.get('gt_clash_missing'))}, extra {n(both.get('gt_clash_extra'))}; "
                 f"contact pairs missing {n(both.get('gt_contact_missing'))}, extra {n(both.get('gt_contact_extra'))}; "
                 f"clearance-test gaps missing {n(both.get('gt_gap_missing'))}, extra {n(both.get('gt_gap_extra'))}.")
        L.append("")
    if ok_row(fcl):
        L.append(f"FCL against the exact result (the hard test's body pairs with verdict clash: "
                 f"{n(fcl.get('exact_clash_pairs'))}): FCL reports {n(fcl.get('fcl_pairs'))} colliding pairs "
                 f"({n(fcl.get('fcl_triangle_pairs'))} triangle pairs); **false pairs {n(fcl.get('false_pairs'))}** "
                 f"({n(fcl.get('false_contact'))} only touching — designed contacts FCL cannot tell from clashes — and "
                 f"{n(fcl.get('false_clear'))} apart), **missed pairs {n(fcl.get('missed_pairs'))}**.")
        L.append("")

    # ---- moving
    L.append("### Moving bodies")
    L.append("")
    if ok_row(mov) or ok_row(mov_asm):
        L.append("| Run | Frames | Time (median) | Frames/s | Candidate pairs per frame | Frames with a clash | "
                 "Clashes per frame | Contacts per frame | prepare / broad / narrow |")
        L.append("|---|---|---|---|---|---|---|---|---|")
        for label, b in ((f"moving cells (near pairs: {n(mov.get('near_pairs')) if mov else '—'})", mov),
                         ("the bolted assembly, every body moving (the first version)", mov_asm)):
            if not ok_row(b):
                L.append(f"| {label} | {b.get('error') if b else 'not run'} | | | | | | | |")
                continue
            L.append(f"| interfere, {label}: {n(b.get('bodies'))} bodies, {n(b.get('triangles'))} triangles, hard "
                     f"({thr} threads) | {n(b.get('frames'))} | {ms(b['ms'])} | {b.get('frames_per_second', 0):.3g} | "
                     f"{b.get('candidates_per_frame', 0):.1f} | {n(b.get('frames_with_clash'))} | "
                     f"{b.get('clashes_per_frame', 0):.1f} | {b.get('contacts_per_frame', 0):.1f} | "
                     f"{secs(b.get('prepare_s'))} / {secs(b.get('broad_s'))} / {secs(b.get('narrow_s'))} |")
    else:
        L.append(f"Not measured: {mov.get('error') if mov else 'not run'}.")
    L.append("")

    # ---- whole process
    L.append("### Whole process: files to report")
    L.append("")
    if wp.get("programs"):
        f = wp.get("files", {})
        L.append(f"Two binary STL files of {n(f.get('tris_a'))} and {n(f.get('tris_b'))} triangles "
                 f"({wp.get('file_bytes', 0) / 1e6:.0f} MB together), each program a fresh process, wall time "
                 f"measured from the calling script: interfere {wp['repetitions']} runs after one untimed warm-up, "
                 f"each peer {wp.get('peer_repetitions', wp['repetitions'])} runs, interleaved.")
        L.append("")
        L.append("| Program | Median | min–max | read | trees / boxes (+ statistics) | query | Triangle pairs |")
        L.append("|---|---|---|---|---|---|---|")
        for name, label in (("interfere", "`interfere clash A.stl B.stl --json out.json` (2 threads)"),
                            ("cgal", "CGAL 5.5 `box_intersection_d` + `do_intersect` (1 thread)"),
                            ("fcl", "FCL 0.7 `BVHModel<OBBRSS>` + `collide` (1 thread)")):
            e = wp["programs"].get(name)
            if not e:
                continue
            if not e.get("wall_s"):
                L.append(f"| {label} | {e.get('error', 'no run')} | | | | | |")
                continue
            reps = e["reports"]
            if name == "interfere":
                keys = {k for r in reps if isinstance(r.get("timings_s"), dict) for k in r["timings_s"]}
                read = median_split(reps, "read")
                build_ = median_split(reps, "build")
                query = median_split(reps, "query")
                pairs = next((r.get("pairs") for r in reps if r.get("pairs") is not None), None)
                extra = sorted(keys - {"read", "build", "query", "total"})
                note = (" (other report timings: " + ", ".join(f"{k} {secs(median_split(reps, k))}" for k in extra) + ")"
                        if extra else "")
            else:
                read = statistics.median(r["read_s"] for r in reps)
                build_ = statistics.median(r["build_s"] for r in reps)
                query = statistics.median(r["query_s"] for r in reps)
                pairs = reps[0].get("pairs")
                note = ""
            L.append(f"| {label} | {secs(e['median_s'])} | {secs(min(e['wall_s']))}–{secs(max(e['wall_s']))} | "
                     f"{secs(read)} | {secs(build_)} | {secs(query)}{note} | {n(pairs)} |")
        L.append("")
        L.append("The split columns come from each program's own report (interfere: the JSON report's `timings_s`; "
                 "the peers print theirs); the median column is the whole process as a user runs it, start-up, "
                 "reading, output and exit included. The peers read the STL with the minimal reader of "
                 "`bench/peer_stl.h` (a triangle soup, no welding, nothing checked but the size).")
    else:
        L.append("Not measured.")
    L.append("")

    # ---- the assembly from files
    sf = raw.get("scene_file_process")
    L.append("### The assembly from files, as a user runs it")
    L.append("")
    if sf and "error" not in sf and sf.get("reports"):
        c, rep = sf["construction"], sf["reports"][-1]
        sm = rep.get("summary") or {}
        ts = [r.get("timings_s") or {} for r in sf["reports"]]
        def med(key):
            v = [t[key] for t in ts if isinstance(t.get(key), (int, float))]
            return statistics.median(v) if v else None
        splits = ", ".join(f"{k} {secs(med(k))}" for k in ("prepare", "broad", "narrow", "total") if med(k) is not None)
        L.append(f"The same assembly written as a user would give it: its five part meshes as binary STL files and a "
                 f"scene file listing all {n(c['bodies'])} bodies ({n(c['triangles'])} triangles) with their poses, "
                 f"tests `hard` and `clearance` 0.1 mm; `{sf['command']}` as a fresh process, "
                 f"{len(sf['wall_s'])} runs after one untimed warm-up: **median {secs(sf['median_s'])}** "
                 f"({secs(min(sf['wall_s']))}–{secs(max(sf['wall_s']))}; the report's own timings: {splits or '—'}), "
                 f"{n(sm.get('core_runs'))} core runs for {n(sm.get('candidate_pairs'))} candidate pairs. Body pairs "
                 f"against the construction: clashing {n(rep['clash_pairs'])} (construction {n(c['clash_pairs'])}), "
                 f"contact {n(rep['contact_pairs'])} ({n(c['contact_pairs'])}), clearance gaps "
                 f"{n(rep['gap_pairs'])} ({n(c['gap_pairs'])}).")
    else:
        L.append(f"Not measured: {sf.get('error') if sf else 'not run'}.")
    L.append("")

    # ---- memory
    L.append("### Peak memory (own process)")
    L.append("")
    if run_ and "error" not in run_:
        L.append(f"`interfere_scene_run assembly {run_.get('bodies')} {run_.get('segments')} {run_.get('threads')}`: "
                 f"{n(run_.get('bodies'))} bodies, {n(run_.get('triangles'))} triangles, hard + clearance 0.1 mm, "
                 f"one run: clash_scene {secs(run_.get('clash_s'))} (prepare {secs(run_.get('prepare_s'))}, broad "
                 f"{secs(run_.get('broad_s'))}, narrow {secs(run_.get('narrow_s'))}); peak resident set "
                 f"**{run_['peak_rss_bytes'] / GB:.2f} GB** (VmHWM; {run_['peak_rss_after_generate_bytes'] / GB:.3f} GB "
                 "after generating the scene, whose bodies share five part meshes).")
    else:
        L.append(f"Not measured: {run_.get('error') if run_ else 'not run'}.")
    return "\n".join(L), targets


SKELETON = f"""# Scene benchmarks

Issue #24, items 8 and 9: the scene engine (`scene::clash_scene`, docs/report.md) on a generated assembly of
10,000 bodies, on moving bodies, and `interfere clash` as a whole process, with FCL and CGAL measured in the
same run. `python3 bench/scene_tables.py` builds and runs everything and rewrites the block below.

{BEGIN}
{END}
"""


def write_doc(raw: dict) -> list:
    block, targets = make_block(raw)
    text = DOC.read_text() if DOC.exists() else SKELETON
    if BEGIN not in text or END not in text:
        text = text.rstrip("\n") + "\n\n" + BEGIN + "\n" + END + "\n"
    head, rest = text.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    DOC.write_text(head + BEGIN + "\n" + block + "\n" + END + tail)
    return targets


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build-dir", default=str(ROOT / "build-bench"))
    ap.add_argument("--cli", default=str(ROOT / "build" / "apps" / "cli" / "interfere"),
                    help="the interfere CLI of the whole-process run (default: the main build's)")
    ap.add_argument("--no-build", action="store_true")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--repetitions", type=int, default=3, help="Google Benchmark repetitions (default 3)")
    ap.add_argument("--process-repetitions", type=int, default=5, help="whole-process runs of interfere (default 5)")
    ap.add_argument("--peer-repetitions", type=int, default=3,
                    help="whole-process runs of each peer (default 3: FCL's take 10-30 s each)")
    ap.add_argument("--threads", default="2", help="interfere's thread count (default 2, as the issue's targets)")
    ap.add_argument("--filter", default=None, help="--benchmark_filter for interfere_bench_scene")
    ap.add_argument("--skip", default="", help="comma-separated parts to skip: bench, memory, scenefile, process")
    ap.add_argument("--quick", action="store_true", help="1,000 bodies, 1 frame, 1 repetition, 3 process runs")
    ap.add_argument("--report-only", action="store_true", help="rewrite the doc from docs/scene-benchmarks.json")
    args = ap.parse_args()
    if args.report_only:
        raw = json.loads(RAW.read_text())
        targets = write_doc(raw)
        for t in targets:
            log(f"  {verdict(t['pass'])}  {t['target']}: {t['measured']}")
        return 0

    build_dir = Path(args.build_dir)
    if not args.no_build:
        build(build_dir, ROOT / "build", args.jobs)
    skip = {s for s in args.skip.split(",") if s}
    machine = machine_description()
    env = dict(os.environ)
    env["INTERFERE_BENCH_SCENE_THREADS"] = args.threads
    reps, preps = args.repetitions, args.process_repetitions
    bodies = "10000"
    if args.quick:
        env.setdefault("INTERFERE_BENCH_SCENE_BODIES", "1000")
        env.setdefault("INTERFERE_BENCH_MOVING_FRAMES", "1")
        reps, preps, bodies = 1, 3, "1000"
    bodies = env.get("INTERFERE_BENCH_SCENE_BODIES", bodies)
    raw = {"machine": machine, "settings": {"threads": args.threads, "repetitions": reps, "quick": args.quick,
                                            **{k: v for k, v in env.items() if k.startswith("INTERFERE_BENCH_")}},
           "google_benchmark": {}, "assembly_process": None, "whole_process": None}
    old = json.loads(RAW.read_text()) if RAW.exists() else {}
    # When and under what load each part was measured (a part skipped keeps its earlier stamp).
    raw["parts"] = dict(old.get("parts", {}))

    def stamp(part: str) -> None:
        raw["parts"][part] = {"date_utc": machine_description()["date_utc"],
                              "loadavg": " ".join(Path("/proc/loadavg").read_text().split()[:3])}
    started = time.monotonic()
    if "bench" not in skip:
        stamp("bench")
        data = run_google_benchmark(build_dir / "bench" / "interfere_bench_scene", reps, env, args.filter)
        raw["google_benchmark"] = medians(data)
        raw["google_benchmark_context"] = data.get("context", {})
        if args.filter:  # a subset: the other rows as they were
            raw["google_benchmark"] = {**old.get("google_benchmark", {}), **raw["google_benchmark"]}
    else:
        raw["google_benchmark"] = old.get("google_benchmark", {})
    if "memory" not in skip:
        stamp("memory")
        try:
            raw["assembly_process"] = run_json([build_dir / "bench" / "interfere_scene_run", "assembly", bodies, "48",
                                                args.threads])
        except (subprocess.CalledProcessError, ValueError) as e:
            raw["assembly_process"] = {"error": str(e)}
    else:
        raw["assembly_process"] = old.get("assembly_process")
    if "scenefile" not in skip:
        stamp("scenefile")
        try:
            raw["scene_file_process"] = scene_file_process(build_dir, Path(args.cli), preps, bodies)
        except (subprocess.CalledProcessError, ValueError, OSError) as e:
            raw["scene_file_process"] = {"error": str(e)}
    else:
        raw["scene_file_process"] = old.get("scene_file_process")
    if "process" not in skip:
        stamp("process")
        raw["whole_process"] = whole_process(build_dir, Path(args.cli), preps, min(preps, args.peer_repetitions), "1e6")
    else:
        raw["whole_process"] = old.get("whole_process")
    RAW.write_text(json.dumps(raw, indent=1) + "\n")
    targets = write_doc(raw)
    log(f"wrote {DOC} and {RAW} in {time.monotonic() - started:.0f} s")
    for t in targets:
        log(f"  {verdict(t['pass'])}  {t['target']}: {t['measured']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
