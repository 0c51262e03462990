#!/usr/bin/python3
"""
Frictionless Hertz-type indentation of a transversely isotropic piezoelectric
half-space (z >= 0, poling axis = z = indentation axis, +z points INTO the
body) by a rigid sphere of radius R, contact radius a (small deformation,
paraboloid approximation of the sphere).  numpy only.

WHAT IS TAKEN FROM WHERE  (read this before trusting the numbers)
-----------------------------------------------------------------
None of the piezoelectric papers named below could be read here (only their
titles/abstracts are reachable), so NO equation numbers from them are quoted
and NO coefficient was copied from them.  Every piezoelectric formula below
was DERIVED by the author of this file by the route below, which is the same
route as those papers (potential-theory / Hankel solution + a 2x2 "matrix
Boussinesq" surface Green's function).  The structure of the result is the one
described in:
  * W.Q. Chen, H.J. Ding, Acta Mech. Solida Sinica 12 (1999) 114-120 (sphere);
  * H. Ding, P. Hou, F. Guo, IJSS 37 (2000) 3201-3229 (3D contact, general
    solution with z_i = s_i z);
  * A.E. Giannakopoulos, S. Suresh, Acta Mater. 47 (1999) 2153-2164;
  * E. Karapetian, I. Sevostianov, M. Kachanov, Phil. Mag. B 80 (2000) 331
    (point force / point charge on the half-space surface);
  * S.V. Kalinin, E. Karapetian, M. Kachanov, Phys. Rev. B 70 (2004) 184101;
    E. Karapetian, M. Kachanov, S.V. Kalinin, Phil. Mag. 85 (2005) 1017
    ("Nanoelectromechanics of piezoelectric indentation ...");
    the "Stiffness relations ... arbitrary planform" paper of the same authors
    is J. Mech. Phys. Solids 57 (2009) 673 (doi 10.1016/j.jmps.2009.01.002),
    not Phil. Mag. 85 (2005).
  * F. Yang, J. Appl. Phys. 103 (2008) 074115 (conducting indenter,
    arbitrary axisymmetric profile).
The constants C1*, C3*, C4* below are named after Karapetian/Kalinin's
notation (P = 2a(C1* w0 + C3* psi0), Q = 2a(-C3* w0 + C4* psi0) for a flat
conducting punch); the IDENTIFICATION with their definitions and their sign
convention for Q is mine and NOT checked against the papers.

Only literature formula actually seen in the stored corpora and used here:
  Delafargue & Ulm, IJSS 41 (2004) 7351, Eq. (9) (as implemented in
  github abrandberg/indentationToElasticModulus, delafargueAndUlmMethod.m):
  M3 = 2 sqrt( (C11 C33 - C13^2)/C11 * (1/C44 + 2/(sqrt(C11 C33)+C13))^-1 )
  = indentation modulus of a purely elastic TI half-space along its axis.
  Used only as a check of the e = 0 limit (1/m11 must equal M3).

DERIVATION (own work)
---------------------
1. Characteristic roots s_i (Ding's convention: potentials psi_i(x, y, s_i z)
   harmonic, fields ~ exp(i xi x - xi s z)).  Substituting u_x = i*alpha,
   u_z = B, phi = C times exp(i xi x - xi s z) into the 3 field equations
   (the x-z problem; c12, c66 drop out for normal loading) gives K(s) v = 0,
       K = [[c44 s^2 - c11, -(c13+c44) s, -(e31+e15) s],
            [(c13+c44) s,  c33 s^2 - c44, e33 s^2 - e15],
            [(e15+e31) s,  e33 s^2 - e15, eps11 - eps33 s^2]]
   det K = 0  <=>  a s^6 - b s^4 + c s^2 - d = 0 with (expanded with sympy)
     a = c44 (c33 eps33 + e33^2)
     b = c11 (c33 eps33 + e33^2) + c33 (c44 eps11 + (e15+e31)^2)
         - c13 (c13 + 2 c44) eps33 - 2 c13 e33 (e15+e31) - 2 c44 e31 e33
     c = c11 (c33 eps11 + c44 eps33 + 2 e15 e33) + c44 e31^2
         - c13 (c13 + 2 c44) eps11 - 2 c13 e15 (e15+e31)
     d = c11 (c44 eps11 + e15^2)
   (a and d agree with the form quoted by Ding et al.; b, c are mine.)
   s_i = sqrt(root) with Re s_i > 0.

2. Surface Green's function (point normal force P, point free charge Q on the
   surface, r = distance):  w(r) = (m11 P + m12 Q)/(pi r),
                            phi(r) = (m21 P + m22 Q)/(pi r),
   with w = surface displacement INTO the body, Q = free surface charge
   = D_z(z=0+) integrated.  m_ij = G_ij(|xi|=1)/2, where G is the 2D-Fourier
   surface compliance (w_hat = G11 p_hat / |xi| ...).  G is computed twice,
   independently:  (A) from the s_i and the null vectors of K(s_i) (3x3 solve
   for the traction-free/charged surface), and (B) from the matrix-sign-
   function projector of the 6x6 Stroh-type system matrix (robust also for
   the degenerate isotropic case, where s1 = s2 = s3 = 1).
   Reciprocity gives m21 = -m12 (checked numerically).
   Isotropic elastic: m11 = (1-nu^2)/E.

3. Contact problem.  With L[f] = (1/pi) int f dA'/|x-x'| the surface relation
   is [w, phi] = M L[p, q].  Define N = M^-1 and
       C1* = N11 = m22/det M,  C3* = N12 = -m12/det M,  C4* = N22 = m11/det M.
   In the contact disc w = h - r^2/(2R).
   (1) Conducting indenter at potential phi0 (contact disc equipotential;
       p = q = 0 outside):  L[p] = C1*(h - r^2/2R) + C3* phi0,
       L[q] = -C3*(h - r^2/2R) + C4* phi0.  Bounded p at r = a requires
         h   = a^2/R - (C3*/C1*) phi0
         P   = 4 C1* a^3 / (3R)            (independent of phi0)
         p(r)= p0 sqrt(1 - r^2/a^2),  p0 = 2 C1* a/(pi R) = 3P/(2 pi a^2)
         Q   = -(4 a^3/(3R)) C3* + 2a (C4* + C3*^2/C1*) phi0
         q(r)= -(2 C3* a/(pi R)) sqrt(1-r^2/a^2)
               + (C4* + C3*^2/C1*) phi0 / (pi sqrt(a^2 - r^2))
         phi(r) = phi0 in the contact; for phi0 = 0, phi = 0 on the WHOLE
         surface (p and q are proportional, so M N = I gives phi = 0).
   (2) Insulating indenter, charge-free surface (q = 0 everywhere):
         h   = a^2/R
         P   = 4 a^3 / (3 R m11) = 4 a^3 (C1* + C3*^2/C4*) / (3R)
         p0  = 2 a/(pi R m11)
         phi(r) = (m21/m11) w(r) = (C3*/C4*) w(r) on the whole surface, so
         phi(0) = (C3*/C4*) a^2/R   (w(r) = Hertz surface profile).
   The e = 0 limit gives Hertz with E* = 1/m11 (isotropic: E/(1-nu^2)).

SELF-CHECKS (run the file): isotropic e=0 -> Hertz exactly; TI e=0 -> 1/m11 =
Delafargue-Ulm M3 (1e-8); e=0 -> m22 = 1/(2 sqrt(eps11 eps33)) (charged
dielectric half-space); routes A and B agree (1e-15); reciprocity m21 = -m12
(a deliberate sign error in one coupling term breaks it by O(1)).
NOT checked against any published piezoelectric number.

SIGNS: +z into the body, poling along +z, tension positive, P > 0
compressive, Q = integral of D_z(z=0+) = free charge on the indenter/body
interface (charge carried by the body surface).  If the FE model has the
poling pointing out of the body, e changes sign and so do phi, Q, C3*.
"""
import numpy as np


