#!/usr/bin/env python3
"""Runs every code block of docs/*.md as written (issue #30, item 6), so that none can rot: the
rules of README.md's test (test_readme.py), plus the kinds of block the topic docs have.

usage: test_docs.py SOURCE_DIR CLI_DIR PYTHON_MODULE_DIR STAGE_PREFIX WORK_DIR [DOC.md ...]

Each doc runs in its own directory WORK_DIR/<doc>, where data/, examples/ and tests/ link into the
source tree (as in a checkout), `interfere` is the built CLI (CLI_DIR first on PATH) and the Python
module is the built one (PYTHON_MODULE_DIR on PYTHONPATH). Blocks run in the order of the doc, so a
block may use the files an earlier block of the same doc wrote. The fence's info string says what
a block is:

- ```sh: every command (continuation lines joined; a here-document `<<'EOF'` ... `EOF` is part of
  its command) runs with bash; its exit status must be 0, or N where its comment says
  "exit status N"; the report it writes (`--json FILE`) must validate against docs/schema.
- ```sh no-run covered-by=TEST: not run here (a cluster, an install as root, a rebuild); TEST must
  be a ctest of this project (add_test(NAME TEST) in a tests/ CMakeLists.txt) that runs it.
- ```python: run with the module; ```cpp: compiled against the installed package
  (find_package(interfere) from STAGE_PREFIX) and run: exit status 0, or N with `exit=N`.
- ```json: parsed; a CLI report (report_schema.is_report) is validated against docs/schema;
  `file=NAME` writes the block to NAME for the blocks after it.
- ```csv: every row has the header's number of fields; `file=NAME` as for json.
- ```text output: sample console output, not run; a line `$ interfere ...` in it is a command
  whose subcommand and every --flag must be in that subcommand's --help.
- ```text synopsis: a usage line (`interfere CMD ... [--flag ...]`, also after `mpirun -n K`):
  every --flag must be in `interfere CMD --help` (interfere-mpi: skipped when not built).
- ```text diagram, ```text format: a picture or a file format's outline (placeholders such as
  `[12 numbers]`): not code, nothing to run.
Any other info string (a bare ``` too) is an error: a new kind of block needs a rule here.

Blocks that need what this build or machine lacks are skipped, not failed: a command stopping
with "interfere built with OpenCASCADE" (no STEP reader), a Python block failing on a missing
attribute of a module built without it (interfere.HAVE_CAD false), a block naming ../shared/data
when that directory is absent.
"""
import csv
import io
import json
import os
import re
import shlex
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "cli"))
from doc_blocks import blocks, build_cpp_snippet, commands, ctest_names  # noqa: E402
import report_schema  # noqa: E402

NO_CAD = "interfere built with OpenCASCADE"


