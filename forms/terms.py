"""The catalogue of terms: every form and expression a run is made of, each
integrated over one kind of piece of the mesh, with its role.

The executable's kernel table (write_cpp_header.py, at build time), ffcx's
entry points (entry_points.py), the Python package's JIT model and the
reference engine's whole residual (python/piezocontact/model.py) are each
one loop over this list; none of them names a term. Adding a term is its
UFL in piezo_forms.py and one entry here.

A term is built from a context `c` (see `Context`): the unknown c.x, the
previous state c.x_prev, the velocity c.u_dot (backward Euler from them, or
a coefficient of its own in a linearisation), the test function c.y, the
shared Constants c.data,
the piece's material c.mat (region and electrode pieces) or loads c.load
(boundary pieces), the contact law c.law, and c.m, the measure of the piece
(dx or ds restricted to it).

Pieces (what one instance of a term is integrated over, and its Constants):
  region     the cells of one region            shared + that region's material
  boundary   the facets of one named boundary   shared + that boundary's data
  contact    the contact facets (all together)  shared
             (the paper's foundation: "contact": true with the top-level block)
  obstacle   the facets of one contact boundary with an obstacle or a block
             of its own, that bound one region
                                                 shared + that boundary's data
                                                 + that region's material
  electrode  the facets of one electrode that bound one region
                                                 shared + that region's material
  exterior   every exterior facet                shared (+ the one material)
  mesh       every cell                          shared
Roles of the forms: "F" residual (summed), "L" applied loads (summed; they
scale the force balance), "M" inertia (its derivative is the mass matrix of
dynamic analyses), "output" (a functional, a linear form or an
expression the core reports: `slot` names the Model member it fills). The
Jacobian is not listed: it is the derivative of each residual term
(`jacobian`), "J" when it is constant in a run, "J_state" when it depends
on the state (the core compares those to keep an LU factorisation).
Neither are the forms of a linearisation about a state (`linearised`):
the stiffness "K", the derivative of each residual term with the velocity
held, and the damping "C", its derivative in the velocity (SPEC's
dynamics: K without the backward-Euler term, C = A from the viscosity).

Variants: a manufactured-solution run replaces some terms (the same
physics with the exact solution's loads) and adds others; its Jacobian is
the model's (the loads do not depend on x).
"""

import manufactured as mms
import piezo_forms as pf
import ufl

PIECES = ("region", "boundary", "contact", "electrode", "exterior", "mesh", "obstacle")


class Term:
    """One entry of the catalogue. `where`: on boundary pieces, the config
    key a boundary must set for the term to be instantiated on it (None:
    every named boundary). `points`: where an expression is evaluated
    ("midpoint" of the cell, or "u_nodes", "phi_nodes": the nodes of
    that field's space). `space`: the test space of a linear form, x's
    ("W") or the contact pressure's ("P", tested with c.q). `variant`: the
    variant that defines it (None: the model's)."""

    def __init__(self, name, piece, role, build, slot=None, where=None, points=None,
                 variant=None, space="W"):
        assert piece in PIECES and role in ("F", "L", "M", "output") and space in ("W", "P")
        self.name, self.piece, self.role, self.build = name, piece, role, build
        self.slot, self.where, self.points, self.variant = slot, where, points, variant
        self.space = space

    @property
    def expression(self):
        return self.points is not None


class Context:
    """What a term is built from (see the module's docstring); `kin`: the
    formulation's kinematics (piezo_forms.Kinematics), whose weight every
    measure of a piece carries."""

    def __init__(self, x, x_prev, y, data, m=None, mat=None, load=None, law=pf.p, q=None,
                 kin=pf.CARTESIAN, x_dot=None):
        self.x, self.x_prev, self.y, self.data = x, x_prev, y, data
        self.m, self.mat, self.load, self.law, self.q = m, mat, load, law, q
        self.kin, self.x_dot = kin, x_dot

    def on(self, m, mat=None, load=None):
        """The same context on another piece (m: its unweighted measure)."""
        return Context(self.x, self.x_prev, self.y, self.data, self.kin.measure(m), mat, load,
                       self.law, self.q, self.kin, self.x_dot)

    def linearised(self, x_dot):
        """The same context with the velocity a coefficient of its own,
        x_dot = (u_dot, phi_dot) (a linearisation: `linearised`)."""
        return Context(self.x, self.x_prev, self.y, self.data, self.m, self.mat, self.load,
                       self.law, self.q, self.kin, x_dot)

    @property
    def u_dot(self):
        """The velocity the terms see: backward Euler, (u - u_prev) / k, or
        the linearisation's own."""
        if self.x_dot is not None:
            return ufl.split(self.x_dot)[0]
        u, _, u_prev = self.fields
        return pf.velocity(u, u_prev, self.data)

    @property
    def fields(self):
        """u, phi, u_prev"""
        u, phi = ufl.split(self.x)
        u_prev, _ = ufl.split(self.x_prev)
        return u, phi, u_prev


