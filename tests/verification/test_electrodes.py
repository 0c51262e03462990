"""Electrodes (issue 14): floating potentials, the charge on every electrode
two ways (int D.nu and the reaction of the electric residual), currents,
charge conservation, the contact pressure field; the engines agree with
floating electrodes, histories and regions, serial and under MPI."""

import json
import math

import numpy as np
import pytest
from conftest import ROOT, resume, run_solver
from test_devices import BILAYER, QUIET, SIGMA0, relative, step_values, uniform_block, write

CONTACTOR = ROOT / "demos" / "contactor.json"


def block(tmp_path, d, top):
    """The uniform block of test_devices poled along y (the unit cube, or
    in 2D the unit square), grounded at the bottom, compressed by SIGMA0 on
    its top, which is the electrode `top` (a dict of boundary keys)."""
    cfg = json.loads(uniform_block(tmp_path, 1).read_text())
    cfg["boundaries"]["top"].update(top)
    if d == 2:
        cfg["mesh"] = {"type": "unit_square", "n": 2, "diagonal": "crossed"}
        cfg["material"]["poling"] = [0.0, 1.0]
        del cfg["boundaries"]["back"]
        for bc in cfg["boundaries"].values():
            for key in ("displacement", "traction"):
                if key in bc:
                    bc[key] = bc[key][:2]
        cfg["probes"] = [[1.0, 1.0], [0.5, 0.25]]
    return write(tmp_path / f"block_{d}d.json", cfg)


def recurrence(material, k, steps, top_charge=None):
    """Backward Euler on the block's uniform state: normal strains eps, no
    shear (rollers), sigma_yy = -SIGMA0, the other normal stresses 0.
    Floating top (top_charge(t): its charge, the block's top of unit
    measure): D = (0, Q, 0) everywhere, grad phi = beta^-1 (e eps - D), so
    (B + e^T beta^-1 e) eps + A (eps - eps_prev)/k = load + e^T beta^-1 D.
    Short-circuited (top_charge None): grad phi = 0, D = e eps.
    Returns (eps, grad phi, D) per step."""
    B, A = np.array(material["elastic"]), np.array(material["viscosity"])
    e, beta = np.array(material["piezoelectric"]), np.array(material["permittivity"])
    d = len(beta)
    normal = np.ix_(range(d), range(d))

    def strain(eps):
        s = np.zeros(len(B))
        s[:d] = eps
        return s

    coupling = e.T @ np.linalg.solve(beta, e) if top_charge else np.zeros_like(B)
    visc = A[normal] / k
    eps, out = np.zeros(d), []
    for n in range(1, steps + 1):
        load = np.zeros(d)
        load[1] = -SIGMA0
        D = np.zeros(d)
        if top_charge:
            D[1] = top_charge(n * k)
            load += (e.T @ np.linalg.solve(beta, D))[:d]
        eps = np.linalg.solve((B + coupling)[normal] + visc, load + visc @ eps)
        grad_phi = np.linalg.solve(beta, e @ strain(eps) - D) if top_charge else np.zeros(d)
        out.append((eps, grad_phi, e @ strain(eps) - beta @ grad_phi))
    return out


Q0 = 2e-4  # C (C/m in 2D): of the order of the piezoelectric charge SIGMA0 makes in PZT-5H
CHARGES = {"open": ({}, lambda t: 0.0),
           "charged": ({"charge": {"value": Q0, "history": {"ramp": 0.25}}},
                       lambda t: Q0 * min(t / 0.25, 1.0))}


