"""Per-step quantities of interest, as cpp/diagnostics.cpp computes them:
probe values, the contact resultant and the largest u.nu - g on Gamma_C (the
reactions come from the residual: twin._Problem)."""

import numpy as np
from dolfinx import fem, geometry
from dolfinx import cpp as _cpp
from mpi4py import MPI

from .config import ConfigError, _fmt


class Probes:
    """Point evaluation of (u, phi); each point is evaluated on the lowest
    rank that holds a cell containing it."""

    def __init__(self, problem, points, source="config"):
        msh, comm = problem.mesh, problem.comm
        self.points = np.zeros((len(points), 3))
        self.points[:, :2] = points
        tree = geometry.BoundingBoxTree(msh, msh.topology.dim)
        candidates = geometry.compute_collisions(tree, self.points)
        colliding = geometry.compute_colliding_cells(msh, candidates, self.points)
        cells = np.full(len(points), -1, dtype=np.int32)
        for i in range(len(points)):
            links = colliding.links(i)
            if len(links) > 0:
                cells[i] = links[0]  # a ghost cell is fine: ghosts are up to date
        have = np.where(cells >= 0, comm.rank, comm.size).astype(np.int32)
        owner = np.empty_like(have)
        comm.Allreduce(have, owner, op=MPI.MIN)
        for i, o in enumerate(owner):
            if o == comm.size:
                where = _fmt([float(v) for v in points[i]])
                raise ConfigError(f"{source}: probes[{i}] = {where}: outside the mesh")
        self.mine = np.flatnonzero(owner == comm.rank)
        self.cells = cells[self.mine]
        self.comm = comm

    def evaluate(self, u, phi):
        """[(u_x, u_y, phi)] for every probe, identical on all ranks."""
        values = np.zeros((len(self.points), 3))
        if len(self.mine):
            pts = self.points[self.mine]
            values[self.mine, :2] = u.eval(pts, self.cells).reshape(len(pts), 2)
            values[self.mine, 2] = phi.eval(pts, self.cells).reshape(len(pts))
        total = np.empty_like(values)
        self.comm.Allreduce(values, total, op=MPI.SUM)
        return total


class ContactGeometry:
    """Vertices of the contact facets, their cells and outward unit normals."""

    def __init__(self, problem):
        msh = problem.mesh
        tdim = msh.topology.dim
        chi = problem.data["chi"].value
        contact_tags = [s + 1 for s in range(len(chi)) if chi[s] > 0]
        facets = problem.facet_tags.indices[np.isin(problem.facet_tags.values, contact_tags)]
        msh.topology.create_connectivity(tdim - 1, tdim)
        f_to_c = msh.topology.connectivity(tdim - 1, tdim)
        cells = np.array([f_to_c.links(f)[0] for f in facets], dtype=np.int32)
        x = msh.geometry.x[:, :2]
        fv = x[_cpp.mesh.entities_to_geometry(msh._mesh, tdim - 1, facets, False)] if len(facets) else \
            np.zeros((0, 2, 2))
        cv = x[_cpp.mesh.entities_to_geometry(msh._mesh, tdim, cells, False)] if len(cells) else \
            np.zeros((0, 3, 2))
        t = fv[:, 1] - fv[:, 0]
        n = np.column_stack([t[:, 1], -t[:, 0]]) / np.linalg.norm(t, axis=1)[:, None]
        outward = np.sum(n * (fv[:, 0] - cv.mean(axis=1)), axis=1) > 0
        n[~outward] *= -1
        self.points = np.zeros((2 * len(facets), 3))
        self.points[:, :2] = fv.reshape(-1, 2)
        self.cells = np.repeat(cells, 2)
        self.normals = np.repeat(n, 2, axis=0)
        self.comm = problem.comm

    def max_normal_gap(self, u, gap):
        """Largest u.nu - g over Gamma_C (None without a contact boundary)."""
        local = -np.inf
        if len(self.cells):
            values = u.eval(self.points, self.cells).reshape(len(self.points), 2)
            local = float(np.max(np.sum(values * self.normals, axis=1)) - gap)
        largest = self.comm.allreduce(local, op=MPI.MAX)
        return None if largest == -np.inf else largest


def contact_force(problem):
    return [problem.comm.allreduce(fem.assemble_scalar(f), op=MPI.SUM)
            for f in problem.contact_force_forms]
