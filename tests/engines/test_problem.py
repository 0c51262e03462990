"""piezocontact.Problem, the dolfinx-native API: a model on the user's mesh
and tags, solved in memory, the state handed back as dolfinx Functions.

- every shipped config gives bit for bit the same run through
  Problem.from_config (in memory, its mesh made by the core) as through its
  file (piezocontact.solve with an output folder);
- a mesh made with dolfinx in the test, with typed objects, gives bit for
  bit example 1's run of demos/square.json, and a UFL load the run of the
  same load as a config expression (to round-off);
- the engines agree through the API (1e-9 of each quantity's size), and
  under mpirun -n 2 the answers are the serial ones;
- the observer's Functions are each step's converged state (the probes of
  the summary) and stay so after the run;
- bad input raises ConfigError with the config's one-line message."""

import glob
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
import piezocontact
import pytest
import ufl
from conftest import ENV, ROOT, SQUARE
from dolfinx import mesh as dmesh
from mpi4py import MPI
from piezocontact import _compat as compat
from piezocontact import compare
from test_demo_agreement import SMALL

import demo_dolfinx_api as device
from problem_mpi import owned_norm, small_device

QUIET = ["output.xdmf=false", "output.nodal=none"]
# what differs between two runs of one model: wall times, and where files are
RUN_SPECIFIC = {"timing", "analysis_timing", "config_file", "mesh_file", "checkpoint"}


def same_run(a, b):
    return {k: v for k, v in a.items() if k not in RUN_SPECIFIC} \
        == {k: v for k, v in b.items() if k not in RUN_SPECIFIC}


def scratch_meshes():
    return set(glob.glob(os.path.join(tempfile.gettempdir(), "piezocontact-mesh-*")))


@pytest.mark.parametrize("name", sorted(SMALL))
def test_shipped_config_in_memory_is_bit_identical(name, tmp_path, monkeypatch):
    config, overrides = ROOT / "demos" / name, SMALL[name] + QUIET
    on_file = piezocontact.solve(config, tmp_path / "file", overrides=overrides, progress=False)
    monkeypatch.chdir(tmp_path)  # a run in memory leaves nothing behind, here or in /tmp
    before, scratch = set(os.listdir(tmp_path)), scratch_meshes()
    in_memory = piezocontact.Problem.from_config(config, overrides).solve()
    assert set(os.listdir(tmp_path)) == before and scratch_meshes() == scratch
    assert in_memory.summary["status"] == "completed"
    assert same_run(in_memory.summary, on_file)
    assert same_run(piezocontact.solve(config, None, overrides=overrides, progress=False),
                    on_file)


# -- example 1 on a mesh made here

def unit_square(n, comm=MPI.COMM_WORLD, ghost_mode=dmesh.GhostMode.shared_facet):
    """dolfinx's unit square, its sides tagged with tags of our choosing"""
    msh = dmesh.create_unit_square(comm, n, n, dmesh.CellType.triangle, ghost_mode=ghost_mode)
    tdim = msh.topology.dim
    msh.topology.create_connectivity(tdim - 1, tdim)
    sides = {7: lambda x: np.isclose(x[0], 0.0), 8: lambda x: np.isclose(x[0], 1.0),
             9: lambda x: np.isclose(x[1], 0.0), 10: lambda x: np.isclose(x[1], 1.0)}
    found = [dmesh.locate_entities_boundary(msh, tdim - 1, m) for m in sides.values()]
    indices, values = np.concatenate(found), np.concatenate(
        [np.full(f.size, tag, np.int32) for f, tag in zip(found, sides)])
    order = np.argsort(indices)
    return msh, dmesh.meshtags(msh, tdim - 1, indices[order].astype(np.int32), values[order])


NAMES = {"left": 7, "right": 8, "bottom": 9, "top": 10}


def example_1(msh, facets, steps, top=None, **kwargs):
    """demos/square.json with typed objects (its material: the ZnO preset)"""
    return piezocontact.Problem(
        msh, facets, boundary_names=NAMES,
        material=piezocontact.Material(preset="ZnO-paper", poling=[0, 1]),
        contact=piezocontact.Contact(c_p=1e12, gap=0.0),
        boundaries={"left": piezocontact.Boundary(displacement=[0.0, 0.0], potential=0.0),
                    "top": top or piezocontact.Boundary(traction=[0.0, -10.0]),
                    "bottom": {"contact": True}},
        time=piezocontact.Time(T=1.0, steps=steps),
        probes=[[1.0, 1.0], [1.0, 0.0], [0.5, 0.0], [1.0, 0.5]], **kwargs)


