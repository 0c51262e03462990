#!/usr/bin/python3
# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # The paper's Figure 3: convergence of example 1 as h = k -> 0
#
# Example 1 (`demos/square.json`) is solved with h = k = 1/2, 1/4, ..., 1/N
# (h = 1/n: n x n squares cut in two), and two kinds of error are measured:
#
# * **against the finest run** (the paper's way): for each level n,
#   `max_j (||u_j - u_ref(t_j)||_H1 + ||phi_j - phi_ref(t_j)||_H1)` over its
#   time steps t_j = j/n, the coarse solution carried onto the reference mesh
#   (the meshes are nested and P1 is exact there, so the transfer is exact);
#   u (metres) and phi (volts) also separately, since their sum adds units;
# * **between successive levels** (n against 2n), which does not lean on the
#   reference: `max_j ||x_n(t_j) - x_2n(t_j)||_H1`.
#
# Corollary 3.4 promises O(h + k) for solutions with the regularity (3.10),
# which the paper leaves unproven. The default finest level is 1/128 (the
# whole study runs in 15 s on 2 cores); `--finest 256` is the paper's
# (86 s). Results and their reading: docs/verification.md.
#
#     /usr/bin/python3 demos/convergence_study.py [--finest 256] [--solver reference]

import argparse
import math
import os
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import ufl  # noqa: E402
from dolfinx import fem  # noqa: E402
from piezocontact._compat import colliding_cells, functionspace  # noqa: E402

from piezocontact import compare  # noqa: E402
from piezodemos import runs  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


def solve(solver, n, out, build):
    return runs.run_quietly(solver, HERE / "square.json", out,
                            [f"mesh.n={n}", f"time.steps={n}", "output.xdmf=false",
                             "output.nodal=all"], build)


class Level:
    """One run's P1 fields on its own mesh, read from its nodal files."""

    def __init__(self, out, summary):
        self.dir, self.n = Path(out), summary["config"]["mesh"]["n"]
        self.fields = compare.FieldComparer(summary["config"])

    def field(self, step, name):
        return self.fields.function(self.dir / "nodal" / f"{name}_{step:04d}.npy", name)


class Transfer:
    """Coarse P1 functions evaluated at a finer mesh's dofs (exact: nested)."""

    def __init__(self, coarse, fine):
        self.coarse, self.fine = coarse, fine
        self.cells, self.points = {}, {}
        for name, V in fine.fields.V.items():
            pts = V.tabulate_dof_coordinates()
            hits = colliding_cells(coarse.fields.mesh, pts)
            self.cells[name] = np.array([hits.links(i)[0] for i in range(len(pts))],
                                        dtype=np.int32)
            self.points[name] = pts

    def __call__(self, f, name):
        out = fem.Function(self.fine.fields.V[name])
        bs = out.function_space.dofmap.index_map_bs
        out.x.array[:] = f.eval(self.points[name], self.cells[name]).reshape(-1, bs).ravel()
        return out


def h1_error(a, b, weight=1.0):
    e = a - b
    return math.sqrt(fem.assemble_scalar(fem.form(
        weight * (ufl.inner(e, e) + ufl.inner(ufl.grad(e), ufl.grad(e))) * ufl.dx)))


# Where the error lives: discs of radius 1/4 around each corner of the
# square (named by the edges that meet there), and the rest
CORNERS = {"(0,0) clamped/contact": (0.0, 0.0), "(0,1) clamped/loaded": (0.0, 1.0),
           "(1,0) contact/free": (1.0, 0.0), "(1,1) loaded/free": (1.0, 1.0)}
RADIUS = 0.25


def region_indicators(level):
    """DG0 indicator of each region on a level's mesh (by cell midpoint)."""
    msh = level.fields.mesh
    Q = functionspace(msh, ("DG", 0))
    mid = Q.tabulate_dof_coordinates()[:, :2]
    near = {name: np.hypot(*(mid - c).T) < RADIUS for name, c in CORNERS.items()}
    near["rest"] = ~np.logical_or.reduce(list(near.values()))
    out = {}
    for name, mask in near.items():
        out[name] = fem.Function(Q)
        out[name].x.array[:] = mask.astype(float)
    return out


def regional_errors(coarse, fine, transfer):
    """H1 errors of u and phi at t = 1 restricted to each region (against
    the finer run), to see where the error of the successive levels lives."""
    weights = region_indicators(fine)
    j = coarse.n
    pairs = {name: (transfer(coarse.field(j, name), name), fine.field(fine.n, name))
             for name in ("u", "phi")}
    return {region: {name: h1_error(*pairs[name], weight=w) for name in pairs}
            for region, w in weights.items()}


def max_error(coarse, fine, transfer):
    """max over the coarse time steps of the H1 errors of u and phi (and of
    their sum) against the finer run at the same times."""
    ratio = fine.n // coarse.n
    worst = {"u": 0.0, "phi": 0.0, "sum": 0.0}
    for j in range(1, coarse.n + 1):
        e = {name: h1_error(transfer(coarse.field(j, name), name), fine.field(j * ratio, name))
             for name in ("u", "phi")}
        worst = {"u": max(worst["u"], e["u"]), "phi": max(worst["phi"], e["phi"]),
                 "sum": max(worst["sum"], e["u"] + e["phi"])}
    return worst


