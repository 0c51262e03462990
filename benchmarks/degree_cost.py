#!/usr/bin/python3
"""Cost of a step at degree 2 against degree 1 at (nearly) equal dofs, with
the direct and the iterative linear solver, and the iterative solver's
Krylov iterations against h at each degree.

demos/slab.json (3D, tetrahedra): degree 1 on n = [8m, 8m, 2m] and degree 2
on n = [4m, 4m, m] have the same nodes, so the same dofs; 8 steps, k = 1/16,
output off. Per run, from its summary.json: dofs, time per step (the run's
total over its steps, set-ups included), the time per triangular solve (or
Krylov solve) and per factorisation (or AMG set-up), Newton and Krylov
iterations per step after the first (which starts from zero).

    /usr/bin/python3 benchmarks/degree_cost.py [--m 1 2 3] [--steps 8]
"""

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SLAB = ROOT / "demos" / "slab.json"


def run(out, n, degree, solver, steps):
    args = [str(ROOT / "build" / "piezo-contact"), "--config", str(SLAB), "--output", str(out),
            "--quiet", "--set", f"mesh.n=[{n[0]},{n[1]},{n[2]}]", "--set", f"time.steps={steps}",
            "--set", f"time.T={steps / 16}", "--set", f"elements.degree={degree}",
            "--set", f"solver.linear={solver}", "--set", "output.xdmf=false",
            "--set", "output.nodal=none"]
    subprocess.run(args, check=True, capture_output=True)
    return json.loads((out / "summary.json").read_text())


def row(s, degree, solver):
    t = s["timing"]
    ops = t["operations"]
    later = s["steps"][1:]
    newton = sum(st["newton_iterations"] for st in later) / len(later)
    krylov = (sum(st.get("krylov_iterations", 0) for st in later)
              / sum(st["newton_iterations"] for st in later))
    solve = ops["triangular_solve"]["seconds"] / max(ops["triangular_solve"]["count"], 1)
    setup = ops["factorisation"]["seconds"] / max(ops["factorisation"]["count"], 1)
    return (f"| {degree} | {solver} | {s['config']['mesh']['n']} | {s['dofs']} | "
            f"{t['total_s'] / len(s['steps']) * 1e3:.1f} | {solve * 1e3:.2f} | {setup * 1e3:.1f} | "
            f"{newton:.2f} | " + (f"{krylov:.1f} |" if solver == "iterative" else "- |"))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--m", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--steps", type=int, default=8)
    args = ap.parse_args()
    print("| degree | solver | n | dofs | ms/step | ms/solve | ms/set-up | Newton/step | "
          "Krylov/Newton |")
    print("|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for m in args.m:
            for degree, n in ((1, (8 * m, 8 * m, 2 * m)), (2, (4 * m, 4 * m, m))):
                for solver in ("direct", "iterative"):
                    out = Path(tmp) / f"{degree}_{solver}_{m}"
                    print(row(run(out, n, degree, solver, args.steps), degree, solver),
                          flush=True)


if __name__ == "__main__":
    sys.exit(main())
