"""The model of a run in dolfinx Python: the mixed space, the Constants and
the forms of forms/ (JIT-compiled), bound to a mesh built by the C++ core.

This is the Python counterpart of the executable's `compiled_model.cpp`: one
loop over the same catalogue of terms (forms/terms.py), compiled at run
time, so that a script can change the physics with no rebuild
(`extra_residual`, `contact_law`)."""

import collections
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
import entry_points  # noqa: E402
import piezo_forms as pf  # noqa: E402
import terms  # noqa: E402
# the elements (those ffcx compiles), by cell
from entry_points import DIMENSION, elements, points  # noqa: E402


def python_mesh(named, given=None):
    """dolfinx's Python Mesh around the C++ mesh of a NamedMesh, on the
    coordinate element of the forms; `given`: the user's own Python Mesh of
    it (piezocontact.Problem), so that their UFL data and the Functions
    returned live on their mesh."""
    if given is not None:
        return given
    cpp_mesh = named.mesh
    cell_name = compat.cell_name(cpp_mesh.topology)
    if cpp_mesh.geometry.dim != DIMENSION[cell_name]:  # the element's, and the kernels'
        raise ValueError(f"a mesh of {cell_name}s in {cpp_mesh.geometry.dim}D: "
                         f"expected {DIMENSION[cell_name]}D coordinates")
    coordinate = elements(cell_name)[0]
    return dmesh.Mesh(cpp_mesh, ufl.Mesh(coordinate))


def ufl_keys(dim):
    """{config key: shape} of the data a UFL expression may give (the
    `data` hook's keys, from the forms' Datum declarations): the shared
    data that vary in space but the gap ("loads.body_force"), and a
    boundary's ("boundaries.NAME." + "traction")."""
    groups = entry_points.data(dim, False)
    shared = {d.key: d.shape for n, d in groups["shared"].items() if d.spatial and n != "g"}
    load = {"boundaries.NAME." + d.key: d.shape for d in groups["load"].values()
            if d.spatial and "." not in d.key}
    return {**shared, **load}


def _constant(msh, shape):
    return fem.Constant(msh, np.zeros(shape))


def model_constants(msh, named, manufactured=False, axisymmetric=False):
    """The Constants of the forms, zero: those shared by every term, each
    region's material and each named boundary's loads."""
    groups = entry_points.data(msh.geometry.dim, manufactured, axisymmetric)

    def zeros(group):
        return {name: _constant(msh, datum.shape) for name, datum in groups[group].items()}
    return (zeros("shared"), {region: zeros("material") for region in named.region_of},
            {boundary: zeros("load") for boundary in named.tag_of})


def sources(dim, manufactured=False, fields=False):
    """Where each Constant's value comes from (the forms' declarations), as
    the core takes them (`fields`: the spatial data have their fields)."""
    out = []
    for group, data in entry_points.data(dim, manufactured).items():
        for name, datum in data.items():
            s = cpp.ConstantSource()
            s.group, s.name, s.key, s.timed = group, name, datum.key or "", datum.timed
            s.flag = datum.flag or ""
            s.field = pf.field_name(name) if datum.spatial and fields else ""
            out.append(s)
    return out


def needs_fields(dim, spec):
    """Whether the config gives some datum that has a field by expressions
    (the forms then carry the fields; a manufactured run has none)."""
    data = entry_points.data(dim, False)
    return not spec.manufactured and any(
        datum.spatial and datum.key in spec.expression_keys
        for group in data.values() for datum in group.values())


def model_fields(msh, named, degrees):
    """The zero fields of the data that may vary in space (the core
    interpolates a datum given by expressions into its field): the shared
    data's, and each named boundary's loads', on one space per shape."""
    groups = entry_points.data(msh.geometry.dim, False)
    cell_name = compat.cell_name(msh.topology)
    spaces = {}

    def space(shape):
        if shape not in spaces:
            element = entry_points.lagrange(cell_name, entry_points.field_degree(degrees), shape)
            spaces[shape] = compat.functionspace(msh, element)
        return spaces[shape]

    def zeros(group):
        return {name: fem.Function(space(datum.shape), name=pf.field_name(name))
                for name, datum in groups[group].items() if datum.spatial}
    return zeros("shared"), {boundary: zeros("load") for boundary in named.tag_of}


