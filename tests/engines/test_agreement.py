"""The three engines solve the same discrete problem. The executable (AOT
kernels) and the C++ loop from Python (JIT kernels of the same UFL) are one
loop: they agree to round-off. The reference engine (its own loop, Newton
and convergence test) must agree with them to 1e-8 relative on every probe
value, both fields (relative L2 norm), the contact force, the penetration and
the reactions at every step, serial and under mpirun -n 2."""

import shutil

import numpy as np
import pytest
from conftest import ENGINES, run_solver
from piezocontact import compare

TOL = 1e-8  # both converge to round-off: 1e-10 per field (cpp), 1e-11 increments (reference)
# Same loop and UFL, kernels compiled apart (ffcx AOT vs dolfinx JIT flags)
ROUND_OFF = 1e-12
PAIRS = [("cpp", "cpp-jit", ROUND_OFF), ("cpp", "reference", TOL)]


@pytest.mark.parametrize("a,b,tol", PAIRS)
def test_probes_agree_every_step(small_runs, a, b, tol):
    ra, rb = small_runs[a][0], small_runs[b][0]
    assert len(ra["steps"]) == len(rb["steps"]) == 8
    for d in compare.probe_differences(ra, rb):
        assert d["u"] < tol and d["phi"] < tol, d


@pytest.mark.parametrize("a,b,tol", PAIRS)
def test_fields_agree_every_step(small_runs, a, b, tol):
    diffs = compare.field_differences(small_runs[a][1], small_runs[b][1], small_runs[b][0])
    assert sorted(diffs) == list(range(1, 9))
    for step, d in diffs.items():
        assert d["u"] < tol and d["phi"] < tol, (step, d)


@pytest.mark.parametrize("a,b,tol", PAIRS)
def test_scalar_outputs_agree(small_runs, a, b, tol):
    ra, rb = small_runs[a][0], small_runs[b][0]
    assert ra["dofs"] == rb["dofs"] == 3 * 81
    assert set(ra) == set(rb) and set(ra["steps"][0]) == set(rb["steps"][0])
    assert (ra["solver"], rb["solver"]) == (a, b)
    for sa, sb in zip(ra["steps"], rb["steps"]):
        if b == "cpp-jit":
            assert sa["newton_iterations"] == sb["newton_iterations"]
        assert np.allclose(sa["contact_force"], sb["contact_force"], rtol=tol, atol=0)
        assert sa["max_penetration"] == pytest.approx(sb["max_penetration"], rel=tol)
        fa, fb = np.array(sa["reactions"]["left"]), np.array(sb["reactions"]["left"])
        # componentwise round-off is relative to the size of the reaction
        assert np.linalg.norm(fa - fb) <= tol * np.linalg.norm(fb)


def test_field_comparison_detects_a_difference(small_runs, tmp_path):
    """The comparison itself can fail: perturb one nodal value by 1e-6."""
    cpp, cpp_dir = small_runs["cpp"]
    shutil.copytree(cpp_dir / "nodal", tmp_path / "nodal")
    rows = np.load(tmp_path / "nodal" / "phi_0008.npy")
    rows[len(rows) // 2, 2] *= 1 + 1e-6
    np.save(tmp_path / "nodal" / "phi_0008.npy", rows)
    d = compare.field_differences(tmp_path, cpp_dir, cpp)[8]
    assert d["u"] == 0.0 and 1e-9 < d["phi"] < 1e-6


@pytest.mark.parametrize("solver", ENGINES)
def test_mpi_matches_serial(solver, small_runs, tmp_path):
    serial, serial_dir = small_runs[solver]
    par, _ = run_solver(solver, tmp_path, ["mesh.n=8", "time.steps=8", "output.nodal=all"],
                        np_=2)
    assert par["mpi_size"] == 2 and par["dofs"] == serial["dofs"]
    for d in compare.probe_differences(par, serial):
        assert d["u"] < TOL and d["phi"] < TOL, d
    for step, d in compare.field_differences(tmp_path, serial_dir, serial).items():
        assert d["u"] < TOL and d["phi"] < TOL, (step, d)
