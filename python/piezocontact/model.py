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

from . import _compat as compat
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
# the elements (those ffcx compiles) and the reference points, by cell
from entry_points import DIMENSION, MIDPOINT, VERTICES, elements  # noqa: E402


def python_mesh(named):
    """dolfinx's Python Mesh around the C++ mesh of a NamedMesh, on the
    coordinate element of the forms."""
    cpp_mesh = named.mesh
    cell_name = compat.cell_name(cpp_mesh.topology)
    if cpp_mesh.geometry.dim != DIMENSION[cell_name]:  # the element's, and the kernels'
        raise ValueError(f"a mesh of {cell_name}s in {cpp_mesh.geometry.dim}D: "
                         f"expected {DIMENSION[cell_name]}D coordinates")
    coordinate, _ = elements(cell_name)
    return dmesh.Mesh(cpp_mesh, ufl.Mesh(coordinate))


def _constant(msh, shape):
    return fem.Constant(msh, np.zeros(shape))


def model_constants(msh, named, manufactured=False):
    """The Constants of the forms, zero: those shared by every term, each
    region's material and each named boundary's loads."""
    d = msh.geometry.dim
    shapes = dict(pf.constant_shapes(d))
    if manufactured:
        shapes.update(mms.constant_shapes())
    shared = {name: _constant(msh, shape) for name, shape in shapes.items()}
    materials = {region: {name: _constant(msh, shape)
                          for name, shape in pf.material_shapes(d).items()}
                 for region in named.region_of}
    loads = {boundary: {name: _constant(msh, shape) for name, shape in pf.load_shapes(d).items()}
             for boundary in named.tag_of}
    return shared, materials, loads


def set_constants(cfg, shared, materials, loads, source="config"):
    """Fill the Constants from a validated config, by the C++ core (as for a
    run)."""
    def cpp_map(constants):
        return {n: compat.cpp(c) for n, c in constants.items()}
    cpp.set_constants(json.dumps(cfg), cpp_map(shared),
                      {r: cpp_map(m) for r, m in materials.items()},
                      {b: cpp_map(m) for b, m in loads.items()}, source)


def _depends_on_state(form, x, x_prev, data):
    """Whether a form changes within a run: it involves x, x_prev or t."""
    if form.empty():
        return False
    state = {x, x_prev}
    return bool(state & set(form.coefficients())) or (
        "t" in data and data["t"] in form.constants())


def _mark(msh, dim, entities):
    """Tags marking `entities` with 1: the piece a term is integrated over."""
    entities = np.unique(np.asarray(entities, dtype=np.int32))
    return dmesh.meshtags(msh, dim, entities, np.ones_like(entities))


