#!/usr/bin/env python3
"""CLI conventions (issue #30, item 5): exit statuses in every --help; FE-only and STEP-only options
under their own headings; every error, CLI11's parse errors included, prefixed `interfere: error:`
and phrased for the command line (no C++ option names); --version; the generated bash completion
(`interfere completion bash`, the build's interfere.bash) is valid bash and completes commands and
flags; long work shows a progress bar with rate and ETA when stderr is a terminal (a pty here) and
plain lines otherwise.

Usage: test_conventions.py PATH_TO_INTERFERE WORK_DIR   (ctest cli_conventions). Standard library only.
"""
import os
import pty
import re
import shutil
import subprocess
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_common  # noqa: E402
from cli_common import path, run, write_text  # noqa: E402

SOURCE = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
EX = os.path.join(SOURCE, "data", "examples")


def raw(*args):
    p = subprocess.run([cli_common.EXE, *args], capture_output=True, text=True, timeout=120)
    return p.returncode, p.stdout, p.stderr


def subcommands():
    _, out, _ = raw("--help")
    return re.findall(r"^  ([a-z][a-z-]+) {2,}", out.split("Subcommands:", 1)[1], re.M)


def help_sections(text):
    """{heading: [option names]} of a --help text."""
    sections, current = {}, None
    for line in text.splitlines():
        m = re.match(r"^(\S[^:]*):$", line)
        if m:
            current = m.group(1)
            sections[current] = []
        elif current and re.match(r"^  -", line):
            sections[current].append(line.split()[0].split("{")[0])
    return sections


def complete(words):
    """COMPREPLY of the generated completion for the command line `words` (the last one partial)."""
    script = subprocess.run([cli_common.EXE, "completion", "bash"], capture_output=True, text=True, check=True).stdout
    line = " ".join("'%s'" % w for w in words)
    prog = script + "\nCOMP_WORDS=(%s); COMP_CWORD=%d; _interfere; printf '%%s\\n' \"${COMPREPLY[@]}\"\n" % (
        line, len(words) - 1)
    p = subprocess.run(["bash", "-c", prog], capture_output=True, text=True, cwd=cli_common.WORK)
    assert p.returncode == 0, p.stderr
    return p.stdout.split()


