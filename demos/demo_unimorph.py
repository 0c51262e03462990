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
# A thin beam bends, and linear tetrahedra lock in bending: the config asks
# for quadratic elements (`"elements": {"degree": 2}`), one element through
# each layer. The demo states its own discretisation error: it runs the
# executable again on a mesh of 0.35 mm instead of 0.5 mm and compares the
# contact force and the tip.
#
# The demo runs the executable and the reference engine, compares them,
# and draws the deformed body coloured by the potential and by the vertical
# displacement, and the history of the tip and the contact force
# (DIR/figures/*.png). XDMF output for ParaView is in DIR/cpp/solution.xdmf
# (at degree 2: on the mesh refined once, whose vertices are the P2 nodes).
#
#     /usr/bin/python3 demos/demo_unimorph.py [--set time.steps=20]

import argparse
import os
import subprocess
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
    """The mesh and u, phi of the last step at its vertices (the nodal files
    hold every node of the fields' spaces, [x, y, z, values...]: at degree 2
    the vertices and the edge midpoints)."""
    msh = compare.FieldComparer(summary["config"], summary.get("mesh_file")).mesh
    x = msh.geometry.x
    n = len(summary["steps"])
    at = {}
    for name in ("u", "phi"):
        rows = np.load(Path(out_dir) / "nodal" / f"{name}_{n:04d}.npy")
        value = {tuple(np.round(r[:3], 12)): r[3:] for r in rows}
        at[name] = np.array([value[tuple(np.round(p, 12))] for p in x])
    return {"mesh": msh, "x": x, "u": at["u"], "phi": at["phi"][:, 0]}


# ## The discretisation error
#
# The same run on a finer mesh (0.35 mm, the mesh script of `meshes/`), by
# the executable: the differences of the contact force and the tip are the
# error of the demo's own mesh, to the accuracy the finer one has.

def finer_run(out, build, overrides):
    fine = out / "fine"
    fine.mkdir(parents=True, exist_ok=True)
    subprocess.run([sys.executable, str(ROOT / "meshes" / "unimorph_msh.py"), "--size", "0.35e-3",
                    "--output", str(fine / "unimorph_fine.msh")], check=True,
                   capture_output=True)
    return runs.run_both(HERE / "unimorph.json", fine, overrides
                         + [f"mesh.path={fine / 'unimorph_fine.msh'}", "output.xdmf=false"],
                         build, engines=("cpp",))["cpp"]


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

    fine = finer_run(out, args.build, args.set)["steps"][-1]
    force_error = abs(last["contact_force"][2] / fine["contact_force"][2] - 1)
    tip_error = abs(last["probes"][0]["u"][2] / fine["probes"][0]["u"][2] - 1)
    print(f"\ndiscretisation (degree {cpp['config']['elements']['degree']}): contact force "
          f"{last['contact_force'][2]:.4g} N here, {fine['contact_force'][2]:.4g} N on the finer "
          f"mesh ({100 * force_error:.2f} %); tip {100 * tip_error:.3f} %")
    # the demo's promise: the answer it prints is within 1 % of the finer mesh's
    if not runs.verdict(max(largest_field, of_size), by_value) or force_error > 0.01:
        sys.exit(1)


if __name__ == "__main__":
    main()
