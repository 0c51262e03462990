#!/usr/bin/python3
"""Symmetric solves: MUMPS' LDL^T of the Jacobian with its electric rows
negated (`solver.symmetric = "auto"`, the default) against its LU
(`"never"`, the solver before), and MUMPS' orderings on the symmetric form.

    /usr/bin/python3 benchmarks/symmetric_solves.py --write docs/benchmarks.md
    /usr/bin/python3 benchmarks/symmetric_solves.py --quick     # small sizes only

Cases: example 1 (demos/square.json) at n = 256, k = 1/256 (the paper's
finest run, 198,147 dofs), medians of --repeat runs of each solver in turn;
the 3D slab (demos/slab.json, n = [4m, 4m, m]) at m = 12 and 16 (124,852 and
287,300 dofs), 4 steps, one run each. Per run, from its summary: wall time,
time per factorisation, per triangular solve (Newton time outside the
callbacks per iteration), MUMPS' factor entries (INFOG(29)), peak memory
(/usr/bin/time), and the largest difference of the probes from the LU run
(relative to each field's largest value). The floor of a triangular solve:
the factors' bytes (8 per entry) read once at the machine's read bandwidth,
measured here by a STREAM-like sum over a 1 GB array (numpy).
"""

import argparse
import json
import os
import platform
import shlex
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
from output_cost import write_section  # noqa: E402

EXE = str(Path(os.environ.get("PIEZO_BUILD", ROOT / "build")) / "piezo-contact")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
HEADING = "## Symmetric solves: LDL^T against LU"
ORDERING_HEADING = "## MUMPS' orderings on the symmetric form"
PIVOTING = "solver.petsc_options.mat_mumps_cntl_1=0.01"
ORDERINGS = {"AMD": 0, "AMF": 2, "SCOTCH": 3, "PORD": 4, "QAMD": 6}


def read_bandwidth_gbs(repeat=5):
    """Sustained read bandwidth: the fastest sum over a 1 GB array."""
    a = np.ones(2**27)  # 1 GiB of float64
    best = min(_timed(a.sum) for _ in range(repeat))
    return a.nbytes / best / 1e9


def _timed(f):
    t0 = time.perf_counter()
    f()
    return time.perf_counter() - t0


def run(config, sets):
    """One run of the executable: its summary, wall time and peak memory."""
    with tempfile.TemporaryDirectory() as out, tempfile.NamedTemporaryFile() as mem:
        args = [EXE, "--config", str(ROOT / config), "--output", out, "--quiet"]
        for o in [*sets, "output.xdmf=false", "output.nodal=none"]:
            args += ["--set", o]
        t0 = time.perf_counter()
        p = subprocess.run(["/usr/bin/time", "-f", "%M", "-o", mem.name, *args], env=ENV,
                           capture_output=True, text=True)
        wall = time.perf_counter() - t0
        if p.returncode != 0:
            raise SystemExit(f"{shlex.join(args)}: exit {p.returncode}\n{p.stderr[-2000:]}")
        s = json.loads((Path(out) / "summary.json").read_text())
        s["peak_mb"] = int(Path(mem.name).read_text().split()[-1]) / 1024
    s["wall_s"] = wall
    return s


def figures(s):
    t = s["timing"]
    ops = t["operations"]
    its = ops["triangular_solve"]["count"]
    return {"dofs": s["dofs"], "wall": s["wall_s"], "total": t["total_s"],
            "factorisations": ops["factorisation"]["count"],
            "factor_s": ops["factorisation"]["seconds"] / max(1, ops["factorisation"]["count"]),
            "solve_s": ops["triangular_solve"]["seconds"] / max(1, its), "its": its,
            "entries": t["factor_entries"], "kind": t["factorisation"],
            "ordering": t.get("factor_ordering", "?"),
            "peak_mb": s["peak_mb"],
            "u": [v for st in s["steps"] for p in st["probes"] for v in p["u"]],
            "phi": [p["phi"] for st in s["steps"] for p in st["probes"]]}


