#!/usr/bin/env python3
"""Builds and runs the interfere benchmark suite and regenerates docs/benchmarks.md + docs/benchmarks.json.

    python3 bench/run_benchmarks.py            # full run (about 10 min on 2 cores)
    python3 bench/run_benchmarks.py --quick    # smoke run, under 3 min: short timing, no repetitions,
                                               # fewer O(n^2), peer and exactness rows
    python3 bench/run_benchmarks.py --big      # also the 1e7 x 1e7 run (interfere_big_run)
    python3 bench/run_benchmarks.py --no-build --filter 'Strategy/.*1e4'   # rerun a subset, merged
                                                                           # into the kept report

Configures a Release build with -DINTERFERE_BUILD_BENCH=ON in build-bench/ (tests and CLI off), builds
interfere_bench and interfere_big_run, runs them, keeps the raw results in docs/benchmarks.json and
writes docs/benchmarks.md. Progress goes to the terminal (stderr): "[k/N] running NAME ..." when a
benchmark starts and its time when it ends. Standard library only.
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
import shutil
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# Targets of issue #2 (item 8). Each: key, description, unit, comparison, threshold.
GB = 1e9
# The issue states its targets "on this 2-core machine": the thread count they are judged on.
ISSUE_THREADS = 2


def log(msg: str) -> None:
    print(f"[run_benchmarks] {msg}", file=sys.stderr, flush=True)


def run(cmd: list[str], env: dict | None = None, capture: bool = False) -> subprocess.CompletedProcess:
    log("$ " + " ".join(str(c) for c in cmd))
    return subprocess.run(cmd, cwd=ROOT, env=env, check=True, text=True,
                          stdout=subprocess.PIPE if capture else None)


# ----------------------------------------------------------------------------- machine
def machine_description() -> dict:
    info: dict = {
        "date_utc": _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "nproc": len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count(),
        "cpu_count": os.cpu_count(),
        "kernel": platform.release(),
        "system": platform.system(),
        "python": platform.python_version(),
    }
    try:
        cpuinfo = Path("/proc/cpuinfo").read_text()
        m = re.search(r"^model name\s*:\s*(.+)$", cpuinfo, re.M)
        info["cpu_model"] = m.group(1).strip() if m else "unknown"
        flags = re.search(r"^flags\s*:\s*(.+)$", cpuinfo, re.M)
        if flags:
            f = set(flags.group(1).split())
            info["simd"] = " ".join(x for x in ("sse4_2", "avx", "avx2", "fma", "avx512f") if x in f)
        mhz = re.search(r"^cpu MHz\s*:\s*(.+)$", cpuinfo, re.M)
        if mhz:
            info["cpu_mhz"] = mhz.group(1).strip()
    except OSError:
        info["cpu_model"] = platform.processor() or "unknown"
    try:
        meminfo = Path("/proc/meminfo").read_text()
        m = re.search(r"^MemTotal:\s*(\d+)\s*kB", meminfo, re.M)
        if m:
            info["memory_gib"] = round(int(m.group(1)) / 2**20, 1)
    except OSError:
        pass
    try:
        info["loadavg_at_start"] = " ".join(Path("/proc/loadavg").read_text().split()[:3])
    except OSError:
        pass
    return info


# ----------------------------------------------------------------------------- build + run
def configure_and_build(build_dir: Path, jobs: int) -> None:
    run(["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
         "-DINTERFERE_BUILD_BENCH=ON", "-DINTERFERE_BUILD_TESTS=OFF", "-DINTERFERE_BUILD_CLI=OFF"])
    run(["cmake", "--build", str(build_dir), "-j", str(jobs), "--target", "interfere_bench",
         "interfere_big_run", "interfere_fem_big_run"])


def run_bench(build_dir: Path, args: argparse.Namespace) -> dict:
    exe = build_dir / "bench" / "interfere_bench"
    if not exe.exists():
        sys.exit(f"{exe} not found (build first or drop --no-build)")
    env = dict(os.environ)
    env.setdefault("INTERFERE_BENCH_BRUTE_MAX", "1e4")
    env.setdefault("INTERFERE_BENCH_PRETEST_MAX", "1e4" if args.quick else "1e5")
    if args.quick:
        env.setdefault("INTERFERE_BENCH_PEER_MAX", "1e5")
        env.setdefault("INTERFERE_BENCH_REPETITIONS", "1")
        env.setdefault("INTERFERE_BENCH_EXACT_BOX_N", "50")
    env.setdefault("INTERFERE_BENCH_REPETITIONS", "3")
    if args.threads:
        env["INTERFERE_BENCH_THREADS"] = args.threads
    if args.pretest_max:
        env["INTERFERE_BENCH_PRETEST_MAX"] = args.pretest_max
    shared = ROOT.parent / "shared" / "data" / "mesh"
    if "INTERFERE_BENCH_DATA" not in env:
        env["INTERFERE_BENCH_DATA"] = str(shared)  # the benchmarks skip absent files themselves
    min_time = args.min_time if args.min_time is not None else (0.01 if args.quick else 0.5)

    base = [str(exe), f"--benchmark_min_time={min_time}"]
    listed = subprocess.run(base + ["--benchmark_list_tests"]
                            + ([f"--benchmark_filter={args.filter}"] if args.filter else []),
                            cwd=ROOT, env=env, check=True, text=True, stdout=subprocess.PIPE).stdout
    planned = [normalize_name(n) for n in listed.split()]
    data: dict = {"benchmarks": [], "crashed": []}
    remaining = planned
    t_start = time.monotonic()
    log(f"{len(planned)} benchmarks to run")
    # The STL benchmark writes ~100 MB under TMPDIR; a folder owned here is removed even after a crash.
    scratch = tempfile.TemporaryDirectory(prefix="interfere_bench_")
    env["TMPDIR"] = scratch.name
    # A benchmark that crashes the process (abort, segfault) must not cost the whole report: the JSON
    # is streamed line-buffered, finished rows are kept, the crashing row is recorded and skipped,
    # and the run resumes with the rows after it.
    while remaining:
        regex = "^(" + "|".join(ere_escape(n) for n in remaining) + ")(/repeats:[0-9]+)?(/real_time)?$"
        part, rc = run_streaming(base + ["--benchmark_format=json", f"--benchmark_filter={regex}"], env,
                                 remaining, len(planned) - len(remaining), len(planned), t_start)
        data.setdefault("context", part.get("context", {}))
        data["benchmarks"] += part.get("benchmarks", [])
        if rc == 0:
            break
        done = {normalize_name(b.get("run_name", b["name"])) for b in part.get("benchmarks", [])
                if b.get("run_type") == "aggregate" or "repetition_index" not in b
                or b.get("repetitions", 1) <= 1}
        crashed = next((n for n in remaining if n not in done), None)
        if crashed is None:
            break
        log(f"benchmark {crashed} crashed the process (exit status {rc}); continuing after it")
        data["crashed"].append({"name": crashed, "exit_status": rc})
        data["benchmarks"] = [b for b in data["benchmarks"]
                              if normalize_name(b.get("run_name", b["name"])) != crashed]
        remaining = remaining[remaining.index(crashed) + 1:]
    scratch.cleanup()
    del env["TMPDIR"]
    data["settings"] = {k: v for k, v in env.items() if k.startswith("INTERFERE_BENCH_")}
    data["settings"]["benchmark_min_time"] = min_time
    data["settings"]["quick"] = bool(args.quick)
    if args.filter:
        data["settings"]["filter"] = args.filter
    return data


def ere_escape(text: str) -> str:
    """Escapes the POSIX extended-regex specials only: Google Benchmark compiles its filter with
    std::regex::extended, which rejects Python's escapes of other characters ("\\-", "\\ ")."""
    return re.sub(r"([.\[\]{}()\\*+?^$|])", r"\\\1", text)


