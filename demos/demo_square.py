#!/usr/bin/python3
# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # Example 1 of the paper: the square, C++ against the Python twin
#
# A viscoelastic ZnO-like square (0,1)^2 is clamped and grounded on its left
# side, pressed by a traction (0, -10) N/m^2 on its top, and rests on a
# normal-compliance foundation (c_p = 1e12 N/m^3, no gap) along its bottom
# (Barboteu, Fernandez & Ouafik 2008, section 4.2). The data are in
# `demos/square.json`.
#
# This demo runs the same config through both solvers:
# * `build/piezo-contact`, the C++ time loop on the ffcx-compiled forms;
# * `demos/piezo_contact.py`, dolfinx Python's NonlinearProblem/NewtonSolver
#   on the same UFL forms, JIT-compiled;
#
# and prints the probe values side by side and the relative L2 difference of
# the u and phi fields at the final time. Extra arguments are passed to both
# solvers, e.g.
#
#     /usr/bin/python3 demos/demo_square.py --set mesh.n=64 --set time.steps=64

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

from piezocontact import compare

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


def solver_commands(build_dir, np_):
    """The two command lines, optionally under mpirun."""
    mpi = ["mpirun", "-n", str(np_)] if np_ > 1 else []
    return {"cpp": mpi + [str(Path(build_dir) / "piezo-contact")],
            "python": mpi + ["/usr/bin/python3", str(HERE / "piezo_contact.py")]}


def run_both(config, out_dir, overrides, build_dir, np_=1):
    """Run C++ then Python on one config; return their summaries."""
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    summaries = {}
    for name, cmd in solver_commands(build_dir, np_).items():
        args = cmd + ["--config", str(config), "--output", str(Path(out_dir) / name)]
        for o in overrides:
            args += ["--set", o]
        print(f"\n$ {' '.join(args)}", flush=True)
        t0 = time.perf_counter()
        subprocess.run(args, check=True, env=env)
        print(f"  ({name}: {time.perf_counter() - t0:.1f} s wall, including start-up)")
        summaries[name] = compare.load_summary(Path(out_dir) / name)
    return summaries


def report(summaries, out_dir):
    cpp, py = summaries["cpp"], summaries["python"]
    print()
    print(compare.table(cpp, py))
    fields = compare.field_differences(Path(out_dir) / "cpp", Path(out_dir) / "python", py)
    final = fields[max(fields)]
    print(f"\nrelative L2 difference at t = {cpp['steps'][-1]['t']:g}: "
          f"u {final['u']:.2e}, phi {final['phi']:.2e}")
    worst = max(max(d["u"], d["phi"]) for d in compare.probe_differences(cpp, py))
    print(f"largest relative probe difference over all steps: {worst:.2e}")
    for name, s in summaries.items():
        its = [st["newton_iterations"] for st in s["steps"]]
        t = s["timing"]
        print(f"{name:>6}: {s['dofs']} dofs, {len(its)} steps, Newton iterations "
              f"{min(its)}-{max(its)} (total {sum(its)}), time {t['total_s']:.2f} s "
              f"(assembly {t['assembly_s']:.2f} s, solve {t['solve_s']:.2f} s)")
    last = cpp["steps"][-1]
    print(f"contact force {last['contact_force']} N/m, largest u.nu - g on Gamma_C "
          f"{last['max_penetration']:.3e} m")
    return max(final.values()), worst


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--config", default=str(HERE / "square.json"))
    ap.add_argument("--output", default=str(ROOT / "out" / "square"))
    ap.add_argument("--build", default=os.environ.get("PIEZO_BUILD", str(ROOT / "build")))
    ap.add_argument("--np", type=int, default=1, help="MPI processes for both solvers")
    ap.add_argument("--set", action="append", default=[], metavar="KEY.PATH=VALUE")
    args = ap.parse_args()
    summaries = run_both(args.config, args.output, args.set, args.build, args.np)
    field_diff, probe_diff = report(summaries, args.output)
    print(f"\noutputs in {args.output}/{{cpp,python}}: summary.json, solution.xdmf "
          "(open in ParaView), nodal/*.npy")
    if max(field_diff, probe_diff) > 1e-8:
        print("C++ and Python DISAGREE beyond 1e-8", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