def _contact_force(i):
    return lambda c: pf.contact_force(c.x, c.m, c.data, i, c.law)


def _obstacle_force(i):
    return lambda c: pf.obstacle_force(c.x, c.u_dot, c.m, c.load, c.mat, c.data, i, c.law,
                                       c.kin)


def _obstacle_moment(k):
    return lambda c: pf.obstacle_pressure_moments(c.x, c.u_dot, c.q, c.m, c.load, c.mat, c.data,
                                                  c.law, c.kin)[k]


def _spring_force(i):
    return lambda c: pf.spring_force(c.x, c.m, c.load, i)


def model(d):
    """The terms of the model in d dimensions, in the order they are summed."""
    def stress(c):
        u, phi, _ = c.fields
        return pf.stress_voigt(u, c.u_dot, phi, c.mat, c.kin)

    def electric_displacement(c):
        u, phi, _ = c.fields
        return pf.electric_displacement(u, phi, c.mat, c.kin)

    return [
        Term("F_region", "region", "F",
             lambda c: pf.region_residual(c.x, c.u_dot, c.y, c.m, c.mat, c.data, c.kin)),
        Term("M_region", "region", "M", lambda c: pf.inertia(c.x, c.y, c.m, c.mat)),
        Term("L_region", "region", "L", lambda c: pf.body_loads(c.y, c.m, c.data)),
        Term("F_boundary", "boundary", "F", lambda c: -pf.boundary_loads(c.y, c.m, c.load)),
        Term("L_boundary", "boundary", "L", lambda c: pf.boundary_loads(c.y, c.m, c.load)),
        Term("F_spring", "boundary", "F", lambda c: pf.spring_residual(c.x, c.y, c.m, c.load),
             where="spring"),
        Term("F_contact", "contact", "F",
             lambda c: pf.contact_residual(c.x, c.y, c.m, c.data, c.law)),
        # what the core reports
        Term("boundary_measure", "boundary", "output", lambda c: 1.0 * c.m,
             slot="boundary_measures"),
        Term("electrode_charge", "electrode", "output",
             lambda c: pf.electrode_charge(c.x, c.m, c.mat, c.kin), slot="electrode_charge"),
        Term("contact_pressure_load", "contact", "output",
             lambda c: pf.contact_pressure_moments(c.x, c.q, c.m, c.data, c.law)[0],
             slot="contact_pressure_load", space="P"),
        Term("contact_nodal_area", "contact", "output",
             lambda c: pf.contact_pressure_moments(c.x, c.q, c.m, c.data, c.law)[1],
             slot="contact_nodal_area", space="P"),
        *[Term(f"contact_force_{axis}", "contact", "output", _contact_force(i),
               slot="contact_force") for i, axis in enumerate("xyz"[:d])],
        *[Term(f"spring_force_{axis}", "boundary", "output", _spring_force(i),
               slot="spring_force", where="spring") for i, axis in enumerate("xyz"[:d])],
        # contact boundaries with an obstacle or a block of their own
        Term("F_obstacle", "obstacle", "F",
             lambda c: pf.obstacle_residual(c.x, c.u_dot, c.y, c.m, c.load, c.mat, c.data,
                                            c.law, c.kin)),
        *[Term(f"obstacle_force_{axis}", "obstacle", "output", _obstacle_force(i),
               slot="obstacle_force") for i, axis in enumerate("xyz"[:d])],
        Term("obstacle_pressure_load", "obstacle", "output", _obstacle_moment(0),
             slot="obstacle_pressure_load", space="P"),
        Term("obstacle_nodal_area", "obstacle", "output", _obstacle_moment(1),
             slot="obstacle_nodal_area", space="P"),
        Term("obstacle_contact_measure", "obstacle", "output",
             lambda c: pf.obstacle_contact_measure(c.x, c.u_dot, c.m, c.load, c.mat, c.data,
                                                   c.law, c.kin), slot="obstacle_contact_measure"),
        Term("obstacle_penetration", "obstacle", "output",
             lambda c: pf.obstacle_penetration_at(c.x, c.load), slot="obstacle_penetration",
             points="u_nodes"),
        Term("electric_displacement", "region", "output", electric_displacement,
             slot="electric_displacement", points="midpoint"),
        Term("stress", "region", "output", stress, slot="stress", points="midpoint"),
    ]