# --------------------------------------------------------------------------
def _ti_constants(C, e, eps):
    C = np.asarray(C, float); e = np.asarray(e, float); eps = np.asarray(eps, float)
    k = dict(c11=C[0, 0], c12=C[0, 1], c13=C[0, 2], c33=C[2, 2], c44=C[3, 3],
             c66=C[5, 5], e31=e[2, 0], e33=e[2, 2], e15=e[0, 4],
             eps11=eps[0, 0], eps33=eps[2, 2])
    # light consistency checks of transverse isotropy about z
    tol = 1e-6
    sc = max(abs(C).max(), 1.0)
    if (abs(C[0, 0] - C[1, 1]) > tol * sc or abs(C[0, 2] - C[1, 2]) > tol * sc
            or abs(C[3, 3] - C[4, 4]) > tol * sc):
        raise ValueError("C is not transversely isotropic about z (Voigt 3)")
    if abs(e[2, 0] - e[2, 1]) > 1e-6 * max(abs(e).max(), 1e-30) or \
       abs(e[0, 4] - e[1, 3]) > 1e-6 * max(abs(e).max(), 1e-30):
        raise ValueError("e is not of 6mm / infinity-mm form")
    return k


def _nondim(k):
    """Scale: c0 = c44, eps0 = eps33, e0 = sqrt(c0 eps0)."""
    c0, eps0 = k["c44"], k["eps33"]
    e0 = np.sqrt(c0 * eps0)
    kn = {}
    for n, v in k.items():
        if n.startswith("c"):
            kn[n] = v / c0
        elif n.startswith("eps"):
            kn[n] = v / eps0
        else:
            kn[n] = v / e0
    return kn, c0, e0, eps0