def normalize_name(name: str) -> str:
    """Benchmark name without Google Benchmark's /repeats:N and /real_time suffixes."""
    return re.sub(r"/(repeats:\d+|real_time)(?=/|$)", "", name)


def parse_partial_json(text: str) -> dict:
    """The finished part of a Google Benchmark JSON report cut short by a crash."""
    try:
        return json.loads(text)
    except ValueError:
        pass
    out: dict = {"benchmarks": []}
    dec = json.JSONDecoder()
    m = re.search(r'"context"\s*:\s*', text)
    if m:
        try:
            out["context"], _ = dec.raw_decode(text, m.end())
        except ValueError:
            pass
    m = re.search(r'"benchmarks"\s*:\s*\[', text)
    pos = m.end() if m else len(text)
    while True:
        while pos < len(text) and text[pos] in " \t\r\n,":
            pos += 1
        try:
            obj, pos = dec.raw_decode(text, pos)
        except ValueError:
            break
        out["benchmarks"].append(obj)
    return out


def run_streaming(cmd: list[str], env: dict, planned: list[str], done_before: int = 0,
                  total: int | None = None, t0: float | None = None) -> tuple[dict, int]:
    """Runs interfere_bench with JSON on stdout, line-buffered (stdbuf) so that a crash keeps the rows
    already finished. Progress goes to the terminal (stderr): the row that is running now
    ("[k/N] running NAME ...", rows run in the listed order) and, when it finishes, its time.
    `planned` are the rows this process will run, in order; `done_before` rows ran before it; the
    elapsed time counts from `t0` (default: now)."""
    if shutil.which("stdbuf"):
        cmd = ["stdbuf", "-oL"] + cmd
    total = total if total is not None else done_before + len(planned)
    log("$ " + " ".join(cmd[:4]) + " ...")
    t0 = time.monotonic() if t0 is None else t0
    started = time.monotonic()
    proc = subprocess.Popen(cmd, cwd=ROOT, env=env, text=True, stdout=subprocess.PIPE)
    lines: list[str] = []
    obj: list[str] | None = None  # lines of the benchmark object being read
    index = 0  # position in `planned` of the row running now

    def announce() -> None:
        if index < len(planned):
            log(f"[{done_before + index + 1}/{total}] running {planned[index]} ... "
                f"(elapsed {_elapsed(time.monotonic() - t0)})")

    announce()
    assert proc.stdout is not None
    for line in proc.stdout:
        lines.append(line)
        # Google Benchmark writes each result as an object opened by "    {" and closed by "    }".
        if line.rstrip() == "    {":
            obj = [line]
            continue
        if obj is None:
            continue
        obj.append(line)
        if line.rstrip() not in ("    }", "    },"):
            continue
        try:
            b = json.loads("".join(obj).rstrip().rstrip(","))
        except ValueError:
            b = None
        obj = None
        if not b or b.get("run_type") == "aggregate":
            continue
        name = normalize_name(b.get("run_name", b.get("name", "?")))
        reps, rep = int(b.get("repetitions", 1) or 1), int(b.get("repetition_index", 0) or 0)
        if b.get("error_occurred"):
            what = "error: " + str(b.get("error_message"))
        else:
            what = f"{b['real_time']:.4g} {b.get('time_unit', '')}"
        if reps > 1 and rep + 1 < reps:
            log(f"      repetition {rep + 1}/{reps}: {what}")
            continue
        log(f"      done {name}: {what}" + (f" (repetition {reps}/{reps})" if reps > 1 else ""))
        if name in planned[index:]:
            index = planned.index(name, index) + 1
            announce()
    rc = proc.wait()
    log(f"benchmark process finished (exit status {rc}) after {_elapsed(time.monotonic() - started)}")
    return parse_partial_json("".join(lines)), rc


def _elapsed(s: float) -> str:
    return f"{int(s // 60)}:{int(s % 60):02d}"


def _run_big_exe(build_dir: Path, exe_name: str, what: str, n: str, size_key: str, size_text: str,
                 threads: str | None, done) -> dict | None:
    """bench/<exe_name> N [THREADS]: its JSON on stdout, dated, with the line done(result) logged;
    {size_key: N, "error": ...} when it fails, None when it is not built. `what` names the run in the
    log ("big run", "FEM big run")."""
    exe = build_dir / "bench" / exe_name
    if not exe.exists():
        log(f"{exe} not found; {what} skipped")
        return None
    cmd = [str(exe), n] + ([threads] if threads else [])
    log(f"running {exe_name} at {n} {size_text} ...")
    try:
        cp = run(cmd, capture=True)
    except subprocess.CalledProcessError as e:
        log(f"{what} {n} failed: exit {e.returncode}")
        return {size_key: float(n), "error": f"exit status {e.returncode}"}
    result = json.loads(cp.stdout)
    log("      done: " + done(result))
    result["date_utc"] = _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    return result


def run_big(build_dir: Path, n: str, threads: str | None) -> dict | None:
    return _run_big_exe(build_dir, "interfere_big_run", "big run", n, "triangles_per_part", "triangles per part",
                        threads, lambda r: f"build + query {r.get('build_and_query_s', 0):.3g} s, peak "
                                           f"{r.get('peak_rss_bytes', 0) / GB:.2f} GB")


def run_fem_big(build_dir: Path, n: str, threads: str | None) -> dict | None:
    """interfere_fem_big_run: a generated 1e7-tet MSH read, extracted and clashed (issue #3)."""
    return _run_big_exe(build_dir, "interfere_fem_big_run", "FEM big run", n, "elements", "tets", threads,
                        lambda r: f"read {r.get('read_s', 0):.3g} s, extract {r.get('extract_s', 0):.3g} s, "
                                  f"peak {r.get('peak_rss_gb', {}).get('end', 0):.2f} GB")


# ----------------------------------------------------------------------------- helpers
class Results:
    """Benchmarks by name (without the /real_time suffix). Rows run with repetitions are represented
    by their median aggregate (Google Benchmark's `_median`)."""

    def __init__(self, data: dict):
        self.by_name: dict[str, dict] = {}
        medians: dict[str, dict] = {}
        for b in data.get("benchmarks", []):
            name = normalize_name(b.get("run_name", b["name"]))
            if b.get("run_type", "iteration") == "aggregate":
                if b.get("aggregate_name") == "median":
                    medians[name] = b
                continue
            self.by_name.setdefault(name, b)  # first repetition, until a median replaces it
        self.by_name.update(medians)

    def find(self, pattern: str) -> dict | None:
        """The first benchmark whose name matches the regex `pattern` (re.search)."""
        for name, b in self.by_name.items():
            if re.search(pattern, name) and not b.get("error_occurred"):
                return b
        return None

    def get(self, name: str) -> dict | None:
        b = self.by_name.get(name)
        if b is None or b.get("error_occurred"):
            return None
        return b

    def error(self, name: str) -> str | None:
        b = self.by_name.get(name)
        return b.get("error_message") if b and b.get("error_occurred") else None

    def names(self, prefix: str) -> list[str]:
        return [n for n in self.by_name if n.startswith(prefix)]


