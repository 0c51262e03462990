"""The 2D formulations ("formulation": plane_strain | plane_stress |
axisymmetric) against closed forms no one here wrote:

* axisymmetric: a poled cylinder under axial pressure, short- and
  open-circuited (uniform fields: exact at degree 1); manufactured
  solutions at degrees 1 and 2 (exact polynomials, and the rates);
* plane stress: the exact pure-bending solution of a poled piezoelectric
  strip with electroded faces (Lim & He, Int. J. Mech. Sci. 43 (2001) 2479,
  homogeneous case; elastic part Timoshenko & Goodier, Theory of Elasticity
  sec. 21), loaded by a traction that varies linearly over the end,
  reproduced to round-off at degree 2;
* the material reductions are checked entry by entry in
  tests/cpp/test_materials.cpp.

The constants are read from config/materials.json here, independently of
the core's reductions."""

import json
import math

import numpy as np
import pytest
from conftest import ROOT, run_solver

PRESETS = json.loads((ROOT / "config" / "materials.json").read_text())["presets"]


def pzt5h():
    """PZT-5H's transversely isotropic constants (Pa, C/m^2, F/m)."""
    p = PRESETS["PZT-5H"]
    GPa, eps0 = 1e9, p["eps0"]
    return dict(c11=p["c11"] * GPa, c12=p["c12"] * GPa, c13=p["c13"] * GPa, c33=p["c33"] * GPa,
                c44=p["c44"] * GPa, e31=p["e31"], e33=p["e33"], e15=p["e15"],
                eps11=p["eps11"] * eps0, eps33=p["eps33"] * eps0)


def write(tmp_path, cfg, name="config.json"):
    path = tmp_path / name
    path.write_text(json.dumps(cfg))
    return path


def run(tmp_path, cfg, solver="cpp", name="run", overrides=()):
    config = write(tmp_path, cfg, name + ".json")
    return run_solver(solver, tmp_path / name, ["output.xdmf=false", "output.nodal=none",
                                                *overrides], config=config)[0]


# -- axisymmetric: a poled cylinder under axial pressure -------------------

PRESSURE = 1e6  # Pa, on the top face
TAU = 0.1       # the preset's relaxation time (s); one step of k = 1 s


def cylinder(top_electrode):
    """The unit cylinder r, y in [0, 1], poled along its axis y, on rollers
    at y = 0 (grounded), pressed by PRESSURE on y = 1."""
    return {
        "mesh": {"type": "unit_square", "n": 4, "diagonal": "crossed"},
        "formulation": "axisymmetric",
        "material": {"preset": "PZT-5H", "poling": [0, 1]},
        "boundaries": {"bottom": {"displacement": [None, 0.0], "potential": 0.0},
                       "top": {"traction": [0.0, -PRESSURE], **top_electrode},
                       "right": {}},
        "time": {"T": 1.0, "steps": 1},
        "probes": [[1.0, 1.0], [0.5, 0.5], [0.25, 0.75]],
    }


def uniform_state(open_circuit):
    """(eps_rr = eps_tt, eps_yy, E_y) of the uniform solution: sigma_rr =
    sigma_tt = 0, sigma_yy = -PRESSURE, and E_y = 0 (short circuit) or
    D_y = 0 (open). One backward-Euler step from rest with A = tau B is the
    elastic problem with B (1 + tau / k)."""
    m = pzt5h()
    s = 1 + TAU / 1.0
    c11, c12, c13, c33 = (s * m[k] for k in ("c11", "c12", "c13", "c33"))
    e31, e33, eps33 = m["e31"], m["e33"], m["eps33"]
    rows = [[c11 + c12, c13, -e31],          # sigma_rr = 0
            [2 * c13, c33, -e33],            # sigma_yy = -p
            [2 * e31, e33, eps33] if open_circuit else [0.0, 0.0, 1.0]]  # D_y = 0 | E_y = 0
    return np.linalg.solve(np.array(rows), np.array([0.0, -PRESSURE, 0.0]))


