"""Shared fixtures of the Python module's tests (run by ctest's `python` test: PYTHONPATH holds the
built package, PHYSARUM_EXE the command-line program the module is compared with)."""
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

SOURCE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(SOURCE / "tests"))
from read_exports import parse_ply  # noqa: E402  (the tests' own PLY reader, independent of the engine)

EXE = os.environ.get("PHYSARUM_EXE", str(SOURCE / "build" / "physarum"))

# Small scenes: a few seconds each on two cores.
AGENT_SCENE = {"mesh": "shape:sphere", "scale_to_area": 4.0, "max_circumradius": 0.06, "agents": 3000,
               "time_step": 0.01, "sensor_distance": 0.05, "sensor_angle": 22.5, "move_rate": 0.5,
               "turn_rate": 180.0, "turn_frequency": 20.0, "deposit_rate": 1.0, "decay_rate": 1.0,
               "diffuse_rate": 0.0002, "mean_lifetime": 1.0, "activation_time": 0.2, "seed": 3, "steps": 40}
GRAY_SCOTT_SCENE = {"mesh": "shape:torus", "scale_to_area": 1.0, "max_circumradius": 0.03, "model": "gray-scott",
                    "parameters": {"F": 0.035, "k": 0.065},
                    "morphogens": {"u": {"diffusion": 2e-5, "initial": 1.0}, "v": {"diffusion": 1e-5, "initial": 0.0}},
                    "initial": {"noise": 0.01, "spots": {"count": 10, "radius": 0.05, "values": {"u": 0.5, "v": 0.25}}},
                    "time_step": 1.0, "integrator": "forward", "seed": 1, "steps": 150}


def have_opencl():
    import physarum
    return bool(physarum.devices())


BACKENDS = ["reference", pytest.param("opencl", marks=pytest.mark.skipif(not have_opencl(), reason="no OpenCL device"))]


def write_scene(folder: Path, scene: dict, name: str = "scene.json") -> Path:
    path = folder / name
    path.write_text(json.dumps(scene))
    return path


def physarum_command(*args, check=True):
    """The command-line program, as a user runs it."""
    result = subprocess.run([EXE, *map(str, args)], capture_output=True, text=True)
    if check and result.returncode != 0:
        raise AssertionError(f"physarum {' '.join(map(str, args))} exited {result.returncode}: {result.stderr}")
    return result


def ply_property(path: Path, name: str) -> np.ndarray:
    vertices, _ = parse_ply(path)
    return np.asarray(vertices[name], dtype=np.float64)
