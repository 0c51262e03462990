"""The UFL objects that every .ufl entry point declares: the mesh, the mixed
P1 space W of (u, phi), the coefficients x = (u_n, phi_n) and x_prev, and one
Constant per runtime datum.

ffcx names coefficients and constants in the generated C after the top-level
variables of the .ufl file that hold them (fem::create_form looks them up by
those names), so each .ufl file puts these into its namespace with
`globals().update(...)`."""

import ufl


def declare(shapes):
    """Mesh, W, x, x_prev and {name: Constant} for the given constant shapes."""
    cell = ufl.triangle
    mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
    W = ufl.FunctionSpace(mesh, ufl.MixedElement([ufl.VectorElement("Lagrange", cell, 1),
                                                  ufl.FiniteElement("Lagrange", cell, 1)]))
    objects = {"mesh": mesh, "W": W,
               "x": ufl.Coefficient(W),       # (u_n, phi_n), the unknown of the step
               "x_prev": ufl.Coefficient(W)}  # (u_{n-1}, phi_{n-1})
    constants = {name: ufl.Constant(mesh, shape=shape) for name, shape in shapes.items()}
    return objects, constants
