#!/usr/bin/python3
"""The disc transducer of demos/disc.json (PZT-5H, R = 10 mm, T = 2 mm,
bottom clamped and grounded, 100 V on top) in the axisymmetric formulation
and in 3D (a quarter of the cylinder, symmetry planes on rollers, meshed in
layers: meshes/disc_quarter_msh.py), both at degree 2, on finer and finer
meshes: the top's centre and edge displacements and the top electrode's
charge (its reaction, per full disc) converge together.

    /usr/bin/python3 benchmarks/disc_axisymmetric_vs_3d.py [--sizes-2d 0.5 0.25 0.125]
        [--sizes-3d 1.0 0.7 0.5]   (mm)
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def three_d_config(axi, msh):
    """The 3D quarter model of the axisymmetric config: the same material
    (poling along y in the 3D frame), the same electrodes and clamp, the
    symmetry planes x = 0 and z = 0 on rollers."""
    cfg = json.loads(json.dumps(axi))
    del cfg["formulation"]
    cfg["mesh"] = {"type": "msh", "path": str(msh)}
    cfg["material"]["poling"] = [0, 1, 0]
    b = cfg["boundaries"]
    b["bottom"]["displacement"] = [0.0, 0.0, 0.0]
    b["sym_x"] = {"displacement": [0.0, None, None]}
    b["sym_z"] = {"displacement": [None, None, 0.0]}
    cfg["probes"] = [p + [0.0] for p in cfg["probes"]]
    return cfg


def quantities(summary, copies):
    """Top centre u_y, top edge u_r, u_y (nm) and the top electrode's
    charge (its reaction, nC, per full disc)."""
    last = summary["steps"][-1]
    centre, _, edge = last["probes"][:3]
    return {"centre u_y": 1e9 * centre["u"][1], "edge u_r": 1e9 * edge["u"][0],
            "edge u_y": 1e9 * edge["u"][1],
            "charge": 1e9 * copies * last["electrodes"]["top"]["reaction_charge"]}


def run(config, out, build):
    path = Path(out).with_suffix(".json")
    path.write_text(json.dumps(config))
    subprocess.run([str(Path(build) / "piezo-contact"), "--config", str(path), "--output",
                    str(out), "--quiet", "--set", "output.xdmf=false", "--set",
                    "output.nodal=none"], check=True, env=ENV)
    return json.loads((Path(out) / "summary.json").read_text())


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes-2d", type=float, nargs="+", default=[0.5, 0.25, 0.125])
    ap.add_argument("--sizes-3d", type=float, nargs="+", default=[1.0, 0.7, 0.5])
    ap.add_argument("--build", default=os.environ.get("PIEZO_BUILD", str(ROOT / "build")))
    args = ap.parse_args()
    axi = json.loads((ROOT / "demos" / "disc.json").read_text())
    axi["mesh"]["geometry"] = str(ROOT / "meshes" / "disc.py")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for h in args.sizes_2d:
            cfg = json.loads(json.dumps(axi))
            cfg["mesh"]["size"] = h * 1e-3
            s = run(cfg, Path(tmp) / f"axi{h}", args.build)
            rows.append((f"axisymmetric h = {h:g} mm", s["dofs"], quantities(s, 1)))
        for h in args.sizes_3d:
            msh = Path(tmp) / f"quarter{h}.msh"
            subprocess.run([sys.executable, str(ROOT / "meshes" / "disc_quarter_msh.py"),
                            "--size", str(h * 1e-3), "--output", str(msh)], check=True,
                           capture_output=True)
            s = run(three_d_config(axi, msh), Path(tmp) / f"q{h}", args.build)
            rows.append((f"3D quarter h = {h:g} mm", s["dofs"], quantities(s, 4)))
    names = list(rows[0][2])
    print("| model | dofs | " + " | ".join(names) + " |")
    print("|---|---:|" + "---:|" * len(names))
    for label, dofs, q in rows:
        print(f"| {label} | {dofs} | " + " | ".join(f"{q[n]:.5g}" for n in names) + " |")
    best = rows[len(args.sizes_2d) - 1][2]
    print(f"\nrelative to the finest axisymmetric run:")
    for label, _, q in rows:
        print(f"  {label:26s} " + "  ".join(f"{n} {abs(q[n] / best[n] - 1):.1e}" for n in names))


if __name__ == "__main__":
    main()
