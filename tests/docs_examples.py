"""Every example in the README and docs/ run as it is written (ctest's `docs_examples`).

The fenced blocks of README.md and docs/*.md are taken out of the Markdown:
  sh      run by bash -e, the blocks of one file one after another in one fresh folder that holds
          the repository's tools/, build/ and .venv (links), so the commands' relative paths
          resolve as from the repository's top, a later block finds what an earlier one wrote, and
          nothing lands in the repository. A command whose comment names a verdict of `physarum
          compare` (# equivalent, # different, # inconclusive) must exit with that verdict's code;
  python  the blocks of one file run one after another in one interpreter (a page reads as one
          session: later blocks use what earlier ones defined), with the built module importable;
  json    a value that must parse; one with a "mesh" is a scene and is run by `physarum run`;
  cpp, cmake (docs/library.md) are built and run by ctest's `install_consumer`.
A block listed in LEFT_OUT is not run; the list says why, and the test prints it. A block that is
neither run nor listed fails the test, as does a listed one that no longer exists, so the docs and
this list cannot drift apart. An example that takes longer than LIMIT_SECONDS fails: it belongs in
LEFT_OUT (the docs promise examples that finish within a minute; the limit leaves room for slower
machines).

    python docs_examples.py REPOSITORY BUILD_DIR
"""
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import time

LIMIT_SECONDS = 180

# (file, the block's first line) -> why it is not run here.
LEFT_OUT = {
    ("README.md", "bash tools/setup.sh && ./build/physarum run tools/scenes/default.json --out out"):
        "the README's two commands install packages as root and build everything: CI runs the second one, and "
        "the first one's run is the docs/commands.md example",
    ("README.md", "./build/physarum sweep tools/scenes/default.json --vary sensor_angle=11.25,22.5,45 --seeds 100 \\"):
        "a cluster's Slurm and /scratch, 300 runs (tests/test_cli_sweep*.cpp submit sweeps to a private Slurm)",
    ("docs/commands.md", "# on the login node (or a laptop, then copy the folder over)"):
        "a cluster's Slurm and /scratch, 300 runs (tests/test_cli_sweep*.cpp submit sweeps to a private Slurm)",
    ("docs/commands.md", '{"input": {"vertices", "faces", "components", "genus", "boundary_loops", "area", ...},'):
        "the shape of `physarum mesh --json`'s output, not a value (tests/test_cli_mesh.cpp reads the real one)",
    ("docs/harness.md", "./build/physarum compare tools/scenes/resolved.json --arm max_circumradius=0.03 --arm max_circumradius=0.02  # equivalent"):
        "four whole comparisons at 50,000 agents, minutes each (the validation suite runs them: "
        "ValidationCompareResolution, ctest -L validation)",
    ("docs/python.md", ".venv/bin/pip install --no-build-isolation -C build-dir=build ."):
        "builds and installs the package into the .venv the tests use (minutes); the tests import the module "
        "built in build/python",
    ("docs/python.md", "python3 -m venv env && env/bin/pip install .        # or: pip wheel . -w dist, then pip install dist/physarum-*.whl"):
        "builds the engine from scratch with packages from PyPI (half an hour on two cores): the validation "
        "test python_wheel runs it (ctest -L validation)",
    ("docs/python.md", "import polyscope as ps                     # any viewer that takes numpy arrays (pip install polyscope)"):
        "opens a window in a viewer that is not installed here",
    ("docs/library.md", "bash tools/setup.sh                       # the Debian packages the library depends on, and build/"):
        "installs packages as root; `install_consumer` runs its `cmake --install` into a fresh prefix",
    ("docs/library.md", "#include \"api/physarum.hpp\""): "built and run against the installed package by `install_consumer`",
    ("docs/library.md", "cmake_minimum_required(VERSION 3.25)"): "the outside project `install_consumer` builds",
}

FENCE = re.compile(r"^```(\w*)\n(.*?)^```", re.S | re.M)

# `physarum compare`'s exit codes by verdict (docs/harness.md).
VERDICT_EXIT = {"equivalent": 0, "different": 3, "inconclusive": 4}
VERDICT_COMMENT = re.compile(r"#\s*(equivalent|different|inconclusive)\s*$")


