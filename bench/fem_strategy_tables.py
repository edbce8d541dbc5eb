#!/usr/bin/env python3
"""Runs interfere_bench_fem_strategies and rewrites the section "The paper's strategy table on FE parts"
of docs/fem.md (between <!-- fem-strategies:begin --> and <!-- fem-strategies:end -->), issue #26 item 6.

    python3 bench/fem_strategy_tables.py                      # configure build-bench/, build, run, write
    python3 bench/fem_strategy_tables.py --exe build/bench/interfere_bench_fem_strategies
    python3 bench/fem_strategy_tables.py --no-run             # rewrite from docs/fem_strategies_bench.json
    python3 bench/fem_strategy_tables.py --sizes 1e4,1e5 --repetitions 5

The benchmark generates the FE parts with gmsh on first use (cached under <build>/bench_cache) and
takes the median of --repetitions runs of every row. The paper (Deng et al. 2018, §2.1) gives its
Table 2 as relative changes in the text; those are set beside ours. Standard library only.
"""
from __future__ import annotations

import argparse
import datetime as _dt
import json
import os
import re
import statistics
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from run_benchmarks import fmt_time, seconds  # noqa: E402  (one formatting for every benchmark table)

ROOT = Path(__file__).resolve().parent.parent
BUILD = ROOT / "build-bench"
RAW = ROOT / "docs" / "fem_strategies_bench.json"
DOC = ROOT / "docs" / "fem.md"
BEGIN, END = "<!-- fem-strategies:begin -->", "<!-- fem-strategies:end -->"
HEADING = "## The paper's strategy table on FE parts"

# name, label, builds on, change
ROWS = [
    ("1_brute_force_moller", "(1) brute force, Möller (double)", "", "all pairs, Möller 1997"),
    ("2_brute_force_guigue_devillers", "(2) brute force, Guigue–Devillers (double)", "1", "triangle test"),
    ("3_box_pretest_guigue_devillers", "(3) box pre-test, Guigue–Devillers", "2", "box pre-test"),
    ("3x_box_pretest_exact", "(3x) box pre-test, exact test", "3", "triangle test: exact"),
    ("4_insertion_tree", "(4) insertion-built tree, Guigue–Devillers", "3", "tree vs tree (insertion)"),
    ("5_median_split_tree", "(5) median-split tree, Guigue–Devillers", "4", "builder: median split"),
    ("5x_sah_tree", "(5x) binned-SAH tree, Guigue–Devillers", "5", "builder: binned SAH"),
    ("6_median_split_tree_parallel", "(6) median-split tree, parallel", "5", "parallel traversal"),
    ("7_exact_test", "(7) = 6 with the exact test", "6", "triangle test: exact"),
    ("8_default_tree", "(8) = 7 on the default tree (lbvh)", "7", "builder: lbvh"),
    ("9_engine_default", "(9) engine default (= 8 + regions, curves, containment)", "8",
     "default request"),
]
SERIAL = {r[0] for r in ROWS[:7]}
# The paper's Table 2 as its text states it (§2.1, points (1)-(5)): the change of (row) against (base).
PAPER = {
    "2": "≈ 20 % faster (Devillers vs Möller)",
    "3": "≈ 30 % less time",
    "4": "an order of magnitude less",
    "5": "more than 60 % less",
    "6": "≈ 30 % less (4 threads)",
}


def log(msg):
    print(f"[fem_strategy_tables] {msg}", file=sys.stderr, flush=True)


def label(n: int) -> str:
    p, m = 0, n
    while m >= 10 and m % 10 == 0:
        m, p = m // 10, p + 1
    return f"{m}e{p}" if p else str(n)


def bench_label(n: int) -> str:
    """The size as the benchmark names it (bench/common.cpp size_label)."""
    p, m = 0, n
    while m >= 10 and m % 10 == 0:
        m, p = m // 10, p + 1
    return f"1e{p}" if m == 1 and p else str(n)


def parse_sizes(text: str) -> list[int]:
    return [int(round(float(s))) for s in text.split(",") if s.strip()]


def loadavg() -> str:
    try:
        return " ".join(Path("/proc/loadavg").read_text().split()[:3])
    except OSError:
        return "unknown"


def cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown CPU"


def run(exe: Path | None, sizes: list[int], reps: int, bench_filter: str | None) -> dict:
    if exe is None:
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(BUILD), "-DCMAKE_BUILD_TYPE=Release",
                        "-DINTERFERE_BUILD_TESTS=OFF", "-DINTERFERE_BUILD_CLI=OFF", "-DINTERFERE_BUILD_BENCH=ON",
                        "-DINTERFERE_BUILD_PYTHON=OFF"], check=True)
        subprocess.run(["nice", "cmake", "--build", str(BUILD), "-j2", "--target",
                        "interfere_bench_fem_strategies"], check=True)
        exe = BUILD / "bench" / "interfere_bench_fem_strategies"
    env = dict(os.environ)
    env["INTERFERE_BENCH_FEM_SIZES"] = ",".join(str(n) for n in sizes)
    env["INTERFERE_BENCH_REPETITIONS"] = str(reps)
    out = RAW.with_suffix(".tmp.json")
    cmd = [str(exe), f"--benchmark_out={out}", "--benchmark_out_format=json"]
    if bench_filter:
        cmd.append(f"--benchmark_filter={bench_filter}")
    meta = {"load_before": loadavg(), "start": _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "cpu": cpu_model(), "cores": os.cpu_count(), "sizes": sizes, "repetitions": reps}
    log(f"running {exe} (sizes {meta['sizes']}, {reps} repetitions; load {meta['load_before']})")
    t0 = time.monotonic()
    subprocess.run(cmd, check=True, env=env)
    meta["seconds"] = time.monotonic() - t0
    meta["load_after"] = loadavg()
    raw = json.loads(out.read_text())
    out.unlink()
    raw["fem_strategy_meta"] = meta
    RAW.write_text(json.dumps(raw, indent=1) + "\n")
    return raw


def medians(raw: dict) -> dict:
    """name (without /repeats:k and /real_time) -> {s: median wall time, counters of the last run}."""
    runs: dict[str, list[dict]] = {}
    for b in raw["benchmarks"]:
        if b.get("run_type") != "iteration" or b.get("error_occurred"):
            continue
        name = re.sub(r"(/repeats:\d+)?(/real_time)?$", "", b["name"])
        runs.setdefault(name, []).append(b)
    out = {}
    for name, bs in runs.items():
        r = dict(bs[-1])
        r["s"] = statistics.median(seconds(b) for b in bs)
        r["reps"] = len(bs)
        out[name] = r
    return out


def table_head(columns: list[str], sizes: list[int]) -> list[str]:
    return ["| " + " | ".join(columns + [label(n) for n in sizes]) + " |",
            "|" + "---|" * (len(columns) + len(sizes))]


def strategy_name(row: str, n: int, threads: int | None) -> str:
    return f"Strategy/{row}/{bench_label(n)}" + (f"/threads:{threads}" if threads else "")


def row_variants(row: str, threads: list[int]) -> list[tuple[str, int | None]]:
    return [("", None)] if row in SERIAL else [(f", {t} thread{'s' if t > 1 else ''}", t) for t in threads]


