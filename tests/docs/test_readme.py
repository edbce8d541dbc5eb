#!/usr/bin/env python3
"""Runs every code block of README.md as written (issue #30, item 6), so that none can rot.

usage: test_readme.py SOURCE_DIR CLI_DIR PYTHON_MODULE_DIR STAGE_PREFIX WORK_DIR

- The first block (the project's two commands: install, build and demo / every test) is what CI runs
  (.ci/run calls tools/test.sh): checked to be exactly those two commands, not run here.
- ```sh blocks: each command (continuation lines joined) runs with bash in WORK_DIR, where data/ and
  examples/ link into the source tree and `interfere` is the built CLI (CLI_DIR first on PATH). Its
  exit status must be 0, or N where its comment says "exit status N"; a report it writes (--json)
  must validate against docs/schema.
- ```sh no-run covered-by=TEST blocks: TEST must be a ctest of this project (add_test(NAME TEST) in a
  tests/ CMakeLists.txt), which runs those commands.
- ```cpp: compiled against the installed package (find_package(interfere) from STAGE_PREFIX, the
  ctest package_install's), linked with interfere::core, run in WORK_DIR: exit status 1 (the
  README's pin goes through the plate) and a line starting "clash:".
- ```python: run with the built module (PYTHON_MODULE_DIR on PYTHONPATH) in WORK_DIR.
- ```json: parsed.
Any other language is an error (a new kind of block needs a rule here).
"""
import json
import os
import re
import shlex
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli"))
import report_schema  # noqa: E402  (reports the commands write, against docs/schema)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_blocks import blocks, build_cpp_snippet, commands, ctest_names  # noqa: E402


def main():
    source, cli_dir, pymod, stage, work = sys.argv[1:6]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    for d in ("data", "examples"):
        os.symlink(os.path.join(source, d), os.path.join(work, d))
    env = dict(os.environ)
    env["PATH"] = cli_dir + os.pathsep + env.get("PATH", "")
    env["PYTHONPATH"] = pymod + os.pathsep + env.get("PYTHONPATH", "")
    text = open(os.path.join(source, "README.md")).read()
    found = blocks(text)
    failures, ran = [], 0
    names = ctest_names(source)
    first = found[0]
    if commands(first[2]) != ["bash tools/demo.sh   # installs dependencies, builds, clashes the bundled example, writes out/report.json",
                              "bash tools/test.sh   # installs dependencies, builds everything and runs every test (ctest)"]:
        failures.append("README.md:%d: the first block must be the two commands (demo, tests)" % first[0])
    if "tools/test.sh" not in open(os.path.join(source, ".ci", "run")).read():
        failures.append(".ci/run does not run tools/test.sh (the first block's second command)")
    for line_no, info, body in found[1:]:
        words = info.split()
        lang = words[0] if words else ""
        where = "README.md:%d (```%s)" % (line_no, info)
        if "no-run" in words:
            covered = [w.split("=", 1)[1] for w in words if w.startswith("covered-by=")]
            if not covered or any(c not in names for c in covered):
                failures.append("%s: no-run needs covered-by=TEST naming a ctest of this project (have: %s)" % (where, covered))
            continue
        ran += 1
        if lang in ("sh", "bash"):
            for cmd in commands(body):
                m = re.search(r"#.*exit status (\d+)", cmd)
                want = int(m.group(1)) if m else 0
                p = subprocess.run(["bash", "-c", cmd], cwd=work, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                   text=True, timeout=600)
                if p.returncode != want:
                    failures.append("%s: `%s`: exit status %d, the README says %d\n%s%s" %
                                    (where, cmd, p.returncode, want, p.stdout[-2000:], p.stderr[-2000:]))
                try:
                    report_schema.validate_outputs(shlex.split(cmd, comments=True), work, p.returncode)
                except (AssertionError, ValueError) as e:
                    failures.append("%s: `%s`: %s" % (where, cmd, e))
        elif lang == "cpp":
            app, error = build_cpp_snippet(os.path.join(work, "cpp_%d" % line_no), body, stage)
            if error:
                failures.append("%s: %s" % (where, error))
            else:
                p = subprocess.run([app], cwd=work, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                   text=True, timeout=300)
                if p.returncode != 1 or not p.stdout.startswith("clash:"):
                    failures.append("%s: the program exited %d (want 1, a clash) and printed %r %r" %
                                    (where, p.returncode, p.stdout, p.stderr))
        elif lang == "python":
            p = subprocess.run([sys.executable, "-c", body], cwd=work, env=env, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, timeout=600)
            if p.returncode != 0:
                failures.append("%s: exit status %d\n%s%s" % (where, p.returncode, p.stdout[-2000:], p.stderr[-3000:]))
        elif lang == "json":
            try:
                json.loads(body)
            except ValueError as e:
                failures.append("%s: %s" % (where, e))
        else:
            failures.append("%s: no rule for this kind of block (tests/docs/test_readme.py)" % where)
    for f in failures:
        print(f)
    print("README.md: %d blocks, %d run, %d failure(s)" % (len(found), ran, len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
