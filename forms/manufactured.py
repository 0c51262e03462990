"""Manufactured solutions: an exact (u, phi) in closed form and the loads
that make it solve the model, derived by UFL from piezo_forms.py, in 2D and
3D.

The exact solution is u = U0 theta(t) U(x), phi = PHI0 theta(t) Phi(x), with
runtime switches (Constants equal to 0 or 1):
  * space_smooth: U, Phi linear in x (P1 reproduces them exactly) or linear
    plus a trigonometric part (P1 errors O(h) in H1, O(h^2) in L2);
  * time_smooth: theta = t (backward Euler has no truncation error on it)
    or theta = sin(pi t / 2) (error O(k)).
theta(0) = 0, so u_0 = 0 as in the paper.

The loads come from the strong form of the equations that piezo_forms
weakens, with its stress and electric displacement evaluated at the exact
solution and its exact velocity:
  f0 = -div sigma, q0 = div D in the body (region_residual),
  fF = sigma n, qF = -D.n on every exterior facet (exterior_loads; on
    Dirichlet boundaries the rows are replaced by the boundary values, so
    these are never felt there),
  plus p(u.nu - g) nu on the contact facets (contact_loads), so that the
    penalty the discrete problem applies is part of the balance. With a
    positive gap the contact zone opens at t > 0 and then grows along
    Gamma_C.
A manufactured run has one material (the exterior loads use it). Weakening
the contact term of piezo_forms.contact_residual leaves the foundation's
load unbalanced, and the discrete solution misses the exact one.
"""

import piezo_forms as pf
import ufl

U0 = 1e-10  # size of the exact displacement (m): Bv eps(u) ~ e grad(phi) ~ 10 Pa
PHI0 = 1.0  # size of the exact potential (V)


def quadrature_degree(x):
    """Quadrature degree of the loads and the errors: 2k + 2 at degree k.
    UFL's estimate for the trigonometric terms is 8-12 (half of a run's time
    at 1/128); 2k + 2 (4 at P1) integrates the loads against P_k test
    functions and the squared errors with quadrature errors far below the
    discretisation errors measured (the rates 2, 3 at P2 come out, tests/
    verification/test_degree.py), and the polynomial solutions of degree
    <= k exactly (their loads and errors are polynomials of degree <= 2k)."""
    return 2 * max(pf.degrees(x)) + 2


def shared_data():
    """The Constants the manufactured forms add to piezo_forms' (any d),
    all set by the core (from the step's time and the config's
    "manufactured" block)."""
    return {
        "t": pf.Datum(()),             # time of the step (s)
        # 1: add the trigonometric part of U, Phi; 0: linear
        "space_smooth": pf.Datum((), "manufactured.space", flag="smooth"),
        # 1: add a quadratic part (P2 holds it exactly)
        "space_quadratic": pf.Datum((), "manufactured.space", flag="quadratic"),
        # 1: theta = sin(pi t/2); 0: theta = t
        "time_smooth": pf.Datum((), "manufactured.time", flag="smooth"),
    }


def space_profile(X, data, axisymmetric=False):
    """U(x), Phi(x): linear, plus the smooth part when space_smooth = 1, or
    a quadratic part (bending of the body: u_y ~ x^2, and a potential
    quadratic through the thickness) when space_quadratic = 1. In
    axisymmetry (x = r) the radial displacement vanishes on the axis, as
    the formulation imposes: the terms of U_x that do not are left out."""
    s, q, pi, sin, cos = data["space_smooth"], data["space_quadratic"], ufl.pi, ufl.sin, ufl.cos
    if axisymmetric:
        x, y = X[0], X[1]
        U = (ufl.as_vector([0.5 * x, 0.5 - x + 0.3 * y])
             + s * ufl.as_vector([0.5 * sin(pi * x) * cos(pi * y),
                                  0.3 * cos(pi * x) * sin(pi * y) - 0.2 * sin(pi * x)])
             + q * ufl.as_vector([-0.6 * x * y, 0.3 * x * x - 0.2 * x * y]))
        Phi = (0.3 + 0.5 * x - 0.4 * y + s * 0.5 * sin(pi * x) * cos(pi * y)
               + q * (0.4 * y * y - 0.3 * x * y + 0.2 * x * x))
        return U, Phi
    if X.ufl_shape[0] == 2:
        x, y = X[0], X[1]
        U = (ufl.as_vector([0.5 * x + 0.25 * y, 0.5 - x + 0.3 * y])
             + s * ufl.as_vector([0.5 * sin(pi * x) * cos(pi * y),
                                  0.3 * cos(pi * x) * sin(pi * y) - 0.2 * sin(pi * x)])
             + q * ufl.as_vector([-0.6 * x * y + 0.1 * y * y, 0.3 * x * x - 0.2 * x * y]))
        Phi = (0.3 + 0.5 * x - 0.4 * y + s * 0.5 * sin(pi * x) * cos(pi * y)
               + q * (0.4 * y * y - 0.3 * x * y + 0.2 * x * x))
        return U, Phi
    x, y, z = X[0], X[1], X[2]
    U = (ufl.as_vector([0.5 * x + 0.25 * y - 0.1 * z, 0.5 - x + 0.3 * y + 0.2 * z,
                        0.2 * x - 0.15 * y + 0.4 * z])
         + s * ufl.as_vector([0.5 * sin(pi * x) * cos(pi * y) * cos(pi * z),
                              0.3 * cos(pi * x) * sin(pi * y) - 0.2 * sin(pi * x) * cos(pi * z),
                              0.25 * sin(pi * y) * sin(pi * z) + 0.1 * cos(pi * x)])
         + q * ufl.as_vector([-0.6 * x * z + 0.1 * y * y, 0.2 * y * z - 0.1 * x * x,
                              0.3 * x * x - 0.2 * x * y]))
    Phi = (0.3 + 0.5 * x - 0.4 * y + 0.2 * z
           + s * 0.5 * sin(pi * x) * cos(pi * y) * cos(pi * z)
           + q * (0.4 * z * z - 0.3 * x * y + 0.2 * y * z))
    return U, Phi


