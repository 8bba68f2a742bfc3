#!/usr/bin/env python3
"""What Python costs on top of the engine (issue 38's targets), in one run, each pair interleaved:

  1. a heat-method geodesic distance on a ~6,000-vertex mesh, factorization included, against
     potpourri3d's MeshHeatMethodDistanceSolver (when installed), and the two errors against the
     exact great-circle distance on the sphere;
  2. the default scene from Python (Simulation + step + write) against `physarum run`, alternated;
  3. fields(on="intrinsic") on a surface of about a million intrinsic vertices;
  4. step(1) in a loop against the same steps taken by one step(n) call: the cost per call.

    PYTHONPATH=build/python .venv/bin/python bench/python/python_bench.py [--quick]

Prints one line per measurement (median of the repeats, seconds)."""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import physarum

SOURCE = Path(__file__).resolve().parents[2]
EXE = os.environ.get("PHYSARUM_EXE", str(SOURCE / "build" / "physarum"))
# A small Gray-Scott system on the unit sphere (tools/scenes/gray_scott.json's kinetics).
GRAY_SCOTT = dict(mesh="shape:sphere", model="gray-scott", parameters={"F": 0.035, "k": 0.065},
                  morphogens={"u": {"diffusion": 2e-5, "initial": 1.0}, "v": {"diffusion": 1e-5, "initial": 0.0}},
                  initial={"noise": 0.01}, time_step=1.0, integrator="forward", seed=1)


def median_time(function, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return float(np.median(times))


def geodesic(repeats):
    # A unit sphere of 6,002 vertices (the built-in one refined, then taken as a plain mesh: the heat
    # method on the triangles as given, as potpourri3d gets them).
    sphere = physarum.Surface.from_shape("sphere", max_circumradius=0.04)
    V, F = sphere.full_mesh()
    surface = physarum.Surface(V, F)
    exact = np.arccos(np.clip(V @ V[0] / np.linalg.norm(V, axis=1) / np.linalg.norm(V[0]), -1, 1))
    ours = median_time(lambda: physarum.geodesic_distance(surface, [0]), repeats)
    ours_error = np.abs(physarum.geodesic_distance(surface, [0]) - exact).mean()
    line = f"geodesic heat, {len(V)} vertices: physarum {ours:.4f} s (mean error {ours_error:.2e})"
    try:
        import potpourri3d as pp3d
    except ImportError:
        print(line + "; potpourri3d not installed")
        return
    theirs = median_time(lambda: pp3d.MeshHeatMethodDistanceSolver(V, F).compute_distance(0), repeats)
    theirs_error = np.abs(pp3d.MeshHeatMethodDistanceSolver(V, F).compute_distance(0) - exact).mean()
    print(line + f"; potpourri3d {theirs:.4f} s (mean error {theirs_error:.2e}); ratio {ours / theirs:.2f}")


def default_run(repeats):
    scene = SOURCE / "tools" / "scenes" / "default.json"
    cli, python = [], []
    with tempfile.TemporaryDirectory() as folder:
        for k in range(repeats):
            start = time.perf_counter()
            subprocess.run([EXE, "run", str(scene), "--out", f"{folder}/cli{k}"], check=True, capture_output=True)
            cli.append(time.perf_counter() - start)
            start = time.perf_counter()
            simulation = physarum.Simulation(physarum.Scene(scene))
            simulation.step(simulation.planned_steps)
            simulation.write(f"{folder}/py{k}")
            python.append(time.perf_counter() - start)
    c, p = float(np.median(cli)), float(np.median(python))
    print(f"default scene: physarum run {c:.2f} s, Python {p:.2f} s; Python adds {100 * (p / c - 1):+.1f} %")


def fields_on_a_million(repeats):
    simulation = physarum.Simulation(dict(GRAY_SCOTT, max_circumradius=0.0021, steps=1), backend="reference")
    count = simulation._simulation.intrinsic_vertex_count
    seconds = median_time(lambda: simulation.fields(on="intrinsic"), repeats)
    print(f"fields(on='intrinsic') on {count} intrinsic vertices: {1000 * seconds:.2f} ms")


def per_call(repeats):
    scene = dict(GRAY_SCOTT, steps=1_000_000)
    n = 2000
    one_call = physarum.Simulation(scene, backend="reference")
    many_calls = physarum.Simulation(scene, backend="reference")
    single = median_time(lambda: one_call.step(n), repeats) / n
    looped = median_time(lambda: [many_calls.step(1) for _ in range(n)], repeats) / n
    print(f"step(1) in a loop: {1e6 * looped:.1f} us per call, step({n}): {1e6 * single:.1f} us per step; "
          f"{1e6 * (looped - single):.2f} us per call above the step")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="one repeat each, no million-vertex surface")
    args = parser.parse_args()
    repeats = 1 if args.quick else 5
    geodesic(repeats)
    per_call(repeats)
    default_run(1 if args.quick else 3)
    if not args.quick:
        fields_on_a_million(repeats)


if __name__ == "__main__":
    sys.exit(main())
