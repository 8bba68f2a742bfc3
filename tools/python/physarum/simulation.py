"""Simulations: a scene's run, made and stepped as ``physarum run`` makes and steps it (the same
session, run loop and output writers), with its fields as numpy arrays between steps."""
from __future__ import annotations

import io
import json
import logging
import os
from typing import Callable

import numpy as np

from . import _physarum as _engine
from .scene import Scene

# The engine's notes (the backend chosen, the maps, sub-steps, a mesh without UVs) and each write's
# closing line go here, at INFO; configure logging (e.g. logging.basicConfig(level=logging.INFO)) to
# see them.
logger = logging.getLogger("physarum")


class Simulation:
    """A scene's run: ``Simulation(scene, backend="auto", device=None, seed=None, steps=None)``.

    ``backend`` is "auto" (OpenCL where a device exists, else the reference), "reference" or "opencl";
    ``device`` an index from ``devices()`` or a name substring; ``seed`` replaces the scene's; ``steps``
    is the run's length (else the scene's ``steps`` or ``sim_time``; a growth scene's is its
    schedule). The length places stats.csv's rows (about 100, as ``physarum run`` takes them), so
    ``step()`` through the whole length then ``write()`` gives the files ``physarum run`` writes.
    Everything that can refuse the scene (keys, mesh, maps, memory, the device) is checked here.
    """

    def __init__(self, scene: Scene | dict | str | os.PathLike, *, backend: str = "auto",
                 device: int | str | None = None, seed: int | None = None, steps: int | None = None):
        if not isinstance(scene, Scene):
            scene = Scene(scene)
        if seed is not None and not (isinstance(seed, (int, np.integer)) and 0 <= seed < 2**32):
            raise ValueError(f"seed: expected an integer in 0..2^32-1, got {seed!r}")
        if steps is not None and not isinstance(steps, (int, np.integer)):
            raise ValueError(f"steps: expected an integer, got {steps!r}")
        self._scene = scene  # keeps the scene's array files alive
        scene_file, scene_json = scene._engine_arguments()
        self._simulation = _engine._Simulation(scene_file, scene_json, backend, "" if device is None else str(device),
                                               None if seed is None else int(seed),
                                               None if steps is None else int(steps), logger.info)

    def step(self, n: int = 1, progress: Callable[[int, int], object] | None = None) -> int:
        """Takes ``n`` steps (the GIL released; Ctrl-C stops between two steps with KeyboardInterrupt).
        ``progress(done, n)`` is called about every 0.1 s. Returns the steps taken: fewer than ``n`` only
        when a growth model's solve failed (see ``stopped``)."""
        if not isinstance(n, (int, np.integer)):
            raise ValueError(f"n: expected an integer, got {n!r}")
        return self._simulation.step(int(n), progress)

    @property
    def time(self) -> float:
        """Simulated seconds."""
        return self._simulation.time

    @property
    def steps_taken(self) -> int:
        """Steps taken so far (a restored state's included)."""
        return self._simulation.steps_taken

    @property
    def planned_steps(self) -> int:
        """The run's length in steps."""
        return self._simulation.planned_steps

    @property
    def layer_names(self) -> list[str]:
        """The dynamic layers: "pheromone" (competing species: "pheromone_0", ...) or the morphogens."""
        return self._simulation.layer_names

    @property
    def backend(self) -> str:
        """The backend that runs: "reference" or "opencl" (what "auto" chose)."""
        return self._simulation.backend

    @property
    def device(self) -> str:
        """The device it runs on ("host" for the reference backend)."""
        return self._simulation.device

    @property
    def stopped(self) -> str | None:
        """Why a growth run stopped early (its equilibrium solve failed), else None."""
        return self._simulation.stopped

    def fields(self, on: str = "input") -> dict[str, np.ndarray]:
        """Every layer by name: per input vertex (``on="input"``), per intrinsic vertex
        (``"intrinsic"``), or per vertex of the full-resolution mesh (``"full"``: the same numbers as
        "intrinsic", in ``Surface.full_mesh()``'s order). A growth run's are on its sheet as it is now."""
        return self._simulation.fields(on)

    def set(self, key: str, value) -> int:
        """A live change: ``key`` (a path as ``physarum run --set`` takes it: "sensor_angle",
        "parameters.F") takes ``value`` from the next step on, for a key the running model takes on
        the fly (the agent model's Table 1 parameters, a reaction's coefficients; the studio and the
        library's Session::set use the same rule). Returns the step after which it applies.
        ValueError naming the key for one that needs a new run, or for a bad value; nothing changes
        then. The statistics columns measured against U (coverage) keep the U the run started with."""
        if isinstance(value, np.generic):
            value = value.item()
        try:
            text = json.dumps(value)
        except TypeError as e:
            raise ValueError(f"{key}: the value {value!r} is not a JSON value") from e
        return self._simulation.set(str(key), text)

    def set_field(self, name: str, values, *, on: str = "input") -> None:
        """Replaces the layer ``name`` (one of ``layer_names``) by ``values``, from the next step on:
        per input vertex (``on="input"``, interpolated onto the intrinsic vertices) or per intrinsic
        vertex (``"intrinsic"``; a growth run's: per vertex of its sheet as it is now). ValueError for
        an unknown layer or a wrong number of values, naming what was expected."""
        self._simulation.set_field(str(name), np.ascontiguousarray(values, dtype=np.float64).ravel(), on)

    def sheet(self) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
        """A growth run's sheet as it is now: ``(V, F, fields)`` with V (n, 3) float64 the deformed
        vertices, F (m, 3) int64 its triangles, and per vertex every morphogen and "area_growth" (rest
        area now / at the start). ValueError for a scene of another model."""
        sheet = self._simulation.sheet()
        if sheet is None:
            raise ValueError("sheet(): only a growth scene (\"model\": \"growth\") has a growing sheet; this "
                             "simulation's surface is fixed (fields() gives its layers)")
        return sheet

    def stats(self) -> dict[str, float]:
        """stats.csv's columns for the state now (time, mean, coverage, ... or each morphogen's mean
        and variance)."""
        return self._simulation.stats()

    def stats_table(self) -> dict[str, np.ndarray]:
        """stats.csv so far as columns: the rows taken at the run's row steps."""
        text = self._simulation.statistics_text()
        names = text.split("\n", 1)[0].split(",")
        rows = np.loadtxt(io.StringIO(text), delimiter=",", skiprows=1, ndmin=2)
        return {name: rows[:, i] for i, name in enumerate(names)}

    def save_state(self) -> bytes:
        """The whole state (fields, agents, random streams, the statistics so far) as bytes: a
        checkpoint in physarum's format."""
        return self._simulation.save_state()

    def restore_state(self, state: bytes) -> None:
        """Continues from ``save_state()``'s bytes bit for bit. ValueError (nothing changed) for the state
        of another scene, backend, device or build, or damaged bytes."""
        if not isinstance(state, (bytes, bytearray, memoryview)):
            raise ValueError(f"state: expected bytes from save_state(), got {type(state).__name__}")
        self._simulation.restore_state(bytes(state))

    def write(self, out: str | os.PathLike) -> str:
        """Writes the run's files into the folder ``out`` as ``physarum run --out`` does (the fields'
        PLY files, preview.png, result.glb, stats.csv, run.json, ...). Returns ``out``. A run written
        before its last step records the steps taken. RuntimeError when a growth run had stopped
        (its files are written first)."""
        out = os.fspath(out)
        stopped = self._simulation.write(out)
        if stopped is not None:
            raise RuntimeError(f"{out}: written, but the run stopped early: {stopped}")
        return out

    def __repr__(self) -> str:
        return (f"Simulation({self.backend}, step {self.steps_taken} of {self.planned_steps}, "
                f"t = {self.time:.6g} s, layers {self.layer_names})")
