"""Surfaces: a mesh prepared as a run prepares it (loaded and repaired, scaled, its intrinsic
Delaunay triangulation refined), with its counts, its intrinsic vertices' places on the input
surface, the full-resolution mesh and the Laplacian's eigenvalues."""
from __future__ import annotations

import os

import numpy as np

from . import _physarum as _engine
from ._arrays import float_array, index_array


class Surface:
    """A surface as physarum simulates on it.

    ``Surface(V, F)`` takes a mesh as numpy arrays (V: (n, 3) float64, F: (m, 3) integer, counter-clockwise
    seen from outside); ``Surface.from_file(path)`` a mesh file; ``Surface.from_shape("sphere")`` a built-in
    shape. The keywords are the scene's surface keys: ``max_circumradius`` (refine until every intrinsic
    triangle's circumradius is below it, in scaled units), ``min_angle`` (degrees), ``scale_to_area``.
    The mesh goes through the same repair and refusals as ``physarum run`` (ValueError with its message).
    """

    def __init__(self, V, F, *, max_circumradius: float | None = None, min_angle: float = 0.0,
                 scale_to_area: float | None = None):
        V = float_array(V, "V", (-1, 3))
        F = index_array(F, "F", (-1, 3), bound=len(V))
        if len(F) == 0:
            raise ValueError("F: the mesh has no triangles")
        _check_keywords(max_circumradius, min_angle, scale_to_area)
        # The same repair and refusals as a mesh file's polygons, at full double precision.
        self._surface = _engine._Surface(V, F, scale_to_area, max_circumradius, float(min_angle))
        self._mesh = "the arrays V, F"

    @classmethod
    def from_file(cls, path: str | os.PathLike, **keywords) -> "Surface":
        """The mesh in ``path`` (OBJ, PLY, OFF, STL, ... as physarum reads them)."""
        surface = cls.__new__(cls)
        surface._mesh = os.fspath(path)
        keywords = _surface_keywords(keywords)
        _check_keywords(keywords.get("max_circumradius"), keywords.get("min_angle", 0.0), keywords.get("scale_to_area"))
        surface._surface = _engine._Surface(surface._mesh, keywords.get("scale_to_area"),
                                            keywords.get("max_circumradius"), float(keywords.get("min_angle", 0.0)))
        return surface

    @classmethod
    def from_shape(cls, name: str, **keywords) -> "Surface":
        """A built-in shape: "sphere", "torus", "plane", "disk-N", ... (``physarum mesh --help`` lists them)."""
        return cls.from_file(name if name.startswith("shape:") else "shape:" + name, **keywords)

    # ---- counts and geometry ----
    @property
    def vertex_count(self) -> int:
        """Vertices of the intrinsic triangulation (input vertices first: input vertex i is intrinsic vertex
        ``input_to_intrinsic[i]``)."""
        return self._surface.vertex_count

    @property
    def face_count(self) -> int:
        """Triangles of the intrinsic triangulation."""
        return self._surface.face_count

    @property
    def input_vertex_count(self) -> int:
        """Vertices of the input mesh as loaded and repaired (what per-input-vertex arrays have)."""
        return self._surface.input_vertex_count

    @property
    def input_face_count(self) -> int:
        """Triangles of the input mesh (what per-input-face arrays have)."""
        return self._surface.input_face_count

    @property
    def area(self) -> float:
        """Total area in the simulated (scaled) units."""
        return self._surface.area

    @property
    def warnings(self) -> list[str]:
        """Repairs made while loading (split non-manifold vertices, dropped unused ones, ...)."""
        return self._surface.warnings

    def input_mesh(self) -> tuple[np.ndarray, np.ndarray]:
        """The input mesh as loaded and repaired: (V (n, 3) float64, F (m, 3) int64)."""
        return self._surface.input_mesh()

    def full_mesh(self) -> tuple[np.ndarray, np.ndarray]:
        """The full-resolution mesh: every intrinsic vertex at its place on the input surface and the
        intrinsic triangles (the mesh of ``fields_full.ply``; vertex i is intrinsic vertex i)."""
        return self._surface.full_mesh()

    @property
    def intrinsic_positions(self) -> np.ndarray:
        """(vertex_count, 3): where each intrinsic vertex lies on the input surface, in input coordinates."""
        return self.full_mesh()[0]

    @property
    def input_to_intrinsic(self) -> np.ndarray:
        """(input_vertex_count,) int64: the intrinsic vertex sitting on each input vertex."""
        return self._surface.input_to_intrinsic()

    @property
    def vertex_mass(self) -> np.ndarray:
        """(vertex_count,): the lumped mass (a third of the incident intrinsic triangles' areas)."""
        return self._surface.vertex_mass()

    def eigenvalues(self, count: int) -> np.ndarray:
        """The ``count`` smallest eigenvalues of L x = lambda M x (cotan Laplacian, lumped mass), ascending."""
        return self._surface.eigenvalues(int(count))

    def __repr__(self) -> str:
        return (f"Surface({self._mesh!r}: {self.input_vertex_count} input vertices, {self.vertex_count} intrinsic "
                f"vertices, {self.face_count} faces, area {self.area:.6g})")


def _check_keywords(max_circumradius, min_angle, scale_to_area) -> None:
    for value, name in ((max_circumradius, "max_circumradius"), (scale_to_area, "scale_to_area")):
        if value is not None and not (np.isfinite(value) and value > 0):
            raise ValueError(f"{name}: must be a positive number, got {value}")
    if not (np.isfinite(min_angle) and 0 <= min_angle):
        raise ValueError(f"min_angle: must be >= 0 degrees, got {min_angle}")


def _surface_keywords(keywords: dict) -> dict:
    known = {"max_circumradius", "min_angle", "scale_to_area"}
    unknown = set(keywords) - known
    if unknown:
        raise ValueError(f"{sorted(unknown)[0]}: not a surface keyword (known: {', '.join(sorted(known))})")
    return keywords
