#!/usr/bin/python3
"""Hertz's problems on the executable (tests/verification/test_obstacles.py
sets them up): a rigid cylinder (plane strain) and a rigid sphere
(axisymmetric) of radius 20 mm pressed into a 40 mm elastic block
(meshes/hertz_block.py, E = 100 GPa, nu = 0.3, no piezoelectric coupling),
at degree 2.

  1. Nitsche's method as the contact zone's cells shrink: the contact
     half-width (radius) a and the peak pressure p0 against Hertz's for the
     force the run gives;
  2. normal compliance as c_p grows, against Nitsche on the same mesh: the
     force, a and p0 tend to Nitsche's, the penetration to 0;
  3. Nitsche's gamma_0 and theta: how little they matter once gamma_0 is
     large enough;
  4. the pressure profile on the finest mesh against Hertz's ellipse
     p0 sqrt(1 - (x/a)^2) (docs/figures/hertz_pressure.png).

    /usr/bin/python3 benchmarks/hertz.py [--sizes 40 20 10] (um) [--build build]
        [--figure docs/figures/hertz_pressure.png]
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "verification"))
sys.path.insert(0, str(ROOT / "tests"))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")

from test_obstacles import NITSCHE, hertz, hertz_config, measured  # noqa: E402

CASES = {"plane_strain": 28e-6, "axisymmetric": 12.5e-6}  # formulation: the indenter's depth (m)


def run(config, out, build):
    path = Path(out).with_suffix(".json")
    path.write_text(json.dumps(config))
    subprocess.run([str(Path(build) / "piezo-contact"), "--config", str(path), "--output",
                    str(out), "--quiet"], check=True, env=ENV, capture_output=True)
    return json.loads((Path(out) / "summary.json").read_text())


def row(formulation, summary):
    P, a, p0 = measured(formulation, summary)
    a_h, p0_h = hertz(formulation, P)
    c = summary["steps"][-1]["contacts"]["top"]
    return P, a, p0, a / a_h - 1, p0 / p0_h - 1, c["max_penetration"]


def pressure_profile(out):
    """(x, p) of the lumped pressure along the top (y = 0), by x."""
    nodal = sorted((Path(out) / "nodal").glob("contact_pressure_*.npy"))[-1]
    xyp = np.load(nodal)
    top = xyp[np.abs(xyp[:, 1]) < 1e-12]
    top = top[np.argsort(top[:, 0])]
    return top[:, 0], top[:, -1]


def plot(profiles, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4))
    s = np.linspace(0, 1, 200)
    ax.plot(s, np.sqrt(1 - s ** 2), "k-", lw=1, label="Hertz: sqrt(1 - (x/a)^2)")
    for (label, x, p, a_h, p0_h), marker in zip(profiles, "os"):
        keep = x < 1.3 * a_h
        ax.plot(x[keep] / a_h, p[keep] / p0_h, marker, ms=3, mfc="none", label=label)
    ax.set_xlabel("x / a_Hertz (r / a_Hertz)")
    ax.set_ylabel("p / p0_Hertz")
    ax.set_title("Rigid indenters on an elastic block, Nitsche, P2")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    print(f"wrote {path}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=float, nargs="+", default=[40, 20, 10],
                    help="cell sizes in the contact zone (um)")
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--parts", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--figure", default=str(ROOT / "docs" / "figures" / "hertz_pressure.png"))
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        def solve(formulation, contact, size, name):
            cfg = hertz_config(formulation, CASES[formulation], contact, size=size * 1e-6)
            return row(formulation, run(cfg, Path(tmp) / name, args.build))

        if 1 in args.parts:
            nitsche_against_hertz(solve, args, Path(tmp))
        if 2 in args.parts:
            penalty_against_nitsche(solve, args.sizes[-1])
        if 3 in args.parts:
            nitsche_parameters(solve, args.sizes[-1])


def nitsche_against_hertz(solve, args, tmp):
    profiles = []
    print("1. Nitsche (gamma_0 = 10, theta = 1) against Hertz")
    print(f"{'formulation':13} {'h (um)':>7} {'P':>11} {'a (mm)':>9} {'a/a_H-1':>9} "
          f"{'p0 (GPa)':>9} {'p0/p0_H-1':>10}")
    for formulation in CASES:
        for h in args.sizes:
            P, a, p0, ea, ep, _ = solve(formulation, NITSCHE, h, f"n{formulation}{h}")
            print(f"{formulation:13} {h:7g} {P:11.5g} {1e3 * a:9.5f} {ea:+9.2%} "
                  f"{1e-9 * p0:9.5f} {ep:+10.2%}")
        x, p = pressure_profile(tmp / f"n{formulation}{h}")
        profiles.append((formulation.replace("_", " ") + (": cylinder" if formulation ==
                         "plane_strain" else ": sphere"), x, p, *hertz(formulation, P)))
    plot(profiles, args.figure)


def penalty_against_nitsche(solve, h):
    print(f"\n2. normal compliance against Nitsche (h = {h:g} um)")
    print(f"{'formulation':13} {'c_p (N/m^3)':>12} {'P/P_N-1':>9} {'a/a_N-1':>9} "
          f"{'p0/p0_N-1':>10} {'penetration (m)':>16}")
    for formulation in CASES:
        P_n, a_n, p0_n, *_ = solve(formulation, NITSCHE, h, f"ref{formulation}")
        for c_p in (1e15, 1e16, 1e17, 1e18):
            P, a, p0, _, _, r = solve(formulation, {"c_p": c_p}, h, f"p{formulation}{c_p}")
            print(f"{formulation:13} {c_p:12.0e} {P / P_n - 1:+9.2e} {a / a_n - 1:+9.2e} "
                  f"{p0 / p0_n - 1:+10.2e} {r:16.3e}")


def nitsche_parameters(solve, h):
    print(f"\n3. Nitsche's parameters (axisymmetric, h = {h:g} um)")
    print(f"{'gamma_0':>8} {'theta':>6} {'a/a_H-1':>9} {'p0/p0_H-1':>10} {'penetration (m)':>16}")
    for gamma in (1, 10, 100):
        for theta in (1, 0, -1):
            contact = {**NITSCHE, "gamma": gamma, "theta": theta}
            try:
                _, _, _, ea, ep, r = solve("axisymmetric", contact, h, f"g{gamma}t{theta}")
            except subprocess.CalledProcessError as e:  # exit 3: Newton failed
                print(f"{gamma:8g} {theta:6d}   Newton fails (exit {e.returncode})")
                continue
            print(f"{gamma:8g} {theta:6d} {ea:+9.2%} {ep:+10.2%} {r:16.3e}")


if __name__ == "__main__":
    main()