def difference(a, b):
    """Largest probe difference relative to each field's largest value."""
    out = 0.0
    for f in ("u", "phi"):
        x, y = np.array(a[f]), np.array(b[f])
        scale = max(np.abs(x).max(), 1e-300)
        out = max(out, float(np.abs(x - y).max() / scale))
    return out


def medians(runs):
    med = dict(runs[0])
    for key in ("wall", "total", "factor_s", "solve_s", "peak_mb"):
        med[key] = statistics.median(r[key] for r in runs)
    return med


ROW = ("| {case} | {dofs} | {kind} | {wall:.1f} | {factor_s:.2f} ({factorisations}) "
       "| {solve_ms:.1f} | {floor_ms:.1f} | {ratio:.1f} | {entries_m:.1f} | {peak_mb:.0f} | {diff} |")
HEAD = ["| case | dofs | factorisation | wall s | factorisation s (count) | one solve ms "
        "| floor ms | solve / floor | factor entries (M) | peak MB | probes vs LU |",
        "|---|---|---|---|---|---|---|---|---|---|---|"]


def row(case, f, bandwidth, reference):
    # a solve reads every factor entry once for LU (L forward, U backward),
    # L twice for LDL^T (forward, then L^T backward): the same bytes
    reads = 2 if f["kind"] == "LDLT" else 1
    floor_ms = 8 * reads * f["entries"] / (bandwidth * 1e9) * 1e3
    diff = "-" if reference is None else f"{difference(f, reference):.1e}"
    return ROW.format(case=case, solve_ms=1e3 * f["solve_s"], floor_ms=floor_ms,
                      ratio=1e3 * f["solve_s"] / floor_ms, entries_m=f["entries"] / 1e6,
                      diff=diff, **f)