def char_coeffs(k):
    """Coefficients (a, b, c, d) of a s^6 - b s^4 + c s^2 - d = 0."""
    c11, c13, c33, c44 = k["c11"], k["c13"], k["c33"], k["c44"]
    e31, e33, e15 = k["e31"], k["e33"], k["e15"]
    k11, k33 = k["eps11"], k["eps33"]
    a = c44 * (c33 * k33 + e33 ** 2)
    b = (c11 * (c33 * k33 + e33 ** 2) + c33 * (c44 * k11 + (e15 + e31) ** 2)
         - c13 * (c13 + 2 * c44) * k33 - 2 * c13 * e33 * (e15 + e31)
         - 2 * c44 * e31 * e33)
    c = (c11 * (c33 * k11 + c44 * k33 + 2 * e15 * e33) + c44 * e31 ** 2
         - c13 * (c13 + 2 * c44) * k11 - 2 * c13 * e15 * (e15 + e31))
    d = c11 * (c44 * k11 + e15 ** 2)
    return a, b, c, d


def char_roots(k):
    """s_i (Re s_i > 0) from the cubic in s^2 (dimensionless input ok)."""
    a, b, c, d = char_coeffs(k)
    t = np.roots([a, -b, c, -d]).astype(complex)
    s = np.sqrt(t)
    s = np.where(s.real < 0, -s, s)
    return np.sort_complex(s)


def _Kmat(k, s):
    c11, c13, c33, c44 = k["c11"], k["c13"], k["c33"], k["c44"]
    e31, e33, e15 = k["e31"], k["e33"], k["e15"]
    k11, k33 = k["eps11"], k["eps33"]
    return np.array([[c44 * s * s - c11, -(c13 + c44) * s, -(e31 + e15) * s],
                     [(c13 + c44) * s, c33 * s * s - c44, e33 * s * s - e15],
                     [(e15 + e31) * s, e33 * s * s - e15, k11 - k33 * s * s]],
                    dtype=complex)


