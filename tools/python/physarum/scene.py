"""Scenes: what to simulate, as a scene file holds it (docs/scenes.md lists every key of every model),
given as a dict, a JSON file or keyword arguments. numpy arrays may stand wherever a map is taken."""
from __future__ import annotations

import copy
import json
import os
import tempfile

import numpy as np

from ._arrays import float_array, vertex_values_map, write_ply


class Scene:
    """A scene: ``Scene("tools/scenes/default.json")``, ``Scene({"mesh": "shape:sphere", ...})`` or
    ``Scene(mesh="shape:sphere", agents=20000, steps=300)`` (keywords are scene keys; with a dict they
    add to or replace its keys; nested keys as dicts: ``bias={"strength": 40}``).

    Any key that takes a map also takes a numpy array: per input vertex values, shape (n,), for a
    scalar map (a parameter such as ``sensor_angle``, a map in ``maps``), per input face vectors,
    shape (m, 3), for a direction map. The arrays are handed to the engine as the PLY maps a scene
    file would name (``{"ply": FILE, "property": NAME}``), so a run is the same as with such a file.
    The engine checks the scene when a Simulation is made; ``Scene.check()`` does it now.
    """

    def __init__(self, source: dict | str | os.PathLike | None = None, /, **keys):
        self._file: str | None = None
        self._folder = None  # the numpy arrays' PLY files live here as long as the scene does
        if isinstance(source, (str, os.PathLike)):
            if keys:
                raise ValueError("keys: a scene file takes no keywords (load it with json and pass the dict)")
            self._file = os.fspath(source)
            if not os.path.isfile(self._file):
                raise ValueError(f"source: no scene file {self._file}")
            self._json = None
            return
        if source is not None and not isinstance(source, dict):
            raise ValueError(f"source: expected a dict or a JSON file path, got {type(source).__name__}")
        given = copy.deepcopy(source) if source else {}
        given.update(keys)
        self._json = self._with_arrays_as_maps(given)

    @property
    def file(self) -> str | None:
        """The scene file, for a scene read from one."""
        return self._file

    def to_dict(self) -> dict:
        """The scene as JSON data (arrays replaced by the maps that read them)."""
        if self._file is not None:
            with open(self._file) as f:
                return json.load(f)
        return json.loads(self._json)

    def check(self) -> "Scene":
        """Checks every key and value as ``physarum run`` does (no surface is built); ValueError naming the
        key otherwise. Returns the scene."""
        from . import _physarum as _engine
        _engine._check_scene(self._file or "", self._json or "")
        return self

    def _with_arrays_as_maps(self, scene: dict) -> str:
        maps = scene.setdefault("maps", {})
        if not isinstance(maps, dict):
            raise ValueError("maps: expected a dict of named maps")

        def replace(value, where: str):
            if isinstance(value, np.ndarray):
                name = "numpy_" + where.replace(".", "_")
                maps[name] = self._array_map(value, where)
                return name
            if isinstance(value, dict):
                return {k: replace(v, f"{where}.{k}" if where else k) for k, v in value.items()}
            if isinstance(value, list):
                return [replace(v, f"{where}.{i}") for i, v in enumerate(value)]
            return value

        for name in list(maps):
            if isinstance(maps[name], np.ndarray):  # an array as a map's whole definition keeps the map's name
                maps[name] = self._array_map(maps[name], f"maps.{name}")
            else:  # an array as an operand inside a definition becomes a map of its own
                maps[name] = replace(maps[name], f"maps.{name}")
        scene.update({k: replace(v, k) for k, v in scene.items() if k != "maps"})
        if not maps:
            del scene["maps"]
        try:
            return json.dumps(scene)
        except TypeError as error:
            raise ValueError(f"scene: a value is not JSON data or a numpy array ({error})") from None

    def _array_map(self, array: np.ndarray, where: str) -> dict:
        if self._folder is None:
            self._folder = tempfile.TemporaryDirectory(prefix="physarum-scene-")
        path = os.path.join(self._folder.name, where.replace("/", "_") + ".ply")
        if array.ndim == 1:
            return vertex_values_map(path, float_array(array, where, (-1,)))
        vectors = float_array(array, where, (-1, 3))
        faces = np.zeros((len(vectors), 3), np.int64)
        write_ply(path, np.zeros((1, 3)), faces,
                  face_values={"values_x": vectors[:, 0], "values_y": vectors[:, 1], "values_z": vectors[:, 2]})
        return {"ply": path, "face_property": "values"}

    def _engine_arguments(self) -> tuple[str, str]:
        return self._file or "", self._json or ""

    def __repr__(self) -> str:
        return f"Scene({self._file!r})" if self._file else f"Scene({self._json[:60]}...)"
