"""physarum from Python: Physarum (slime-mold) and reaction-diffusion patterns grown on curved
surfaces, and thin shells grown by them, with numpy arrays in and out (docs/python.md).

    import physarum
    sim = physarum.Simulation(physarum.Scene("tools/scenes/default.json"), steps=300)
    sim.step(300)
    pheromone = sim.fields()["pheromone"]       # per input vertex, numpy float64
    sim.write("out")                            # the files `physarum run` writes

Meshes are (V, F): V (n, 3) float64, F (m, 3) int64. Errors are ValueError for bad input and
RuntimeError for device failures, with the engine's message.
"""
from ._physarum import devices, read_mesh
from .scene import Scene
from .simulation import Simulation
from .surface import Surface
from .tools import (analyze, colormap, compare, diffuse, elevation, geodesic_distance, gradient,
                    laplace_interpolation, sketch, slope)

__all__ = ["Scene", "Simulation", "Surface", "analyze", "colormap", "compare", "devices", "diffuse", "elevation",
           "geodesic_distance", "gradient", "laplace_interpolation", "read_mesh", "sketch", "slope"]
__version__ = "0.1"