def _G_from_roots(kn):
    """Route (A): surface compliance at |xi| = 1 from s_i and null vectors."""
    s = char_roots(kn)
    if min(abs(s[0] - s[1]), abs(s[1] - s[2]), abs(s[0] - s[2])) < 1e-3:
        return None, s                         # (near-)degenerate: route A unusable
    c13, c33, c44 = kn["c13"], kn["c33"], kn["c44"]
    e31, e33, e15, k33 = kn["e31"], kn["e33"], kn["e15"], kn["eps33"]
    V = []
    for sj in s:
        _, _, vh = np.linalg.svd(_Kmat(kn, sj))
        V.append(vh[-1].conj())                # (alpha, B, C)
    V = np.array(V).T
    al, B, Cc = V
    # rows: T1 = sigma_xz / i, T2 = sigma_zz, T3 = D_z at z = 0 per unit amplitude
    T = np.array([c44 * (B - s * al) + e15 * Cc,
                  -(c13 * al + c33 * s * B + e33 * s * Cc),
                  -(e31 * al + e33 * s * B - k33 * s * Cc)])
    U = np.array([al, B, Cc])
    Zinv = U @ np.linalg.inv(T)                # U = Zinv @ (T1, T2, T3)
    G = np.array([[-Zinv[1, 1], Zinv[1, 2]],
                  [-Zinv[2, 1], Zinv[2, 2]]])   # sigma_zz = -p, D_z = +q
    return G.real, s


def _G_from_sign(kn):
    """Route (B): Stroh-type 6x6 system y' = N y, y = (U1,U2,U3,T1,T2,T3),
    decaying subspace from the matrix sign function (Newton iteration)."""
    c11, c13, c33, c44 = kn["c11"], kn["c13"], kn["c33"], kn["c44"]
    e31, e33, e15 = kn["e31"], kn["e33"], kn["e15"]
    k11, k33 = kn["eps11"], kn["eps33"]
    Minv = np.linalg.inv(np.array([[c33, e33], [e33, -k33]]))
    N = np.zeros((6, 6))
    for j in range(6):
        y = np.zeros(6); y[j] = 1.0
        U1, U2, U3, T1, T2, T3 = y
        dU1 = T1 / c44 - U2 - e15 / c44 * U3
        dU2, dU3 = Minv @ np.array([T2 + c13 * U1, T3 + e31 * U1])
        dT1 = c11 * U1 - c13 * dU2 - e31 * dU3
        dT2 = T1
        dT3 = e15 * (dU1 + U2) - k11 * U3
        N[:, j] = [dU1, dU2, dU3, dT1, dT2, dT3]
    S = N.copy()
    for _ in range(100):
        Sn = 0.5 * (S + np.linalg.inv(S))
        if np.linalg.norm(Sn - S) < 1e-14 * np.linalg.norm(S):
            S = Sn; break
        S = Sn
    Pm = 0.5 * (np.eye(6) - S)                 # projector, Re(eig N) < 0 (decay)
    Uq, _, _ = np.linalg.svd(Pm)
    Y = Uq[:, :3]
    Zinv = Y[:3] @ np.linalg.inv(Y[3:])        # U = Zinv T at the surface
    G = np.array([[-Zinv[1, 1], Zinv[1, 2]],
                  [-Zinv[2, 1], Zinv[2, 2]]])
    svals = -np.linalg.eigvals(N)
    return G, np.sort_complex(svals[svals.real > 0])


def surface_green(C, e, eps):
    """Return dict with m (2x2, SI), s_i, and the route-A/route-B agreement."""
    k = _ti_constants(C, e, eps)
    kn, c0, e0, eps0 = _nondim(k)
    GB, sB = _G_from_sign(kn)
    GA, sA = _G_from_roots(kn)
    scale = np.array([[1 / c0, 1 / e0], [e0 / (eps0 * c0), 1 / eps0]])
    m = 0.5 * GB * scale
    relAB = None if GA is None else np.max(np.abs(GA - GB)) / np.max(np.abs(GB))
    return dict(m=m, s=sA, s_from_N=sB, rel_diff_routeA_routeB=relAB,
                char_coeffs_nondim=char_coeffs(kn))