def rates(errors):
    return runs.observed_rates([2.0 ** -i for i in range(len(errors))], errors)


def fmt(r):
    return "" if r is None else f"{r:.2f}"


def main():
    ap = argparse.ArgumentParser(description="The paper's Figure 3 on example 1")
    ap.add_argument("--finest", type=int, default=128, help="finest 1/h = 1/k (power of 2)")
    ap.add_argument("--solver", choices=["cpp", "cpp-jit", "reference"], default="cpp")
    ap.add_argument("--output", default=str(ROOT / "out" / "convergence"))
    ap.add_argument("--build", default=os.environ.get("PIEZO_BUILD", str(ROOT / "build")))
    args = ap.parse_args()
    if args.finest < 4 or args.finest & (args.finest - 1):
        ap.error(f"--finest {args.finest}: must be a power of 2, at least 4")
    ns = [2 ** i for i in range(1, int(math.log2(args.finest)) + 1)]
    t0 = time.perf_counter()
    levels, dofs = {}, {}
    for n in ns:
        summary, wall = solve(args.solver, n, Path(args.output) / f"n{n}", args.build)
        levels[n] = Level(Path(args.output) / f"n{n}", summary)
        dofs[n] = summary["dofs"]
        print(f"solved h = k = 1/{n}: {summary['dofs']} dofs, {wall:.1f} s", flush=True)
    solve_s = time.perf_counter() - t0

    ref = levels[ns[-1]]
    paper = {n: max_error(levels[n], ref, Transfer(levels[n], ref)) for n in ns[:-1]}
    successive = {n: max_error(levels[n], levels[2 * n], Transfer(levels[n], levels[2 * n]))
                  for n in ns[:-1]}
    coarse = ns[:-1]
    r_sum = rates([paper[n]["sum"] for n in coarse])
    r_u = rates([paper[n]["u"] for n in coarse])
    r_phi = rates([paper[n]["phi"] for n in coarse])
    r_succ = rates([successive[n]["sum"] for n in coarse])
    lines = [f"Example 1, {args.solver} solver, reference h = k = 1/{ns[-1]} "
             f"({dofs[ns[-1]]} dofs); errors in H1, max over time steps", "",
             "| h = k | dofs | error u+phi vs ref | rate | error u (m) | rate | "
             "error phi (V) | rate | n vs 2n (u+phi) | rate |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for i, n in enumerate(coarse):
        p, s = paper[n], successive[n]
        lines.append(f"| 1/{n} | {dofs[n]} | {p['sum']:.3e} | {fmt(r_sum[i])} | {p['u']:.3e} "
                     f"| {fmt(r_u[i])} | {p['phi']:.3e} | {fmt(r_phi[i])} | {s['sum']:.3e} "
                     f"| {fmt(r_succ[i])} |")
    regional = {n: regional_errors(levels[n], levels[2 * n], Transfer(levels[n], levels[2 * n]))
                for n in coarse}
    regions = list(regional[coarse[0]])
    for name, unit in (("phi", "V"), ("u", "m")):
        lines += ["", f"Where the error lives: H1 error of {name} ({unit}) at t = 1, n vs 2n, "
                  f"in discs of radius {RADIUS} around each corner and in the rest (rate)", "",
                  "| h = k | " + " | ".join(regions) + " |", "|---|" + "---|" * len(regions)]
        r_region = {r: rates([regional[n][r][name] for n in coarse]) for r in regions}
        for i, n in enumerate(coarse):
            lines.append(f"| 1/{n} | " + " | ".join(
                f"{regional[n][r][name]:.2e} ({fmt(r_region[r][i]) or '-'})" for r in regions)
                + " |")
    total = time.perf_counter() - t0
    lines.append(f"\nsolves {solve_s:.1f} s, whole study {total:.1f} s")
    print("\n".join(lines))

    fig, ax = plt.subplots(figsize=(6, 4.5))
    h = np.array([1 / n for n in coarse])
    ax.loglog(h, [paper[n]["sum"] for n in coarse], "o-", label="u + phi vs finest run")
    ax.loglog(h, [successive[n]["sum"] for n in coarse], "s--", label="u + phi, n vs 2n")
    guide = paper[coarse[-1]]["sum"] * h / h[-1]
    ax.loglog(h, guide, "k:", label="slope 1")
    ax.set_xlabel("h = k")
    ax.set_ylabel("max_n H1 error")
    ax.set_title(f"Example 1: reference h = k = 1/{ns[-1]}", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    png = Path(args.output) / "figure3.png"
    fig.savefig(png, dpi=130)
    (Path(args.output) / "table.md").write_text("\n".join(lines) + "\n")
    print(f"plot: {png}, table: {Path(args.output) / 'table.md'}")


if __name__ == "__main__":
    main()
