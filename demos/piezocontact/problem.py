"""The discrete problem in dolfinx Python: the mixed P1 space on the mesh,
the runtime Constants and the forms of forms/piezo_forms.py, the BCs.
Mirrors cpp/problem.cpp; neither writes a term of the weak form itself."""

import sys
from pathlib import Path

import numpy as np
import ufl
from dolfinx import fem

from . import meshing
from .config import ConfigError
from .manufactured_solution import ManufacturedSolution, add_constants

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "forms"))
import piezo_forms as pf  # noqa: E402

def make_constants(msh, cfg, tag_of):
    """The runtime Constants of the forms, filled from the config."""
    d = {name: fem.Constant(msh, np.zeros(shape, dtype=np.float64))
         for name, shape in pf.constant_shapes().items()}
    mat = cfg["material"]
    d["Bv"].value[:] = mat["elastic"]
    d["Av"].value[:] = mat["viscosity"]
    d["e"].value[:] = mat["piezoelectric"]
    d["beta"].value[:] = mat["permittivity"]
    d["c_p"].value = cfg["contact"]["c_p"]
    d["g"].value = cfg["contact"]["gap"]
    d["k"].value = cfg["time"]["T"] / cfg["time"]["steps"]
    d["f0"].value[:] = cfg["loads"]["body_force"]
    d["q0"].value = cfg["loads"]["charge_density"]
    for name, bc in cfg["boundaries"].items():
        s = tag_of[name] - 1
        d["fF"].value[s, :] = bc.get("traction", [0.0, 0.0])
        d["qF"].value[s] = bc.get("surface_charge", 0.0)
        d["chi"].value[s] = 1.0 if bc.get("contact", False) else 0.0
    return d


class Problem:
    """Everything one run needs that depends on the config."""

    def __init__(self, cfg, comm, source="config", mesh_file=None):
        self.cfg = cfg
        self.comm = comm
        self.mesh, self.facet_tags, self.tag_of = meshing.build(cfg, comm, mesh_file, source)
        if len(self.tag_of) > pf.MAX_BOUNDARIES:
            raise ConfigError(f"{source}: mesh: {len(self.tag_of)} named boundaries, "
                              f"the forms support {pf.MAX_BOUNDARIES}")
        for name in cfg["boundaries"]:
            if name not in self.tag_of:
                raise ConfigError(f"{source}: boundaries.{name}: the mesh has no boundary "
                                  f"'{name}' (it has: {', '.join(sorted(self.tag_of))})")

        cell = self.mesh.ufl_cell()
        element = ufl.MixedElement([ufl.VectorElement("Lagrange", cell, 1),
                                    ufl.FiniteElement("Lagrange", cell, 1)])
        self.W = fem.FunctionSpace(self.mesh, element)
        self.x = fem.Function(self.W, name="x")
        self.x_prev = fem.Function(self.W, name="x_prev")

        self.data = make_constants(self.mesh, cfg, self.tag_of)
        # Sub-spaces: collapsed spaces and their dofs in W
        self.V_u, self.u_dofs = self.W.sub(0).collapse()
        self.V_phi, self.phi_dofs = self.W.sub(1).collapse()
        self.u_dofs, self.phi_dofs = np.asarray(self.u_dofs), np.asarray(self.phi_dofs)

        ds = ufl.Measure("ds", domain=self.mesh, subdomain_data=self.facet_tags)
        y = ufl.TestFunction(self.W)
        self.manufactured = None
        if "manufactured" in cfg:
            # its residual replaces the model's; its exact fields are the
            # "exact" Dirichlet data
            add_constants(self.mesh, self.data, cfg["manufactured"])
            self.manufactured = ManufacturedSolution(self.x, self.x_prev, y, ds, self.data,
                                                     self.V_u, self.V_phi)
            self.F_ufl = self.manufactured.F_ufl
        else:
            self.F_ufl = pf.residual(self.x, self.x_prev, y, ds, self.data)
        self.J_ufl = pf.jacobian(self.F_ufl, self.x, ufl.TrialFunction(self.W))
        self.contact_force_forms = [fem.form(pf.contact_force(self.x, ds, self.data, i))
                                    for i in range(2)]
        self.F_form = fem.form(self.F_ufl)
        self.bcs, self.clamped_dofs = self._dirichlet_bcs()
        # Collapsed copies of the solution, for evaluation and output
        self.u = fem.Function(self.V_u, name="u")
        self.phi = fem.Function(self.V_phi, name="phi")

        # Cell-wise post-processing fields (DG0), as in piezo_contact.ufl
        u, phi = ufl.split(self.x)
        u_prev, _ = ufl.split(self.x_prev)
        midpoint = np.array([[1.0 / 3.0, 1.0 / 3.0]])
        self.D_expr = fem.Expression(pf.electric_displacement(u, phi, self.data), midpoint)
        stress = pf.stress_voigt(u, pf.velocity(u, u_prev, self.data), phi, self.data)
        self.stress_expr = fem.Expression(stress, midpoint)

    def update_fields(self):
        """Copy the mixed solution into the collapsed u and phi."""
        self.u.x.array[:] = self.x.x.array[self.u_dofs]
        self.phi.x.array[:] = self.x.x.array[self.phi_dofs]

    def boundary_facets(self, name):
        return self.facet_tags.indices[self.facet_tags.values == self.tag_of[name]]

    def _dirichlet_bcs(self):
        """u and phi Dirichlet conditions on the collapsed sub-spaces (a
        Constant on a vector sub-space of a mixed space is not supported in
        0.5.2), per clamped boundary the W-dofs of each u component, and in
        self.bc_dofs the W-dofs of every condition."""
        bcs, clamped, self.bc_dofs = [], {}, []
        for name, bc in sorted(self.cfg["boundaries"].items()):
            facets = self.boundary_facets(name)
            if "displacement" in bc:
                if bc["displacement"] == "exact":
                    g = self.manufactured.u_exact  # updated every step
                else:
                    g = fem.Function(self.V_u)
                    g.x.array.reshape(-1, 2)[:] = bc["displacement"]
                dofs = fem.locate_dofs_topological((self.W.sub(0), self.V_u), 1, facets)
                bcs.append(fem.dirichletbc(g, dofs, self.W.sub(0)))
                self.bc_dofs.append(dofs[0])
                clamped[name] = [
                    fem.locate_dofs_topological(
                        (self.W.sub(0).sub(i), self.V_u.sub(i).collapse()[0]), 1, facets)[0]
                    for i in range(2)]
            if "potential" in bc:
                if bc["potential"] == "exact":
                    g = self.manufactured.phi_exact  # updated every step
                else:
                    g = fem.Function(self.V_phi)
                    g.x.array[:] = bc["potential"]
                dofs = fem.locate_dofs_topological((self.W.sub(1), self.V_phi), 1, facets)
                bcs.append(fem.dirichletbc(g, dofs, self.W.sub(1)))
                self.bc_dofs.append(dofs[0])
        return bcs, clamped