@pytest.mark.parametrize("circuit", ["short", "open"])
def test_axisymmetric_poled_cylinder_is_exact_at_degree_1(tmp_path, circuit):
    """u_r = a r, u_y = b y, phi = -E y: in the P1 space, so the discrete
    solution is the exact one (to round-off); the charge of the top
    electrode per revolution is pi R^2 D_y, the axial reaction pi R^2 p."""
    top = {"potential": 0.0} if circuit == "short" else {"floating": {}}
    s = run(tmp_path, cylinder(top))
    a, b, E = uniform_state(circuit == "open")
    step = s["steps"][-1]
    for probe in step["probes"]:
        r, y = probe["point"]
        assert probe["u"] == pytest.approx([a * r, b * y], rel=1e-10, abs=1e-12 * abs(b))
        assert probe["phi"] == pytest.approx(-E * y, rel=1e-10, abs=1e-10 * (abs(E) + 1))
    m = pzt5h()
    D_y = 2 * m["e31"] * a + m["e33"] * b + m["eps33"] * E
    charge = step["electrodes"]["top"]["charge"]
    assert charge == pytest.approx(math.pi * D_y, rel=1e-9, abs=1e-12 * math.pi * abs(m["e33"] * b))
    assert abs(step["reactions"]["bottom"][1]) == pytest.approx(math.pi * PRESSURE, rel=1e-10)
    assert s["units"]["charges"] == "C, per full revolution"  # the summary says so
    if circuit == "open":  # the open circuit stiffens the cylinder (the coupling)
        assert abs(b) < abs(uniform_state(False)[1])


# -- axisymmetric: manufactured solutions ----------------------------------

MMS_2D = ROOT / "demos" / "manufactured.json"
AXISYMMETRIC = ["formulation=axisymmetric", 'material={"preset": "PZT-5H", "poling": [0, 1]}']


def mms_errors(tmp_path, space, n, degree, solver="cpp"):
    """Largest error of each field over two steps (linear in time: the space
    error alone), relative to the exact solution's size."""
    from manufactured import PHI0, U0
    s = run_solver(solver, tmp_path / f"{space}{n}p{degree}{solver}",
                   [*AXISYMMETRIC, f"manufactured.space={space}", "manufactured.time=linear",
                    f"mesh.n={n}", "time.steps=2", f"elements.degree={degree}",
                    "output.xdmf=false", "output.nodal=none"], config=MMS_2D)[0]
    return {name: max(st["errors"][name] for st in s["steps"]) / (U0 if name[0] == "u" else PHI0)
            for name in ("u_L2", "u_H1", "phi_L2", "phi_H1")}


@pytest.fixture(autouse=True)
def forms_on_path():
    import sys
    sys.path.insert(0, str(ROOT / "forms"))


@pytest.mark.parametrize("space,degree", [("linear", 1), ("quadratic", 2)])
def test_axisymmetric_polynomial_solutions_are_exact(tmp_path, space, degree):
    """A linear solution at P1 and a quadratic one at P2 (u_r vanishing on
    the axis, as the formulation imposes; the hoop strain u_r / r and the
    2 pi r weight in every term): round-off. Measured 2e-14 (P1), 4e-13 (P2)."""
    errors = mms_errors(tmp_path, space, 8, degree)
    assert max(errors.values()) < 1e-11, errors


@pytest.mark.parametrize("degree,sizes", [(1, (16, 32)), (2, (8, 16))])
def test_axisymmetric_rates(tmp_path, degree, sizes):
    """Smooth solution: H1 rate k, L2 rate k + 1. Measured: P1 (16 -> 32)
    see docs/verification.md; P2 (8 -> 16) u 2.05 / 3.13, phi 1.97 / 2.98."""
    coarse, fine = (mms_errors(tmp_path, "smooth", n, degree) for n in sizes)
    for name in coarse:
        rate = math.log2(coarse[name] / fine[name])
        expected = degree if name.endswith("H1") else degree + 1
        assert abs(rate - expected) <= 0.2, (name, rate)