class JitModel:
    """The forms of a run and the objects they hold; `cpp_model()` hands
    them to the C++ core as lists of terms, one per region, named boundary
    and the contact facets (as the executable's compiled_model.cpp does);
    `F_whole`, `J_whole` are the same residual as one form on the mesh's own
    tags, for the reference engine. The hooks:
      extra_residual(u, phi, w, psi, data) -> UFL form added to F (J follows
        by differentiation); data: the shared Constants and, with one
        material, the material's (Bv, Av, e, beta);
      contact_law(r, c_p) -> UFL expression replacing the law p."""

    def __init__(self, named, cfg, extra_residual=None, contact_law=None):
        self.named = named
        self.mesh = python_mesh(named)
        msh = self.mesh
        d, tdim = msh.geometry.dim, msh.topology.dim
        cell_name = compat.cell_name(msh.topology)
        self.W = compat.functionspace(msh, elements(cell_name)[1])
        self.x = fem.Function(self.W, name="x")
        self.x_prev = fem.Function(self.W, name="x_prev")
        x, x_prev = self.x, self.x_prev
        manufactured = "manufactured" in cfg
        self.data, self.materials, self.loads = model_constants(msh, named, manufactured)
        data = self.data
        law = contact_law or pf.p
        y, dx_trial = ufl.TestFunction(self.W), ufl.TrialFunction(self.W)
        contact_names = [b for b, bc in cfg["boundaries"].items()
                         if bc.get("contact") and b in named.tag_of]
        self.contact_facets = np.unique(np.concatenate(
            [named.boundary_facets(b) for b in contact_names] + [np.zeros(0, np.int32)]))

        # The terms, each on its piece (dx(1), ds(1) of tags marking it)
        def dx_on(cells):
            return ufl.Measure("dx", domain=msh, subdomain_data=_mark(msh, tdim, cells))(1)

        def ds_on(facets):
            return ufl.Measure("ds", domain=msh, subdomain_data=_mark(msh, tdim - 1, facets))(1)

        F, J, L, J_state = [], [], [], []
        self.fields = []
        midpoint = np.array(MIDPOINT[cell_name])
        u, phi = ufl.split(x)
        u_prev, _ = ufl.split(x_prev)
        for region, mat in self.materials.items():
            cells = named.region_cells(region)
            dx_r = dx_on(cells)
            scope = {**data, **mat}
            region_residual = mms.region_residual if manufactured else pf.region_residual
            F_r = region_residual(x, x_prev, y, dx_r, mat, scope)
            F.append(F_r)
            J.append(pf.jacobian(pf.region_residual(x, x_prev, y, dx_r, mat, scope), x, dx_trial))
            L.append(pf.body_loads(y, dx_r, data)
                     + (mms.body_loads(y, dx_r, mat, data) if manufactured else 0))
            if manufactured:  # one region (checked): the exact solution's surface loads
                ds_all = ufl.Measure("ds", domain=msh)
                F.append(-mms.exterior_loads(y, ds_all, mat, data))
                L.append(mms.exterior_loads(y, ds_all, mat, data))
            self.fields.append((cells, fem.Expression(pf.electric_displacement(u, phi, mat), midpoint),
                                fem.Expression(pf.stress_voigt(u, pf.velocity(u, u_prev, data),
                                                               phi, mat), midpoint)))
        self.boundary_measures = {}
        for boundary, load in self.loads.items():
            ds_b = ds_on(named.boundary_facets(boundary))
            F.append(-pf.boundary_loads(y, ds_b, load))
            L.append(pf.boundary_loads(y, ds_b, load))
            self.boundary_measures[boundary] = fem.form(1.0 * ds_b)
        ds_c = ds_on(self.contact_facets)
        contact_residual = mms.contact_residual if manufactured else pf.contact_residual
        F.append(contact_residual(x, y, ds_c, data, law))
        J_contact = pf.jacobian(pf.contact_residual(x, y, ds_c, data, law), x, dx_trial)
        J.append(J_contact)
        J_state.append(J_contact)
        if manufactured:
            L.append(mms.contact_loads(y, ds_c, data, law))
        if extra_residual is not None:
            hook_data = {**data, **(next(iter(self.materials.values()))
                                    if len(self.materials) == 1 else {})}
            w, psi = ufl.split(y)
            extra = extra_residual(u, phi, w, psi, hook_data)
            F.append(extra)
            J_extra = pf.jacobian(extra, x, dx_trial)
            J.append(J_extra)
            # LU reuse compares the state-dependent part of J: the extra
            # term's derivative joins it unless it is constant in the run
            if _depends_on_state(ufl.algorithms.expand_derivatives(J_extra), x, x_prev, data):
                J_state.append(J_extra)
        self.F_terms, self.J_terms, self.J_state, self.L_terms = (
            [fem.form(f) for f in forms] for forms in (F, J, J_state, L))
        self.contact_force = [fem.form(pf.contact_force(x, ds_c, data, i, law)) for i in range(d)]
        self.contact_pressure = [fem.form(f) for f in
                                 pf.contact_pressure_moments(x, y, ds_c, data, law)]
        # every boundary with a potential condition is an electrode: its
        # charge, one term per region it bounds
        self.electrode_charge = {
            b: [fem.form(pf.electrode_charge(x, ds_on(named.boundary_facets_of(b, region)), mat))
                for region, mat in self.materials.items()]
            for b, bc in cfg["boundaries"].items()
            if ("potential" in bc or "floating" in bc) and b in named.tag_of}
        self._whole(cfg, manufactured, law, extra_residual)

        self.exact, self.squared_errors = None, {}
        if manufactured:
            u_ex, phi_ex, _ = mms.exact_solution(msh.ufl_domain(), data)
            vertices = np.array(VERTICES[cell_name])
            self.exact = (fem.Expression(u_ex, vertices), fem.Expression(phi_ex, vertices))
            self.squared_errors = {name: fem.form(f)
                                   for name, f in mms.squared_errors(x, data).items()}

    def _whole(self, cfg, manufactured, law, extra_residual):
        """The residual and its Jacobian as one form each, on the mesh's own
        cell and facet tags: the reference engine's view of the model."""
        named, msh, x, x_prev = self.named, self.mesh, self.x, self.x_prev
        y, dx_trial = ufl.TestFunction(self.W), ufl.TrialFunction(self.W)
        dx = ufl.Measure("dx", domain=msh, subdomain_data=compat.meshtags(named.cell_tags))
        ds = ufl.Measure("ds", domain=msh, subdomain_data=compat.meshtags(named.facet_tags))
        contact = [named.tag_of[b] for b, bc in cfg["boundaries"].items()
                   if bc.get("contact") and b in named.tag_of]
        if manufactured:
            (region, mat), = self.materials.items()
            F = mms.residual(x, x_prev, y, dx(named.region_of[region]), ds, mat, contact,
                             self.data, law)
        else:
            F = pf.residual(x, x_prev, y, dx, ds,
                            {named.region_of[r]: m for r, m in self.materials.items()},
                            {named.tag_of[b]: load for b, load in self.loads.items()},
                            contact, self.data, law)
        if extra_residual is not None:
            u, phi = ufl.split(x)
            w, psi = ufl.split(y)
            hook_data = {**self.data, **(next(iter(self.materials.values()))
                                         if len(self.materials) == 1 else {})}
            F = compat.one_subdomain_data(F + extra_residual(u, phi, w, psi, hook_data))
        self.F_whole = fem.form(F)
        self.J_whole = fem.form(pf.jacobian(F, x, dx_trial))

    def cpp_model(self):
        """The Model the C++ core runs: the C++ objects under the Python
        ones (compat.cpp), which stay alive in this JitModel."""
        c = compat.cpp

        def cpp_map(objects):
            return {name: c(obj) for name, obj in objects.items()}
        m = cpp.Model()
        m.mesh = self.named
        m.W, m.x, m.x_prev = c(self.W), c(self.x), c(self.x_prev)
        m.constants = cpp_map(self.data)
        m.materials = {r: cpp_map(mat) for r, mat in self.materials.items()}
        m.loads = {b: cpp_map(load) for b, load in self.loads.items()}
        m.contact_facets = self.contact_facets
        m.F, m.J, m.J_contact, m.L = ([c(f) for f in forms] for forms in
                                      (self.F_terms, self.J_terms, self.J_state, self.L_terms))
        m.contact_force = [c(f) for f in self.contact_force]
        fields = []
        for cells, D, stress in self.fields:
            f = cpp.RegionFields()
            f.cells, f.electric_displacement, f.stress = cells, c(D), c(stress)
            fields.append(f)
        m.fields = fields
        if self.exact:
            m.u_exact, m.phi_exact = (c(e) for e in self.exact)
        m.squared_errors = cpp_map(self.squared_errors)
        m.boundary_measures = cpp_map(self.boundary_measures)
        m.contact_pressure_load, m.contact_nodal_area = (c(f) for f in self.contact_pressure)
        m.electrode_charge = {b: [c(f) for f in forms]
                              for b, forms in self.electrode_charge.items()}
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