def _squared_error(name):
    return lambda c: mms.squared_errors(c.x, c.m, c.data, c.kin)[name]


def _exact(i):
    return lambda c: mms.exact_solution(c.x.ufl_domain(), c.data, c.kin)[i]


def manufactured(d):
    """The terms of a manufactured-solution run: the model's, with the
    exact solution's loads in the bulk, on every exterior facet and on the
    contact facets, and the exact fields and errors."""
    variant = "manufactured"
    replaced = {
        "F_region": lambda c: mms.region_residual(c.x, c.u_dot, c.y, c.m, c.mat, c.data, c.kin),
        "L_region": lambda c: (pf.body_loads(c.y, c.m, c.data)
                               + mms.body_loads(c.y, c.m, c.mat, c.data, c.kin)),
        "F_contact": lambda c: mms.contact_residual(c.x, c.y, c.m, c.data, c.law, c.kin),
    }
    added_after = {
        "L_region": [
            Term("F_exterior", "exterior", "F",
                 lambda c: -mms.exterior_loads(c.y, c.m, c.mat, c.data, c.kin), variant=variant),
            Term("L_exterior", "exterior", "L",
                 lambda c: mms.exterior_loads(c.y, c.m, c.mat, c.data, c.kin), variant=variant)],
        "F_contact": [
            Term("L_contact", "contact", "L",
                 lambda c: mms.contact_loads(c.y, c.m, c.data, c.law, c.kin), variant=variant)],
    }
    terms = []
    for t in model(d):
        if t.name in replaced:
            t = Term(t.name, t.piece, t.role, replaced[t.name], t.slot, t.where, t.points,
                     variant, t.space)
            t.jacobian_of = base_builder(d, t.name)
        terms += [t] + added_after.get(t.name, [])
    terms += [Term(name, "mesh", "output", _squared_error(name), slot="squared_errors",
                   variant=variant) for name in ("u_L2", "u_H1", "phi_L2", "phi_H1")]
    terms += [Term("u_exact", "mesh", "output", _exact(0), slot="u_exact", points="u_nodes",
                   variant=variant),
              Term("phi_exact", "mesh", "output", _exact(1), slot="phi_exact", points="phi_nodes",
                   variant=variant)]
    return terms


def base_builder(d, name):
    (t,) = [t for t in model(d) if t.name == name]
    return t.build


def catalogue(d, manufactured_run=False):
    """The terms of a run: the model's, or a manufactured solution's."""
    return manufactured(d) if manufactured_run else model(d)


def jacobian(term, c, dx_trial):
    """The Jacobian of a residual term on the piece of c: the derivative of
    the model's own term (a variant's loads do not depend on x), or None
    where it is zero (a load)."""
    build = getattr(term, "jacobian_of", term.build)
    J = ufl.derivative(build(c), c.x, dx_trial)
    return None if ufl.algorithms.expand_derivatives(J).empty() else J


def depends_on_state(J, c):
    """Whether a Jacobian term changes within a run: it involves x, x_prev
    or the time t."""
    J = ufl.algorithms.expand_derivatives(J)
    state = {c.x, c.x_prev}
    return bool(state & set(J.coefficients())) or (
        "t" in c.data and c.data["t"] in J.constants())


def jacobian_name(term):
    assert term.name.startswith("F_"), f"a residual term's name starts with F_: {term.name}"
    return "J" + term.name[1:]


def linearised(term, c, x_dot, dx_trial):
    """The forms of a residual term linearised about a state, with the
    velocity held (c.linearised(x_dot)): {"K": its stiffness, the
    derivative in x, or None where it is the Jacobian's (the term has no
    velocity), "C": its damping, the derivative in the velocity, or None
    where that is zero}."""
    build = getattr(term, "jacobian_of", term.build)
    F = build(c.linearised(x_dot))
    if x_dot not in F.coefficients():
        return {"K": None, "C": None}
    C = ufl.derivative(F, x_dot, dx_trial)
    return {"K": ufl.derivative(F, c.x, dx_trial),
            "C": None if ufl.algorithms.expand_derivatives(C).empty() else C}


def mass(term, c, dx_trial):
    """The mass matrix of an "M" term: its derivative in x."""
    return ufl.derivative(term.build(c), c.x, dx_trial)