def with_verdicts_checked(body):
    """The block with each command that names a verdict in its comment held to that verdict's exit code."""
    lines, command = [], ""
    for line in body.splitlines():
        command += line + "\n"
        if line.endswith("\\"):
            continue
        verdict = VERDICT_COMMENT.search(line)
        if verdict:
            code = VERDICT_EXIT[verdict.group(1)]
            command = (f"set +e\n{command}code=$?\nset -e\n[ $code -eq {code} ] || {{ echo 'expected exit {code} "
                       f"({verdict.group(1)}), got '$code >&2; exit 1; }}\n")
        lines.append(command)
        command = ""
    return "".join(lines) + command


def blocks(repository):
    pages = [repository / "README.md"] + sorted((repository / "docs").glob("*.md"))
    for page in pages:
        name = str(page.relative_to(repository))
        for language, body in FENCE.findall(page.read_text()):
            yield name, language, body


def scratch_folder(repository, build):
    folder = pathlib.Path(tempfile.mkdtemp(prefix="physarum_docs_"))
    for name, target in (("tools", repository / "tools"), ("build", build), (".venv", repository / ".venv")):
        (folder / name).symlink_to(target)
    return folder


def run(command, cwd, env, what):
    start = time.monotonic()
    try:
        done = subprocess.run(command, cwd=cwd, env=env, capture_output=True, text=True, timeout=LIMIT_SECONDS)
    except subprocess.TimeoutExpired:
        return f"{what}: still running after {LIMIT_SECONDS} s (list it in LEFT_OUT with the reason)"
    seconds = time.monotonic() - start
    print(f"  ran {what} in {seconds:.1f} s", flush=True)
    if done.returncode != 0:
        return f"{what}: exit {done.returncode}\n--- stdout\n{done.stdout[-3000:]}\n--- stderr\n{done.stderr[-3000:]}"
    return None


def main():
    repository, build = pathlib.Path(sys.argv[1]).resolve(), pathlib.Path(sys.argv[2]).resolve()
    env = dict(os.environ, PYTHONPATH=str(build / "python"))
    failures, seen, python_pages, folders = [], set(), {}, {}

    def folder_of(page):
        if page not in folders:
            folders[page] = scratch_folder(repository, build)
        return folders[page]

    for page, language, body in blocks(repository):
        first = body.split("\n", 1)[0]
        key = (page, first)
        if key in LEFT_OUT:
            seen.add(key)
            print(f"left out: {page}: {first[:70]}\n    because {LEFT_OUT[key]}")
            continue
        what = f"{page} ({language}) {first[:60]!r}"
        if language == "sh":
            failures.append(run(["bash", "-e", "-c", with_verdicts_checked(body)], folder_of(page), env, what))
        elif language == "python":
            python_pages.setdefault(page, []).append(body)
        elif language == "json":
            try:
                value = json.loads(body)
            except json.JSONDecodeError as e:
                failures.append(f"{what}: not JSON ({e})")
                continue
            if isinstance(value, dict) and "mesh" in value:
                (folder_of(page) / "scene.json").write_text(body)
                failures.append(run([str(build / "physarum"), "run", "scene.json", "--out", "scene_out"], folder_of(page),
                                    env, what))
        else:
            failures.append(f"{what}: a ```{language} block this test does not know how to run (run it, or list it "
                            "in LEFT_OUT with the reason)")
    for page, bodies in python_pages.items():
        # Blocks that are left out are skipped inside a page too (a viewer's window, say).
        (folder_of(page) / "page.py").write_text("\n".join(bodies))
        failures.append(run([sys.executable, "page.py"], folder_of(page), env, f"{page}'s {len(bodies)} python blocks"))
    for key in LEFT_OUT:
        if key not in seen:
            failures.append(f"LEFT_OUT names a block that no longer exists: {key[0]}: {key[1]!r}")
    for folder in folders.values():
        shutil.rmtree(folder, ignore_errors=True)
    failures = [f for f in failures if f]
    for f in failures:
        print("FAILED " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
