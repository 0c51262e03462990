"""Manufactured solutions: an exact (u, phi) in closed form and the loads
that make it solve the model, derived by UFL from piezo_forms.py.

The exact solution is u = U0 theta(t) U(x), phi = PHI0 theta(t) Phi(x), with
runtime switches (Constants equal to 0 or 1):
  * space_smooth: U, Phi linear in x (P1 reproduces them exactly) or linear
    plus a trigonometric part (P1 errors O(h) in H1, O(h^2) in L2);
  * time_smooth: theta = t (backward Euler has no truncation error on it)
    or theta = sin(pi t / 2) (error O(k)).
theta(0) = 0, so u_0 = 0 as in the paper.

The loads come from the strong form of the equations that residual() of
piezo_forms weakens, with the stress and electric displacement of
piezo_forms evaluated at the exact solution and its exact velocity:
  f0 = -div sigma, q0 = div D in the body,
  fF = sigma n, qF = -D.n on every boundary (on Dirichlet boundaries the
    rows are replaced by the boundary values, so these are never felt there),
  plus p(u.nu - g) nu on the contact boundaries, so that the penalty the
    discrete problem applies is part of the balance. With a positive gap the
    contact zone opens at t > 0 and then grows along Gamma_C.
Removing the contact term from piezo_forms.residual leaves that last load
unbalanced, and the discrete solution misses the exact one.
"""

import piezo_forms as pf
import ufl

U0 = 1e-10  # size of the exact displacement (m): Bv eps(u) ~ e grad(phi) ~ 10 Pa
PHI0 = 1.0  # size of the exact potential (V)

# Quadrature degree of the loads and the errors. UFL's estimate for the
# trigonometric terms is 8-12 (half of a run's time at 1/128); degree 4
# integrates the loads against P1 test functions and the squared errors with
# quadrature errors far below the P1 errors measured, and the linear
# solution's exactly.
QUADRATURE_DEGREE = 4


def constant_shapes():
    """The Constants the manufactured forms add to piezo_forms'."""
    return {
        "t": (),             # time of the step (s)
        "space_smooth": (),  # 1: add the trigonometric part of U, Phi; 0: linear
        "time_smooth": (),   # 1: theta = sin(pi t/2); 0: theta = t
    }


def space_profile(X, data):
    """U(x), Phi(x): linear, plus the smooth part when space_smooth = 1."""
    x, y = X[0], X[1]
    s, pi = data["space_smooth"], ufl.pi
    U = (ufl.as_vector([0.5 * x + 0.25 * y, 0.5 - x + 0.3 * y])
         + s * ufl.as_vector([0.5 * ufl.sin(pi * x) * ufl.cos(pi * y),
                              0.3 * ufl.cos(pi * x) * ufl.sin(pi * y) - 0.2 * ufl.sin(pi * x)]))
    Phi = 0.3 + 0.5 * x - 0.4 * y + s * 0.5 * ufl.sin(pi * x) * ufl.cos(pi * y)
    return U, Phi


def time_profile(t, data):
    """theta(t): t, or sin(pi t/2) when time_smooth = 1."""
    s = data["time_smooth"]
    return (1 - s) * t + s * ufl.sin(ufl.pi * t / 2)


def exact_solution(mesh, data):
    """(u, phi, du/dt) of the exact solution at time data["t"]."""
    t = ufl.variable(data["t"])
    theta = time_profile(t, data)
    U, Phi = space_profile(ufl.SpatialCoordinate(mesh), data)
    u = U0 * theta * U
    return u, PHI0 * theta * Phi, ufl.diff(u, t)


def loads(y, ds, data, law=pf.p):
    """The body force, charge, tractions, surface charges and the foundation's
    pressure of the exact solution, as a linear form in the test function y."""
    mesh = y.ufl_domain()
    w, psi = ufl.split(y)
    n = ufl.FacetNormal(mesh)
    dx = ufl.dx(domain=mesh, degree=QUADRATURE_DEGREE)
    ds_all = ds(degree=QUADRATURE_DEGREE)  # no subdomain id: every exterior facet
    u, phi, u_dot = exact_solution(mesh, data)
    sigma = pf.voigt_to_tensor(pf.stress_voigt(u, u_dot, phi, data))
    D = pf.electric_displacement(u, phi, data)
    body = ufl.inner(-ufl.div(sigma), w) * dx + ufl.div(D) * psi * dx
    surface = ufl.inner(ufl.dot(sigma, n), w) * ds_all - ufl.dot(D, n) * psi * ds_all
    return body + surface + pf.contact_term(u, w, n, ds, data, law)


def applied_loads(y, ds, data, law=pf.p):
    """Every load of a manufactured run (the config's are zero): the scale
    of its forces."""
    return pf.applied_loads(y, ds, data) + loads(y, ds, data, law)


def residual(x, x_prev, y, ds, data, law=pf.p):
    """The model's residual with the loads of the exact solution. Its
    Jacobian is piezo_forms' (the loads do not depend on x)."""
    return pf.residual(x, x_prev, y, ds, data, law) - loads(y, ds, data, law)


def squared_errors(x, data):
    """Squared L2 and H1 norms of u_h - u and phi_h - phi (cell integrals;
    the drivers sum them over ranks and take the root)."""
    mesh = x.ufl_domain()
    dx = ufl.dx(domain=mesh, degree=QUADRATURE_DEGREE)
    u_h, phi_h = ufl.split(x)
    u, phi, _ = exact_solution(mesh, data)
    forms = {}
    for name, e in (("u", u_h - u), ("phi", phi_h - phi)):
        l2 = ufl.inner(e, e) * dx
        forms[f"{name}_L2"] = l2
        forms[f"{name}_H1"] = l2 + ufl.inner(ufl.grad(e), ufl.grad(e)) * dx
    return forms