class Doc:
    def __init__(self, args, name):
        self.source, self.cli_dir, self.pymod, self.stage, work = args
        self.name = name
        self.work = os.path.join(work, os.path.splitext(name)[0])
        shutil.rmtree(self.work, ignore_errors=True)
        os.makedirs(self.work)
        for d in ("data", "examples", "tests"):
            os.symlink(os.path.join(self.source, d), os.path.join(self.work, d))
        shared = os.path.join(self.source, "..", "shared")
        if os.path.isdir(shared):
            os.symlink(os.path.abspath(shared), os.path.join(work, "shared")) if not os.path.exists(
                os.path.join(work, "shared")) else None
        self.env = dict(os.environ)
        mpi_dir = os.path.join(os.path.dirname(self.cli_dir), "mpi")  # (interfere-mpi, when built)
        self.env["PATH"] = os.pathsep.join([self.cli_dir, mpi_dir, self.env.get("PATH", "")])
        self.env["PYTHONPATH"] = self.pymod + os.pathsep + self.env.get("PYTHONPATH", "")
        self.failures, self.skipped, self.ran, self.not_run, self.reports = [], [], 0, 0, 0
        self.help_cache = {}

    def fail(self, where, text):
        self.failures.append("%s: %s" % (where, text))

    def run(self, argv_or_cmd, timeout=600, shell=False):
        if shell:
            argv_or_cmd = ["bash", "-c", argv_or_cmd]
        return subprocess.run(argv_or_cmd, cwd=self.work, env=self.env, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True, timeout=timeout)

    def help_text(self, exe, sub):
        key = (exe, sub)
        if key not in self.help_cache:
            path = shutil.which(exe, path=self.env["PATH"])
            if path is None:
                self.help_cache[key] = None
            else:
                p = self.run([path] + ([sub] if sub else []) + ["--help"])
                text = p.stdout + p.stderr  # (interfere-mpi prints its usage, exit status 2)
                self.help_cache[key] = text if p.returncode == 0 or "usage:" in text.lower() else ""
        return self.help_cache[key]

    def check_flags(self, where, line):
        """`interfere CMD ... --flags` (or interfere-mpi): the subcommand and its flags exist."""
        m = re.search(r"\b(interfere(?:-mpi)?)\s+(?:-q\s+|--quiet\s+)?([a-z][a-z-]*)", line)
        if not m:
            return self.fail(where, "no `interfere CMD` in %r" % line)
        exe, sub = m.group(1), m.group(2)
        text = self.help_text(exe, sub)
        if text is None:
            self.skipped.append("%s: %s is not built" % (where, exe))
            return
        if not text:
            return self.fail(where, "`%s %s --help` fails: no such subcommand?" % (exe, sub))
        for flag in re.findall(r"(?<![\w-])(--[a-z][a-z0-9-]*)", line[m.end():]):
            if not re.search(r"(?<![\w-])%s(?![\w-])" % re.escape(flag), text):
                self.fail(where, "`%s %s --help` has no %s" % (exe, sub, flag))

    def shell(self, where, body):
        for cmd in commands(body):
            if "../shared/data" in cmd and not os.path.isdir(os.path.join(self.work, "..", "shared", "data")):
                self.skipped.append("%s: `%s` (no ../shared/data)" % (where, cmd))
                continue
            m = re.search(r"#.*exit status (\d+)", cmd.split("\n")[0])
            want = int(m.group(1)) if m else 0
            p = self.run(cmd, shell=True)
            if p.returncode != want and NO_CAD in p.stderr:
                self.skipped.append("%s: `%s` (no OpenCASCADE in this build)" % (where, cmd))
            elif p.returncode != want:
                self.fail(where, "`%s`: exit status %d, the doc says %d\n%s%s" %
                          (cmd, p.returncode, want, p.stdout[-2000:], p.stderr[-2000:]))
            else:  # the report it wrote (--json FILE) against docs/schema (issue #30, item 4)
                try:
                    argv = shlex.split(cmd.split("\n")[0], comments=True)
                except ValueError:
                    argv = []
                try:
                    self.reports += report_schema.validate_outputs(argv, self.work, p.returncode)
                except AssertionError as e:
                    self.fail(where, "`%s`: %s" % (cmd, e))

    def have_cad(self):
        """Whether the module was built with OpenCASCADE (interfere.HAVE_CAD)."""
        if not hasattr(self, "_have_cad"):
            p = self.run([sys.executable, "-c", "import interfere; print(interfere.HAVE_CAD)"])
            self._have_cad = p.stdout.strip() == "True"
        return self._have_cad

    def python(self, where, body):
        p = self.run([sys.executable, "-c", body])
        if p.returncode != 0 and (NO_CAD in p.stderr or ("AttributeError" in p.stderr and not self.have_cad())):
            self.skipped.append("%s (no OpenCASCADE in this build)" % where)
        elif p.returncode != 0:
            self.fail(where, "exit status %d\n%s%s" % (p.returncode, p.stdout[-2000:], p.stderr[-3000:]))

    def cpp(self, where, line_no, body, attrs):
        app, error = build_cpp_snippet(os.path.join(self.work, "cpp_%d" % line_no), body, self.stage)
        if error:
            return self.fail(where, error)
        p = self.run([app], timeout=300)
        want = int(attrs.get("exit", "0"))
        if p.returncode != want:
            self.fail(where, "the program exited %d (the doc says %d): %r %r" % (p.returncode, want, p.stdout, p.stderr))

    def write_file(self, attrs, body):
        if "file" in attrs:
            with open(os.path.join(self.work, attrs["file"]), "w") as f:
                f.write(body + "\n")

    def block(self, line_no, info, body, names):
        words = info.split()
        lang = words[0] if words else ""
        attrs = dict(w.split("=", 1) for w in words[1:] if "=" in w)
        flags = [w for w in words[1:] if "=" not in w]
        where = "docs/%s:%d (```%s)" % (self.name, line_no, info)
        if "no-run" in flags:
            covered = attrs.get("covered-by", "").split(",") if attrs.get("covered-by") else []
            if not covered or any(c not in names for c in covered):
                self.fail(where, "no-run needs covered-by=TEST naming a ctest of this project (have: %s)" % covered)
            self.not_run += 1
            return
        if lang == "text":
            kind = flags[0] if flags else ""
            if kind not in ("output", "synopsis", "diagram", "format"):
                return self.fail(where, "a text block says what it is: output, synopsis, diagram or format")
            self.not_run += 1
            if kind == "output":
                for line in body.split("\n"):
                    if line.startswith("$ "):
                        self.check_flags(where, line[2:])
            elif kind == "synopsis":
                joined = re.sub(r"\\\n", " ", body)
                cur = None
                for line in joined.split("\n"):
                    if re.match(r"^\s*(mpirun\b.*?)?interfere(-mpi)?\s", line) and not line.startswith(" "):
                        if cur:
                            self.check_flags(where, cur)
                        cur = line
                    elif cur is not None:
                        cur += " " + line
                if cur:
                    self.check_flags(where, cur)
                else:
                    self.fail(where, "a synopsis without an `interfere CMD` line")
            return
        self.ran += 1
        try:
            if lang in ("sh", "bash"):
                self.shell(where, body)
            elif lang == "python":
                self.python(where, body)
            elif lang == "cpp":
                self.cpp(where, line_no, body, attrs)
            elif lang == "json":
                obj = json.loads(body)
                if report_schema.is_report(obj):
                    if report_schema.AVAILABLE:
                        report_schema.validate(obj, where)
                    else:
                        self.skipped.append("%s: schema validation (no python3-jsonschema)" % where)
                self.write_file(attrs, body)
            elif lang == "csv":
                rows = list(csv.reader(io.StringIO(body)))
                bad = [i + 1 for i, r in enumerate(rows) if len(r) != len(rows[0])]
                if not rows or bad:
                    self.fail(where, "rows %s do not have the header's %d fields" % (bad, len(rows[0]) if rows else 0))
                self.write_file(attrs, body)
            else:
                self.ran -= 1
                self.fail(where, "no rule for this kind of block (tests/docs/test_docs.py)")
        except (ValueError, AssertionError, subprocess.TimeoutExpired) as e:
            self.fail(where, str(e))


