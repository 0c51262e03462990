"""Dynamic analyses against closed forms: the thickness-mode resonator of
IEEE Std 176-1987 (section 6.2: a plate poled and electroded across its
thickness, its lateral faces on rollers, is exactly one-dimensional), its
natural frequencies short- and open-circuited, their rates of convergence,
its admittance with Kelvin-Voigt damping, and a layer on the paper's
normal-compliance foundation with the contact open and closed.

The 1D layer, y in (0, t), poled along y: v(y) the displacement, phi(y),
D = e33 v' - eps33 phi' uniform (div D = 0), sigma = c33 v' + e33 phi'.
Short circuit (phi = 0 on both faces): D = e33 (v(t) - v(0)) / t and
sigma = c^D v' - (e33 / eps33) D, c^D = c33 + e33^2 / eps33: the modes odd
about the mid-plane solve X cos X = k_t^2 sin X, X = omega t / (2 v^D),
k_t^2 = e33^2 / (eps33 c^D), v^D = sqrt(c^D / rho); the even ones have
X = n pi. Open circuit (the top floating, zero charge): D = 0 and
f_n = n v^D / (2 t) (the antiresonances). Both with a rigid mode at 0 Hz."""

import cmath
import json
import math

import numpy as np
import pytest
from conftest import ROOT, run_solver

T, W = 1e-3, 0.1e-3  # meshes/thickness_layer.py
EPS0 = 8.854e-12
C33, E33, EPS33, RHO = 115e9, 15.1, 635 * EPS0, 7500.0  # the PZT-4 preset
CD = C33 + E33 ** 2 / EPS33
VD = math.sqrt(CD / RHO)
KT2 = E33 ** 2 / (EPS33 * CD)


def root(f, a, b, tol=1e-15):
    """f's root in [a, b] by bisection (f(a), f(b) of opposite signs)."""
    fa = f(a)
    for _ in range(200):
        m = 0.5 * (a + b)
        if (f(m) > 0) == (fa > 0):
            a, fa = m, f(m)
        else:
            b = m
        if b - a < tol * abs(b):
            break
    return 0.5 * (a + b)