@pytest.mark.parametrize("d", [2, 3])
@pytest.mark.parametrize("kind", list(CHARGES))
def test_floating_potential_is_the_creep_recurrence(tmp_path, d, kind):
    """A floating top electrode (open circuit, or a ramped charge) on the
    block grounded at its bottom: its potential at every step is the
    backward-Euler recurrence of the strains and the field to 1e-10, the
    field uniform (probes), and the charge on it, both ways, the prescribed
    one; the grounded bottom carries the opposite charge."""
    floating, Q = CHARGES[kind]
    s = run_solver("cpp", tmp_path / "out", QUIET,
                   config=block(tmp_path, d, {"floating": floating}))[0]
    exact = recurrence(s["config"]["material"], 0.1, 5, Q)
    scale = max(abs(D[1]) for _, _, D in exact) + Q0  # the charges in play
    for step, (eps, grad_phi, D) in zip(s["steps"], exact):
        top, bottom = step["electrodes"]["top"], step["electrodes"]["bottom"]
        assert top["potential"] == pytest.approx(grad_phi[1], rel=1e-10)
        for probe in step["probes"]:
            assert probe["phi"] == pytest.approx(grad_phi @ probe["point"], rel=1e-10)
        for key in ("charge", "reaction_charge"):
            assert abs(top[key] - Q(step["t"])) < 1e-10 * scale, (step["t"], key, top)
            assert abs(bottom[key] + Q(step["t"])) < 1e-10 * scale, (step["t"], key, bottom)
        assert bottom["potential"] == 0.0
    assert abs(exact[-1][1][1]) > 1e3  # volts: the field was there to be found


@pytest.mark.parametrize("d", [2, 3])
def test_short_circuit_charges_are_plus_minus_D_y(tmp_path, d):
    """Both electrodes grounded: no field, D = e eps uniform; the charges,
    both ways, are +D_y (top) and -D_y (bottom) times the unit measure to
    1e-10 and sum to zero; the current is their backward-Euler rate."""
    s = run_solver("cpp", tmp_path / "out", QUIET,
                   config=block(tmp_path, d, {"potential": 0.0}))[0]
    exact = recurrence(s["config"]["material"], 0.1, 5)
    before = 0.0
    for step, (_, _, D) in zip(s["steps"], exact):
        top, bottom = step["electrodes"]["top"], step["electrodes"]["bottom"]
        for key in ("charge", "reaction_charge"):
            assert top[key] == pytest.approx(D[1], rel=1e-10)
            assert bottom[key] == pytest.approx(-D[1], rel=1e-10)
            assert abs(top[key] + bottom[key]) < 1e-10 * abs(D[1])
        assert top["current"] == pytest.approx((top["charge"] - before) / 0.1, rel=1e-12)
        before = top["charge"]
    assert abs(exact[-1][2][1]) > 1e-4  # C/m^2


def polygon_area(points):
    x, y = np.array(points).T
    return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def test_charge_is_conserved(tmp_path):
    """Example 2 with its high electrode floating under a sine charge, a
    free charge q0 and a surface charge qF on its upper free side: at every
    step the charges of all electrodes by reaction sum to int q0 + int qF
    (the signs of (2.19)) to round-off, and the floating one carries its
    charge; int D.nu, through the field's singularity at the electrode
    ends, agrees to discretisation error only (docs/verification.md)."""
    import sys
    sys.path.insert(0, str(ROOT / "meshes"))
    from contactor import POINTS
    cfg = json.loads(CONTACTOR.read_text())
    cfg["mesh"]["geometry"] = str(ROOT / "meshes" / "contactor.py")
    Qf = 3e-10
    cfg["boundaries"]["electrode_high"] = {
        "floating": {"charge": {"value": Qf, "history": {"sine": {"frequency": 0.1}}}}}
    cfg["boundaries"]["free_upper"] = {"surface_charge": 2e-10}
    cfg["loads"] = {"charge_density": -1e-10}
    s = run_solver("cpp", tmp_path / "out", ["time.steps=5"] + QUIET,
                   config=write(tmp_path / "contactor.json", cfg))[0]
    free = -1e-10 * polygon_area(POINTS) + 2e-10 * s["boundary_lengths"]["free_upper"]
    for step in s["steps"]:
        charges = {n: e["reaction_charge"] for n, e in step["electrodes"].items()}
        scale = sum(abs(q) for q in charges.values())
        assert abs(sum(charges.values()) - free) < 1e-12 * scale, step["electrodes"]
        target = Qf * math.sin(2 * math.pi * 0.1 * step["t"])
        assert abs(charges["electrode_high"] - target) < 1e-10 * scale
        functional = sum(e["charge"] for e in step["electrodes"].values())
        assert abs(functional - free) < 0.5 * scale  # discretisation, not round-off
    assert abs(free) > 1e-10


