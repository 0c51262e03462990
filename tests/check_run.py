#!/usr/bin/python3
"""Run the C++ executable (n = 8, 8 steps) and check its summary. Used by
ctest (serial and mpirun -n 2).

  square: example 1; both fields converged at every step, the phi residual
      measured on its own, and global equilibrium.
  manufactured: the solution linear in space and time, with the foundation
      pushing on part of Gamma_C, reproduced to round-off.

    check_run.py --case square --np 2 --output DIR -- build/piezo-contact
"""

import argparse
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--case", choices=["square", "manufactured"], default="square")
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--output", required=True)
    ap.add_argument("exe", nargs="+")
    args = ap.parse_args()
    extra = {"square": [], "manufactured": ["manufactured.space=linear",
                                            "manufactured.time=linear"]}[args.case]
    cmd = (["mpirun", "-n", str(args.np)] if args.np > 1 else []) + args.exe + [
        "--config", str(ROOT / "demos" / f"{args.case}.json"), "--output", args.output,
        "--quiet"]
    for o in ["mesh.n=8", "time.steps=8"] + extra:
        cmd += ["--set", o]
    subprocess.run(cmd, check=True)
    s = json.loads((Path(args.output) / "summary.json").read_text())
    failures = []
    if s["mpi_size"] != args.np or len(s["steps"]) != 8:
        failures.append(f"mpi_size {s['mpi_size']}, {len(s['steps'])} steps")
    check = {"square": check_square, "manufactured": check_manufactured}[args.case]
    failures += check(s)
    print("\n".join(failures) or f"ok: {args.case}, {len(s['steps'])} steps")
    sys.exit(1 if failures else 0)


def check_manufactured(s):
    """Errors relative to the exact solution's size (U0, PHI0): round-off
    is ~1e-15; see tests/verification/test_manufactured.py."""
    sys.path.insert(0, str(ROOT / "forms"))
    from manufactured import PHI0, U0
    failures = []
    for step in s["steps"]:
        e = step["errors"]
        worst = max(e["u_H1"] / U0, e["phi_H1"] / PHI0)
        if not worst < 1e-12:
            failures.append(f"t = {step['t']}: error {worst:.2e} (relative) is not round-off")
    if not s["steps"][-1]["contact_force"][1] > 1.0:
        failures.append(f"the foundation does not push: {s['steps'][-1]['contact_force']}")
    return failures


def check_square(s):
    failures = []
    for step in s["steps"]:
        rel = step["relative_residuals"]
        if not (rel["u"] <= 1e-10 and rel["phi"] <= 1e-10):
            failures.append(f"t = {step['t']}: not converged {rel}")
        fx = step["contact_force"][0] + step["reactions"]["left"][0]
        fy = step["contact_force"][1] + step["reactions"]["left"][1] - 10.0
        if abs(fx) > 1e-9 or abs(fy) > 1e-9:
            failures.append(f"t = {step['t']}: out of equilibrium by ({fx:.2e}, {fy:.2e}) N/m")
    return failures


if __name__ == "__main__":
    main()
