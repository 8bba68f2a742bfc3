"""The package installs as Python users install it (validation suite: `ctest -L validation`).

    python python_wheel.py SOURCE WORKDIR

`pip wheel SOURCE` with build isolation (scikit-build-core and nanobind from PyPI) into a fresh build
folder under WORKDIR, then the wheel installed into a fresh virtual environment that has never seen
the build, and from there: the default scene run through the module, through the `physarum` command
the wheel installs, and through `python -m physarum`, the last two writing the same bytes. Prints the
wall time of each stage. Exit 77 (ctest: skipped) with a message when PyPI cannot be reached."""
import filecmp
import json
import os
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

SKIPPED = 77


def pypi_reachable() -> bool:
    try:
        with urllib.request.urlopen("https://pypi.org/simple/scikit-build-core/", timeout=15) as reply:
            return reply.status == 200
    except OSError:
        return False


def run(command, **kwargs) -> float:
    start = time.monotonic()
    print("$", " ".join(str(c) for c in command), flush=True)
    subprocess.run([str(c) for c in command], check=True, **kwargs)
    return time.monotonic() - start


def main() -> int:
    source, work = Path(sys.argv[1]).resolve(), Path(sys.argv[2]).resolve()
    if not pypi_reachable():
        print("python_wheel: skipped: PyPI (https://pypi.org) cannot be reached, and a build with isolation "
              "takes scikit-build-core and nanobind from it")
        return SKIPPED
    if work.exists():
        subprocess.run(["rm", "-rf", str(work)], check=True)
    work.mkdir(parents=True)
    builder, user = work / "builder", work / "user"
    run([sys.executable, "-m", "venv", builder])
    # A fresh build folder: nothing of the source tree's build/ is reused.
    wheel_time = run([builder / "bin" / "pip", "wheel", "--no-deps", "-w", work / "dist", "-C",
                      f"build-dir={work / 'build'}", source])
    wheels = sorted((work / "dist").glob("physarum-*.whl"))
    assert len(wheels) == 1, wheels
    run([sys.executable, "-m", "venv", user])
    install_time = run([user / "bin" / "pip", "install", wheels[0]])

    scene = source / "tools" / "scenes" / "default.json"
    # Outside the source tree, so nothing there can be imported by mistake.
    module = ("import physarum, json; s = physarum.Simulation(%r, backend='reference', steps=40); s.step(40); "
              "s.write(%r); print(json.dumps(s.stats()))" % (str(scene), str(work / "from_module")))
    run([user / "bin" / "python", "-c", module], cwd=work)
    run([user / "bin" / "physarum", "run", scene, "--backend", "reference", "--steps", "40", "--out",
         work / "from_command"], cwd=work)
    run([user / "bin" / "python", "-m", "physarum", "run", scene, "--backend", "reference", "--steps", "40", "--out",
         work / "from_python_m"], cwd=work)
    for name in ("fields_full.ply", "stats.csv"):
        for other in ("from_command", "from_python_m"):
            assert filecmp.cmp(work / "from_module" / name, work / other / name, shallow=False), (name, other)
    run_json = json.loads((work / "from_command" / "run.json").read_text())
    assert run_json["steps"] == 40 and run_json["backend"] == "reference"
    print(f"python_wheel: pip wheel (fresh build, isolation) {wheel_time:.0f} s; pip install of the wheel into a "
          f"fresh venv {install_time:.0f} s; the default scene from the module, the physarum command and "
          f"python -m physarum wrote the same fields_full.ply and stats.csv")
    return 0


if __name__ == "__main__":
    sys.exit(main())