def hertz_profile(r, a, R):
    """Hertz surface displacement shape w(r)/(a^2/R) * a^2/R, i.e. w(r) for
    a unit-normalised Hertz pressure (w(0) = a^2/R, w(a) = a^2/(2R))."""
    r = np.abs(np.asarray(r, float))
    out = np.empty_like(r)
    i = r <= a
    out[i] = (2 * a * a - r[i] ** 2) / (2 * R)
    ro = r[~i]
    out[~i] = ((2 * a * a - ro ** 2) * np.arcsin(a / ro)
               + a * np.sqrt(ro ** 2 - a * a)) / (np.pi * R)
    return out


def sphere(C, e, eps, R, a, phi0=0.0):
    """Rigid sphere (radius R) on a TI piezoelectric half-space, contact radius a.
    C: 6x6 Voigt stiffness (Pa), e: 3x6 (C/m^2), eps: 3x3 (F/m).
    Returns SI quantities for (1) conducting indenter at potential phi0
    (default 0 = grounded) and (2) insulating indenter (charge-free surface)."""
    g = surface_green(C, e, eps)
    m = g["m"]
    det = m[0, 0] * m[1, 1] - m[0, 1] * m[1, 0]
    C1 = m[1, 1] / det
    C3 = -m[0, 1] / det
    C4 = m[0, 0] / det
    Eins = 1.0 / m[0, 0]                       # = C1 + C3^2/C4
    cond = dict(
        P=4 * C1 * a ** 3 / (3 * R),
        h=a * a / R - C3 / C1 * phi0,
        p0=2 * C1 * a / (np.pi * R),
        Q=-4 * a ** 3 * C3 / (3 * R) + 2 * a * (C4 + C3 ** 2 / C1) * phi0,
        q0_elliptic=-2 * C3 * a / (np.pi * R),
        phi_center=phi0,
        Estar=C1)
    ins = dict(
        P=4 * Eins * a ** 3 / (3 * R),
        h=a * a / R,
        p0=2 * Eins * a / (np.pi * R),
        phi_center=(C3 / C4) * a * a / R,
        phi_edge=(C3 / C4) * a * a / (2 * R),
        Q=0.0,
        Estar=Eins)
    return dict(
        # flat keys requested in the brief (insulating/conducting share h if phi0 = 0)
        P_conducting=cond["P"], h_conducting=cond["h"], p0_conducting=cond["p0"],
        phi0_conducting_center=cond["phi_center"], Q_conducting=cond["Q"],
        P_insulating=ins["P"], h_insulating=ins["h"], p0_insulating=ins["p0"],
        phi_insulating_center=ins["phi_center"],
        conducting=cond, insulating=ins,
        C1star=C1, C3star=C3, C4star=C4, m=m, s=g["s"],
        rel_diff_routeA_routeB=g["rel_diff_routeA_routeB"])


# --------------------------------------------------------------------------
def _iso(E, nu, epsr=1e-8):
    lam = E * nu / ((1 + nu) * (1 - 2 * nu)); mu = E / (2 * (1 + nu))
    C = np.zeros((6, 6))
    C[:3, :3] = lam
    C[[0, 1, 2], [0, 1, 2]] = lam + 2 * mu
    C[[3, 4, 5], [3, 4, 5]] = mu
    return C, np.zeros((3, 6)), epsr * np.eye(3)


def _ti(c11, c12, c13, c33, c44, c66, e31, e33, e15, k11, k33):
    C = np.array([[c11, c12, c13, 0, 0, 0], [c12, c11, c13, 0, 0, 0],
                  [c13, c13, c33, 0, 0, 0], [0, 0, 0, c44, 0, 0],
                  [0, 0, 0, 0, c44, 0], [0, 0, 0, 0, 0, c66]], float)
    e = np.zeros((3, 6)); e[2, 0] = e[2, 1] = e31; e[2, 2] = e33
    e[0, 4] = e[1, 3] = e15
    eps = np.diag([k11, k11, k33])
    return C, e, eps