_UNIT = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def seconds(b: dict | None, cpu: bool = False) -> float | None:
    """Wall time per iteration (CPU time for the single-threaded microbenchmarks with cpu=True)."""
    if not b:
        return None
    return b["cpu_time" if cpu else "real_time"] * _UNIT[b.get("time_unit", "ns")]


def fmt_time(s: float | None) -> str:
    if s is None:
        return "—"
    if s >= 3600:
        return f"{s / 3600:.1f} h"
    if s >= 120:
        return f"{s / 60:.1f} min"
    if s >= 1:
        return f"{s:.2f} s"
    if s >= 1e-3:
        return f"{s * 1e3:.3g} ms" if s * 1e3 < 100 else f"{s * 1e3:.0f} ms"
    if s >= 1e-6:
        return f"{s * 1e6:.3g} µs"
    return f"{s * 1e9:.3g} ns"


def fmt_rate(v: float | None, unit: str = "tri/s") -> str:
    if v is None:
        return "—"
    for scale, prefix in ((1e9, "G"), (1e6, "M"), (1e3, "k")):
        if v >= scale:
            return f"{v / scale:.3g} {prefix}{unit}"
    return f"{v:.3g} {unit}"


def fmt_int(v) -> str:
    if v is None:
        return "—"
    return f"{int(round(v)):,}"


def size_label(n: int) -> str:
    p, m = 0, n
    while m >= 10 and m % 10 == 0:
        m //= 10
        p += 1
    return f"1e{p}" if m == 1 and p > 0 else str(n)


def counter(b: dict | None, key: str):
    return None if b is None else b.get(key)


def verdict(ok: bool | None) -> str:
    return "—" if ok is None else ("**PASS**" if ok else "**MISS**")


CONTAINMENT = {0: "none", 1: "A inside B", 2: "B inside A", 3: "not checked"}
CONTACT_KIND = {0: "disjoint", 1: "touch", 2: "cross"}


def disagreement(peer: str, where: str, b: dict | None, kind: str) -> str | None:
    """One line for the first `extra` or `missing` pair a peer row recorded, or None."""
    if not b or b.get(f"first_{kind}_a") is None:
        return None
    text = (f"{peer} {where}: {fmt_int(b.get(kind))} {kind}, e.g. triangle {int(b[f'first_{kind}_a'])} "
            f"of A with {int(b[f'first_{kind}_b'])} of B")
    if kind == "extra":
        dist = b.get("first_extra_distance")
        text += " (exact test: disjoint" + (f"; distance {dist:.3g})" if dist is not None else ")")
    elif b.get("first_missing_kind") is not None:
        text += f" (exact test: {CONTACT_KIND.get(int(b['first_missing_kind']), '?')})"
    return text


def peer_disagreements(where: str, fp_where: str, fcl: dict | None, cgal: dict | None, examples: list,
                       fcl_fp: tuple[str, dict] | None) -> tuple[str, dict] | None:
    """The FCL and CGAL rows' first extra and missing pairs (disagreement, at `where`) appended to
    examples; returns FCL's first false positive (fp_where, row), the one given if already found."""
    for peer, b in (("FCL", fcl), ("CGAL", cgal)):
        for kind in ("extra", "missing"):
            text = disagreement(peer, where, b, kind)
            if text:
                examples.append(text)
                if peer == "FCL" and kind == "extra" and fcl_fp is None:
                    fcl_fp = (fp_where, b)
    return fcl_fp


def missing_extra_sentence(fcl_fp: tuple[str, dict] | None, meshes: str, cgal_rows: list) -> str:
    """The sentence under a peer table: what `missing` and `extra` mean, and FCL's first false
    positive as the example."""
    text = ("*missing* counts the pairs that our exact test finds intersecting (touching included) and "
            "the peer does not report; *extra* counts the pairs the peer reports although they are "
            "disjoint in exact arithmetic — false positives. ")
    cg = [b for b in cgal_rows if b]
    if cg and all(not b.get("missing") and not b.get("extra") for b in cg):
        text += ("CGAL's exact predicates agree with us on every pair here (0 / 0), so each "
                 "disagreement is the peer's double-precision test, not ours. ")
    if fcl_fp:
        where, b = fcl_fp
        dist = b.get("first_extra_distance")
        text += (f"Example of an FCL false positive ({where}): FCL reports triangle {int(b['first_extra_a'])} "
                 f"of A with triangle {int(b['first_extra_b'])} of B, which the exact test finds disjoint"
                 + (f", {dist:.3g} apart" if dist is not None else "")
                 + " — a gap that FCL's double-precision triangle test rounds away.")
    else:
        text += f"FCL reported no false positive on {meshes} in this run."
    return text


EXACT_SCENES = [
    (r"coplanar_face/n:(\d+)", "two boxes sharing a face, n = {0}",
     "`make_box([0,1]³, n)` and the same box translated by exactly its width along x: the two "
     "x = 1 faces coincide with identical grids"),
    (r"resting_box/n:(\d+)", "box resting on a bigger box, offset grids, n = {0}",
     "A = `make_box([-0.5,0.5]² × [0,1], n)` shifted by 0.6/n in x and y rests on "
     "B = `make_box([-1,1]² × [-1,0], n)`: coplanar contact in z = 0, grid spacings 1/n and 2/n that "
     "never line up"),
    (r"contained_sphere", "small sphere wholly inside a big sphere",
     "a closed bumpy sphere of radius 0.5, off-centre, inside a closed bumpy sphere of radius 1: no "
     "surface pair; the right answer is containment (A inside B)"),
    (r"rotated_sphere/0\.001rad", "sphere vs itself turned 1e-3 rad about z",
     "`make_sphere` against a copy of itself rotated 1e-3 rad about z"),
    (r"rotated_sphere/quarter_turn", "sphere vs itself turned exactly 90° about z",
     "`make_sphere` against a copy of itself rotated by exactly a quarter turn ((x, y) → (−y, x), "
     "exact in double): the copy's vertices land within rounding of the original's, so pairs of "
     "triangles nearly coincide"),
]


def exact_scene_label(scene: str) -> tuple[str, str]:
    for pattern, label, description in EXACT_SCENES:
        m = re.fullmatch(pattern, scene)
        if m:
            return label.format(*m.groups()), description
    return scene, ""


