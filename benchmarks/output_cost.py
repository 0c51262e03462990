#!/usr/bin/python3
"""What writing the outputs costs per step: example 1 (k = h = 1/n, T = 1),
XDMF on and off (nodal files off), wall time measured from outside, and the
run's own split of its output time (summary.json timing.output: step files,
checkpoint, summary). With --baseline BUILD, the same runs of another build
(e.g. the release before the outputs were made kill-safe) for comparison.

    /usr/bin/python3 benchmarks/output_cost.py                       # prints markdown
    /usr/bin/python3 benchmarks/output_cost.py --sizes 128 256 --baseline /tmp/old/build
    /usr/bin/python3 benchmarks/output_cost.py --solver python --sizes 64 128

Each configuration is run --repeat times and the fastest run is kept (the
disk cache makes the first write of a file slower than the others).
"""

import argparse
import json
import os
import subprocess
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SQUARE = ROOT / "demos" / "square.json"


def command(solver, build):
    if solver == "cpp":
        return [str(Path(build) / "piezo-contact")]
    return ["/usr/bin/python3", str(ROOT / "demos" / "piezo_contact.py")]


def run(cmd, n, xdmf):
    """Wall time (s) and summary of one run."""
    with tempfile.TemporaryDirectory(dir=os.environ.get("PIEZO_BENCH_DIR")) as out:
        args = cmd + ["--config", str(SQUARE), "--output", out, "--quiet"]
        for o in (f"mesh.n={n}", f"time.steps={n}", "output.nodal=none",
                  f"output.xdmf={'true' if xdmf else 'false'}"):
            args += ["--set", o]
        t0 = time.perf_counter()
        subprocess.run(args, check=True, capture_output=True)
        wall = time.perf_counter() - t0
        return wall, json.loads((Path(out) / "summary.json").read_text())


def fastest(cmd, n, xdmf, repeat):
    return min((run(cmd, n, xdmf) for _ in range(repeat)), key=lambda r: r[0])


def ms_per_step(seconds, steps):
    return f"{1e3 * seconds / steps:.1f}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[128, 256])
    ap.add_argument("--solver", choices=["cpp", "python"], default="cpp")
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--baseline", help="another build directory to compare with (C++)")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()

    builds = [("this", args.build)] + ([("baseline", args.baseline)] if args.baseline else [])
    print(f"{args.solver}: example 1, steps = n, nodal files off; fastest of {args.repeat}; "
          "ms per step\n")
    print("| n | build | wall, XDMF off (s) | wall, XDMF on (s) | XDMF on - off | "
          "in run: step files | checkpoint | summary |")
    print("|---|---|---|---|---|---|---|---|")
    for n in args.sizes:
        for name, build in builds:
            cmd = command(args.solver, build)
            off, _ = fastest(cmd, n, False, args.repeat)
            on, summary = fastest(cmd, n, True, args.repeat)
            split = summary["timing"].get("output")
            inside = ([ms_per_step(split[k]["seconds"], n)
                       for k in ("step_files", "checkpoint", "summary")]
                      if split else ["-", "-", "-"])
            print(f"| {n} | {name} | {off:.2f} | {on:.2f} | {ms_per_step(on - off, n)} | "
                  + " | ".join(inside) + " |", flush=True)


if __name__ == "__main__":
    main()
