"""Floating electrodes in the reference engine, by dolfinx_mpc.

The C++ loop solves a floating electrode as one extra unknown bordering the
factorisation in use (cpp/piezocontact/floating.h). The reference engine
checks it by another construction: a multi-point constraint (dolfinx_mpc
0.5 or 0.9) ties every potential dof of the electrode to one master dof, so that the
space itself holds only uniform potentials there. The master's row of the
constrained residual is then the residual tested with psi_E, the sum of the
electrode's basis functions, and the electrode's charge condition
-R(x; psi_E) = Q is that row plus Q. Nothing is shared with the C++ loop but
the forms and the electrodes' dofs.

Two properties of dolfinx_mpc 0.5 shape the code: every copy of an
electrode dof (ghosts too) must be a slave, and the constrained space has
ghosts of its own (remote masters), so the solver's vectors live on
`mpc.function_space` and the full x is rebuilt from them (homogenize, then
backsubstitution: it adds) before each assembly.
"""

import dolfinx_mpc
import dolfinx_mpc.cpp
import numpy as np
from dolfinx import fem
from mpi4py import MPI
from petsc4py import PETSc

from ._compat import cpp, create_petsc_vector, dirichletbcs, mpc_backsubstitution, petsc_vec

_NONE = np.iinfo(np.int64).max


class FloatingConstraint:
    """The constraint of a problem's floating electrodes on W, and the
    residual and Jacobian assembled under it."""

    def __init__(self, x, problem, F_form, J_form):
        self.x, self.problem = x, problem
        self.F_form, self.J_form = F_form, J_form
        self.bcs = dirichletbcs(problem.fixed_bcs)
        W = x.function_space
        self.comm = W.mesh.comm
        imap = W.dofmap.index_map
        assert W.dofmap.index_map_bs == 1  # the mixed space
        owned = imap.size_local
        self.index = [i for i, e in enumerate(problem.electrodes) if e.floating]
        slaves, masters, owners = [], [], []
        self.master_row = []  # per floating electrode: its local row here, or None
        for i in self.index:
            dofs = np.asarray(problem.electrodes[i].dofs, dtype=np.int32)
            glob = imap.local_to_global(dofs).astype(np.int64)
            mine = glob[dofs < owned]
            master = self.comm.allreduce(int(mine.min()) if mine.size else _NONE, op=MPI.MIN)
            owner = self.comm.allreduce(self.comm.rank if master in mine else self.comm.size,
                                        op=MPI.MIN)
            slave = dofs[glob != master]
            slaves.append(slave)
            masters.append(np.full(slave.size, master, dtype=np.int64))
            owners.append(np.full(slave.size, owner, dtype=np.int32))
            self.master_row.append(int(master - imap.local_range[0])
                                   if self.comm.rank == owner else None)
        slaves = np.concatenate(slaves).astype(np.int32)
        self.mpc = dolfinx_mpc.MultiPointConstraint(W)
        self.mpc.add_constraint(W, slaves, np.concatenate(masters),
                                np.ones(slaves.size, dtype=PETSc.ScalarType),
                                np.concatenate(owners),
                                np.arange(slaves.size + 1, dtype=np.int32))
        self.mpc.finalize()
        V = self.mpc.function_space
        self._full = fem.Function(V)  # x on the constrained space's layout

    def create_vector(self):
        V = self.mpc.function_space
        return create_petsc_vector(V.dofmap.index_map, V.dofmap.index_map_bs)

    def create_matrix(self):
        return dolfinx_mpc.cpp.mpc.create_matrix(cpp(self.J_form), self.mpc._cpp_object)

    def take(self, X):
        """x <- the full state of the solver's X (slaves = their master)."""
        full = petsc_vec(self._full)
        X.copy(full)
        full.ghostUpdate(PETSc.InsertMode.INSERT, PETSc.ScatterMode.FORWARD)
        mpc_backsubstitution(self.mpc, self._full)
        petsc_vec(self.x).array_w[:] = full.array_r
        self.x.x.scatter_forward()

    def residual(self, b):
        """The constrained residual at x, before its Dirichlet rows are set,
        with each master row plus the electrode's charge."""
        dolfinx_mpc.assemble_vector(self.F_form, self.mpc, b=b)
        dolfinx_mpc.apply_lifting(b, [self.J_form], [self.bcs], self.mpc,
                                  x0=[petsc_vec(self.x)], scale=-1.0)
        b.ghostUpdate(PETSc.InsertMode.ADD, PETSc.ScatterMode.REVERSE)
        charges = self.problem.target_charges()
        with b.localForm() as local:
            for i, row in zip(self.index, self.master_row):
                if row is not None:
                    local.array_w[row] += charges[i]

    def jacobian(self, A):
        A.zeroEntries()
        dolfinx_mpc.assemble_matrix(self.J_form, self.mpc, bcs=self.bcs, A=A)
        A.assemble()
