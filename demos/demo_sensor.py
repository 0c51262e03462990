#!/usr/bin/python3
# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # A contactor that senses: a cyclic drive, a floating electrode, hysteresis
#
# The contactor of example 2 (the paper's section 4.3), clamped on [P4, P5],
# its lower edge 10 pm above a normal-compliance foundation, is driven by a
# sine voltage of 20 V amplitude and 0.5 Hz on `electrode_high`;
# `electrode_ground` holds 0 V. A third electrode, `sensor`, on half of the
# upper free side, is connected to nothing: its potential is one unknown,
# uniform over it, and the charge on it is zero (an open circuit, an ideal
# voltmeter). Its config is `demos/sensor.json`: the key is
# `"sensor": {"floating": {}}`, the drive a `potential` with a `sine` history.
#
# In the positive half-cycles the body leans onto the foundation; in the
# negative ones it lifts off. The material creeps with a relaxation time of
# 0.1 s, so displacements, contact force and the part of the sensed voltage
# that comes from strain lag the drive. A second run with the viscosity
# divided by 1000 (relaxation time 0.1 ms, much shorter than the step)
# shows what the lag is due to.
#
# The demo runs the executable and the reference engine (which imposes the
# floating electrode its own way, by a multi-point constraint), checks that
# they agree, and draws (DIR/figures/): the histories of the applied and
# sensed voltages, of the contact force and the contact length; the loops
# these make against the applied voltage, with and without viscosity; the
# contact pressure along Gamma_C at a few times.
#
#     /usr/bin/python3 demos/demo_sensor.py [--set time.steps=80]

import argparse
import json
import os
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from piezodemos import runs  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT / "meshes"))
from contactor import POINTS  # noqa: E402


# ## The quantities of each step
#
# Everything is in `summary.json`: each step's `electrodes` (potential,
# charge both ways, current), `contact_force` and `contact_length`. The
# force is a resultant of magnitude |F|; the contact edge [P1, P2] has
# length sqrt(2).

def series(summary):
    steps = summary["steps"]
    electrodes = [s["electrodes"] for s in steps]
    return {"t": np.array([s["t"] for s in steps]),
            "applied": np.array([e["electrode_high"]["potential"] for e in electrodes]),
            "sensed": np.array([e["sensor"]["potential"] for e in electrodes]),
            "sensor_charge": np.array([e["sensor"]["reaction_charge"] for e in electrodes]),
            "force": np.array([np.hypot(*s["contact_force"]) for s in steps]),
            "length": np.array([s["contact_length"] for s in steps])}


def histories(s, path):
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 5.5), sharex=True)
    ax1.plot(s["t"], s["applied"], label="applied (electrode_high)")
    ax1.plot(s["t"], 5 * s["sensed"], label="sensed x 5 (floating sensor)")
    ax1.set_ylabel("potential (V)")
    ax1.legend(loc="lower left", fontsize=8)
    ax2.plot(s["t"], s["force"], color="C2", label="|contact force| (N/m)")
    ax2.set_ylabel("force (N/m)")
    ax2.set_xlabel("t (s)")
    ax3 = ax2.twinx()
    ax3.plot(s["t"], s["length"], color="C3", ls="--", label="contact length (m)")
    ax3.set_ylabel("contact length (m)")
    ax2.legend(loc="upper left", fontsize=8)
    ax3.legend(loc="upper right", fontsize=8)
    fig.savefig(path, dpi=130, bbox_inches="tight")
    plt.close(fig)


# ## The loops
#
# Plotted against the applied voltage, over the last cycle, a quantity
# that follows the drive instantly traces a curve; one that lags traces a
# loop whose area is the energy the viscosity dissipates per cycle. The thin
# lines are the nearly inviscid run.

def loops(s, fast, path):
    last = s["t"] > s["t"][-1] - 2.0 + 1e-9  # the last period
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    for run, style, label in ((s, "-", "relaxation time 0.1 s"),
                              (fast, ":", "relaxation time 0.1 ms")):
        ax1.plot(run["applied"][last], run["sensed"][last], style, label=label)
        ax2.plot(run["applied"][last], run["force"][last], style, label=label)
    ax1.set(xlabel="applied potential (V)", ylabel="sensed potential (V)")
    ax2.set(xlabel="applied potential (V)", ylabel="|contact force| (N/m)")
    ax1.legend(fontsize=8)
    ax2.legend(fontsize=8)
    fig.savefig(path, dpi=130, bbox_inches="tight")
    plt.close(fig)


def loop_area(x, y):
    """The area a closed curve encloses (shoelace, the last period)."""
    return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


