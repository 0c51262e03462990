"""Newton failures are retried with a smaller step or stop cleanly, keeping
every step computed before (interruptions: test_interrupts.py)."""

import json

import pytest
from conftest import ROOT, run_solver, xdmf_times

SMALL = ["output.nodal=none"]


@pytest.fixture
def variant(tmp_path_factory):
    """contactor_in_contact.json on a fixed mesh (the contactor at size 0.2,
    237 cells, tests/data): the iteration counts below belong to a mesh, and
    each gmsh release meshes the geometry a little differently."""
    cfg = json.loads((ROOT / "demos" / "contactor_in_contact.json").read_text())
    cfg["mesh"] = {"type": "xdmf", "path": str(ROOT / "tests" / "data" / "contactor_0.2.xdmf")}
    path = tmp_path_factory.mktemp("variant") / "contactor_0.2.json"
    path.write_text(json.dumps(cfg))
    return path


@pytest.mark.parametrize("solver", ["cpp", "cpp-jit"])
def test_step_cut_rescues_newton(solver, tmp_path, variant):
    """At most 3 Newton iterations: the first steps need 4 at k = 1 and are
    retried with k halved until they converge; the run then completes."""
    s, _ = run_solver(solver, tmp_path, SMALL + ["time.steps=10",
                                                 "solver.newton.max_iterations=3"],
                      config=variant)
    assert s["status"] == "completed"
    assert s["steps"][-1]["t"] == pytest.approx(10.0, rel=1e-14)
    cuts = [e for e in s["events"] if e["action"] == "halve k"]
    assert cuts and cuts[0]["t"] == 1.0 and cuts[0]["k"] == 1.0
    assert min(st["k"] for st in s["steps"]) < 1.0
    assert all(st["newton_iterations"] <= 3 for st in s["steps"])
    # the nominal times are all reached exactly
    times = [st["t"] for st in s["steps"]]
    assert all(any(abs(t - n) < 1e-12 for t in times) for n in range(1, 11))


@pytest.mark.parametrize("solver", ["cpp", "cpp-jit"])
def test_newton_failure_stops_cleanly_keeping_what_was_computed(solver, tmp_path, variant):
    """k = 0.25: step 1 converges in 3 iterations, step 2 needs 4; with no
    halving allowed the run stops there, naming time and residuals, and the
    first step stays on disk, readable."""
    s, proc = run_solver(solver, tmp_path, SMALL + [
        "time.steps=40", "solver.newton.max_iterations=3",
        "solver.newton.max_step_halvings=0"], config=variant, check=False)
    assert proc.returncode == 3
    message = proc.stderr.strip().splitlines()[-1]
    assert message.startswith("error: Newton did not converge at t = 0.5 (k = 0.25) in 3 "
                              "iterations: relative residuals u = ")
    assert message.endswith("; gave up after 0 halvings of the time step")
    assert s["status"] == "failed" and s["error"] in message
    assert len(s["steps"]) == 1 and s["events"][-1]["action"] == "stop"
    assert {name: len(t) for name, t in xdmf_times(tmp_path / "solution.xdmf").items()} == \
        {"u": 1, "phi": 1, "contact_pressure": 1, "D": 1, "stress_xx": 1, "stress_yy": 1,
         "stress_xy": 1}


