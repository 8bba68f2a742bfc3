"""The tools from Python are the commands' own: a Surface counts as `physarum mesh` does, a heat-method
distance equals `physarum map`'s to the last bit, analyze and compare return what the commands write;
and known answers: the sphere's spectrum, a distance on the plane, harmonic interpolation of a ramp."""
import json

import numpy as np
import pytest

import physarum
from conftest import GRAY_SCOTT_SCENE, SOURCE, parse_ply, physarum_command, write_scene


def test_a_surface_has_the_counts_physarum_mesh_reports():
    surface = physarum.Surface.from_shape("sphere", max_circumradius=0.02)
    report = physarum_command("mesh", "shape:sphere", "--max-circumradius", "0.02").stdout
    intrinsic = report.split("intrinsic")[1].split()
    assert surface.input_vertex_count == 2562 and surface.input_face_count == 5120
    assert surface.vertex_count == int(intrinsic[1]) and surface.face_count == int(intrinsic[3])
    assert surface.vertex_count > surface.input_vertex_count  # refined
    V, F = surface.full_mesh()
    assert V.shape == (surface.vertex_count, 3) and F.shape == (surface.face_count, 3) and F.dtype == np.int64
    # Every intrinsic vertex lies on the input surface: on the unit sphere's chords, within its sagitta.
    radius = np.linalg.norm(surface.intrinsic_positions, axis=1)
    assert radius.max() <= 1.0 + 1e-9 and radius.min() > 0.99
    # Input vertex i is intrinsic vertex input_to_intrinsic[i], at the same place.
    Vin, _ = surface.input_mesh()
    np.testing.assert_allclose(V[surface.input_to_intrinsic], Vin, atol=1e-12)


def test_the_spheres_spectrum_is_l_times_l_plus_one():
    surface = physarum.Surface.from_shape("sphere")  # the unit sphere (area 12.55, 4 pi to 0.1 %)
    values = surface.eigenvalues(9)
    np.testing.assert_allclose(values[0], 0.0, atol=1e-8)
    np.testing.assert_allclose(values[1:4], 2.0, rtol=0.01)
    np.testing.assert_allclose(values[4:9], 6.0, rtol=0.01)


def test_a_surface_from_numpy_arrays_is_the_surface_from_the_file(tmp_path):
    V, F = physarum.read_mesh("shape:torus")
    from_arrays = physarum.Surface(V, F, max_circumradius=0.05)
    from_shape = physarum.Surface.from_shape("torus", max_circumradius=0.05)
    assert (from_arrays.vertex_count, from_arrays.face_count) == (from_shape.vertex_count, from_shape.face_count)
    np.testing.assert_array_equal(from_arrays.full_mesh()[1], from_shape.full_mesh()[1])
    np.testing.assert_array_equal(from_arrays.full_mesh()[0], from_shape.full_mesh()[0])


def test_a_heat_distance_from_python_is_physarum_maps_to_the_last_bit(tmp_path):
    surface = physarum.Surface.from_shape("sphere", max_circumradius=0.03)
    V, _ = surface.input_mesh()
    python = physarum.geodesic_distance(surface, [7, 100])
    out = tmp_path / "distance.ply"
    points = json.dumps({"points": V[[7, 100]].tolist()})
    physarum_command("map", "shape:sphere", "--max-circumradius", "0.03", "--kind", "geodesic_distance",
                     "--arg", f"from={points}", "--arg", "method=heat", "--name", "d", "--out", out, "--no-preview")
    vertices, _ = parse_ply(out)
    command = np.asarray(vertices["d"], dtype=np.float64)
    # The PLY holds the map as written: compare in its precision, every value, no tolerance.
    np.testing.assert_array_equal(python.astype(vertices["d"].dtype), command.astype(vertices["d"].dtype))
    # And the known answer: the great-circle distance on the unit sphere, within the heat method's error.
    exact = np.minimum(*(np.arccos(np.clip(V @ V[i] / np.linalg.norm(V, axis=1) / np.linalg.norm(V[i]), -1, 1))
                         for i in (7, 100)))
    assert np.abs(python - exact).max() < 0.05
    fmm = physarum.geodesic_distance(surface, V[[7, 100]], method="fmm")
    assert np.abs(fmm - exact).max() < 0.05


def test_laplace_interpolation_between_two_ends_of_a_square_is_the_linear_ramp():
    surface = physarum.Surface.from_shape("square")
    V, _ = surface.input_mesh()
    left, right = V[:, 0] <= V[:, 0].min() + 1e-9, V[:, 0] >= V[:, 0].max() - 1e-9
    ramp = physarum.laplace_interpolation(surface, [(left, 0.0), (right, 1.0)])
    expected = (V[:, 0] - V[:, 0].min()) / np.ptp(V[:, 0])
    np.testing.assert_allclose(ramp, expected, atol=1e-6)
    slope = physarum.gradient(surface, ramp)
    np.testing.assert_allclose(slope[:, 0], 1.0 / np.ptp(V[:, 0]), rtol=1e-5)


def test_diffusion_conserves_the_integral():
    surface = physarum.Surface.from_shape("sphere")
    V, _ = surface.input_mesh()
    spike = (V[:, 2] > 0.9).astype(float)
    blurred = physarum.diffuse(surface, spike, time=0.05, on="intrinsic")
    mass = surface.vertex_mass
    before = physarum.diffuse(surface, spike, time=1e-12, on="intrinsic")
    assert np.dot(mass, blurred) == pytest.approx(np.dot(mass, before), rel=1e-9)
    assert blurred.max() < before.max()


