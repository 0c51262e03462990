"""Load histories (issue 14): a prescribed datum is value * factor(t) with
a ramp, a sine or a table. Checked against exact discrete solutions (the
uniform block's creep recurrence under a varying load, Dirichlet values at
boundary probes), between engines, and against the constant case."""

import json
import math

import numpy as np
import pytest
from conftest import ROOT, run_solver
from test_devices import QUIET, SIGMA0, creep_recurrence, relative, step_values, uniform_block

SQUARE = ROOT / "demos" / "square.json"

HISTORIES = {
    "ramp": ({"ramp": 0.25}, lambda t: min(t / 0.25, 1.0)),
    "sine": ({"sine": {"frequency": 1.5, "phase": 0.3}},
             lambda t: math.sin(2 * math.pi * 1.5 * t + 0.3)),
    "table": ({"table": [[0.0, 0.0], [0.2, 1.0], [0.35, -0.5]]},
              lambda t: float(np.interp(t, [0.0, 0.2, 0.35], [0.0, 1.0, -0.5]))),
}


@pytest.mark.parametrize("kind", list(HISTORIES))
def test_a_varying_load_on_the_uniform_block_is_exact(tmp_path, kind):
    """The block of test_devices (PZT-5H poled along y, rollers) under a
    traction SIGMA0 * factor(t): u and phi at the probes equal the
    recurrence with the load of each step to 1e-10, while the run's contact
    pressures and loads differ from step to step (a sine and a table load
    reverse it: tension)."""
    history, factor = HISTORIES[kind]
    config = uniform_block(tmp_path, 1)
    cfg = json.loads(config.read_text())
    cfg["boundaries"]["top"]["traction"] = {"value": [0.0, -SIGMA0, 0.0], "history": history}
    config.write_text(json.dumps(cfg))
    s = run_solver("cpp", tmp_path / "out", QUIET, config=config)[0]
    exact = creep_recurrence(s["config"]["material"], 0.1, 5, 1, factor)
    for step, (eps, grad_phi) in zip(s["steps"], exact):
        for probe in step["probes"]:
            x = np.array(probe["point"])
            assert relative(probe["u"], eps * x) < 1e-10, (step["t"], probe)
            assert probe["phi"] == pytest.approx(grad_phi @ x, rel=1e-10, abs=1e-12 * abs(grad_phi).max())
    assert len({round(e[0][1], 20) for e in exact}) == 5  # the load did vary


def test_dirichlet_data_follow_their_history(tmp_path):
    """A potential on the left side of example 1 following a sine, and the
    bottom left corner pulled down along a ramp: the P1 field at a boundary
    node is the prescribed value at every step, to round-off."""
    cfg = json.loads(SQUARE.read_text())
    cfg["boundaries"]["left"] = {
        "displacement": {"value": [0.0, -1e-11], "history": {"ramp": 0.5}},
        "potential": {"value": 3.0, "history": {"sine": {"frequency": 1.0}}}}
    cfg["probes"] = [[0.0, 0.5], [1.0, 1.0]]
    config = tmp_path / "square.json"
    config.write_text(json.dumps(cfg))
    s = run_solver("cpp", tmp_path / "out", ["mesh.n=8", "time.steps=8"] + QUIET, config=config)[0]
    for step in s["steps"]:
        t = step["t"]
        left = step["probes"][0]
        assert left["phi"] == pytest.approx(3.0 * math.sin(2 * math.pi * t), abs=1e-14)
        assert left["u"][1] == pytest.approx(-1e-11 * min(t / 0.5, 1.0), abs=1e-25)


def test_a_constant_table_is_the_constant_load_and_engines_agree(tmp_path):
    """A table of factor 1 gives the constant run bit for bit; with a sine
    traction the three engines agree to 1e-8 at every step."""
    base = ["mesh.n=8", "time.steps=8"] + QUIET
    const = run_solver("cpp", tmp_path / "const", base)[0]
    table = run_solver("cpp", tmp_path / "table", base + [
        'boundaries.top.traction={"value": [0, -10], "history": {"table": [[0, 1], [1, 1]]}}'])[0]
    assert [s["probes"] for s in const["steps"]] == [s["probes"] for s in table["steps"]]
    sine = ['boundaries.top.traction={"value": [0, -10], "history": {"sine": {"frequency": 2}}}']
    runs = {e: run_solver(e, tmp_path / e, base + sine)[0] for e in ("cpp", "cpp-jit", "reference")}
    # each quantity relative to its largest over the run (the load passes
    # through zero: the reactions there are round-off)
    a = step_values(runs["cpp"])
    for other in ("cpp-jit", "reference"):
        b = step_values(runs[other])
        for q in range(4):
            scale = max(np.abs(x[q]).max() for x in a)
            for x, y in zip(a, b):
                assert np.abs(y[q] - x[q]).max() < 1e-8 * scale
    forces = [s["contact_force"][1] for s in runs["cpp"]["steps"]]
    assert max(forces) > 1.0 and min(forces) == 0.0  # pressed, then lifted off
