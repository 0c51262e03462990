"""The physics of piezocontact, written once.

Backward-Euler weak form (3.3)-(3.4) of Barboteu, Fernandez & Ouafik (2008)
for the frictionless contact of a viscoelastic piezoelectric body with a
normal-compliance foundation, unknowns x = (u, phi), in d = 2 (plane strain)
or d = 3 dimensions: every function here reads d from its arguments.

This module is the single source of truth for every term. It is used twice:
  * the .ufl entry points (`entry_points.py`) call it with UFL Coefficients
    and Constants, and ffcx compiles the result into C kernels for the
    executable `piezo-contact`, once per cell type;
  * the Python package (JIT, `python/piezocontact/model.py`) calls it with
    dolfinx Functions/Constants, and dolfinx JIT-compiles the very same
    expressions, solved by the C++ loop (`python3 -m piezocontact`) or by
    the reference engine (`--engine reference`).

The residual is a sum of terms, each integrated over one piece of the mesh
with its own data: the bulk of each region (cells) with its material, the
loads of each named boundary (facets), and the contact boundary. A term is
compiled once and instantiated per piece, so neither regions nor
boundaries are limited in number. All material data, loads and the time
step are Constants (runtime data). Changing the law `p` or adding a term is
an edit here (and a rebuild of the executable); from Python, the law can
also be passed in (`law=`).
"""

import ufl


def degrees(x):
    """(degree of u, degree of phi) of the mixed space of x."""
    def value(attribute):  # a method in UFL 2022, a property in basix.ufl
        return attribute() if callable(attribute) else attribute
    return tuple(value(e.degree) for e in value(x.ufl_element().sub_elements))


def contact_quadrature_degree(x):
    """One quadrature rule for every integral of the contact pressure: twice
    u's degree (p (w.n) with p linear in u). UFL would pick 2 for p (w.n) but
    1 for p n_i at degree 1, and with the kink of max(r, 0) inside a facet the
    two rules differ: the reported contact force would not be the force the
    residual applies."""
    return 2 * degrees(x)[0]


def voigt_size(d):
    """Length of a Voigt strain vector in d dimensions."""
    return {2: 3, 3: 6}[d]


def p(r, c_p):
    """Normal compliance law (4.3): the penalty p(r) = c_p max(r, 0)."""
    return c_p * ufl.max_value(r, 0)


# Voigt index pairs: [xx, yy, xy] in 2D (plane strain), [xx, yy, zz, yz, xz,
# xy] in 3D, engineering shears (2 eps_ij) in the strain vector
VOIGT_PAIRS = {2: [(0, 0), (1, 1), (0, 1)],
               3: [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)]}


def strain_voigt(v):
    """Voigt strain of a displacement v (engineering shears)."""
    eps = ufl.sym(ufl.grad(v))
    return ufl.as_vector([eps[i, j] if i == j else 2 * eps[i, j]
                          for i, j in VOIGT_PAIRS[v.ufl_shape[0]]])


def voigt_to_tensor(s):
    """The symmetric d x d tensor of a Voigt stress s."""
    d = {3: 2, 6: 3}[s.ufl_shape[0]]
    entry = {}
    for a, (i, j) in enumerate(VOIGT_PAIRS[d]):
        entry[i, j] = entry[j, i] = s[a]
    return ufl.as_matrix([[entry[i, j] for j in range(d)] for i in range(d)])


def velocity(u, u_prev, data):
    """Backward-Euler velocity (u_n - u_{n-1}) / k."""
    return (u - u_prev) / data["k"]


def stress_voigt(u, u_dot, phi, mat):
    """Total stress (2.1) in Voigt form: Bv s(u) + Av s(u_dot) + e^T grad phi,
    u_dot the velocity, mat a region's material."""
    return (ufl.dot(mat["Bv"], strain_voigt(u)) + ufl.dot(mat["Av"], strain_voigt(u_dot))
            + ufl.dot(ufl.transpose(mat["e"]), ufl.grad(phi)))


def electric_displacement(u, phi, mat):
    """Electric displacement (2.2): D = e s(u) - beta grad phi."""
    return ufl.dot(mat["e"], strain_voigt(u)) - ufl.dot(mat["beta"], ufl.grad(phi))


def gap_function(u, n, data):
    """The argument of p on Gamma_C: normal displacement minus gap."""
    return ufl.dot(u, n) - data["g"]


def contact_pressure(u, n, data, law=p):
    """Normal contact pressure -sigma_nu = law(u.nu - g, c_p) (2.7)."""
    return law(gap_function(u, n, data), data["c_p"])


def region_residual(x, x_prev, y, dx, mat, data):
    """The bulk of (3.3)-(3.4) on one region (dx: its cells) with its
    material: viscous + elastic + piezoelectric stress against the strain of
    the test function, permittivity - coupling against grad psi (with the
    right-hand side of (2.19) as the paper writes it), minus the body loads."""
    u, phi = ufl.split(x)
    u_prev, _ = ufl.split(x_prev)
    w, psi = ufl.split(y)
    F = ufl.inner(stress_voigt(u, velocity(u, u_prev, data), phi, mat), strain_voigt(w)) * dx
    F += ufl.inner(ufl.dot(mat["beta"], ufl.grad(phi)), ufl.grad(psi)) * dx
    F -= ufl.inner(ufl.dot(mat["e"], strain_voigt(u)), ufl.grad(psi)) * dx
    return F - body_loads(y, dx, data)


def body_loads(y, dx, data):
    """Body force f0 and free charge q0 on the cells of dx."""
    w, psi = ufl.split(y)
    return ufl.inner(data["f0"], w) * dx + data["q0"] * psi * dx


