#!/usr/bin/python3
# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # A thin plate in plane stress: a piezoelectric bending sensor
#
# A square PZT-5H plate (1 m x 1 m in its plane, thin in z), poled along y,
# with electrodes on its edges y = 0 and y = 1 (both grounded), is clamped
# on x = 0 and pulled and bent in its plane on x = 1: a traction that
# varies linearly across the end, `"traction": ["5e5 - 1e6*(2*y - 1)",
# 0.0]` (a mean pull of 0.5 MPa and a moment), an expression of the
# coordinates (muparser), ramped in 0.2 s. The pull stretches the plate
# along x, and through e31 a charge flows through the grounded electrodes
# (the moment alone would give none: its stretch and squeeze cancel).
#
# A thin plate has free faces: the stresses out of its plane vanish, and
# `"formulation": "plane_stress"` condenses them out of the 3D law (the
# preset's reduced moduli, coupling and permittivity:
# docs/formulations.md). The demo checks what that means: it solves the
# same plate in 3D for thinner and thinner plates (a box mesh, one layer of
# quadratic tetrahedra through the thickness) and shows their tip
# deflection and charge (per unit thickness) tending to the plane-stress
# answer, and not to the plane-strain one (a thick body's).
#
# Pictures: the deformed plate coloured by the potential, and the 3D
# plates against the two 2D formulations (DIR/figures/*.png).
#
#     /usr/bin/python3 demos/demo_plate.py [--thicknesses 0.2 0.1 0.05 0.025]

import argparse
import json
import os
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402
from piezocontact import compare  # noqa: E402
from piezodemos import runs  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


# ## The same plate in 3D
#
# Half of a plate of thickness t: the box [0, 1] x [0, 1] x [0, t/2], its
# face z = 0 the mid-plane (a symmetry plane: u_z = 0), its face z = t/2
# free; the plate's edges as in 2D: the clamp holds u_x and u_y (the
# thickness is free to change there, as plane stress assumes), the pull
# and moment, the electrodes. The probes sit on the mid-plane, and the
# charge is per unit thickness (twice the half's, over t), as in 2D.

def plate_3d(plate, t, n):
    cfg = json.loads(json.dumps(plate))
    del cfg["formulation"]
    cfg["mesh"] = {"type": "box", "n": [n, n, 1], "size": [1.0, 1.0, t / 2]}
    cfg["material"]["poling"] = [0, 1, 0]
    b = cfg["boundaries"]
    b["left"]["displacement"] = [0.0, 0.0, None]
    b["back"] = {"displacement": [None, None, 0.0]}
    b["right"]["traction"]["value"] = b["right"]["traction"]["value"] + [0.0]
    cfg["probes"] = [p + [0.0] for p in cfg["probes"]]
    return cfg


def answer(summary, thickness=1.0):
    """Tip deflection (m) and the top electrode's charge per unit thickness (C/m)."""
    last = summary["steps"][-1]
    return {"tip u_y": last["probes"][0]["u"][1],
            "charge": last["electrodes"]["top"]["reaction_charge"] / thickness}


def run_one(config, out, build, overrides=()):
    path = Path(str(out) + ".json")
    path.write_text(json.dumps(config))
    return runs.run_quietly("cpp", path, out, ["output.xdmf=false", *overrides], build)[0]


def draw_plate(out_dir, summary, path):
    msh = compare.FieldComparer(summary["config"], summary.get("mesh_file")).mesh
    x = msh.geometry.x[:, :2]
    n = len(summary["steps"])
    rows = {name: np.load(Path(out_dir) / "nodal" / f"{name}_{n:04d}.npy")
            for name in ("u", "phi")}
    at = {name: {tuple(np.round(r[:2], 12)): r[2:] for r in v} for name, v in rows.items()}
    u = np.array([at["u"][tuple(np.round(p, 12))] for p in x])
    phi = np.array([at["phi"][tuple(np.round(p, 12))][0] for p in x])
    dofmap = msh.geometry.dofmap
    cells = (dofmap if isinstance(dofmap, np.ndarray) else dofmap.array).reshape(-1, 3)
    amplification = 10 ** round(np.log10(0.1 / np.abs(u).max()))
    xd = x + amplification * u
    fig, ax = plt.subplots(figsize=(5.5, 4.5))
    ax.triplot(Triangulation(x[:, 0], x[:, 1], cells), color="0.85", lw=0.3)
    tpc = ax.tripcolor(Triangulation(xd[:, 0], xd[:, 1], cells), phi, shading="gouraud",
                       cmap="coolwarm")
    fig.colorbar(tpc, ax=ax, label="phi (V)")
    ax.set(xlabel="x (m)", ylabel="y (m), the poling", aspect="equal",
           title=f"plane stress, displacement x {amplification:g}")
    fig.savefig(path, dpi=130, bbox_inches="tight")
    plt.close(fig)


