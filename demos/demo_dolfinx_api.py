#!/usr/bin/python3
# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # A layered device from dolfinx objects: no config file
#
# A FEniCSx user has a mesh and its tags in memory and wants `u` and `phi`
# back as dolfinx Functions. This demo builds everything in the script:
#
# 1. a two-layer cantilever (a unimorph, plane strain) meshed with
#    `dolfinx.mesh.create_rectangle`, its layers and faces tagged with
#    `dolfinx.mesh.meshtags`;
# 2. the model on it: a PZT-5H film poled through its thickness on an
#    elastic substrate, clamped at x = 0, the film's top electrode driven to
#    100 V, the interface grounded, a foundation 1 um below the beam, and a
#    pressure on the top that grows along the beam and in time, given as a
#    UFL expression of the coordinates and the time;
# 3. a solve with both engines of piezocontact, in memory, an observer
#    following the tip from the Functions it receives;
# 4. post-processing with dolfinx alone: the charge on the top electrode by
#    `assemble_scalar` of D.n from the returned Functions (checked against
#    the charge the core reports), and the deflection of the top face
#    sampled at its dofs and plotted.
#
#     /usr/bin/python3 demos/demo_dolfinx_api.py [--nx 80] [--steps 8]
#     mpirun -n 2 /usr/bin/python3 demos/demo_dolfinx_api.py

# +
import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import piezocontact  # noqa: E402
import ufl  # noqa: E402
from dolfinx import fem  # noqa: E402
from dolfinx import mesh as dmesh  # noqa: E402
from mpi4py import MPI  # noqa: E402
from piezocontact import compare  # noqa: E402

HERE = Path(__file__).resolve().parent
L, H_SUB, H_PZT = 20e-3, 0.5e-3, 0.5e-3  # m
H = H_SUB + H_PZT
# -

# ## The mesh and its tags, with dolfinx
#
# Two rows of cells per layer, so that the interface y = H_SUB is a row of
# facets. Under MPI the cells across process boundaries are ghosted
# (`GhostMode.shared_facet`), as the contact and electrode integrals need.
# The tag values are the user's: the names are given beside them.

# +
SUBSTRATE, PZT = 1, 2
CLAMP, TOP, INTERFACE, BOTTOM = 11, 12, 13, 14


def layered_beam(comm, nx):
    msh = dmesh.create_rectangle(comm, [np.array([0.0, 0.0]), np.array([L, H])], [nx, 4],
                                 dmesh.CellType.triangle,
                                 ghost_mode=dmesh.GhostMode.shared_facet)
    tdim = msh.topology.dim
    msh.topology.create_connectivity(tdim - 1, tdim)

    def tags(dim, where):
        indices, values = [], []
        for value, marker in where.items():
            found = dmesh.locate_entities(msh, dim, marker)
            indices.append(found)
            values.append(np.full(found.size, value, dtype=np.int32))
        indices, values = np.concatenate(indices), np.concatenate(values)
        order = np.argsort(indices)
        return dmesh.meshtags(msh, dim, indices[order].astype(np.int32), values[order])

    cells = tags(tdim, {SUBSTRATE: lambda x: x[1] <= H_SUB + 1e-12,
                        PZT: lambda x: x[1] >= H_SUB - 1e-12})
    facets = tags(tdim - 1, {CLAMP: lambda x: np.isclose(x[0], 0.0),
                             TOP: lambda x: np.isclose(x[1], H),
                             INTERFACE: lambda x: np.isclose(x[1], H_SUB),
                             BOTTOM: lambda x: np.isclose(x[1], 0.0)})
    return msh, cells, facets
# -

# `locate_entities` marks a cell by its vertices: a cell of the substrate has
# every vertex at y <= H_SUB, one of the film every vertex at y >= H_SUB, and
# no cell has both.
#
# ## The model
#
# Materials are typed objects or the config's dicts; the film's tensors come
# from a preset and its poling direction (the core rotates and reduces them
# to plane strain). The pressure on the top face is a UFL expression of
# x = ufl.SpatialCoordinate and the time t, `q(x, t) = Q t x / L`, pushing
# down: a function f(x, t) returning it, which the forms evaluate at their
# quadrature points every step. The potential of the top electrode is a
# history, ramped over the first half of the run. Alone, the film would bend
# the tip 18 um down at 100 V; the foundation, 1 um below the whole bottom
# face, stops it: the beam rests on it near its tip, and the clamp's moment
# lifts the span behind.

# +
Q = 2e4  # Pa, the pressure at the tip at t = 1 s


def pressure(x, t):
    return ufl.as_vector((0.0, -Q * t * x[0] / L))


def unimorph(msh, cells, facets, steps):
    steel = np.array([[270e9, 115e9, 0], [115e9, 270e9, 0], [0, 0, 77.5e9]])  # Pa, plane strain
    return piezocontact.Problem(
        msh, facets, cells,
        boundary_names={"clamp": CLAMP, "top": TOP, "interface": INTERFACE, "bottom": BOTTOM},
        region_names={"substrate": SUBSTRATE, "pzt": PZT},
        regions={"pzt": piezocontact.Material(preset="PZT-5H", poling=[0, 1]),
                 "substrate": piezocontact.Material(elastic=steel, relaxation_time=0.1,
                                                    piezoelectric=np.zeros((2, 3)),
                                                    permittivity=1e-10 * np.eye(2))},
        boundaries={"clamp": piezocontact.Boundary(displacement=[0.0, 0.0]),
                    "top": piezocontact.Boundary(
                        potential={"value": 100.0, "history": {"ramp": 0.5}},
                        traction=pressure),
                    "interface": piezocontact.Boundary(potential=0.0),
                    "bottom": piezocontact.Boundary(contact=True)},
        contact=piezocontact.Contact(c_p=1e13, gap=1e-6),
        degree=2,  # a thin beam: P1 locks in bending
        time=piezocontact.Time(T=1.0, steps=steps),
        probes=[[L, H]])
