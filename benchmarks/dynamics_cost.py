#!/usr/bin/python3
"""What the dynamic analyses cost, on the executable (docs/benchmarks.md).

  1. Ten modes of a 3D P2 device (a PZT-4 block 20 x 20 x 10 mm poled along
     z, electrodes on its z faces, clamped on one) at about 100k and 300k
     dofs: time and peak memory against the floor of shift-and-invert, one
     factorisation of K - sigma M plus the solves the eigensolver made, each
     timed on that factorisation; and a solve against the memory bandwidth
     (an LDL^T solve reads L twice, forward and backward: 16 GB/s read,
     shared/DOLFINX-0.5-NOTES.md).
  2. A 200-point admittance sweep of a 2D device (the disc transducer of
     demos/transducer.json): time per frequency against one factorisation
     of its block system (each frequency is a new matrix: the floor of a
     direct sweep).

    /usr/bin/python3 benchmarks/dynamics_cost.py [--cells 9 13] [--points 200] [--build build]
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
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
READ_BANDWIDTH = 16e9  # B/s, measured on this machine (shared/DOLFINX-0.5-NOTES.md)


def block(n):
    return {
        "mesh": {"type": "box", "n": [2 * n, 2 * n, n], "size": [0.02, 0.02, 0.01]},
        "elements": {"degree": 2},
        "material": {"preset": "PZT-4", "poling": [0, 0, 1], "relaxation_time": 1e-9},
        "boundaries": {"back": {"displacement": [0.0, 0.0, 0.0], "potential": 0.0},
                       "front": {"potential": 0.0}},
        "time": {"T": 1.0, "steps": 1},
        "analysis": {"modal": {"modes": 10}},
        "output": {"xdmf": False},
    }


def run(exe, cfg, out):
    """(summary, wall s, peak memory MB) of one run."""
    path = Path(out).with_suffix(".json")
    path.write_text(json.dumps(cfg))
    proc = subprocess.run(["/usr/bin/time", "-f", "%e %M", exe, "--config", str(path),
                           "--output", str(out), "--quiet"], capture_output=True, text=True,
                          env=ENV, check=True)
    wall, kb = proc.stderr.strip().splitlines()[-1].split()
    return json.loads((Path(out) / "summary.json").read_text()), float(wall), float(kb) / 1024


def modal(exe, cells, tmp):
    print("1. ten modes of a 3D P2 block (PZT-4, clamped below, both electrodes grounded)")
    print(f"{'dofs':>8} {'wall s':>7} {'MB':>6} {'K,C,M s':>8} {'LU s':>6} {'eigen s':>8} "
          f"{'solves':>6} {'1 solve s':>9} {'floor s':>8} {'LU+eigen / floor':>16} "
          f"{'factors MB':>10} {'solve / bandwidth':>17}")
    for n in cells:
        s, wall, mb = run(exe, block(n), Path(tmp) / f"block{n}")
        t = s["analysis_timing"]
        floor = t["factorisation_s"] + t["solves"] * t["one_solve_s"]
        spent = t["factorisation_s"] + t["eigensolver_s"]
        print(f"{s['dofs']:>8} {wall:>7.1f} {mb:>6.0f} {t['linearisation_s']:>8.2f} "
              f"{t['factorisation_s']:>6.2f} {t['eigensolver_s']:>8.2f} {t['solves']:>6} "
              f"{t['one_solve_s']:>9.3f} {floor:>8.2f} {spent / floor:>16.2f} "
              f"{t['factor_entries'] * 8 / 1e6:>10.0f} "
              f"{t['one_solve_s'] / (2 * t['factor_entries'] * 8 / READ_BANDWIDTH):>17.1f}")
        first = ", ".join(f"{m['frequency']:.0f}" for m in s["modes"][:4])
        print(f"{'':>8} first modes (Hz): {first}")


def sweep(exe, points, tmp):
    print(f"\n2. a {points}-point admittance sweep of the disc transducer (axisymmetric P2)")
    cfg = json.loads((ROOT / "demos" / "transducer.json").read_text())
    cfg["mesh"]["geometry"] = str(ROOT / "meshes" / "disc.py")
    cfg["mesh"]["size"] = 0.1e-3  # 28k dofs
    cfg["boundaries"]["top"] = {"potential": 1.0}
    cfg["analysis"] = {"harmonic": {"frequencies": {"start": 8e4, "stop": 1.4e5,
                                                    "points": points}}}
    cfg["output"] = {"xdmf": False}
    s, wall, mb = run(exe, cfg, Path(tmp) / "sweep")
    t = {k: np.array(v) for k, v in s["analysis_timing"].items() if isinstance(v, list)}
    per = t["assembly_s"] + t["factorisation_s"] + t["solve_s"]
    print(f"dofs {s['dofs']} (the block system: {2 * s['dofs']}), wall {wall:.1f} s, {mb:.0f} MB")
    print(f"per frequency: {np.median(per) * 1e3:.1f} ms (median): forming the block system "
          f"{np.median(t['assembly_s']) * 1e3:.1f} ms, its LU "
          f"{np.median(t['factorisation_s']) * 1e3:.1f} ms, the solve "
          f"{np.median(t['solve_s']) * 1e3:.1f} ms; per frequency / one LU = "
          f"{np.median(per / t['factorisation_s']):.2f}")


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--cells", type=int, nargs="+", default=[9, 13],
                    help="cells along z (2n x 2n x n): 9 ~ 100k dofs, 13 ~ 300k")
    ap.add_argument("--points", type=int, default=200)
    ap.add_argument("--build", default=str(ROOT / "build"))
    args = ap.parse_args()
    exe = str(Path(args.build) / "piezo-contact")
    with tempfile.TemporaryDirectory() as tmp:
        modal(exe, args.cells, tmp)
        sweep(exe, args.points, tmp)
    return 0


if __name__ == "__main__":
    sys.exit(main())
