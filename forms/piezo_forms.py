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


def voigt_size(d, axisymmetric=False):
    """Length of a Voigt strain vector in d dimensions (4 in axisymmetry:
    the hoop strain joins the three in-plane ones)."""
    return 4 if axisymmetric else {2: 3, 3: 6}[d]


def p(r, c_p):
    """Normal compliance law (4.3): the penalty p(r) = c_p max(r, 0)."""
    return c_p * ufl.max_value(r, 0)


# Voigt index pairs of the 3D frame: [xx, yy, xy] in 2D (plane strain and
# stress), [xx, yy, zz, yz, xz, xy] in 3D, [xx, yy, zz, xy] in axisymmetry
# (x = r, y the axis, z the hoop direction), engineering shears (2 eps_ij)
# in the strain vector
VOIGT_PAIRS = {2: [(0, 0), (1, 1), (0, 1)],
               3: [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)],
               "axisymmetric": [(0, 0), (1, 1), (2, 2), (0, 1)]}


class Kinematics:
    """What a formulation changes in the forms: the strain and the measure.
    Cartesian (3D, and 2D in plane strain or stress: those two differ only
    in how the material is reduced, config layer) or axisymmetric: the mesh
    is the (r, z) half-plane x = r >= 0, y the axis; the strain carries the
    hoop term u_r / r, and every integral the weight 2 pi r (results per
    full revolution)."""

    def __init__(self, axisymmetric=False):
        self.axisymmetric = axisymmetric

    def pairs(self, d):
        return VOIGT_PAIRS["axisymmetric" if self.axisymmetric else d]

    def hoop(self, v):
        """u_r / r; 0 on the axis, where the weight r is 0 too (facet
        quadrature points lie there)."""
        r = ufl.SpatialCoordinate(_domain(v))[0]
        return ufl.conditional(ufl.gt(r, 0), v[0] / r, 0)

    def strain(self, v):
        """Voigt strain of a displacement v (engineering shears)."""
        eps = ufl.sym(ufl.grad(v))
        return ufl.as_vector([self.hoop(v) if (i, j) == (2, 2) and self.axisymmetric
                              else eps[i, j] if i == j else 2 * eps[i, j]
                              for i, j in self.pairs(v.ufl_shape[0])])

    def tensor(self, s):
        """The symmetric tensor of a Voigt stress s (3 x 3 in axisymmetry,
        the hoop entry on the diagonal)."""
        d = 3 if self.axisymmetric else {3: 2, 6: 3}[s.ufl_shape[0]]
        entry = {(i, j): 0 for i in range(d) for j in range(d)}
        for a, (i, j) in enumerate(self.pairs(2 if self.axisymmetric else d)):
            entry[i, j] = entry[j, i] = s[a]
        return ufl.as_matrix([[entry[i, j] for j in range(d)] for i in range(d)])

    def weight(self, domain):
        """The weight of every integral: 2 pi r, or None (Cartesian)."""
        return 2 * ufl.pi * ufl.SpatialCoordinate(domain)[0] if self.axisymmetric else None

    def measure(self, m):
        """m, weighted by the formulation (every term integrates with it)."""
        if not self.axisymmetric:
            return m
        return Weighted(m, self.weight(m.ufl_domain()))

    def div(self, T):
        """Divergence of a tensor (3 x 3 in axisymmetry) or vector field in
        the formulation's coordinates: its in-plane components (r, z)."""
        if not self.axisymmetric:
            return ufl.div(T)
        r = ufl.SpatialCoordinate(_domain(T))[0]
        if T.ufl_shape == (2,):
            return ufl.div(T) + T[0] / r
        in_plane = ufl.as_matrix([[T[i, j] for j in range(2)] for i in range(2)])
        return ufl.div(in_plane) + ufl.as_vector([(T[0, 0] - T[2, 2]) / r, T[0, 1] / r])

    def in_plane(self, T):
        """The (r, z) block of a 3 x 3 tensor, T itself otherwise."""
        if not self.axisymmetric:
            return T
        return ufl.as_matrix([[T[i, j] for j in range(2)] for i in range(2)])


CARTESIAN = Kinematics()


