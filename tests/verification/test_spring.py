"""A block on an elastic (Winkler) bed under uniform load, in every engine,
against its exact solution.

The block [0, 1]^d rests on a spring bed on its bottom face (y = 0):
traction -k_n (u.nu) nu - k_t u_tau. Its top carries the traction
(tau, -p), its x faces (0, -/+tau) (x = 0 / x = 1), so that the stress is
uniform: sigma_yy = -p, sigma_xy = tau, every other component zero, given
elastic and viscosity tensors that do not couple the normal components
(diagonal here). The top and bottom are grounded electrodes, and the
piezoelectric tensor has a D_y row only: phi = 0 and D_y is uniform. Then
    u_x = tau / k_t + gamma_n y,  u_y = -p / k_n + eps_n y  (u_z = 0),
the bed's share fixed by its balance with the uniform stress, the body's by
backward Euler on the uniform state,
    (B + A / k) eps_n = s + A / k eps_{n-1},  s = (0, -p, 0 | tau) in Voigt,
and the electrodes' charges are +/- D_y = e_y . eps_n (area 1); the bed's
resultant force on the body is (-tau, p) (area 1). P1 holds
the linear fields exactly: every probe value to round-off."""

import json

import numpy as np
import pytest
from conftest import ENGINES, ROOT, run_solver

P, TAU = 1e6, 3e5            # Pa: the top's pressure and shear
K_N, K_T = 1e12, 5e11        # N/m^3: the bed
T, STEPS = 1.0, 4


def tensors(d):
    """Diagonal elastic and viscosity tensors (Pa, Pa s), a piezoelectric
    tensor with a D_y row only (C/m^2), permittivity (F/m)."""
    if d == 2:
        B = np.diag([1.2e11, 1.1e11, 4e10])
        e = [[0.0, 0.0, 0.0], [-0.6, 1.1, 0.3]]
    else:
        B = np.diag([1.2e11, 1.1e11, 1.2e11, 4e10, 4e10, 3.5e10])
        e = [[0.0] * 6, [-0.6, 1.1, -0.6, 0.0, 0.0, 0.3], [0.0] * 6]
    return B, 0.1 * B, np.array(e), 7.4e-11 * np.eye(d)


def config(d):
    B, A, e, beta = tensors(d)
    zero = [0.0] * (d - 2)
    boundaries = {
        "bottom": {"spring": {"normal": K_N, "tangential": K_T}, "potential": 0.0},
        "top": {"traction": [TAU, -P] + zero, "potential": 0.0},
        "left": {"traction": [0.0, -TAU] + zero},
        "right": {"traction": [0.0, TAU] + zero},
    }
    mesh = ({"type": "unit_square", "n": 4} if d == 2
            else {"type": "box", "n": [2, 2, 2], "size": [1.0, 1.0, 1.0]})
    probes = [[1.0, 1.0], [0.5, 0.5], [0.0, 0.0]] if d == 2 else \
        [[1.0, 1.0, 1.0], [0.5, 0.5, 0.5], [0.0, 0.0, 1.0]]
    return {"mesh": mesh,
            "material": {"elastic": B.tolist(), "viscosity": A.tolist(),
                         "piezoelectric": e.tolist(), "permittivity": beta.tolist()},
            "boundaries": boundaries, "time": {"T": T, "steps": STEPS},
            "probes": probes, "output": {"xdmf": False}}


def exact_strains(d):
    """The uniform Voigt strain at each step (backward Euler)."""
    B, A, _, _ = tensors(d)
    k = T / STEPS
    s = np.zeros(len(B))
    s[1], s[-1] = -P, TAU  # sigma_yy, sigma_xy (the last Voigt entry in 2D and 3D)
    eps, out = np.zeros(len(B)), []
    for _ in range(STEPS):
        eps = np.linalg.solve(B + A / k, s + A @ eps / k)
        out.append(eps)
    return out


@pytest.mark.parametrize("d", [2, 3])
@pytest.mark.parametrize("engine", ENGINES)
def test_block_on_a_spring_bed(tmp_path, d, engine):
    cfg_file = tmp_path / "bed.json"
    cfg_file.write_text(json.dumps(config(d)))
    summary, _ = run_solver(engine, tmp_path / "out", config=cfg_file)
    assert summary["status"] == "completed"
    _, _, e, beta = tensors(d)
    for step, eps in zip(summary["steps"], exact_strains(d)):
        gamma, eps_yy = eps[-1], eps[1]
        scale = abs(P / K_N) + abs(eps_yy)
        for probe in step["probes"]:
            x, y = probe["point"][0], probe["point"][1]
            exact = [TAU / K_T + gamma * y, -P / K_N + eps_yy * y] + [0.0] * (d - 2)
            assert np.allclose(probe["u"], exact, rtol=0, atol=1e-10 * scale), (x, y)
            # the potential this strain would drive across the block, were
            # it not grounded on both faces
            assert abs(probe["phi"]) <= 1e-10 * abs(e[1] @ eps) / beta[1, 1]
        # the bed carries the top's load: (-tau, p) on the body, area 1
        assert np.allclose(step["spring_force"]["bottom"], [-TAU, P] + [0.0] * (d - 2),
                           rtol=0, atol=1e-10 * P)
        D_y = e[1] @ eps
        for name, sign in (("top", 1.0), ("bottom", -1.0)):
            electrode = step["electrodes"][name]
            assert electrode["charge"] == pytest.approx(sign * D_y, rel=1e-9)
            assert electrode["reaction_charge"] == pytest.approx(sign * D_y, rel=1e-9)


def test_spring_is_not_used_with_a_manufactured_solution(tmp_path):
    cfg = json.loads((ROOT / "demos" / "manufactured.json").read_text())
    cfg["boundaries"][next(iter(cfg["boundaries"]))]["spring"] = {"normal": 1e9}
    cfg_file = tmp_path / "mms.json"
    cfg_file.write_text(json.dumps(cfg))
    _, proc = run_solver("cpp", tmp_path / "out", config=cfg_file, check=False)
    assert proc.returncode == 2
    assert proc.stderr.count("\n") == 1 and ".spring: not used with a manufactured" in proc.stderr