def short_circuit(n):
    """The first n nonzero natural frequencies of the short-circuited layer."""
    X = []
    for j in range(n):
        if j % 2:  # even about the mid-plane: X = m pi
            X.append((j + 1) // 2 * math.pi)
        else:  # odd: X cos X = k^2 sin X, one root in (m pi, m pi + pi/2)
            m = j // 2
            X.append(root(lambda x: x * math.cos(x) - KT2 * math.sin(x),
                          m * math.pi + 1e-9, m * math.pi + math.pi / 2))
    return [x * VD / (math.pi * T) for x in X]


def open_circuit(n):
    return [k * VD / (2 * T) for k in range(1, n + 1)]


def layer(circuit, degree, size, analysis):
    top = {"potential": 0.0} if circuit == "short" else {"floating": {}}
    return {
        "mesh": {"type": "gmsh", "geometry": str(ROOT / "meshes" / "thickness_layer.py"),
                 "size": size},
        "formulation": "plane_strain",
        "elements": {"degree": degree},
        "material": {"preset": "PZT-4", "poling": [0.0, 1.0], "relaxation_time": 1e-9},
        "boundaries": {"left": {"displacement": [0.0, None]},
                       "right": {"displacement": [0.0, None]},
                       "bottom": {"potential": 0.0}, "top": top},
        "time": {"T": 1.0, "steps": 1},
        "analysis": analysis,
        "output": {"xdmf": False},
    }


def modes(tmp_path, cfg, engine="cpp"):
    path = tmp_path / "layer.json"
    path.write_text(json.dumps(cfg))
    summary, _ = run_solver(engine, tmp_path / f"out_{engine}", config=path)
    return [m["frequency"] for m in summary["modes"]], summary


@pytest.mark.parametrize("circuit", ["short", "open"])
def test_thickness_resonator(tmp_path, circuit):
    """P2 at t/30: the first three modes within 1e-5 of the exact ones, the
    rigid mode at 0 Hz (below 1e-4 of the first)."""
    f, _ = modes(tmp_path, layer(circuit, 2, T / 30, {"modal": {"modes": 4}}))
    exact = short_circuit(3) if circuit == "short" else open_circuit(3)
    print(circuit, [f"{a:.8g} ({a / b - 1:+.2e})" for a, b in zip(f[1:], exact)])
    assert abs(f[0]) < 1e-4 * exact[0]
    assert np.allclose(f[1:], exact, rtol=1e-5, atol=0)


@pytest.mark.parametrize("degree, n", [(1, (16, 32)), (2, (8, 16))])
def test_eigenvalue_rate(tmp_path, degree, n):
    """The eigenvalue error of the first short-circuit mode falls as h^(2p)
    (conforming Galerkin: twice the energy norm's rate), on the structured
    unit square (t = 1 m: the frequency scales as 1 / t; its lateral modes
    interleave, the mode nearest the exact one is asked for)."""
    exact = short_circuit(1)[0] * T / 1.0
    errors = []
    for cells in n:
        cfg = layer("short", degree, None, {"modal": {"modes": 1, "target": exact}})
        cfg["mesh"] = {"type": "unit_square", "n": cells}
        (tmp_path / str(cells)).mkdir()
        f, _ = modes(tmp_path / str(cells), cfg)
        errors.append(f[0] ** 2 / exact ** 2 - 1)
    rate = math.log(errors[0] / errors[1]) / math.log(n[1] / n[0])
    print(f"P{degree}: errors {errors}, rate {rate:.2f}")
    assert errors[0] > errors[1] > 0  # from above: Rayleigh-Ritz
    assert abs(rate - 2 * degree) < 0.1


def admittance(f, tau, V=1.0):
    """The closed-form admittance of the layer (per unit depth, width W)
    driven by V on top, grounded below, with Kelvin-Voigt damping A = tau B
    (elastic only: c33 -> c33 (1 + i omega tau)); Y = I / V, I the current
    the source drives into the top electrode, -i omega int D.nu."""
    w = 2 * math.pi * f
    cD = C33 * (1 + 1j * w * tau) + E33 ** 2 / EPS33
    k = w * cmath.sqrt(RHO / cD)
    h = T / 2
    # v = A sin(k (y - h)): sigma(0) = sigma(T) = 0 with D = (e33 (v(T) - v(0)) - eps33 V) / T
    A = -E33 * V / T / (cD * k * cmath.cos(k * h) - 2 * E33 ** 2 / (EPS33 * T) * cmath.sin(k * h))
    D = (E33 * 2 * A * cmath.sin(k * h) - EPS33 * V) / T
    Q = W * D  # int D.nu over the top (nu = +y)
    return Q, -1j * w * Q / V


def test_admittance_with_damping(tmp_path):
    """P2 at t/20 below, at and above the first resonance: the charge on
    the driven electrode within 1e-4 of the closed form (1e-3 at the
    resonance, where the damping alone bounds it)."""
    tau = 1e-9
    fr, fa = short_circuit(1)[0], open_circuit(1)[0]
    freqs = [0.5 * fr, fr, 0.5 * (fr + fa), 1.5 * fa]
    cfg = layer("short", 2, T / 20, {"harmonic": {"frequencies": freqs}})
    cfg["boundaries"]["top"] = {"potential": 1.0}
    cfg["material"]["relaxation_time"] = tau
    path = tmp_path / "layer.json"
    path.write_text(json.dumps(cfg))
    summary, _ = run_solver("cpp", tmp_path / "out", config=path)
    for entry, f in zip(summary["harmonic"], freqs):
        top = entry["electrodes"]["top"]
        Q = complex(*top["charge"])
        Y = complex(*top["admittance"])
        Q_exact, Y_exact = admittance(f, tau)
        print(f"{f:.6g} Hz: Y = {Y:.6g}, exact {Y_exact:.6g}, {abs(Y / Y_exact - 1):.2e}")
        tol = 1e-3 if f == fr else 1e-4
        assert abs(Q / Q_exact - 1) < tol and abs(Y / Y_exact - 1) < tol


def on_foundation(state):
    """The layer on the paper's foundation (c_p t / c^D = 1), its top
    grounded: open at the start (gap 1 nm), closed at the end of a run
    pressing it down."""
    cfg = layer("short", 2, T / 20, {"modal": {"modes": 3, "at": state}})
    cfg["contact"] = {"c_p": CD / T, "gap": 1e-9}
    cfg["boundaries"]["bottom"] = {"contact": True}
    cfg["boundaries"]["top"] = {"potential": 0.0,
                                "traction": [0.0, -1e6]} if state == "end" else {"potential": 0.0}
    return cfg


@pytest.mark.parametrize("state", ["start", "end"])
def test_modes_on_a_compliant_foundation(tmp_path, state):
    """Open (no contact): free-free, f = n v^D / (2 t) and a rigid mode.
    Closed: the bed is a spring c_p per unit area at y = 0,
    c^D v'(0) = c_p v(0), v'(t) = 0: X tan X = c_p t / c^D = 1, X = k t,
    then X + n pi roughly (each a root of the same equation)."""
    f, _ = modes(tmp_path, on_foundation(state))
    if state == "start":
        exact = [0.0] + open_circuit(2)
    else:
        X = [root(lambda x: x * math.tan(x) - 1.0, m * math.pi + 1e-9,
                  m * math.pi + math.pi / 2 - 1e-9) for m in range(3)]
        exact = [x * VD / (2 * math.pi * T) for x in X]
    print(state, f, exact)
    assert abs(f[0]) < 1e-4 * exact[1] if state == "start" else abs(f[0] / exact[0] - 1) < 1e-5
    assert np.allclose(f[1:], exact[1:], rtol=1e-5, atol=0)
