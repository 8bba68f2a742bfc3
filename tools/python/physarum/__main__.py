"""``python -m physarum ARGS`` (and the ``physarum`` command a wheel installs): the command-line
program, as ``physarum ARGS`` runs it (docs/commands.md). The wheel carries it inside the package
(physarum/bin/physarum); a module imported from the build tree (PYTHONPATH=build/python) runs
build/physarum beside it."""
from __future__ import annotations

import os
import sys
from pathlib import Path


def program() -> Path:
    """The physarum program this package goes with."""
    package = Path(__file__).resolve().parent
    for candidate in (package / "bin" / "physarum", package.parent.parent / "physarum"):
        if candidate.is_file() and os.access(candidate, os.X_OK):
            return candidate
    raise FileNotFoundError(f"no physarum program beside the package {package} (looked in {package / 'bin'} and "
                            f"{package.parent.parent}): install the package with pip, or build the project")


def main() -> None:
    try:
        exe = program()
    except FileNotFoundError as e:
        print(f"physarum: error: {e}", file=sys.stderr)
        sys.exit(1)
    sys.stdout.flush()
    os.execv(exe, [str(exe), *sys.argv[1:]])


if __name__ == "__main__":
    main()
