#!/usr/bin/env python3
"""Compares two scene clash reports (docs/report.md) apart from what may differ between a run on
one process and one on K MPI ranks (docs/mpi.md): seconds, timings_s, threads (also under options) and the "mpi"
section. summary.core_runs is compared: a class of pairs the engine decides once stays on one rank (issue #31).
Usage: compare_reports.py SINGLE.json MPI.json; exit 0 when equal, 1 with the first differences."""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli"))
import report_schema  # noqa: E402  (both reports against docs/schema, issue #30)


def strip(r):
    r = dict(r)
    for k in ("timings_s", "threads", "mpi", "seconds"):
        r.pop(k, None)
    if "options" in r:
        r["options"] = {k: v for k, v in r["options"].items() if k != "threads"}
    return r


def diff(a, b, path="$", out=None):
    out = [] if out is None else out
    if type(a) != type(b):
        out.append("%s: %r != %r" % (path, a, b))
    elif isinstance(a, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                out.append("%s.%s: only in %s" % (path, k, "first" if k in a else "second"))
            else:
                diff(a[k], b[k], path + "." + k, out)
    elif isinstance(a, list):
        if len(a) != len(b):
            out.append("%s: %d != %d items" % (path, len(a), len(b)))
        for i, (x, y) in enumerate(zip(a, b)):
            diff(x, y, "%s[%d]" % (path, i), out)
    elif a != b:
        out.append("%s: %r != %r" % (path, a, b))
    return out


if __name__ == "__main__":
    with open(sys.argv[1]) as f:
        a = json.load(f)
    with open(sys.argv[2]) as f:
        b = json.load(f)
    for r, name in ((a, sys.argv[1]), (b, sys.argv[2])):
        try:
            report_schema.validate(r, name)
        except AssertionError as e:
            print(e)
            sys.exit(1)
    d = diff(strip(a), strip(b))
    for line in d[:20]:
        print(line)
    if len(d) > 20:
        print("... %d differences" % len(d))
    sys.exit(1 if d else 0)
