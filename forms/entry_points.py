"""What ffcx compiles ahead of time for the executable, per cell type: the
.ufl files of forms/ are one line each, calling `entry` (the model, or its
manufactured variant) and putting the result at top level (ffcx names the generated forms,
coefficients and constants after the top-level variables that hold them,
and fem::create_form looks them up by those names).

Each form here is one term of the catalogue (terms.py), integrated over the
entities tagged 1 (dx(1), ds(1)): the executable instantiates it once per
piece (region, named boundary, ...) with that piece's Constants and a tag
set that marks only its entities. Nothing physical is written here, and no
term is named: this is one loop over the catalogue."""

import manufactured as mms
import piezo_forms as pf
import terms
import ufl

DIMENSION = {"triangle": 2, "tetrahedron": 3}

try:  # basix >= 0.7 (dolfinx 0.9): elements are basix.ufl's, UFL has none of its own
    import basix.ufl as basix_ufl
except ImportError:  # basix 0.5 (dolfinx 0.5): UFL 2022's own elements
    basix_ufl = None


def lagrange(cell_name, degree, shape=()):
    """The Lagrange element of a degree on a cell (scalar, or of a shape)."""
    if basix_ufl:
        return basix_ufl.element("Lagrange", cell_name, degree, shape=shape)
    cell = getattr(ufl, cell_name)  # its geometric dimension is its own
    if shape:
        return ufl.VectorElement("Lagrange", cell, degree)
    return ufl.FiniteElement("Lagrange", cell, degree)


def elements(cell_name, degree_u=1, degree_phi=1):
    """(coordinate element, mixed element of x = (u, phi), element of the
    contact pressure) on a cell: the geometry is P1 (straight-sided cells),
    x is P{degree_u}^d x P{degree_phi}, the lumped contact pressure P1 (at
    degree 2 the vertex functions of a triangle integrate to zero: no
    lumping). The one definition of the elements, for ffcx here and for the
    package's JIT (model.py)."""
    vector = (DIMENSION[cell_name],)
    u, phi = lagrange(cell_name, degree_u, vector), lagrange(cell_name, degree_phi)
    mixed = basix_ufl.mixed_element([u, phi]) if basix_ufl else ufl.MixedElement([u, phi])
    return lagrange(cell_name, 1, vector), mixed, lagrange(cell_name, 1)


# The degrees the executable carries (compiled ahead of time: one .ufl file
# per cell and pair), as (degree_u, degree_phi)
COMPILED_DEGREES = ((1, 1), (2, 2))


def node_points(cell_name, degree):
    """The reference nodes of the Lagrange element of a degree, in basix's
    order (the interpolation points of the space)."""
    import basix
    cell = getattr(basix.CellType, cell_name)
    element = basix.create_element(basix.ElementFamily.P, cell, degree,
                                   basix.LagrangeVariant.gll_warped)
    return element.points.tolist()


def points(kind, cell_name, degrees):
    """Reference points of an expression: the cell midpoint (the cell-wise,
    DG0, output), or the nodes of u's or phi's space (the exact fields)."""
    if kind == "midpoint":
        return [[1 / (DIMENSION[cell_name] + 1)] * DIMENSION[cell_name]]
    return node_points(cell_name, degrees[{"u_nodes": 0, "phi_nodes": 1}[kind]])


def field_degree(degrees):
    """The degree of the fields a spatial datum is interpolated in: the
    higher of u's and phi's (data given by expressions are then exact
    wherever the solution can be)."""
    return max(degrees)


def declare(cell_name, data, degrees=(1, 1), fields=False):
    """Mesh, W, x, x_prev, the pressure's space, {name: Constant} of the
    data ({name: Datum}) and, with `fields`, {name: field coefficient} of
    the spatial ones."""
    coordinate, mixed, pressure = elements(cell_name, *degrees)
    mesh = ufl.Mesh(coordinate)
    W = ufl.FunctionSpace(mesh, mixed)
    objects = {"mesh": mesh, "W": W,
               "x": ufl.Coefficient(W),       # (u_n, phi_n), the unknown of the step
               "x_prev": ufl.Coefficient(W),  # (u_{n-1}, phi_{n-1})
               "x_dot": ufl.Coefficient(W),   # the velocity held in a linearisation
               "P": ufl.FunctionSpace(mesh, pressure)}
    constants = {name: ufl.Constant(mesh, shape=datum.shape) for name, datum in data.items()}
    fields = {name: ufl.Coefficient(ufl.FunctionSpace(
        mesh, lagrange(cell_name, field_degree(degrees), datum.shape)))
        for name, datum in data.items() if datum.spatial and fields}
    return objects, constants, fields


