#!/usr/bin/python3
# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # A 3D device in contact: a unimorph actuator bends onto a foundation
#
# A PZT-5H film (0.25 mm, poled through its thickness, +z) is bonded on an
# elastic substrate (0.5 mm), 10 mm long and 2 mm wide: a unimorph. It is
# clamped at x = 0. The film's top electrode holds 200 V, the film/substrate
# interface (an interior face) is grounded. The field through the film makes
# it expand in-plane (d31 < 0 with E against the poling); the substrate does
# not, so the beam bends down, and 2 um below its free end waits a stiff
# normal-compliance foundation (c_p = 1e13 N/m^3). The film creeps with a
# relaxation time of 0.1 s, so the beam keeps sinking into the foundation.
#
# Everything comes from one config, `demos/unimorph.json`: the mesh is the
# user's own gmsh file (`demos/unimorph.msh`, written by
# `meshes/unimorph_msh.py`; its physical groups name the two volumes and the
# four faces), the film's tensors come from a preset and its poling
# direction, the substrate's are given explicitly (3D Voigt shapes), and the
# summary records the tensors that were solved with, in the mesh frame.
#
# The demo runs the executable and the reference engine, compares them,
# and draws the deformed body coloured by the potential and by the vertical
# displacement, and the history of the tip and the contact force
# (DIR/figures/*.png). XDMF output for ParaView is in DIR/cpp/solution.xdmf.
#
#     /usr/bin/python3 demos/demo_unimorph.py [--set time.steps=20]

import argparse
import os
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402
from piezocontact import _compat as compat  # noqa: E402
from piezocontact import compare  # noqa: E402
from piezodemos import runs  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


# ## The deformed body
#
# The exterior triangles of the mesh, moved by the displacement (amplified:
# it is a few micrometres on a 10 mm beam), coloured by a nodal field; the
# foundation is the grey plane at z = -g.

def draw(state, values, label, amplification, gap, path, title):
    x = 1e3 * (state["x"] + amplification * state["u"])  # mm
    tris = compat.exterior_facet_geometry(state["mesh"])  # vertex indices (geometry nodes)
    colours = values[tris].mean(axis=1)
    fig = plt.figure(figsize=(9, 4.5))
    ax = fig.add_subplot(projection="3d")
    norm = matplotlib.colors.Normalize(colours.min(), colours.max())
    ax.add_collection3d(Poly3DCollection(x[tris], facecolors=plt.cm.viridis(norm(colours)),
                                         edgecolors="k", linewidths=0.05))
    L, W = 1e3 * state["x"][:, 0].max(), 1e3 * state["x"][:, 1].max()
    zf = -1e3 * amplification * gap
    ax.add_collection3d(Poly3DCollection([[(0, -0.5 * W, zf), (1.1 * L, -0.5 * W, zf),
                                           (1.1 * L, 1.5 * W, zf), (0, 1.5 * W, zf)]],
                                         facecolors="0.85", alpha=0.5))
    lo, hi = x.min(axis=0), x.max(axis=0)
    ax.set(xlim=(0, 1.1 * L), ylim=(-0.5 * W, 1.5 * W), zlim=(min(lo[2], zf), hi[2]),
           xlabel="x (mm)", ylabel="y (mm)", zlabel="z (mm)")
    ax.locator_params(nbins=4)
    ax.set_box_aspect((1.1 * L, 2 * W, hi[2] - min(lo[2], zf)))
    ax.view_init(elev=18, azim=-60)
    fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap="viridis"), ax=ax, shrink=0.6,
                 label=label)
    ax.set_title(f"{title} (displacement x {amplification:g})")
    fig.savefig(path, dpi=130, bbox_inches="tight")
    plt.close(fig)


def final_state(out_dir, summary):
    """The mesh and the nodal u, phi of the last step, as arrays on the
    geometry nodes (P1: the same points)."""
    fields = compare.FieldComparer(summary["config"], summary.get("mesh_file"))
    n = len(summary["steps"])
    u = fields.function(Path(out_dir) / "nodal" / f"u_{n:04d}.npy", "u")
    phi = fields.function(Path(out_dir) / "nodal" / f"phi_{n:04d}.npy", "phi")
    msh = fields.mesh
    # P1 dofs and geometry nodes follow the same cell-local order
    node_of_dof = np.empty(msh.geometry.x.shape[0], dtype=np.int64)
    cells = compat.geometry_dofmap(msh)
    node_of_dof[compat.dofmap_array(fields.V["phi"])] = cells
    order = np.argsort(node_of_dof)
    return {"mesh": msh, "x": msh.geometry.x,
            "u": u.x.array.reshape(-1, 3)[order], "phi": phi.x.array[order]}


def history(summary, path):
    t = [s["t"] for s in summary["steps"]]
    tip = [-s["probes"][0]["u"][2] * 1e6 for s in summary["steps"]]
    force = [s["contact_force"][2] for s in summary["steps"]]
    fig, ax = plt.subplots(figsize=(6, 3.5))
    ax.plot(t, tip, "o-", label="tip deflection (um, down)")
    ax.axhline(summary["config"]["contact"]["gap"] * 1e6, color="0.5", ls="--", label="gap")
    ax.set_xlabel("t (s)")
    ax2 = ax.twinx()
    ax2.plot(t, force, "s-", color="C1", label="contact force (N)")
    ax.legend(loc="center right")
    ax2.legend(loc="lower right")
    fig.savefig(path, dpi=130, bbox_inches="tight")
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--output", default=str(ROOT / "out" / "unimorph"))
    ap.add_argument("--build", default=os.environ.get("PIEZO_BUILD", str(ROOT / "build")))
    ap.add_argument("--set", action="append", default=[], metavar="KEY.PATH=VALUE")
    args = ap.parse_args()
    out = Path(args.output)
    summaries = runs.run_both(HERE / "unimorph.json", out, args.set, args.build)
    largest_field, of_size, by_value = runs.report(summaries, out)
    cpp = summaries["cpp"]

    # ## What the device does
    last = cpp["steps"][-1]
    gap = cpp["config"]["contact"]["gap"]
    film = cpp["config"]["regions"]["piezo"]
    print(f"\nfilm tensors solved with (mesh frame, from {film['resolved_from']}): "
          f"e[2] = {film['piezoelectric'][2]} C/m^2")
    print(f"tip at t = {cpp['steps'][0]['t']:g} s: {cpp['steps'][0]['probes'][0]['u'][2]:.3e} m, "
          f"at t = {last['t']:g} s: {last['probes'][0]['u'][2]:.3e} m (gap {gap:g} m); "
          f"the foundation pushes back with {last['contact_force'][2]:.4g} N, "
          f"largest u.nu - g {last['max_penetration']:.3e} m")

    figures = out / "figures"
    figures.mkdir(parents=True, exist_ok=True)
    state = final_state(out / "cpp", cpp)
    amplification = 10 ** round(np.log10(0.1 * 10e-3 / np.abs(state["u"]).max()))
    draw(state, state["phi"], "phi (V)", amplification, gap, figures / "unimorph_phi.png",
         f"potential at t = {last['t']:g} s")
    draw(state, state["u"][:, 2] * 1e6, "u_z (um)", amplification, gap,
         figures / "unimorph_uz.png", f"vertical displacement at t = {last['t']:g} s")
    history(cpp, figures / "unimorph_history.png")
    print(f"figures in {figures}")
    if not runs.verdict(max(largest_field, of_size), by_value):
        sys.exit(1)


if __name__ == "__main__":
    main()
