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
    cells = mesh.topology.index_map(mesh.topology.dim)
    num_cells = cells.size_local + cells.num_ghosts
    nodes = mesh.geometry.dofmap.array.reshape(-1, mesh.topology.dim + 1)[:num_cells]
    dofs = V.dofmap.list.array.reshape(-1, mesh.topology.dim + 1)[:num_cells]
    imap = V.dofmap.index_map
    vertex = np.full(imap.size_local + imap.num_ghosts, -1, dtype=np.int64)
    vertex[dofs.ravel()] = np.asarray(mesh.geometry.input_global_indices)[nodes.ravel()]
    return vertex


class StateFile:
    """Which table entry each dof goes to is worked out once."""

    def __init__(self, problem):
        self.comm = problem.comm
        owned_dofs, owned_slots, dofs, slots = [], [], [], []
        last = -1
        for V, w, column in ((problem.V_u, problem.u_dofs, 0),
                             (problem.V_phi, problem.phi_dofs, 2)):
            vertex = _input_vertex_of_dofs(V)
            last = max(last, int(vertex.max()) if vertex.size else -1)
            bs, owned = V.dofmap.index_map_bs, V.dofmap.index_map.size_local
            for c in range(bs):
                dofs.append(w[c::bs])
                slots.append(vertex * COLUMNS + column + c)
                owned_dofs.append(w[c:owned * bs:bs])
                owned_slots.append(vertex[:owned] * COLUMNS + column + c)
        # Input indices need not be 0..N-1 (a file may hold nodes no cell uses)
        self.rows = self.comm.allreduce(last, op=MPI.MAX) + 1
        self.dofs, self.slots = np.concatenate(dofs), np.concatenate(slots)
        self.owned_dofs = np.concatenate(owned_dofs)
        all_slots = self.comm.gather(np.concatenate(owned_slots), root=0)
        self.all_slots = np.concatenate(all_slots) if self.comm.rank == 0 else None

    def write(self, path, states):
        """Gather x_n, x_{n-1}, x_J (arrays of W's local dofs) by input vertex
        and write them on rank 0. Collective."""
        values = np.column_stack([x[self.owned_dofs] for x in states])
        gathered = self.comm.gather(values, root=0)

        def write():
            table = np.zeros(self.rows * COLUMNS)
            v = np.vstack(gathered)
            for s in range(3):
                table[self.all_slots + 3 * s] = v[:, s]
            output.save_npy(path, table.reshape(self.rows, COLUMNS))
        output.collectively(self.comm, self.comm.rank == 0, write)

    def read(self, path, states):
        """Read what write() wrote into the owned and ghost dofs of `states`."""
        table = np.load(path)
        if table.shape != (self.rows, COLUMNS):
            raise ValueError(f"{path}: holds {table.shape[0]} x {table.shape[1]} values, "
                             f"the mesh needs {self.rows} x {COLUMNS}")
        table = table.ravel()
        for s, x in enumerate(states):
            x[self.dofs] = table[self.slots + 3 * s]


def step_state(steps, k_J, events, file):
    """The summary's "checkpoint" record (cpp/checkpoint.h, StepState)."""
    return {"step": steps.accepted, "nominal_steps": steps.n, "t": steps.t, "k": steps.k,
            "k_last": steps.k_last, "k_J": k_J, "events": events, "file": file}
