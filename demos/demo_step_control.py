#!/usr/bin/python3
# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # Control between steps: a load changed from Python as the run goes
#
# The observer of `Problem.solve` is called after every accepted step with
# the converged state; whatever it changes is what the next step sees. Here
# it closes a loop: the pressure on the top of example 1's body (the ZnO
# square of the paper, on a foundation) is a `dolfinx.fem.Constant` in a UFL
# traction, and after each step the observer rescales it so that the
# contact force reaches a target, F* = 5 N/m, although the body creeps
# (its viscosity: relaxation time 0.1 s) and the step has no closed-form
# answer.
#
#     /usr/bin/python3 demos/demo_step_control.py [--n 16] [--steps 20]

# +
import argparse

import numpy as np
import piezocontact
import ufl
from dolfinx import fem
from dolfinx import mesh as dmesh
from mpi4py import MPI

TARGET = 5.0  # N/m, the contact force wanted
# -

# ## The body: example 1 of the paper, built in the script
#
# The unit square of `demos/square.json`, meshed by dolfinx, its sides
# tagged; the `ZnO-paper` preset poled along y is that config's material to
# the last digit (`../shared/MATERIALS.md`). The left side is clamped and
# grounded, the bottom rests on the paper's foundation (gap 0).

# +
def unit_square(comm, n):
    msh = dmesh.create_unit_square(comm, n, n, dmesh.CellType.triangle,
                                   ghost_mode=dmesh.GhostMode.shared_facet)
    tdim = msh.topology.dim
    msh.topology.create_connectivity(tdim - 1, tdim)
    sides = {1: lambda x: np.isclose(x[0], 0.0), 2: lambda x: np.isclose(x[1], 0.0),
             3: lambda x: np.isclose(x[1], 1.0)}
    found = [dmesh.locate_entities_boundary(msh, tdim - 1, m) for m in sides.values()]
    indices = np.concatenate(found)
    values = np.concatenate([np.full(f.size, tag, dtype=np.int32)
                             for f, tag in zip(found, sides)])
    order = np.argsort(indices)
    return msh, dmesh.meshtags(msh, tdim - 1, indices[order].astype(np.int32), values[order])


def pressed_square(msh, facets, q, steps):
    """The top pushed down by the pressure q (a Constant, Pa)."""
    return piezocontact.Problem(
        msh, facets, boundary_names={"left": 1, "bottom": 2, "top": 3},
        material=piezocontact.Material(preset="ZnO-paper", poling=[0, 1]),
        boundaries={"left": piezocontact.Boundary(displacement=[0.0, 0.0], potential=0.0),
                    "top": piezocontact.Boundary(traction=ufl.as_vector((0.0, -q))),
                    "bottom": piezocontact.Boundary(contact=True)},
        contact=piezocontact.Contact(c_p=1e12, gap=0.0),
        time=piezocontact.Time(T=2.0, steps=steps))
# -

# ## The controller
#
# With the foundation in contact over the whole bottom the response is
# linear in q at equilibrium, so the secant update q <- q F*/F would be
# exact in one step without the creep; with it, F lags q, and the update
# converges over a few relaxation times. The observer reads the force from
# the step's record, and could as well read the Functions (`step.u`,
# `step.phi`).

# +
class Controller:
    def __init__(self, q):
        self.q, self.history = q, []

    def __call__(self, step):
        force = step.record["contact_force"][1]  # N/m, the foundation pushing up
        self.history.append((step.t, float(self.q.value), force))
        if force > 0:
            self.q.value = float(self.q.value) * TARGET / force
        else:  # not yet in contact: push harder
            self.q.value = 2.0 * float(self.q.value)
# -

# ## The run

# +
def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=16)
    ap.add_argument("--steps", type=int, default=20)
    ap.add_argument("--output", default=None, help="unused: the run writes nothing")
    args = ap.parse_args()
    comm = MPI.COMM_WORLD
    msh, facets = unit_square(comm, args.n)
    q = fem.Constant(msh, 10.0)  # Pa, a first guess
    control = Controller(q)
    solution = pressed_square(msh, facets, q, args.steps).solve(observer=control)

    final = solution.summary["steps"][-1]["contact_force"][1]
    if comm.rank == 0:
        print("   t (s)     q (Pa)   contact force (N/m)")
        for t, pressure, force in control.history:
            print(f"{t:8.3f} {pressure:10.4f} {force:12.6f}")
        print(f"final contact force {final:.6f} N/m, target {TARGET} N/m "
              f"(relative error {abs(final - TARGET) / TARGET:.1e})")
    # the loop closes: the last steps hold the target within 1e-3
    assert abs(final - TARGET) <= 1e-3 * TARGET, final
    # and the pressure changed between steps: the load the core saw was ours
    assert len({round(p, 12) for _, p, _ in control.history}) > 3


if __name__ == "__main__":
    main()
# -