def floating_bilayer(tmp_path):
    """The two-region bilayer with a sine potential on its left side, a
    floating right side (both layers) under a ramped charge and a ramped
    traction: floating electrodes, histories and regions together."""
    cfg = json.loads(BILAYER.read_text())
    cfg["mesh"]["path"] = str(BILAYER.parent / cfg["mesh"]["path"])
    cfg["boundaries"]["left"]["potential"] = {"value": 5.0, "history": {"sine": {"frequency": 0.5}}}
    cfg["boundaries"]["right"] = {"floating": {"charge": {"value": 1e-10, "history": {"ramp": 0.5}}}}
    cfg["boundaries"]["top"]["traction"] = {"value": [0.0, -10.0], "history": {"ramp": 0.5}}
    return write(tmp_path / "bilayer.json", cfg)


ELECTRODE_KEYS = ("potential", "charge", "reaction_charge", "current")


def electrode_values(summary):
    """Per quantity of ELECTRODE_KEYS: (steps, electrodes) values, each
    compared in its own unit."""
    return {k: np.array([[e[k] for _, e in sorted(step["electrodes"].items())]
                         for step in summary["steps"]]) for k in ELECTRODE_KEYS}


def assert_electrodes_agree(a, b, tol=1e-8):
    assert len(a["steps"]) == len(b["steps"])
    x, y = electrode_values(a), electrode_values(b)
    for k in ELECTRODE_KEYS:
        assert relative(x[k], y[k]) < tol, k


@pytest.mark.parametrize("other,np_", [("cpp-jit", 1), ("reference", 1), ("cpp", 2),
                                       ("reference", 2)])
def test_engines_agree_with_floating_electrodes(tmp_path, other, np_):
    """cpp against the other engines, serial and on two ranks: probes,
    forces, reactions, electrode potentials and charges at every step to
    1e-8."""
    config = floating_bilayer(tmp_path)
    a = run_solver("cpp", tmp_path / "cpp", ["time.steps=4"] + QUIET, config=config)[0]
    b = run_solver(other, tmp_path / other, ["time.steps=4"] + QUIET, config=config, np_=np_)[0]
    assert len(a["steps"]) == len(b["steps"]) == 4
    for x, y in zip(step_values(a), step_values(b)):
        for qa, qb in zip(x, y):
            assert relative(qa, qb) < 1e-8
    assert_electrodes_agree(a, b)
    assert abs(a["steps"][-1]["electrodes"]["right"]["potential"]) > 0.1


def test_contact_pressure_of_a_uniform_compression(tmp_path):
    """The 2D block standing on the foundation (frictionless contact at the
    bottom, a roller on the left) under SIGMA0 on its top: the stress is
    uniform, so the lumped contact pressure is SIGMA0 at every vertex of
    Gamma_C to 1e-10, zero elsewhere, and the contact length the whole
    bottom."""
    cfg = json.loads(block(tmp_path, 2, {}).read_text())
    cfg["contact"] = {"c_p": 1e12, "gap": 0.0}
    cfg["boundaries"]["bottom"] = {"contact": True, "potential": 0.0}
    s = run_solver("cpp", tmp_path / "out", ["output.nodal=final", "output.xdmf=false"],
                   config=write(tmp_path / "standing.json", cfg))[0]
    assert s["steps"][-1]["contact_length"] == pytest.approx(1.0, rel=1e-14)
    # the body is held up only by the foundation: from u = 0, at the kink of
    # p, the first try may be cut; the last step's file is what counts
    final = len(s["steps"])
    nodal = np.load(tmp_path / "out" / "nodal" / f"contact_pressure_{final:04d}.npy")
    bottom = np.abs(nodal[:, 1]) < 1e-12
    assert np.allclose(nodal[bottom, 2], SIGMA0, rtol=1e-10, atol=0)
    assert np.all(nodal[~bottom, 2] == 0.0)


