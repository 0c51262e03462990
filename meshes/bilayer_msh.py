"""Write demos/bilayer.msh: the unit square of example 1 as two layers, a
piezoelectric film (y > 0.5, physical surface "film") on a substrate
(y < 0.5, "substrate"), with the named sides left, right, top, bottom (the
sides of both layers). An example of a user's own gmsh mesh: the solver
reads the .msh as it is (`"mesh": {"type": "msh", "path": "bilayer.msh"}`).

    /usr/bin/python3 meshes/bilayer_msh.py [--size 0.0625] [--output demos/bilayer.msh]
"""

import argparse
from pathlib import Path

import gmsh
from physical_groups import name_groups


def build(size):
    occ = gmsh.model.occ
    substrate = occ.addRectangle(0, 0, 0, 1, 0.5)
    film = occ.addRectangle(0, 0.5, 0, 1, 0.5)
    occ.fragment([(2, substrate)], [(2, film)])  # one conforming interface
    occ.synchronize()
    gmsh.model.mesh.setSize(gmsh.model.getEntities(0), size)
    sides = {"left": [], "right": [], "top": [], "bottom": []}
    for _, curve in gmsh.model.getEntities(1):
        x0, y0, _, x1, y1, _ = gmsh.model.getBoundingBox(1, curve)
        for name, hit in (("left", x1 < 1e-6), ("right", x0 > 1 - 1e-6),
                          ("bottom", y1 < 1e-6), ("top", y0 > 1 - 1e-6)):
            if hit:
                sides[name].append(curve)
    name_groups(1, dict(sorted(sides.items())))
    name_groups(2, {"substrate": [substrate], "film": [film]})
    gmsh.model.mesh.generate(2)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=float, default=1 / 16)
    ap.add_argument("--output", type=Path,
                    default=Path(__file__).resolve().parents[1] / "demos" / "bilayer.msh")
    args = ap.parse_args()
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    try:
        gmsh.model.add("bilayer")
        build(args.size)
        gmsh.write(str(args.output))
    finally:
        gmsh.finalize()
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