def set_constants(cfg, shared, materials, loads):
    """Fill the Constants from a validated config, by the C++ core (as for a
    run)."""
    def cpp_map(constants):
        return {n: compat.cpp(c) for n, c in constants.items()}
    m = cpp.Model()
    m.constants = cpp_map(shared)
    m.materials = {r: cpp_map(mat) for r, mat in materials.items()}
    m.loads = {b: cpp_map(load) for b, load in loads.items()}
    # the coordinates' length: UFL 2025 made geometric_dimension a property
    gdim = ufl.SpatialCoordinate(shared["k"].ufl_domain()).ufl_shape[0]
    m.sources = sources(gdim, "t" in shared)
    cpp.set_constants(json.dumps(cfg), m)


def _mark(msh, dim, entities):
    """Tags marking `entities` with 1: the piece a term is integrated over."""
    entities = np.unique(np.asarray(entities, dtype=np.int32))
    return dmesh.meshtags(msh, dim, entities, np.ones_like(entities))


Spec = collections.namedtuple("Spec", "manufactured contact electrodes boundary_keys degrees "
                              "axisymmetric expression_keys obstacles with_obstacle linearised")


class JitModel:
    """The forms of a run and the objects they hold: one loop over the
    catalogue of terms (forms/terms.py), each term on every piece of its
    kind. `cpp_model()` hands them to the C++ core (as the executable's
    compiled_model.cpp does); `F_whole`, `J_whole` are the same residual as
    one form on the mesh's own tags, for the reference engine. The hooks:
      extra_residual(u, phi, w, psi, data) -> UFL form added to F (J follows
        by differentiation); data: the shared Constants, with one material
        the material's (Bv, Av, e, beta), and "weight": the formulation's
        weight of an integral (2 pi r in axisymmetry, where a hook's
        integrals are per revolution as the model's are, 1 otherwise);
      contact_law(r, c_p) -> UFL expression replacing the law p;
      data: {config key: f(x, t)}, a datum that may vary in space given as
        a UFL expression of x = ufl.SpatialCoordinate (x[0] = r in
        axisymmetry) and the time t (a Constant the core sets every step),
        evaluated by the forms at their quadrature points; it adds to what
        the config gives for that key. Keys: "loads.body_force",
        "loads.charge_density", "boundaries.NAME.traction",
        "boundaries.NAME.surface_charge" (a gap that varies: an expression
        in the config); and "boundaries.NAME.contact.obstacle": the signed
        distance d(x, t) to an obstacle of any shape (>= 0 outside it; the
        contact normal is its normalised gradient), which replaces the
        geometry of the obstacle the config gives that boundary (its method
        and law stay the config's)."""

    def __init__(self, named, spec, extra_residual=None, contact_law=None, data=None,
                 mesh=None):
        self.named = named
        # a copy: the core's ModelSpec lives for the factory's call only
        self.spec = Spec(spec.manufactured, list(spec.contact), list(spec.electrodes),
                         {b: list(keys) for b, keys in spec.boundary_keys.items()},
                         tuple(spec.degrees), spec.axisymmetric, list(spec.expression_keys),
                         list(spec.obstacles), list(spec.with_obstacle), spec.linearised)
        self.mesh = msh = python_mesh(named, mesh)
        cell_name = compat.cell_name(msh.topology)
        _, mixed, pressure = elements(cell_name, *spec.degrees)
        self.W = compat.functionspace(msh, mixed)
        self.P = compat.functionspace(msh, pressure)  # the contact pressure's
        self.x = fem.Function(self.W, name="x")
        self.x_prev = fem.Function(self.W, name="x_prev")
        # the velocity a linearisation holds (dynamic analyses only)
        self.x_dot = fem.Function(self.W, name="x_dot") if spec.linearised else None
        self.data, self.materials, self.loads = model_constants(msh, named, spec.manufactured,
                                                                spec.axisymmetric)
        fields = needs_fields(msh.geometry.dim, self.spec)
        self.sources = sources(msh.geometry.dim, spec.manufactured, fields)
        self.fields, self.load_fields = (model_fields(msh, named, spec.degrees) if fields
                                         else ({}, {b: {} for b in named.tag_of}))
        self.terms = terms.catalogue(msh.geometry.dim, spec.manufactured)
        self.kin = pf.Kinematics(spec.axisymmetric)
        self.ufl_data = self._ufl_data(data or {})
        self.context = terms.Context(self.x, self.x_prev, ufl.TestFunction(self.W),
                                     pf.with_fields(self.data, self._fields_of("")),
                                     law=contact_law or pf.p, q=ufl.TestFunction(self.P),
                                     kin=self.kin)
        self.dx_trial = ufl.TrialFunction(self.W)
        self.contact_facets = np.unique(np.concatenate(
            [named.boundary_facets(b) for b in spec.contact] + [np.zeros(0, np.int32)]))
        self.points = {kind: np.array(points(kind, cell_name, self.spec.degrees))
                       for kind in ("midpoint", "u_nodes", "phi_nodes")}
        self.F, self.J, self.J_state, self.L = [], [], [], []
        self.K, self.C, self.M = [], [], []  # a linearisation's (spec.linearised)
        self.outputs = {}  # slot -> [(piece name, term name, form or expression)]
        for term in self.terms:
            for name, c in self._instances(term):
                self._place(term, name, c)
        self._hook(extra_residual)
        self._extra_residual, self._whole_forms = extra_residual, None

    # -- the pieces
    def _dx_on(self, cells):
        tdim = self.mesh.topology.dim
        return ufl.Measure("dx", domain=self.mesh, subdomain_data=_mark(self.mesh, tdim, cells))(1)

    def _ds_on(self, facets):
        tdim = self.mesh.topology.dim
        return ufl.Measure("ds", domain=self.mesh,
                           subdomain_data=_mark(self.mesh, tdim - 1, facets))(1)

    def _load(self, boundary):
        """A boundary's data as its terms see them (Constants and fields,
        and the hook's distance to its obstacle)."""
        data = pf.with_fields(self.loads[boundary], self._fields_of(boundary))
        if (distance := self.ufl_data.get(boundary, {}).get("distance")) is not None:
            data["distance"] = distance
        return data

    def _fields_of(self, piece):
        """The parts that vary in space of a piece's data ("": the shared
        ones): the fields of the config's expressions plus the hook's UFL."""
        fields = dict(self.fields if piece == "" else self.load_fields[piece])
        for name, expr in self.ufl_data.get(piece, {}).items():
            fields[name] = fields[name] + expr if name in fields else expr
        return fields

    def _ufl_data(self, data):
        """{piece ("" shared, or a boundary): {datum name: UFL expression}}
        of the `data` hook; the time Constant "t" joins the shared data."""
        groups = entry_points.data(self.mesh.geometry.dim, False)
        # the gap stays the config's (an expression there): the core reports
        # the penetration u.nu - g with the fields it interpolates
        shared = {d.key: n for n, d in groups["shared"].items() if d.spatial and n != "g"}
        load = {d.key: n for n, d in groups["load"].items() if d.spatial}
        out = {"": {}}
        if data and "t" not in self.data:
            self.data["t"] = _constant(self.mesh, ())
            s = cpp.ConstantSource()
            s.group, s.name = "shared", "t"
            self.sources.append(s)
        x = ufl.SpatialCoordinate(self.mesh)
        for key, f in data.items():
            parts = key.split(".")
            if parts[0] == "boundaries" and parts[2:] == ["contact", "obstacle"]:
                out.setdefault(parts[1], {})["distance"] = self._distance(key, f(x, self.data["t"]))
                continue
            if key in shared:
                piece, name = "", shared[key]
                shape = groups["shared"][name].shape
            elif len(parts) == 3 and parts[0] == "boundaries" and parts[2] in load:
                if parts[1] not in self.loads:
                    raise ValueError(f"data: {key}: the mesh has no boundary {parts[1]!r}")
                piece, name = parts[1], load[parts[2]]
                shape = groups["load"][name].shape
            else:
                raise ValueError(f"data: {key!r}: not a datum that varies in space (one of "
                                 f"{', '.join(sorted(shared))}, boundaries.NAME."
                                 f"{{{', '.join(sorted(load))}}}, "
                                 "boundaries.NAME.contact.obstacle)")
            expr = ufl.as_ufl(f(x, self.data["t"]))
            if expr.ufl_shape != shape:
                raise ValueError(f"data: {key}: a UFL expression of shape {expr.ufl_shape}, "
                                 f"expected {shape}")
            out.setdefault(piece, {})[name] = expr
        return out

    def _distance(self, key, d):
        """The hook's signed distance to a boundary's obstacle, checked."""
        boundary = key.split(".")[1]
        if boundary not in self.spec.with_obstacle:
            raise ValueError(
                f"data: {key}: the boundary has no obstacle in the config (give it \"contact\": "
                "{\"obstacle\": ...} with the method: the distance replaces the obstacle's "
                "geometry)")
        d = ufl.as_ufl(d)
        if d.ufl_shape != ():
            raise ValueError(f"data: {key}: a signed distance is a scalar UFL expression, "
                             f"not of shape {d.ufl_shape}")
        return d

    def _sets(self, boundary, key):
        return key in self.spec.boundary_keys.get(boundary, [])

    def _instances(self, term):
        """(piece name, context on the piece) of every instance of a term,
        in a fixed order (compiled_model.cpp's)."""
        c, named = self.context, self.named
        one = next(iter(self.materials.values())) if len(self.materials) == 1 else None
        if term.piece == "region":
            return [(r, c.on(self._dx_on(named.region_cells(r)), mat=mat))
                    for r, mat in self.materials.items()]
        if term.piece == "boundary":
            return [(b, c.on(self._ds_on(named.boundary_facets(b)), load=self._load(b)))
                    for b in self.loads
                    if term.where is None or self._sets(b, term.where)]
        if term.piece == "contact":
            return [("", c.on(self._ds_on(self.contact_facets)))]
        if term.piece == "electrode":  # one term per region it bounds
            return [(b, c.on(self._ds_on(named.boundary_facets_of(b, r)), mat=mat))
                    for b in self.spec.electrodes for r, mat in self.materials.items()]
        if term.piece == "obstacle":  # one term per region its facets bound
            return [(b if not term.expression else (b, r),
                     c.on(self._ds_on(named.boundary_facets_of(b, r)), mat=mat, load=self._load(b)))
                    for b in self.spec.obstacles for r, mat in self.materials.items()]
        if term.piece == "exterior":  # a manufactured run has one material (checked)
            return [("", c.on(ufl.Measure("ds", domain=self.mesh), mat=one))]
        return [("", c.on(ufl.Measure("dx", domain=self.mesh)))]  # mesh

    def _place(self, term, name, c):
        if term.expression:
            self.outputs.setdefault(term.slot, []).append(
                (name, term.name, fem.Expression(term.build(c), self.points[term.points])))
            if term.piece == "obstacle":  # the facets the expression is evaluated on
                b, r = name
                self.outputs[term.slot][-1] = (b, term.name, self.outputs[term.slot][-1][2],
                                               self.named.boundary_facets_of(b, r))
            return
        if term.role == "M":
            if self.spec.linearised:
                self.M.append(fem.form(terms.mass(term, c, self.dx_trial)))
            return
        form = term.build(c)
        if term.role == "output":
            self.outputs.setdefault(term.slot, []).append((name, term.name, fem.form(form)))
            return
        (self.F if term.role == "F" else self.L).append(fem.form(form))
        J = terms.jacobian(term, c, self.dx_trial) if term.role == "F" else None
        if J is not None:
            self._jacobian(J, terms.depends_on_state(J, c))
            if self.spec.linearised:
                self._linearised(term, c)

    def _linearised(self, term, c):
        """A residual term's stiffness (its own form, or its Jacobian's) and
        damping (terms.linearised)."""
        forms = terms.linearised(term, c, self.x_dot, self.dx_trial)
        self.K.append(fem.form(forms["K"]) if forms["K"] is not None else self.J[-1])
        if forms["C"] is not None:
            self.C.append(fem.form(forms["C"]))

    def _jacobian(self, J, state):
        self.J.append(fem.form(J))
        if state:  # LU reuse compares the state-dependent part of J
            self.J_state.append(self.J[-1])

    def _hook_data(self):
        one = next(iter(self.materials.values())) if len(self.materials) == 1 else {}
        weight = self.kin.weight(self.mesh.ufl_domain()) if self.kin.axisymmetric else 1.0
        return {**pf.with_fields(self.data, self._fields_of("")), **one, "weight": weight}

    def _hook(self, extra_residual):
        """The script's extra residual term, on the whole mesh."""
        if extra_residual is None:
            return
        u, phi = ufl.split(self.x)
        w, psi = ufl.split(self.context.y)
        extra = extra_residual(u, phi, w, psi, self._hook_data())
        self.F.append(fem.form(extra))
        J = pf.jacobian(extra, self.x, self.dx_trial)
        if not ufl.algorithms.expand_derivatives(J).empty():
            self._jacobian(J, terms.depends_on_state(J, self.context))
            if self.spec.linearised:  # its stiffness: a user term has no velocity
                self.K.append(self.J[-1])

    @property
    def F_whole(self):
        """The residual as one form (the reference engine's: _whole)."""
        return self._whole_pair()[0]

    @property
    def J_whole(self):
        """Its Jacobian, one form."""
        return self._whole_pair()[1]

    def _whole_pair(self):
        if self._whole_forms is None:
            self._whole_forms = self._whole(self._extra_residual)
        return self._whole_forms

    def _whole(self, extra_residual):
        """The residual and its Jacobian as one form each, on the mesh's own
        cell and facet tags: the reference engine's view of the model (the
        same terms, summed by UFL rather than by the core). Built on demand:
        only the reference engine needs it (it has no pieces of a boundary
        and a region: _material_of)."""
        return self._whole_sum(self.context, extra_residual)

    def linearised_whole(self):
        """(K, C, M) as one form each: the reference engine's view of the
        linearisation (terms.linearised), summed by UFL."""
        c = self.context.linearised(self.x_dot)
        F = self._whole_sum(c, self._extra_residual, forms=False)
        named, msh = self.named, self.mesh
        dx = ufl.Measure("dx", domain=msh, subdomain_data=compat.meshtags(named.cell_tags))
        M = sum(pf.inertia(self.x, c.y, c.on(dx(named.region_of[r])).m, m) for r, m in
                self.materials.items())
        trial = self.dx_trial
        return (fem.form(compat.one_subdomain_data(ufl.derivative(F, self.x, trial))),
                fem.form(compat.one_subdomain_data(ufl.derivative(F, self.x_dot, trial))),
                fem.form(ufl.derivative(M, self.x, trial)))

    def _whole_sum(self, c, extra_residual, forms=True):
        """The residual's terms on c, summed (see _whole); `forms`: the pair
        (F, J) compiled, else the UFL sum."""
        named, msh = self.named, self.mesh
        dx = ufl.Measure("dx", domain=msh, subdomain_data=compat.meshtags(named.cell_tags))
        ds = ufl.Measure("ds", domain=msh, subdomain_data=compat.meshtags(named.facet_tags))
        contact = tuple(named.tag_of[b] for b in self.spec.contact)
        one = next(iter(self.materials.values())) if len(self.materials) == 1 else None
        pieces = {
            "region": [c.on(dx(named.region_of[r]), mat=m) for r, m in self.materials.items()],
            "obstacle": [c.on(ds(named.tag_of[b]), mat=self._material_of(b), load=self._load(b))
                         for b in self.spec.obstacles],
            "contact": [c.on(ds(contact))] if contact else [],
            "exterior": [c.on(ds, mat=one)],
            "mesh": [c.on(dx)],
        }
        F = 0
        for term in self.terms:
            if term.role != "F":
                continue
            if term.piece == "electrode":  # one form: one subdomain data per integral type
                raise NotImplementedError(f"{term.name}: the whole residual has no pieces of "
                                          "an electrode and a region (the mesh's tags mark "
                                          "neither)")
            if term.piece == "boundary":
                on = [c.on(ds(named.tag_of[b]), load=self._load(b)) for b in self.loads
                      if term.where is None or self._sets(b, term.where)]
            else:
                on = pieces[term.piece]
            for ct in on:
                F = F + term.build(ct)
        if extra_residual is not None:
            u, phi = ufl.split(self.x)
            w, psi = ufl.split(c.y)
            F = compat.one_subdomain_data(F + extra_residual(u, phi, w, psi, self._hook_data()))
        if not forms:
            return F
        return fem.form(F), fem.form(pf.jacobian(F, self.x, self.dx_trial))

    def _material_of(self, boundary):
        """The material of the cells a boundary's facets bound, in the whole
        form (one: it has no pieces of a boundary and a region)."""
        regions = [r for r, _ in self.materials.items()
                   if len(self.named.boundary_facets_of(boundary, r)) > 0]
        regions = self.mesh.comm.allgather(regions)
        regions = sorted({r for part in regions for r in part})
        if len(regions) > 1:
            raise NotImplementedError(
                f"boundaries.{boundary}.contact: the reference engine takes a contact boundary "
                f"with an obstacle that bounds one region (it bounds {', '.join(regions)})")
        return self.materials[regions[0]] if regions else next(iter(self.materials.values()))

    def _obstacles(self):
        """{boundary: cpp.ObstacleContact} of the contact boundaries with an
        obstacle or a block of their own."""
        c = compat.cpp
        out = {b: cpp.ObstacleContact() for b in self.spec.obstacles}
        force = {b: [[] for _ in range(self.mesh.geometry.dim)] for b in out}
        for b, name, f in self._output("obstacle_force"):
            force[b]["xyz".index(name[-1])].append(c(f))
        for b, oc in out.items():
            oc.force = force[b]
            oc.pressure_load = [c(f) for n, _, f in self._output("obstacle_pressure_load")
                                if n == b]
            oc.nodal_area = [c(f) for n, _, f in self._output("obstacle_nodal_area") if n == b]
            oc.contact_measure = [c(f) for n, _, f in self._output("obstacle_contact_measure")
                                  if n == b]
            penetration = []
            for n, _, e, facets in self._output("obstacle_penetration"):
                if n == b:
                    p = cpp.ObstaclePenetration()
                    p.facets, p.expression = facets, c(e)
                    penetration.append(p)
            oc.penetration = penetration
        return out

    def _output(self, slot):
        return self.outputs.get(slot, [])

    def cpp_model(self):
        """The Model the C++ core runs: the C++ objects under the Python
        ones (compat.cpp), which stay alive in this JitModel."""
        c = compat.cpp

        def cpp_map(objects):
            return {name: c(obj) for name, obj in objects.items()}
        m = cpp.Model()
        m.mesh = self.named
        m.axisymmetric = self.spec.axisymmetric
        m.W, m.P, m.x, m.x_prev = c(self.W), c(self.P), c(self.x), c(self.x_prev)
        m.constants = cpp_map(self.data)
        m.materials = {r: cpp_map(mat) for r, mat in self.materials.items()}
        m.loads = {b: cpp_map(load) for b, load in self.loads.items()}
        m.data_fields = cpp_map(self.fields)
        m.load_data_fields = {b: cpp_map(fields) for b, fields in self.load_fields.items()}
        m.sources = self.sources
        m.contact_facets = self.contact_facets
        m.F, m.J, m.J_contact, m.L = ([c(f) for f in forms] for forms in
                                      (self.F, self.J, self.J_state, self.L))
        if self.x_dot is not None:
            m.x_dot = c(self.x_dot)
            m.K, m.C, m.M = ([c(f) for f in forms] for forms in (self.K, self.C, self.M))
        m.contact_force = [c(f) for _, _, f in self._output("contact_force")]
        fields = []
        for (region, _, D), (_, _, stress) in zip(self._output("electric_displacement"),
                                            self._output("stress")):
            f = cpp.RegionFields()
            f.region, f.cells = region, self.named.region_cells(region)
            f.electric_displacement, f.stress = c(D), c(stress)
            fields.append(f)
        m.fields = fields
        for slot in ("u_exact", "phi_exact", "contact_pressure_load", "contact_nodal_area"):
            for _, _, obj in self._output(slot):
                setattr(m, slot, c(obj))
        m.squared_errors = {name: c(f) for _, name, f in self._output("squared_errors")}
        m.boundary_measures = {b: c(f) for b, _, f in self._output("boundary_measures")}
        charges = {}
        for b, _, f in self._output("electrode_charge"):
            charges.setdefault(b, []).append(c(f))
        m.electrode_charge = charges
        springs = {}
        for b, _, f in self._output("spring_force"):
            springs.setdefault(b, []).append(c(f))
        m.spring_force = springs
        m.obstacles = self._obstacles()
        return m


def factory(extra_residual=None, contact_law=None, keep=None, data=None, mesh=None):
    """A model factory for the C++ driver: (NamedMesh, ModelSpec) -> Model.
    The JitModel is appended to `keep` (its Python objects must outlive the
    run, and the reference engine works on them). `mesh`: the Python Mesh
    of the NamedMesh the driver is given (piezocontact.Problem)."""
    def make(named, spec):
        model = JitModel(named, spec, extra_residual, contact_law, data, mesh)
        if keep is not None:
            keep.append(model)
        return model.cpp_model()
    return make
