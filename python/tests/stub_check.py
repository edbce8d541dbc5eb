"""Checks the generated type stubs `_interfere.pyi` against the imported module (issue #30).

Used by test_stubs.py (the build tree) and pip_install_check.py (an installed package). Without
mypy (Debian 12 ships none by default) the check is structural: the stub parses, and every public
name of `interfere._interfere` (and of its submodules, as namespace classes) is declared in it,
with every public method and property of every class.
"""

import ast
import keyword
import os
import subprocess
import sys
import types


def declared(body):
    """Names a stub body declares: classes, functions, annotated names -> their ast node."""
    out = {}
    for node in body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
            out.setdefault(node.name, node)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            out.setdefault(node.target.id, node)
    return out


def public(obj):
    """Public names a stub can declare (a keyword such as bearing.Roller.raise cannot be)."""
    return sorted(n for n in dir(obj) if not n.startswith("_") and not keyword.iskeyword(n))


def missing_names(stub_text, module):
    """Public names of `module` (recursively into its classes and submodules) the stub lacks."""
    top = declared(ast.parse(stub_text).body)
    missing = []

    def check_class(cls, node, prefix):
        members = declared(node.body)
        # the class's own members and those of its bases in the module, not object's/Exception's
        own = [vars(b) for b in cls.__mro__ if b.__module__ != "builtins" and b.__name__ != "pybind11_object"]
        for name in public(cls):
            if not any(name in v for v in own):
                continue
            if name not in members and not isinstance(getattr(cls, name, None), type):
                missing.append(prefix + name)

    def check_scope(obj, names, prefix):
        for name in public(obj):
            value = getattr(obj, name)
            if name not in names:
                missing.append(prefix + name)
            elif isinstance(value, type) and isinstance(names[name], ast.ClassDef):
                check_class(value, names[name], prefix + name + ".")
            elif isinstance(value, types.ModuleType) and isinstance(names[name], ast.ClassDef):
                check_scope(value, declared(names[name].body), prefix + name + ".")

    check_scope(module, top, "")
    if "__version__" not in top:
        missing.append("__version__")
    return missing


def check_stub_file(path, module):
    """Raises AssertionError naming what is wrong; runs mypy on the stub when it is installed."""
    with open(path) as f:
        text = f.read()
    missing = missing_names(text, module)
    assert not missing, f"{path} lacks {len(missing)} public names: {missing[:20]}"
    try:
        import mypy  # noqa: F401
    except ImportError:
        return "structural check (mypy not installed)"
    r = subprocess.run([sys.executable, "-m", "mypy", "--no-error-summary", path], capture_output=True, text=True)
    assert r.returncode == 0, f"mypy {path}:\n{r.stdout}{r.stderr}"
    return "structural check + mypy"


def stub_path(module):
    return os.path.join(os.path.dirname(module.__file__), "_interfere.pyi")
