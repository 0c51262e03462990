"""The C++ solver and the Python twin solve the same discrete problem: they
must agree to 1e-8 relative on every probe value and on both fields (relative
L2 norm) at every step, serial and under mpirun -n 2."""

import shutil

import numpy as np
import pytest
from conftest import run_solver
from piezocontact import compare

TOL = 1e-8  # Newton stops at 1e-10 relative per field; both reach round-off


def test_probes_agree_every_step(small_runs):
    cpp, py = small_runs["cpp"][0], small_runs["python"][0]
    assert len(cpp["steps"]) == len(py["steps"]) == 8
    for d in compare.probe_differences(cpp, py):
        assert d["u"] < TOL and d["phi"] < TOL, d


def test_fields_agree_every_step(small_runs):
    (cpp, cpp_dir), (_, py_dir) = small_runs["cpp"], small_runs["python"]
    diffs = compare.field_differences(cpp_dir, py_dir, small_runs["python"][0])
    assert sorted(diffs) == list(range(1, 9))
    for step, d in diffs.items():
        assert d["u"] < TOL and d["phi"] < TOL, (step, d)


def test_scalar_outputs_agree(small_runs):
    cpp, py = small_runs["cpp"][0], small_runs["python"][0]
    assert cpp["dofs"] == py["dofs"] == 3 * 81
    for a, b in zip(cpp["steps"], py["steps"]):
        assert a["newton_iterations"] == b["newton_iterations"]
        assert np.allclose(a["contact_force"], b["contact_force"], rtol=TOL, atol=0)
        assert a["max_penetration"] == pytest.approx(b["max_penetration"], rel=TOL)
        ra, rb = np.array(a["reactions"]["left"]), np.array(b["reactions"]["left"])
        # componentwise round-off is relative to the size of the reaction
        assert np.linalg.norm(ra - rb) <= TOL * np.linalg.norm(rb)


def test_field_comparison_detects_a_difference(small_runs, tmp_path):
    """The comparison itself can fail: perturb one nodal value by 1e-6."""
    cpp, cpp_dir = small_runs["cpp"]
    shutil.copytree(cpp_dir / "nodal", tmp_path / "nodal")
    rows = np.load(tmp_path / "nodal" / "phi_0008.npy")
    rows[len(rows) // 2, 2] *= 1 + 1e-6
    np.save(tmp_path / "nodal" / "phi_0008.npy", rows)
    d = compare.field_differences(tmp_path, cpp_dir, cpp)[8]
    assert d["u"] == 0.0 and 1e-9 < d["phi"] < 1e-6


@pytest.mark.parametrize("solver", ["cpp", "python"])
def test_mpi_matches_serial(solver, small_runs, tmp_path):
    serial, serial_dir = small_runs[solver]
    par, _ = run_solver(solver, tmp_path, ["mesh.n=8", "time.steps=8", "output.nodal=all"],
                        np_=2)
    assert par["mpi_size"] == 2 and par["dofs"] == serial["dofs"]
    for d in compare.probe_differences(par, serial):
        assert d["u"] < TOL and d["phi"] < TOL, d
    for step, d in compare.field_differences(tmp_path, serial_dir, serial).items():
        assert d["u"] < TOL and d["phi"] < TOL, (step, d)
