#!/usr/bin/env python3
"""Regenerates docs/fem-benchmarks.md: the FE targets of issue #26, item 7, measured on this machine.

    python3 bench/fem_targets_tables.py                 # build, run (about 3-5 minutes), write the doc
    python3 bench/fem_targets_tables.py --no-build      # use the existing build/ executables
    python3 bench/fem_targets_tables.py --quick         # small models, 1 repetition: a smoke run (doc not written)
    python3 bench/fem_targets_tables.py --report-only   # rewrite the doc from docs/fem-benchmarks.json

Runs (bench/fem_targets.cpp, Google Benchmark, --repetitions times each, the tables give medians):
  (a) BM_FrdRead/ascii and /binary: read_fem of a CalculiX .frd of 10^6 hex8 elements with 10 DISP
      steps (written once by the bench-only writer, cached in <build>/bench/fem_targets_data); then
      the CLI end to end, `interfere clash big.frd --json out.json`, each file as a child process
      timed from here (wall clock, --cli-repetitions times after one untimed run).
  (b) BM_Fem20BodiesStep: 20 bodies, 10^7 elements, all pairs per step through the scene engine.
  (c) BM_FemSceneSeriesStep: two 10^6-element bodies, 100 steps, per step through the scene engine.
The machine's load average is recorded before and after (the targets are for 2 cores; a loaded
machine shares them). Writes docs/fem-benchmarks.json (raw) and docs/fem-benchmarks.md. Standard
library only.
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

DOC = ROOT / "docs" / "fem-benchmarks.md"
RAW = ROOT / "docs" / "fem-benchmarks.json"

# The targets (issue #26, item 7).
TARGET_READ_MS = 2000.0
TARGET_MODEL20_MS = 200.0
TARGET_SERIES_MS = 30.0

QUICK_ENV = {"INTERFERE_BENCH_FRD_ELEMENTS": "64000", "INTERFERE_BENCH_FRD_STEPS": "3",
             "INTERFERE_BENCH_MODEL20_ELEMENTS": "200000", "INTERFERE_BENCH_MODEL20_STEPS": "10",
             "INTERFERE_BENCH_SERIES_ELEMENTS": "20000", "INTERFERE_BENCH_SERIES_STEPS": "100"}


def log(msg: str) -> None:
    print(f"[fem_targets_tables] {msg}", file=sys.stderr, flush=True)


def run(cmd, **kw) -> subprocess.CompletedProcess:
    log("$ " + " ".join(str(c) for c in cmd))
    return subprocess.run([str(c) for c in cmd], cwd=ROOT, **kw)


def loadavg() -> str:
    try:
        return " ".join(Path("/proc/loadavg").read_text().split()[:3])
    except OSError:
        return "unknown"


def build(build_dir: Path, jobs: int) -> None:
    run(["cmake", "--build", build_dir, "-j", str(jobs), "--target", "interfere_bench_fem_targets", "interfere"],
        check=True)


def google_benchmark(exe: Path, repetitions: int, env: dict) -> dict:
    return google_benchmark_json(run, exe, repetitions, env)


def medians(data: dict) -> dict:
    """name -> {'ms': median real time, 'ms_min', 'ms_max', 'reps', counters (median)} over the runs."""
    rows: dict[str, list[dict]] = {}
    for b in data.get("benchmarks", []):
        if b.get("run_type") == "aggregate":
            continue
        name = re.sub(r"/(iterations:\d+|repeats:\d+|real_time|manual_time|\d+)(?=/|$)", "", b.get("run_name", b["name"]))
        rows.setdefault(name, []).append(b)
    skip = {"name", "run_name", "run_type", "family_index", "per_family_instance_index", "repetitions",
            "repetition_index", "threads", "iterations", "real_time", "cpu_time", "time_unit", "label",
            "error_occurred", "error_message", "aggregate_name", "aggregate_unit"}
    out = {}
    for name, bs in rows.items():
        errors = [b.get("error_message", "error") for b in bs if b.get("error_occurred")]
        bs = [b for b in bs if not b.get("error_occurred")]
        if not bs:
            out[name] = {"error": errors[0] if errors else "no result"}
            continue
        scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[bs[0].get("time_unit", "ns")]
        times = [b["real_time"] * scale for b in bs]
        r = {"ms": statistics.median(times), "ms_min": min(times), "ms_max": max(times), "reps": len(bs),
             "label": bs[0].get("label", "")}
        for k in bs[0]:
            if k not in skip and isinstance(bs[0][k], (int, float)):
                r[k] = statistics.median(b.get(k, 0) for b in bs)
        out[name] = r
    return out


def cli_runs(cli: Path, files: list[str], reps: int) -> dict:
    res = {}
    with tempfile.TemporaryDirectory(prefix="interfere_fem_targets_") as tmp:
        report = Path(tmp) / "out.json"
        for f in files:
            kind = "binary" if f.endswith("_bin.frd") else "ascii"
            cmd = [cli, "clash", f, "--json", report]
            walls, codes = [], []
            for i in range(reps + 1):  # the first run is untimed (page cache)
                t0 = time.perf_counter()
                p = subprocess.run([str(c) for c in cmd], cwd=ROOT, capture_output=True, text=True)
                wall = time.perf_counter() - t0
                if p.returncode not in (0, 1):
                    raise SystemExit(f"{' '.join(map(str, cmd))}: exit status {p.returncode}\n{p.stderr[-2000:]}")
                if i > 0:
                    walls.append(wall * 1e3)
                    codes.append(p.returncode)
            summary = json.loads(report.read_text()).get("summary", {}) if report.exists() else {}
            res[kind] = {"command": f"interfere clash {Path(f).name} --json out.json", "file": Path(f).name,
                         "file_mb": os.path.getsize(f) / 1e6, "ms": statistics.median(walls), "ms_min": min(walls),
                         "ms_max": max(walls), "reps": len(walls), "exit_status": codes[-1],
                         "clashes": summary.get("clashes"), "triangles": summary.get("triangles")}
    return res


# ----------------------------------------------------------------------------- the document
def verdict(ms: float, target: float) -> str:
    return "**PASS**" if ms <= target else "**MISS**"


def fmt_ms(r: dict) -> str:
    return f"{r['ms']:.0f} ms ({r['ms_min']:.0f}–{r['ms_max']:.0f})" if r["ms"] >= 100 else \
        f"{r['ms']:.1f} ms ({r['ms_min']:.1f}–{r['ms_max']:.1f})"


def scene_rows(res: dict, family: str, target: float) -> list[str]:
    out = ["| options | per step (median, min–max) | target | | clash_scene, all frames | tree builds (prepare) | "
           "candidate pairs | clash pairs | frames with clashes |",
           "| --- | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: |"]
    for variant, what in (("depth_maps", "as `interfere clash model.frd`: clash, depth and bound, depth maps"),
                          ("clash_depth", "engine defaults: clash, depth and its upper bound (no depth maps)"),
                          ("no_bound", "clash and depth, no upper bound (for comparison)"),
                          ("no_depth", "clash only, no depth (for comparison)")):
        r = res.get(f"{family}/{variant}")
        if not r or "error" in r:
            continue
        judged = variant == "depth_maps" or (variant == "clash_depth" and f"{family}/depth_maps" not in res)
        out.append(f"| {what} | {fmt_ms(r)} | {target:.0f} ms | {verdict(r['ms'], target) if judged else '(not judged)'} "
                   f"| {r['clash_scene_s']:.2f} s | {r['prepare_s'] * 1e3:.1f} ms | {r['candidate_pairs']:.0f} "
                   f"| {r['clash_pairs']:.0f} | {r['clashing_frames']:.0f} of {r['frames']:.0f} |")
    d = res.get(f"{family}/depth_maps")
    if d and "error" not in d and d.get("depth_maps"):
        out += ["", f"Depth maps of the first row: {d['depth_maps']:.0f} (pair, step) maps, {d['depth_map_vertices']:,.0f} "
                "surface vertices inside the other body in all, each with its depth."]
    return out


def write_doc(raw: dict) -> None:
    m = raw["machine"]
    res = raw["benchmarks"]
    cli = raw.get("cli", {})
    L: list[str] = []
    L += ["# FE targets (issue #26, item 7)", "",
          "Generated by `bench/fem_targets_tables.py` (do not edit by hand; rerun it). Medians of "
          f"{raw['repetitions']} repetitions (min–max in brackets) on {m.get('cpu_model', '?')}, "
          f"{m.get('nproc', '?')} cores, {m.get('memory_gib', '?')} GiB, {m.get('date_utc', '?')}. "
          f"Load average (1, 5, 15 min) before the run: {raw['load_before']}, after: {raw['load_after']} (the "
          "benchmark's own threads count in it; above that, other jobs shared the 2 cores). The scene rows run on "
          "`INTERFERE_BENCH_THREADS` threads (2), the reader on every core (2 here).", ""]
    L += ["## (a) Reading a 10^6-element CalculiX `.frd` with 10 steps — target ≤ 2 s", ""]
    a = res.get("BM_FrdRead/ascii", {})
    if a and "error" not in a:
        L += [f"Two hex8 (C3D8) boxes, {a['elements']:,.0f} elements, {a['nodes']:,.0f} nodes, "
              f"{a['steps']:.0f} DISP steps (`bench/fem_targets_models.h` (a); B moves into A from step 3 on), "
              "written by the bench-only writer `bench/frd_bench_writer.cpp` as ccx 2.20 writes them: ASCII long "
              "format (`*NODE FILE`) and binary (`*NODE OUTPUT`: nodes float64, results float32). The read is "
              "`read_fem` (format, nodes, elements, every DISP step), after one untimed read that puts the file "
              "in the page cache.", ""]
    L += ["| what | file | per read or run (median, min–max) | target | |", "| --- | ---: | ---: | ---: | --- |"]
    for kind in ("ascii", "binary"):
        r = res.get(f"BM_FrdRead/{kind}")
        if r and "error" not in r:
            L.append(f"| `read_fem`, {kind} | {r['file_MB']:.0f} MB | {fmt_ms(r)} | 2000 ms | {verdict(r['ms'], TARGET_READ_MS)} |")
    for kind in ("ascii", "binary"):
        r = cli.get(kind)
        if r:
            L.append(f"| `{r['command']}` ({kind}), whole process | {r['file_mb']:.0f} MB | {fmt_ms(r)} | — | "
                     f"(not the target's measure: it also extracts the surfaces, checks the undeformed model and 10 "
                     f"frames and writes the report; exit status {r['exit_status']}) |")
    L += ["", "How: `src/fem/io/frd_read.cpp` maps the file (no copy), advises huge pages for its large arrays, "
          "parses numbers with an exact fast path and reads the node, element and DISP blocks in parallel chunks. Before, the "
          "same files took 7.0 s (ASCII) and 3.6 s (binary) on this machine, most of it in page faults of "
          "freshly allocated memory (a fresh 4 KiB page costs microseconds on this VM).", ""]

    L += ["## (b) 20 bodies, 10^7 elements, all pairs per step — target ≤ 200 ms", ""]
    b = res.get("BM_Fem20BodiesStep/clash_depth", {})
    if b and "error" not in b:
        L += [f"{b['bodies']:.0f} tet4 bodies (unit boxes and balls of radius 0.5 in a checkerboard on a 5 × 4 grid "
              f"of pitch 1.1), {b['elements']:,.0f} elements, {b['nodes']:,.0f} nodes, {b['triangles']:,.0f} surface "
              f"triangles, {b['frames']:.0f} steps in which every ball grows (6 % of its radius per step: it "
              "crosses its 2–4 box neighbours from step 4 on) and every box shears; built in memory "
              "(`bench/fem_targets_models.h` (b)), made a scene by `fem_scene` and checked by "
              "`scene::clash_scene` with the default all-pairs test. Per step = the whole clash_scene / steps: "
              "its tree builds and, with the engine's defaults, its one check of the undeformed model "
              "(SceneClashOptions::reference, one frame's work) are included.", "",
              f"One-time costs: generating the model {b['generate_s']:.1f} s (bench only), `fem_scene` (surface "
              f"extraction, bodies, frames) {b['extract_s']:.2f} s; the tree builds are inside clash_scene "
              "(column prepare).", ""]
    L += scene_rows(res, "BM_Fem20BodiesStep", TARGET_MODEL20_MS)
    L += ["", "## (c) 100-step series of two 10^6-element bodies, per step — target ≤ 30 ms on 2 cores", ""]
    c = res.get("BM_FemSceneSeriesStep/clash_depth", {})
    if c and "error" not in c:
        L += [f"A tet4 unit box and a tet4 ball of radius 0.5 moving into it by 0.01 per step (BM_FemSeriesStep's "
              f"pair, `bench/fem_targets_models.h` (c)): {c['elements']:,.0f} elements, {c['triangles']:,.0f} surface "
              f"triangles, {c['frames']:.0f} steps, the ball touching the box from step 10 and 0.9 deep at step 99, the box "
              "sagging a little at every step (both bodies are refitted every step). "
              "Through `fem_scene` + `scene::clash_scene` (what `interfere clash model.frd` runs), per step = the "
              f"whole clash_scene / steps. One-time: `fem_scene` {c['extract_s']:.2f} s.", ""]
    L += scene_rows(res, "BM_FemSceneSeriesStep", TARGET_SERIES_MS)
    if not res.get("BM_FemSceneSeriesStep/depth_maps"):
        L += ["", "The per-node depth map (SceneClashOptions::depth_maps) is not in these rows: this run's engine "
              "has no such option."]
    L += ["", "`bench/bench_fem.cpp` BM_FemSeriesStep times the same pair through `fem::clash_series` (refit + "
          "clash, no depth); docs/benchmarks.md has its numbers.", ""]
    L += ["## Reproduce", "",
          "```sh",
          "cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DINTERFERE_BUILD_BENCH=ON -DINTERFERE_BUILD_CLI=ON",
          "python3 bench/fem_targets_tables.py            # builds interfere_bench_fem_targets and interfere, runs, writes this file",
          "python3 bench/fem_targets_tables.py --quick    # small models: a smoke run, prints, writes nothing",
          "build/bench/interfere_bench_fem_targets --benchmark_filter=FrdRead   # one family by hand",
          "```", "",
          "The .frd files (0.7 GB ASCII, 0.24 GB binary) are written on the first run into "
          "`<build>/bench/fem_targets_data` (`INTERFERE_BENCH_FRD_DIR` to move them) and reused. Sizes and "
          "threads: `INTERFERE_BENCH_FRD_ELEMENTS`, `_FRD_STEPS`, `_MODEL20_ELEMENTS`, `_MODEL20_STEPS`, "
          "`_SERIES_ELEMENTS`, `_SERIES_STEPS`, `INTERFERE_BENCH_THREADS` (default 2). Peak memory: about 1.5 GB "
          "(the 20-body model).", ""]
    DOC.write_text("\n".join(L).rstrip("\n") + "\n")
    log(f"wrote {DOC.relative_to(ROOT)}")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build-dir", type=Path, default=ROOT / "build")
    ap.add_argument("--no-build", action="store_true")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--repetitions", type=int, default=3)
    ap.add_argument("--cli-repetitions", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="small models, 1 repetition; prints, writes no doc")
    ap.add_argument("--report-only", action="store_true")
    args = ap.parse_args()
    if args.report_only:
        write_doc(json.loads(RAW.read_text()))
        return 0
    if not args.no_build:
        build(args.build_dir, args.jobs)
    exe = args.build_dir / "bench" / "interfere_bench_fem_targets"
    cli = args.build_dir / "apps" / "cli" / "interfere"
    env = dict(os.environ)
    reps = args.repetitions
    if args.quick:
        env.update(QUICK_ENV)
        reps = 1
    raw: dict = {"machine": machine_description(), "load_before": loadavg(), "repetitions": reps}
    files = run([exe, "--write-frd"], check=True, env=env, stdout=subprocess.PIPE, text=True).stdout.split()
    raw["benchmarks"] = medians(google_benchmark(exe, reps, env))
    if cli.exists():
        raw["cli"] = cli_runs(cli, files, 1 if args.quick else args.cli_repetitions)
    else:
        log(f"{cli} not built: the whole-process rows are left out")
    raw["load_after"] = loadavg()
    print(json.dumps(raw, indent=1))
    if args.quick:
        return 0
    RAW.write_text(json.dumps(raw, indent=1) + "\n")
    write_doc(raw)
    return 0


if __name__ == "__main__":
    sys.exit(main())
