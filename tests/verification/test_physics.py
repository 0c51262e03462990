"""Physical checks of example 1 that do not lean on the other solver."""

import numpy as np
import pytest
from conftest import SQUARE, run_solver
import piezocontact

TRACTION_TOTAL = np.array([0.0, -10.0])  # (0, -10) N/m^2 on the top edge, length 1


def run_in_process(tmp_path, *overrides, engine="cpp"):
    """Example 1 at n = 8, 4 steps, through piezocontact.solve."""
    return piezocontact.solve(SQUARE, tmp_path, engine=engine, progress=False,
                              overrides=["mesh.n=8", "time.steps=4", "output.xdmf=false",
                                         "output.nodal=none", *overrides])


def test_global_equilibrium(small_runs, solver):
    """Applied traction + contact force + reaction of the clamp = 0, the
    reaction taken from the unconstrained residual, the contact force from
    its own functional, the traction from the data: a wrong facet tag, a
    silently empty ds or a sign error in either term breaks it."""
    for step in small_runs[solver][0]["steps"]:
        total = TRACTION_TOTAL + np.array(step["contact_force"]) + \
            np.array(step["reactions"]["left"])
        assert np.linalg.norm(total) < 1e-10 * np.linalg.norm(TRACTION_TOTAL), step["t"]
        assert step["contact_force"][1] > 1.0  # the foundation carries a real share


def test_zero_load_gives_zero_solution(tmp_path, solver):
    summary, _ = run_solver(solver, tmp_path, ["mesh.n=4", "time.steps=2",
                                               "boundaries.top.traction=[0,0]"])
    for step in summary["steps"]:
        assert step["newton_iterations"] == 1  # one update, zero: the zero predictor is exact
        for p in step["probes"]:
            assert p["u"] == [0.0, 0.0] and p["phi"] == 0.0
        assert step["contact_force"] == [0.0, 0.0]


def test_without_contact_the_problem_is_linear(tmp_path):
    """c_p = 0: the linear viscoelastic-piezoelectric problem. Every step takes
    one Newton iteration and the response scales with the load."""
    a = run_in_process(tmp_path / "a", "contact.c_p=0")
    b = run_in_process(tmp_path / "b", "contact.c_p=0", "boundaries.top.traction=[0,-20]")
    for sa, sb in zip(a["steps"], b["steps"]):
        assert sa["newton_iterations"] == 1
        assert sa["contact_force"] == [0.0, 0.0]
        for pa, pb in zip(sa["probes"], sb["probes"]):
            assert np.allclose(pb["u"], 2 * np.array(pa["u"]), rtol=1e-10, atol=0)
            assert pb["phi"] == pytest.approx(2 * pa["phi"], rel=1e-10)


def test_stiffer_foundation_penetrates_less(tmp_path):
    """The largest penetration u.nu - g on Gamma_C decreases as c_p grows,
    like 1/c_p once the foundation is much stiffer than the body."""
    pen = {}
    for c_p in (0.0, 1e10, 1e11, 1e12, 1e13, 1e14):
        pen[c_p] = run_in_process(tmp_path / f"{c_p:g}", f"contact.c_p={c_p}")["steps"][-1][
            "max_penetration"]
    values = [pen[c] for c in sorted(pen)]
    assert all(b < a for a, b in zip(values, values[1:])), pen
    assert pen[1e14] / pen[1e13] == pytest.approx(0.1, rel=0.05)