def test_analyze_and_compare_return_what_the_commands_write(tmp_path):
    scene_file = write_scene(tmp_path, dict(GRAY_SCOTT_SCENE, steps=2000))
    simulation = physarum.Simulation(physarum.Scene(scene_file), backend="reference")
    simulation.step(2000)
    run = simulation.write(tmp_path / "run")
    physarum_command("analyze", run, "--out", tmp_path / "analysis")
    command = json.loads((tmp_path / "analysis" / "analysis.json").read_text())
    assert physarum.analyze(run) == command
    assert command["spot_count"] > 0  # Gray-Scott's spots are there to measure
    # A Simulation is analysed in memory: the same field on the same full-resolution mesh, which the
    # file holds in float32 (positions and values). The threshold agrees to float32's precision; a
    # vertex within that of it can fall on the other side, moving a spot's centre by a fraction of
    # an edge, so the spacing agrees to about a percent, the counts exactly.
    memory = physarum.analyze(simulation)
    assert (memory["spot_count"], memory["stripe_count"]) == (command["spot_count"], command["stripe_count"])
    assert memory["threshold"] == pytest.approx(command["threshold"], rel=1e-6)
    assert memory["spacing"]["mean"] == pytest.approx(command["spacing"]["mean"], rel=0.01)


def test_devices_lists_what_physarum_devices_lists():
    listed = physarum_command("devices", check=False)
    devices = physarum.devices()
    assert [d["description"] for d in devices] == [line for line in listed.stdout.splitlines() if line]


def test_compare_returns_the_commands_verdict(tmp_path):
    scene = SOURCE / "tools" / "scenes" / "compare" / "gray_scott_square.json"
    arms = ["backend=reference", "backend=reference,parameters.F=0.036"]
    physarum_command("compare", scene, "--max-seeds", 4, "--arm", arms[0], "--arm", arms[1], "--out", tmp_path / "cmd",
                     check=False)
    command = json.loads((tmp_path / "cmd" / "verdict.json").read_text())
    python = physarum.compare(physarum.Scene(scene), arms=arms, seeds=4)
    for verdict in (command, python):
        del verdict["run"]["seconds"]  # the only entry that depends on the machine's load
    assert python == command
    assert python["seeds"] == {arms[0]: 4, arms[1]: 4}


def test_the_type_stubs_are_the_modules_own(tmp_path):
    # tools/python/physarum/_physarum.pyi is committed for editors; it must be what stubgen makes of the
    # module as built (regenerate: python -m nanobind.stubgen -m physarum._physarum -o tools/python/physarum/_physarum.pyi).
    import subprocess
    import sys
    out = tmp_path / "_physarum.pyi"
    subprocess.run([sys.executable, "-m", "nanobind.stubgen", "-q", "-m", "physarum._physarum", "-o", str(out)], check=True)
    assert out.read_text() == (SOURCE / "tools" / "python" / "physarum" / "_physarum.pyi").read_text()


def test_colormap_is_the_commands_map(tmp_path):
    exemplar = SOURCE / "tools" / "colormaps" / "exemplar_lichen.png"
    physarum_command("colormap", exemplar, "--out", tmp_path / "command.json")
    python = physarum.colormap(exemplar, tmp_path / "python.json")
    assert python == json.loads((tmp_path / "command.json").read_text())
    assert (tmp_path / "python.png").exists()  # its strip picture beside it


def _nine_spots() -> dict:
    """A JSON sketch: a 3 x 3 lattice of round spots of area 0.0052 (window units), 0.17 apart."""
    radius = (0.0052 / np.pi) ** 0.5
    marks = [{"ellipse": {"center": [0.5 + 0.17 * i, 0.5 + 0.17 * j], "radii": [radius, radius], "angle": 0.0}}
             for i in (-1, 0, 1) for j in (-1, 0, 1)]
    return {"window": [1.0, 1.0], "marks": marks}


def test_sketch_is_the_commands_sketch(tmp_path):
    # One region on a 0.25 m^2 patch (about 3 s a run): the command from a file, Python from the dict.
    sketch_file = tmp_path / "nine.json"
    sketch_file.write_text(json.dumps(_nine_spots()))
    physarum_command("sketch", sketch_file, "--regions", 1, "--area", 0.25, "--out", tmp_path / "cmd")
    report = physarum.sketch(_nine_spots(), tmp_path / "py", regions=1, area=0.25)
    assert report == json.loads((tmp_path / "cmd" / "report.json").read_text())
    for name in ("scene.json", "sketch_maps.ply", "morphogens.ply"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cmd" / name).read_bytes(), name
    region = report["regions"][0]
    assert region["sketched"]["area"] == pytest.approx(0.0052, rel=1e-9)
    assert region["verdict"]["area"] == "pass"  # the texture has the sketched spot size


def test_a_refused_sketch_is_a_value_error_and_runs_nothing(tmp_path):
    tiny = _nine_spots()
    for mark in tiny["marks"]:
        mark["ellipse"]["radii"] = [1e-4, 1e-4]
    with pytest.raises(ValueError, match="sketch"):
        physarum.sketch(tiny, tmp_path / "out", regions=1, area=0.25)
    assert not (tmp_path / "out" / "morphogens.ply").exists()
