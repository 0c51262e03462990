"""Run outputs, same layout as the C++ solver (cpp/output.cpp):
  DIR/summary.json           the run's record, rewritten atomically each step
  DIR/solution.xdmf (+.h5)   u, phi (vertex) and D, stress (cell) for ParaView
  DIR/nodal/{u,phi}_NNNN.npy nodal values [x, y, value...] gathered on rank 0,
                             the exact data the C++/Python comparison reads
"""

import json
import math
import os
from pathlib import Path

import numpy as np
from dolfinx import fem, io


def _finite(obj):
    """NaN/inf become null, as the C++ writer does: summary.json stays JSON."""
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, dict):
        return {k: _finite(v) for k, v in obj.items()}
    if isinstance(obj, list):
        return [_finite(v) for v in obj]
    return obj


def write_json_atomic(path, obj):
    """Write-then-rename: an interrupted run never leaves a half-written file."""
    path = Path(path)
    tmp = path.with_name("." + path.name + ".tmp")
    tmp.write_text(json.dumps(_finite(obj), indent=1, allow_nan=False))
    os.replace(tmp, path)


def gather_nodal(function, comm):
    """[x, y, values...] of the owned dofs of a collapsed P1 function, on rank 0."""
    V = function.function_space
    n = V.dofmap.index_map.size_local
    bs = V.dofmap.index_map_bs
    rows = np.column_stack([V.tabulate_dof_coordinates()[:n, :2],
                            function.x.array[:n * bs].reshape(n, bs)])
    parts = comm.gather(rows, root=0)
    return np.vstack(parts) if comm.rank == 0 else None


class Writer:
    def __init__(self, problem, out_dir, cfg):
        self.problem = problem
        self.comm = problem.comm
        self.dir = Path(out_dir)
        self.nodal = cfg["output"]["nodal"]
        if self.comm.rank == 0:
            (self.dir / "nodal").mkdir(parents=True, exist_ok=True)
        self.comm.barrier()
        self.xdmf = None
        if cfg["output"]["xdmf"]:
            dg0 = ("DG", 0)
            self.D = fem.Function(fem.VectorFunctionSpace(problem.mesh, dg0), name="D")
            self.stress = fem.Function(fem.VectorFunctionSpace(problem.mesh, dg0, dim=3),
                                       name="stress_voigt")
            self.xdmf = self.dir / "solution.xdmf"
            with io.XDMFFile(self.comm, str(self.xdmf), "w") as f:
                f.write_mesh(problem.mesh)

    def write_step(self, step, t, final):
        """Write the state of problem.u, problem.phi (updated by the caller)."""
        u, phi = self.problem.u, self.problem.phi
        if self.xdmf is not None:
            self.D.interpolate(self.problem.D_expr)
            self.stress.interpolate(self.problem.stress_expr)
            # open and close at every step: a killed run leaves a file that is
            # complete up to its last step (HDF5 flushed, XML rewritten)
            with io.XDMFFile(self.comm, str(self.xdmf), "a") as xdmf:
                for f in (u, phi, self.D, self.stress):
                    xdmf.write_function(f, t)
        if self.nodal == "all" or (self.nodal == "final" and final):
            for name, f in (("u", u), ("phi", phi)):
                rows = gather_nodal(f, self.comm)
                if self.comm.rank == 0:
                    np.save(self.dir / "nodal" / f"{name}_{step:04d}.npy", rows)

    def close(self):
        """Nothing is held open between steps."""
