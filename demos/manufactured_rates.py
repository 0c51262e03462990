#!/usr/bin/python3
# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # Manufactured solutions: convergence rates in h and in k
#
# `demos/manufactured.json` solves the model on the unit square with the
# loads of an exact solution (forms/manufactured.py): u = U0 theta(t) U(x),
# phi = PHI0 theta(t) Phi(x). Every kind of boundary condition is on: u and
# phi Dirichlet (left, from the exact solution at t_n), phi Dirichlet (top),
# tractions (top, right), surface charges (right, bottom) and the foundation
# on the bottom, where the gap g = 2e-11 m closes when theta = 0.4 and the
# contact zone then grows to 30 % (linear U) or half (smooth U) of Gamma_C:
# the penalty is part of the balance.
#
# Three studies, errors `max_n ||x_n - x(t_n)||` in L2 and H1, u and phi apart:
#
# * **h**: U, Phi smooth, theta = t. Backward Euler has no truncation error
#   on a solution linear in time, so the error is the spatial one for any k
#   (checked below by refining k alone): expect 2 in L2 and 1 in H1 (P1).
# * **k**: U, Phi linear, theta = sin(pi t / 2). P1 reproduces the fields, so
#   the error is the time error on any mesh: expect 1 in both norms.
# * **h = k**: both smooth, refined together (Corollary 3.4): expect 1 in H1.
#
# Each runs with the C++ solver and the reference engine (`--solver` for one).
# Results and their reading: docs/verification.md.
#
#     /usr/bin/python3 demos/manufactured_rates.py [--finest 128] [--solver cpp]

import argparse
import os
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from piezodemos import runs  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
CONFIG = HERE / "manufactured.json"
NORMS = ("u_L2", "u_H1", "phi_L2", "phi_H1")

# study: (space, time, what is refined, expected rates in L2 and H1)
STUDIES = {
    "h": ("smooth", "linear", "h", {"L2": 2, "H1": 1}),
    "k": ("linear", "smooth", "k", {"L2": 1, "H1": 1}),
    "h = k": ("smooth", "smooth", "h = k", {"L2": 1, "H1": 1}),
}
H_STUDY_STEPS = 8  # k = 1/8 throughout the h study
K_STUDY_N = 8      # h = 1/8 throughout the k study


def overrides(study, level, steps=None):
    """The --set options of level 1/level of a study (time.steps may be
    forced, for the h study's premise)."""
    space, time_, _, _ = STUDIES[study]
    n, default_steps = {"h": (level, H_STUDY_STEPS), "k": (K_STUDY_N, level),
                        "h = k": (level, level)}[study]
    steps = steps or default_steps
    return [f"manufactured.space={space}", f"manufactured.time={time_}", f"mesh.n={n}",
            f"time.steps={steps}", "output.xdmf=false", "output.nodal=none"]


def max_errors(summary):
    """Each norm's largest error over the time steps."""
    return {name: max(step["errors"][name] for step in summary["steps"]) for name in NORMS}


def run_study(study, levels, solver, out, build):
    rows = []
    for level in levels:
        summary, wall = runs.run_quietly(solver, CONFIG, Path(out) / solver / f"{study}-{level}",
                                         overrides(study, level), build)
        rows.append({"level": level, "dofs": summary["dofs"], "wall": wall,
                     "errors": max_errors(summary)})
    sizes = [1.0 / r["level"] for r in rows]
    rates = {name: runs.observed_rates(sizes, [r["errors"][name] for r in rows])
             for name in NORMS}
    return rows, rates


