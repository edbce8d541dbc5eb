"""Shared plumbing of the CLI end-to-end tests (tests/cli/test_*.py, run by ctest as
`test_X.py PATH_TO_INTERFERE WORK_DIR`): the executable and a fresh work directory from the command
line, running the CLI, paths in the work directory, readers and writers. Standard library only."""
import csv
import json
import os
import shutil
import subprocess
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report_schema  # noqa: E402  (issue #30: every report the tests read is validated)

EXE = None   # path of the interfere executable (set by main)
WORK = None  # fresh work directory of the test module (set by main)


def run(*args, command=()):
    """Runs `interfere --quiet [command...] args...`; returns (exit status, stdout, stderr). A report
    it wrote (`--json FILE`, exit status 0, 1 or 3) is validated against docs/schema (issue #30)."""
    p = subprocess.run([EXE, "--quiet", *command, *args], capture_output=True, text=True, timeout=120)
    validate_written_report([*command, *args], p.returncode)
    return p.returncode, p.stdout, p.stderr


def validate_written_report(argv, code):
    """The report named by --json in `argv` against docs/schema, when the run wrote one (the run's
    working directory is this process's)."""
    report_schema.validate_outputs(argv, os.getcwd(), code)


def path(name):
    """`name` inside the work directory (an absolute path is returned as it is)."""
    return os.path.join(WORK, name)


def read_text(name):
    with open(path(name)) as f:
        return f.read()


def load_json(name):
    """The JSON file `name`; a CLI report is validated against docs/schema first (report_schema.py)."""
    with open(path(name)) as f:
        obj = json.load(f)
    report_schema.validate(obj, path(name))
    return obj


def read_csv(name):
    with open(path(name), newline="") as f:
        return list(csv.DictReader(f))


def write_text(name, text):
    with open(path(name), "w") as f:
        f.write(text)
    return path(name)


def write_obj(name, mesh):
    """Writes (vertices, triangles with 0-based indices) as OBJ; returns its path."""
    v, f = mesh
    with open(path(name), "w") as out:
        for p in v:
            out.write("v %r %r %r\n" % tuple(p))
        for t in f:
            out.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))
    return path(name)


def assert_input_error(test, args, needles, outputs=()):
    """Runs `interfere *args` expecting bad input: exit status 2, every needle in stderr, and none of
    `outputs` written (removed first). Returns stderr."""
    for o in outputs:
        if os.path.exists(o):
            os.remove(o)
    rc, out, err = run(*args)
    test.assertEqual(rc, 2, out + err)
    for n in needles:
        test.assertIn(n, err)
    for o in outputs:
        test.assertFalse(os.path.exists(o), o)
    return err


def main():
    """Reads EXE and WORK from the command line, empties WORK, runs the calling module's tests."""
    global EXE, WORK
    EXE, WORK = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    prog = unittest.main(module="__main__", argv=[sys.argv[0], "-v"], exit=False)
    sys.exit(0 if prog.result.wasSuccessful() else 1)
