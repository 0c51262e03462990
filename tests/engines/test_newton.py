"""Newton's method on the coupled system, field by field."""

import math

import ufl
from conftest import SQUARE
import piezocontact

RTOL = 1e-10  # the default solver.newton.rtol


def test_fixed_contact_set_converges_in_one_iteration(small_runs, solver):
    """With p piecewise linear and the contact set of the predictor right,
    the problem is linear and one Newton step reaches round-off in both
    fields; only the first step, where contact starts, needs more."""
    summary = small_runs[solver][0]
    for step in summary["steps"][1:]:
        assert step["newton_iterations"] == 1
        for field in ("u", "phi"):
            assert step["relative_residuals"][field] < 1e-13


def test_both_fields_are_tested(small_runs, solver):
    """The phi residual is measured on its own: in SI units it is ~1e-25 C/m
    at convergence, invisible inside a joint norm dominated by u (N/m)."""
    for step in small_runs[solver][0]["steps"]:
        history = step["residual_history"]
        assert all(h["phi"] >= 0 for h in history)
        assert step["relative_residuals"]["phi"] <= RTOL
        assert step["relative_residuals"]["u"] <= RTOL
        # in SI units the converged phi residual is ~1e-25 C/m: a joint norm
        # with u's (N/m) could not tell it from a phi off by 1e-10 relative
        assert step["residual_norms"]["phi"] < 1e-20
    # the predictor leaves a phi residual that Newton has to remove
    second = small_runs[solver][0]["steps"][1]["residual_history"]
    assert second[0]["phi"] > 1e-6 and second[-1]["phi"] < 1e-13


def test_smooth_law_converges_quadratically(tmp_path):
    """With the C^1 law p(r) = c_p max(r,0)^2 the contact term is smooth near
    the solution and Newton converges quadratically. The order is estimated
    from three successive residuals, q = log(r_{k+1}/r_k) / log(r_k/r_{k-1}),
    which does not depend on the constant in r_{k+1} = C r_k^q."""
    summary = piezocontact.solve(
        SQUARE, tmp_path, contact_law=lambda r, c_p: c_p * ufl.max_value(r, 0) ** 2,
        overrides=["mesh.n=8", "time.steps=2", "contact.c_p=1e22", "output.xdmf=false",
                   "output.nodal=none"], progress=False)
    rates = []
    for step in summary["steps"]:
        # the first entry is undefined (null) while u is still zero
        r = [h["u"] for h in step["residual_history"] if h["u"] is not None]
        assert step["newton_iterations"] >= 4  # genuinely nonlinear
        for a, b, c in zip(r, r[1:], r[2:]):
            if a < 1e-2 and c > 1e-14:  # asymptotic range, above round-off
                rates.append(math.log(c / b) / math.log(b / a))
    assert rates, "no iterate in the asymptotic range"
    assert min(rates) > 1.8, rates