class Weighted:
    """A measure whose integrands are multiplied by a weight: `f * m` is
    (w f) dm, and m(degree=..) keeps the weight."""

    def __init__(self, measure, weight):
        self.measure, self.weight = measure, weight

    def __rmul__(self, integrand):
        return (self.weight * integrand) * self.measure

    def __call__(self, *args, **kwargs):
        return Weighted(self.measure(*args, **kwargs), self.weight)

    def ufl_domain(self):
        return self.measure.ufl_domain()


def _domain(expr):
    """The mesh of a UFL expression."""
    return ufl.domain.extract_unique_domain(expr)


def strain_voigt(v, kin=CARTESIAN):
    """Voigt strain of a displacement v (engineering shears)."""
    return kin.strain(v)


def voigt_to_tensor(s, kin=CARTESIAN):
    """The symmetric tensor of a Voigt stress s."""
    return kin.tensor(s)


def velocity(u, u_prev, data):
    """Backward-Euler velocity (u_n - u_{n-1}) / k."""
    return (u - u_prev) / data["k"]


def stress_voigt(u, u_dot, phi, mat, kin=CARTESIAN):
    """Total stress (2.1) in Voigt form: Bv s(u) + Av s(u_dot) + e^T grad phi,
    u_dot the velocity, mat a region's material."""
    return (ufl.dot(mat["Bv"], kin.strain(u)) + ufl.dot(mat["Av"], kin.strain(u_dot))
            + ufl.dot(ufl.transpose(mat["e"]), ufl.grad(phi)))


def electric_displacement(u, phi, mat, kin=CARTESIAN):
    """Electric displacement (2.2): D = e s(u) - beta grad phi (in
    axisymmetry its (r, z) components: the hoop field is zero)."""
    return ufl.dot(mat["e"], kin.strain(u)) - ufl.dot(mat["beta"], ufl.grad(phi))


def gap_function(u, n, data):
    """The argument of p on Gamma_C: normal displacement minus gap."""
    return ufl.dot(u, n) - data["g"]


def contact_pressure(u, n, data, law=p):
    """Normal contact pressure -sigma_nu = law(u.nu - g, c_p) (2.7)."""
    return law(gap_function(u, n, data), data["c_p"])


def region_residual(x, u_dot, y, dx, mat, data, kin=CARTESIAN):
    """The bulk of (3.3)-(3.4) on one region (dx: its cells) with its
    material: viscous + elastic + piezoelectric stress against the strain of
    the test function, permittivity - coupling against grad psi (with the
    right-hand side of (2.19) as the paper writes it), minus the body loads;
    u_dot the velocity (velocity(): backward Euler)."""
    u, phi = ufl.split(x)
    w, psi = ufl.split(y)
    F = ufl.inner(stress_voigt(u, u_dot, phi, mat, kin), kin.strain(w)) * dx
    F += ufl.inner(ufl.dot(mat["beta"], ufl.grad(phi)), ufl.grad(psi)) * dx
    F -= ufl.inner(ufl.dot(mat["e"], kin.strain(u)), ufl.grad(psi)) * dx
    return F - body_loads(y, dx, data)


def inertia(x, y, dx, mat):
    """int rho u.w on a region: its derivative in x is the mass matrix
    M = int rho du.w (nothing on phi: the electric field is
    quasi-static, SPEC's dynamics)."""
    u, _ = ufl.split(x)
    w, _ = ufl.split(y)
    return mat["rho"] * ufl.inner(u, w) * dx


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


def _unit(v):
    """v / |v|, and 0 where v is 0 (a datum the config leaves out)."""
    length = ufl.sqrt(ufl.dot(v, v))
    return ufl.conditional(ufl.gt(length, 0), v / length, 0 * v)