def boundary_loads(y, ds, load):
    """Traction fF and surface charge qF of one named boundary (ds: its
    facets). Its residual term is minus this."""
    w, psi = ufl.split(y)
    return ufl.inner(load["fF"], w) * ds + load["qF"] * psi * ds


def spring_residual(x, y, ds, load):
    """An elastic (Winkler) bed on the facets of ds: the traction
    -k_n (u.nu) nu - k_t u_tau, u_tau = u - (u.nu) nu, whose residual term is
    int (k_n (u.nu)(w.nu) + k_t u_tau.w_tau) ds."""
    u, _ = ufl.split(x)
    w, _ = ufl.split(y)
    n = ufl.FacetNormal(x.ufl_domain())
    u_n, w_n = ufl.dot(u, n), ufl.dot(w, n)
    return (load["k_n"] * u_n * w_n + load["k_t"] * ufl.dot(u - u_n * n, w - w_n * n)) * ds


def spring_force(x, ds, load, i):
    """Component i of the bed's resultant force on the body over the facets
    of ds: int -(k_n (u.nu) nu + k_t u_tau)_i ds."""
    u, _ = ufl.split(x)
    n = ufl.FacetNormal(x.ufl_domain())
    u_n = ufl.dot(u, n)
    return -(load["k_n"] * u_n * n[i] + load["k_t"] * (u[i] - u_n * n[i])) * ds


def contact_term(u, w, n, ds, data, law=p):
    """j(u, w) of (2.18), normal compliance on the contact facets of ds.
    Assembled alone, minus it is the nodal force of the foundation."""
    return contact_pressure(u, n, data, law) * ufl.dot(w, n) * ds


def contact_residual(x, y, ds, data, law=p):
    """The contact term of the residual (ds: the contact facets)."""
    u, _ = ufl.split(x)
    w, _ = ufl.split(y)
    dsq = ds(degree=contact_quadrature_degree(x))
    return contact_term(u, w, ufl.FacetNormal(x.ufl_domain()), dsq, data, law)


def jacobian(F, x, dx_trial):
    """Exact Newton Jacobian: the Gateaux derivative of F."""
    return ufl.derivative(F, x, dx_trial)


def contact_force(x, ds, data, i, law=p):
    """Component i of the resultant force of the foundation on the body,
    -int_{Gamma_C} p(u.nu - g) nu ds (N/m per unit thickness in 2D, N in 3D)."""
    u, _ = ufl.split(x)
    n = ufl.FacetNormal(x.ufl_domain())
    return -contact_pressure(u, n, data, law) * n[i] * ds(degree=contact_quadrature_degree(x))


def electrode_charge(x, ds, mat):
    """Charge of an electrode, int D . nu over its facets that bound cells of
    one material (ds: those facets), nu outward: C/m per unit thickness in
    2D, C in 3D."""
    u, phi = ufl.split(x)
    n = ufl.FacetNormal(x.ufl_domain())
    return ufl.dot(electric_displacement(u, phi, mat), n) * ds


def contact_pressure_moments(x, q, ds, data, law=p):
    """int p(u.nu - g) q ds and int q ds over the contact facets (ds), q a
    P1 test function (one per vertex). At a vertex, the first over the
    second is the lumped L2 projection of the contact pressure; the second
    alone is the vertex's share of Gamma_C."""
    u, _ = ufl.split(x)
    n = ufl.FacetNormal(x.ufl_domain())
    return (contact_pressure(u, n, data, law) * q * ds(degree=contact_quadrature_degree(x)),
            q * ds)


class Datum:
    """A Constant of the forms: its shape and where its value comes from.
    `key`: the config key that sets it (from the top for the shared data,
    within a region's material or a boundary's entry for the others; None:
    the core sets it, as the time step); `timed`: the key may carry a
    history (the core scales the value at every step); `flag`: a switch,
    1 where the key's value is this string, else 0. A key the config leaves
    out leaves the Constant zero."""

    def __init__(self, shape, key=None, timed=False, flag=None):
        self.shape, self.key, self.timed, self.flag = shape, key, timed, flag


def shared_data(d):
    """The Constants shared by every term (d dimensions)."""
    return {
        "c_p": Datum((), "contact.c_p"),                    # surface stiffness of the foundation (N/m^3)
        "g": Datum((), "contact.gap"),                      # initial gap along nu (m)
        "k": Datum(()),                                     # time step (s)
        "f0": Datum((d,), "loads.body_force", timed=True),  # body force (N/m^3)
        "q0": Datum((), "loads.charge_density", timed=True),  # free charge density (C/m^3)
    }


def material_data(d):
    """The Constants of one region's material (Voigt, see VOIGT_PAIRS)."""
    m = voigt_size(d)
    return {
        "Bv": Datum((m, m), "elastic"),          # elastic tensor (Pa)
        "Av": Datum((m, m), "viscosity"),        # viscosity tensor (Pa s)
        "e": Datum((d, m), "piezoelectric"),     # piezoelectric tensor (C/m^2), rows: D components
        "beta": Datum((d, d), "permittivity"),   # permittivity (C^2/(N m^2)), positive definite
    }


def load_data(d):
    """The Constants of one named boundary: its loads and its elastic bed."""
    return {
        "fF": Datum((d,), "traction", timed=True),     # traction (N/m^2)
        "qF": Datum((), "surface_charge", timed=True),  # surface charge (C/m^2)
        "k_n": Datum((), "spring.normal"),              # bed stiffness along nu (N/m^3)
        "k_t": Datum((), "spring.tangential"),          # bed stiffness across nu (N/m^3)
    }


def shapes(data):
    """{name: shape} of a dict of Datum."""
    return {name: datum.shape for name, datum in data.items()}
