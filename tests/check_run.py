#!/usr/bin/python3
"""Run the C++ executable on example 1 (n = 8, 8 steps) and check its
summary: both fields converged at every step, the phi residual measured on
its own, and global equilibrium. Used by ctest (serial and mpirun -n 2).

    check_run.py --np 2 --output DIR -- build/piezo-contact
"""

import argparse
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--output", required=True)
    ap.add_argument("exe", nargs="+")
    args = ap.parse_args()
    cmd = (["mpirun", "-n", str(args.np)] if args.np > 1 else []) + args.exe + [
        "--config", str(ROOT / "demos" / "square.json"), "--output", args.output,
        "--set", "mesh.n=8", "--set", "time.steps=8", "--quiet"]
    subprocess.run(cmd, check=True)
    s = json.loads((Path(args.output) / "summary.json").read_text())
    failures = []
    if s["mpi_size"] != args.np or len(s["steps"]) != 8:
        failures.append(f"mpi_size {s['mpi_size']}, {len(s['steps'])} steps")
    for step in s["steps"]:
        rel = step["relative_residuals"]
        if not (rel["u"] <= 1e-10 and rel["phi"] <= 1e-10):
            failures.append(f"t = {step['t']}: not converged {rel}")
        fx = step["contact_force"][0] + step["reactions"]["left"][0]
        fy = step["contact_force"][1] + step["reactions"]["left"][1] - 10.0
        if abs(fx) > 1e-9 or abs(fy) > 1e-9:
            failures.append(f"t = {step['t']}: out of equilibrium by ({fx:.2e}, {fy:.2e}) N/m")
    print("\n".join(failures) or f"ok: {len(s['steps'])} steps converged in both fields, "
          "in equilibrium")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
