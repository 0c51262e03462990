"""What --resume needs to continue a run as if never stopped, the format of
cpp/checkpoint.h: the states x_n and x_{n-1} (the predictor extrapolates
from both) and the iterate x_J at which the Jacobian in use was assembled
(the convergence test's scaling is rebuilt from it), stored by input vertex
(rows) as [u_x, u_y, phi] of x_n, x_{n-1}, x_J (columns) in one .npy file
gathered on rank 0: a run can be resumed on any number of processes."""

import numpy as np
from mpi4py import MPI

from . import output

COLUMNS = 9


def _input_vertex_of_dofs(V):
    """Input (file) index of the vertex of each local dof (owned and ghost)
    of a P1 space: P1 dofs and P1 geometry nodes share the cell-local order."""
    mesh = V.mesh
    num_cells = (mesh.topology.index_map(mesh.topology.dim).size_local
                 + mesh.topology.index_map(mesh.topology.dim).num_ghosts)
    nodes = mesh.geometry.dofmap.array.reshape(-1, mesh.topology.dim + 1)[:num_cells]
    dofs = V.dofmap.list.array.reshape(-1, mesh.topology.dim + 1)[:num_cells]
    imap = V.dofmap.index_map
    vertex = np.full(imap.size_local + imap.num_ghosts, -1, dtype=np.int64)
    vertex[dofs.ravel()] = np.asarray(mesh.geometry.input_global_indices)[nodes.ravel()]
    return vertex


def _fields(problem):
    """(space, its W-dofs, first column of the field)"""
    return ((problem.V_u, problem.u_dofs, 0), (problem.V_phi, problem.phi_dofs, 2))


def _table_rows(problem):
    """Input indices need not be 0..N-1 (a file may hold nodes no cell uses)."""
    vertex = _input_vertex_of_dofs(problem.V_phi)
    last = int(vertex.max()) if vertex.size else -1
    return problem.comm.allreduce(last, op=MPI.MAX) + 1


def write_states(path, problem, states):
    """Gather x_n, x_{n-1}, x_J (arrays of W's local dofs) by input vertex and
    write them on rank 0. Collective."""
    parts = []
    for V, dofs, column in _fields(problem):
        vertex = _input_vertex_of_dofs(V)
        bs, owned = V.dofmap.index_map_bs, V.dofmap.index_map.size_local
        for c in range(bs):
            w = dofs[c:owned * bs:bs]
            parts.append((vertex[:owned], column + c, [x[w] for x in states]))
    gathered = problem.comm.gather(parts, root=0)
    rows = _table_rows(problem)

    def write():
        table = np.zeros((rows, COLUMNS))
        for rank_parts in gathered:
            for vertex, column, values in rank_parts:
                for s, v in enumerate(values):
                    table[vertex, 3 * s + column] = v
        output.save_npy(path, table)
    output.collectively(problem.comm, problem.comm.rank == 0, write)


def read_states(path, problem, states):
    """Read what write_states wrote into the owned and ghost dofs of `states`."""
    rows = _table_rows(problem)
    table = np.load(path)
    if table.shape != (rows, COLUMNS):
        raise ValueError(f"{path}: holds {table.shape[0]} x {table.shape[1]} values, "
                         f"the mesh needs {rows} x {COLUMNS}")
    for V, dofs, column in _fields(problem):
        vertex = _input_vertex_of_dofs(V)
        bs = V.dofmap.index_map_bs
        for c in range(bs):
            w = dofs[c::bs]
            for s, x in enumerate(states):
                x[w] = table[vertex, 3 * s + column + c]


def step_state(steps, k_J, events, file):
    """The summary's "checkpoint" record (cpp/checkpoint.h, StepState)."""
    return {"step": steps.accepted, "nominal_steps": steps.n, "t": steps.t, "k": steps.k,
            "k_last": steps.k_last, "k_J": k_J, "events": events, "file": file}