def obstacle_geometry(domain, ob, nu=None):
    """(d, n_o): the signed distance of the reference point x to the
    obstacle's surface (>= 0 outside) and the obstacle's outward normal at
    its closest point (pointing towards the body). The obstacle has moved by
    U_o, so it is the distance of X = x - U_o to the obstacle at rest. Its
    kind is the datum it carries: a plane (point P, normal N), a sphere
    (centre C, radius R; a circle in 2D) or a cylinder (a point P_a of its
    axis, direction A, radius R_a); with none of them the paper's foundation,
    d = g along n_o = -nu (nu the body's outward normal: None where it has
    none, as in an expression on cells, where that kind is not evaluated).
    ob["distance"], where given (a UFL expression of x and t: the Python data
    hook), replaces the config's geometry: n_o is its normalised gradient."""
    if "distance" in ob:
        return ob["distance"], _unit(ufl.grad(ob["distance"]))
    X = ufl.SpatialCoordinate(domain) - ob["U_o"]
    N = _unit(ob["plane_N"])
    A = _unit(ob["cylinder_A"])
    radius = ob["sphere_R"] + ob["cylinder_R"]   # one of the two is given
    q = X - ob["sphere_C"] - ob["cylinder_P"]     # from the centre (a point of the axis)
    q = q - ufl.dot(q, A) * A                     # ... across the axis (A = 0 for a sphere)
    plane, round_ = ufl.gt(ufl.dot(N, N), 0.5), ufl.gt(radius, 0)
    d_round, n_round = ufl.sqrt(ufl.dot(q, q)) - radius, _unit(q)
    offset_d, offset_n = (ob["g_o"], -nu) if nu is not None else (0 * radius, 0 * N)
    d = ufl.conditional(plane, ufl.dot(X - ob["plane_P"], N),
                        ufl.conditional(round_, d_round, offset_d))
    n = ufl.conditional(plane, N, ufl.conditional(round_, n_round, offset_n))
    return d, n


def obstacle_penetration(u, d, n_o):
    """r = -(d + u.n_o): how far the displaced point x + u is inside the
    obstacle, the gap d(x + u) linearised about x (small displacements)."""
    return -(d + ufl.dot(u, n_o))


def contact_normal_stress(s, nu, n_o, kin=CARTESIAN):
    """sigma_n = -(sigma nu) . n_o of a Voigt stress s: the traction on the
    body's surface (outward normal nu) along the obstacle's normal n_o,
    negative in compression. Frictionless contact along n_o is sigma nu =
    lambda n_o, so sigma_n = -lambda also where the surfaces are not
    parallel (n_o != -nu: a curved obstacle or body)."""
    sigma = kin.in_plane(kin.tensor(s))
    return -ufl.dot(ufl.dot(sigma, nu), n_o)


def nitsche_gamma(x, mat, ob, data):
    """Nitsche's parameter gamma_0 E / h (Pa/m): the dimensionless gamma_0 of
    the config, E the largest diagonal entry of the step's tangent moduli
    B + A / k (the viscous part counts: with a short step it dominates), h
    the diameter of the cell of the facet."""
    moduli = mat["Bv"] + mat["Av"] / data["k"]
    E = moduli[0, 0]
    for i in range(1, moduli.ufl_shape[0]):
        E = ufl.max_value(E, moduli[i, i])
    return ob["gamma_N"] * E / ufl.CellDiameter(x.ufl_domain())


