"""Manufactured solutions (demos/manufactured.json, forms/manufactured.py):
the exactly representable solution is reproduced to round-off, the observed
rates in h and in k are the expected ones, and the check has teeth: with
half the contact term in the forms the discrete solution misses the exact one."""

import json
import math
import shutil
import subprocess
import sys

import pytest
from conftest import ENV, MODULE, ROOT, run_solver

sys.path.insert(0, str(ROOT / "forms"))
from manufactured import PHI0, U0  # noqa: E402

MMS = ROOT / "demos" / "manufactured.json"
# The contact term of the residual (piezo_forms.contact_residual), and the
# same halved: the edit of the tests below
CONTACT_TERM = "    return contact_term(u, w, ufl.FacetNormal(x.ufl_domain()), dsq, data, law)\n"
HALF_CONTACT_TERM = CONTACT_TERM.replace("return ", "return 0.5 * ")


def mms_run(solver, out, space, time, n, steps, extra=(), np_=1):
    overrides = [f"manufactured.space={space}", f"manufactured.time={time}", f"mesh.n={n}",
                 f"time.steps={steps}", "output.xdmf=false", "output.nodal=none", *extra]
    return run_solver(solver, out, overrides, config=MMS, np_=np_)[0]


def relative_errors(summary):
    """Largest error over the steps, relative to the exact solution's scale
    (|u| ~ U0 m and |phi| ~ PHI0 V on the unit square)."""
    return {name: max(s["errors"][name] for s in summary["steps"])
            / (U0 if name.startswith("u") else PHI0)
            for name in ("u_L2", "u_H1", "phi_L2", "phi_H1")}


@pytest.mark.parametrize("np_", [1, 2])
@pytest.mark.parametrize("gap,in_contact", [(2e-11, True), (1.0, False)],
                         ids=["contact-active", "contact-inactive"])
def test_linear_solution_is_reproduced_to_round_off(solver, tmp_path, np_, gap, in_contact):
    """u, phi linear in space and time: P1 holds them and backward Euler
    integrates them exactly, so the discrete solution is the exact one up to
    round-off (measured ~1e-15 relative; 1e-12 leaves room for the condition
    of the coupled system, while any O(h) or O(k) error would be >= 1e-3).
    With g = 2e-11 m the contact zone opens at t = 0.4 and covers 30 %
    of Gamma_C at t = 1: the kink of max(r, 0) then sits inside facets, and
    the forms' contact quadrature integrates it the same way for the exact
    and the discrete field."""
    s = mms_run(solver, tmp_path, "linear", "linear", 8, 8, [f"contact.gap={gap}"], np_)
    assert max(relative_errors(s).values()) < 1e-12
    force = abs(s["steps"][-1]["contact_force"][1])
    if in_contact:
        assert force > 1.0 and s["steps"][-1]["max_penetration"] > 0  # N/m, m
        assert s["steps"][0]["contact_force"] == [0.0, 0.0]  # closes later
    else:
        assert force == 0.0


def rates(errors):
    """Observed rates between successive halvings."""
    return [math.log2(a / b) for a, b in zip(errors, errors[1:])]


def test_rate_in_h(solver, tmp_path):
    """Smooth in space, linear in time (no time error at all): P1 gives 2 in
    L2 and 1 in H1. Measured at 1/8 -> 1/16: 1.91-2.07 (L2) and 1.00 (H1);
    the thresholds are the issue's (0.1 below the asymptotic values)."""
    runs = [mms_run(solver, tmp_path / f"h{n}", "smooth", "linear", n, 4) for n in (4, 8, 16)]
    for name, expected in (("u_L2", 1.8), ("phi_L2", 1.8), ("u_H1", 0.9), ("phi_H1", 0.9)):
        r = rates([max(s["errors"][name] for s in run["steps"]) for run in runs])
        assert r[-1] > expected, (name, r)
        assert r[-1] < expected + 0.4, (name, r)  # not superconvergence by accident


def test_rate_in_k(solver, tmp_path):
    """Linear in space (no spatial error), sin(pi t/2) in time: backward
    Euler gives 1 in every norm. Measured at k = 1/8 -> 1/16: 0.98."""
    runs = [mms_run(solver, tmp_path / f"k{m}", "linear", "smooth", 4, m) for m in (4, 8, 16)]
    for name in ("u_L2", "u_H1", "phi_L2", "phi_H1"):
        r = rates([max(s["errors"][name] for s in run["steps"]) for run in runs])
        assert 0.9 < r[-1] < 1.2, (name, r)


def test_engines_agree_on_a_smooth_solution(tmp_path):
    """The same errors from the C++ loop and the reference engine, to the
    agreement tests' 1e-8."""
    c, p = (mms_run(s, tmp_path / s, "smooth", "smooth", 8, 8) for s in ("cpp", "reference"))
    for a, b in zip(c["steps"], p["steps"]):
        for name, value in a["errors"].items():
            assert b["errors"][name] == pytest.approx(value, rel=1e-8)


@pytest.fixture(scope="module")
def half_contact_term(tmp_path_factory):
    """A copy of forms/ with the contact term of the residual halved in
    piezo_forms.py (the loads still carry the foundation's full pressure,
    derived from the same contact_term); PIEZOCONTACT_FORMS points the
    package to it."""
    repo = tmp_path_factory.mktemp("no_contact")
    shutil.copytree(ROOT / "forms", repo / "forms", ignore=shutil.ignore_patterns("__pycache__"))
    forms = repo / "forms" / "piezo_forms.py"
    text = forms.read_text()
    assert text.count(CONTACT_TERM) == 1, "contact_residual() no longer returns the contact term"
    forms.write_text(text.replace(CONTACT_TERM, HALF_CONTACT_TERM))
    return repo


@pytest.mark.parametrize("gap,misses", [(2e-11, True), (1.0, False)],
                         ids=["contact-active", "contact-inactive"])
def test_with_half_the_contact_term_the_solution_misses(half_contact_term, tmp_path, gap,
                                                      misses):
    """Where the foundation pushes (gap 2e-11 m) the edited forms miss the
    exact solution by far more than round-off; where it never touches
    (gap 1 m) they still reproduce it, so the miss is the contact term's."""
    repo = half_contact_term
    args = MODULE + ["--config", str(ROOT / "demos" / "manufactured.json"),
                     "--output", str(tmp_path), "--quiet"]
    for o in ("manufactured.space=linear", "manufactured.time=linear", "mesh.n=8",
              "time.steps=8", "output.xdmf=false", "output.nodal=none", f"contact.gap={gap}"):
        args += ["--set", o]
    subprocess.run(args, check=True, env=dict(ENV, PIEZOCONTACT_FORMS=str(repo / "forms")),
                   capture_output=True)
    worst = max(relative_errors(json.loads((tmp_path / "summary.json").read_text())).values())
    if misses:
        assert worst > 1e-3
    else:
        assert worst < 1e-12
