"""A run from Python is `physarum run`: the same files byte for byte, fields equal to the files'
values, states saved and restored bit for bit, numpy maps equal to PLY maps."""
import filecmp
import json

import numpy as np
import pytest

import physarum
from conftest import AGENT_SCENE, BACKENDS, GRAY_SCOTT_SCENE, parse_ply, physarum_command, ply_property, write_scene


def run_both(tmp_path, scene, backend, steps):
    """The scene through `physarum run` and through Simulation + write; returns both folders."""
    scene_file = write_scene(tmp_path, scene)
    command_out, python_out = tmp_path / "command", tmp_path / "python"
    physarum_command("run", scene_file, "--backend", backend, "--steps", steps, "--out", command_out)
    simulation = physarum.Simulation(physarum.Scene(scene_file), backend=backend, steps=steps)
    assert simulation.step(steps) == steps
    simulation.write(python_out)
    return command_out, python_out, simulation


@pytest.mark.parametrize("backend", BACKENDS)
def test_an_agent_run_from_python_writes_the_commands_bytes(tmp_path, backend):
    command_out, python_out, simulation = run_both(tmp_path, AGENT_SCENE, backend, 40)
    for name in ("pheromone.ply", "fields_full.ply", "stats.csv"):
        assert filecmp.cmp(command_out / name, python_out / name, shallow=False), name
    # fields() are the values the PLY files hold (stored as float32 there).
    fields = simulation.fields()
    assert list(fields) == ["pheromone"]
    np.testing.assert_array_equal(fields["pheromone"].astype(np.float32),
                                  ply_property(python_out / "pheromone.ply", "pheromone").astype(np.float32))
    intrinsic = simulation.fields(on="intrinsic")["pheromone"]
    assert intrinsic.shape == (simulation._simulation.intrinsic_vertex_count,)
    np.testing.assert_array_equal(intrinsic.astype(np.float32),
                                  ply_property(python_out / "fields_full.ply", "pheromone").astype(np.float32))
    run = json.loads((python_out / "run.json").read_text())
    assert run["steps"] == 40 and run["backend"] == simulation.backend


@pytest.mark.parametrize("backend", BACKENDS)
def test_a_reaction_diffusion_run_from_python_writes_the_commands_bytes(tmp_path, backend):
    command_out, python_out, simulation = run_both(tmp_path, GRAY_SCOTT_SCENE, backend, 150)
    for name in ("morphogens.ply", "fields_full.ply", "stats.csv"):
        assert filecmp.cmp(command_out / name, python_out / name, shallow=False), name
    fields = simulation.fields(on="full")
    assert set(fields) == {"u", "v"}
    for name, values in fields.items():
        np.testing.assert_array_equal(values.astype(np.float32),
                                      ply_property(python_out / "fields_full.ply", name).astype(np.float32))


def test_a_scene_from_a_dict_runs_as_the_same_scene_from_a_file(tmp_path):
    from_dict = physarum.Simulation(physarum.Scene(GRAY_SCOTT_SCENE), backend="reference")
    from_keywords = physarum.Simulation(physarum.Scene(**GRAY_SCOTT_SCENE), backend="reference")
    from_file = physarum.Simulation(physarum.Scene(write_scene(tmp_path, GRAY_SCOTT_SCENE)), backend="reference")
    for simulation in (from_dict, from_keywords, from_file):
        simulation.step(50)
    np.testing.assert_array_equal(from_dict.fields()["v"], from_file.fields()["v"])
    np.testing.assert_array_equal(from_keywords.fields()["v"], from_file.fields()["v"])
    assert from_file.fields()["v"].max() > 0.1  # the spots are there: not a trivially equal zero field


@pytest.mark.parametrize("backend", BACKENDS)
def test_save_and_restore_continue_bit_for_bit(backend):
    straight = physarum.Simulation(AGENT_SCENE, backend=backend)
    straight.step(40)
    interrupted = physarum.Simulation(AGENT_SCENE, backend=backend)
    interrupted.step(15)
    state = interrupted.save_state()
    interrupted.step(10)  # wander off, then come back
    interrupted.restore_state(state)
    assert interrupted.steps_taken == 15
    interrupted.step(25)
    np.testing.assert_array_equal(straight.fields(on="intrinsic")["pheromone"],
                                  interrupted.fields(on="intrinsic")["pheromone"])
    assert straight.time == interrupted.time
    # A fresh simulation of the same scene takes the state too.
    fresh = physarum.Simulation(AGENT_SCENE, backend=backend)
    fresh.restore_state(state)
    fresh.step(25)
    np.testing.assert_array_equal(straight.fields()["pheromone"], fresh.fields()["pheromone"])
    np.testing.assert_array_equal(straight.stats_table()["mean"], fresh.stats_table()["mean"])


