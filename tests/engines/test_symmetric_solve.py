"""solver.symmetric = "auto" (cpp/piezocontact/linear_solver.h): the
Jacobian with its electric rows negated is factorised by MUMPS' LDL^T where
it is symmetric, with the LU's answers, Newton iterations and LU reuse, at
half the factor entries, without pivoting where it is quasi-definite (the
inertia checks it); a form that breaks the symmetry (Nitsche on a
piezoelectric contact boundary, a user's skew term) is factorised by LU.

Tolerances. LDL^T and LU solve the same system to round-off; the runs'
probes differ by the condition number times 1e-16: measured 1e-16..4e-13
relative on the demo configs (scripts/compare_builds.sh with TOLERANCE), so
1e-10 is the bound (the issue's is 1e-12 on example 1, checked at 1e-11
here for margin across machines). The symmetry defect of the paper's forms is
assembly round-off: measured 2e-16..3e-15 of the Jacobi-scaled entries; the
detection threshold is 1e-12. MUMPS' LDL^T stores one triangle: its factor
entries are about half the LU's (0.50-0.51 measured)."""

import numpy as np
import piezocontact
import pytest
import ufl
from conftest import ROOT, SQUARE, relative_difference, run_solver, slab

SLAB = ROOT / "demos" / "slab.json"
SENSOR = ROOT / "demos" / "sensor.json"
DISC = ROOT / "demos" / "disc.json"
INDENTATION = ROOT / "demos" / "indentation.json"
QUIET = ["output.xdmf=false", "output.nodal=none"]
LU = ["solver.symmetric=never"]


def counts(summary):
    ops = summary["timing"]["operations"]
    return ([s["newton_iterations"] for s in summary["steps"]],
            ops["factorisation"]["count"], ops["reused_factorisation"])


CASES = {
    "example 1": (SQUARE, ["mesh.n=32", "time.steps=8", "time.T=0.25"]),
    "3D": (SLAB, slab(3)),
    "3D P2": (SLAB, slab(2) + ["elements.degree=2"]),
    "axisymmetric P2": (DISC, ["time.steps=2"]),
    "floating electrode": (SENSOR, ["time.steps=20", "time.T=0.5"]),
}


@pytest.mark.parametrize("case", CASES)
def test_ldlt_gives_the_lu_answers(case, tmp_path):
    config, overrides = CASES[case]
    ldlt, _ = run_solver("cpp", tmp_path / "ldlt", overrides + QUIET, config=config)
    lu, _ = run_solver("cpp", tmp_path / "lu", overrides + QUIET + LU, config=config)
    assert (ldlt["timing"]["factorisation"], lu["timing"]["factorisation"]) == ("LDLT", "LU")
    assert ldlt["timing"]["symmetry_defect"] < 1e-13
    # quasi-definite: factorised without pivoting, the inertia as predicted
    assert not ldlt["timing"]["ldlt_pivoting"]
    du, dphi = relative_difference(ldlt, lu)
    assert du < 1e-11 and dphi < 1e-11, (du, dphi)
    # the same Newton iterations, factorisations and LU reuse: only the
    # factorisation changed
    assert counts(ldlt) == counts(lu)
    ratio = ldlt["timing"]["factor_entries"] / lu["timing"]["factor_entries"]
    assert 0.4 < ratio < 0.6, ratio


def test_floating_potentials_are_those_of_lu(tmp_path):
    """The bordered step's unit responses are solves of D J too (the hooks
    negate their right-hand sides): the floating potential as with LU."""
    config, overrides = CASES["floating electrode"]
    ldlt, _ = run_solver("cpp", tmp_path / "ldlt", overrides + QUIET, config=config)
    lu, _ = run_solver("cpp", tmp_path / "lu", overrides + QUIET + LU, config=config)
    v = [np.array([s["electrodes"]["sensor"]["potential"] for s in r["steps"]])
         for r in (ldlt, lu)]
    assert np.abs(v[0]).max() > 0.1  # volts: there was a potential to find
    assert np.abs(v[0] - v[1]).max() < 1e-11 * np.abs(v[1]).max()