def test_a_dolfinx_mesh_is_the_config_mesh(tmp_path):
    """The same model from dolfinx objects and typed pieces as from
    demos/square.json: the same run, bit for bit."""
    on_file = piezocontact.solve(SQUARE, tmp_path, overrides=["mesh.n=8", "time.steps=4"] + QUIET,
                                 progress=False)
    msh, facets = unit_square(8)
    solution = example_1(msh, facets, 4).solve()
    assert solution.summary["steps"] == on_file["steps"]
    assert solution.u.function_space.mesh is msh  # the user's mesh, not a copy


def test_a_ufl_load_is_the_config_expression(tmp_path):
    """A traction linear in x, as UFL (evaluated at quadrature points) and
    as a config expression (interpolated into the degree-1 data field:
    exact for it): the same run to round-off."""
    msh, facets = unit_square(8)
    as_ufl = example_1(msh, facets, 4, top=piezocontact.Boundary(
        traction=lambda x, t: ufl.as_vector((0.0, -20.0 * x[0])))).solve()
    as_text = example_1(msh, facets, 4, top=piezocontact.Boundary(
        traction=[0.0, "-20*x"])).solve()
    assert as_ufl.summary["steps"][-1]["contact_force"][1] > 1.0  # the load does act
    for of_size, _ in compare.agreement(as_ufl.summary, as_text.summary).values():
        assert of_size <= 1e-12


# -- the engines through the API, and MPI

@pytest.fixture(scope="module")
def device_runs():
    problem, facets = small_device()
    return {engine: problem.solve(engine=engine) for engine in ("cpp", "reference")}, facets


def test_engines_agree_through_the_api(device_runs):
    runs, _ = device_runs
    assert runs["cpp"].summary["steps"][-1]["max_penetration"] > 0  # in contact
    for quantity, (of_size, _) in compare.agreement(runs["cpp"].summary,
                                                    runs["reference"].summary).items():
        assert of_size <= 1e-9, (quantity, of_size)


def test_a_charge_from_the_functions_is_the_cores(device_runs):
    """The user's own form on the returned Functions (assemble_scalar of
    D.n on the top electrode) gives the charge the core reports."""
    runs, facets = device_runs
    core = runs["cpp"].summary["steps"][-1]["electrodes"]["top"]["charge"]
    assert abs(device.electrode_charge(runs["cpp"], facets) - core) <= 1e-10 * abs(core)


def test_mpi_gives_the_serial_answers(device_runs, tmp_path):
    runs, _ = device_runs
    out = tmp_path / "mpi.json"
    proc = subprocess.run(["mpirun", "-n", "2", sys.executable, str(ROOT / "tests" / "problem_mpi.py"),
                           str(out)], env=ENV,
                          capture_output=True, text=True, timeout=600, cwd=ROOT)
    assert proc.returncode == 0, proc.stderr[-3000:]
    parallel = json.loads(out.read_text())
    assert parallel["mpi_size"] == 2 and parallel["dofs"] == runs["cpp"].summary["dofs"]
    for quantity, (of_size, _) in compare.agreement(parallel, runs["cpp"].summary).items():
        assert of_size <= 1e-10, (quantity, of_size)
    # the Functions, each process its part: their norms are the serial ones
    assert parallel["u_norm"] == pytest.approx(owned_norm(runs["cpp"].u), rel=1e-10)


# -- the observer

def point_values(f, points):
    """f at points of the serial mesh"""
    msh = f.function_space.mesh
    cells = compat.colliding_cells(msh, points)
    return np.array([f.eval(p, cells.links(i)[:1]) for i, p in enumerate(points)])


