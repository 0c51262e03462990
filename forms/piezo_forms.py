"""The physics of piezocontact, written once.

Backward-Euler weak form (3.3)-(3.4) of Barboteu, Fernandez & Ouafik (2008)
for the frictionless contact of a viscoelastic piezoelectric body with a
normal-compliance foundation, plane strain, unknowns x = (u, phi).

This module is the single source of truth for every term. It is used twice:
  * `piezo_contact.ufl` calls it with UFL Coefficients/Constants, and ffcx
    compiles the result into C kernels for the executable `piezo-contact`;
  * the Python package (JIT, `python/piezocontact/model.py`) calls it with
    dolfinx Functions/Constants, and dolfinx JIT-compiles the very same
    expressions, solved by the C++ loop (`python3 -m piezocontact`) or by
    the reference engine (`--engine reference`).
All material data, loads and the time step are Constants (runtime data).
Changing the law `p` or adding a term is an edit here (and a rebuild of the
executable); from Python, the law can also be passed in (`law=`).
"""

import ufl

# Facet tags 1..MAX_BOUNDARIES carry the named boundaries of the config (in
# sorted name order); per-boundary data are arrays of this length.
MAX_BOUNDARIES = 8

# One quadrature rule for every integral of the contact pressure. UFL would
# pick degree 2 for p (w.n) but 1 for p n_i, and with the kink of max(r, 0)
# inside a facet the two rules differ: the reported contact force would not
# be the force the residual applies.
CONTACT_QUADRATURE_DEGREE = 2


def p(r, c_p):
    """Normal compliance law (4.3): the penalty p(r) = c_p max(r, 0)."""
    return c_p * ufl.max_value(r, 0)


def strain_voigt(v):
    """Voigt strain [eps_xx, eps_yy, 2 eps_xy] of a plane displacement."""
    eps = ufl.sym(ufl.grad(v))
    return ufl.as_vector([eps[0, 0], eps[1, 1], 2 * eps[0, 1]])


def velocity(u, u_prev, data):
    """Backward-Euler velocity (u_n - u_{n-1}) / k."""
    return (u - u_prev) / data["k"]


def stress_voigt(u, u_dot, phi, data):
    """Total stress (2.1) in Voigt form [s_xx, s_yy, s_xy]:
    Bv s(u) + Av s(u_dot) + e^T grad phi, u_dot the velocity."""
    return (ufl.dot(data["Bv"], strain_voigt(u)) + ufl.dot(data["Av"], strain_voigt(u_dot))
            + ufl.dot(ufl.transpose(data["e"]), ufl.grad(phi)))


def voigt_to_tensor(s):
    """The symmetric 2x2 tensor of a Voigt stress [s_xx, s_yy, s_xy]."""
    return ufl.as_matrix([[s[0], s[2]], [s[2], s[1]]])


def electric_displacement(u, phi, data):
    """Electric displacement (2.2): D = e s(u) - beta grad phi."""
    return ufl.dot(data["e"], strain_voigt(u)) - ufl.dot(data["beta"], ufl.grad(phi))


def gap_function(u, n, data):
    """The argument of p on Gamma_C: normal displacement minus gap."""
    return ufl.dot(u, n) - data["g"]


def contact_pressure(u, n, data, law=p):
    """Normal contact pressure -sigma_nu = law(u.nu - g, c_p) (2.7)."""
    return law(gap_function(u, n, data), data["c_p"])