def exact_make_section(w, res: "Results", data: dict) -> None:
    """The "Exactness beside the peers" section (Exact/<scene>/<method> rows)."""
    scenes = list(dict.fromkeys(m.group(1) for n in res.by_name
                                for m in [re.match(r"^Exact/(.+)/(?:interfere|fcl|cgal)$", n)] if m))
    w("## Exactness beside the peers")
    w("")
    if not scenes:
        w("Not run (filtered out, or a binary without the Exact/ rows).")
        w("")
        return
    w("The issue: FCL's double-precision triangle tests report false pairs on coplanar contact, and it "
      "misses a part lying wholly inside another. Small fixed scenes (`bench/common.cpp`), all closed "
      "meshes, the same world coordinates handed to all three:")
    w("")
    described = set()
    for scene in scenes:
        label, description = exact_scene_label(scene)
        key = re.sub(r", n = \d+$", "", label)
        if description and key not in described:
            described.add(key)
            w(f"- *{key}*: {description}.")
    w("")
    threads = next((int(b["threads"]) for sc in scenes
                    for b in [res.get(f"Exact/{sc}/interfere")] if b and b.get("threads")), None)
    w("interfere: both default trees with statistics (closedness, needed for containment) + the default "
      "`clash()` (exact test with cross/touch classification, regions, containment)"
      + (f", {threads} thread{'s' if threads > 1 else ''}" if threads else "") + ". "
      "FCL: both `BVHModel<OBBRSS>` + `collide()` for all contacts, identity transforms. CGAL: "
      "`box_intersection_d` + `do_intersect` (Epick). *time*: wall time of each whole pipeline from the "
      "meshes in memory (build + query), for information only — ours includes the statistics, regions, "
      "curves and containment test that the peers do not compute.")
    w("")
    w("| scene | triangles A / B | interfere: pairs | interfere: containment | FCL: pairs | FCL: missing / extra "
      "| FCL: collide() | CGAL: pairs | CGAL: missing / extra | time: interfere / FCL / CGAL |")
    w("|---|---|---|---|---|---|---|---|---|---|")
    examples: list[str] = []
    fcl_fp = None
    cgal_rows = []
    for scene in scenes:
        label, _ = exact_scene_label(scene)
        ours, fcl, cgal = (res.get(f"Exact/{scene}/{m}") for m in ("interfere", "fcl", "cgal"))
        cgal_rows.append(cgal)
        anyb = ours or fcl or cgal
        tris = (f"{fmt_int(counter(anyb, 'tris_a'))} / {fmt_int(counter(anyb, 'tris_b'))}" if anyb else "—")
        if ours:
            pairs, cross, touch = ours.get("pairs", 0), ours.get("cross", 0), ours.get("touch", 0)
            if not pairs:
                op = "0"
            elif not cross:
                op = f"{fmt_int(pairs)} (all `touch`)"
            else:
                op = f"{fmt_int(pairs)} ({fmt_int(cross)} cross, {fmt_int(touch)} touch)"
            oc = CONTAINMENT.get(int(ours.get("containment", 3)), "?")
            if int(ours.get("containment", 0)) in (1, 2):
                oc = f"**{oc}** (interference, no surface pair)"
        else:
            err = res.error(f"Exact/{scene}/interfere")
            op, oc = ("error: " + err if err else "—"), "—"

        def peer_cells(b: dict | None, name: str) -> tuple[str, str]:
            if not b:
                err = res.error(name)
                return ("error: " + err if err else "—"), "—"
            return fmt_int(b.get("pairs")), f"{fmt_int(b.get('missing'))} / {fmt_int(b.get('extra'))}"

        fp, fd = peer_cells(fcl, f"Exact/{scene}/fcl")
        cp, cd = peer_cells(cgal, f"Exact/{scene}/cgal")
        fcoll = "—" if not fcl or fcl.get("fcl_collides") is None else (
            "collision" if fcl["fcl_collides"] else "**no collision**")
        times = " / ".join(fmt_time(seconds(b)) for b in (ours, fcl, cgal))
        w(f"| {label} | {tris} | {op} | {oc} | {fp} | {fd} | {fcoll} | {cp} | {cd} | {times} |")
        fcl_fp = peer_disagreements(f"on {label}", f"{label}", fcl, cgal, examples, fcl_fp)
    w("")
    # A one-line summary of what this run found, from the counters (not a fixed claim).
    fcl_bad = [exact_scene_label(sc)[0] for sc in scenes for b in [res.get(f"Exact/{sc}/fcl")]
               if b and (b.get("missing") or b.get("extra"))]
    cgal_bad = [exact_scene_label(sc)[0] for sc in scenes for b in [res.get(f"Exact/{sc}/cgal")]
                if b and (b.get("missing") or b.get("extra"))]
    missed_containment = [exact_scene_label(sc)[0] for sc in scenes
                          for o, f in [(res.get(f"Exact/{sc}/interfere"), res.get(f"Exact/{sc}/fcl"))]
                          if o and f and int(o.get("containment", 0)) in (1, 2) and not f.get("fcl_collides")]
    n_fcl = sum(1 for sc in scenes if res.get(f"Exact/{sc}/fcl"))
    n_cgal = sum(1 for sc in scenes if res.get(f"Exact/{sc}/cgal"))
    if n_fcl or n_cgal:
        summary = "In this run: "
        if n_fcl:
            summary += (f"FCL's pair set differs from the exact one on {len(fcl_bad)} of {n_fcl} scenes"
                        + (f" ({'; '.join(fcl_bad)})" if fcl_bad else ""))
            if missed_containment:
                summary += ", and `collide()` reports no collision for the contained part"
            summary += "; "
        if n_cgal:
            summary += f"CGAL's differs on {len(cgal_bad)} of {n_cgal}" + (f" ({'; '.join(cgal_bad)})" if cgal_bad else "")
        w(summary.rstrip("; ") + ".")
        w("")
    w(missing_extra_sentence(fcl_fp, "these scenes", cgal_rows)
      + " Containment is not a pair: FCL's `collide()` and CGAL's box sweep see no intersecting "
        "triangles when one part lies wholly inside the other, so they report nothing; the engine "
        "answers it with a point-in-closed-mesh test (`ClashResult::containment`).")
    w("")
    if examples:
        w("Disagreements with the exact result:")
        w("")
        for e in examples:
            w(f"- {e}")
        w("")


# ----------------------------------------------------------------------------- report
STRATEGIES = [
    ("1_brute_force_moller", "(1) brute force, Möller 1997 (double)"),
    ("2_brute_force_guigue_devillers", "(2) brute force, Guigue–Devillers 2003 (double)"),
    ("3_box_pretest", "(3) per-triangle AABB pre-test, exact test"),
    ("4_insertion_tree", "(4) insertion-built tree, exact test"),
    ("5_median_split_tree", "(5) split-optimised (median) tree, exact test"),
    ("6_sah_tree_parallel", "(6) binned-SAH tree, parallel, exact test"),
    ("7_default_tree_parallel", "(7) = (6) on the engine's default tree ({default}), parallel"),
]


def sizes_in(res: Results) -> list[str]:
    found = set()
    for n in res.by_name:
        m = re.match(r"^(?:Strategy|Build|Engine)/.+?/(1e\d+|\d+)(?:/|$)", n)
        if m:
            found.add(m.group(1))
    return sorted(found, key=lambda s: float(s))


def threads_in(res: Results) -> list[int]:
    found = set()
    for n in res.by_name:
        m = re.search(r"/threads:(\d+)$", n)
        if m:
            found.add(int(m.group(1)))
    return sorted(found) or [1]


