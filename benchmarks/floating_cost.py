#!/usr/bin/python3
"""What a floating electrode costs per step: example 1 with its right side an
electrode, floating, and then prescribed with the potentials the floating
run found (the same discrete problem), at k = h = 1/n, T = 1, outputs off
but summary and checkpoints. A floating
electrode adds one back-substitution per factorisation (its unit response)
and a few dot products per Newton iteration (cpp/piezocontact/floating.h).

    /usr/bin/python3 benchmarks/floating_cost.py                   # prints markdown
    /usr/bin/python3 benchmarks/floating_cost.py --sizes 64 128 --write docs/benchmarks.md

Each run is repeated --repeat times and the fastest kept.
"""

import argparse
import json
import os
import platform
import subprocess
import tempfile
import time
from pathlib import Path

from output_cost import write_section

ROOT = Path(__file__).resolve().parents[1]
SQUARE = ROOT / "demos" / "square.json"
HEADING = "## Cost of a floating electrode"


def run(build, cfg, n):
    """Wall time (s) and summary of one run of the executable."""
    with tempfile.TemporaryDirectory(dir=os.environ.get("PIEZO_BENCH_DIR")) as out:
        config = Path(out) / "config.json"
        config.write_text(json.dumps(cfg))
        args = [str(Path(build) / "piezo-contact"), "--config", str(config), "--output",
                str(Path(out) / "run"), "--quiet"]
        for o in (f"mesh.n={n}", f"time.steps={n}", "output.nodal=none", "output.xdmf=false"):
            args += ["--set", o]
        t0 = time.perf_counter()
        subprocess.run(args, check=True, capture_output=True)
        wall = time.perf_counter() - t0
        return wall, json.loads((Path(out) / "run" / "summary.json").read_text())


def fastest(build, cfg, n, repeat):
    return min((run(build, cfg, n) for _ in range(repeat)), key=lambda r: r[0])


def row(n, kind, wall, summary):
    steps = summary["steps"]
    ops = summary["timing"]["operations"]
    its = sum(s["newton_iterations"] for s in steps)
    right = steps[-1]["electrodes"]["right"]
    floating = ops.get("floating_electrodes", {"seconds": 0.0})["seconds"]
    return (f"| {n} | {kind} | {wall:.2f} | "
            f"{1e3 * summary['timing']['total_s'] / len(steps):.1f} | {its} | "
            f"{ops['factorisation']['count']} | "
            f"{1e3 * ops['triangular_solve']['seconds'] / len(steps):.2f} | "
            f"{1e3 * floating / len(steps):.2f} | "
            f"{right['potential']:.6g} | {right['reaction_charge']:.4e} |")


def potential_table(summary):
    """The right electrode's potential at every step, as a table history:
    prescribing it poses the floating run's discrete problem again."""
    return {"value": 1.0, "history": {"table": [
        [s["t"], s["electrodes"]["right"]["potential"]] for s in summary["steps"]]}}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[128])
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--write", help="(re)place the report's section in this markdown file")
    args = ap.parse_args()
    t0 = time.perf_counter()
    lines = [f"{HEADING}\n",
             f"Regenerate: `/usr/bin/python3 benchmarks/floating_cost.py --sizes "
             f"{' '.join(map(str, args.sizes))} --write docs/benchmarks.md` (this run: "
             f"{platform.node()}, {os.cpu_count()} cores, {time.strftime('%Y-%m-%d')}).\n",
             "Example 1 with `right` an electrode, k = h = 1/n, T = 1, XDMF and nodal "
             f"files off; fastest of {args.repeat} runs. First `right` floating with a "
             "constant charge (the one a 20 V electrode ends with), then `right` prescribed "
             "with the potential the floating run found at each step (a table history): the "
             "same discrete problem, solved with and without the floating machinery. *per "
             "step*: the run's own `timing.total_s` / steps; *solves*: triangular solves "
             "per step; *floating*: unit responses, charge residuals and bordered updates "
             "per step (`timing.operations.floating_electrodes`); the last columns: the "
             "right electrode at t = 1.\n",
             "| n | right electrode | wall (s) | per step (ms) | Newton its | "
             "factorisations | solves per step (ms) | floating per step (ms) | "
             "potential (V) | reaction charge (C/m) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    print("\n".join(lines), flush=True)
    base = json.loads(SQUARE.read_text())
    for n in args.sizes:
        prescribed = json.loads(json.dumps(base))
        prescribed["boundaries"]["right"] = {"potential": 20.0}
        charge = run(args.build, prescribed, n)[1]["steps"][-1]["electrodes"]["right"][
            "reaction_charge"]
        floating = json.loads(json.dumps(base))
        floating["boundaries"]["right"] = {"floating": {"charge": charge}}
        wall, summary = fastest(args.build, floating, n, args.repeat)
        lines.append(row(n, f"floating, Q = {charge:.4e} C/m", wall, summary))
        print(lines[-1], flush=True)
        again = json.loads(json.dumps(base))
        again["boundaries"]["right"] = {"potential": potential_table(summary)}
        wall, summary = fastest(args.build, again, n, args.repeat)
        lines.append(row(n, "prescribed, the floating run's potentials", wall, summary))
        print(lines[-1], flush=True)
    lines.append(f"\n(benchmark wall time {time.perf_counter() - t0:.0f} s)")
    if args.write:
        write_section(args.write, HEADING, lines)

if __name__ == "__main__":
    main()