def time_profile(t, data):
    """theta(t): t, or sin(pi t/2) when time_smooth = 1."""
    s = data["time_smooth"]
    return (1 - s) * t + s * ufl.sin(ufl.pi * t / 2)


def exact_solution(mesh, data, kin=pf.CARTESIAN):
    """(u, phi, du/dt) of the exact solution at time data["t"]."""
    t = ufl.variable(data["t"])
    theta = time_profile(t, data)
    U, Phi = space_profile(ufl.SpatialCoordinate(mesh), data, kin.axisymmetric)
    u = U0 * theta * U
    return u, PHI0 * theta * Phi, ufl.diff(u, t)


def _exact_fields(mesh, mat, data, kin):
    u, phi, u_dot = exact_solution(mesh, data, kin)
    sigma = kin.tensor(pf.stress_voigt(u, u_dot, phi, mat, kin))
    return u, sigma, pf.electric_displacement(u, phi, mat, kin)


def body_loads(y, dx, mat, data, kin=pf.CARTESIAN):
    """Body force -div sigma and charge div D of the exact solution (the
    divergences of the formulation's coordinates)."""
    w, psi = ufl.split(y)
    _, sigma, D = _exact_fields(y.ufl_domain(), mat, data, kin)
    dxq = dx(degree=quadrature_degree(y))
    return ufl.inner(-kin.div(sigma), w) * dxq + kin.div(D) * psi * dxq


def exterior_loads(y, ds, mat, data, kin=pf.CARTESIAN):
    """Traction sigma n and surface charge -D.n of the exact solution on the
    exterior facets of ds."""
    w, psi = ufl.split(y)
    n = ufl.FacetNormal(y.ufl_domain())
    _, sigma, D = _exact_fields(y.ufl_domain(), mat, data, kin)
    dsq = ds(degree=quadrature_degree(y))
    return ufl.inner(ufl.dot(kin.in_plane(sigma), n), w) * dsq - ufl.dot(D, n) * psi * dsq


def contact_loads(y, ds, data, law=pf.p, kin=pf.CARTESIAN):
    """The foundation's pressure at the exact solution, on the contact facets."""
    w, _ = ufl.split(y)
    u, _, _ = exact_solution(y.ufl_domain(), data, kin)
    dsq = ds(degree=pf.contact_quadrature_degree(y))
    return pf.contact_term(u, w, ufl.FacetNormal(y.ufl_domain()), dsq, data, law)


def region_residual(x, u_dot, y, dx, mat, data, kin=pf.CARTESIAN):
    """piezo_forms' bulk term with the body loads of the exact solution."""
    return (pf.region_residual(x, u_dot, y, dx, mat, data, kin)
            - body_loads(y, dx, mat, data, kin))


def contact_residual(x, y, ds, data, law=pf.p, kin=pf.CARTESIAN):
    """piezo_forms' contact term minus the exact solution's contact load."""
    return pf.contact_residual(x, y, ds, data, law) - contact_loads(y, ds, data, law, kin)


def squared_errors(x, dx, data, kin=pf.CARTESIAN):
    """Squared L2 and H1 norms of u_h - u and phi_h - phi (cell integrals
    over dx, the formulation's measure; the drivers sum them over ranks and
    take the root)."""
    mesh = x.ufl_domain()
    dx = dx(degree=quadrature_degree(x))
    u_h, phi_h = ufl.split(x)
    u, phi, _ = exact_solution(mesh, data, kin)
    forms = {}
    for name, e in (("u", u_h - u), ("phi", phi_h - phi)):
        l2 = ufl.inner(e, e) * dx
        forms[f"{name}_L2"] = l2
        forms[f"{name}_H1"] = l2 + ufl.inner(ufl.grad(e), ufl.grad(e)) * dx
    return forms
