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

import json
import math

import numpy as np
import pytest
from conftest import run_solver
from resonators import (VD, T, W, admittance, layer, on_foundation, on_rigid_plane,
                        open_circuit, root, short_circuit)


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


@pytest.mark.parametrize("state", ["start", "end"])
def test_modes_on_a_compliant_foundation(tmp_path, state):
    """The top held (v(t) = 0), v = sin(k (t - y)). Open (no contact): the
    bottom free, v'(0) = 0, X = k t = (2n - 1) pi / 2. Closed: the bed is
    a spring c_p per unit area at y = 0, c^D v'(0) = c_p v(0):
    tan X = -X c^D / (c_p t) = -X, one root in each ((2m + 1) pi / 2,
    (m + 1) pi): closing the contact raises every mode."""
    f, _ = modes(tmp_path, on_foundation(state))
    if state == "start":
        X = [(2 * n - 1) * math.pi / 2 for n in (1, 2, 3)]
    else:
        X = [root(lambda x: math.sin(x) + x * math.cos(x), (2 * m + 1) * math.pi / 2,
                  (m + 1) * math.pi) for m in range(3)]
    exact = [x * VD / (2 * math.pi * T) for x in X]
    print(state, f, exact)
    assert np.allclose(f, exact, rtol=1e-5, atol=0)


def test_modes_on_a_rigid_plane_by_nitsche(tmp_path):
    """Closed by Nitsche's method, the contact is the Signorini limit: the
    bottom cannot move along y, fixed-fixed, X = n pi, f_n = n v^D / (2 t).
    The pencil is not Hermitian (the normal stress holds the electric
    field): the condensed eigensolver answers. Nitsche is consistent, the
    error is the discretisation's: P2 at t/20, measured 3.0e-6, 1.4e-5 and
    3.8e-5 (the rigid boundary condition is weak: coarser than the bed's)."""
    f, summary = modes(tmp_path, on_rigid_plane("end"))
    exact = open_circuit(3)
    print(f, exact)
    assert summary["analysis_timing"]["pencil"] == "condensed"
    assert summary["steps"][-1]["contacts"]["bottom"]["force"][1] > 0
    assert abs(f[0] / exact[0] - 1) < 1e-5
    assert np.allclose(f, exact, rtol=1e-4, atol=0)


def test_fewer_modes_than_asked(tmp_path):
    """More modes than the model has: the ones found are kept in the
    summary, one line says how many, exit 3."""
    cfg = layer("short", 1, T / 4, {"modal": {"modes": 1000}})
    path = tmp_path / "layer.json"
    path.write_text(json.dumps(cfg))
    summary, proc = run_solver("cpp", tmp_path / "out", config=path, check=False)
    errors = [line for line in proc.stderr.splitlines() if line.startswith("error: ")]
    assert proc.returncode == 3 and len(errors) == 1, proc.stderr
    assert "the eigensolver converged" in errors[0] and "of the 1000 modes asked for" in errors[0]
    assert summary["status"] == "failed" and 0 < len(summary["modes"]) < 1000


def test_thickness_resonator_in_3d(tmp_path):
    """The same layer in 3D: a column 0.1 x 0.1 x 1 mm poled along z, its
    four lateral faces on rollers, P2: the first short-circuit modes
    within 1e-5."""
    cfg = layer("short", 2, None, {"modal": {"modes": 3}})
    cfg["mesh"] = {"type": "box", "n": [1, 1, 30], "size": [W, W, T]}
    cfg["material"]["poling"] = [0.0, 0.0, 1.0]
    del cfg["formulation"]
    cfg["boundaries"] = {"left": {"displacement": [0.0, None, None]},
                         "right": {"displacement": [0.0, None, None]},
                         "bottom": {"displacement": [None, 0.0, None]},
                         "top": {"displacement": [None, 0.0, None]},
                         "back": {"potential": 0.0}, "front": {"potential": 0.0}}
    f, _ = modes(tmp_path, cfg)
    exact = short_circuit(2)
    print(f, exact)
    assert abs(f[0]) < 1e-4 * exact[0]
    assert np.allclose(f[1:], exact, rtol=1e-5, atol=0)
