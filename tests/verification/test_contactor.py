"""Example 2, the contactor: gmsh meshes with named boundaries, read by the
C++ core; the three engines agree at every step (serial and mpirun -n 2);
the pictures' data against the solver's."""

import importlib.util
import math
import subprocess
import sys

import numpy as np
import pytest
import ufl
from conftest import ENGINES, ENV, ROOT, run_solver
from dolfinx import fem
from mpi4py import MPI
from piezocontact import cpp
from piezocontact._compat import meshtags
from piezocontact.model import python_mesh
from piezocontact import compare
from piezodemos import figures

CONTACTOR = ROOT / "demos" / "contactor.json"
VARIANT = ROOT / "demos" / "contactor_in_contact.json"
SMALL = ["mesh.size=0.2", "time.steps=10", "output.nodal=all"]
TOL = 1e-8
PAIRS = [("cpp", "cpp-jit", 1e-12), ("cpp", "reference", TOL)]  # as in test_agreement


def polygon(script):
    sys.path.insert(0, str(script.parent))  # the scripts import polygon_mesh
    spec = importlib.util.spec_from_file_location(script.stem, script)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.POINTS, module.EDGES


def edge_lengths(points, edges):
    out = {}
    for i, name in enumerate(edges):
        (x0, y0), (x1, y1) = points[i], points[(i + 1) % len(points)]
        out[name] = out.get(name, 0.0) + math.hypot(x1 - x0, y1 - y0)
    return out


@pytest.fixture(scope="module")
def variant_runs(tmp_path_factory):
    base = tmp_path_factory.mktemp("contactor")
    return {s: (run_solver(s, base / s, SMALL, config=VARIANT)[0], base / s) for s in ENGINES}


@pytest.mark.parametrize("name", ["contactor", "square"])
def test_facet_tags_from_xdmf_measure_the_polygon_edges(name, tmp_path):
    """Each named group's measure, assembled with the facet tags read back
    from XDMF (and remapped to slots), equals its edge length to 1e-12."""
    script = ROOT / "meshes" / f"{name}.py"
    out = tmp_path / f"{name}.xdmf"
    subprocess.run(["/usr/bin/python3", str(script), "--size", "0.3", "--output", str(out)],
                   check=True, env=ENV, capture_output=True)
    named = cpp.build_mesh("{}", MPI.COMM_WORLD, str(out))
    msh, tags, tag_of = python_mesh(named), meshtags(named.facet_tags), named.tag_of
    ds = ufl.Measure("ds", domain=msh, subdomain_data=tags)
    one = fem.Constant(msh, 1.0)
    expected = edge_lengths(*polygon(script))
    assert sorted(tag_of) == sorted(expected)
    for boundary, length in expected.items():
        measured = fem.assemble_scalar(fem.form(one * ds(tag_of[boundary])))
        assert measured == pytest.approx(length, rel=1e-12, abs=1e-12), boundary


def test_both_engines_see_the_named_boundaries(variant_runs):
    points, edges = polygon(ROOT / "meshes" / "contactor.py")
    expected = edge_lengths(points, edges)
    for solver, (summary, _) in variant_runs.items():
        for name, length in expected.items():
            assert summary["boundary_lengths"][name] == pytest.approx(length, rel=1e-12), \
                (solver, name)


def agree(run_a, run_b, tol):
    """Probes, fields, contact force and penetration at every step."""
    (a, a_dir), (b, b_dir) = run_a, run_b
    assert a["dofs"] == b["dofs"]
    for d in compare.probe_differences(a, b):
        assert d["u"] < tol and d["phi"] < tol, d
    diffs = compare.field_differences(a_dir, b_dir, b)
    assert sorted(diffs) == list(range(1, 11))
    for step, d in diffs.items():
        assert d["u"] < tol and d["phi"] < tol, (step, d)
    for sa, sb in zip(a["steps"], b["steps"]):
        assert np.allclose(sa["contact_force"], sb["contact_force"], rtol=tol, atol=0)
        assert sa["max_penetration"] == pytest.approx(sb["max_penetration"], rel=tol)