def pivoting_row(case, f, bandwidth, reference):
    return row(case, f, bandwidth, reference).replace("| LDLT |", "| LDLT, pivoting |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="n = 64 and m = 6 only")
    ap.add_argument("--write", help="(re)place the report's sections in this markdown file")
    ap.add_argument("--orderings-only", action="store_true",
                    help="only the section on MUMPS' orderings")
    args = ap.parse_args()
    start = time.perf_counter()
    bandwidth = read_bandwidth_gbs()
    n2d = 64 if args.quick else 256
    m3d = [6] if args.quick else [12, 16]
    lines = [HEADING, "",
             f"Regenerate: `/usr/bin/python3 benchmarks/symmetric_solves.py --write "
             f"docs/benchmarks.md` (this run: {platform.node()}, {os.cpu_count()} cores, "
             f"{time.strftime('%Y-%m-%d')}; read bandwidth {bandwidth:.1f} GB/s measured by "
             f"the script). What the symmetric form is: docs/solvers.md.", "",
             "*one solve*: Newton time outside the callbacks per iteration (MUMPS' "
             "triangular solves and the vector updates); *floor*: the bytes a solve must "
             "read at the measured bandwidth, 8 per factor entry, read once by LU's "
             "forward and backward sweeps (L, then U) and twice by LDL^T's (L, then L^T); "
             "*LDLT, pivoting*: MUMPS' threshold pivoting kept (CNTL(1) = 0.01, what the "
             "core falls back to when D J is not quasi-definite); *probes vs LU*: "
             "largest difference of every probe at every step from the LU run, relative "
             "to each field's largest value.", "",
             f"### Example 1, n = k^-1 = {n2d}, medians of {args.repeat}", ""] + HEAD
    if not args.orderings_only:
        compare_factorisations(args, bandwidth, n2d, m3d, lines, start)
    orderings(args, n2d, m3d)


def compare_factorisations(args, bandwidth, n2d, m3d, lines, start):
    print("\n".join(lines), flush=True)
    sq = ["mesh.n=%d" % n2d, "time.steps=%d" % n2d]
    lus, ldlts = [], []
    for _ in range(args.repeat):  # the two in turn, so that drift hits both
        lus.append(figures(run("demos/square.json", sq + ["solver.symmetric=never"])))
        ldlts.append(figures(run("demos/square.json", sq)))
    lu, ldlt = medians(lus), medians(ldlts)
    pivoting = figures(run("demos/square.json", sq + [PIVOTING]))
    for f, ref in ((lu, None), (ldlt, lu)):
        lines.append(row(f"example 1, n = {n2d}", f, bandwidth, ref))
        print(lines[-1], flush=True)
    lines.append(pivoting_row(f"example 1, n = {n2d} (one run)", pivoting, bandwidth, lu))
    lines.append(f"\nLDL^T / LU: wall {ldlt['wall'] / lu['wall']:.2f}, factorisation "
                 f"{ldlt['factor_s'] / lu['factor_s']:.2f}, one solve "
                 f"{ldlt['solve_s'] / lu['solve_s']:.2f}, factor entries "
                 f"{ldlt['entries'] / lu['entries']:.2f}, peak memory "
                 f"{ldlt['peak_mb'] / lu['peak_mb']:.2f}.")

    lines += ["", "### 3D slab (demos/slab.json), n = [4m, 4m, m], 4 steps, k = 1/16, one run each",
              ""] + HEAD
    for m in m3d:
        sets = [f"mesh.n=[{4 * m},{4 * m},{m}]", "time.steps=4", "time.T=0.25"]
        lu3 = figures(run("demos/slab.json", sets + ["solver.symmetric=never"]))
        ld3 = figures(run("demos/slab.json", sets))
        pv3 = figures(run("demos/slab.json", sets + [PIVOTING]))
        for f, ref in ((lu3, None), (ld3, lu3)):
            lines.append(row(f"slab, m = {m}", f, bandwidth, ref))
            print(lines[-1], flush=True)
        lines.append(pivoting_row(f"slab, m = {m}", pv3, bandwidth, lu3))
        print(lines[-1], flush=True)

    lines.append(f"\n(benchmark wall time {time.perf_counter() - start:.0f} s)")
    if args.write:
        write_section(args.write, HEADING, lines)


def orderings(args, n2d, m3d):
    start = time.perf_counter()
    lines = [ORDERING_HEADING, "",
             "Regenerate: the command above (one run per ordering, asked by "
             "`solver.petsc_options.mat_mumps_icntl_7`; LDL^T throughout). PETSc's own "
             "orderings (nested dissection) cannot be passed: PETSc 3.18 refuses "
             "ICNTL(7) = 1 with a PETSc ordering (error 63, argument out of range; "
             "tried with pc_factor_mat_ordering_type nd and rcm).",
             "",
             "| case | ordering asked | ordering MUMPS ran (INFOG(7)) | factorisation s "
             "| one solve ms | factor entries (M) |",
             "|---|---|---|---|---|---|"]
    cases = [(f"example 1, n = {n2d}, 8 steps", "demos/square.json",
              [f"mesh.n={n2d}", "time.steps=8", "time.T=%g" % (8 / n2d)])]
    cases += [(f"slab, m = {m3d[0]}, 2 steps", "demos/slab.json",
               [f"mesh.n=[{4 * m3d[0]},{4 * m3d[0]},{m3d[0]}]", "time.steps=2", "time.T=0.125"])]
    for case, config, sets in cases:
        for name, icntl in ORDERINGS.items():
            f = figures(run(config, sets + [f"solver.petsc_options.mat_mumps_icntl_7={icntl}"]))
            lines.append(f"| {case} | {name} | {f['ordering']} | {f['factor_s']:.2f} "
                         f"| {1e3 * f['solve_s']:.1f} "
                         f"| {f['entries'] / 1e6:.1f} |")
            print(lines[-1], flush=True)
    lines.append(f"\n(benchmark wall time {time.perf_counter() - start:.0f} s)")
    if args.write:
        write_section(args.write, ORDERING_HEADING, lines)


if __name__ == "__main__":
    main()