def render(raw: dict) -> str:
    meta = raw.get("fem_strategy_meta", {})
    m = medians(raw)
    sizes = meta.get("sizes") or sorted({int(float(k.split("/")[2])) for k in m if k.startswith("Load/")})
    threads = sorted({int(k.rsplit(":", 1)[1]) for k in m if "/threads:" in k and k.startswith("Strategy/")})
    ctx = raw.get("context", {})
    L = []
    L.append(f"Generated by `bench/fem_strategy_tables.py` on {meta.get('start', ctx.get('date', '?'))}: "
             f"{meta.get('cpu', '?')}, {meta.get('cores', '?')} cores shared with other work; load average "
             f"{meta.get('load_before', '?')} before the run, {meta.get('load_after', '?')} after "
             f"(1, 5, 15 min), so wall times are pessimistic. The run took {meta.get('seconds', 0) / 60:.1f} min; "
             f"every cell is the median of {meta.get('repetitions', '?')} repetitions (Google Benchmark, "
             f"`interfere_bench_fem_strategies`, {ctx.get('interfere_build', '?')}).")
    L.append("")
    L.append("**The parts** (`bench/fem_strategy_tables.py` → `bench/fem_strategy_parts.cpp`): the paper "
             "tests \"two adjacent CFETR parts\" (§2), finite-element models whose surfaces are triangulated. "
             "Here gmsh (SDK, built-in kernel) meshes a 22.5° vacuum-vessel sector (torus shell, major radius "
             "6 m, wall 2.0–2.2 m minor radius; hex8 by a recombined revolution of transfinite quads) and a "
             "rectangular port duct (1.6 × 2.0 m, wall 0.15 m, tilted 3°; tet4 by extrusion) that crosses the "
             "vessel wall all around; both are written as MSH 4.1 binary, read by `read_fem` and surfaced by "
             "`extract_surface` (one part per physical group), the user's path. Each load checks that both "
             "surfaces are one closed, outward component whose enclosed volume matches the solid (port: "
             "exactly, vessel: within 0.5 %, the inscribed polygons). A is the vessel, B the port.")
    L.append("")
    L.append("| size | hex8 (A) | tet4 (B) | nodes | triangles A | triangles B | volume A / analytic | "
             "volume B / analytic | gmsh | read_fem + extract_surface |")
    L.append("|---|---|---|---|---|---|---|---|---|---|")
    for n in sizes:
        r = m.get(f"Load/read_fem_extract_surface/{bench_label(n)}")
        if not r:
            continue
        gm = r.get("gmsh_seconds", 0)
        L.append(f"| {label(n)} | {r['hex8']:,.0f} | {r['tet4']:,.0f} | {r['nodes']:,.0f} | {r['tris_a']:,.0f} | "
                 f"{r['tris_b']:,.0f} | {r['volume_a']:.5f} / {r['volume_a_analytic']:.5f} m³ | "
                 f"{r['volume_b']:.5f} / {r['volume_b_analytic']:.5f} m³ | "
                 f"{f'{gm:.1f} s' if gm > 0 else 'cached'} | {fmt_time(r['s'])} |")
    L.append("")
    L.append("**Strategies** (query only: `clash()` with `regions = false, containment = false` except row 9, "
             "trees prebuilt; their builds are the next table). Each row changes one thing against the row it "
             "builds on, as the paper's rows do (its (3)–(6) each add one step to the previous). The paper ran "
             "Guigue–Devillers (\"Devillers\") from (2) on, so rows 3–6 keep it; the exact test is its own row "
             "(3x, 7). Rows 1–5x run on one thread. The O(n²) rows (1–3x) are capped at "
             f"{label(int(float(os.environ.get('INTERFERE_BENCH_BRUTE_MAX', '1e4'))))} (brute force) and "
             f"{label(int(float(os.environ.get('INTERFERE_BENCH_PRETEST_MAX', '1e5'))))} (box pre-test) "
             "triangles per part; a capped cell shows the |A|·|B| extrapolation from the largest measured size "
             "(≈). Cells: wall time (triangle pairs found; for the double tests, pairs more/fewer than the exact "
             "set where they differ).")
    L.append("")
    L.extend(table_head(["strategy", "builds on", "change"], sizes))
    times: dict[tuple[str, int | None, int], float] = {}
    for row, text, base, change in ROWS:
        for suffix, t in row_variants(row, threads):
            cells = []
            last = None
            for n in sizes:
                r = m.get(strategy_name(row, n, t))
                if r:
                    times[(row, t, n)] = r["s"]
                    diff = ""
                    if r.get("extra", 0) or r.get("missing", 0):
                        diff = f"; +{r['extra']:.0f}/−{r['missing']:.0f}"
                    cells.append(f"{fmt_time(r['s'])} ({r['pairs']:,.0f}{diff})")
                    last = r
                elif last is not None and row[0] in "123":
                    load = m.get(f"Load/read_fem_extract_surface/{bench_label(n)}")
                    if load:
                        f = (load["tris_a"] * load["tris_b"]) / (last["tris_a"] * last["tris_b"])
                        cells.append(f"capped (≈ {fmt_time(last['s'] * f)})")
                    else:
                        cells.append("capped")
                else:
                    cells.append("—")
            L.append(f"| {text}{suffix} | {base or '—'} | {change} | " + " | ".join(cells) + " |")
    L.append("")
    L.append("**Step by step beside the paper** (§2.1, points (1)–(5); its Table 2 values are not in the text we "
             "have, only these relative changes; the paper's machine: 4 cores at 3.3 GHz, 8 GB, Windows 10, "
             "4 threads in (6)). Ours: time of the row / time of the row it builds on, per size; the parallel "
             "rows on the most threads measured against their serial base.")
    L.append("")
    L.extend(table_head(["row vs base", "paper"], sizes))
    tmax = max(threads) if threads else None
    for row, text, base, change in ROWS[1:]:
        base_row = next(r for r in ROWS if r[0].split("_")[0] == base)[0]
        t_row = None if row in SERIAL else tmax
        t_base = None if base_row in SERIAL else tmax
        cells = []
        for n in sizes:
            a, b = times.get((row, t_row, n)), times.get((base_row, t_base, n))
            cells.append(f"{a / b:.3g}×" if a and b else "—")
        key = row.split("_")[0]
        L.append(f"| ({key}) vs ({base}){f', {tmax} threads' if t_row else ''} | {PAPER.get(key, '—')} | "
                 + " | ".join(cells) + " |")
    L.append("")
    L.append("**Tree builds** (both parts one after the other, `make_model` without statistics, meshes copied "
             "outside the timing):")
    L.append("")
    L.extend(table_head(["builder", "threads"], sizes))
    builds = {}
    for b in ("insertion", "median_split", "binned_sah", "lbvh"):
        for t in [1] + [t for t in threads if t != 1]:
            cells = []
            for n in sizes:
                r = m.get(f"Build/{b}/{bench_label(n)}/threads:{t}")
                cells.append(fmt_time(r["s"]) if r else "—")
                if r:
                    builds[(b, t, n)] = r["s"]
            if any(c != "—" for c in cells):
                L.append(f"| {b} | {t} | " + " | ".join(cells) + " |")
    L.append("")
    L.extend(reading(times, builds, sizes, tmax))
    return "\n".join(L)