class Obstacle:
    """The contact of one boundary with its obstacle, on the facets of that
    boundary that bound one region (ob: the boundary's contact data, mat: the
    region's material; Nitsche's terms need the region's stress).

    Normal compliance: the pressure is lambda = law(r, c_p). Nitsche (Chouly &
    Hild 2013; Chouly, Hild & Renard 2015), with sigma_n = -(sigma nu).n_o
    (contact_normal_stress) and P = sigma_n(u) - gamma r the
    Signorini condition reads sigma_n = min(P, 0), i.e. lambda = -sigma_n =
    max(gamma r - sigma_n(u), 0), and the residual gets
      int lambda (-w.n_o) ds - theta/gamma int (sigma_n(u) + lambda) sigma_n'(w) ds,
    sigma_n'(w) the derivative of sigma_n along w (elastic and viscous:
    the electric equation is unchanged); theta = 1 keeps the displacement
    block of the Jacobian symmetric, the second term vanishes at the exact
    solution (consistency)."""

    def __init__(self, x, u_dot, ob, mat, data, law=p, kin=CARTESIAN, nu=None):
        self.u, self.phi = ufl.split(x)
        self.ob, self.mat, self.kin, self.data = ob, mat, kin, data
        self.d, self.n_o = obstacle_geometry(x.ufl_domain(), ob, nu)
        self.r = obstacle_penetration(self.u, self.d, self.n_o)
        self.nitsche = ufl.gt(ob["nitsche"], 0.5)
        if mat is not None:  # on facets (nu): Nitsche's terms
            self.gamma = nitsche_gamma(x, mat, ob, data)
            s = stress_voigt(self.u, u_dot, self.phi, mat, kin)
            self.sigma_n = contact_normal_stress(s, nu, self.n_o, kin)
        self.law, self.nu = law, nu

    def pressure(self):
        """lambda >= 0, the obstacle's pressure on the body."""
        penalty = self.law(self.r, self.ob["cp_o"])
        if self.mat is None:
            return penalty
        return ufl.conditional(self.nitsche,
                               ufl.max_value(self.gamma * self.r - self.sigma_n, 0), penalty)

    def test_normal_stress(self, w):
        """sigma_n'(w): the normal stress of a displacement w at this step
        (elastic plus viscous, B + A / k)."""
        s = ufl.dot(self.mat["Bv"], self.kin.strain(w)) \
            + ufl.dot(self.mat["Av"], self.kin.strain(w)) / self.data["k"]
        return contact_normal_stress(s, self.nu, self.n_o, self.kin)

    def residual(self, w, ds):
        F = -self.pressure() * ufl.dot(w, self.n_o) * ds
        consistency = -self.ob["theta_N"] / self.gamma * (self.sigma_n + self.pressure()) \
            * self.test_normal_stress(w)
        return F + ufl.conditional(self.nitsche, consistency, 0) * ds


def obstacle(x, u_dot, ds, ob, mat, data, law=p, kin=CARTESIAN):
    """The contact with the obstacle of the facets of ds."""
    return Obstacle(x, u_dot, ob, mat, data, law, kin, ufl.FacetNormal(x.ufl_domain()))


def obstacle_residual(x, u_dot, y, ds, ob, mat, data, law=p, kin=CARTESIAN):
    """The obstacle's term of the residual on the facets of ds."""
    w, _ = ufl.split(y)
    return obstacle(x, u_dot, ds, ob, mat, data, law, kin).residual(
        w, ds(degree=contact_quadrature_degree(x)))


def obstacle_force(x, u_dot, ds, ob, mat, data, i, law=p, kin=CARTESIAN):
    """Component i of the obstacle's resultant force on the body,
    int lambda n_o ds."""
    o = obstacle(x, u_dot, ds, ob, mat, data, law, kin)
    return o.pressure() * o.n_o[i] * ds(degree=contact_quadrature_degree(x))


def obstacle_pressure_moments(x, u_dot, q, ds, ob, mat, data, law=p, kin=CARTESIAN):
    """int lambda q ds and int q ds (see contact_pressure_moments)."""
    o = obstacle(x, u_dot, ds, ob, mat, data, law, kin)
    return o.pressure() * q * ds(degree=contact_quadrature_degree(x)), q * ds


# Quadrature of the contact measure: the indicator of lambda > 0 jumps
# inside a facet, and the measure is resolved to about a fifth of the facet
# (5 Gauss points on an edge at degree 8)
CONTACT_MEASURE_DEGREE = 8


def obstacle_contact_measure(x, u_dot, ds, ob, mat, data, law=p, kin=CARTESIAN):
    """The measure of the facets of ds where lambda > 0 (the contact
    length in 2D, area in 3D, per revolution in axisymmetry)."""
    o = obstacle(x, u_dot, ds, ob, mat, data, law, kin)
    return ufl.conditional(ufl.gt(o.pressure(), 0), 1, 0) * ds(degree=CONTACT_MEASURE_DEGREE)


def obstacle_penetration_at(x, ob):
    """r at points of cells (an expression: the obstacles with a geometry;
    the core measures the paper's foundation along the facets' normals)."""
    u, _ = ufl.split(x)
    d, n_o = obstacle_geometry(x.ufl_domain(), ob)
    return obstacle_penetration(u, d, n_o)