def main():
    args = sys.argv[1:6]
    source = args[0]
    docs_dir = os.path.join(source, "docs")
    names = sys.argv[6:] or sorted(f for f in os.listdir(docs_dir) if f.endswith(".md"))
    os.makedirs(args[4], exist_ok=True)
    ctests = ctest_names(source)
    total_fail, total, reports = 0, [0, 0, 0, 0], 0
    for name in names:
        d = Doc(args, name)
        found = blocks(open(os.path.join(docs_dir, name)).read())
        for line_no, info, body in found:
            d.block(line_no, info, body, ctests)
        for s in d.skipped:
            print("skipped:", s)
        for f in d.failures:
            print("FAILED:", f)
        print("docs/%s: %d blocks, %d run (%d reports validated), %d not run (not code, or covered elsewhere), "
              "%d skipped, %d failure(s)" % (name, len(found), d.ran, d.reports, d.not_run, len(d.skipped), len(d.failures)))
        reports += d.reports
        total_fail += len(d.failures)
        total = [total[0] + len(found), total[1] + d.ran, total[2] + d.not_run, total[3] + len(d.skipped)]
    print("docs: %d blocks, %d run, %d not run (not code, or covered elsewhere), %d skipped, %d failure(s); "
          "%d reports validated against docs/schema" % (*total, total_fail, reports))
    return 1 if total_fail else 0


if __name__ == "__main__":
    sys.exit(main())
