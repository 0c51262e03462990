"""Manufactured-solution runs (config key "manufactured") in dolfinx Python:
the residual with the loads of the exact solution, the exact fields as
Dirichlet data, the errors of a step. Mirrors cpp/manufactured_solution.cpp;
the physics is forms/manufactured.py's."""

import sys
from pathlib import Path

import numpy as np
from dolfinx import fem
from mpi4py import MPI

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "forms"))
import manufactured as mms  # noqa: E402


def add_constants(msh, data, settings):
    """The Constants manufactured.py adds, with the switches of the config."""
    for name, shape in mms.constant_shapes().items():
        data[name] = fem.Constant(msh, np.zeros(shape, dtype=np.float64))
    data["space_smooth"].value = 1.0 if settings["space"] == "smooth" else 0.0
    data["time_smooth"].value = 1.0 if settings["time"] == "smooth" else 0.0


class ManufacturedSolution:
    def __init__(self, x, x_prev, y, ds, data, V_u, V_phi):
        self.data = data
        self.F_ufl = mms.residual(x, x_prev, y, ds, data)
        self._squared_errors = {name: fem.form(f)
                                for name, f in mms.squared_errors(x, data).items()}
        u, phi, _ = mms.exact_solution(x.ufl_domain(), data)
        self._u_expr = fem.Expression(u, V_u.element.interpolation_points())
        self._phi_expr = fem.Expression(phi, V_phi.element.interpolation_points())
        self.u_exact = fem.Function(V_u, name="u_exact")
        self.phi_exact = fem.Function(V_phi, name="phi_exact")
        self.set_time(0.0)

    def set_time(self, t):
        """Set the time of the loads and interpolate the exact fields at t."""
        self.data["t"].value = t
        self.u_exact.interpolate(self._u_expr)
        self.phi_exact.interpolate(self._phi_expr)

    def errors(self, comm):
        """L2 and H1 norms of the error at the current time, on every rank."""
        return {name: float(np.sqrt(comm.allreduce(fem.assemble_scalar(f), op=MPI.SUM)))
                for name, f in self._squared_errors.items()}