def electrode_charge(x, ds, mat, kin=CARTESIAN):
    """Charge of an electrode, int D . nu over its facets that bound cells of
    one material (ds: those facets), nu outward: C/m per unit thickness in
    2D, C in 3D."""
    u, phi = ufl.split(x)
    n = ufl.FacetNormal(x.ufl_domain())
    return ufl.dot(electric_displacement(u, phi, mat, kin), n) * ds


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
    1 where the key's value is this string, else 0; `spatial`: the key's
    numbers may be expressions in x, y, z, t, which the core interpolates
    into a field of its own (`field_name`): the forms see the datum as the
    Constant plus that field (one of the two is zero). A key the config
    leaves out leaves the Constant zero."""

    def __init__(self, shape, key=None, timed=False, flag=None, spatial=False):
        self.shape, self.key, self.timed, self.flag = shape, key, timed, flag
        self.spatial = spatial


def field_name(name):
    """The coefficient of the forms that carries the part of a spatial
    datum that varies in space."""
    return f"{name}_field"


def with_fields(constants, fields):
    """The data the terms see: each Constant, plus its field where the
    datum is spatial (fields: {datum name: coefficient})."""
    return {name: c + fields[name] if name in fields else c for name, c in constants.items()}


def shared_data(d):
    """The Constants shared by every term (d dimensions)."""
    return {
        "c_p": Datum((), "contact.c_p"),                    # surface stiffness of the foundation (N/m^3)
        "g": Datum((), "contact.gap", spatial=True),        # initial gap along nu (m)
        "k": Datum(()),                                     # time step (s)
        "f0": Datum((d,), "loads.body_force", timed=True, spatial=True),  # body force (N/m^3)
        # free charge density (C/m^3)
        "q0": Datum((), "loads.charge_density", timed=True, spatial=True),
    }


def material_data(d, axisymmetric=False):
    """The Constants of one region's material (Voigt, see VOIGT_PAIRS)."""
    m = voigt_size(d, axisymmetric)
    return {
        "Bv": Datum((m, m), "elastic"),          # elastic tensor (Pa)
        "Av": Datum((m, m), "viscosity"),        # viscosity tensor (Pa s)
        "e": Datum((d, m), "piezoelectric"),     # piezoelectric tensor (C/m^2), rows: D components
        "beta": Datum((d, d), "permittivity"),   # permittivity (C^2/(N m^2)), positive definite
        "rho": Datum((), "density"),             # mass density (kg/m^3): dynamic analyses
    }


def load_data(d):
    """The Constants of one named boundary: its loads and its elastic bed."""
    return {
        "fF": Datum((d,), "traction", timed=True, spatial=True),      # traction (N/m^2)
        "qF": Datum((), "surface_charge", timed=True, spatial=True),  # surface charge (C/m^2)
        "k_n": Datum((), "spring.normal"),              # bed stiffness along nu (N/m^3)
        "k_t": Datum((), "spring.tangential"),          # bed stiffness across nu (N/m^3)
        **contact_data(d),
    }


def contact_data(d):
    """The Constants of one contact boundary with a block of its own or an
    obstacle (keys within its "contact" block; "contact": true takes the
    top-level block's): its law, its obstacle and the method."""
    return {
        "cp_o": Datum((), "contact.c_p"),                         # penalty stiffness (N/m^3)
        "g_o": Datum((), "contact.gap", spatial=True),            # the foundation's gap (m)
        "plane_P": Datum((d,), "contact.obstacle.plane.point"),   # (m)
        "plane_N": Datum((d,), "contact.obstacle.plane.normal"),  # out of the obstacle
        "sphere_C": Datum((d,), "contact.obstacle.sphere.center"),
        "sphere_R": Datum((), "contact.obstacle.sphere.radius"),
        "cylinder_P": Datum((d,), "contact.obstacle.cylinder.point"),
        "cylinder_A": Datum((d,), "contact.obstacle.cylinder.axis"),
        "cylinder_R": Datum((), "contact.obstacle.cylinder.radius"),
        # the obstacle's rigid displacement (m)
        "U_o": Datum((d,), "contact.obstacle.displacement", timed=True, spatial=True),
        "nitsche": Datum((), "contact.method", flag="nitsche"),
        "gamma_N": Datum((), "contact.gamma"),                    # gamma_0 (1)
        "theta_N": Datum((), "contact.theta"),                    # 1, 0 or -1
    }


def shapes(data):
    """{name: shape} of a dict of Datum."""
    return {name: datum.shape for name, datum in data.items()}
