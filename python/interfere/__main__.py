"""``python -m interfere ARGS``: runs the ``interfere`` command-line tool with ARGS (docs/python.md).

``pip install .`` puts the CLI into the package (``interfere/bin/interfere``, and ``interfere-cad``
for STEP input when OpenCASCADE was found; setup.py, ``INTERFERE_PIP_CLI=0`` leaves them out). The
executable is, in this order: ``$INTERFERE_CLI``; ``interfere/bin/interfere``; ``interfere`` on PATH. The process is
replaced by the CLI (exec), so its exit code is the CLI's (0 clear, 1 interference, 2 error).
"""

import os
import shutil
import sys

_HELP = (
    "interfere: error: the `interfere` executable was not found (looked at $INTERFERE_CLI, {bundled} and PATH).\n"
    "This Python package was built without the command-line tool (INTERFERE_PIP_CLI=0, or a build tree without it): "
    "reinstall with `pip install .`, build it with CMake "
    "(cmake -S . -B build && cmake --build build --target interfere) and put build/apps/cli on PATH, "
    "install it (cmake --install build), or set INTERFERE_CLI to its path.\n"
)


def find_cli():
    """Path of the `interfere` executable, or None."""
    env = os.environ.get("INTERFERE_CLI")
    if env:
        return env if os.path.isfile(env) and os.access(env, os.X_OK) else None
    bundled = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bin", "interfere")
    if os.path.isfile(bundled) and os.access(bundled, os.X_OK):
        return bundled
    return shutil.which("interfere")


def main(argv=None):
    args = sys.argv[1:] if argv is None else list(argv)
    cli = find_cli()
    if cli is None:
        env = os.environ.get("INTERFERE_CLI")
        if env:
            sys.stderr.write(f"interfere: error: INTERFERE_CLI={env} is not an executable file\n")
        else:
            bundled = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bin", "interfere")
            sys.stderr.write(_HELP.format(bundled=bundled))
        return 2
    sys.stdout.flush()
    sys.stderr.flush()
    os.execv(cli, [cli] + args)
    return 2  # not reached


if __name__ == "__main__":
    sys.exit(main())