# -- plane stress: pure bending of a poled strip ---------------------------

def plane_stress_constants():
    """PZT-5H poled along y, sigma_zz = 0 condensed out by hand (the
    classical reduced constants): C11, C12, C22, e31, e33, eps33."""
    m = pzt5h()
    c11, c12, c13, c33, e31, e33 = (m[k] for k in ("c11", "c12", "c13", "c33", "e31", "e33"))
    return dict(C11=c11 - c12 ** 2 / c11, C12=c13 - c12 * c13 / c11, C22=c33 - c13 ** 2 / c11,
                e31=e31 - e31 * c12 / c11, e33=e33 - e31 * c13 / c11,
                eps33=m["eps33"] + e31 ** 2 / c11)


def bending_solution(curvature, tau_factor):
    """The strip 0 <= x, y <= 1 (y across it), electrodes y = 0, 1 grounded,
    sigma_yy = sigma_xy = 0, no axial force: eps_xx = A0 + A1 y, D_y = D0
    (div D = 0), and at each y sigma_yy = 0, D_y = D0 give eps_yy, E_y
    linear in y; A0 and D0 from N = int sigma_xx dy = 0 and int E_y dy = 0
    (both electrodes at 0 V). Returns polynomial coefficients of eps_yy,
    E_y, sigma_xx in y (numpy order: highest first) and A0, A1."""
    c = plane_stress_constants()
    s = tau_factor
    C11, C12, C22 = s * c["C11"], s * c["C12"], s * c["C22"]
    e31, e33, eps33 = c["e31"], c["e33"], c["eps33"]
    # [[C22, -e33], [e33, eps33]] [eps_yy, E] = [-C12 eps_xx, D0 - e31 eps_xx]
    K = np.linalg.inv(np.array([[C22, -e33], [e33, eps33]]))

    def fields(A0, A1, D0):
        exx = np.array([A1, A0])  # A1 y + A0
        rhs0, rhs1 = -C12 * exx, np.array([0.0, D0]) - e31 * exx
        eyy, E = K[0, 0] * rhs0 + K[0, 1] * rhs1, K[1, 0] * rhs0 + K[1, 1] * rhs1
        sxx = C11 * exx + C12 * eyy - e31 * E
        return eyy, E, sxx

    def integral(p):  # int_0^1 of a linear polynomial
        return p[0] / 2 + p[1]

    A1 = curvature
    # N and int E are linear in (A0, D0): solve from their values at unit steps
    base = [integral(f) for f in fields(0.0, A1, 0.0)[2:0:-1]]   # [N, int E] at A0 = D0 = 0
    dA0 = [integral(f) - b for f, b in zip(fields(1.0, A1, 0.0)[2:0:-1], base)]
    dD0 = [integral(f) - b for f, b in zip(fields(0.0, A1, 1.0)[2:0:-1], base)]
    A0, D0 = np.linalg.solve(np.array([dA0, dD0]).T, -np.array(base))
    eyy, E, sxx = fields(A0, A1, D0)
    return dict(A0=A0, A1=A1, D0=D0, eyy=eyy, E=E, sxx=sxx)


def num(v):
    """A number as an expression reads it, to the last bit."""
    return repr(float(v))


