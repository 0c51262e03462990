#!/usr/bin/python3
# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # A disc transducer, axisymmetric: two electrodes on a clamped PZT disc
#
# The most common piezoelectric transducer is a disc poled through its
# thickness with an electrode on each face. Here a PZT-5H disc (radius
# 10 mm, thickness 2 mm) is bonded on a rigid backing (its bottom face
# clamped and grounded) and its top electrode is driven to 100 V in 0.2 s.
# The field points against the poling: the disc gets thinner and, through
# d31, wider; the clamp holds the bottom, so the top edge bulges out.
#
# The disc is a body of revolution with a field that is too:
# `"formulation": "axisymmetric"` solves it on its half-section, the
# rectangle 0 <= r <= R, 0 <= y <= T (x = r, y the axis, z the hoop
# direction of the 3D frame). The preset's poling [0, 1] is along the axis;
# the core reduces the 3D tensors to the strains (rr, yy, hoop, ry); the
# hoop strain u_r / r and the weight 2 pi r enter every term (forms/), and
# u_r = 0 on the axis is the formulation's own condition. Charges, forces
# and currents are per full revolution: the charge is the disc's.
#
# The demo runs the executable and the reference engine and compares them,
# then solves the same disc in 3D (a quarter of the cylinder, its symmetry
# planes on rollers, `meshes/disc_quarter_msh.py`) and compares the
# displacements of the top and the charge: the two models are one problem
# and must agree to their discretisation error (1 % here; the convergence
# table is `benchmarks/disc_axisymmetric_vs_3d.py`, in docs/verification.md).
# Pictures: the deformed section coloured by the potential, and the top
# surface of both models (DIR/figures/*.png).
#
#     /usr/bin/python3 demos/demo_disc.py [--set mesh.size=0.25e-3]

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402
from piezocontact import compare  # noqa: E402
from piezodemos import runs  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT / "benchmarks"))
from disc_axisymmetric_vs_3d import quantities, three_d_config  # noqa: E402


# ## The state at the end, at the nodes
#
# The nodal files hold every node of the fields' spaces (at degree 2 the
# vertices and the edge midpoints) as [x, y, values...] in 2D, [x, y, z,
# values...] in 3D.

def nodal(out_dir, summary, name):
    n = len(summary["steps"])
    return np.load(Path(out_dir) / "nodal" / f"{name}_{n:04d}.npy")


def section(out_dir, summary, path):
    """The half-section, displaced (amplified) and coloured by phi."""
    msh = compare.FieldComparer(summary["config"], summary.get("mesh_file")).mesh
    x = msh.geometry.x[:, :2]
    at = {tuple(np.round(r[:2], 12)): r for r in nodal(out_dir, summary, "u")}
    u = np.array([at[tuple(np.round(p, 12))][2:4] for p in x])
    phi_rows = {tuple(np.round(r[:2], 12)): r[2] for r in nodal(out_dir, summary, "phi")}
    phi = np.array([phi_rows[tuple(np.round(p, 12))] for p in x])
    cells = msh.geometry.dofmap.reshape(-1, 3) if hasattr(msh.geometry.dofmap, "reshape") \
        else msh.geometry.dofmap.array.reshape(-1, 3)
    amplification = 10 ** round(np.log10(0.1 * 2e-3 / np.abs(u).max()))
    xd = 1e3 * (x + amplification * u)
    fig, ax = plt.subplots(figsize=(9, 3))
    ax.triplot(Triangulation(1e3 * x[:, 0], 1e3 * x[:, 1], cells), color="0.8", lw=0.3)
    tpc = ax.tripcolor(Triangulation(xd[:, 0], xd[:, 1], cells), phi, shading="gouraud")
    fig.colorbar(tpc, ax=ax, label="phi (V)")
    ax.set(xlabel="r (mm)", ylabel="y (mm), the axis", aspect="equal",
           title=f"half-section, displacement x {amplification:g} (grey: undeformed)")
    fig.savefig(path, dpi=130, bbox_inches="tight")
    plt.close(fig)