@pytest.mark.parametrize("a,b,tol", PAIRS)
def test_engines_agree_on_the_contactor(variant_runs, a, b, tol):
    agree(variant_runs[a], variant_runs[b], tol)


@pytest.mark.parametrize("solver", ENGINES)
def test_contactor_under_mpi_matches_serial(solver, variant_runs, tmp_path):
    summary, _ = run_solver(solver, tmp_path, SMALL, config=VARIANT, np_=2)
    assert summary["mpi_size"] == 2
    agree((summary, tmp_path), variant_runs[solver], TOL)


def test_every_step_converged_in_both_fields(variant_runs):
    """Both relative residuals below rtol at every step (Dirichlet rows, with
    their unit diagonal, must not dilute the measure)."""
    for summary, _ in variant_runs.values():
        for step in summary["steps"]:
            assert step["relative_residuals"]["u"] <= 1e-10
            assert step["relative_residuals"]["phi"] <= 1e-10


def test_variant_is_in_partial_contact(variant_runs):
    """The pictures' data (forms evaluated on the C++ nodal output) match the
    solver's: the nodal contact forces sum to its contact resultant, normal
    to Gamma_C, and only part of Gamma_C touches."""
    summary, out = variant_runs["cpp"]
    state = figures.RunState(out, summary)
    total = state.contact_force.sum(axis=0)
    assert np.allclose(total, summary["steps"][-1]["contact_force"], rtol=1e-10, atol=0)
    assert total[0] > 0 and total[0] == pytest.approx(total[1], rel=1e-10)  # along -nu
    assert 0 < state.contact_length < summary["boundary_lengths"]["contact"]


def test_equilibrium_in_partial_contact(variant_runs):
    """No load but the foundation and the clamp: contact force + reaction = 0
    up to what Newton leaves on the free dofs, |sum F_i| <= sqrt(n) ||F_u||.
    With part of Gamma_C active, the kink of p inside facets breaks this
    (by ~1e-3 relative) unless the contact force is integrated exactly as the
    residual does."""
    for summary, _ in variant_runs.values():
        for step in summary["steps"]:
            f, r = np.array(step["contact_force"]), np.array(step["reactions"]["clamp"])
            bound = math.sqrt(summary["dofs"]) * step["residual_norms"]["u"]
            assert np.linalg.norm(f) > 0.1
            assert np.linalg.norm(f + r) <= bound + 1e-13 * np.linalg.norm(f), step["t"]
            assert bound < 1e-6 * np.linalg.norm(f)  # and Newton's leftover is small


def test_paper_data_leave_the_gap_open(tmp_path):
    summary, _ = run_solver("cpp", tmp_path, ["mesh.size=0.2", "time.steps=10"],
                            config=CONTACTOR)
    g = summary["config"]["contact"]["gap"]
    for step in summary["steps"]:
        assert step["contact_force"] == [0.0, 0.0]
        assert 0 < step["max_penetration"] + g < 1e-9 < g  # moves ~1e-10 m toward it


@pytest.mark.parametrize("solver", ["cpp", "cpp-jit"])
def test_mesh_size_from_the_command_line(solver, tmp_path):
    coarse, _ = run_solver(solver, tmp_path / "a", ["mesh.size=0.4", "time.steps=1"],
                           config=CONTACTOR)
    fine, _ = run_solver(solver, tmp_path / "b", ["mesh.size=0.2", "time.steps=1"],
                         config=CONTACTOR)
    assert 3 * coarse["dofs"] < fine["dofs"] < 5 * coarse["dofs"]


def test_missing_geometry_is_a_clear_error(tmp_path):
    messages = {}
    for solver in ("cpp", "cpp-jit"):
        _, proc = run_solver(solver, tmp_path / solver, ["mesh.geometry=nope.py"],
                             config=CONTACTOR, check=False)
        assert proc.returncode == 2
        messages[solver] = proc.stderr.strip().splitlines()[-1]
    assert messages["cpp"] == messages["cpp-jit"]
    assert messages["cpp"].startswith(f'error: {CONTACTOR}: mesh.geometry = "nope.py": no such file')