def test_plane_stress_pure_bending_is_exact_at_degree_2(tmp_path):
    """u_x = (A0 + A1 y) x, u_y = int eps_yy dy - A1 x^2 / 2, phi = -int E dy:
    quadratic, so P2 holds it. Loads given as expressions: sigma_xx(y) on
    x = 1 (a traction varying linearly over the end), the exact u on x = 0
    (u_x = 0, u_y(y) quadratic). Viscosity: one step from rest, B (1 + tau)."""
    sol = bending_solution(1e-5, 1 + TAU)
    eyy, E, sxx = sol["eyy"], sol["E"], sol["sxx"]
    uy0 = f"{num(eyy[0] / 2)}*y*y + {num(eyy[1])}*y"     # int_0^y eps_yy
    cfg = {
        "mesh": {"type": "unit_square", "n": 4, "diagonal": "crossed"},
        "formulation": "plane_stress",
        "elements": {"degree": 2},
        "material": {"preset": "PZT-5H", "poling": [0, 1]},
        "boundaries": {"left": {"displacement": [0.0, uy0]},
                       "right": {"traction": [f"{num(sxx[0])}*y + {num(sxx[1])}", 0.0]},
                       "bottom": {"potential": 0.0}, "top": {"potential": 0.0}},
        "time": {"T": 1.0, "steps": 1},
        "probes": [[1.0, 1.0], [0.5, 0.25], [0.75, 0.6], [1.0, 0.0]],
    }
    s = run(tmp_path, cfg)
    scale_u = abs(sol["A1"]) / 2 + abs(sol["A0"])
    scale_phi = abs(E).sum()
    for probe in s["steps"][-1]["probes"]:
        x, y = probe["point"]
        ux = (sol["A0"] + sol["A1"] * y) * x
        uy = eyy[0] / 2 * y * y + eyy[1] * y - sol["A1"] * x * x / 2
        phi = -(E[0] / 2 * y * y + E[1] * y)
        assert np.allclose(probe["u"], [ux, uy], rtol=0, atol=1e-9 * scale_u), (probe, ux, uy)
        assert probe["phi"] == pytest.approx(phi, abs=1e-9 * scale_phi)
    # the electrodes carry -+ D0 per unit length and thickness
    assert s["units"]["charges"] == "C/m, per unit thickness"
    electrodes = s["steps"][-1]["electrodes"]
    assert electrodes["top"]["charge"] == pytest.approx(sol["D0"], rel=1e-8)
    assert electrodes["bottom"]["charge"] == pytest.approx(-sol["D0"], rel=1e-8)


# -- data that vary in space: loads given only as expressions --------------

def polynomial_solution(formulation):
    """An exact solution u = t U(x), phi = t Phi(x) (U, Phi quadratic: P2
    holds them; linear in t: backward Euler is exact) and the loads that
    make it solve the model, derived here with sympy from the strong form,
    as muparser expressions: the body force and free charge, the traction
    and surface charge of every side of the unit square, the Dirichlet
    values of the left side. Material: PZT-5H poled along y, reduced by
    the formulation by the core (its tensors are read back from the
    summary, so that this derivation is independent of the reduction)."""
    import sympy as sp
    x, y, t = sp.symbols("x y t")
    if formulation == "axisymmetric":  # regular on the axis: u_r odd in r, u_z and phi even
        U = [x * (sp.Rational(1, 2) - sp.Rational(3, 5) * y),
             1 + sp.Rational(3, 10) * x * x - sp.Rational(1, 5) * y * y]
        Phi = sp.Rational(3, 10) + y / 2 - sp.Rational(2, 5) * y ** 2 + x * x / 5
    else:
        U = [x / 2 + y / 4 - sp.Rational(3, 5) * x * y, 1 - x + sp.Rational(3, 10) * x * x]
        Phi = sp.Rational(3, 10) + x / 2 - sp.Rational(2, 5) * y ** 2 + sp.Rational(1, 5) * x * y
    return x, y, t, [1e-9 * t * c for c in U], 100 * t * Phi


def expression(e):
    """A sympy expression as muparser reads it."""
    import sympy as sp
    return str(sp.nsimplify(e, rational=False)).replace("**", "^")