def residual(x, x_prev, y, ds, data, law=p):
    """Residual F(x; y) of (3.3)-(3.4) at the new time level.

    x, x_prev: mixed (u, phi) at t_n and t_{n-1}; y: mixed test function;
    ds: exterior-facet measure whose subdomain ids are 1..MAX_BOUNDARIES.
    data: dict of Constants, see `constant_shapes`; law(r, c_p): the
    normal compliance law.
    """
    u, phi = ufl.split(x)
    u_prev, _ = ufl.split(x_prev)
    w, psi = ufl.split(y)
    n = ufl.FacetNormal(x.ufl_domain())
    dx = ufl.dx(domain=x.ufl_domain())

    # (3.3): viscous + elastic + piezoelectric coupling = body force
    F = ufl.inner(stress_voigt(u, velocity(u, u_prev, data), phi, data), strain_voigt(w)) * dx
    # (3.4): permittivity - piezoelectric coupling = free charge, with the
    # right-hand side of (2.19) as the paper writes it
    F += ufl.inner(ufl.dot(data["beta"], ufl.grad(phi)), ufl.grad(psi)) * dx
    F -= ufl.inner(ufl.dot(data["e"], strain_voigt(u)), ufl.grad(psi)) * dx
    return F - applied_loads(y, ds, data) + contact_term(u, w, n, ds, data, law)


def applied_loads(y, ds, data):
    """The loads of (3.3)-(3.4) as a linear form in the test function y: body
    force, free charge, tractions and surface charges. Assembled alone, its
    size is the scale of the forces in play (the solvers' force balance)."""
    w, psi = ufl.split(y)
    dx = ufl.dx(domain=y.ufl_domain())
    L = ufl.inner(data["f0"], w) * dx + data["q0"] * psi * dx
    for s in range(MAX_BOUNDARIES):
        traction = ufl.as_vector([data["fF"][s, 0], data["fF"][s, 1]])
        L += ufl.inner(traction, w) * ds(s + 1) + data["qF"][s] * psi * ds(s + 1)
    return L


def contact_term(u, w, n, ds, data, law=p):
    """j(u, w) of (2.18): normal compliance on the boundaries switched on as
    contact (chi = 1). Assembled alone, minus it is the nodal force of the
    foundation on the body."""
    return sum(data["chi"][s] * contact_pressure(u, n, data, law) * ufl.dot(w, n)
               * ds(s + 1, degree=CONTACT_QUADRATURE_DEGREE) for s in range(MAX_BOUNDARIES))


def jacobian(F, x, dx_trial):
    """Exact Newton Jacobian: the Gateaux derivative of F."""
    return ufl.derivative(F, x, dx_trial)


def contact_jacobian(x, y, dx_trial, ds, data, law=p):
    """The derivative of contact_term alone: the only part of the Jacobian
    that depends on the state (the bulk is linear)."""
    u, _ = ufl.split(x)
    w, _ = ufl.split(y)
    n = ufl.FacetNormal(x.ufl_domain())
    return ufl.derivative(contact_term(u, w, n, ds, data, law), x, dx_trial)


def contact_force(x, ds, data, i, law=p):
    """Component i of the resultant force of the foundation on the body,
    -int_{Gamma_C} p(u.nu - g) nu ds (N/m per unit thickness)."""
    u, _ = ufl.split(x)
    n = ufl.FacetNormal(x.ufl_domain())
    return sum(-data["chi"][s] * contact_pressure(u, n, data, law) * n[i]
               * ds(s + 1, degree=CONTACT_QUADRATURE_DEGREE) for s in range(MAX_BOUNDARIES))


def constant_shapes():
    """Names and shapes of the runtime Constants of the forms."""
    m = MAX_BOUNDARIES
    return {
        "Bv": (3, 3),      # elastic tensor, Voigt (Pa)
        "Av": (3, 3),      # viscosity tensor, Voigt (Pa s)
        "e": (2, 3),       # piezoelectric tensor (C/m^2), rows x,y
        "beta": (2, 2),    # permittivity (C^2/(N m^2)), positive definite
        "c_p": (),         # surface stiffness of the foundation (N/m^3)
        "g": (),           # initial gap along nu (m)
        "k": (),           # time step (s)
        "f0": (2,),        # body force (N/m^3)
        "q0": (),          # free charge density (C/m^3)
        "fF": (m, 2),      # traction on boundary slot s (N/m^2)
        "qF": (m,),        # surface charge on boundary slot s (C/m^2)
        "chi": (m,),       # 1 if boundary slot s is contact, else 0
    }
