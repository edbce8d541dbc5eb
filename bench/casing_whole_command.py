#!/usr/bin/env python3
"""The paper's casing case as a whole command (issue #29 target: <= 0.5 s including the STEP import).

Runs `interfere simplify data/examples/casing.step OUT.glb --linear-deflection D --target 5200 --step S
--process data/examples/casing_process.json --json OUT.json` for steps P1 and P2, interleaved with any other
variants given, and prints the medians docs/simplify.md ("Whole command on the casing") reports: wall time,
CPU time of the process and its children (all threads), the report's timings_s.total, the STEP import (total
less the simplification), the simplification with the error measurement and the error measurement alone,
with the load average before and after.

    python3 bench/casing_whole_command.py                     # build/apps/cli/interfere, 7 runs x P1, P2
    python3 bench/casing_whole_command.py --runs 9 \\
        --variant old=/tmp/interfere-cad.old:0.0205 --variant new=build/apps/cli/interfere-cad

A variant is LABEL=EXECUTABLE[:DEFLECTION] (the `interfere` launcher or `interfere-cad`, which the launcher
hands STEP input to); the default deflection is the README's (data/examples/README.md: the paper's 35,548 case).
The launcher runs `interfere-cad` with glibc malloc settings in its environment (GLIBC_TUNABLES, unless set
already: apps/cli/cad_exec.cpp, issue #29); a variant that is `interfere-cad` itself runs without them unless
GLIBC_TUNABLES is set for this script. On a loaded machine, `chrt -r 10 python3 bench/casing_whole_command.py`
(as root) keeps the runs apart from the other work (docs/simplify.md, "Fourth round").
"""
import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DEFLECTION = 0.01696  # data/examples/README.md: 35,556 triangles, the paper's 35,548 case


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_once(exe, deflection, step, work):
    out, rep = work / "c.glb", work / "c.json"
    cmd = [exe, "simplify", str(ROOT / "data/examples/casing.step"), str(out), "--linear-deflection", str(deflection),
           "--target", "5200", "--step", step, "--process", str(ROOT / "data/examples/casing_process.json"),
           "--json", str(rep)]
    c0, t0 = children_cpu(), time.perf_counter()
    p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall, cpu = time.perf_counter() - t0, children_cpu() - c0
    if p.returncode != 0:
        sys.exit(f"{' '.join(cmd)}: exit {p.returncode}: {p.stderr.strip()}")
    d = json.loads(rep.read_text())
    t = d["timings_s"]
    phases = {x["phase"]: x["seconds"] for x in t["phases"]}
    return {"wall": wall, "cpu": cpu, "total": t["total"], "import": t["total"] - t["simplify"],
            "simplify": t["simplify"], "error": phases.get("error", 0.0),
            "triangles": f"{d['input_triangles']} -> {d['output_triangles']}"}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=7, help="interleaved runs of each variant and step (default 7)")
    ap.add_argument("--variant", action="append", default=[], metavar="LABEL=EXE[:DEFLECTION]")
    ap.add_argument("--steps", default="P1,P2")
    a = ap.parse_args()
    variants = []
    for v in a.variant or [f"interfere={ROOT / 'build/apps/cli/interfere'}"]:
        label, _, rest = v.partition("=")
        exe, _, d = rest.partition(":")
        variants.append((label, exe, float(d) if d else DEFLECTION))
    steps = a.steps.split(",")
    load0 = os.getloadavg()
    res = {(lab, s): [] for lab, _, _ in variants for s in steps}
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for _ in range(a.runs):
            for s in steps:
                for lab, exe, d in variants:
                    res[(lab, s)].append(run_once(exe, d, s, work))
    load1 = os.getloadavg()
    print(f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {a.runs} interleaved runs of each variant for "
          f"{', '.join(steps)}, medians of the {a.runs * len(steps)}; load average {load0[0]:.1f} before, "
          f"{load1[0]:.1f} after ({os.cpu_count()} CPUs)\n")
    keys = [("wall", "whole command, wall"), ("cpu", "CPU time of the process (all threads)"),
            ("total", "the report's `timings_s.total`"), ("import", "of it: STEP import (total less simplification)"),
            ("simplify", "of it: simplification with the error measurement"), ("error", "of that: the error measurement")]
    labels = [f"{lab} (d = {d:g})" for lab, _, d in variants]
    print("| what | " + " | ".join(labels) + " |")
    print("|---|" + "---:|" * len(variants))
    for k, name in keys:
        cells = [f"{statistics.median(r[k] for s in steps for r in res[(lab, s)]):.3f} s" for lab, _, _ in variants]
        print(f"| {name} | " + " | ".join(cells) + " |")
    cells = [" / ".join(sorted({r['triangles'] for s in steps for r in res[(lab, s)]})) for lab, _, _ in variants]
    print("| triangles | " + " | ".join(cells) + " |")
    walls = [f"{min(r['wall'] for s in steps for r in res[(lab, s)]):.2f}-"
             f"{max(r['wall'] for s in steps for r in res[(lab, s)]):.2f} s" for lab, _, _ in variants]
    print("| wall, range | " + " | ".join(walls) + " |")


if __name__ == "__main__":
    main()