def make_markdown(data: dict, machine: dict, big: dict | None, big_small: dict | None,
                  big_note: str, fem_big: dict | None = None, fem_big_note: str = "") -> tuple[str, list[dict]]:
    res = Results(data)
    ctx = data.get("context", {})
    sizes = sizes_in(res)
    threads = threads_in(res)
    tmax = max(threads)
    default_builder = ctx.get("default_builder", "lbvh")
    L: list[str] = []
    w = L.append

    w("# Benchmarks")
    w("")
    w("Generated by `python3 bench/run_benchmarks.py"
      + (" --quick" if data["settings"].get("quick") else "") + "` — do not edit by hand; the raw "
      "Google Benchmark output (plus the big run) is kept in [benchmarks.json](benchmarks.json).")
    w("")
    w("## Machine")
    w("")
    w("| | |")
    w("|---|---|")
    merged = data["settings"].get("filter_merged_into")
    w(f"| date | {machine.get('date_utc')}"
      + (f" (only rows matching `{data['settings'].get('filter')}`; the others are from an earlier run)" if merged else "")
      + " |")
    w(f"| CPU | {machine.get('cpu_model')} ({machine.get('simd', '')}) |")
    w(f"| cores usable (nproc) | {machine.get('nproc')} of {machine.get('cpu_count')} |")
    w(f"| memory | {machine.get('memory_gib', '?')} GiB |")
    w(f"| load average at start | {machine.get('loadavg_at_start', '?')} (machine shared with other builds) |")
    w(f"| OS | {machine.get('system')} {machine.get('kernel')} |")
    w(f"| compiler | {ctx.get('compiler', '?')}, {ctx.get('interfere_build', '?')} (CMake Release, -O3) |")
    w(f"| oneTBB | {ctx.get('tbb_version', '?')} |")
    w(f"| peers | FCL {ctx.get('fcl_version', 'not built')}, CGAL {ctx.get('cgal_version', 'not built')} |")
    w(f"| Google Benchmark | min_time {data['settings'].get('benchmark_min_time')} s, wall-clock (real) time |")
    w("")
    w("Geometry: `make_overlapping_spheres(n)` — two closed bumpy UV spheres of about n triangles each "
      "(the nearest UV-sphere size), radius 1, centres 1.96 apart, about 1 % of each surface inside the "
      "other. Sizes below are triangles **per part**. Thread counts are set with `tbb::global_control`.")
    w("")

    # ---- targets
    # The issue states its targets "on this 2-core machine": they are judged on the 2-thread rows with
    # the default builder only. Rows on other thread counts or builders are information, no verdict.
    targets: list[dict] = []
    info: list[dict] = []

    def target(name: str, measured: str, ok: bool | None, value=None, note: str = "") -> None:
        targets.append({"target": name, "measured": measured, "pass": ok, "value": value, "note": note})

    def information(name: str, measured: str, value=None, note: str = "") -> None:
        info.append({"measurement": name, "measured": measured, "value": value, "note": note})

    it = ISSUE_THREADS
    quick = bool(data.get("settings", {}).get("quick"))
    missing = f"not measured (run with {it} threads)"
    bd = res.get(f"Bvh/Build/{default_builder}/1e6/threads:{it}")
    v = counter(bd, "items_per_second")
    target(f"tree build, default builder ({default_builder}), 1e6 triangles, {it} threads ≥ 30 M tri/s",
           missing if v is None else fmt_rate(v), None if v is None else v >= 30e6, v)
    rf = res.get(f"Bvh/Refit/1e6/threads:{it}")
    v = counter(rf, "items_per_second")
    target(f"refit, 1e6 triangles, {it} threads ≥ 100 M tri/s", missing if v is None else fmt_rate(v),
           None if v is None else v >= 100e6, v)
    e2e = res.get(f"Engine/end_to_end/1e6/threads:{it}")
    s = seconds(e2e)
    target(f"end to end 1e6 × 1e6, both trees built + exact clash + regions, {it} threads ≤ 60 ms",
           missing if s is None else fmt_time(s), None if s is None else s <= 0.060, s)
    # Single-threaded microbenchmark: CPU time is the robust measure on a shared machine.
    ex = seconds(res.get("BM_TriTri_exact_intersects"), cpu=True)
    gd = seconds(res.get("BM_TriTri_guigue_devillers"), cpu=True)
    ratio = ex / gd if ex and gd else None
    target("exact tri-tri (yes/no) ≤ 1.5 × double Guigue–Devillers",
           "—" if ratio is None else f"{ratio:.2f} ×", None if ratio is None else ratio <= 1.5, ratio)
    if big and "peak_rss_bytes" in big and big.get("triangles_per_part", 0) >= 1e7:
        peak = big["peak_rss_bytes"]
        target("1e7 × 1e7 peak memory ≤ 6 GB", f"{peak / GB:.2f} GB", peak <= 6 * GB, peak, big_note)
    else:
        target("1e7 × 1e7 peak memory ≤ 6 GB", "not run (use --big)", None, None)
    rd = res.get("BM_ReadStlBinary_weld")
    v = counter(rd, "bytes_per_second")
    target("binary STL read (with exact weld) ≥ 1 GB/s", "—" if v is None else f"{v / GB:.2f} GB/s",
           None if v is None else v >= GB, v)

    # Issue #3 (FEM) targets, from bench_fem.cpp and interfere_fem_big_run.
    fem_x = res.find(rf"BM_FemExtract/tet4/\d+/1000000/{it}(/|$)")
    v = counter(fem_x, "elements_per_s")
    target(f"FEM surface extraction, linear tets (~1e6), {it} threads ≥ 5 M elements/s (issue #3)",
           missing if v is None else fmt_rate(v, "elements/s"), None if v is None else v >= 5e6, v)
    fem_s = res.find(rf"BM_FemSeriesStep/1000000/{it}(/|$)")
    s = seconds(fem_s)
    target(f"FEM per step refit + clash, two ~1e6-element parts, {it} threads ≤ 20 ms (issue #3)",
           missing if s is None else fmt_time(s), None if s is None else s <= 0.020, s)
    if fem_big and "peak_rss_gb" in fem_big and fem_big.get("elements", 0) >= 1e7:
        peak = max(fem_big["peak_rss_gb"].values())
        target("FEM 1e7-tet model read, extracted and clashed within 8 GB (issue #3)",
               f"{peak:.2f} GB peak (read {fmt_time(fem_big.get('read_s'))}, extract "
               f"{fmt_time(fem_big.get('extract_s'))}, clash {fmt_time(fem_big.get('clash_s'))})",
               peak <= 8, peak, fem_big_note)
    else:
        target("FEM 1e7-tet model read, extracted and clashed within 8 GB (issue #3)",
               "not run (use --big)", None, None)

    # Information rows: the same measurements on other thread counts / builders.
    def plural(t: int) -> str:
        return f"{t} thread{'s' if t > 1 else ''}"

    for builder in dict.fromkeys((default_builder, "binned_sah")):
        for t in threads:
            if builder == default_builder and t == it:
                continue  # the judged row
            v = counter(res.get(f"Bvh/Build/{builder}/1e6/threads:{t}"), "items_per_second")
            if v is not None:
                tag = "default builder" if builder == default_builder else "not the default builder"
                information(f"tree build, {builder} ({tag}), 1e6 triangles, {plural(t)}", fmt_rate(v), v)
    for t in threads:
        if t != it:
            v = counter(res.get(f"Bvh/Refit/1e6/threads:{t}"), "items_per_second")
            if v is not None:
                information(f"refit, 1e6 triangles, {plural(t)}", fmt_rate(v), v)
    for t in threads:
        if t != it:
            s = seconds(res.get(f"Engine/end_to_end/1e6/threads:{t}"))
            if s is not None:
                information(f"end to end 1e6 × 1e6, {plural(t)}", fmt_time(s), s)
    if big_small and "build_and_query_s" in big_small:
        s = big_small["build_and_query_s"]
        information(f"end to end 1e6 × 1e6 in a fresh process (`interfere_big_run`, "
                    f"{plural(int(big_small.get('threads', 0)))}; first touch of every page included)",
                    fmt_time(s), s)

    w("## Targets")
    w("")
    w(f"The issue's targets, stated for this 2-core machine: judged on the {it}-thread rows with the "
      f"default builder (`{default_builder}`)."
      + (" Quick run (short timing, no repetitions): the verdicts are indicative only." if quick else ""))
    w("")
    w("| target | measured | verdict |")
    w("|---|---|---|")
    for t in targets:
        note = f" ({t['note']})" if t["note"] else ""
        w(f"| {t['target']} | {t['measured']}{note} | {verdict(t['pass'])} |")
    w("")
    if info:
        w("For information only — not targets of the issue, so no verdict: the same measurements on "
          "other thread counts and on a non-default builder.")
        w("")
        w("| measurement (information, no verdict) | measured |")
        w("|---|---|")
        for t in info:
            note = f" ({t['note']})" if t["note"] else ""
            w(f"| {t['measurement']} | {t['measured']}{note} |")
        w("")

    # ---- strategy table
    w("## The paper's strategy table (query only, trees prebuilt)")
    w("")
    brute_max = int(float(data["settings"].get("INTERFERE_BENCH_BRUTE_MAX", "1e4")))
    pretest_max = int(float(data["settings"].get("INTERFERE_BENCH_PRETEST_MAX", "1e5")))
    w("Time of `clash()` with `regions = false, containment = false` (the sorted pair list only); the "
      "trees are built beforehand (next table). Rows 1–5 run on one thread. The O(n²) rows are capped "
      f"at {size_label(brute_max)} (brute force) and {size_label(pretest_max)} (box pre-test) triangles "
      "per part: they make |A|·|B| triangle (or box) tests, so a brute-force row at 1e5 × 1e5 is 1e10 "
      "triangle tests, minutes per iteration. Capped cells show the O(n²) extrapolation from the largest "
      "measured size (marked ≈). Lift the caps with INTERFERE_BENCH_BRUTE_MAX / --pretest-max. "
      "Cells: wall time (triangle pairs found).")
    w("")
    w("| strategy | " + " | ".join(sizes) + " |")
    w("|---|" + "---|" * len(sizes))
    for key, label in STRATEGIES:
        label = label.format(default=default_builder)
        variants = [(f"Strategy/{key}/{{n}}", label)] if key[0] not in "67" else [
            (f"Strategy/{key}/{{n}}/threads:{t}", f"{label}, {t} thread{'s' if t > 1 else ''}") for t in threads]
        for pattern, lab in variants:
            cells = []
            last = None  # (triangles per part, seconds) of the largest measured size
            for n in sizes:
                b = res.get(pattern.format(n=n))
                err = res.error(pattern.format(n=n))
                if b:
                    cells.append(f"{fmt_time(seconds(b))} ({fmt_int(b.get('pairs'))})")
                    last = (float(n), seconds(b))
                elif err:
                    cells.append("error: " + err)
                elif last and key[0] in "123":
                    cells.append(f"capped (≈ {fmt_time(last[1] * (float(n) / last[0]) ** 2)})")
                else:
                    cells.append("not run")
            w(f"| {lab} | " + " | ".join(cells) + " |")
    w("")
    w("Tree builds (both parts one after the other, `make_model` without statistics; meshes copied outside the timing):")
    w("")
    w("| builder | threads | " + " | ".join(sizes) + " |")
    w("|---|---|" + "---|" * len(sizes))
    for builder in ("insertion", "median_split", "binned_sah", "lbvh"):
        for t in threads:
            row = [res.get(f"Build/{builder}/{n}/threads:{t}") for n in sizes]
            if not any(row):
                continue
            cells = [f"{fmt_time(seconds(b))} ({fmt_rate(counter(b, 'items_per_second'))})" if b else "—" for b in row]
            w(f"| {builder} | {t} | " + " | ".join(cells) + " |")
    w("")

    # ---- engine end to end
    w("## Default engine end to end")
    w("")
    w(f"Meshes in memory → both default trees (`{default_builder}`, built concurrently by `make_models`, as the CLI "
      "and the Python API do) → `clash()` with the default request "
      "(exact test with cross/touch classification, regions with intersection curves, containment) → "
      "sorted pair list. *query* is the same `clash()` alone on prebuilt trees.")
    w("")
    w("| size | threads | end to end | query | throughput | pairs | cross | touch | candidates | regions | curves |")
    w("|---|---|---|---|---|---|---|---|---|---|---|")
    for n in sizes:
        for t in threads:
            b = res.get(f"Engine/end_to_end/{n}/threads:{t}")
            if not b:
                continue
            q = res.get(f"Engine/query_default/{n}/threads:{t}")
            w(f"| {n} | {t} | {fmt_time(seconds(b))} | {fmt_time(seconds(q))} | {fmt_rate(counter(b, 'items_per_second'))} | "
              f"{fmt_int(b.get('pairs'))} | {fmt_int(b.get('cross'))} | {fmt_int(b.get('touch'))} | "
              f"{fmt_int(b.get('candidates'))} | {fmt_int(b.get('regions'))} | {fmt_int(b.get('curves'))} |")
    w("")

    # ---- peers
    w("## Peers on the same meshes")
    w("")
    w("FCL: `BVHModel<OBBRSS>` (beginModel/addSubModel/endModel) for both parts, then `collide()` with "
      "`CollisionRequest(num_max_contacts = 2^40, enable_contact = false)`, all contacts. CGAL: "
      "`box_intersection_d` over triangle boxes + `do_intersect` (Epick, exact predicates), all pairs, "
      "from the meshes in memory. Both peers are single-threaded. `missing`/`extra` compare each peer's "
      "pair set with our exact pair set (0/0 = identical).")
    w("")
    w("Our rows: both trees built (`make_model`, default builder) + `clash()` pair list (exact test, no "
      "regions) — the same work as the peers do. Our `missing`/`extra` are 0 by definition (reference).")
    w("")
    w("| size | method | build | query | total | pairs | missing | extra |")
    w("|---|---|---|---|---|---|---|---|")
    examples: list[str] = []
    fcl_false_positive = None  # (where, benchmark) of FCL's first extra pair
    for n in sizes:
        rows = []
        for t in sorted({1, tmax}):
            bb = res.get(f"Build/{default_builder}/{n}/threads:{t}")
            bq = res.get(f"Strategy/7_default_tree_parallel/{n}/threads:{t}")
            if bb or bq:
                sb, sq = seconds(bb), seconds(bq)
                tot = sb + sq if sb is not None and sq is not None else None
                rows.append((f"interfere ({default_builder}, exact, {t} thread{'s' if t > 1 else ''})", sb, sq,
                             tot, counter(bq, "pairs"), 0 if bq else None, 0 if bq else None))
        fb, fc = res.get(f"Peer/fcl/build/{n}"), res.get(f"Peer/fcl/collide/{n}")
        if fb or fc:
            sb, sq = seconds(fb), seconds(fc)
            tot = sb + sq if sb is not None and sq is not None else None
            rows.append(("FCL 0.7 OBBRSS (double tri test)", sb, sq, tot, counter(fc, "pairs"),
                         counter(fc, "missing"), counter(fc, "extra")))
        cg = res.get(f"Peer/cgal/box_intersection_d/{n}")
        if cg:
            rows.append(("CGAL box_intersection_d + do_intersect (exact)", None, None, seconds(cg),
                         counter(cg, "pairs"), counter(cg, "missing"), counter(cg, "extra")))
        for lab, sb, sq, tot, pairs, miss, extra in rows:
            w(f"| {n} | {lab} | {fmt_time(sb)} | {fmt_time(sq)} | {fmt_time(tot)} | {fmt_int(pairs)} | "
              f"{fmt_int(miss)} | {fmt_int(extra)} |")
        fcl_false_positive = peer_disagreements(f"at {n}", f"at {n}", fc, cg, examples, fcl_false_positive)
    w("")
    w(missing_extra_sentence(fcl_false_positive, "the sphere pairs",
                             [res.get(f"Peer/cgal/box_intersection_d/{n}") for n in sizes]))
    w("")
    if examples:
        w("Disagreements with the exact result (check a pair with `tri_tri_exact` and "
          "`triangle_triangle_closest`):")
        w("")
        for e in examples:
            w(f"- {e}")
        w("")

    # ---- exactness scenes
    exact_make_section(w, res, data)

    # ---- microbenchmarks
    fem_rows = [(n, b) for n, b in res.by_name.items() if n.startswith(("BM_FemExtract/", "BM_FemSeriesStep/",
                                                                          "BM_FemRead_"))]
    if fem_rows:
        w("## FEM models (issue #3)")
        w("")
        w("Surface extraction (`bench/bench_fem.cpp`): generated boxes (`make_fem_box`) of each element type, "
          "`extract_surface` with the default options (quadratic faces subdivided), wall time per call. "
          "Series: two tet4 parts (a cube and a ball moving into it over 100 steps), one step = deformed "
          "positions + refit of both trees + the default `clash()`. Reading: a generated box of about 1e6 tets "
          "(`bench/bench_fem_io.cpp`, one thread), the gmsh SDK as the peer where built.")
        w("")
        w("| benchmark | elements | threads | time | throughput |")
        w("|---|---|---|---|---|")
        for n, b in fem_rows:
            el = b.get("elements") or b.get("elements_a")
            th = b.get("threads", "—")
            rate = b.get("elements_per_s")
            label = n.split("/min_time")[0]
            w(f"| `{label}` | {'—' if el is None else f'{el:,.0f}'} | "
              f"{'—' if th == '—' else int(th)} | {fmt_time(seconds(b))} | "
              f"{'—' if rate is None else fmt_rate(rate, 'elements/s')} |")
        if fem_big and "peak_rss_gb" in fem_big:
            w("")
            w(f"1e7 run (`interfere_fem_big_run`{', ' + fem_big_note if fem_big_note else ''}): "
              f"{fem_big.get('elements', 0):,.0f} tets written as binary MSH 4.1 and read back in "
              f"{fmt_time(fem_big.get('read_s'))}, surface of {fem_big.get('surface_triangles', 0):,} triangles "
              f"extracted in {fmt_time(fem_big.get('extract_s'))}, trees built in {fmt_time(fem_big.get('build_s'))} "
              f"and clashed against a 1e6-tet ball in {fmt_time(fem_big.get('clash_s'))}; peak resident set "
              f"{max(fem_big['peak_rss_gb'].values()):.2f} GB.")
        w("")

    w("## Microbenchmarks")
    w("")
    tt = [("BM_TriTri_exact_intersects", "exact, yes/no (`tri_tri_exact_intersects`)"),
          ("BM_TriTri_exact_classify", "exact + classification + segment (`tri_tri_exact`)"),
          ("BM_TriTri_guigue_devillers", "Guigue–Devillers, double"),
          ("BM_TriTri_moller", "Möller, double")]
    any_tt = res.get(tt[0][0]) or res.get(tt[2][0])
    w("Triangle–triangle tests on every box-overlapping pair of the 1e5 sphere pair "
      f"({fmt_int(counter(any_tt, 'pairs'))} pairs, one thread, CPU time):")
    w("")
    w("| test | time per pair | relative to GD | pairs reported intersecting |")
    w("|---|---|---|---|")
    for name, lab in tt:
        b = res.get(name)
        if not b:
            w(f"| {lab} | — | — | — |")
            continue
        per = seconds(b, cpu=True) / b["pairs"] if b.get("pairs") else None
        rel = seconds(b, cpu=True) / gd if gd else None
        w(f"| {lab} | {fmt_time(per)} | {'—' if rel is None else f'{rel:.2f} ×'} | {fmt_int(b.get('hits'))} |")
    w("")
    w("BVH alone (`bench/bench_bvh.cpp`, one tree of `make_sphere`; throughput = triangles / wall time):")
    w("")
    bvh_sizes = sorted({m.group(1) for n in res.by_name
                        for m in [re.match(r"^Bvh/(?:Build/[^/]+|Refit)/([^/]+)/", n)] if m}, key=float)
    w("| operation | threads | " + " | ".join(bvh_sizes) + " |")
    w("|---|---|" + "---|" * len(bvh_sizes))
    ops = [f"Build/{b}" for b in ("insertion", "median_split", "binned_sah", "lbvh")] + ["Refit"]
    for op in ops:
        for t in threads:
            row = [res.get(f"Bvh/{op}/{n}/threads:{t}") for n in bvh_sizes]
            if any(row):
                cells = [f"{fmt_time(seconds(b))} ({fmt_rate(counter(b, 'items_per_second'))})" if b else "—"
                         for b in row]
                w(f"| {op.lower().replace('/', ' ')} | {t} | " + " | ".join(cells) + " |")
    overlap = [n for n in res.by_name if n.startswith("Bvh/Overlap/")]
    if overlap:
        w("")
        w("Tree-vs-tree box overlap only (no triangle test), sphere pair 1e6 (`bench_bvh.cpp`):")
        w("")
        w("| builder | margin | traversal | time | box pairs |")
        w("|---|---|---|---|---|")
        for n in overlap:
            m = re.match(r"^Bvh/Overlap/([^/]+)/[^/]+/margin:([^/]+)/(.+)$", n)
            b = res.get(n)
            if m and b:
                w(f"| {m.group(1)} | {m.group(2)} | {m.group(3).replace('/threads:', ', threads ')} | "
                  f"{fmt_time(seconds(b))} | {fmt_int(b.get('pairs'))} |")
    w("")
    w("Binary STL read (generated bumpy sphere written to a temporary folder, read from the page cache):")
    w("")
    w("| read | file | time | throughput | triangles/s |")
    w("|---|---|---|---|---|")
    for name, lab in (("BM_ReadStlBinary_weld", "default (exact weld)"), ("BM_ReadStlBinary_noweld", "weld = false")):
        b = res.get(name)
        if b:
            w(f"| {lab} | {b.get('file_bytes', 0) / 1e6:.0f} MB | {fmt_time(seconds(b))} | "
              f"{b.get('bytes_per_second', 0) / GB:.2f} GB/s | {fmt_rate(b.get('items_per_second'))} |")
        elif res.error(name):
            w(f"| {lab} | — | error: {res.error(name)} | — | — |")
    w("")

    # ---- shared data
    data_rows = [n for n in res.by_name if n.startswith("Data/")]
    w("## Shared test meshes")
    w("")
    if data_rows:
        w("Clashes between meshes of `../shared/data/mesh` (both default trees + default clash, end to end):")
        w("")
        w("| case | threads | triangles A / B | time | pairs | cross | touch | regions |")
        w("|---|---|---|---|---|---|---|---|")
        for n in data_rows:
            b = res.get(n)
            if b:
                case, _, th = n[5:].partition("/threads:")
                w(f"| {case} | {th} | {fmt_int(b.get('tris_a'))} / {fmt_int(b.get('tris_b'))} | {fmt_time(seconds(b))} | "
                  f"{fmt_int(b.get('pairs'))} | {fmt_int(b.get('cross'))} | {fmt_int(b.get('touch'))} | "
                  f"{fmt_int(b.get('regions'))} |")
    else:
        w("Skipped: `../shared/data/mesh` not present (or filtered out).")
    w("")

    # ---- big run
    w("## Large runs (`interfere_big_run`)")
    w("")
    w("Generation, both default trees (meshes moved in, no copy), default clash; peak resident set from "
      "`getrusage` (includes the generated meshes).")
    w("")
    w("| triangles per part | threads | build | query | build + query | pairs | regions | peak memory | when |")
    w("|---|---|---|---|---|---|---|---|---|")
    for r in (big_small, big):
        if not r:
            continue
        if "error" in r:
            w(f"| {size_label(int(r['triangles_per_part']))} | — | failed: {r['error']} | | | | | | |")
            continue
        w(f"| {size_label(int(r['triangles_per_part']))} | {r['threads']} | {fmt_time(r['build_s'])} | "
          f"{fmt_time(r['query_s'])} | {fmt_time(r['build_and_query_s'])} | {fmt_int(r['pairs'])} | "
          f"{fmt_int(r['regions'])} | {r['peak_rss_bytes'] / GB:.2f} GB | {r.get('date_utc', '')} |")
    if not big:
        w("| 1e7 | | not run: `run_benchmarks.py --big` | | | | | | |")
    w("")

    # ---- failures
    if data.get("crashed") or any(b.get("error_occurred") for b in data.get("benchmarks", [])):
        w("## Failed benchmarks")
        w("")
        for c in data.get("crashed", []):
            w(f"- `{c['name']}` crashed the benchmark process (exit status {c['exit_status']}); "
              "the run continued after it.")
        for b in data.get("benchmarks", []):
            if b.get("error_occurred"):
                w(f"- `{b['name']}`: {b.get('error_message')}")
        w("")

    # ---- notes
    reps = int(data["settings"].get("INTERFERE_BENCH_REPETITIONS", "3"))
    w("## Method notes")
    w("")
    w("- Times are wall-clock (`UseRealTime`, except the single-threaded triangle-test microbenchmarks: CPU "
      "time), the mean over Google Benchmark's iterations. "
      + (f"The end-to-end 1e6, STL-read and triangle-test rows are repeated {reps} times and the median is "
         "shown; the BVH rows of `bench_bvh.cpp` run once. " if reps > 1 else "No repetitions (quick run). ")
      + "Models are cached between rows, so no row pays for another's setup.")
    w("- *Build* and *query* are timed separately; *end to end* times both trees' builds plus the query, "
      "from meshes in memory to the sorted pair list. Freeing the previous iteration's models and "
      "copying the input meshes are outside the timing.")
    w("- `interfere_big_run` starts a fresh process per size, so its build times include the first touch "
      "of every new page; the Google Benchmark rows run with the allocator's memory already warm.")
    w("- Strategy rows 3–7 use the exact test: there the broad phase decides the cost (the candidate count "
      "is small); the triangle tests are compared on their own in the microbenchmarks.")
    w("- Pair counts of rows 1–2 come from non-robust double tests and may differ from the exact count.")
    w("- The machine is shared with other compiling engineers; expect a few percent of noise.")
    w("")
    return "\n".join(L), targets, info


