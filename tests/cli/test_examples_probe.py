#!/usr/bin/env python3
"""Runs every command of examples/probe/README.md as written (issue #28, deliverable 6), in a copy of
that directory: each line of a ```sh block, `interfere` replaced by the built executable and
`python3` by this interpreter, must end with the exit status its `# exit N` comment states; a
plain ``` block right after a sh block is the stdout its last command prints; cell_report.csv must
equal expected/cell_report.csv; make_cell.py must regenerate the shipped files unchanged.

Usage: test_examples_probe.py PATH_TO_INTERFERE WORK_DIR   (run by ctest)."""
import filecmp
import os
import re
import shlex
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report_schema  # noqa: E402  (the reports the README's commands write, against docs/schema)

EXAMPLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples", "probe")


def blocks(readme):
    """[(language, text)] of the fenced blocks."""
    return [(m.group(1), m.group(2)) for m in re.finditer(r"```(\w*)\n(.*?)```", readme, re.S)]


def main():
    exe, work = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    shutil.rmtree(work, ignore_errors=True)
    shutil.copytree(EXAMPLE, work)
    with open(os.path.join(work, "README.md")) as f:
        bs = blocks(f.read())
    failures, ran = [], 0
    have_numpy = subprocess.run([sys.executable, "-c", "import numpy"], capture_output=True).returncode == 0
    for i, (lang, text) in enumerate(bs):
        if lang != "sh":
            continue
        last_out = None
        for line in text.strip().splitlines():
            cmd, _, comment = line.partition("#")
            m = re.search(r"exit (\d+)", comment)
            if not m:
                failures.append("no '# exit N' on: " + line)
                continue
            argv = shlex.split(cmd)
            if argv[0] == "interfere":
                argv = [exe, *argv[1:]]
            elif argv[0] == "python3":
                if not have_numpy:
                    print("skipped (no numpy):", line)
                    continue
                argv = [sys.executable, *argv[1:]]
            p = subprocess.run(argv, cwd=work, capture_output=True, text=True, timeout=120)
            ran += 1
            try:
                report_schema.validate_outputs(argv, work, p.returncode)
            except AssertionError as e:
                failures.append("%s: %s" % (line, e))
            print("$", line, "->", p.returncode)
            if p.returncode != int(m.group(1)):
                failures.append("%s: exit %d, README says %s\n%s%s" % (line, p.returncode, m.group(1), p.stdout, p.stderr))
            last_out = p.stdout
        if i + 1 < len(bs) and bs[i + 1][0] == "" and last_out is not None and last_out != bs[i + 1][1]:
            failures.append("stdout differs from the README:\n--- README\n%s--- got\n%s" % (bs[i + 1][1], last_out))
    if not filecmp.cmp(os.path.join(work, "cell_report.csv"), os.path.join(work, "expected", "cell_report.csv"), shallow=False):
        failures.append("cell_report.csv differs from expected/cell_report.csv")
    if have_numpy:  # make_cell.py ran in the copy: the shipped inputs are what it writes
        for root, _, files in os.walk(EXAMPLE):
            for name in files:
                rel = os.path.relpath(os.path.join(root, name), EXAMPLE)
                if rel.endswith((".obj", ".urdf", ".csv")) and not rel.startswith("expected"):
                    if not filecmp.cmp(os.path.join(EXAMPLE, rel), os.path.join(work, rel), shallow=False):
                        failures.append("make_cell.py does not regenerate " + rel)
    print("%d commands run" % ran)
    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures or ran == 0 else 0)


if __name__ == "__main__":
    main()
