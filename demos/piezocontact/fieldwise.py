"""Per-field Newton convergence (the rule cpp/fieldwise.cpp implements too).

In SI units the u-block of the Jacobian is ~1e11 and the phi-block ~1e-10, so
one residual norm sees only u. We measure both fields in the Jacobi-scaled
system  D^-1/2 J D^-1/2 (D^1/2 x) = D^-1/2 F,  D = |diag J|, in which both
blocks are O(1) (the coupling becomes e/sqrt(B beta) ~ 0.4). Per field f:
    r_f = ||D^-1/2 F||_f   (scaled residual)
    s_f = ||D^1/2 x||_f    (scaled solution, the same units as r_f)
and the step has converged when, for every field, r_f <= rtol s_f + atol s,
with s = sqrt(s_u^2 + s_phi^2). D comes from the latest assembled Jacobian.
Dirichlet dofs are left out: their rows hold x - g (zero once the predictor
has the BC values) under an arbitrary unit diagonal, so a 20 V electrode
would otherwise weigh 20 in s_phi where a free dof weighs ~1e-4.
The SI norms ||F_u|| (N/m) and ||F_phi|| (C/m) are reported alongside.
"""

import numpy as np
from mpi4py import MPI

FIELDS = ("u", "phi")


class FieldwiseConvergence:
    def __init__(self, W, field_dofs, bc_dofs, rtol, atol, comm):
        owned = W.dofmap.index_map.size_local * W.dofmap.index_map_bs
        constrained = np.concatenate([np.asarray(d) for d in bc_dofs] or [[]])
        self.dofs = {f: np.setdiff1d(np.asarray(d)[np.asarray(d) < owned], constrained)
                     for f, d in field_dofs.items()}
        self.rtol, self.atol, self.comm = rtol, atol, comm
        self.sqrt_d = None
        self.history = []

    def set_scaling(self, A):
        """Take D = |diag J| from an assembled Jacobian."""
        diag = A.getDiagonal()
        self.sqrt_d = np.sqrt(np.abs(diag.array_r))
        self.sqrt_d[self.sqrt_d == 0] = 1.0
        diag.destroy()

    def _norms(self, x_owned, b_owned):
        local = []
        for f in FIELDS:
            d = self.dofs[f]
            local += [np.sum(b_owned[d] ** 2), np.sum((b_owned[d] / self.sqrt_d[d]) ** 2),
                      np.sum((x_owned[d] * self.sqrt_d[d]) ** 2)]
        local = np.array(local)
        total = np.empty_like(local)
        self.comm.Allreduce(local, total, op=MPI.SUM)
        return np.sqrt(total).reshape(2, 3)

    def check(self, x_owned, b_owned):
        """Record one iterate; return True when every field has converged."""
        norms = self._norms(x_owned, b_owned)
        s_total = float(np.linalg.norm(norms[:, 2]))
        entry = {"residual": {}, "scaled_residual": {}, "relative": {}}
        ok = True
        for (si, r, s), f in zip(norms, FIELDS):
            entry["residual"][f] = float(si)
            entry["scaled_residual"][f] = float(r)
            # undefined (null in summary.json) while a field is still zero
            entry["relative"][f] = float(r / s) if s > 0 else (0.0 if r == 0 else None)
            ok &= bool(r <= self.rtol * s + self.atol * s_total)
        self.history.append(entry)
        return ok