class Conventions(unittest.TestCase):
    def test_every_help_states_the_exit_statuses(self):
        code, out, _ = raw("--help")
        self.assertEqual(code, 0)
        self.assertIn("Exit status:", out)
        cmds = subcommands()
        self.assertIn("clash", cmds)
        self.assertIn("completion", cmds)
        for c in cmds:
            code, out, err = raw(c, "--help")
            self.assertEqual(code, 0, err)
            self.assertIn("Exit status: 0", out, c)
            self.assertIn("2 usage or input error", out, c)
        _, out, _ = raw("clash", "--help")
        self.assertIn("3 undecided", out)
        self.assertIn("--fail-on", out.split("Exit status:")[-1])

    def test_fe_and_step_options_have_their_own_headings(self):
        _, out, _ = raw("clash", "--help")
        sec = help_sections(out)
        fe = [k for k in sec if k.startswith("FE models")]
        self.assertEqual(len(fe), 1, list(sec))
        for flag in ("--part", "--part-a", "--disp", "--field", "--scale", "--step", "--split", "--no-reference",
                     "--regions-vtu", "--linear-faces"):
            self.assertIn(flag, sec[fe[0]])
            self.assertNotIn(flag, sec["Options"])
        self.assertIn("--linear-deflection", sec["STEP inputs"])
        self.assertGreaterEqual(len(sec[fe[0]]), 15)
        # none of the general options is described as FE-only
        for line in out.split(fe[0] + ":")[0].splitlines():
            self.assertFalse(re.search(r"^\s+--\S+( [A-Z]+)?\s{2,}(FEM|FE steps): ", line), line)

    def test_parse_errors_have_the_prefix(self):
        for args in (["clash", "--bogus", "a.stl", "b.stl"], [], ["distance", "a.stl", "b.stl", "--threads", "x"],
                     ["nosuchcommand"], ["completion"], ["completion", "fish"], ["bearing", "--frames"]):
            code, out, err = raw(*args)
            self.assertEqual(code, 2, (args, out, err))
            self.assertTrue(err.startswith("interfere: error: "), (args, err))
            self.assertIn("--help", err)

    def test_errors_speak_of_the_command_line(self):
        xyz = write_text("part.xyz", "not a mesh\n")
        stl = os.path.join(EX, "plate.stl")
        for args in (["clash", xyz, stl], ["check", xyz], ["simplify", stl, path("out.xyz"), "--ratio", "0.5"]):
            code, out, err = run(*args)
            self.assertEqual(code, 2, (args, out, err))
            self.assertTrue(err.startswith("interfere: error: "), err)
            self.assertNotRegex(err, r"[A-Z][A-Za-z]*(Options|Request)::", args)

    def test_version(self):
        code, out, _ = raw("--version")
        self.assertEqual(code, 0)
        with open(os.path.join(SOURCE, "CMakeLists.txt")) as f:
            version = f.read().split("project(interfere VERSION ", 1)[1].split()[0]
        self.assertEqual(out.strip(), version)

    def test_bash_completion(self):
        if not shutil.which("bash"):
            self.skipTest("no bash")
        code, script, err = raw("completion", "bash")
        self.assertEqual(code, 0, err)
        self.assertEqual(subprocess.run(["bash", "-n"], input=script, text=True).returncode, 0)
        built = os.path.join(os.path.dirname(cli_common.EXE), "interfere.bash")
        if os.path.exists(built):  # (written by the build next to the executable; installed)
            with open(built) as f:
                self.assertEqual(f.read(), script)
        self.assertEqual(complete(["interfere", "cl"]), ["clash"])
        self.assertEqual(complete(["interfere", "-q", "as"]), ["assembly-clash"])
        self.assertIn("--json", complete(["interfere", "clash", "--js"]))
        self.assertIn("--part-a", complete(["interfere", "clash", "plate.stl", "--part"]))
        self.assertEqual(complete(["interfere", "sweep", "--probe-r"]), ["--probe-radius"])
        write_text("model_x.stl", "")
        self.assertEqual(complete(["interfere", "check", "model_"]), ["model_x.stl"])
        self.assertIn("--version", complete(["interfere", "--ver"]))

    def simplify_args(self):
        return ["simplify", os.path.join(EX, "plate.stl"), path("p.ply"), "--ratio", "0.3"]

    def test_progress_plain_lines_when_not_a_terminal(self):
        code, _, err = raw(*self.simplify_args())
        self.assertEqual(code, 0, err)
        bars = [l for l in err.splitlines() if l.startswith("[interfere] simplifying [")]
        self.assertGreaterEqual(len(bars), 2, err)
        self.assertNotIn("\r", err)
        self.assertNotIn("\x1b", err)
        self.assertIn("100 %", bars[-1])
        code, _, err = raw("--quiet", *self.simplify_args())
        self.assertEqual(code, 0, err)
        self.assertNotIn("simplifying [", err)

    def test_progress_bar_on_a_terminal(self):
        # stderr a pty (stdout a pipe): the bar is rewritten in place, with the share done and an ETA.
        master, slave = pty.openpty()
        p = subprocess.Popen([cli_common.EXE, *self.simplify_args()], stdout=subprocess.DEVNULL, stderr=slave)
        os.close(slave)
        chunks = []
        while True:
            try:
                data = os.read(master, 4096)
            except OSError:
                break
            if not data:
                break
            chunks.append(data)
        p.wait(timeout=120)
        os.close(master)
        self.assertEqual(p.returncode, 0)
        text = b"".join(chunks).decode(errors="replace")
        self.assertRegex(text, r"\r\[interfere\] simplifying \[[#.]{24}\] +\d+ %")
        self.assertIn("ETA ", text)

    def test_frames_progress_has_rate_and_eta(self):
        scene = write_text("moving.json", """{"bodies": [
          {"id": "plate", "file": "%s"},
          {"id": "pin", "file": "%s", "transform": [1,0,0,30, 0,1,0,30, 0,0,1,5]}]}""" % (
            os.path.join(EX, "plate.stl"), os.path.join(EX, "pin.obj")))
        rows = ["frame,body,r00,r01,r02,tx,r10,r11,r12,ty,r20,r21,r22,tz"]
        rows += ["%d,pin,1,0,0,%d,0,1,0,30,0,0,1,5" % (i, 30 + i) for i in range(12)]
        motion = write_text("motion.csv", "\n".join(rows) + "\n")
        code, _, err = raw("clash", "--scene", scene, "--motion", motion)
        self.assertIn(code, (0, 1), err)
        bars = [l for l in err.splitlines() if l.startswith("[interfere] frames [")]
        self.assertGreaterEqual(len(bars), 2, err)
        self.assertIn("12/12", bars[-1])
        self.assertRegex(bars[-1], r"frames/s +ETA \d+:\d\d")

    def test_long_commands_show_progress(self):
        # bearing (assembly frames and pair frames), sweep, cell, assembly-clash and a static scene:
        # plain lines on a pipe, the last at the whole count with a rate; none with --quiet.
        probe = os.path.join(SOURCE, "examples", "probe")
        scene = write_text("static.json", """{"bodies": [
          {"id": "plate", "file": "%s"},
          {"id": "pin-1", "file": "%s", "transform": [1,0,0,30, 0,1,0,30, 0,0,1,5]},
          {"id": "pin-2", "file": "%s", "transform": [1,0,0,60, 0,1,0,30, 0,0,1,5]}]}""" % (
            os.path.join(EX, "plate.stl"), os.path.join(EX, "pin.obj"), os.path.join(EX, "pin.obj")))
        cases = [
            (["bearing", "--assembly", os.path.join(EX, "bearing_axle.json"), "--frames", "12"], "frames", r"12/12 +[\d.]+ frames/s"),
            (["bearing", "--params", os.path.join(EX, "bearing.parameters")], "frames", r"(\d+)/\1 +[\d.]+ frames/s"),
            (["sweep", "--workpiece", os.path.join(EX, "plate.stl"), "--robot", os.path.join(EX, "probe_paper_machine.json"),
              "--path", os.path.join(EX, "probe_path.csv"), "--probe-radius", "5", "--probe-length", "40"],
             "sweep", r"(\d+)/\1 +[\d.]+ checks/s"),
            (["cell", os.path.join(probe, "cell.json")], "frames", r"(\d+)/\1 +[\d.]+ frames/s"),
            (["clash", "--scene", scene], "pairs", r"(\d+)/\1 +[\d.]+ pairs/s"),
        ]
        for args, what, last in cases:
            with self.subTest(command=args[0], what=what):
                code, _, err = raw(*args)
                self.assertIn(code, (0, 1), err)
                bars = [l for l in err.splitlines() if l.startswith("[interfere] %s [" % what)]
                self.assertTrue(bars, err)
                self.assertRegex(bars[-1], last)
                self.assertRegex(bars[-1], r"ETA \d+:\d\d$")
                self.assertNotIn("\r", err)
                code, _, err = raw("--quiet", *args)
                self.assertNotIn("[interfere] %s [" % what, err)

    def test_assembly_clash_progress(self):
        # the instance pairs of the test assembly (tests/cli/data/assembly.step, three plates; a 15 mm
        # clearance makes a candidate pair); skipped where this build has no STEP reader (exit 2).
        asm = os.path.join(SOURCE, "tests", "cli", "data", "assembly.step")
        code, out, err = raw("assembly-clash", asm, "--clearance", "15")
        if code == 2 and "OpenCASCADE" in err:
            self.skipTest("no STEP reader in this build")
        self.assertIn(code, (0, 1), err)
        bars = [l for l in err.splitlines() if l.startswith("[interfere] pairs [")]
        self.assertTrue(bars, err)
        self.assertRegex(bars[-1], r"(\d+)/\1 +[\d.]+ pairs/s +ETA \d+:\d\d$")

    def test_fe_steps_progress(self):
        fem = os.path.join(SOURCE, "tests", "data", "fem")
        code, _, err = raw("clash", os.path.join(fem, "tets_ascii.vtu"), os.path.join(fem, "tets_ascii.vtu"),
                           "--part-a", "MaterialIds -2", "--part-b", "MaterialIds 3", "--disp-a",
                           os.path.join(fem, "tets_disp.csv"))
        self.assertIn(code, (0, 1), err)
        bars = [l for l in err.splitlines() if l.startswith("[interfere] steps [")]
        self.assertTrue(bars, err)
        self.assertRegex(bars[-1], r"\] 2/2 +\d+(\.\d+)? steps/s +ETA 0:00$")

if __name__ == "__main__":
    cli_common.main()