def draw_thickness(thicknesses, plates, stress, strain, path):
    """How far each 3D plate is from plane stress, against its thickness;
    plane strain's distance for scale."""
    fig, ax = plt.subplots(figsize=(6, 3.8))
    for i, name in enumerate(("tip u_y", "charge")):
        ax.loglog(thicknesses, [abs(p[name] / stress[name] - 1) for p in plates], "o-",
                  color=f"C{i}", label=f"3D plate: {name}")
        ax.axhline(abs(strain[name] / stress[name] - 1), color=f"C{i}", ls="--",
                   label=f"plane strain: {name}")
    ax.set(xlabel="plate thickness t (m), in-plane size 1 m",
           ylabel="relative difference to plane stress")
    ax.xaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xticks(thicknesses)
    ax.legend(fontsize=8)
    fig.savefig(path, dpi=130, bbox_inches="tight")
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--output", default=str(ROOT / "out" / "plate"))
    ap.add_argument("--build", default=os.environ.get("PIEZO_BUILD", str(ROOT / "build")))
    ap.add_argument("--set", action="append", default=[], metavar="KEY.PATH=VALUE")
    ap.add_argument("--thicknesses", type=float, nargs="+", default=[0.2, 0.1, 0.05, 0.025])
    args = ap.parse_args()
    out = Path(args.output)

    # ## Plane stress, by both engines
    summaries = runs.run_both(HERE / "plate.json", out, args.set, args.build)
    largest_field, of_size, by_value = runs.report(summaries, out)
    stress = answer(summaries["cpp"])

    # ## The thick-body formulation, and the 3D plates
    plate = json.loads((HERE / "plate.json").read_text())
    n = summaries["cpp"]["config"]["mesh"]["n"]  # the in-plane mesh, --set included
    strain = answer(run_one(dict(plate, formulation="plane_strain"), out / "plane_strain",
                            args.build, args.set))
    plates = [answer(run_one(plate_3d(plate, t, n), out / f"plate_{t:g}", args.build), t / 2)
              for t in args.thicknesses]
    print(f"\n{'':22s} {'tip u_y (m)':>14s} {'charge (C/m)':>14s}  off plane stress")
    rows = [("plane stress", stress), ("plane strain", strain)] + [
        (f"3D, t = {t:g} m", p) for t, p in zip(args.thicknesses, plates)]
    for label, a in rows:
        off = max(abs(a[k] / stress[k] - 1) for k in a)
        print(f"{label:22s} {a['tip u_y']:14.6e} {a['charge']:14.6e}  {100 * off:.2f} %")

    figures = out / "figures"
    figures.mkdir(parents=True, exist_ok=True)
    draw_plate(out / "cpp", summaries["cpp"], figures / "plate_phi.png")
    draw_thickness(args.thicknesses, plates, stress, strain, figures / "plate_thickness.png")
    print(f"figures in {figures}")

    # the demo's promises: the engines agree; the thinnest plate is plane
    # stress to 0.1 %, and the formulation matters (plane strain is not)
    thinnest = max(abs(plates[-1][k] / stress[k] - 1) for k in stress)
    strain_off = max(abs(strain[k] / stress[k] - 1) for k in stress)
    if not runs.verdict(max(largest_field, of_size), by_value) or thinnest > 0.001 \
            or strain_off < 0.05:
        sys.exit(1)


if __name__ == "__main__":
    main()
