"""numpy arrays checked and written where the engine reads them: the argument checks that name the
argument, and binary PLY files (the engine's own map and mesh format) for meshes and per-vertex or
per-face values handed over from numpy."""
from __future__ import annotations

import os

import numpy as np


def float_array(value, name: str, shape: tuple) -> np.ndarray:
    """`value` as a C-contiguous float64 array of `shape` (-1: any length), finite; ValueError naming
    `name` otherwise."""
    try:
        array = np.asarray(value)
    except Exception as error:  # noqa: BLE001 - anything numpy cannot read is the caller's error
        raise ValueError(f"{name}: not an array of numbers ({error})") from None
    if array.dtype == object or not (np.issubdtype(array.dtype, np.floating) or np.issubdtype(array.dtype, np.integer)):
        raise ValueError(f"{name}: expected real numbers, got dtype {array.dtype}")
    _check_shape(array, name, shape)
    array = np.ascontiguousarray(array, dtype=np.float64)
    bad = ~np.isfinite(array)
    if bad.any():
        first = np.argwhere(bad)[0]
        where = int(first[0]) if len(first) == 1 else tuple(int(i) for i in first)
        raise ValueError(f"{name}: value at {where} is not finite ({array[tuple(first)]})")
    return array


def index_array(value, name: str, shape: tuple, bound: int | None = None) -> np.ndarray:
    """`value` as an int64 array of `shape`, every entry in 0..bound-1 when `bound` is given."""
    array = np.asarray(value)
    if not np.issubdtype(array.dtype, np.integer):
        raise ValueError(f"{name}: expected integer indices, got dtype {array.dtype}")
    _check_shape(array, name, shape)
    array = np.ascontiguousarray(array, dtype=np.int64)
    if bound is not None and array.size and (array.min() < 0 or array.max() >= bound):
        raise ValueError(f"{name}: indices must lie in 0..{bound - 1}, found {array.min()}..{array.max()}")
    return array


def _check_shape(array: np.ndarray, name: str, shape: tuple) -> None:
    if array.ndim != len(shape) or any(s != -1 and s != a for s, a in zip(shape, array.shape)):
        wanted = "(" + ", ".join("n" if s == -1 else str(s) for s in shape) + ("," if len(shape) == 1 else "") + ")"
        raise ValueError(f"{name}: expected shape {wanted}, got {array.shape}")


def write_ply(path: str | os.PathLike, V: np.ndarray, F: np.ndarray | None = None,
              vertex_values: dict[str, np.ndarray] | None = None,
              face_values: dict[str, np.ndarray] | None = None) -> None:
    """A binary little-endian PLY: positions as doubles, triangles, and float64 vertex and face
    properties (the layout the engine's PLY reader takes: common/mesh/ply_reader.hpp)."""
    vertex_values = vertex_values or {}
    face_values = face_values or {}
    F = np.zeros((0, 3), np.int64) if F is None else F
    header = ["ply", "format binary_little_endian 1.0", f"element vertex {len(V)}",
              "property double x", "property double y", "property double z"]
    header += [f"property double {name}" for name in vertex_values]
    if len(F):
        header += [f"element face {len(F)}", "property list uchar int vertex_indices"]
        header += [f"property double {name}" for name in face_values]
    header.append("end_header")
    vertex = np.zeros(len(V), dtype=[("p", "<f8", 3)] + [(n, "<f8") for n in vertex_values])
    vertex["p"] = V
    for name, values in vertex_values.items():
        vertex[name] = values
    face = np.zeros(len(F), dtype=[("n", "u1"), ("i", "<i4", 3)] + [(n, "<f8") for n in face_values])
    face["n"] = 3
    face["i"] = F
    for name, values in face_values.items():
        face[name] = values
    with open(path, "wb") as out:
        out.write(("\n".join(header) + "\n").encode("ascii"))
        out.write(vertex.tobytes())
        out.write(face.tobytes())


def vertex_values_map(path: str | os.PathLike, values: np.ndarray) -> dict:
    """Per input vertex `values` written to `path` as a PLY, and the scalar map that reads them
    (``{"ply": FILE, "property": "values"}``, as a scene file would name it)."""
    write_ply(path, np.zeros((len(values), 3)), vertex_values={"values": values})
    return {"ply": os.fspath(path), "property": "values"}
