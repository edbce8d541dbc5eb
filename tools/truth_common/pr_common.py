"""What the truth sets' table writers share (tools/hole_truth/pr_table.py, tools/floor_truth/pr_table.py;
issue #29, item 2): the test run that writes the precision/recall JSON, the totals' ratios, the per-type
table and the replacement of a marked section of docs/simplify.md."""
import json, os, subprocess, tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def run_truth_test(build, env_var, gtest_filter):
    """Runs interfere_cad_tests --gtest_filter=gtest_filter in build/tests with env_var naming a temporary
    file, and returns the JSON table it writes (the file removed)."""
    out = tempfile.mktemp(suffix=".json")
    env = dict(os.environ, **{env_var: out})
    subprocess.run([os.path.join(build, "tests", "interfere_cad_tests"), "--gtest_filter=" + gtest_filter], env=env,
                   check=True, stdout=subprocess.DEVNULL)
    table = json.load(open(out))
    os.unlink(out)
    return table


def total_ratios(t):
    """Precision, recall, typed precision, typed recall of the counts t (1 when nothing to count)."""
    return (t["found"] / t["reported"] if t["reported"] else 1.0, t["found"] / t["truth"] if t["truth"] else 1.0,
            t["typed"] / t["reported"] if t["reported"] else 1.0, t["typed"] / t["truth"] if t["truth"] else 1.0)


def type_table(types):
    """The per-type table's header and rows (truth, found, typed, reported), types sorted."""
    lines = ["| type | truth | found | typed | reported |", "|---|---|---|---|---|"]
    for k, v in sorted(types.items()):
        lines.append("| %s | %d | %d | %d | %d |" % (k, v["truth"], v["found"], v["typed_found"], v["reported"]))
    return lines


def replace_section(name, section, insert_at):
    """Replaces <!-- NAME:begin --> ... <!-- NAME:end --> (and the newline after it) of docs/simplify.md by
    section; when absent, insert_at(text) gives the text with the section put in."""
    doc = os.path.join(ROOT, "docs", "simplify.md")
    text = open(doc).read()
    a, e = "<!-- %s:begin -->" % name, "<!-- %s:end -->" % name
    if a in text:
        i, j = text.index(a), text.index(e) + len(e) + 1
        text = text[:i] + section + text[j:]
    else:
        text = insert_at(text)
    open(doc, "w").write(text)