# -

# ## Solving, and following the solution step by step
#
# `solve` runs the C++ time loop (`engine="cpp"`) or the independent
# reference engine, writes nothing with `output=None`, and calls the
# observer after every accepted step with the time and the converged `u`,
# `phi` as dolfinx Functions (new ones each step: they may be kept).

# +
def tip_deflection(u):
    """u_y at the dof nearest the top corner (L, H), gathered over processes."""
    x = u.function_space.tabulate_dof_coordinates()
    owned = u.function_space.dofmap.index_map.size_local
    d = np.linalg.norm(x[:owned, :2] - [L, H], axis=1)
    mine = (d.min(), u.x.array[2 * d.argmin() + 1]) if owned else (np.inf, 0.0)
    return min(u.function_space.mesh.comm.allgather(mine))[1]


def solve(problem, engine, comm):
    def report(step, tip):
        if comm.rank == 0:
            print(f"[{engine}] step {step.n}  t = {step.t:.3f} s  tip u_y = "
                  f"{tip * 1e6:+.4f} um  contact force "
                  f"{step.record['contact_force'][1]:.4g} N/m")
    return problem.solve(engine=engine, observer=lambda step: report(step, tip_deflection(step.u)))
# -

# `tip_deflection` is collective (an `allgather`), and so is the observer:
# every process calls it, each with its part of the Functions.
#
# ## Post-processing with dolfinx alone
#
# The charge on the top electrode is Q = int D.n ds with
# D = e s(u) - beta grad phi (the Voigt strain s with engineering shear).
# The tensors the core solved with are in the summary's config, rotated and
# reduced to plane strain: the user's own form reads them from there.

# +
def electrode_charge(solution, facets, region="pzt", tag=TOP):
    u, phi = solution.u, solution.phi
    msh = u.function_space.mesh
    material = solution.summary["config"]["regions"][region]
    e = fem.Constant(msh, np.array(material["piezoelectric"]))
    beta = fem.Constant(msh, np.array(material["permittivity"]))
    eps = ufl.sym(ufl.grad(u))
    strain = ufl.as_vector([eps[0, 0], eps[1, 1], 2 * eps[0, 1]])
    D = ufl.dot(e, strain) - ufl.dot(beta, ufl.grad(phi))
    ds = ufl.Measure("ds", domain=msh, subdomain_data=facets)
    charge = fem.form(ufl.dot(D, ufl.FacetNormal(msh)) * ds(tag))
    return msh.comm.allreduce(fem.assemble_scalar(charge), op=MPI.SUM)


def top_deflection(u):
    """(x, u_y) at the dofs of the top face, gathered on every process."""
    x = u.function_space.tabulate_dof_coordinates()
    owned = u.function_space.dofmap.index_map.size_local
    on_top = np.flatnonzero(np.isclose(x[:owned, 1], H))
    pairs = np.column_stack([x[on_top, 0], u.x.array[2 * on_top + 1]])
    pairs = np.concatenate(u.function_space.mesh.comm.allgather(pairs))
    return pairs[np.argsort(pairs[:, 0])].T


def plot(x, uy, path):
    fig, ax = plt.subplots(figsize=(7, 3))
    ax.plot(1e3 * x, 1e6 * uy, "-", label="top face")
    ax.axhline(-1.0, color="grey", ls="--", label="foundation (gap 1 um)")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("u_y (um)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
# -

# ## The run
#
# Both engines, their agreement (1e-9 of each quantity's size, as every
# engine comparison of piezocontact), the charge by the user's form against
# the core's, and the figure.

# +
def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--nx", type=int, default=80)
    ap.add_argument("--steps", type=int, default=8)
    ap.add_argument("--output", default=str(HERE.parent / "out" / "dolfinx_api"))
    args = ap.parse_args()
    comm = MPI.COMM_WORLD
    msh, cells, facets = layered_beam(comm, args.nx)
    problem = unimorph(msh, cells, facets, args.steps)
    solutions = {engine: solve(problem, engine, comm) for engine in ("cpp", "reference")}

    worst = max(of_size for of_size, _ in compare.agreement(
        solutions["cpp"].summary, solutions["reference"].summary).values())
    last = solutions["cpp"].summary["steps"][-1]
    charge = electrode_charge(solutions["cpp"], facets)
    core = last["electrodes"]["top"]["charge"]
    x, uy = top_deflection(solutions["cpp"].u)
    if comm.rank == 0:
        out = Path(args.output)
        out.mkdir(parents=True, exist_ok=True)
        plot(x, uy, out / "deflection.png")
        print(f"{solutions['cpp'].summary['dofs']} dofs; final tip u_y "
              f"{uy[-1] * 1e6:+.4f} um, largest u.nu - g {last['max_penetration']:.3e} m, "
              f"contact force {last['contact_force'][1]:.4g} N/m")
        print(f"cpp vs reference: largest difference {worst:.1e} of each quantity's size")
        print(f"top electrode charge: assemble_scalar {charge:.6e} C/m, the core's "
              f"{core:.6e} C/m (relative difference {abs(charge - core) / abs(core):.1e})")
        print(f"figure: {out / 'deflection.png'}")
    assert worst <= 1e-9, worst
    assert abs(charge - core) <= 1e-10 * abs(core), (charge, core)
    assert last["max_penetration"] > 0, "the beam was meant to reach the foundation"


if __name__ == "__main__":
    main()
# -
