#!/usr/bin/env python3
"""One report schema (issue #30, item 4): a report of every command (tests/cli/report_samples.py)
validates against docs/schema/report.schema.json and its command's schema; every subcommand of
`interfere --help` has a schema; the schemas are not vacuous (a report without `seconds`, or with
a string `seconds`, fails); docs/report.md documents every key of the common schema and names
every schema file, and each command schema's keys are documented where it says
(x-documented-in); `interfere check` prints the report it writes.

Usage: test_report_schema.py PATH_TO_INTERFERE WORK_DIR   (ctest cli_report_schema). Exits 77
(skipped) without python3-jsonschema.
"""
import copy
import json
import os
import re
import subprocess
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_common  # noqa: E402
import report_samples  # noqa: E402
import report_schema  # noqa: E402

SOURCE = report_samples.SOURCE
REPORTS = {}


def doc(path):
    with open(os.path.join(SOURCE, path)) as f:
        return f.read()


class ReportSchema(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        if not REPORTS:
            REPORTS.update(report_samples.make_reports(cli_common.EXE, cli_common.WORK))

    def test_every_report_validates(self):
        self.assertGreaterEqual(len(REPORTS), 12, sorted(REPORTS))
        for name, path in sorted(REPORTS.items()):
            with self.subTest(report=name):
                with open(path) as f:
                    r = json.load(f)
                self.assertEqual(report_schema.errors(r), [])
                for key in ("schema_version", "command", "version", "inputs", "options", "result", "warnings",
                            "seconds"):
                    self.assertIn(key, r)

    def test_every_command_has_a_schema(self):
        p = subprocess.run([cli_common.EXE, "--help"], capture_output=True, text=True, check=True)
        commands = re.findall(r"^  ([a-z][a-z-]+) {2,}", p.stdout.split("Subcommands:", 1)[1], re.M)
        self.assertIn("clash", commands)
        for c in commands:
            if c == "completion":  # (writes a shell script, no report)
                continue
            self.assertTrue(os.path.exists(os.path.join(report_schema.SCHEMA_DIR, c + ".schema.json")),
                            "`interfere %s` has no docs/schema/%s.schema.json: a command's report needs one (and "
                            "report_envelope.h's report_text, and its keys in the enum of report.schema.json)" % (c, c))
        self.assertEqual(sorted(set(report_schema.load_schema("report")["properties"]["command"]["enum"])),
                         sorted(report_schema.schema_names()))
        made = set()
        for path in REPORTS.values():
            with open(path) as f:
                made.add(json.load(f)["command"])
        cad = {"features", "assembly-clash"}
        self.assertEqual(made | cad, set(report_schema.schema_names()) | cad)

    def test_schemas_reject_what_they_should(self):
        with open(REPORTS["distance"]) as f:
            r = json.load(f)
        bad = copy.deepcopy(r)
        del bad["seconds"]
        self.assertTrue(any("seconds" in e for e in report_schema.errors(bad)))
        bad = copy.deepcopy(r)
        bad["seconds"] = "1 s"
        self.assertTrue(report_schema.errors(bad))
        bad = copy.deepcopy(r)
        bad["exit_status"] = 2  # (an input error writes no report)
        self.assertTrue(report_schema.errors(bad))
        bad = copy.deepcopy(r)
        bad["command"] = "unknown"
        self.assertTrue(report_schema.errors(bad))
        with self.assertRaises(AssertionError):
            report_schema.validate(bad)

    def test_docs_cover_the_schemas(self):
        report_md = doc("docs/report.md")
        for key in report_schema.load_schema("report")["properties"]:
            self.assertTrue("| `%s` |" % key in report_md, "docs/report.md has no row for " + key)
        for name in ["report"] + report_schema.schema_names():
            self.assertIn("%s.schema.json" % name, report_md, "docs/report.md does not name the schema " + name)
            schema = report_schema.load_schema(name)
            text = "".join(doc(d) for d in schema["x-documented-in"])
            common = report_schema.load_schema("report")["properties"] if name != "report" else {}
            missing = [key for key in schema.get("properties", {})  # (as `key`, `key[]` or `key.sub`)
                       if key not in common and not re.search(r"`%s(`|\[\]|\.)" % re.escape(key), text)]
            self.assertEqual(missing, [], "%s: keys not documented in %s" % (name, schema["x-documented-in"]))

    def test_check_prints_the_report_it_writes(self):
        out = cli_common.path("check2.json")
        p = subprocess.run([cli_common.EXE, "--quiet", "check", os.path.join(report_samples.EX, "plate.stl"), "--json",
                            out], capture_output=True, text=True, check=True)
        with open(out) as f:
            self.assertEqual(json.loads(p.stdout), json.load(f))


if __name__ == "__main__":
    if not report_schema.AVAILABLE:
        print("skipped: python3-jsonschema (with Draft 2020-12) not found")
        sys.exit(77)
    cli_common.main()
