"""piezocontact.solve from a script: both engines honour the hooks that
change the physics with no rebuild (an extra residual term, a replaced
contact law) and agree to 1e-8; bad input raises the validator's message."""

import json

import numpy as np
import piezocontact
import pytest
import ufl
from conftest import SQUARE
from piezocontact import compare

TOL = 1e-8
SMALL = ["mesh.n=8", "time.steps=4", "output.xdmf=false", "output.nodal=none"]
# A cubic spring in the bulk, c |u|^2 u: about as stiff as the body at
# |u| ~ 1e-11 m. Its Jacobian changes with u, so LU reuse must see it.
CUBIC = 1e32


def cubic_spring(u, phi, w, psi, data):
    return CUBIC * ufl.inner(u, u) * ufl.inner(u, w) * ufl.dx


def square_law(r, c_p):
    """c_p max(r, 0)^2: with c_p = 1e22 N/m^4 the body sinks ~3e-11 m."""
    return c_p * ufl.max_value(r, 0) ** 2


def run(tmp_path, name, degree=1, **kwargs):
    return piezocontact.solve(SQUARE, tmp_path / name, progress=False,
                              overrides=SMALL + ["contact.c_p=1e22", f"elements.degree={degree}"],
                              **kwargs)


@pytest.fixture(scope="module", params=[1, 2], ids=["P1", "P2"])
def hooked(tmp_path_factory, request):
    """The hooks at degree 1 and at degree 2 (the hooks are UFL: any degree)"""
    base = tmp_path_factory.mktemp("hooks")
    hooks = dict(extra_residual=cubic_spring, contact_law=square_law)
    return {"plain": run(base, "plain", request.param),
            "cpp": run(base, "cpp", request.param, engine="cpp", **hooks),
            "reference": run(base, "reference", request.param, engine="reference", **hooks)}


def test_hooks_change_the_solution(hooked):
    """Not a no-op: the penalty law lets the body sink ~1e-11 m, where the
    linear law with c_p = 1e22 N/m^3 allows ~1e-21 m; the spring moves the
    probes by far more than the agreement tolerance."""
    plain, cpp = hooked["plain"]["steps"][-1], hooked["cpp"]["steps"][-1]
    assert abs(plain["max_penetration"]) < 1e-18 < 1e-12 < cpp["max_penetration"]
    assert compare.rel(cpp["probes"][0]["u"], plain["probes"][0]["u"]) > 1e-3


def test_both_engines_honour_the_hooks_alike(hooked):
    cpp, ref = hooked["cpp"], hooked["reference"]
    assert (cpp["solver"], ref["solver"]) == ("cpp-jit", "reference")
    for d in compare.probe_differences(cpp, ref):
        assert d["u"] < TOL and d["phi"] < TOL, d
    for a, b in zip(cpp["steps"], ref["steps"]):
        assert a["max_penetration"] == pytest.approx(b["max_penetration"], rel=TOL)
        assert np.allclose(a["contact_force"], b["contact_force"], rtol=TOL, atol=0)


def test_state_dependent_extra_term_keeps_newton_exact(hooked):
    """The spring's Jacobian joins the part of J compared for LU reuse, so
    J is rebuilt whenever it changes (every iterate but the first of step 1,
    which sits where the initial J was assembled): Newton converges."""
    steps = hooked["cpp"]["steps"]
    assert steps[0]["factorisations"] == steps[0]["newton_iterations"] - 1
    for step in steps:
        assert step["newton_iterations"] >= 2  # genuinely nonlinear
        if step is not steps[0]:
            assert step["factorisations"] == step["newton_iterations"]
        assert step["relative_residuals"]["u"] <= 1e-10


def test_config_as_a_dict(tmp_path):
    cfg = json.loads(SQUARE.read_text())
    summary = piezocontact.solve(cfg, tmp_path, overrides=SMALL, progress=False)
    again = piezocontact.solve(SQUARE, tmp_path / "file", overrides=SMALL, progress=False)
    assert summary["steps"][-1]["probes"] == again["steps"][-1]["probes"]


@pytest.mark.parametrize("engine", ["cpp", "reference"])
def test_bad_input_raises_the_validators_message(tmp_path, engine):
    with pytest.raises(piezocontact.ConfigError) as e:
        piezocontact.solve(SQUARE, tmp_path, engine=engine, overrides=["time.steps=0"])
    assert str(e.value).startswith(f"{SQUARE}: time.steps = 0")
    assert not (tmp_path / "summary.json").exists()


@pytest.mark.parametrize("engine", ["cpp", "reference"])
def test_data_as_ufl_expressions(tmp_path, engine):
    """A traction given as a UFL expression of x and t (the `data` hook,
    evaluated by the forms at their quadrature points) and the same
    traction as a config expression (interpolated at the P1 nodes: exact
    for it, linear in x) with its history: one answer, to round-off; and
    a datum the hook cannot take is refused naming it."""
    traction = ["-20*x", "-10*min(2*t, 1)"]
    by_config = piezocontact.solve(SQUARE, tmp_path / "config", progress=False, engine=engine,
                                   overrides=SMALL + [f"boundaries.top.traction={json.dumps(traction)}"])

    def top(x, t):
        return ufl.as_vector([-20 * x[0], -10 * ufl.min_value(2 * t, 1)])
    by_ufl = piezocontact.solve(SQUARE, tmp_path / "ufl", progress=False, engine=engine,
                                overrides=SMALL + ["boundaries.top.traction=[0, 0]"],
                                data={"boundaries.top.traction": top})
    for d in compare.probe_differences(by_config, by_ufl):
        assert d["u"] < 1e-12 and d["phi"] < 1e-12, d
    with pytest.raises(ValueError, match="data: 'boundaries.top.potential': not a datum"):
        piezocontact.solve(SQUARE, tmp_path / "bad", progress=False, engine=engine,
                           overrides=SMALL, data={"boundaries.top.potential": top})
