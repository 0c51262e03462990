"""Dynamic analyses: the engines agree (the C++ core on ahead-of-time and
JIT kernels, the reference engine with its own assembly, constraints and
eigensolver), frequencies within 1e-9 relative and harmonic charges within
1e-9 of their size; under MPI the core gives the serial answers. The modes
and responses themselves are checked against closed forms in
tests/verification/test_dynamics.py."""

import json
import math

import pytest
from conftest import ENGINES, run_solver
from resonators import T, layer, on_foundation, on_rigid_plane, open_circuit, short_circuit


def run_all(tmp_path, cfg, engines=ENGINES, np_=1):
    path = tmp_path / "cfg.json"
    path.write_text(json.dumps(cfg))
    return {e: run_solver(e, tmp_path / f"out_{e}_{np_}", config=path, np_=np_)[0]
            for e in engines}


def frequencies(summary):
    return [m["frequency"] for m in summary["modes"]]


def same_frequencies(a, b, first):
    """Each mode's frequency within 1e-9 relative, compared as omega^2
    against the largest one's (a rigid mode's omega^2 is round-off of 0,
    about 1e-14 of the others: its frequency, their square root, is not)."""
    assert len(a) == len(b)
    for x, y in zip(a, b):
        assert abs(math.copysign(x * x, x) - math.copysign(y * y, y)) <= 1e-9 * first ** 2, (a, b)


# config, and what the modes carry besides frequencies: a prescribed
# electrode's charge (short circuit), a floating one's potential (open), or
# nothing (the charge-free layer on the foundation: round-off of zero)
CASES = {
    "short circuit": (lambda: layer("short", 2, T / 10, {"modal": {"modes": 4}}),
                      ("charge", ["bottom", "top"])),
    "open circuit (a floating electrode)": (
        lambda: layer("open", 2, T / 10, {"modal": {"modes": 4}}), ("potential", ["top"])),
    "contact closed at the end": (lambda: on_foundation("end"), (None, [])),
    "a rigid plane by Nitsche (not Hermitian)": (lambda: on_rigid_plane("end"), (None, [])),
}


@pytest.mark.parametrize("case", list(CASES))
def test_engines_agree_on_modes(tmp_path, case):
    make, (key, names) = CASES[case]
    summaries = run_all(tmp_path, make())
    f = {e: frequencies(s) for e, s in summaries.items()}
    first = max(abs(x) for x in f["cpp"])
    for e in ENGINES[1:]:
        same_frequencies(f["cpp"], f[e], first)
    # per unit modal amplitude, up to the shape's sign (each engine makes its
    # largest entry positive)
    for name in names:
        values = {e: [abs(m["electrodes"][name][key]) for m in s["modes"]]
                  for e, s in summaries.items()}
        scale = max(values["cpp"])
        for e in ENGINES[1:]:
            for a, b in zip(values["cpp"], values[e]):
                assert abs(a - b) <= 1e-7 * scale, (e, name, key, values)


def test_modes_under_mpi(tmp_path):
    """mpirun -n 2 gives the serial frequencies (the floating electrode's
    dofs are merged across the ranks)."""
    cfg = layer("open", 2, T / 10, {"modal": {"modes": 4}})
    serial = frequencies(run_all(tmp_path, cfg, ("cpp",))["cpp"])
    parallel = run_all(tmp_path, cfg, ("cpp", "reference"), np_=2)
    for e, s in parallel.items():
        same_frequencies(serial, frequencies(s), serial[1])


def test_engines_agree_on_harmonic_responses(tmp_path):
    """The layer shaken by a traction on its grounded bottom, its top
    floating (a sensor: its open-circuit voltage) and held: the sensor's
    potential and a probe, around the first resonance."""
    fr, fa = short_circuit(1)[0], open_circuit(1)[0]
    cfg = layer("open", 2, T / 10, {"harmonic": {"frequencies": [0.5 * fr, fa, 2 * fa]}})
    cfg["boundaries"]["bottom"] = {"potential": 0.0, "traction": [0.0, 1e6]}
    cfg["boundaries"]["top"]["displacement"] = [None, 0.0]
    cfg["probes"] = [[0.05e-3, 0.5e-3]]
    summaries = run_all(tmp_path, cfg)
    ref = summaries["cpp"]["harmonic"]
    for e in ENGINES[1:]:
        for a, b in zip(ref, summaries[e]["harmonic"]):
            assert a["frequency"] == b["frequency"]
            x, y = (complex(*s["electrodes"]["top"]["potential"]) for s in (a, b))
            assert abs(x - y) <= 1e-9 * abs(x), (e, x, y)
            u, v = a["probes"][0]["u"][1], b["probes"][0]["u"][1]
            size = math.hypot(*u)
            assert math.hypot(u[0] - v[0], u[1] - v[1]) <= 1e-9 * size, (e, u, v)


def test_engines_agree_on_admittance(tmp_path):
    """The layer driven on top, grounded below, damped: the charge and the
    admittance of the driven electrode."""
    fr = short_circuit(1)[0]
    cfg = layer("short", 2, T / 10, {"harmonic": {"frequencies": [0.5 * fr, fr, 1.5 * fr]}})
    cfg["boundaries"]["top"] = {"potential": 1.0}
    summaries = run_all(tmp_path, cfg)
    for e in ENGINES[1:]:
        for a, b in zip(summaries["cpp"]["harmonic"], summaries[e]["harmonic"]):
            for key in ("charge", "admittance"):
                x, y = (complex(*s["electrodes"]["top"][key]) for s in (a, b))
                assert abs(x - y) <= 1e-9 * abs(x), (e, key, x, y)


def test_admittance_under_mpi(tmp_path):
    """mpirun -n 2 gives the serial admittance (the block system's rows
    interleaved per dof across the ranks)."""
    fr = short_circuit(1)[0]
    cfg = layer("short", 2, T / 10, {"harmonic": {"frequencies": [0.5 * fr, fr]}})
    cfg["boundaries"]["top"] = {"potential": 1.0}
    serial = run_all(tmp_path, cfg, ("cpp",))["cpp"]["harmonic"]
    parallel = run_all(tmp_path, cfg, ("cpp",), np_=2)["cpp"]["harmonic"]
    for a, b in zip(serial, parallel):
        x, y = (complex(*s["electrodes"]["top"]["admittance"]) for s in (a, b))
        assert abs(x - y) <= 1e-9 * abs(x), (x, y)
