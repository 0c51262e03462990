"""A field that is exactly zero converges in every engine, to the exact answer.

A short-circuited block (every face at 0 V) on rollers under a ramped
uniaxial traction: the stress is uniform, the strain uniform and phi = 0
everywhere (div D = div(e eps) = 0 for a uniform strain). P1 holds the
linear displacement exactly, and backward Euler in time gives, per step,
(Av / k + Bv) eps_n = s_n + Av / k eps_{n-1}, s_n the uniaxial Voigt stress.
phi's discrete equations are then sums of coupling terms that cancel: phi is
zero to round-off, and a test of the increment or residual relative to phi's
own size can never pass (the reference engine once stopped with exit 3 here).
No contact boundary: the contact block is optional too."""

import json

import numpy as np
import pytest
from conftest import ENGINES, run_solver

P = 1e6  # Pa, the traction on the top face at the end of the ramp
RAMP, T, STEPS = 0.5, 1.0, 4

SQUARE = {
    "mesh": {"type": "unit_square", "n": 4},
    "material": {"preset": "ZnO-paper", "poling": [0, 1]},
    "boundaries": {
        "left": {"displacement": [0.0, None], "potential": 0.0},
        "bottom": {"displacement": [None, 0.0], "potential": 0.0},
        "right": {"potential": 0.0},
        "top": {"potential": 0.0,
                "traction": {"value": [0.0, -P], "history": {"ramp": RAMP}}}},
    "time": {"T": T, "steps": STEPS},
    "probes": [[1.0, 1.0], [0.5, 0.5]],
    "output": {"xdmf": False},
}

BOX = {
    "mesh": {"type": "box", "n": [2, 2, 2], "size": [1.0, 1.0, 1.0]},
    "material": {"preset": "PZT-5H", "poling": [0, 1, 0]},
    "boundaries": {
        "left": {"displacement": [0.0, None, None], "potential": 0.0},
        "bottom": {"displacement": [None, 0.0, None], "potential": 0.0},
        "back": {"displacement": [None, None, 0.0], "potential": 0.0},
        "right": {"potential": 0.0},
        "front": {"potential": 0.0},
        "top": {"potential": 0.0,
                "traction": {"value": [0.0, -P, 0.0], "history": {"ramp": RAMP}}}},
    "time": {"T": T, "steps": STEPS},
    "probes": [[1.0, 1.0, 1.0], [0.5, 0.5, 0.5]],
    "output": {"xdmf": False},
}


def exact_strains(material, d):
    """Voigt strain at each step from the backward-Euler ODE of the
    uniform state (Bv, Av of the summary: the tensors solved with)."""
    B, A = np.array(material["elastic"]), np.array(material["viscosity"])
    k = T / STEPS
    eps, out = np.zeros(len(B)), []
    for n in range(1, STEPS + 1):
        s = np.zeros(len(B))
        s[1] = -P * min(n * k / RAMP, 1.0)  # sigma_yy; every other component free
        eps = np.linalg.solve(A / k + B, s + A @ eps / k)
        out.append(eps)
    return out


@pytest.mark.parametrize("case", ["2d", "3d"])
@pytest.mark.parametrize("engine", ENGINES)
def test_short_circuit_on_rollers(tmp_path, case, engine):
    cfg = SQUARE if case == "2d" else BOX
    d = 2 if case == "2d" else 3
    config = tmp_path / "short.json"
    config.write_text(json.dumps(cfg))
    summary, _ = run_solver(engine, tmp_path / "out", config=config)
    assert summary["status"] == "completed"
    material = summary["config"]["material"]
    e = np.abs(np.array(material["piezoelectric"])).max()
    beta = np.array(material["permittivity"]).diagonal().min()
    for step, eps in zip(summary["steps"], exact_strains(material, d)):
        assert step["newton_iterations"] >= 1
        # the potential a strain of this size would drive across the body,
        # were it not short-circuited
        phi_scale = e * np.abs(eps).max() / beta
        for probe in step["probes"]:
            x = np.array(probe["point"])
            exact = eps[:d] * x  # u_i = eps_ii x_i: no shear under uniaxial stress
            assert np.allclose(probe["u"], exact, rtol=0, atol=1e-10 * np.abs(exact).max())
            assert abs(probe["phi"]) <= 1e-12 * phi_scale
        # the bottom roller carries the traction (area 1), the left one nothing
        traction = P * min(step["t"] / RAMP, 1.0)
        assert step["reactions"]["bottom"][1] == pytest.approx(traction, rel=1e-10)
        assert abs(step["reactions"]["left"][0]) <= 1e-10 * traction
