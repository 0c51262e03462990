#!/usr/bin/python3
# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # Example 1 of the paper: the square, C++ against the reference engine
#
# A viscoelastic ZnO-like square (0,1)^2 is clamped and grounded on its left
# side, pressed by a traction (0, -10) N/m^2 on its top, and rests on a
# normal-compliance foundation (c_p = 1e12 N/m^3, no gap) along its bottom
# (Barboteu, Fernandez & Ouafik 2008, section 4.2). The data are in
# `demos/square.json`.
#
# This demo runs the same config through two engines:
# * `piezo-contact`, the C++ time loop on the ffcx-compiled forms;
# * `python3 -m piezocontact --engine reference`, the independent reference
#   engine: petsc4py's SNES in a loop of its own on the same UFL forms,
#   JIT-compiled;
#
# and prints the probe values side by side and the relative L2 difference of
# the u and phi fields at the final time. Extra arguments are passed to both
# engines, e.g.
#
#     /usr/bin/python3 demos/demo_square.py --set mesh.n=64 --set time.steps=64

import argparse
import os
import sys
from pathlib import Path

from piezodemos import runs

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--config", default=str(HERE / "square.json"))
    ap.add_argument("--output", default=str(ROOT / "out" / "square"))
    ap.add_argument("--build", default=os.environ.get("PIEZO_BUILD", str(ROOT / "build")))
    ap.add_argument("--np", type=int, default=1,
                    help="MPI processes (mpirun -n) of each run: the executable and the "
                         "reference engine")
    ap.add_argument("--set", action="append", default=[], metavar="KEY.PATH=VALUE")
    args = ap.parse_args()
    summaries = runs.run_both(args.config, args.output, args.set, args.build, args.np)
    field_diff, of_size, by_value = runs.report(summaries, args.output)
    print(f"\noutputs in {args.output}/{{cpp,reference}}: summary.json, solution.xdmf "
          "(open in ParaView), nodal/*.npy")
    if not runs.verdict(max(field_diff, of_size), by_value):
        sys.exit(1)


if __name__ == "__main__":
    main()