def test_the_observer_gets_each_steps_state():
    msh, facets = unit_square(8)
    seen = []
    solution = example_1(msh, facets, 4).solve(observer=seen.append)
    steps = solution.summary["steps"]
    assert [s.n for s in seen] == [1, 2, 3, 4]
    assert [s.t for s in seen] == [s["t"] for s in steps]
    assert [s.record for s in seen] == steps
    points = np.array([p["point"] + [0.0] for p in steps[0]["probes"]])
    for step, record in zip(seen, steps):  # evaluated after the run: still that step's state
        u, phi = point_values(step.u, points), point_values(step.phi, points)
        size = np.abs(u).max()
        for i, probe in enumerate(record["probes"]):
            assert np.abs(u[i] - probe["u"]).max() <= 1e-12 * size
            assert abs(phi[i][0] - probe["phi"]) <= 1e-12 * np.abs(phi).max()
    assert not np.array_equal(seen[0].u.x.array, seen[-1].u.x.array)  # the loads grow
    assert np.array_equal(seen[-1].u.x.array, solution.u.x.array)
    assert np.array_equal(seen[-1].phi.x.array, solution.phi.x.array)


# -- bad input: the config's messages, one line

def refused(make):
    with pytest.raises(piezocontact.ConfigError) as e:
        make()
    message = str(e.value)
    assert "\n" not in message and message.startswith("piezocontact.Problem: ")
    return message


def test_bad_input_is_refused_with_the_configs_message():
    msh, facets = unit_square(4)

    def problem(boundaries, names=NAMES, tags=facets, material=None, **kwargs):
        return piezocontact.Problem(msh, tags, boundary_names=names,
                                    material=material or {"preset": "PZT-4", "poling": [0, 1]},
                                    boundaries=boundaries, time={"T": 1.0, "steps": 1}, **kwargs)
    clamp = {"left": {"displacement": [0.0, 0.0], "potential": 0.0}}
    assert "material.stiffness" in refused(lambda: problem(clamp, material={"stiffness": 1.0}))
    assert "time.steps" in refused(lambda: example_1(msh, facets, 0))
    assert "boundary_names.top = 99: no entity" in refused(
        lambda: problem(clamp, names={**NAMES, "top": 99}))
    assert "boundaries.side: the mesh has no boundary 'side'" in refused(
        lambda: problem({"side": {"displacement": [0.0, 0.0], "potential": 0.0}}))
    assert "boundaries.left.potential: a UFL value" in refused(
        lambda: problem({"left": {"potential": lambda x, t: x[0]}}))
    assert "facet_tags: tags of entities of dimension 2, expected 1" in refused(
        lambda: problem(clamp, names={"left": 1}, tags=dmesh.meshtags(
            msh, 2, np.arange(2, dtype=np.int32), np.ones(2, np.int32))))
    assert "region_names: regions need cell_tags" in refused(
        lambda: problem(clamp, region_names={"body": 1}))
    assert "UFL values go directly under their key" in refused(lambda: problem(
        {**clamp, "top": {"traction": {"value": ufl.as_vector((0.0, -1.0)),
                                       "history": {"ramp": 1.0}}}}))
    quads = dmesh.create_unit_square(MPI.COMM_WORLD, 2, 2, dmesh.CellType.quadrilateral)
    assert "mesh: cells of type quadrilateral" in refused(lambda: piezocontact.Problem(
        quads, None, material={"preset": "PZT-4", "poling": [0, 1]}, boundaries={},
        time={"T": 1.0, "steps": 1}))


def test_an_observers_exception_reaches_the_caller():
    """A user's observer that raises stops the run with its own exception,
    on both engines, and the Problem can be solved again."""
    msh, facets = unit_square(4)
    problem = example_1(msh, facets, 3)

    def fails(step):
        raise LookupError(f"stop at step {step.n}")
    for engine in ("cpp", "reference"):
        with pytest.raises(LookupError, match="stop at step 1"):
            problem.solve(engine=engine, observer=fails)
    assert problem.solve().summary["status"] == "completed"


def test_an_output_folder_gets_the_files(tmp_path):
    """output=DIR writes what the config path writes: the summary returned
    is summary.json's, and the XDMF file is there."""
    msh, facets = unit_square(4)
    solution = example_1(msh, facets, 2).solve(output=tmp_path)
    assert json.loads((tmp_path / "summary.json").read_text()) == solution.summary
    assert (tmp_path / "solution.xdmf").is_file()