def regenerate_from_json(docs: Path) -> None:
    """Rewrites benchmarks.md from the kept benchmarks.json (no run): for report-format changes."""
    raw = json.loads((docs / "benchmarks.json").read_text())
    big = raw.get("big_run")
    note = raw.get("big_run_note", "")
    md, targets, info = make_markdown(raw["google_benchmark"], raw["machine"], big, raw.get("big_run_1e6"),
                                      note)
    raw["targets"] = targets
    raw["target_information"] = info
    (docs / "benchmarks.json").write_text(json.dumps(raw, indent=1) + "\n")
    (docs / "benchmarks.md").write_text(md + "\n")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true",
                    help="smoke run in under 3 minutes: min_time 0.01 s, no repetitions, box pre-test only "
                         "at 1e4, peers only up to 1e5, exactness boxes only at n = 50")
    ap.add_argument("--big", action="store_true", help="also run interfere_big_run at --big-n")
    ap.add_argument("--big-n", default="1e7", help="triangles per part of the big run (default 1e7)")
    ap.add_argument("--build-dir", default=str(ROOT / "build-bench"))
    ap.add_argument("--no-build", action="store_true", help="use the existing build")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--min-time", type=float, default=None, help="--benchmark_min_time (s)")
    ap.add_argument("--filter", default=None, help="--benchmark_filter regex")
    ap.add_argument("--threads", default=None, help="thread counts, e.g. 1,2 (default 1,2)")
    ap.add_argument("--pretest-max", default=None, help="largest size for the box pre-test row (default 1e5)")
    ap.add_argument("--docs", default=str(ROOT / "docs"), help="where benchmarks.md/.json go")
    ap.add_argument("--report-only", action="store_true",
                    help="only rewrite benchmarks.md from the existing benchmarks.json")
    args = ap.parse_args()
    if args.report_only:
        regenerate_from_json(Path(args.docs))
        return 0

    started = time.monotonic()
    build_dir = Path(args.build_dir)
    docs = Path(args.docs)
    machine = machine_description()
    if not args.no_build:
        configure_and_build(build_dir, args.jobs)
    data = run_bench(build_dir, args)
    old_json = docs / "benchmarks.json"
    if args.filter and old_json.exists():
        # A subset run updates its rows in the kept report and leaves the others as they were.
        try:
            old = json.loads(old_json.read_text())["google_benchmark"]
            fresh = {normalize_name(b.get("run_name", b["name"])) for b in data["benchmarks"]}
            fresh |= {c["name"] for c in data.get("crashed", [])}
            data["benchmarks"] = [b for b in old.get("benchmarks", [])
                                  if normalize_name(b.get("run_name", b["name"])) not in fresh] + data["benchmarks"]
            data["crashed"] = [c for c in old.get("crashed", []) if c["name"] not in fresh] + data["crashed"]
            data["settings"]["filter_merged_into"] = old.get("settings", {})
        except (OSError, ValueError, KeyError):
            log("could not merge into the previous benchmarks.json; writing the subset only")

    threads = None
    if args.threads:
        threads = str(max(int(t) for t in args.threads.split(",")))
    big_small = run_big(build_dir, "1e6", threads)

    def big_or_previous(runner, key: str) -> tuple[dict | None, str]:
        """With --big the run itself; else the kept report's `key` row (unless it failed), with a note."""
        if args.big:
            return runner(build_dir, args.big_n, threads), ""
        if old_json.exists():
            try:
                prev = json.loads(old_json.read_text()).get(key)
                if prev and "error" not in prev:
                    return prev, f"from the run of {prev.get('date_utc', 'an earlier date')}"
            except (OSError, ValueError):
                pass
        return None, ""

    big, big_note = big_or_previous(run_big, "big_run")
    fem_big, fem_big_note = big_or_previous(run_fem_big, "fem_big_run")

    md, targets, info = make_markdown(data, machine, big, big_small, big_note, fem_big, fem_big_note)
    docs.mkdir(parents=True, exist_ok=True)
    raw = {"machine": machine, "google_benchmark": data, "big_run_1e6": big_small, "big_run": big,
           "fem_big_run": fem_big,
           "big_run_note": big_note, "targets": targets, "target_information": info}
    (docs / "benchmarks.json").write_text(json.dumps(raw, indent=1) + "\n")
    (docs / "benchmarks.md").write_text(md + "\n")
    log(f"wrote {docs / 'benchmarks.md'} and {docs / 'benchmarks.json'}")
    for t in targets:
        log(f"  {'PASS' if t['pass'] else ('MISS' if t['pass'] is False else '----')}  {t['target']}: {t['measured']}")
    for t in info:
        log(f"  info  {t['measurement']}: {t['measured']}")
    log(f"total {_elapsed(time.monotonic() - started)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
