#!/usr/bin/python3
"""Direct against iterative linear solver (`solver.linear`), 3D and 2D.

3D: demos/slab.json (ZnO slab pressed on the foundation, tetrahedra) on box
meshes n = [4m, 4m, m], dofs = 4 (4m + 1)^2 (m + 1), k = 1/16, 16 steps (the
demo's T = 1); 2D: demos/square.json (example 1), k = h = 1/n. Per run: time per
step, preconditioner (or LU) set-up, Krylov iterations per Newton iteration,
peak memory per process; serial and `mpirun -n 2`; the slope of time per step
against dofs (least squares), a log-log plot, and where the crossover is.

    /usr/bin/python3 benchmarks/linear_solvers.py --write docs/benchmarks.md
    /usr/bin/python3 benchmarks/linear_solvers.py --quick      # small sizes only
    /usr/bin/python3 benchmarks/linear_solvers.py --alternatives --write docs/benchmarks.md

Output files are off (XDMF, nodal): this measures the solver. Times come from
each run's summary.json (`timing`): "per step" is the run's total time over
its steps (set-ups included), "set-up" one LU factorisation or AMG set-up,
"solve" the rest per Newton iteration. Peak memory: /usr/bin/time per process.
A direct run that does not fit is reported as such (the library's message),
under a memory cap of --cap-gb per process so that the machine does not swap.
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
sys.path.insert(0, str(ROOT / "benchmarks"))
from output_cost import write_section  # noqa: E402
from square import fit_exponent  # noqa: E402

BUILD = Path(os.environ.get("PIEZO_BUILD", ROOT / "build"))
EXE = str(BUILD / "piezo-contact")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
HEADING = "## Direct against iterative linear solver"


def box_dofs(m):
    return 4 * (4 * m + 1) ** 2 * (m + 1)


def run(config, sets, linear, np_=1, cap_gb=None):
    """One run of the executable; its summary with wall time and peak memory
    of the largest process, or {"failed": message}."""
    with tempfile.TemporaryDirectory() as out, tempfile.TemporaryDirectory() as mem:
        args = [EXE, "--config", str(ROOT / config), "--output", out, "--quiet"]
        for o in [*sets, f"solver.linear={linear}", "output.xdmf=false", "output.nodal=none"]:
            args += ["--set", o]
        # each process writes its own peak (OMPI_COMM_WORLD_RANK, expanded by sh)
        cap = f"ulimit -v {int(cap_gb * 2**20)}; " if cap_gb else ""
        inner = (f"{cap}exec /usr/bin/time -f %M -o {mem}/rss.${{OMPI_COMM_WORLD_RANK:-0}} "
                 + " ".join(shlex.quote(a) for a in args))
        cmd = (["mpirun", "-n", str(np_)] if np_ > 1 else []) + ["sh", "-c", inner]
        t0 = time.perf_counter()
        p = subprocess.run(cmd, env=ENV, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        if p.returncode != 0:
            lines = [ln for ln in (p.stderr + p.stdout).splitlines() if "rror" in ln]
            return {"failed": (lines[-1] if lines else f"exit {p.returncode}")[:300],
                    "wall_s": wall}
        s = json.loads((Path(out) / "summary.json").read_text())
        s["peak_mb"] = max(int(f.read_text().split()[-1]) for f in Path(mem).iterdir()) / 1024
    s["wall_s"] = wall
    return s


def figures(s):
    """The numbers of one run."""
    ops = s["timing"]["operations"]
    steps = s["steps"]
    newton = sum(st["newton_iterations"] for st in steps)
    later = [st for st in steps[1:] if st["newton_iterations"] > 0]  # after the first step
    krylov = (sum(st["krylov_iterations"] for st in later)
              / max(1, sum(st["newton_iterations"] for st in later)))
    setups = ops["factorisation"]["count"]
    u = [v for st in steps for p in st["probes"] for v in p["u"]]
    phi = [p["phi"] for st in steps for p in st["probes"]]
    return {"dofs": s["dofs"], "steps": len(steps), "newton": newton, "u": u, "phi": phi,
            "per_step": s["timing"]["total_s"] / len(steps),
            "setup": ops["factorisation"]["seconds"] / max(1, setups), "setups": setups,
            "lagged": ops.get("lagged_preconditioner", 0),
            "solve": ops["triangular_solve"]["seconds"] / max(1, newton),
            "krylov": krylov, "peak_mb": s["peak_mb"], "wall": s["wall_s"]}


ROW = ("| {label} | {dofs} | {linear} | {np} | {per_step:.2f} | {setup:.2f} ({setups}{lag}) "
       "| {solve:.3f} | {newton} | {krylov_text} | {peak_mb:.0f} |")
HEAD = ["| mesh | dofs | solver | processes | s/step | set-up s (count) | solve s/Newton it. "
        "| Newton its | Krylov its/Newton it. | peak MB/process |",
        "|---|---|---|---|---|---|---|---|---|---|"]


def row(label, linear, np_, s, lines, results):
    if "failed" in s:
        lines.append(f"| {label} | | {linear} | {np_} | does not fit / failed: "
                     f"{s['failed']} ({s['wall_s']:.0f} s) | | | | | |")
    else:
        f = figures(s)
        results.append({"label": label, "linear": linear, "np": np_, **f})
        lines.append(ROW.format(label=label, linear=linear, np=np_,
                                lag=f", {f['lagged']} lagged" if f["lagged"] else "",
                                krylov_text=f"{f['krylov']:.1f}" if linear == "iterative" else "-",
                                **f))
    print(lines[-1], flush=True)


def box3d(sizes, direct_sizes, mpi_sizes, steps, cap_gb, lines, results):
    lines += [f"\n### 3D: demos/slab.json, n = [4m, 4m, m], {steps} steps, k = 1/16\n"] + HEAD
    for m in sizes:
        sets = [f"mesh.n=[{4 * m},{4 * m},{m}]", f"time.steps={steps}", f"time.T={steps / 16}"]
        label = f"m = {m}"
        linears = ["iterative"] + (["direct"] if m in direct_sizes else [])
        for linear in linears:
            # direct on 2 processes only where it fits twice (each capped)
            mpi = m in mpi_sizes and (linear == "iterative" or box_dofs(m) < 2e5)
            for np_ in [1] + ([2] if mpi else []):
                row(label, linear, np_, run("demos/slab.json", sets, linear, np_, cap_gb),
                    lines, results)


def square2d(sizes, steps, lines, results):
    lines += [f"\n### 2D: demos/square.json (example 1), {steps} steps, k = h = 1/n\n"] + HEAD
    for n in sizes:
        sets = [f"mesh.n={n}", f"time.steps={steps}", f"time.T={steps / n}"]
        for linear in ("direct", "iterative"):
            row(f"n = {n}", linear, 1, run("demos/square.json", sets, linear), lines, results)


def answers_agree(results, lines):
    """For every 3D size run more than one way: the largest probe difference
    over all steps against the serial iterative run, relative to the
    largest value (u, phi)"""
    base = {r["dofs"]: r for r in results
            if r["dim"] == 3 and r["linear"] == "iterative" and r["np"] == 1}
    for r in results:
        b = base.get(r["dofs"])
        if r["dim"] != 3 or b is None or r is b:
            continue
        du = max(abs(x - y) for x, y in zip(r["u"], b["u"])) / max(abs(x) for x in b["u"])
        dp = max(abs(x - y) for x, y in zip(r["phi"], b["phi"])) / max(abs(x) for x in b["phi"])
        where = "serial" if r["np"] == 1 else f"on {r['np']} processes"
        lines.append(f"- {r['dofs']} dofs, {r['linear']} {where} against "
                     f"iterative serial: probes u {du:.1e}, phi {dp:.1e}")
        print(lines[-1], flush=True)


ALTERNATIVES = {  # raw solver.petsc_options on top of the iterative defaults
    "default: multiplicative, GAMG + rigid body modes on u": {},
    "additive (block Jacobi)": {"pc_fieldsplit_type": "additive"},
    "Schur, lower, selfp": {"pc_fieldsplit_type": "schur", "pc_fieldsplit_schur_fact_type":
                            "lower", "pc_fieldsplit_schur_precondition": "selfp"},
    "BoomerAMG on u (nodal, 3D settings)": {
        "fieldsplit_u_pc_type": "hypre", "fieldsplit_u_pc_hypre_type": "boomeramg",
        "fieldsplit_u_pc_hypre_boomeramg_nodal_coarsen": 4,
        "fieldsplit_u_pc_hypre_boomeramg_nodal_coarsen_diag": 1,
        "fieldsplit_u_pc_hypre_boomeramg_strong_threshold": 0.5,
        "fieldsplit_u_pc_hypre_boomeramg_coarsen_type": "HMIS",
        "fieldsplit_u_pc_hypre_boomeramg_interp_type": "ext+i",
        "fieldsplit_u_pc_hypre_boomeramg_P_max": 4},
}
ALTERNATIVES["BoomerAMG on u + GM-2 interpolation of the rotations"] = dict(
    ALTERNATIVES["BoomerAMG on u (nodal, 3D settings)"],
    fieldsplit_u_pc_hypre_boomeramg_vec_interp_variant=2,
    fieldsplit_u_pc_hypre_boomeramg_vec_interp_qmax=4,
    fieldsplit_u_pc_hypre_boomeramg_vec_interp_smooth="true",
    fieldsplit_u_pc_hypre_boomeramg_interp_refine=1)


def alternatives(sizes, steps, write):
    """The preconditioners measured against each other (3D slab)"""
    heading = "## Iterative solver: the alternatives measured"
    lines = [heading + "\n", "Regenerate: `/usr/bin/python3 benchmarks/linear_solvers.py "
             f"--alternatives --write docs/benchmarks.md` ({platform.node()}, "
             f"{time.strftime('%Y-%m-%d')}). demos/slab.json, {steps} steps, serial; each "
             "variant is `solver.linear = \"iterative\"` plus the raw `solver.petsc_options` "
             "named in `benchmarks/linear_solvers.py` (ALTERNATIVES). Columns as above; "
             "why the default: docs/solvers.md.\n",
             "| variant | dofs | s/step | set-up s | solve s/Newton it. | Newton its "
             "| Krylov its/Newton it. | ms/Krylov it. |", "|---|---|---|---|---|---|---|---|"]
    for m in sizes:
        sets = [f"mesh.n=[{4 * m},{4 * m},{m}]", f"time.steps={steps}", f"time.T={steps / 16}"]
        for name, opts in ALTERNATIVES.items():
            s = run("demos/slab.json", sets + [f"solver.petsc_options={json.dumps(opts)}"],
                    "iterative")
            if "failed" in s:
                lines.append(f"| {name} | {box_dofs(m)} | failed: {s['failed']} | | | | | |")
            else:
                f = figures(s)
                total_krylov = sum(st["krylov_iterations"] for st in s["steps"])
                ms = 1e3 * s["timing"]["operations"]["triangular_solve"]["seconds"] / total_krylov
                lines.append(f"| {name} | {f['dofs']} | {f['per_step']:.2f} | {f['setup']:.2f} "
                             f"| {f['solve']:.3f} | {f['newton']} | {f['krylov']:.1f} | {ms:.1f} |")
            print(lines[-1], flush=True)
    if write:
        write_section(write, heading, lines)


def plot(results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for label, sel, style in (
            ("3D iterative, serial", lambda r: r["dim"] == 3 and r["linear"] == "iterative"
             and r["np"] == 1, "o-"),
            ("3D iterative, 2 processes", lambda r: r["dim"] == 3 and r["linear"] == "iterative"
             and r["np"] == 2, "s--"),
            ("3D direct, serial", lambda r: r["dim"] == 3 and r["linear"] == "direct"
             and r["np"] == 1, "^-"),
            ("2D iterative", lambda r: r["dim"] == 2 and r["linear"] == "iterative", "o:"),
            ("2D direct", lambda r: r["dim"] == 2 and r["linear"] == "direct", "^:")):
        pts = sorted((r["dofs"], r["per_step"]) for r in results if sel(r))
        if len(pts) < 2:
            continue
        xs, ys = zip(*pts)
        ax.loglog(xs, ys, style, label=f"{label} (slope {fit_exponent(xs, ys):.2f})")
    ax.set_xlabel("dofs")
    ax.set_ylabel("time per step (s)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[6, 8, 12, 16, 20, 24, 25],
                    help="3D: m of n = [4m, 4m, m], iterative")
    ap.add_argument("--direct", type=int, nargs="+", default=[6, 8, 12, 16, 25],
                    help="3D sizes also run with the direct solver")
    ap.add_argument("--mpi", type=int, nargs="+", default=[12, 25],
                    help="3D sizes also run on 2 processes")
    ap.add_argument("--steps", type=int, default=16, help="3D steps (16: the demo's T = 1)")
    ap.add_argument("--sizes-2d", type=int, nargs="+", default=[128, 256, 512])
    ap.add_argument("--steps-2d", type=int, default=16)
    ap.add_argument("--cap-gb", type=float, default=20.0,
                    help="virtual memory cap per process (GiB)")
    ap.add_argument("--quick", action="store_true", help="small sizes only (a smoke run)")
    ap.add_argument("--alternatives", action="store_true",
                    help="only: the preconditioners measured against each other (m = 8, 12)")
    ap.add_argument("--write", help="(re)place the report's section in this markdown file")
    args = ap.parse_args()
    if args.alternatives:
        return alternatives([8, 12], 8, args.write)
    if args.quick:
        args.sizes, args.direct, args.mpi, args.sizes_2d = [4, 6, 8], [4, 6, 8], [6], [64, 128]
        args.steps = 4
    t0 = time.perf_counter()
    lines = [HEADING + "\n",
             "Regenerate: `/usr/bin/python3 benchmarks/linear_solvers.py --write "
             f"docs/benchmarks.md` (this run: {platform.node()}, {os.cpu_count()} cores, "
             f"{time.strftime('%Y-%m-%d')}). What the iterative solver is and why: "
             "docs/solvers.md.\n",
             "*s/step*: the run's in-process time over its steps, set-ups included; "
             "*set-up*: one LU factorisation (direct) or preconditioner set-up (iterative: "
             "scaling, fieldsplit, GAMG and BoomerAMG), with the count of them (and of Jacobians "
             "that kept a lagged preconditioner); *solve*: triangular solves or Krylov solves "
             "per Newton iteration; *Krylov its*: per Newton iteration after the first step "
             "(the first starts from zero: 50-120 iterations); peak memory: /usr/bin/time of "
             f"each process, the largest (virtual memory capped at {args.cap_gb:g} GiB per "
             "process so that a direct solve that does not fit fails rather than swaps)."]
    results = []
    box3d(args.sizes, args.direct, args.mpi, args.steps, args.cap_gb, lines, results)
    for r in results:
        r["dim"] = 3
    n3 = len(results)
    square2d(args.sizes_2d, args.steps_2d, lines, results)
    for r in results[n3:]:
        r["dim"] = 2

    lines.append("\n### Growth\n")
    it3 = sorted((r["dofs"], r) for r in results
                 if r["dim"] == 3 and r["linear"] == "iterative" and r["np"] == 1)
    big = [(d, r) for d, r in it3 if d >= 1e5]
    if len(big) >= 2:
        lines.append(f"- 3D iterative, serial, {big[0][0]} to {big[-1][0]} dofs: time per step "
                     f"~ dofs^{fit_exponent([d for d, _ in big], [r['per_step'] for _, r in big]):.2f}"
                     f", set-up ~ dofs^{fit_exponent([d for d, _ in big], [r['setup'] for _, r in big]):.2f}"
                     f", peak memory ~ dofs^{fit_exponent([d for d, _ in big], [r['peak_mb'] for _, r in big]):.2f}")
    halving = [(m, r) for m in (6, 12, 24) for d, r in it3 if d == box_dofs(m)]
    if len(halving) >= 2:
        text = " -> ".join(f"{r['krylov']:.1f} ({r['dofs']} dofs)" for _, r in halving)
        ratios = ", ".join(f"x{b['krylov'] / a['krylov']:.2f}"
                           for (_, a), (_, b) in zip(halving, halving[1:]))
        lines.append(f"- 3D Krylov iterations per Newton iteration as h halves (m = 6, 12, 24): "
                     f"{text}: {ratios} per halving")
    for dim, name in ((3, "3D"), (2, "2D")):
        pairs = {}
        for r in results:
            if r["dim"] == dim and r["np"] == 1:
                pairs.setdefault(r["dofs"], {})[r["linear"]] = r
        for d, p in sorted(pairs.items()):
            if len(p) == 2:
                ratio = p["direct"]["per_step"] / p["iterative"]["per_step"]
                mem = p["direct"]["peak_mb"] / p["iterative"]["peak_mb"]
                lines.append(f"- {name}, {d} dofs: direct / iterative time per step {ratio:.2f}, "
                             f"peak memory {mem:.1f}")
    mpi = {}
    for r in results:
        if r["dim"] == 3 and r["linear"] == "iterative":
            mpi.setdefault(r["dofs"], {})[r["np"]] = r
    for d, p in sorted(mpi.items()):
        if len(p) == 2:
            lines.append(f"- 3D iterative, {d} dofs: speed-up on 2 processes "
                         f"{p[1]['per_step'] / p[2]['per_step']:.2f} (time per step)")
    lines += ["\n### Same answers\n", "The probes (4 points, every step) of each run "
              "against the serial iterative run of the same mesh, relative to the largest "
              "value; the iterative solve stops at half the Newton test's tolerance "
              "(rtol 1e-10 of each field's scaled state), so 1e-6 has a wide margin:\n"]
    answers_agree(results, lines)
    figure = ROOT / "docs" / "figures" / "linear_solvers.png"
    if not args.quick:
        plot(results, figure)
        lines.append(f"\n![time per step against dofs](figures/{figure.name})\n")
    lines.append(f"(benchmark wall time {time.perf_counter() - t0:.0f} s)")
    print("\n".join(lines))
    (ROOT / "out").mkdir(exist_ok=True)
    (ROOT / "out" / "linear_solvers.json").write_text(json.dumps(results, indent=1))
    if args.write:
        write_section(args.write, HEADING, lines)


if __name__ == "__main__":
    main()
