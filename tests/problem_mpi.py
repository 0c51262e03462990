"""(mpirun -n 2 python3 tests/problem_mpi.py OUT) the small layered device of
test_problem.py solved through piezocontact.Problem, each process its part:
rank 0 writes the summary with the norm of u gathered from the owned dofs."""

import json
import sys
from pathlib import Path

import numpy as np
from mpi4py import MPI

import demo_dolfinx_api as device


def small_device(comm=MPI.COMM_WORLD):
    """The layered device of demos/demo_dolfinx_api.py, small: two regions,
    an interior electrode, a UFL pressure, contact, degree 2"""
    msh, cells, facets = device.layered_beam(comm, 24)
    return device.unimorph(msh, cells, facets, 3), facets


def owned_norm(f):
    """The l2 norm of a Function's dofs, each counted once over processes"""
    imap = f.function_space.dofmap.index_map
    owned = imap.size_local * f.function_space.dofmap.index_map_bs
    return float(np.sqrt(f.function_space.mesh.comm.allreduce(
        float(np.sum(f.x.array[:owned] ** 2)))))


def main(out):
    problem, _ = small_device()
    solution = problem.solve()
    norm = owned_norm(solution.u)
    if MPI.COMM_WORLD.rank == 0:
        out.write_text(json.dumps({**solution.summary, "u_norm": norm}))


if __name__ == "__main__":
    main(Path(sys.argv[1]))
