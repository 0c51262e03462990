#!/usr/bin/python3
"""Benchmark example 1 (the square, k = h = 1/n, T = 1) on the three engines:
the executable (C++ loop, ahead-of-time kernels, LU kept while the Jacobian
is unchanged), the same C++ loop from Python (`python3 -m piezocontact`, JIT
kernels, cache warmed by an untimed run first) and the reference engine
(petsc4py SNES, a factorisation per iteration), serial and on 2 MPI
processes; the cost's growth with the number of dofs; the C++ run against
its own ideal; the whole Figure-3 study. (Direct against iterative:
benchmarks/linear_solvers.py.)

    /usr/bin/python3 benchmarks/square.py                  # prints markdown
    /usr/bin/python3 benchmarks/square.py --write docs/benchmarks.md
    /usr/bin/python3 benchmarks/square.py --sizes 32 64 --no-mpi --no-study
    /usr/bin/python3 benchmarks/square.py --sizes 128 --no-mpi --no-study --repeat 5

Each C++-loop run (cpp, cpp-jit) is repeated --repeat times and the fastest
kept (the machine's noise is one-sided); the reference engine runs once.

Output files (XDMF, nodal) are off: this measures the solver, not the disk
(the per-step checkpoint stays on; benchmarks/output_cost.py measures it).
Timings come from each run's summary.json; wall and peak memory per process
from /usr/bin/time.
"""

import argparse
import json
import math
import os
import platform
import shlex
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SQUARE = ROOT / "demos" / "square.json"
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
NO_OUTPUT = ["output.xdmf=false", "output.nodal=none"]

BUILD = Path(os.environ.get("PIEZO_BUILD", ROOT / "build"))
ENV["PYTHONPATH"] = str(BUILD / "python")  # this tree's package
MODULE = ["/usr/bin/python3", "-m", "piezocontact"]
ENGINES = {"cpp": [str(BUILD / "piezo-contact")], "cpp-jit": MODULE,
           "reference": MODULE + ["--engine", "reference"]}


def run(solver, n, np_=1, steps=None, extra=()):
    """One run; returns its summary plus wall time and peak memory (MB,
    largest process) as measured from outside."""
    exe = ENGINES[solver]
    steps = steps or n
    with tempfile.TemporaryDirectory() as out, tempfile.TemporaryDirectory() as mem:
        args = exe + ["--config", str(SQUARE), "--output", out, "--quiet"]
        for o in [f"mesh.n={n}", f"time.steps={steps}", f"time.T={steps / n}",
                  *NO_OUTPUT, *extra]:
            args += ["--set", o]
        # one file per process: the shell expands the rank (mpirun and
        # /usr/bin/time do not)
        timed = (f"exec /usr/bin/time -f %M -o {mem}/rss.${{OMPI_COMM_WORLD_RANK:-0}} "
                 + " ".join(shlex.quote(a) for a in args))
        cmd = (["mpirun", "-n", str(np_)] if np_ > 1 else []) + ["sh", "-c", timed]
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, env=ENV, capture_output=True)
        wall = time.perf_counter() - t0
        summary = json.loads((Path(out) / "summary.json").read_text())
        peak = max(int(p.read_text().split()[-1]) for p in Path(mem).iterdir()) / 1024
    summary["wall_s"], summary["peak_mb"] = wall, peak
    return summary


def ideal_s(s):
    """steps x (one triangular solve + two residuals) + factorisations x one
    LU, each at its average measured cost in the same run (C++ only)."""
    ops = s["timing"]["operations"]
    avg = {k: ops[k]["seconds"] / max(ops[k]["count"], 1)
           for k in ("triangular_solve", "residual", "factorisation")}
    return (len(s["steps"]) * (avg["triangular_solve"] + 2 * avg["residual"])
            + ops["factorisation"]["count"] * avg["factorisation"])


def factorisations(s):
    ops = s["timing"]["operations"]
    return ops["factorisation"]["count"] if "factorisation" in ops else ops["factorisations"]


def fit_exponent(xs, ys):
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def fastest(solver, n, np_, repeat):
    """The fastest of `repeat` runs (the JIT cache warmed first)."""
    if solver == "cpp-jit":
        run(solver, n, np_, steps=1)
    runs = [run(solver, n, np_) for _ in range(repeat if solver != "reference" else 1)]
    return min(runs, key=lambda s: s["wall_s"])


