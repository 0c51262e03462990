"""The model of a run in dolfinx Python: the mixed space, the Constants and
the forms of forms/ (JIT-compiled), bound to a mesh built by the C++ core.

This is the Python counterpart of the executable's `compiled_model.cpp`: the
same UFL, compiled at run time, so that a script can change the physics with
no rebuild (`extra_residual`, `contact_law`)."""

import json
import os
import sys
from pathlib import Path

import numpy as np
import ufl
from dolfinx import fem
from dolfinx import mesh as dmesh

from . import cpp


def _forms_dir():
    """$PIEZOCONTACT_FORMS (an edited copy of forms/, used with no rebuild),
    else forms/ as installed with the package, or the source tree's."""
    here = Path(__file__).resolve().parent
    chosen = os.environ.get("PIEZOCONTACT_FORMS")
    for d in ([Path(chosen)] if chosen else []) + [here / "forms", here.parents[1] / "forms"]:
        if (d / "piezo_forms.py").is_file():
            return d
    raise ImportError(f"forms/piezo_forms.py not found next to {here}")


sys.path.insert(0, str(_forms_dir()))
import manufactured as mms  # noqa: E402
import piezo_forms as pf  # noqa: E402


def python_mesh(named):
    """dolfinx's Python Mesh around the C++ mesh of a NamedMesh."""
    cpp_mesh = named.mesh
    cell = ufl.Cell(cpp_mesh.topology.cell_name(), geometric_dimension=cpp_mesh.geometry.dim)
    return dmesh.Mesh(cpp_mesh, ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1)))


def zero_constants(msh, manufactured=False):
    """The Constants of the forms (and of a manufactured solution), zero."""
    shapes = dict(pf.constant_shapes())
    if manufactured:
        shapes.update(mms.constant_shapes())
    return {name: fem.Constant(msh, np.zeros(shape)) for name, shape in shapes.items()}


def constants(msh, cfg, tag_of, source="config"):
    """The Constants of the forms on `msh`, filled from a validated config by
    the C++ core (as for a run)."""
    data = zero_constants(msh, "manufactured" in cfg)
    cpp.set_constants(json.dumps(cfg), tag_of, {n: c._cpp_object for n, c in data.items()},
                      source)
    return data


def _depends_on_state(form, x, x_prev, data):
    """Whether a form changes within a run: it involves x, x_prev or t."""
    if form.empty():
        return False
    state = {x, x_prev}
    return bool(state & set(form.coefficients())) or (
        "t" in data and data["t"] in form.constants())


class JitModel:
    """The forms of a run and the objects they hold; `cpp_model()` hands
    them to the C++ core. The hooks:
      extra_residual(u, phi, w, psi, data) -> UFL form added to F (J follows
        by differentiation);
      contact_law(r, c_p) -> UFL expression replacing the law p."""

    def __init__(self, named, cfg, extra_residual=None, contact_law=None):
        self.named = named
        self.mesh = python_mesh(named)
        msh = self.mesh
        cell = msh.ufl_cell()
        element = ufl.MixedElement([ufl.VectorElement("Lagrange", cell, 1),
                                    ufl.FiniteElement("Lagrange", cell, 1)])
        self.W = fem.FunctionSpace(msh, element)
        self.x = fem.Function(self.W, name="x")
        self.x_prev = fem.Function(self.W, name="x_prev")
        manufactured = "manufactured" in cfg
        self.data = zero_constants(msh, manufactured)
        law = contact_law or pf.p

        ds = ufl.Measure("ds", domain=msh, subdomain_data=named.facet_tags)
        y, dx_trial = ufl.TestFunction(self.W), ufl.TrialFunction(self.W)
        residual = mms.residual if manufactured else pf.residual
        F = residual(self.x, self.x_prev, y, ds, self.data, law)
        J_state = pf.contact_jacobian(self.x, y, dx_trial, ds, self.data, law)
        if extra_residual is not None:
            u, phi = ufl.split(self.x)
            w, psi = ufl.split(y)
            extra = extra_residual(u, phi, w, psi, self.data)
            F = F + extra
            # LU reuse compares the state-dependent part of J: the extra
            # term's derivative joins it unless it is constant in the run
            J_extra = ufl.algorithms.expand_derivatives(pf.jacobian(extra, self.x, dx_trial))
            if _depends_on_state(J_extra, self.x, self.x_prev, self.data):
                J_state = J_state + pf.jacobian(extra, self.x, dx_trial)
        self.F_ufl = F
        self.J_ufl = pf.jacobian(F, self.x, dx_trial)
        self.F, self.J, self.J_contact = fem.form([F, self.J_ufl, J_state])
        self.L = fem.form(mms.applied_loads(y, ds, self.data, law) if manufactured
                          else pf.applied_loads(y, ds, self.data))
        self.contact_force = [fem.form(pf.contact_force(self.x, ds, self.data, i, law))
                              for i in range(msh.geometry.dim)]
        self.boundary_measures = {name: fem.form(1.0 * ds(tag))
                                  for name, tag in named.tag_of.items()}

        u, phi = ufl.split(self.x)
        u_prev, _ = ufl.split(self.x_prev)
        midpoint = np.array([[1.0 / 3.0, 1.0 / 3.0]])
        self.electric_displacement = fem.Expression(
            pf.electric_displacement(u, phi, self.data), midpoint)
        self.stress = fem.Expression(
            pf.stress_voigt(u, pf.velocity(u, u_prev, self.data), phi, self.data), midpoint)
        self.exact, self.squared_errors = None, {}
        if manufactured:
            u_ex, phi_ex, _ = mms.exact_solution(msh.ufl_domain(), self.data)
            vertices = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
            self.exact = (fem.Expression(u_ex, vertices), fem.Expression(phi_ex, vertices))
            self.squared_errors = {name: fem.form(f)
                                   for name, f in mms.squared_errors(self.x, self.data).items()}

    def cpp_model(self):
        m = cpp.Model()
        m.mesh = self.named
        m.W = self.W._cpp_object
        m.x = self.x._cpp_object
        m.x_prev = self.x_prev._cpp_object
        m.constants = {name: c._cpp_object for name, c in self.data.items()}
        m.F, m.J, m.J_contact, m.L = self.F, self.J, self.J_contact, self.L
        m.contact_force = self.contact_force
        m.electric_displacement = self.electric_displacement._cpp_object
        m.stress = self.stress._cpp_object
        if self.exact:
            m.u_exact, m.phi_exact = (e._cpp_object for e in self.exact)
        m.squared_errors = self.squared_errors
        m.boundary_measures = self.boundary_measures
        return m


def factory(extra_residual=None, contact_law=None, keep=None):
    """A model factory for the C++ driver: (NamedMesh, config text) -> Model.
    The JitModel is appended to `keep` (its Python objects must outlive the
    run, and the reference engine works on them)."""
    def make(named, cfg_text):
        model = JitModel(named, json.loads(cfg_text), extra_residual, contact_law)
        if keep is not None:
            keep.append(model)
        return model.cpp_model()
    return make
