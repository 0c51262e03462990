"""The configs of two piezoelectric benchmarks of the ANSYS Verification
Manual, from the data of their input decks (ansys/pymapdl,
src/ansys/mapdl/core/examples/verif/vm175.dat and vm176.dat, release
2023R2), and their published targets.

VM175 (Boucher, Lagier & Maerfeld, IEEE Trans. SU-28(5), 1981, table 1): a
PZT4 cube of side 20 mm poled along z, electrodes on the faces normal to z,
a quarter model (symmetry planes x = 0 and y = 0, free along z: a rigid
mode). The first two coupled ("breathing") modes short-circuited (both
electrodes at 0 V) and open-circuited (the top floating).

VM176 (Kagawa & Yamabuchi, IEEE Trans. SU-26(2), 1979): an aluminium /
NEPEC 6 / aluminium sandwich (radius 27.5 mm; ceramic 10 mm, adhesive
0.275 mm and aluminium 10 mm each side), undamped, 1 V across the ceramic:
its input admittance at six frequencies. Axisymmetric here (ANSYS: a 10
degree wedge), cut at the mid-plane (u_y = 0, phi = 0 there, the electrode
at 0.5 V): the full device's admittance is half the half-model's (the same
current, twice the voltage)."""

import numpy as np

EPS0 = 8.854e-12

VM175_TARGET = {"short": (66560.0, 88010.0), "open": (81590.0, 93410.0)}
# Y (mmho) of the full device; None: not given (45 kHz: just above resonance)
VM176_TARGET = {20e3: 0.41, 35e3: 0.90, 42e3: 2.0, 45e3: None, 50e3: 0.39, 54e3: 0.65}
VM176_ANSYS_REL9 = {20e3: 0.43, 35e3: 0.96, 42e3: 2.8, 45e3: -1.74, 50e3: 0.32, 54e3: None}


def vm175(circuit, n, modes=12):
    c = np.zeros((6, 6))  # Voigt xx, yy, zz, yz, xz, xy; 1e10 N/m^2 in the deck
    c[0, 0] = c[1, 1] = 13.2e10
    c[0, 1] = c[1, 0] = 7.1e10
    c[0, 2] = c[2, 0] = c[1, 2] = c[2, 1] = 7.3e10
    c[2, 2] = 11.5e10
    c[3, 3] = c[4, 4] = 2.6e10
    c[5, 5] = 3.0e10  # the deck's c66 (not (c11 - c12) / 2 = 3.05: its effect is 5e-4)
    e = np.zeros((3, 6))
    e[2, 0] = e[2, 1] = -4.1
    e[2, 2] = 14.1
    e[0, 4] = e[1, 3] = 10.5
    return {
        "mesh": {"type": "box", "n": [n, n, 2 * n], "size": [0.01, 0.01, 0.02]},
        "elements": {"degree": 2},
        "material": {"elastic": c.tolist(), "relaxation_time": 1e-12,
                     "piezoelectric": e.tolist(),
                     "permittivity": (np.diag([804.6, 804.6, 659.7]) * EPS0).tolist(),
                     "density": 7500.0},
        "boundaries": {"left": {"displacement": [0.0, None, None]},
                       "bottom": {"displacement": [None, 0.0, None]},
                       "back": {"potential": 0.0},
                       "front": {"potential": 0.0} if circuit == "short" else {"floating": {}}},
        "time": {"T": 1.0, "steps": 1},
        "analysis": {"modal": {"modes": modes}},
        "output": {"xdmf": False},
    }


def coupled(summary, circuit, share=0.1):
    """The frequencies of the modes that move charge (short circuit) or the
    floating electrode's potential (open): above `share` of the largest."""
    key = "charge" if circuit == "short" else "potential"
    size = [abs(m["electrodes"]["front"][key]) for m in summary["modes"]]
    return [m["frequency"] for m, s in zip(summary["modes"], size) if s > share * max(size)]


def _isotropic(E, nu):
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    B = np.zeros((6, 6))
    B[:3, :3] = lam
    B[:3, :3] += 2 * mu * np.eye(3)
    B[3:, 3:] = mu * np.eye(3)
    return B


def _passive(E, nu, rho):
    """An elastic layer; phi lives there too (a dielectric of eps0, charge-
    free outside: it carries no field and no charge)."""
    return {"elastic": _isotropic(E, nu).tolist(), "relaxation_time": 1e-12,
            "piezoelectric": np.zeros((3, 6)).tolist(),
            "permittivity": (EPS0 * np.eye(3)).tolist(), "density": rho}


