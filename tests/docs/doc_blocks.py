"""What the documentation tests share (tests/docs/test_readme.py, test_docs.py, test_bench_commands.py):
the fenced blocks of a Markdown file, the commands of a shell block, the project's ctest names, and a
C++ snippet compiled against the installed package (issue #30, item 6)."""
import os
import re
import subprocess


def blocks(text, name="README.md"):
    """[(line of the opening fence, info string, body)] of the fenced code blocks of `text`."""
    out, cur, info, line_no = [], None, None, 0
    for i, line in enumerate(text.split("\n"), 1):
        m = re.match(r"^```(.*)$", line)
        if m and cur is None:
            cur, info, line_no = [], m.group(1).strip(), i
        elif line.startswith("```") and cur is not None:
            out.append((line_no, info, "\n".join(cur)))
            cur = None
        elif cur is not None:
            cur.append(line)
    if cur is not None:
        raise SystemExit("%s:%d: unclosed code block" % (name, line_no))
    return out


def commands(body):
    """Commands of a shell block: continuation lines joined, comment lines skipped, a here-document
    kept with its command."""
    out, cur, heredoc = [], "", None
    for line in body.split("\n"):
        if heredoc is not None:
            cur += "\n" + line
            if line.strip() == heredoc:
                out.append(cur)
                cur, heredoc = "", None
            continue
        if not cur and (not line.strip() or line.lstrip().startswith("#")):
            continue
        if line.endswith("\\"):
            cur += line[:-1] + " "
            continue
        m = re.search(r"<<-?\s*'?\"?([A-Za-z_]+)'?\"?", line)
        if m and "#" not in line[:m.start()]:
            cur += line
            heredoc = m.group(1)
            continue
        out.append(cur + line)
        cur = ""
    if heredoc is not None:
        raise ValueError("unclosed here-document (%s)" % heredoc)
    return out


def ctest_names(source):
    """The add_test(NAME ...) names of every CMakeLists.txt of the source tree (build trees skipped)."""
    names = set()
    for root, dirs, files in os.walk(source):
        dirs[:] = [d for d in dirs if not d.startswith(("build", ".")) and d not in ("node_modules", "shared")]
        if "CMakeLists.txt" in files:
            with open(os.path.join(root, "CMakeLists.txt")) as f:
                names.update(re.findall(r"add_test\s*\(\s*NAME\s+([A-Za-z0-9_.-]+)", f.read()))
    return names


def build_cpp_snippet(proj, body, stage):
    """Compiles `body` as main.cpp in the new directory `proj` against the interfere package installed
    under `stage` (find_package(interfere), interfere::core). Returns (program path, None) or
    (None, what failed)."""
    os.makedirs(proj)
    with open(os.path.join(proj, "main.cpp"), "w") as f:
        f.write(body + "\n")
    with open(os.path.join(proj, "CMakeLists.txt"), "w") as f:
        f.write("cmake_minimum_required(VERSION 3.25)\nproject(doc_snippet CXX)\n"
                "set(CMAKE_CXX_STANDARD 20)\nfind_package(interfere REQUIRED)\n"
                "add_executable(app main.cpp)\ntarget_link_libraries(app PRIVATE interfere::core)\n")
    build = os.path.join(proj, "build")
    for step in (["cmake", "-S", proj, "-B", build, "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_PREFIX_PATH=" + stage],
                 ["cmake", "--build", build, "-j2"]):
        p = subprocess.run(step, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if p.returncode != 0:
            return None, "%s failed\n%s" % (" ".join(step[:2]), p.stdout[-3000:])
    return os.path.join(build, "app"), None