if __name__ == "__main__":
    np.set_printoptions(precision=6)
    R, a = 10e-3, 0.25e-3

    # ---- check 1: isotropic elastic, e = 0  -> Hertz
    E, nu = 100e9, 0.3
    r = sphere(*_iso(E, nu), R, a)
    Es = E / (1 - nu ** 2)
    P_h = 4 * Es * a ** 3 / (3 * R)
    print("CHECK 1 isotropic (E=100 GPa, nu=0.3), R=10 mm, a=0.25 mm")
    print("  Hertz  P = %.6e N,  h = %.6e m, p0 = %.6e Pa" %
          (P_h, a * a / R, 3 * P_h / (2 * np.pi * a * a)))
    for key in ("conducting", "insulating"):
        d = r[key]
        print("  %-10s P = %.6e N,  h = %.6e m, p0 = %.6e Pa, phi(0) = %.3e V"
              % (key, d["P"], d["h"], d["p0"], d["phi_center"]))
    assert abs(r["P_conducting"] / P_h - 1) < 1e-9
    assert abs(r["P_insulating"] / P_h - 1) < 1e-9

    # ---- check 1b: TI elastic (PZT-5H elastic constants, e = 0) vs Delafargue-Ulm
    C, e, eps = _ti(127.205e9, 80.212e9, 84.670e9, 117.436e9, 22.988e9, 23.474e9,
                    -6.62, 23.24, 17.03, 1.704e-8, 1.433e-8)
    r0 = sphere(C, 0 * e, eps, R, a)
    c11, c13, c33, c44 = C[0, 0], C[0, 2], C[2, 2], C[3, 3]
    M3 = 2 * np.sqrt((c11 * c33 - c13 ** 2) / c11 /
                     (1 / c44 + 2 / (np.sqrt(c11 * c33) + c13)))
    print("CHECK 1b TI elastic, e=0: 1/m11 = %.6e Pa, Delafargue-Ulm M3 = %.6e Pa"
          % (1 / r0["m"][0, 0], M3))
    assert abs(M3 * r0["m"][0, 0] - 1) < 1e-8
    m22_ref = 1 / (2 * np.sqrt(eps[0, 0] * eps[2, 2]))   # charge on dielectric half-space
    print("CHECK 1c e=0: m22 = %.6e V m/C, 1/(2 sqrt(eps11 eps33)) = %.6e"
          % (r0["m"][1, 1], m22_ref))
    assert abs(r0["m"][1, 1] / m22_ref - 1) < 1e-8

    # ---- PZT-5H
    r = sphere(C, e, eps, R, a)
    print("PZT-5H, R = 10 mm, a = 0.25 mm (poling +z into the body)")
    print("  s_i (roots of a s^6 - b s^4 + c s^2 - d = 0):", r["s"])
    print("  same s_i from eigenvalues of the 6x6 system matrix:",
          surface_green(C, e, eps)["s_from_N"])
    print("  route A (s_i, null vectors) vs route B (sign function) rel. diff: %.1e"
          % r["rel_diff_routeA_routeB"])
    m = r["m"]
    print("  m11 = %.6e 1/Pa, m12 = %.6e m^2/C, m21 = %.6e V m/N, m22 = %.6e V m/C"
          % (m[0, 0], m[0, 1], m[1, 0], m[1, 1]))
    print("  reciprocity m12 + m21 = %.2e (relative)" %
          (abs(m[0, 1] + m[1, 0]) / abs(m[0, 1])))
    print("  C1* = %.6e Pa, C3* = %.6e C/m^2, C4* = %.6e F/m"
          % (r["C1star"], r["C3star"], r["C4star"]))
    c = r["conducting"]; i = r["insulating"]
    print("  (1) conducting, grounded: P = %.6e N, h = %.6e m, p0 = %.6e Pa,"
          " phi(0) = %.1f V, Q = %.6e C" % (c["P"], c["h"], c["p0"],
                                            c["phi_center"], c["Q"]))
    print("  (2) insulating:           P = %.6e N, h = %.6e m, p0 = %.6e Pa,"
          " phi(0) = %.6e V" % (i["P"], i["h"], i["p0"], i["phi_center"]))
    print("      insulating phi(r=a) = %.6e V ; Hertz moduli: E*_cond = %.6e,"
          " E*_ins = %.6e Pa" % (i["phi_edge"], c["Estar"], i["Estar"]))