def strong_form_loads(formulation, mat):
    """{body_force, charge_density, traction: {side: [..]}, surface_charge:
    {side: ..}, u, phi} of the polynomial solution, as expressions."""
    import sympy as sp
    x, y, t, u, phi = polynomial_solution(formulation)
    B, A = sp.Matrix(mat["elastic"]), sp.Matrix(mat["viscosity"])
    e, beta = sp.Matrix(mat["piezoelectric"]), sp.Matrix(mat["permittivity"])
    axi = formulation == "axisymmetric"
    ux, uy = u

    def strain(vx, vy):
        parts = [sp.diff(vx, x), sp.diff(vy, y)] + ([vx / x] if axi else []) \
            + [sp.diff(vx, y) + sp.diff(vy, x)]
        return sp.Matrix(parts)

    eps = strain(ux, uy)
    eps_dot = strain(sp.diff(ux, t), sp.diff(uy, t))
    grad_phi = sp.Matrix([sp.diff(phi, x), sp.diff(phi, y)])
    s = B * eps + A * eps_dot + e.T * grad_phi           # Voigt stress
    D = e * eps - beta * grad_phi
    sxx, syy, sxy = s[0], s[1], s[-1]
    f = [-(sp.diff(sxx, x) + sp.diff(sxy, y)), -(sp.diff(sxy, x) + sp.diff(syy, y))]
    q = sp.diff(D[0], x) + sp.diff(D[1], y)
    if axi:  # the hoop terms of div sigma and div D
        f = [f[0] - (sxx - s[2]) / x, f[1] - sxy / x]
        q = q + D[0] / x
    normals = {"left": (-1, 0), "right": (1, 0), "bottom": (0, -1), "top": (0, 1)}
    traction = {side: [sp.expand(sxx * n[0] + sxy * n[1]), sp.expand(sxy * n[0] + syy * n[1])]
                for side, n in normals.items()}
    charge = {side: sp.expand(-(D[0] * n[0] + D[1] * n[1])) for side, n in normals.items()}
    return dict(body_force=[sp.cancel(c) for c in f], charge_density=sp.cancel(q),
                traction=traction, surface_charge=charge, u=u, phi=phi)


def resolved_material(tmp_path, formulation):
    """The material as the core resolves it in a formulation (a zero-step
    look: a 1-step run of the cylinder)."""
    cfg = cylinder({"potential": 0.0})
    cfg["formulation"] = formulation
    if formulation != "axisymmetric":
        cfg["boundaries"]["left"] = {"displacement": [0.0, None]}
    return run(tmp_path, cfg, name=f"material_{formulation}")["config"]["material"]


def loads_only_config(tmp_path, formulation, degree=2, n=4):
    """The unit square with the polynomial solution's data as expressions:
    body loads, the traction and charge of the right, top and bottom sides,
    the exact u and phi on the left side (the axis in axisymmetry, where u_r
    = 0 is the formulation's own condition)."""
    loads = strong_form_loads(formulation, resolved_material(tmp_path, formulation))
    ex = expression
    sides = {side: {"traction": [ex(c) for c in loads["traction"][side]],
                    "surface_charge": ex(loads["surface_charge"][side])}
             for side in ("right", "top", "bottom")}
    left = {"displacement": [None if formulation == "axisymmetric" else ex(loads["u"][0]),
                             ex(loads["u"][1])],
            "potential": ex(loads["phi"])}
    return {
        "mesh": {"type": "unit_square", "n": n, "diagonal": "crossed"},
        "formulation": formulation,
        "elements": {"degree": degree},
        "material": {"preset": "PZT-5H", "poling": [0, 1]},
        "loads": {"body_force": [ex(c) for c in loads["body_force"]],
                  "charge_density": ex(loads["charge_density"])},
        "boundaries": {"left": left, **sides},
        "time": {"T": 1.0, "steps": 2},
        "probes": [[1.0, 1.0], [0.5, 0.25], [0.75, 0.6], [0.25, 0.0]],
    }, loads