def comparison_table(sizes, np_, repeat, lines):
    lines += [f"\n### {'serial' if np_ == 1 else f'mpirun -n {np_}'}\n",
              "| n | dofs | engine | wall (s) | s/step | Newton it./step | factorisations "
              "| peak MB/process | wall / executable's | C++ ideal (s) | actual/ideal |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
    walls = {solver: [] for solver in ENGINES}
    dofs = []
    for n in sizes:
        res = {solver: fastest(solver, n, np_, repeat) for solver in ENGINES}
        dofs.append(res["cpp"]["dofs"])
        for solver, s in res.items():
            steps = len(s["steps"])
            its = sum(st["newton_iterations"] for st in s["steps"]) / steps
            walls[solver].append(s["wall_s"])
            ratio = f"{s['wall_s'] / res['cpp']['wall_s']:.2f}" if solver != "cpp" else ""
            ideal, vs_ideal = "", ""
            if solver != "reference":
                ideal = f"{ideal_s(s):.2f}"
                vs_ideal = f"{s['timing']['total_s'] / ideal_s(s):.2f}"
            lines.append(
                f"| {n} | {s['dofs']} | {solver} | {s['wall_s']:.2f} | {s['wall_s'] / steps:.3f} "
                f"| {its:.2f} | {factorisations(s)} | {s['peak_mb']:.0f} | {ratio} "
                f"| {ideal} | {vs_ideal} |")
            print(lines[-1], flush=True)
    if len(sizes) > 1:
        lines.append("")
        for solver in ENGINES:
            lines.append(f"- {solver}: wall time grows like dofs^{fit_exponent(dofs, walls[solver]):.2f} "
                         f"(least squares over n = {sizes[0]}..{sizes[-1]}, k = 1/n, so the "
                         "number of steps grows too)")
    return lines


def study(finest, lines):
    levels = [2 ** i for i in range(1, int(math.log2(finest)) + 1)]
    t0 = time.perf_counter()
    for n in levels:
        run("cpp", n)
    total = time.perf_counter() - t0
    lines += ["\n### Figure-3 study (C++)\n",
              f"h = k = 1/{levels[0]} .. 1/{levels[-1]} ({len(levels)} runs, one after the "
              f"other, process start-up included): **{total:.1f} s** wall."]
    print(lines[-1], flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[32, 64, 128, 256])
    ap.add_argument("--no-mpi", action="store_true")
    ap.add_argument("--no-study", action="store_true")
    ap.add_argument("--repeat", type=int, default=3,
                    help="runs of the C++ loop per size and engine; the fastest is kept")
    ap.add_argument("--write", help="also write the markdown report to this file")
    args = ap.parse_args()
    t0 = time.perf_counter()
    lines = ["# Benchmarks\n",
             f"Regenerate: `/usr/bin/python3 benchmarks/square.py --write docs/benchmarks.md` "
             f"(this run: {platform.node()}, {os.cpu_count()} cores, "
             f"{time.strftime('%Y-%m-%d')}).\n",
             "Example 1, T = 1, k = h = 1/n; XDMF and nodal output off. Wall time is "
             "measured outside the process (start-up included; for cpp-jit that is the "
             "Python interpreter, dolfinx's import and loading the JIT-compiled kernels "
             f"from the warm cache), the fastest of {args.repeat} runs for cpp and cpp-jit; "
             "peak memory per process "
             "from /usr/bin/time; the C++ ideal is steps x (triangular solve + 2 residual "
             "assemblies) + factorisations x LU at the run's own average costs, set "
             "against the run's in-process time."]
    comparison_table(args.sizes, 1, args.repeat, lines)
    if not args.no_mpi:
        comparison_table(args.sizes, 2, args.repeat, lines)
    if not args.no_study:
        study(max(args.sizes), lines)
    lines.append(f"\n(benchmark wall time {time.perf_counter() - t0:.0f} s)")
    report = "\n".join(lines) + "\n"
    print(report)
    if args.write:
        # sections other scripts write (## headings) are kept
        old = Path(args.write).read_text() if Path(args.write).exists() else ""
        kept = old[old.index("\n## "):] if "\n## " in old else ""
        Path(args.write).write_text(report + kept)


if __name__ == "__main__":
    sys.exit(main())
