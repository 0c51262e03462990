"""Exact resonators for the dynamic analyses' tests: the thickness-mode
layer of IEEE Std 176-1987 (meshes/thickness_layer.py) poled along y, its
closed-form spectra short- and open-circuited, its admittance with
Kelvin-Voigt damping, and the configs of these problems (see
tests/verification/test_dynamics.py for the derivations)."""


import cmath
import math

from conftest import ROOT

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


def on_foundation(state):
    """The layer on the paper's foundation (c_p t / c^D = 1) at its bottom,
    its top grounded and held along y: open at the start (gap 1 nm),
    closed at the end of a run that moves the top down by 10 nm."""
    cfg = layer("short", 2, T / 20, {"modal": {"modes": 3, "at": state}})
    cfg["contact"] = {"c_p": CD / T, "gap": 1e-9}
    cfg["boundaries"]["bottom"] = {"contact": True}
    cfg["boundaries"]["top"] = {"potential": 0.0,
                                "displacement": [None, -1e-8 if state == "end" else 0.0]}
    return cfg


def on_rigid_plane(state):
    """The layer on a rigid plane at y = -1 nm below its bottom, Nitsche's
    method (no penetration: the Signorini limit), its top grounded and
    held: open at the start, closed at the end of a run that moves the top
    10 nm down. Its normal stress holds e^T grad phi: the linearised
    stiffness is not symmetric."""
    cfg = on_foundation(state)
    del cfg["contact"]
    cfg["boundaries"]["bottom"] = {"contact": {
        "method": "nitsche",
        "obstacle": {"plane": {"point": [0.0, -1e-9], "normal": [0.0, 1.0]}}}}
    return cfg
