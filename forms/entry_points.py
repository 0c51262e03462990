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


def elements(cell_name):
    """(coordinate element, mixed element of x = (u, phi)) on a cell: P1
    vectors (the geometry, and u) and P1^d x P1. The one definition of the
    elements, for ffcx here and for the package's JIT (model.py)."""
    if basix_ufl:
        vector = basix_ufl.element("Lagrange", cell_name, 1, shape=(DIMENSION[cell_name],))
        scalar = basix_ufl.element("Lagrange", cell_name, 1)
        return vector, basix_ufl.mixed_element([vector, scalar])
    cell = getattr(ufl, cell_name)  # its geometric dimension is its own
    vector = ufl.VectorElement("Lagrange", cell, 1)
    return vector, ufl.MixedElement([vector, ufl.FiniteElement("Lagrange", cell, 1)])


# Reference points of the expressions: the cell midpoint (the cell-wise, DG0,
# output) and the P1 nodes (the vertices: the exact fields)
POINTS = {"midpoint": {"triangle": [[1 / 3, 1 / 3]], "tetrahedron": [[0.25, 0.25, 0.25]]},
          "nodes": {"triangle": [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
                    "tetrahedron": [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0],
                                    [0.0, 0.0, 1.0]]}}


def declare(cell_name, shapes):
    """Mesh, W, x, x_prev and {name: Constant}."""
    coordinate, mixed = elements(cell_name)
    mesh = ufl.Mesh(coordinate)
    W = ufl.FunctionSpace(mesh, mixed)
    objects = {"mesh": mesh, "W": W,
               "x": ufl.Coefficient(W),       # (u_n, phi_n), the unknown of the step
               "x_prev": ufl.Coefficient(W)}  # (u_{n-1}, phi_{n-1})
    constants = {name: ufl.Constant(mesh, shape=shape) for name, shape in shapes.items()}
    return objects, constants


def data(d, manufactured_run):
    """The Constants of every group, by group: shared, material, load."""
    shared = {**pf.shared_data(d), **(mms.shared_data() if manufactured_run else {})}
    material = pf.material_data(d)
    # a material is constant in time (the core scales shared and boundary data)
    assert not any(datum.timed for datum in material.values()), "a timed material datum"
    return {"shared": shared, "material": material, "load": pf.load_data(d)}


def compiled(cell_name, variant=None):
    """What ffcx compiles for a variant (None: the model): {name: form} and
    {name: (expression, reference points)}, every term of the catalogue the
    variant defines, on its piece (dx(1), ds(1): the core marks the piece
    with 1), and for the model the Jacobian of each residual term (its
    derivative), with {Jacobian's name: "J" or "J_state"}."""
    d = DIMENSION[cell_name]
    groups = data(d, variant == "manufactured")
    objects, constants = declare(cell_name, {name: datum.shape for group in groups.values()
                                             for name, datum in group.items()})
    mesh, W = objects["mesh"], objects["W"]
    by_group = {g: {name: constants[name] for name in group} for g, group in groups.items()}
    c = terms.Context(objects["x"], objects["x_prev"], ufl.TestFunction(W), by_group["shared"])
    dx_trial = ufl.TrialFunction(W)
    dx, ds = ufl.Measure("dx", domain=mesh), ufl.Measure("ds", domain=mesh)
    measure = {"region": dx(1), "boundary": ds(1), "contact": ds(1), "electrode": ds(1),
               "exterior": ds, "mesh": dx}
    forms, expressions, jacobians = {}, {}, {}
    for t in terms.catalogue(d, variant == "manufactured"):
        if t.variant != variant:
            continue  # compiled with the model
        ct = c.on(measure[t.piece], by_group["material"], by_group["load"])
        if t.expression:
            expressions[t.name] = (t.build(ct), POINTS[t.points][cell_name])
            continue
        forms[t.name] = t.build(ct)
        if t.role == "F" and variant is None and (J := terms.jacobian(t, ct, dx_trial)):
            forms[terms.jacobian_name(t)] = J
            jacobians[terms.jacobian_name(t)] = "J_state" if terms.depends_on_state(J, ct) else "J"
    return objects, constants, forms, expressions, jacobians


def entry(cell_name, variant=None):
    """The namespace of a .ufl file: every object by name, and the lists of
    what ffcx compiles."""
    objects, constants, forms, expressions, _ = compiled(cell_name, variant)
    return {**objects, **constants, **forms, **{n: e for n, (e, _) in expressions.items()},
            "forms": list(forms.values()), "expressions": list(expressions.values())}