def table(study, solver, rows, rates):
    _, _, refined, expected = STUDIES[study]
    fixed = {"h": f", k = 1/{H_STUDY_STEPS}", "k": f", h = 1/{K_STUDY_N}", "h = k": ""}[study]
    lines = [f"Study {study} ({solver}): {STUDIES[study][0]} in space, {STUDIES[study][1]} "
             f"in time{fixed}; expected rates L2 {expected['L2']}, H1 {expected['H1']}", "",
             f"| {refined} | dofs | u L2 (m) | rate | u H1 (m) | rate | phi L2 (V) | rate "
             "| phi H1 (V) | rate | wall (s) |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for i, r in enumerate(rows):
        cells = " | ".join(f"{r['errors'][name]:.3e} | {_fmt(rates[name][i])}" for name in NORMS)
        lines.append(f"| 1/{r['level']} | {r['dofs']} | {cells} | {r['wall']:.1f} |")
    return lines


def _fmt(rate):
    return "" if rate is None else f"{rate:.2f}"


def k_independence(solver, n, out, build):
    """The h study's premise: with theta = t, refining k alone leaves the
    error unchanged up to the O(h) transient between the projections."""
    errs = []
    for steps in (H_STUDY_STEPS, 8 * H_STUDY_STEPS):
        summary, _ = runs.run_quietly(solver, CONFIG, Path(out) / solver / f"kfree-{steps}",
                                      overrides("h", n, steps), build)
        errs.append(max_errors(summary))
    change = max(abs(errs[1][k] - errs[0][k]) / errs[0][k] for k in NORMS)
    return (f"h study premise, 1/h = {n}: k = 1/{H_STUDY_STEPS} -> 1/{8 * H_STUDY_STEPS} "
            f"changes every error by at most {change:.1e} (relative)")


def plot(results, path):
    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    for ax, (study, (rows, _)) in zip(axes, results.items()):
        h = [1.0 / r["level"] for r in rows]
        for name, style in zip(NORMS, ("o-", "s-", "o--", "s--")):
            e = [r["errors"][name] for r in rows]
            ax.loglog(h, [v / e[0] for v in e], style, label=name.replace("_", " "), ms=4)
        for order in sorted(set(STUDIES[study][3].values())):
            ax.loglog(h, [(v / h[0]) ** order for v in h], "k:", lw=0.8)
            ax.annotate(f"slope {order}", (h[-1], (h[-1] / h[0]) ** order), fontsize=7)
        ax.set_xlabel(STUDIES[study][2])
        ax.set_title(f"{study}: {STUDIES[study][0]} in space, {STUDIES[study][1]} in time",
                     fontsize=9)
    axes[0].set_ylabel("max_n error / coarsest error")
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    ap = argparse.ArgumentParser(description="Manufactured-solution rates in h and k")
    ap.add_argument("--finest", type=int, default=64,
                    help="finest 1/h of the h studies (power of 2 >= 8); the k study "
                         "goes to 1/k = 2 x finest")
    ap.add_argument("--solver", choices=["cpp", "cpp-jit", "reference", "both"], default="both")
    ap.add_argument("--output", default=str(ROOT / "out" / "manufactured"))
    ap.add_argument("--build", default=os.environ.get("PIEZO_BUILD", str(ROOT / "build")))
    args = ap.parse_args()
    if args.finest < 8 or args.finest & (args.finest - 1):
        ap.error(f"--finest {args.finest}: must be a power of 2, at least 8")
    t0 = time.perf_counter()
    h_levels = [2 ** i for i in range(2, args.finest.bit_length())]
    levels = {"h": h_levels, "k": h_levels + [2 * h_levels[-1]], "h = k": h_levels}
    solvers = ["cpp", "reference"] if args.solver == "both" else [args.solver]
    lines, results = [], {}
    for solver in solvers:
        for study in STUDIES:
            rows, rates = run_study(study, levels[study], solver, args.output, args.build)
            results[(solver, study)] = rows, rates
            lines += table(study, solver, rows, rates) + [""]
            print("\n".join(table(study, solver, rows, rates)), flush=True)
        lines.append(k_independence(solver, 16, args.output, args.build))
        print(lines[-1], flush=True)
    if len(solvers) == 2:
        worst = max(abs(a["errors"][k] - b["errors"][k]) / a["errors"][k]
                    for study in STUDIES
                    for a, b in zip(results[("cpp", study)][0], results[("reference", study)][0])
                    for k in NORMS)
        lines.append(f"C++ vs reference: largest relative difference of any error above: "
                     f"{worst:.1e}")
        print(lines[-1])
    lines.append(f"whole study {time.perf_counter() - t0:.1f} s")
    print(lines[-1])
    out = Path(args.output)
    (out / "table.md").write_text("\n".join(lines) + "\n")
    plot({study: results[(solvers[0], study)] for study in STUDIES}, out / "rates.png")
    print(f"table: {out / 'table.md'}, plot: {out / 'rates.png'}")


if __name__ == "__main__":
    main()
