#!/usr/bin/python3
"""The PVDF bimorph cantilever of Tzou & Tseng (1990) and Hwang & Park
(1993), the classical test of piezoelectric finite elements in bending: two
PVDF layers of thickness h = 0.5 mm, poled in opposite directions along the
thickness, length L = 100 mm (L/t = 100), clamped at x = 0, a potential V
across the total thickness t = 2h (electrodes on the top and bottom faces,
the series connection). Beam theory (Smits, Dalke & Cooney 1991, the series
bimorph) gives the tip deflection

    delta = 3/2 d31 V L^2 / t^2   (= 0.330 um at V = 1 V, d31 = 22 pC/N)

for a material with d31 alone; here in 2D plane strain with Poisson's ratio
0 (E = 2 GPa, G = E/2), where plane strain is the Euler-Bernoulli beam
exactly up to shear (O((t/L)^2) = 1e-4) and the electromechanical stiffening
of the field's variation through each layer (k31^2/4 = 0.2 %).

    /usr/bin/python3 benchmarks/bimorph.py [--degrees 1 2] [--nx 25 50 100 200 400]
        [--per-layer 1 2 4] [--engine cpp|python]

prints, per degree and mesh, the dofs, the tip deflection over beam theory,
the wall time and the peak memory of each run (a subprocess each).
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "meshes"))  # the gmsh helpers
L, H = 0.1, 0.5e-3          # length, thickness of one layer (m)
E, D31 = 2.0e9, 22e-12      # Young's modulus (Pa), d31 (C/N) of PVDF
EPS = 0.1062e-9             # permittivity (F/m)
VOLT = 1.0
THEORY = 1.5 * D31 * VOLT * L ** 2 / (2 * H) ** 2  # 3.3e-7 m


def write_mesh(path, nx, per_layer):
    """Two layers of nx x per_layer rectangles, each cut in two triangles:
    regions "upper" (y > 0), "lower"; boundaries clamp (x = 0), top, bottom."""
    import gmsh
    from physical_groups import name_groups
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    try:
        occ = gmsh.model.occ
        lower = occ.addRectangle(0, -H, 0, L, H)
        upper = occ.addRectangle(0, 0, 0, L, H)
        occ.fragment([(2, lower)], [(2, upper)])
        occ.synchronize()
        named = {"clamp": [], "top": [], "bottom": []}
        for _, curve in gmsh.model.getEntities(1):
            x0, y0, _, x1, y1, _ = gmsh.model.getBoundingBox(1, curve)
            vertical = x1 - x0 < 1e-5  # OCC boxes carry a tolerance
            gmsh.model.mesh.setTransfiniteCurve(curve, (per_layer if vertical else nx) + 1)
            if vertical and x1 < 1e-5:
                named["clamp"].append(curve)
            elif not vertical and y0 > H - 1e-5:
                named["top"].append(curve)
            elif not vertical and y1 < -H + 1e-5:
                named["bottom"].append(curve)
        for surface in (lower, upper):
            gmsh.model.mesh.setTransfiniteSurface(surface)
        name_groups(1, named)
        name_groups(2, {"lower": [lower], "upper": [upper]})
        gmsh.model.mesh.generate(2)
        gmsh.write(str(path))
    finally:
        gmsh.finalize()


def layer(sign):
    """PVDF with d31 alone, poled along +y (sign 1) or -y (-1): already
    reduced 2D tensors (Voigt xx, yy, xy; D rows x, y)."""
    return {"elastic": [[E, 0.0, 0.0], [0.0, E, 0.0], [0.0, 0.0, E / 2]],
            "relaxation_time": 1e-9,  # s: 1e-9 of the step, the elastic answer to 1e-9
            "piezoelectric": [[0.0, 0.0, 0.0], [sign * D31 * E, 0.0, 0.0]],
            "permittivity": [[EPS, 0.0], [0.0, EPS]]}


def config(msh, degree):
    """The run; `degree` an integer (u and phi) or {"u": k_u, "phi": k_phi}"""
    elements = degree if isinstance(degree, dict) else {"degree": degree}
    return {"mesh": {"type": "msh", "path": str(msh)},
            "regions": {"upper": layer(1.0), "lower": layer(-1.0)},
            "boundaries": {"clamp": {"displacement": [0.0, 0.0]},
                           "top": {"potential": VOLT}, "bottom": {"potential": 0.0}},
            "elements": elements,
            "time": {"T": 1.0, "steps": 1},
            "probes": [[L, 0.0]],
            "output": {"xdmf": False, "nodal": "none"}}


def run(workdir, nx, per_layer, degree, engine="cpp"):
    """(dofs, tip deflection / beam theory, wall time s, peak memory MB)"""
    msh = workdir / f"bimorph_{nx}_{per_layer}.msh"
    if not msh.exists():
        write_mesh(msh, nx, per_layer)
    tag = degree if isinstance(degree, int) else f"u{degree['u']}phi{degree['phi']}"
    cfg = workdir / f"bimorph_{nx}_{per_layer}_p{tag}.json"
    cfg.write_text(json.dumps(config(msh, degree)))
    out = workdir / cfg.stem
    exe = ([str(ROOT / "build" / "piezo-contact")] if engine == "cpp"
           else ["/usr/bin/python3", "-m", "piezocontact"])
    start = time.perf_counter()
    # GNU time prints the run's own peak resident memory (KB) as its last line
    # this tree's build of the package, not an installed one
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(ROOT / "build" / "python")] + os.environ.get("PYTHONPATH", "").split(os.pathsep)))
    proc = subprocess.run(["/usr/bin/time", "-f", "%M"] + exe
                          + ["--config", str(cfg), "--output", str(out), "--quiet"],
                          capture_output=True, text=True, env=env)
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        raise RuntimeError(proc.stderr)
    peak = int(proc.stderr.strip().splitlines()[-1]) / 1024
    s = json.loads((out / "summary.json").read_text())
    tip = s["steps"][-1]["probes"][0]["u"][1]
    return s["dofs"], tip / THEORY, wall, peak


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--degrees", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--nx", type=int, nargs="+", default=[25, 50, 100, 200, 400])
    ap.add_argument("--per-layer", type=int, nargs="+", default=[1, 2, 4])
    ap.add_argument("--engine", default="cpp", choices=["cpp", "python"])
    args = ap.parse_args()
    print(f"beam theory: tip deflection {THEORY:.6e} m")
    print(f"{'degree':>6} {'nx':>5} {'per layer':>9} {'dofs':>8} {'tip/theory':>10} "
          f"{'wall s':>7} {'peak MB':>8}")
    with tempfile.TemporaryDirectory() as tmp:
        for degree in args.degrees:
            for per_layer in args.per_layer:
                for nx in args.nx:
                    dofs, ratio, wall, peak = run(Path(tmp), nx, per_layer, degree, args.engine)
                    print(f"{degree:>6} {nx:>5} {per_layer:>9} {dofs:>8} {ratio:>10.5f} "
                          f"{wall:>7.2f} {peak:>8.0f}", flush=True)


if __name__ == "__main__":
    sys.exit(main())