@pytest.mark.parametrize("formulation", ["plane_strain", "plane_stress", "axisymmetric"])
def test_loads_given_only_as_expressions_reproduce_the_exact_solution(tmp_path, formulation):
    """Every datum an expression of x, y, t (the loads of the strong form,
    linear in t): the quadratic solution comes out at degree 2 to
    round-off at every step, in every formulation."""
    import sympy as sp
    cfg, loads = loads_only_config(tmp_path, formulation)
    s = run(tmp_path, cfg)
    x, y, t = sp.symbols("x y t")
    u = [sp.lambdify((x, y, t), c) for c in loads["u"]]
    phi = sp.lambdify((x, y, t), loads["phi"])
    for step in s["steps"]:
        for probe in step["probes"]:
            px, py = probe["point"]
            exact_u = [c(px, py, step["t"]) for c in u]
            assert np.allclose(probe["u"], exact_u, rtol=0, atol=1e-9 * 1e-9), (probe, exact_u)
            assert probe["phi"] == pytest.approx(phi(px, py, step["t"]), abs=1e-9 * 100)


def test_an_expression_in_t_equals_the_same_history_as_a_table(tmp_path):
    """A traction -1e4 x min(2 t, 1) (an expression of x and t) and the
    traction -1e4 x with the history table [[0, 0], [0.5, 1], [1, 1]]: the
    same run, to round-off."""
    from piezocontact import compare
    base = json.loads((ROOT / "demos" / "square.json").read_text())
    base.update({"mesh": {"type": "unit_square", "n": 8}, "time": {"T": 1.0, "steps": 8}})
    by_t = json.loads(json.dumps(base))
    by_t["boundaries"]["top"]["traction"] = ["-1e4*x*min(2*t, 1)", "-10*min(2*t, 1)"]
    table = json.loads(json.dumps(base))
    table["boundaries"]["top"]["traction"] = {
        "value": ["-1e4*x", -10.0], "history": {"table": [[0, 0], [0.5, 1], [1, 1]]}}
    a, b = run(tmp_path, by_t, name="by_t"), run(tmp_path, table, name="table")
    assert len(a["steps"]) == len(b["steps"]) == 8
    for d in compare.probe_differences(a, b):
        assert d["u"] < 1e-13 and d["phi"] < 1e-13, d
    # and the expression matters: without the x, another answer
    base["boundaries"]["top"]["traction"] = {"value": [-1e4, -10.0],
                                             "history": {"table": [[0, 0], [0.5, 1], [1, 1]]}}
    c = run(tmp_path, base, name="uniform")
    assert max(d["u"] for d in compare.probe_differences(a, c)) > 1e-3


# -- engines agree in every formulation, with spatial data -----------------

@pytest.mark.parametrize("formulation", ["plane_strain", "plane_stress", "axisymmetric"])
def test_engines_agree_in_every_formulation(tmp_path, formulation):
    """The executable, the C++ loop on JIT kernels and the reference engine
    on the loads-only problem at degree 1 (not exact there: the engines
    must agree on a discrete answer that is not the exact one) with
    contact on the top (a gap that varies along it): probes and nodal
    fields to 1e-9 of their size (compare.py)."""
    from piezocontact import compare
    cfg, _ = loads_only_config(tmp_path, formulation, degree=1, n=6)
    # the top rises by ~1e-9 t: it meets a foundation 2-4e-10 above it
    cfg["contact"] = {"c_p": 1e13, "gap": "2e-10*(1 + x)"}
    cfg["boundaries"]["top"] = {"contact": True,
                                "surface_charge": cfg["boundaries"]["top"]["surface_charge"]}
    runs = {e: run(tmp_path, cfg, solver=e, name=e, overrides=["output.nodal=all"])
            for e in ("cpp", "cpp-jit", "reference")}
    assert any(st["contact_length"] > 0 for st in runs["cpp"]["steps"])  # contact happens
    if formulation != "axisymmetric":  # the corner (0, 1) holds the exact u: u.nu = 1e-9 t
        for st in runs["cpp"]["steps"]:  # the largest u.nu - g(x) is there: g's field counts
            assert st["max_penetration"] == pytest.approx(1e-9 * st["t"] - 2e-10, rel=1e-9)
    for other in ("cpp-jit", "reference"):
        for d in compare.probe_differences(runs["cpp"], runs[other]):
            assert d["u"] < 1e-9 and d["phi"] < 1e-9, (other, d)
        diffs = compare.field_differences(tmp_path / "cpp", tmp_path / other, runs[other])
        for step, d in diffs.items():
            assert d["u"] < 1e-9 and d["phi"] < 1e-9, (other, step, d)


