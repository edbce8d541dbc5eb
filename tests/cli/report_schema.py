"""Validation of the CLI's JSON reports against docs/schema/ (issue #30, item 4): every report
against report.schema.json (the eight keys every command shares) and against its command's
<command>.schema.json. Used by test_report_schema.py and by cli_common.load_json, so that every
report the CLI tests read is validated. Needs python3-jsonschema (tools/deps.sh); without it
AVAILABLE is False and validate() does nothing."""
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))
SCHEMA_DIR = os.path.abspath(os.path.join(HERE, "..", "..", "docs", "schema"))

try:
    import jsonschema
    AVAILABLE = hasattr(jsonschema, "Draft202012Validator")
except ImportError:  # pragma: no cover
    AVAILABLE = False

_validators = {}


def load_schema(name):
    with open(os.path.join(SCHEMA_DIR, name + ".schema.json")) as f:
        return json.load(f)


def schema_names():
    """The per-command schemas' names (file stems), without `report`."""
    return sorted(f[:-len(".schema.json")] for f in os.listdir(SCHEMA_DIR)
                  if f.endswith(".schema.json") and f != "report.schema.json")


def _validator(name):
    if name not in _validators:
        schema = load_schema(name)
        jsonschema.Draft202012Validator.check_schema(schema)
        _validators[name] = jsonschema.Draft202012Validator(schema)
    return _validators[name]


def errors(report):
    """The validation errors of `report` (strings; empty when valid)."""
    out = []
    for name in ("report", report.get("command") if isinstance(report, dict) else None):
        if name is None or not os.path.exists(os.path.join(SCHEMA_DIR, "%s.schema.json" % name)):
            out.append("no schema docs/schema/%s.schema.json" % name)
            continue
        for e in _validator(name).iter_errors(report):
            out.append("%s.schema.json: $%s: %s" % (name, "".join("[%r]" % p for p in e.absolute_path), e.message))
    return out


def is_report(obj):
    """A CLI report (not a scene file, a glTF document, a motion file, ...)."""
    return isinstance(obj, dict) and isinstance(obj.get("command"), str) and "version" in obj and (
        "exit_status" in obj or "seconds" in obj or "interfere_version" in obj)


def validate_outputs(argv, cwd=".", code=0):
    """The report a CLI run wrote, validated (raises AssertionError): `argv` its arguments, where
    `--json FILE` (relative to `cwd`, the run's working directory) names it; nothing when the run
    could not have written one (exit status other than 0, 1 or 3, `--json -`, no such file) or
    without python3-jsonschema. Returns the number of reports validated (0 or 1)."""
    if code not in (0, 1, 3) or not AVAILABLE:
        return 0
    for i, a in enumerate(argv[:-1]):
        if a == "--json" and argv[i + 1] != "-":
            target = os.path.join(cwd, argv[i + 1])
            if os.path.isfile(target):
                with open(target) as f:
                    try:
                        obj = json.load(f)
                    except ValueError:
                        return 0  # (not a report: --json of a run that wrote none, an old file)
                validate(obj, target)
                return 1
    return 0


def validate(obj, where=""):
    """Raises AssertionError listing the errors when `obj` is a CLI report that does not validate."""
    if not AVAILABLE or not is_report(obj):
        return
    errs = errors(obj)
    if errs:
        raise AssertionError("%s: the report does not match docs/schema:\n  %s" % (where or "report", "\n  ".join(errs[:20])))