# ## The contact pressure along Gamma_C
#
# `nodal/contact_pressure_NNNN.npy` holds the lumped pressure at every
# vertex (zero off Gamma_C), with its coordinates: the vertices of the edge
# [P1, P2] are plotted against their distance from P1.

def pressure_profiles(out_dir, s, path, count=4):
    p1, p2 = np.array(POINTS[0]), np.array(POINTS[1])
    along = (p2 - p1) / np.linalg.norm(p2 - p1)
    normal = np.array([-along[1], along[0]])
    touching = np.flatnonzero(s["force"] > 0)
    chosen = touching[np.linspace(0, touching.size - 1, count).astype(int)] if touching.size else []
    fig, ax = plt.subplots(figsize=(6, 3.5))
    for n in chosen:
        nodal = np.load(Path(out_dir) / "nodal" / f"contact_pressure_{n + 1:04d}.npy")
        rel = nodal[:, :2] - p1
        on_edge = np.abs(rel @ normal) < 1e-9
        d = rel[on_edge] @ along
        order = np.argsort(d)
        ax.plot(d[order], nodal[on_edge, 2][order], ".-", label=f"t = {s['t'][n]:.3g} s")
    ax.set(xlabel="distance from P1 along Gamma_C (m)", ylabel="contact pressure (Pa)")
    ax.legend(fontsize=8)
    fig.savefig(path, dpi=130, bbox_inches="tight")
    plt.close(fig)


def nearly_inviscid(out):
    """sensor.json with the viscosity divided by 1000."""
    cfg = json.loads((HERE / "sensor.json").read_text())
    cfg["mesh"]["geometry"] = str(ROOT / "meshes" / "contactor_sensor.py")
    cfg["material"]["viscosity"] = (np.array(cfg["material"]["viscosity"]) / 1000).tolist()
    path = Path(out) / "sensor_fast.json"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(cfg))
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--output", default=str(ROOT / "out" / "sensor"))
    ap.add_argument("--build", default=os.environ.get("PIEZO_BUILD", str(ROOT / "build")))
    ap.add_argument("--set", action="append", default=[], metavar="KEY.PATH=VALUE")
    args = ap.parse_args()
    out = Path(args.output)
    overrides = ["output.nodal=all", "output.xdmf=false"] + args.set
    summaries = runs.run_both(HERE / "sensor.json", out, overrides, args.build)
    largest_field, of_size, by_value = runs.report(summaries, out)
    cpp, ref = (series(summaries[k]) for k in ("cpp", "reference"))
    electrodes = max(np.max(np.abs(cpp[k] - ref[k])) / np.max(np.abs(ref[k]))
                     for k in ("sensed", "force", "length"))
    print(f"sensed potential, contact force and length: largest difference between the "
          f"engines {electrodes:.1e} of their largest values")
    fast = series(runs.run_quietly("cpp", nearly_inviscid(out), out / "fast", args.set,
                                   args.build)[0])

    # ## What a user learns
    last = cpp["t"] > cpp["t"][-1] - 2.0 + 1e-9
    ratio = np.max(np.abs(cpp["sensed"][last])) / np.max(np.abs(cpp["applied"][last]))
    print(f"\nthe sensor reads {ratio:.3f} of the drive; its charge stays "
          f"{np.max(np.abs(cpp['sensor_charge'])):.1e} C/m (open circuit)")
    high, low = cpp["sensed"][last].max(), cpp["sensed"][last].min()
    print(f"sensed peaks {high:.3f} V (touching) and {low:.3f} V (free): "
          f"{1 - high / -low:.1%} lower where it touches")
    touching = cpp["force"][last] > 0
    print(f"contact in {touching.mean():.0%} of the last cycle, force up to "
          f"{cpp['force'].max():.3g} N/m, contact length up to {cpp['length'].max():.3g} m "
          f"of {np.sqrt(2):.3g}")
    for name, run in (("0.1 s", cpp), ("0.1 ms", fast)):
        print(f"relaxation time {name}: loop areas over the last cycle: "
              f"sensed {loop_area(run['applied'][last], run['sensed'][last]):.3g} V^2, "
              f"force {loop_area(run['applied'][last], run['force'][last]):.3g} V N/m")

    figures = out / "figures"
    figures.mkdir(parents=True, exist_ok=True)
    histories(cpp, figures / "sensor_history.png")
    loops(cpp, fast, figures / "sensor_loops.png")
    pressure_profiles(out / "cpp", cpp, figures / "sensor_pressure.png")
    print(f"figures in {figures}")
    if not runs.verdict(max(largest_field, of_size, electrodes), by_value):
        sys.exit(1)


if __name__ == "__main__":
    main()
