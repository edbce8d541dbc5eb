#!/usr/bin/env python3
"""The benchmark commands of the docs (issue #30, item 6): the blocks ```sh no-run
covered-by=bench_doc_commands of README.md and docs/*.md (tests/docs/test_docs.py) configure,
build and run benchmarks for minutes to hours, so they are not run as written; this test checks
that each of their commands would work as written:

- `cmake -S . -B build ... -DNAME=VALUE`: every NAME (other than CMAKE_*) is an option or cache
  variable of this project's CMake files;
- `cmake --build build --target T ...`: every T is a target of this project (add_executable /
  add_library), built in BUILD_DIR;
- `[VAR=VALUE] [/usr/bin/time -v] [./]build/bench/BIN ARGS`: BIN is in BUILD_DIR/bench; a Google
  Benchmark binary with --benchmark_filter=F lists at least one benchmark for F
  (--benchmark_list_tests, nothing is run);
- `[python3] bench/SCRIPT.py ARGS`: the script exists and its --help works.

usage: test_bench_commands.py SOURCE_DIR BUILD_DIR
"""
import os
import re
import shlex
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_blocks import blocks, commands  # noqa: E402


def cmake_text(source):
    out = []
    for root, dirs, files in os.walk(source):
        dirs[:] = [d for d in dirs if not d.startswith(("build", ".")) and d not in ("node_modules", "shared")]
        for f in files:
            if f == "CMakeLists.txt" or f.endswith(".cmake"):
                with open(os.path.join(root, f), errors="replace") as fh:
                    out.append(fh.read())
    return "\n".join(out)


def main():
    source, build = sys.argv[1:3]
    cmake = cmake_text(source)
    failures, checked = [], 0
    docs = [os.path.join(source, "README.md")] + [os.path.join(source, "docs", f)
                                                 for f in sorted(os.listdir(os.path.join(source, "docs")))
                                                 if f.endswith(".md")]
    for doc in docs:
        for line_no, info, body in blocks(open(doc).read()):
            if "covered-by=" not in info or "bench_doc_commands" not in info.split("covered-by=", 1)[1]:
                continue
            where = "%s:%d" % (os.path.relpath(doc, source), line_no)
            for cmd in commands(body):
                checked += 1
                words = shlex.split(cmd, comments=True)
                while words and re.match(r"^[A-Z_][A-Z0-9_]*=", words[0]):
                    words.pop(0)  # environment assignments
                if words[:2] == ["/usr/bin/time", "-v"]:
                    words = words[2:]
                if words[:1] == ["cmake"] and "--build" in words:
                    targets = words[words.index("--target") + 1:] if "--target" in words else []
                    for t in targets:
                        if not re.search(r"add_(executable|library)\s*\(\s*%s[\s)]" % re.escape(t), cmake):
                            failures.append("%s: `%s`: no target %s in this project" % (where, cmd, t))
                elif words[:1] == ["cmake"]:
                    for w in words:
                        m = re.match(r"^-D([A-Za-z0-9_]+)=", w)
                        if m and not m.group(1).startswith("CMAKE_") and not re.search(
                                r"(option|set)\s*\(\s*%s\b" % m.group(1), cmake):
                            failures.append("%s: `%s`: %s is no option of this project" % (where, cmd, m.group(1)))
                elif words and re.match(r"^(\./)?build/bench/", words[0]):
                    exe = os.path.join(build, "bench", os.path.basename(words[0]))
                    if not os.access(exe, os.X_OK):
                        failures.append("%s: `%s`: %s is not built" % (where, cmd, exe))
                        continue
                    filters = [w.split("=", 1)[1] for w in words if w.startswith("--benchmark_filter=")]
                    if filters:
                        p = subprocess.run([exe, "--benchmark_filter=" + filters[0], "--benchmark_list_tests=true"],
                                           capture_output=True, text=True, timeout=120)
                        if p.returncode != 0 or not p.stdout.strip():
                            failures.append("%s: `%s`: the filter lists no benchmark (exit status %d)\n%s" %
                                            (where, cmd, p.returncode, p.stderr[-1000:]))
                elif words and (words[0].startswith("bench/") or (words[0].startswith("python") and len(words) > 1
                                                                   and words[1].startswith("bench/"))):
                    script = words[0] if words[0].startswith("bench/") else words[1]
                    path = os.path.join(source, script)
                    if not os.path.isfile(path):
                        failures.append("%s: `%s`: no %s" % (where, cmd, script))
                        continue
                    p = subprocess.run([sys.executable, path, "--help"], capture_output=True, text=True, timeout=60,
                                       cwd=source)
                    if p.returncode != 0:
                        failures.append("%s: `%s --help`: exit status %d\n%s" % (where, script, p.returncode, p.stderr[-1000:]))
                else:
                    failures.append("%s: `%s`: no rule for this command (tests/docs/test_bench_commands.py)" % (where, cmd))
    for f in failures:
        print("FAILED:", f)
    print("benchmark commands of the docs: %d checked, %d failure(s)" % (checked, len(failures)))
    return 1 if failures or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
