#!/usr/bin/python3
# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # A disc transducer: resonance, antiresonance, coupling and admittance
#
# The first questions about a piezoelectric device are dynamic: where it
# resonates with its electrodes short-circuited, where it antiresonates
# with them open, how strongly it couples, and what admittance the driving
# circuit sees. Here a free PZT-5H disc (radius 10 mm, thickness 2 mm,
# poled along its axis, electrodes on both faces: `demos/transducer.json`)
# answers them, on its half-section (`"formulation": "axisymmetric"`, P2).
#
# 1. Resonance: both electrodes at 0 V (`"analysis": {"modal": ...}`).
#    The disc is held by nothing: its rigid translation comes out at 0 Hz.
# 2. Antiresonance: the top electrode floating (`"floating": {}`: zero
#    charge, an open circuit).
# 3. The effective coupling of the first radial mode,
#    k_eff^2 = (f_a^2 - f_r^2) / f_a^2 (IEEE Std 176-1987).
# 4. The admittance over the band around it (`"analysis": {"harmonic": ...}`,
#    1 V on top): its peak sits at f_r and its trough at f_a, which this
#    demo checks; the damping is Kelvin-Voigt, A = tau B with
#    `relaxation_time` tau = 10 ns.
#
# Both engines compute the modes; they agree to 1e-9. Pictures go in
# DIR/figures/.
#
#     /usr/bin/python3 demos/demo_transducer.py [--points 200]

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402
from piezodemos import runs  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
CONFIG = HERE / "transducer.json"


def run(engine, out, overrides, build):
    """One run, quiet; its summary."""
    args = runs.solver_commands(build, 1)[engine] + [
        "--config", str(CONFIG), "--output", str(out), "--quiet"]
    for o in overrides:
        args += ["--set", o]
    subprocess.run(args, check=True, env=runs.ENV)
    return json.loads((Path(out) / "summary.json").read_text())


# ## The radial mode among the modes
#
# A free disc has flexural and radial modes. Only those that change its
# thickness strain the poled ceramic along its axis and move charge: the
# radial ones. Each mode carries the charge on each electrode per unit
# modal amplitude (short circuit) or the potential of a floating one (open
# circuit), so the first radial mode is the first with a large charge.

def radial(summary, key):
    modes = summary["modes"]
    size = [abs(m["electrodes"]["top"][key]) for m in modes]
    largest = max(size)
    return next(m for m, s in zip(modes, size) if s > 1e-3 * largest)


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--output", default=str(ROOT / "out" / "transducer"))
    ap.add_argument("--build", default=os.environ.get("PIEZO_BUILD", str(ROOT / "build")))
    ap.add_argument("--points", type=int, default=200, help="frequencies of the sweep")
    args = ap.parse_args()
    out = Path(args.output)
    figures = out / "figures"
    figures.mkdir(parents=True, exist_ok=True)

    # ## Resonance and antiresonance, on both engines
    found, agree = {}, True
    for circuit, top in (("short", '{"potential":0.0}'), ("open", '{"floating":{}}')):
        for engine in ("cpp", "reference"):
            found[circuit, engine] = run(engine, out / f"{circuit}_{engine}",
                                         [f"boundaries.top={top}"], args.build)
        f = [[m["frequency"] for m in found[circuit, e]["modes"]] for e in ("cpp", "reference")]
        worst = max(abs(a * abs(a) - b * abs(b)) for a, b in zip(*f)) / max(f[0]) ** 2
        agree = agree and worst <= 1e-9
        print(f"{circuit} circuit: modes (Hz) {', '.join(f'{x:.1f}' for x in f[0])}; "
              f"engines differ by {worst:.1e} (omega^2, of the largest)")
    f_r = radial(found["short", "cpp"], "charge")["frequency"]
    f_a = radial(found["open", "cpp"], "potential")["frequency"]
    k2 = (f_a ** 2 - f_r ** 2) / f_a ** 2
    print(f"first radial mode: f_r = {f_r:.1f} Hz, f_a = {f_a:.1f} Hz, "
          f"k_eff = {np.sqrt(k2):.4f} (k_eff^2 = {k2:.4f})")

    # ## The admittance over the band
    #
    # One factorisation per frequency (each is a new matrix): the real
    # 2 x 2 block form of K + i omega C - omega^2 M, 1 V on top.
    band = {"start": 0.8 * f_r, "stop": 1.2 * f_a, "points": args.points}
    sweep = run("cpp", out / "admittance",
                ['boundaries.top={"potential":1.0}',
                 f'analysis={{"harmonic":{{"frequencies":{json.dumps(band)}}}}}'], args.build)
    freq = np.array([h["frequency"] for h in sweep["harmonic"]])
    Y = np.array([complex(*h["electrodes"]["top"]["admittance"]) for h in sweep["harmonic"]])
    peak, trough = freq[np.argmax(abs(Y))], freq[np.argmin(abs(Y))]
    step = freq[1] - freq[0]
    print(f"|Y| peaks at {peak:.1f} Hz and dips at {trough:.1f} Hz "
          f"(the sweep's step: {step:.1f} Hz)")
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 5.5), sharex=True)
    a1.semilogy(freq / 1e3, abs(Y) * 1e3)
    a1.set(ylabel="|Y| (mS per revolution)", title="admittance of the disc, 1 V on top")
    for f, name in ((f_r, "f_r"), (f_a, "f_a")):
        a1.axvline(f / 1e3, color="k", ls=":", lw=0.8)
        a1.text(f / 1e3, a1.get_ylim()[1], name, va="top")
    a2.plot(freq / 1e3, np.degrees(np.angle(Y)))
    a2.set(xlabel="frequency (kHz)", ylabel="phase (degrees)")
    fig.tight_layout()
    fig.savefig(figures / "admittance.png", dpi=130)
    plt.close(fig)

    # ## The radial mode's shape
    #
    # modes.xdmf holds each mode's u and phi at "time" = its number (P2
    # fields on the mesh refined once); here it is read with h5py.
    short = found["short", "cpp"]
    number = short["modes"].index(radial(short, "charge")) + 1
    with h5py.File(out / "short_cpp" / "modes.h5") as h5:
        x = h5["Mesh/mesh/geometry"][:, :2]
        cells = h5["Mesh/mesh/topology"][:]
        u = h5[f"Function/u/{number}"][:, :2]
        phi = h5[f"Function/phi/{number}"][:, 0]
    scale = 0.1 * np.ptp(x[:, 0]) / np.abs(u).max()
    fig, ax = plt.subplots(figsize=(8, 2.6))
    tpc = ax.tripcolor(Triangulation(1e3 * (x[:, 0] + scale * u[:, 0]),
                                     1e3 * (x[:, 1] + scale * u[:, 1]), cells),
                       phi, shading="gouraud", cmap="coolwarm")
    fig.colorbar(tpc, ax=ax, label="phi per unit modal amplitude")
    ax.set(aspect="equal", xlabel="r (mm)", ylabel="y (mm)",
           title=f"first radial mode, {f_r / 1e3:.2f} kHz (short circuit)")
    fig.savefig(figures / "radial_mode.png", dpi=130, bbox_inches="tight")
    plt.close(fig)
    print(f"figures: {figures}")

    ok = agree and abs(peak - f_r) <= step and abs(trough - f_a) <= step
    if not ok:
        print("error: the engines disagree, or the admittance's extremes are not at f_r and "
              "f_a", file=sys.stderr)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
