"""A Google Benchmark executable's JSON results, for the bench/*_tables.py scripts."""
from __future__ import annotations

import json
import tempfile
from pathlib import Path


def google_benchmark_json(run, exe: Path, repetitions: int, env: dict, bench_filter: str | None = None) -> dict:
    """exe run through run(cmd, check=True, env=env) (the calling script's logging runner) with the console
    output shown and the JSON written to a temporary file, read back and removed: `repetitions` runs of
    each row, only those matching bench_filter when given."""
    with tempfile.NamedTemporaryFile(suffix=".json", delete=False) as f:
        out = Path(f.name)
    cmd = [exe, "--benchmark_format=console", f"--benchmark_out={out}", "--benchmark_out_format=json",
           f"--benchmark_repetitions={repetitions}"]
    if bench_filter:
        cmd.append(f"--benchmark_filter={bench_filter}")
    run(cmd, check=True, env=env)
    data = json.loads(out.read_text())
    out.unlink()
    return data
