"""The module on the library (api/): setting a layer, a growth run's sheet, the engine's lines through
logging, and the tools run in-process with the engine's own messages."""
import json
import logging

import numpy as np
import pytest

import physarum
from conftest import AGENT_SCENE, GRAY_SCOTT_SCENE, SOURCE
from read_exports import parse_ply


def test_set_field_round_trips_and_the_trivial_state_stays_put():
    simulation = physarum.Simulation(GRAY_SCOTT_SCENE, backend="reference", steps=5)
    n = len(simulation.fields()["u"])
    # u = 1, v = 0 is a fixed point of Gray-Scott: -u v^2 + F (1 - u) = 0 and u v^2 - (F + k) v = 0,
    # and a constant has no Laplacian; the spots and noise of the initial state are overwritten.
    simulation.set_field("u", np.ones(n))
    simulation.set_field("v", np.zeros(n))
    fields = simulation.fields()
    assert np.array_equal(fields["u"], np.ones(n)) and np.array_equal(fields["v"], np.zeros(n))
    simulation.step(5)
    fields = simulation.fields(on="intrinsic")
    assert np.allclose(fields["u"], 1.0, atol=1e-12, rtol=0) and np.allclose(fields["v"], 0.0, atol=1e-12, rtol=0)


def test_set_field_on_input_vertices_is_what_fields_reads_back():
    simulation = physarum.Simulation(GRAY_SCOTT_SCENE, backend="reference", steps=5)
    V, _ = physarum.read_mesh("shape:torus")
    ramp = V[:, 0] - V[:, 0].min()
    simulation.set_field("v", ramp)
    # Each input vertex is an intrinsic vertex: its value comes back as given.
    assert np.array_equal(simulation.fields()["v"], ramp)


def test_set_field_refuses_an_unknown_layer_and_a_wrong_size_naming_what_it_expects():
    simulation = physarum.Simulation(AGENT_SCENE, backend="reference", steps=5)
    n = len(simulation.fields()["pheromone"])
    with pytest.raises(ValueError, match=r"no layer 'u' \(the layers: pheromone\)"):
        simulation.set_field("u", np.zeros(n))
    with pytest.raises(ValueError, match=rf"{n + 1} values for 'pheromone', expected {n} \(one per input vertex\)"):
        simulation.set_field("pheromone", np.zeros(n + 1))
    with pytest.raises(ValueError, match="on:"):
        simulation.set_field("pheromone", np.zeros(n), on="faces")


def test_a_growth_runs_sheet_is_the_mesh_it_writes(tmp_path):
    scene = json.loads((SOURCE / "tools/scenes/growth_cap.json").read_text())
    scene["mesh"] = "shape:disk-8"
    scene["schedule"]["growth_steps"] = 2
    simulation = physarum.Simulation(scene, backend="reference")
    V0, F0, _ = simulation.sheet()
    disk, triangles = physarum.read_mesh("shape:disk-8")
    assert V0.shape == disk.shape and np.array_equal(F0, triangles)
    simulation.step(simulation.planned_steps)
    V, F, fields = simulation.sheet()
    simulation.write(tmp_path / "run")
    written, faces = parse_ply(tmp_path / "run" / "morphogens.ply")
    assert np.allclose(np.column_stack([written["x"], written["y"], written["z"]]), V, rtol=0, atol=1e-6)  # float32 in the file
    assert np.array_equal(np.asarray(faces), F)
    assert set(fields) == set(simulation.layer_names) | {"area_growth"}
    for name, values in fields.items():  # the file holds them as float32
        assert np.allclose(written[name], values, rtol=1e-6, atol=1e-9), name
    assert fields["area_growth"].max() > 1.0  # the cap grew


def test_sheet_of_another_model_says_it_has_none():
    simulation = physarum.Simulation(AGENT_SCENE, backend="reference", steps=5)
    with pytest.raises(ValueError, match="only a growth scene"):
        simulation.sheet()


def test_the_engines_lines_go_through_logging_not_stdout(tmp_path, caplog, capfd):
    caplog.set_level(logging.INFO, logger="physarum")
    simulation = physarum.Simulation(AGENT_SCENE, backend="reference", steps=5)
    simulation.step(5)
    simulation.write(tmp_path / "run")
    lines = [r.getMessage() for r in caplog.records if r.name == "physarum"]
    assert any("has no texture coordinates" in line for line in lines), lines  # shape:sphere has no UVs
    assert any(line.startswith("physarum run: 5 steps") and "wrote" in line for line in lines), lines
    out, err = capfd.readouterr()
    assert "physarum run:" not in out and "physarum run:" not in err


def test_set_applies_from_the_next_step_and_refuses_what_needs_a_new_run():
    changed = physarum.Simulation(AGENT_SCENE, backend="reference", steps=30)
    plain = physarum.Simulation(AGENT_SCENE, backend="reference", steps=30)
    changed.step(10)
    plain.step(10)
    assert changed.set("sensor_angle", np.float64(22.5)) == 10  # the scene's own value: nothing may change
    changed.step(10)
    plain.step(10)
    assert np.array_equal(changed.fields()["pheromone"], plain.fields()["pheromone"])
    changed.set("sensor_angle", 60.0)
    changed.step(10)
    plain.step(10)
    assert not np.array_equal(changed.fields()["pheromone"], plain.fields()["pheromone"])
    before = changed.fields()["pheromone"]
    with pytest.raises(ValueError, match="agents: needs a new run"):
        changed.set("agents", 10)
    with pytest.raises(ValueError, match="sensor_angle: expected a number"):
        changed.set("sensor_angle", "wide")
    assert np.array_equal(changed.fields()["pheromone"], before)