def data(d, manufactured_run, axisymmetric=False):
    """The Constants of every group, by group: shared, material, load."""
    shared = {**pf.shared_data(d), **(mms.shared_data() if manufactured_run else {})}
    material = pf.material_data(d, axisymmetric)
    # a material is constant in time (the core scales shared and boundary data)
    assert not any(datum.timed for datum in material.values()), "a timed material datum"
    return {"shared": shared, "material": material, "load": pf.load_data(d)}


def compiled(cell_name, variant=None, degrees=(1, 1), axisymmetric=False, fields=False):
    """What ffcx compiles for a variant (None: the model): {name: form} and
    {name: (expression, reference points)}, every term of the catalogue the
    variant defines, on its piece (dx(1), ds(1): the core marks the piece
    with 1), and for the model the Jacobian of each residual term (its
    derivative), with {derived form's name: role}: "J" or "J_state" for
    the Jacobians, and the forms of a linearisation: "K" (stiffness, only
    where it is not the Jacobian), "C" (damping), "M" (mass). `axisymmetric`:
    the axisymmetric formulation of a triangle mesh; `fields`: the data
    that may vary in space carry their fields (a run whose config gives
    some by expressions; without, the forms are the Constants' alone, and
    their kernels those of a run without expressions, bit for bit)."""
    d = DIMENSION[cell_name]
    assert d == 2 or not axisymmetric, "axisymmetry is a formulation of 2D meshes"
    groups = data(d, variant == "manufactured", axisymmetric)
    objects, constants, fields = declare(cell_name, {name: datum for group in groups.values()
                                                     for name, datum in group.items()},
                                         degrees, fields)
    objects.update({pf.field_name(name): f for name, f in fields.items()})
    mesh, W = objects["mesh"], objects["W"]
    by_group = {g: pf.with_fields({name: constants[name] for name in group}, fields)
                for g, group in groups.items()}
    c = terms.Context(objects["x"], objects["x_prev"], ufl.TestFunction(W), by_group["shared"],
                      q=ufl.TestFunction(objects["P"]), kin=pf.Kinematics(axisymmetric))
    dx_trial = ufl.TrialFunction(W)
    dx, ds = ufl.Measure("dx", domain=mesh), ufl.Measure("ds", domain=mesh)
    measure = {"region": dx(1), "boundary": ds(1), "contact": ds(1), "electrode": ds(1),
               "exterior": ds, "mesh": dx, "obstacle": ds(1)}
    forms, expressions, jacobians = {}, {}, {}
    for t in terms.catalogue(d, variant == "manufactured"):
        if t.variant != variant:
            continue  # compiled with the model
        ct = c.on(measure[t.piece], by_group["material"], by_group["load"])
        if t.expression:
            expressions[t.name] = (t.build(ct), points(t.points, cell_name, degrees))
            continue
        if t.role == "M":
            forms[t.name] = terms.mass(t, ct, dx_trial)
            jacobians[t.name] = "M"
            continue
        forms[t.name] = t.build(ct)
        if t.role == "F" and variant is None and (J := terms.jacobian(t, ct, dx_trial)):
            forms[terms.jacobian_name(t)] = J
            jacobians[terms.jacobian_name(t)] = "J_state" if terms.depends_on_state(J, ct) else "J"
            for role, form in terms.linearised(t, ct, objects["x_dot"], dx_trial).items():
                if form is not None:
                    forms[role + t.name[1:]] = form
                    jacobians[role + t.name[1:]] = role
    return objects, constants, forms, expressions, jacobians


def entry(cell_name, variant=None, degrees=(1, 1), axisymmetric=False, fields=False):
    """The namespace of a .ufl file: every object by name, and the lists of
    what ffcx compiles."""
    objects, constants, forms, expressions, _ = compiled(cell_name, variant, degrees,
                                                         axisymmetric, fields)
    return {**objects, **constants, **forms, **{n: e for n, (e, _) in expressions.items()},
            "forms": list(forms.values()), "expressions": list(expressions.values())}