def reading(times: dict, builds: dict, sizes: list[int], tmax: int | None) -> list[str]:
    """A short reading of the table, its numbers (and the direction of each statement) taken from the run."""
    def ratios(row, base, t_row=None, t_base=None):
        out = []
        for n in sizes:
            a, b = times.get((row, t_row, n)), times.get((base, t_base, n))
            if a and b:
                out.append((n, a / b))
        return out

    def listing(rs, fmt="{:.2f}×"):
        return ", ".join(f"{fmt.format(r)} at {label(n)}" for n, r in rs)

    out = ["**Reading** (the paper's §2.1, points (1)–(5); ratios are time of the row / time of its base):", ""]
    rs = ratios("2_brute_force_guigue_devillers", "1_brute_force_moller")
    if rs:
        faster = all(r < 1 for _, r in rs)
        out.append(f"- (1)→(2), the triangle test: Guigue–Devillers {'is faster' if faster else 'is not faster everywhere'}"
                   f" ({listing(rs)}); the paper measured it about 20 % faster (and cites 15 % on random "
                   "triangles). Both double-precision tests reject most pairs at their first plane test, and "
                   "nearly all |A|·|B| pairs of an FE assembly are far apart"
                   + (", so they cost about the same here." if all(0.85 < r < 1.15 for _, r in rs) else "."))
    rs = ratios("3_box_pretest_guigue_devillers", "2_brute_force_guigue_devillers")
    if rs:
        out.append(f"- (2)→(3), the box pre-test: {listing(rs, '{:.3g}×')} (paper: about 30 % less). Our box "
                   "test on precomputed boxes rejects a far pair in a few comparisons, where the triangle test "
                   "first computes a plane; the paper's gain is much smaller than ours. Both rows stay O(|A|·|B|).")
    rs = ratios("3x_box_pretest_exact", "3_box_pretest_guigue_devillers")
    if rs:
        out.append(f"- (3x), the exact test behind the same pre-test: {listing(rs)}; only the box-overlapping "
                   "pairs reach it.")
    rs = ratios("4_insertion_tree", "3_box_pretest_guigue_devillers")
    if rs:
        out.append(f"- (3)→(4), the tree: {listing([(n, 1 / r) for n, r in rs], '{:,.0f}× faster')} (paper: an "
                   "order of magnitude less); the pre-test stays O(|A|·|B|) while the traversal visits only "
                   "node pairs near the crossing, so the gain grows with the size.")
    rs = ratios("5_median_split_tree", "4_insertion_tree")
    if rs:
        if all(r < 1 for _, r in rs):
            verdict = "the split tree is faster at every size, as in the paper"
        elif all(r >= 1 for _, r in rs):
            verdict = "the split tree is not faster here, unlike the paper"
        else:
            verdict = "the split tree is faster only at some sizes"
        out.append(f"- (4)→(5), the median-split (\"optimised\") tree: {listing(rs)}: {verdict} (paper: more than "
                   "60 % less). Our insertion builder descends to the child of least volume growth in a shuffled "
                   "order (input order degenerates on strip-ordered meshes), which already gives a tight tree "
                   "on these evenly meshed parts.")
    rs = ratios("5x_sah_tree", "5_median_split_tree")
    if rs:
        out.append(f"- (5x), the binned-SAH tree instead of the median split: {listing(rs)}.")
    if tmax and tmax > 1:
        rs = ratios("6_median_split_tree_parallel", "5_median_split_tree", tmax, None)
        if rs:
            pays = [label(n) for n, r in rs if r < 1]
            out.append(f"- (5)→(6), parallel traversal on {tmax} threads: {listing(rs)} (paper: about 30 % less "
                       f"on 4 threads). It pays {'at ' + ', '.join(pays) if pays else 'at no size measured'}: "
                       "the query is short (the crossing is a small share of the surfaces), so task start-up "
                       "and the cores shared with other work weigh on the small sizes.")
    rs = ratios("7_exact_test", "6_median_split_tree_parallel", tmax, tmax)
    if rs:
        out.append(f"- (6)→(7), the exact test instead of Guigue–Devillers: {listing(rs)}; behind a tree only "
                   "the candidate pairs reach the test.")
    rs = ratios("8_default_tree", "7_exact_test", tmax, tmax)
    if rs:
        b = [(n, builds[("lbvh", tmax, n)] / builds[("median_split", 1, n)]) for n in sizes
             if ("lbvh", tmax, n) in builds and ("median_split", 1, n) in builds]
        out.append(f"- (7)→(8), the engine's default tree (lbvh) instead of the median split: {listing(rs)} for "
                   "the query" + (f"; its build takes {listing(b)} the median split's (build table)" if b else "")
                   + ".")
    rs = ratios("9_engine_default", "8_default_tree", tmax, tmax)
    if rs:
        out.append("- (8)→(9), the engine's default request adds the clash regions with their intersection "
                   f"curves (the containment test is skipped once surfaces cross): {listing(rs)}.")
    return out


def rewrite_doc(body: str):
    text = DOC.read_text()
    block = f"{BEGIN}\n{body}\n{END}"
    if BEGIN in text and END in text:
        text = text[:text.index(BEGIN)] + block + text[text.index(END) + len(END):]
    else:
        at = text.index("## Performance")
        text = text[:at] + f"{HEADING}\n\n{block}\n\n" + text[at:]
    DOC.write_text(text)
    log(f"wrote {DOC.relative_to(ROOT)}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", type=Path, help="an existing interfere_bench_fem_strategies (skips the build)")
    ap.add_argument("--no-run", action="store_true", help="rewrite the doc from docs/fem_strategies_bench.json")
    ap.add_argument("--sizes", default="1e4,1e5,3e5,1e6", help="surface triangles per part (default %(default)s)")
    ap.add_argument("--repetitions", type=int, default=3)
    ap.add_argument("--filter", help="benchmark filter (for a partial run; the doc then shows only those rows)")
    args = ap.parse_args()
    if args.no_run:
        raw = json.loads(RAW.read_text())
    else:
        raw = run(args.exe.resolve() if args.exe else None, parse_sizes(args.sizes), args.repetitions, args.filter)
    rewrite_doc(render(raw))


if __name__ == "__main__":
    main()