# -- plane stress: a thin 3D plate tends to it -----------------------------

def test_thin_3d_plates_tend_to_plane_stress(tmp_path):
    """The plate of demos/plate.json (clamped in its plane, pulled and bent
    by an expression traction) in 3D, half of its thickness t with the
    mid-plane on rollers, at degree 2: the tip deflection and the charge
    per unit thickness approach plane stress as t falls (measured at n = 8:
    0.11 %, 0.02 % at t = 0.2, 0.05), never plane strain (31 % off)."""
    from demo_plate import answer, plate_3d
    plate = json.loads((ROOT / "demos" / "plate.json").read_text())
    plate["mesh"]["n"] = 8
    plate["time"]["steps"] = 1
    stress = answer(run(tmp_path, plate, name="stress"))
    strain = answer(run(tmp_path, dict(plate, formulation="plane_strain"), name="strain"))
    off = []
    for t in (0.2, 0.05):
        a = answer(run(tmp_path, plate_3d(plate, t, 8), name=f"plate{t}"), t / 2)
        off.append(max(abs(a[k] / stress[k] - 1) for k in a))
    assert off[1] < off[0] / 2 and off[1] < 1e-3, off
    assert min(abs(strain[k] / stress[k] - 1) for k in strain) > 0.2


@pytest.mark.parametrize("engine", ["cpp", "cpp-jit", "reference"])
def test_an_expression_that_stops_being_finite_stops_the_run(tmp_path, engine):
    """1/(1 - t) is finite until t = 1: the run stops at that step with
    exit 2 and one line naming the datum, the point and t; the summary
    says failed with that line and keeps the three steps before."""
    s, proc = run_solver(engine, tmp_path / "out",
                         ['boundaries.top.traction=["1/(1-t)", 0]', "mesh.n=4", "time.steps=4",
                          "output.xdmf=false", "output.nodal=none"], check=False)
    errors = [line for line in proc.stderr.splitlines() if line.startswith("error: ")]
    assert proc.returncode == 2 and len(errors) == 1, proc.stderr
    assert 'boundaries.top.traction[0]: "1/(1-t)" is inf at' in errors[0]
    assert "at t = 1.0: a datum must be finite everywhere" in errors[0]
    assert s["status"] == "failed" and s["error"] in errors[0] and len(s["steps"]) == 3


def test_an_expression_of_t_is_a_datum_from_the_first_step_on(tmp_path):
    """Nothing is solved at t = 0: 1/t is a datum (a traction decaying from
    the first step's value on), and the run completes."""
    s, _ = run_solver("cpp", tmp_path / "out",
                      ['boundaries.top.traction=[0, "-2.5/t"]', "mesh.n=4", "time.steps=4",
                       "output.xdmf=false", "output.nodal=none"])
    assert s["status"] == "completed" and len(s["steps"]) == 4
    # the load falls as 1/t (the viscosity lags it): the supports carry less
    first, last = (abs(st["support_force"]) for st in (s["steps"][0], s["steps"][-1]))
    assert first > 2 * last > 0
