"""What ffcx compiles ahead of time for the executable, per cell type: the
.ufl files of forms/ are one line each, calling `model` or `manufactured`
and putting the result at top level (ffcx names the generated forms,
coefficients and constants after the top-level variables that hold them,
and fem::create_form looks them up by those names).

Each form here is one term of the model, integrated over the entities
tagged 1 (dx(1), ds(1)): the executable instantiates it once per region,
per named boundary or for the contact facets, with that piece's Constants
and a tag set that marks only its entities. Nothing physical is written
here: every term comes from piezo_forms.py (and manufactured.py)."""

import manufactured as mms
import piezo_forms as pf
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


# Reference points of the cell-wise (DG0) output: the cell midpoint, and of
# the exact fields: the P1 nodes (the vertices)
MIDPOINT = {"triangle": [[1 / 3, 1 / 3]], "tetrahedron": [[0.25, 0.25, 0.25]]}
VERTICES = {"triangle": [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
            "tetrahedron": [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]}


def declare(cell_name, shapes):
    """Mesh, W, x, x_prev, the test and trial functions and {name: Constant}."""
    coordinate, mixed = elements(cell_name)
    mesh = ufl.Mesh(coordinate)
    W = ufl.FunctionSpace(mesh, mixed)
    objects = {"mesh": mesh, "W": W,
               "x": ufl.Coefficient(W),       # (u_n, phi_n), the unknown of the step
               "x_prev": ufl.Coefficient(W)}  # (u_{n-1}, phi_{n-1})
    constants = {name: ufl.Constant(mesh, shape=shape) for name, shape in shapes.items()}
    return objects, constants


def _shapes(d):
    return {**pf.constant_shapes(d), **pf.material_shapes(d), **pf.load_shapes(d)}


def _split(data, shapes):
    return {name: data[name] for name in shapes}


def model(cell_name):
    """The terms of the model (see piezo_forms) and its post-processing."""
    d = DIMENSION[cell_name]
    objects, data = declare(cell_name, _shapes(d))
    mesh, W, x, x_prev = (objects[k] for k in ("mesh", "W", "x", "x_prev"))
    mat = _split(data, pf.material_shapes(d))
    load = _split(data, pf.load_shapes(d))
    y, dx_trial = ufl.TestFunction(W), ufl.TrialFunction(W)
    dx1 = ufl.Measure("dx", domain=mesh)(1)
    ds1 = ufl.Measure("ds", domain=mesh)(1)

    F_region = pf.region_residual(x, x_prev, y, dx1, mat, data)
    F_contact = pf.contact_residual(x, y, ds1, data)
    u, phi = ufl.split(x)
    u_prev, _ = ufl.split(x_prev)
    forms = {
        "F_region": F_region,
        "J_region": pf.jacobian(F_region, x, dx_trial),
        "L_region": pf.body_loads(y, dx1, data),
        "F_boundary": -pf.boundary_loads(y, ds1, load),
        "L_boundary": pf.boundary_loads(y, ds1, load),
        "F_contact": F_contact,
        # the only part of J that depends on the state (the bulk is linear):
        # the C++ loop compares it to decide whether the LU can be kept
        "J_contact": pf.jacobian(F_contact, x, dx_trial),
        "boundary_measure": 1.0 * ds1,
        # per electrode and region: the charge int D.nu
        "electrode_charge": pf.electrode_charge(x, ds1, mat),
    }
    forms["contact_pressure_load"], forms["contact_nodal_area"] = \
        pf.contact_pressure_moments(x, y, ds1, data)
    for i, axis in enumerate("xyz"[:d]):
        forms[f"contact_force_{axis}"] = pf.contact_force(x, ds1, data, i)
    midpoint = MIDPOINT[cell_name]
    expressions = {
        "electric_displacement": pf.electric_displacement(u, phi, mat),
        "stress": pf.stress_voigt(u, pf.velocity(u, u_prev, data), phi, mat),
    }
    return _entry(objects, data, forms, expressions, midpoint)


def manufactured(cell_name):
    """The terms that differ in a manufactured-solution run, the exact
    fields at the P1 nodes (time-dependent Dirichlet data) and the squared
    errors; the rest is model()'s."""
    d = DIMENSION[cell_name]
    objects, data = declare(cell_name, {**_shapes(d), **mms.constant_shapes()})
    mesh, W, x, x_prev = (objects[k] for k in ("mesh", "W", "x", "x_prev"))
    mat = _split(data, pf.material_shapes(d))
    y = ufl.TestFunction(W)
    dx1 = ufl.Measure("dx", domain=mesh)(1)
    ds1 = ufl.Measure("ds", domain=mesh)(1)
    ds_all = ufl.Measure("ds", domain=mesh)  # every exterior facet
    forms = {
        "F_region": mms.region_residual(x, x_prev, y, dx1, mat, data),
        "L_region": pf.body_loads(y, dx1, data) + mms.body_loads(y, dx1, mat, data),
        "F_exterior": -mms.exterior_loads(y, ds_all, mat, data),
        "L_exterior": mms.exterior_loads(y, ds_all, mat, data),
        "F_contact": mms.contact_residual(x, y, ds1, data),
        "L_contact": mms.contact_loads(y, ds1, data),
    }
    forms.update(mms.squared_errors(x, data))
    u_exact, phi_exact, _ = mms.exact_solution(mesh, data)
    expressions = {"u_exact": u_exact, "phi_exact": phi_exact}
    return _entry(objects, data, forms, expressions, VERTICES[cell_name])


def _entry(objects, data, forms, expressions, points):
    """The namespace of a .ufl file: every object by name, and the lists of
    what ffcx compiles (expressions evaluated at `points`)."""
    return {**objects, **data, **forms, **expressions, "forms": list(forms.values()),
            "expressions": [(e, points) for e in expressions.values()]}