def vm176(msh, frequencies=tuple(VM176_TARGET)):
    B = np.zeros((6, 6))  # NEPEC 6 poled along the axis y (x = r, z the hoop direction)
    B[0, 0] = B[2, 2] = 12.8e10
    B[1, 1] = 11.0e10
    B[0, 2] = B[2, 0] = 6.8e10
    B[0, 1] = B[1, 0] = B[1, 2] = B[2, 1] = 6.6e10
    B[3, 3] = B[4, 4] = B[5, 5] = 2.1e10  # the deck's (not transversely isotropic)
    e = np.zeros((3, 6))
    e[1, 0] = e[1, 2] = -6.10
    e[1, 1] = 15.70  # no e15 in the deck
    ceramic = {"elastic": B.tolist(), "relaxation_time": 1e-12, "piezoelectric": e.tolist(),
               "permittivity": (993.55 * EPS0 * np.eye(3)).tolist(), "density": 7730.0}
    return {
        "mesh": {"type": "msh", "path": str(msh)},
        "formulation": "axisymmetric",
        "elements": {"degree": 2},
        "regions": {"ceramic": ceramic, "adhesive": _passive(10e9, 0.38, 1700.0),
                    "aluminium": _passive(7.03e10, 0.345, 2690.0)},
        "boundaries": {"midplane": {"displacement": [None, 0.0], "potential": 0.0},
                       "electrode": {"potential": 0.5}},
        "time": {"T": 1.0, "steps": 1},
        "analysis": {"harmonic": {"frequencies": list(frequencies)}},
        "output": {"xdmf": False},
    }


def full_admittance_mmho(summary):
    """{frequency: Y of the full device (mmho)}: the susceptance, Im Y (the
    model is undamped: Y is i B; the manual's Y is B, signed)."""
    return {h["frequency"]: 1e3 * h["electrodes"]["electrode"]["admittance"][1] / 2
            for h in summary["harmonic"]}


def vm176_figure(path, build, points=181):
    """The admittance over 15-60 kHz against the published points (a
    figure: `python3 tests/ansys_vm.py --figure docs/figures/vm176_admittance.png`)."""
    import json
    import os
    import subprocess
    import tempfile
    from pathlib import Path

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    root = Path(__file__).resolve().parents[1]
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    with tempfile.TemporaryDirectory() as tmp:
        msh = Path(tmp) / "langevin.msh"
        subprocess.run(["/usr/bin/python3", str(root / "meshes" / "langevin_msh.py"), "--size",
                        "0.5e-3", "--output", str(msh)], check=True, capture_output=True)
        cfg = vm176(msh, list(np.linspace(15e3, 60e3, points)))
        (Path(tmp) / "vm176.json").write_text(json.dumps(cfg))
        subprocess.run([str(Path(build) / "piezo-contact"), "--config", str(Path(tmp) / "vm176.json"),
                        "--output", str(Path(tmp) / "out"), "--quiet"], check=True, env=env)
        Y = full_admittance_mmho(json.loads((Path(tmp) / "out" / "summary.json").read_text()))
    f = np.array(sorted(Y))
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.semilogy(f / 1e3, np.abs([Y[x] for x in f]), label="here (axisymmetric P2)")
    for table, mark, name in ((VM176_TARGET, "ko", "Kagawa & Yamabuchi (the manual's target)"),
                              (VM176_ANSYS_REL9, "rs", "ANSYS Rel. 9.0")):
        pts = [(k, abs(v)) for k, v in table.items() if v is not None]
        ax.plot([p[0] / 1e3 for p in pts], [p[1] for p in pts], mark, mfc="none", label=name)
    ax.set(xlabel="frequency (kHz)", ylabel="|Y| (mmho)",
           title="VM176: the sandwich transducer's input admittance, 1 V, undamped")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    print(f"wrote {path}")


if __name__ == "__main__":
    import argparse
    from pathlib import Path
    ap = argparse.ArgumentParser(description="the VM176 admittance figure")
    ap.add_argument("--figure", required=True)
    ap.add_argument("--build", default=str(Path(__file__).resolve().parents[1] / "build"))
    args = ap.parse_args()
    vm176_figure(args.figure, args.build)
