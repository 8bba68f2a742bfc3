"""Bad input from Python is a Python exception naming the argument, never a crash: each refusal runs
in a fresh interpreter (a crash there would show as a signal, not as the expected exception)."""
import json
import signal
import subprocess
import sys
import textwrap
import time

import pytest

from conftest import AGENT_SCENE

REFUSALS = {
    # what is wrong: (the call, the exception, words its message must hold)
    "V of the wrong shape": ("physarum.Surface(np.zeros((4, 2)), np.zeros((1, 3), np.int64))", "ValueError", "V: expected shape (n, 3)"),
    "F of floats": ("physarum.Surface(np.eye(3), np.zeros((1, 3)))", "ValueError", "F: expected integer indices"),
    "F out of range": ("physarum.Surface(np.eye(3), np.array([[0, 1, 5]]))", "ValueError", "F: indices must lie in 0..2"),
    "NaN in V": ("physarum.Surface(np.array([[0, 0, 0], [1, 0, 0], [0, np.nan, 0]]), np.array([[0, 1, 2]]))",
                 "ValueError", "V: value at (2, 1) is not finite"),
    "a non-manifold mesh": ("physarum.Surface(np.array([[0,0,0],[1,0,0],[0,1,0],[0,0,1],[0,-1,0.]]), "
                            "np.array([[0,1,2],[0,1,3],[0,1,4]]))", "ValueError", "V, F: non-manifold edge"),
    "an unknown scene key": ("physarum.Scene(BASE, sensor_angel=20).check()",
                             "ValueError", "sensor_angel"),
    "a bad scene value": ("physarum.Simulation(dict(BASE, agents=-5))", "ValueError", "agents"),
    "NaN in a map": ("physarum.Scene(BASE, sensor_angle=np.full(2562, np.nan))",
                     "ValueError", "sensor_angle: value at 0 is not finite"),
    "a map of strings": ("physarum.Scene(BASE, sensor_angle=np.array(['a']))",
                         "ValueError", "sensor_angle: expected real numbers"),
    "a map of the wrong length": ("physarum.Simulation(dict(BASE, sensor_angle=np.full(7, 20.0)))", "ValueError", "7 vertices"),
    "a direction map of the wrong shape": ("physarum.Scene(BASE, maps={'d': np.zeros((5, 2))})", "ValueError", "maps.d: expected shape (n, 3)"),
    "an unknown backend": ("physarum.Simulation(BASE, backend='cuda')",
                           "ValueError", "backend: 'cuda'"),
    "a missing scene file": ("physarum.Scene('no/such/scene.json')", "ValueError", "no scene file no/such/scene.json"),
    "a missing mesh file": ("physarum.read_mesh('no/such/mesh.obj')", "ValueError", "no/such/mesh.obj"),
    "geodesic sources out of range": ("physarum.geodesic_distance(physarum.Surface.from_shape('sphere'), [99999])",
                                      "ValueError", "sources: indices must lie in 0..2561"),
    "an unknown method": ("physarum.geodesic_distance(physarum.Surface.from_shape('sphere'), [0], method='exact')",
                          "ValueError", "method: 'exact'"),
    "restore of not a state": ("physarum.Simulation(BASE).restore_state(b'x')",
                               "ValueError", "not a physarum checkpoint"),
    "restore of a string": ("physarum.Simulation(BASE).restore_state('x')",
                            "ValueError", "state: expected bytes"),
    "steps of a float": ("physarum.Simulation(BASE).step(1.5)",
                         "ValueError", "n: expected an integer"),
}


def run_python(code: str, **kwargs):
    program = f"import json, numpy as np, physarum\nBASE = json.loads({json.dumps(json.dumps(AGENT_SCENE))})\n" + code
    return subprocess.run([sys.executable, "-c", program], capture_output=True, text=True, **kwargs)


@pytest.mark.parametrize("what", sorted(REFUSALS))
def test_bad_input_is_a_python_exception_naming_the_argument(what):
    call, exception, words = REFUSALS[what]
    result = run_python(textwrap.dedent(f"""
        try:
            {call}
        except {exception} as error:
            print("REFUSED:", error)
        else:
            print("ACCEPTED")
    """))
    assert result.returncode == 0, f"the interpreter died ({result.returncode}): {result.stderr[-2000:]}"
    assert "REFUSED:" in result.stdout, result.stdout + result.stderr
    assert words in result.stdout, result.stdout


def test_ctrl_c_stops_a_long_step_between_two_steps():
    program = textwrap.dedent("""
        import sys
        sim = physarum.Simulation(dict(BASE, max_circumradius=0.03, agents=20000, steps=100000), backend='reference')
        print('READY', flush=True)
        try:
            sim.step(100000)
        except KeyboardInterrupt:
            taken = sim.steps_taken
            sim.step(1)  # the state is consistent: it steps on
            print('INTERRUPTED', taken, sim.steps_taken, flush=True)
    """)
    process = subprocess.Popen([sys.executable, "-c", f"import json, numpy as np, physarum\nBASE = json.loads({json.dumps(json.dumps(AGENT_SCENE))})\n" + program],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert process.stdout.readline().strip() == "READY"
    time.sleep(1.0)
    process.send_signal(signal.SIGINT)
    out, err = process.communicate(timeout=60)
    assert process.returncode == 0, err
    words = out.split()
    assert words[0] == "INTERRUPTED" and 0 < int(words[1]) < 100000 and int(words[2]) == int(words[1]) + 1, out