def top_surface(axi_dir, axi, q_dir, quarter, path):
    """u_r and u_y along the top, r from 0 to R: the axisymmetric section's
    nodes and the 3D model's nodes on the top face in the plane z = 0."""
    fig, ax = plt.subplots(figsize=(6.5, 3.5))
    T = 2e-3
    for label, d, s, style, dim in (("axisymmetric", axi_dir, axi, "-", 2),
                                    ("3D quarter", q_dir, quarter, "o", 3)):
        rows = nodal(d, s, "u")
        on_top = np.isclose(rows[:, 1], T) & (dim == 2 or np.isclose(rows[:, 2], 0.0))
        rows = rows[on_top][np.argsort(rows[on_top][:, 0])]
        ax.plot(1e3 * rows[:, 0], 1e9 * rows[:, dim], style, color="C0", ms=3,
                label=f"u_r, {label}")
        ax.plot(1e3 * rows[:, 0], 1e9 * rows[:, dim + 1], style, color="C1", ms=3,
                label=f"u_y, {label}")
    ax.set(xlabel="r (mm)", ylabel="displacement of the top (nm)")
    ax.legend(fontsize=8)
    fig.savefig(path, dpi=130, bbox_inches="tight")
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--output", default=str(ROOT / "out" / "disc"))
    ap.add_argument("--build", default=os.environ.get("PIEZO_BUILD", str(ROOT / "build")))
    ap.add_argument("--set", action="append", default=[], metavar="KEY.PATH=VALUE")
    ap.add_argument("--size-3d", type=float, default=1e-3, help="the 3D mesh's size (m)")
    args = ap.parse_args()
    out = Path(args.output)

    # ## The two engines on the axisymmetric disc
    summaries = runs.run_both(HERE / "disc.json", out, args.set, args.build)
    largest_field, of_size, by_value = runs.report(summaries, out)
    axi = summaries["cpp"]
    last = axi["steps"][-1]
    V = last["electrodes"]["top"]["potential"]
    Q = last["electrodes"]["top"]["reaction_charge"]
    print(f"\ntop electrode at {V:g} V: charge {Q:.4e} C (the whole disc), "
          f"capacitance {Q / V * 1e12:.1f} pF; top centre moves {last['probes'][0]['u'][1]:.3e} m, "
          f"the top edge {last['probes'][2]['u'][0]:.3e} m outwards")

    # ## The same disc in 3D
    #
    # A quarter of the cylinder, the same config but for the mesh, the
    # 3D poling [0, 1, 0] and the rollers of the symmetry planes; its
    # charge is a quarter of the disc's.
    mesh_3d = out / "quarter.msh"
    subprocess.run([sys.executable, str(ROOT / "meshes" / "disc_quarter_msh.py"), "--size",
                    str(args.size_3d), "--output", str(mesh_3d)], check=True, capture_output=True)
    cfg = json.loads((HERE / "disc.json").read_text())
    quarter_cfg = out / "quarter.json"
    quarter_cfg.write_text(json.dumps(three_d_config(cfg, mesh_3d)))
    quarter = runs.run_both(quarter_cfg, out / "quarter", [], args.build,
                            engines=("cpp",))["cpp"]
    a, b = quantities(axi, 1), quantities(quarter, 4)
    print(f"\n{'':12s} {'axisymmetric':>14s} {'3D quarter':>14s}  difference")
    worst = 0.0
    for name in a:
        diff = abs(b[name] / a[name] - 1)
        worst = max(worst, diff)
        print(f"{name:12s} {a[name]:14.6g} {b[name]:14.6g}  {100 * diff:.2f} %")
    print(f"({axi['dofs']} dofs axisymmetric, {quarter['dofs']} in 3D; units nm and nC)")

    figures = out / "figures"
    figures.mkdir(parents=True, exist_ok=True)
    section(out / "cpp", axi, figures / "disc_section_phi.png")
    top_surface(out / "cpp", axi, out / "quarter" / "cpp", quarter, figures / "disc_top.png")
    print(f"figures in {figures}")
    # the demo's promises: the engines agree, and 3D says what the section says
    if not runs.verdict(max(largest_field, of_size), by_value) or worst > 0.01:
        sys.exit(1)


if __name__ == "__main__":
    main()