def test_mpi_gives_the_serial_answers(tmp_path):
    overrides = slab(3) + QUIET
    serial, _ = run_solver("cpp", tmp_path / "np1", overrides, config=SLAB)
    parallel, _ = run_solver("cpp", tmp_path / "np2", overrides, config=SLAB, np_=2)
    assert parallel["mpi_size"] == 2
    assert parallel["timing"]["factorisation"] == "LDLT"
    du, dphi = relative_difference(serial, parallel)
    assert du < 1e-10 and dphi < 1e-10, (du, dphi)


def test_nitsche_on_a_piezoelectric_boundary_falls_back_to_lu(tmp_path):
    """Nitsche's sigma_n holds e^T grad phi: the u rows get phi columns the
    phi rows do not mirror. The defect is of order 1, not round-off."""
    s, _ = run_solver("cpp", tmp_path / "nitsche", ["mesh.size=20e-6", "time.steps=2"] + QUIET,
                      config=INDENTATION)
    assert s["timing"]["factorisation"] == "LU"
    assert s["timing"]["symmetry_defect"] > 1e-3


def skew_spring(u, phi, w, psi, data):
    """c u_x w_y: a load along y from a displacement along x, with no
    reciprocal term (a follower-like load), at 1e-4 of the body's stiffness"""
    return 1e9 * u[0] * w[1] * ufl.dx


def cubic_spring(u, phi, w, psi, data):
    """c |u|^2 u.w: its Jacobian c (|u|^2 I + 2 u u^T) is symmetric"""
    return 1e32 * ufl.inner(u, u) * ufl.inner(u, w) * ufl.dx


@pytest.mark.parametrize("hook, expected", [(skew_spring, "LU"), (cubic_spring, "LDLT")],
                         ids=["skew", "symmetric"])
def test_a_users_term_decides_by_its_symmetry(hook, expected, tmp_path):
    s = piezocontact.solve(SQUARE, tmp_path / "hooked", progress=False, extra_residual=hook,
                           overrides=["mesh.n=8", "time.steps=4"] + QUIET)
    assert s["timing"]["factorisation"] == expected
    if expected == "LU":
        assert s["timing"]["symmetry_defect"] > 1e-8
    else:
        assert s["timing"]["symmetry_defect"] < 1e-13


def negative_spring(u, phi, w, psi, data):
    """-c u.w, c = 1e13 N/m^4: symmetric, but K - c M is indefinite (its
    lowest modes have c above their stiffness), so D J is not quasi-definite"""
    return -1e13 * ufl.inner(u, w) * ufl.dx


def test_an_indefinite_stiffness_is_factorised_with_pivoting(tmp_path):
    """The inertia check (one negative pivot per phi row) sees that D J is
    not quasi-definite and refactorises with MUMPS' threshold pivoting: the
    LU's answers and Newton iterations"""
    runs = {sym: piezocontact.solve(SQUARE, tmp_path / sym, progress=False,
                                    extra_residual=negative_spring,
                                    overrides=["mesh.n=8", "time.steps=4",
                                               f"solver.symmetric={sym}"] + QUIET)
            for sym in ("auto", "never")}
    ldlt, lu = runs["auto"], runs["never"]
    assert ldlt["timing"]["factorisation"] == "LDLT" and ldlt["timing"]["ldlt_pivoting"]
    assert [s["newton_iterations"] for s in ldlt["steps"]] \
        == [s["newton_iterations"] for s in lu["steps"]]
    du, dphi = relative_difference(ldlt, lu)
    assert du < 1e-11 and dphi < 1e-11, (du, dphi)


def test_a_users_factorisation_is_kept(tmp_path):
    """solver.petsc_options that choose the factorisation take it over: LU
    here, as the user asked, though the forms are symmetric"""
    s, _ = run_solver("cpp", tmp_path / "user",
                      ["mesh.n=8", "time.steps=2", "solver.petsc_options.pc_type=lu"] + QUIET)
    assert s["timing"]["factorisation"] == "LU"