def test_one_bordered_update_solves_the_charge_equations(tmp_path):
    """The floating electrodes' algebra alone (floating.h), with no second
    engine: the charge equations are linear in (x, V) (the electric rows
    are; the contact term tests only w), so the first bordered Newton update
    of every step solves them to round-off, whatever the contact does to u
    (the first step of this bilayer closes contact: u is not yet solved
    there). A fault in the border c_e, the unit responses z_f or the signs of
    the Schur complement leaves them unsolved."""
    config = floating_bilayer(tmp_path)
    summary = run_solver("cpp", tmp_path / "cpp", ["time.steps=4"] + QUIET, config=config)[0]
    for step in summary["steps"]:
        predictor, first = step["residual_history"][:2]
        # something to solve: the charge's ramp, then the left side's sine
        assert predictor["charge"] > 1e-6
        assert first["charge"] <= 100 * np.finfo(float).eps, step["residual_history"]
    # once contact is settled, the steps are linear: one update solves all
    assert all(s["newton_iterations"] == 1 for s in summary["steps"][1:])


def test_a_resumed_run_continues_the_floating_electrode(tmp_path):
    """The floating bilayer run to T/2 and resumed to T equals the straight
    run (1e-8): the floating potential restarts from the checkpoint's, the
    current from the last recorded charge."""
    config = floating_bilayer(tmp_path)
    straight = run_solver("cpp", tmp_path / "straight", ["time.steps=4"] + QUIET, config=config)[0]
    run_solver("cpp", tmp_path / "short", ["time.steps=2", "time.T=0.5"] + QUIET, config=config)
    extended, _ = resume("cpp", tmp_path / "short", overrides=["time.T=1.0", "time.steps=4"])
    assert_electrodes_agree(extended, straight)


def test_two_floating_electrodes_in_contact(tmp_path):
    """The sensor demo with its driven electrode floating too (a sine
    charge) while the body touches the foundation: two floating potentials
    coupled through the body (the off-diagonal capacitances), contact, LU
    reuse; the executable and the reference engine agree at every step to
    1e-8 on probes, forces and every electrode quantity, and each floating
    electrode carries its charge."""
    cfg = json.loads((ROOT / "demos" / "sensor.json").read_text())
    cfg["mesh"]["geometry"] = str(ROOT / "meshes" / "contactor_sensor.py")
    cfg["boundaries"]["electrode_high"] = {
        "floating": {"charge": {"value": 3e-10, "history": {"sine": {"frequency": 0.5}}}}}
    cfg["boundaries"]["sensor"] = {"floating": {"charge": 1e-10}}
    cfg["loads"] = {"body_force": [-1e3, -1e3]}  # pressed on from the start
    config = write(tmp_path / "two.json", cfg)
    overrides = ["time.steps=8", "time.T=1.0"] + QUIET
    a = run_solver("cpp", tmp_path / "cpp", overrides, config=config)[0]
    b = run_solver("reference", tmp_path / "ref", overrides, config=config)[0]
    for x, y in zip(step_values(a), step_values(b)):
        for qa, qb in zip(x, y):
            assert relative(qa, qb) < 1e-8
    assert_electrodes_agree(a, b)
    for step in a["steps"]:
        e = step["electrodes"]
        scale = sum(abs(v["reaction_charge"]) for v in e.values())
        target = 3e-10 * math.sin(2 * math.pi * 0.5 * step["t"])
        assert abs(e["electrode_high"]["reaction_charge"] - target) < 1e-10 * scale
        assert abs(e["sensor"]["reaction_charge"] - 1e-10) < 1e-10 * scale
    assert min(np.hypot(*s["contact_force"]) for s in a["steps"]) > 0
    assert a["timing"]["operations"]["reused_factorisation"] > 0