def test_a_state_of_another_scene_is_refused_and_changes_nothing():
    other = dict(AGENT_SCENE, agents=2000)
    state = physarum.Simulation(other, backend="reference").save_state()
    simulation = physarum.Simulation(AGENT_SCENE, backend="reference")
    simulation.step(5)
    before = simulation.fields()["pheromone"]
    with pytest.raises(ValueError, match="scene"):
        simulation.restore_state(state)
    with pytest.raises(ValueError, match="checkpoint"):
        simulation.restore_state(state[:100])
    np.testing.assert_array_equal(before, simulation.fields()["pheromone"])
    assert simulation.steps_taken == 5


def test_a_numpy_map_is_the_same_map_as_a_ply_property(tmp_path):
    # The sensor angle varies with height: once as a numpy array, once as the PLY a user would write.
    V, F = physarum.read_mesh("shape:sphere")
    angle = 15.0 + 15.0 * (V[:, 2] - V[:, 2].min()) / np.ptp(V[:, 2])
    from_numpy = physarum.Simulation(dict(AGENT_SCENE, sensor_angle=angle), backend="reference")
    ply = tmp_path / "angle.ply"
    physarum._arrays.write_ply(ply, V, F, vertex_values={"angle": angle})
    from_ply = physarum.Simulation(dict(AGENT_SCENE, maps={"angle": {"ply": str(ply), "property": "angle"}},
                                        sensor_angle="angle"), backend="reference")
    uniform = physarum.Simulation(AGENT_SCENE, backend="reference")
    for simulation in (from_numpy, from_ply, uniform):
        simulation.step(40)
    np.testing.assert_array_equal(from_numpy.fields()["pheromone"], from_ply.fields()["pheromone"])
    assert not np.array_equal(from_numpy.fields()["pheromone"], uniform.fields()["pheromone"])


def test_stepping_past_the_run_and_fields_on_nowhere_are_refused():
    simulation = physarum.Simulation(AGENT_SCENE, backend="reference", steps=10)
    with pytest.raises(ValueError, match="n: 11 steps asked, 10 left"):
        simulation.step(11)
    with pytest.raises(ValueError, match="on:"):
        simulation.fields(on="faces")
    calls = []
    simulation.step(10, progress=lambda done, total: calls.append((done, total)))
    assert calls[-1] == (10, 10)
    assert simulation.stats()["time"] == pytest.approx(0.1)


def test_a_growth_run_from_python_grows_the_sheet(tmp_path):
    scene = json.loads((physarum_source() / "tools/scenes/growth_cap.json").read_text())
    scene["mesh"] = "shape:disk-8"
    scene["schedule"]["growth_steps"] = 2
    simulation = physarum.Simulation(scene, backend="reference")
    vertices_before = simulation._simulation.intrinsic_vertex_count
    simulation.step(simulation.planned_steps)
    assert simulation.stopped is None
    out = simulation.write(tmp_path / "growth")
    run = json.loads((tmp_path / "growth" / "run.json").read_text())
    assert run["growth_steps"] == 2 and run["area_growth"] > 1.0
    vertices, _ = parse_ply(tmp_path / "growth" / "fields_full.ply")
    assert len(vertices) == len(next(iter(simulation.fields(on="intrinsic").values())))
    assert out == str(tmp_path / "growth")
    assert len(vertices) >= vertices_before  # refinement only adds vertices


def physarum_source():
    from conftest import SOURCE
    return SOURCE


def test_an_array_as_an_operand_inside_a_map_definition():
    V, _ = physarum.read_mesh("shape:sphere")
    height = (V[:, 2] - V[:, 2].min()) / np.ptp(V[:, 2])
    inside = physarum.Scene(dict(AGENT_SCENE, maps={"angle": {"map": height, "range": [15.0, 30.0]}},
                                 sensor_angle="angle"))
    direct = physarum.Scene(dict(AGENT_SCENE, sensor_angle=15.0 + 15.0 * height))
    runs = [physarum.Simulation(scene, backend="reference") for scene in (inside, direct)]
    for simulation in runs:
        simulation.step(20)
    # lo + (hi - lo) * value rounds as 15 + 15 * value does: the same run
    np.testing.assert_allclose(runs[0].fields()["pheromone"], runs[1].fields()["pheromone"], rtol=0, atol=0)
