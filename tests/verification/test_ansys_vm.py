"""ANSYS VM175 and VM176 (tests/ansys_vm.py): our converged values beside
the published ones. Campaigns (slow): 3D P2 and a 2D sweep, ~1 min.

VM175: converged at P2 (n = 6 -> 8 changes them by < 2e-4), the first
breathing mode comes out 2.2 % below the paper's in both circuits, the
second 0.15-0.2 % above, and the coupling f_a / f_r of each mode matches the
paper's to 1e-4: the offset of the first mode is mechanical and common to
both circuits (the paper's 1981 perturbation method on a coarse mesh; the
deck's c66 = 3.0 instead of 3.05 moves it by 2e-6). VM176 (converged: mesh
1 mm -> 0.5 mm changes Y by < 1e-3): the admittance away from the first
resonance within 1-9 % of the target (+5.7, +8.7, -4.1, +0.8 % at 20, 35,
50, 54 kHz; ANSYS's own Rel. 9.0 results are +4.7, +6.3, -17 % off it),
near it the values follow the computed resonance (43.2 kHz here, about
44 kHz in the manual)."""

import json
import subprocess

import pytest
from ansys_vm import VM175_TARGET, VM176_TARGET, coupled, full_admittance_mmho, vm175, vm176
from conftest import ROOT, run_solver


def run(tmp_path, name, cfg):
    path = tmp_path / f"{name}.json"
    path.write_text(json.dumps(cfg))
    return run_solver("cpp", tmp_path / name, config=path)[0]


@pytest.mark.slow
def test_vm175_pzt4_cube(tmp_path):
    found = {c: coupled(run(tmp_path, c, vm175(c, 6)), c)[:2] for c in ("short", "open")}
    for c, f in found.items():
        print(c, [f"{x:.1f} ({x / t - 1:+.2%})" for x, t in zip(f, VM175_TARGET[c])])
    for k in (0, 1):
        ratio = found["open"][k] / found["short"][k]
        target = VM175_TARGET["open"][k] / VM175_TARGET["short"][k]
        assert abs(ratio / target - 1) < 1e-3  # the coupling
    assert all(abs(found[c][0] / VM175_TARGET[c][0] - 1) < 0.025 for c in found)
    assert all(abs(found[c][1] / VM175_TARGET[c][1] - 1) < 0.003 for c in found)


@pytest.mark.slow
def test_vm176_sandwich_admittance(tmp_path):
    msh = tmp_path / "langevin.msh"
    subprocess.run(["/usr/bin/python3", str(ROOT / "meshes" / "langevin_msh.py"), "--size",
                    "0.5e-3", "--output", str(msh)], check=True, capture_output=True)
    Y = full_admittance_mmho(run(tmp_path, "vm176", vm176(msh)))
    for f, y in Y.items():
        t = VM176_TARGET[f]
        print(f"{f / 1e3:.0f} kHz: Y = {y:.3f} mmho, target {t}")
    for f in (20e3, 35e3, 50e3, 54e3):  # away from the resonance
        assert abs(Y[f] / VM176_TARGET[f] - 1) < 0.1
    assert Y[42e3] > 0 > Y[45e3]  # the resonance between them
