"""Write demos/bilayer.msh: the unit square of example 1 as two layers, a
piezoelectric film (y > 0.5, physical surface "film") on a substrate
(y < 0.5, "substrate"), with the named sides left, right, top, bottom (the
sides of both layers). An example of a user's own gmsh mesh: the solver
reads the .msh as it is (`"mesh": {"type": "msh", "path": "bilayer.msh"}`).

    /usr/bin/python3 meshes/bilayer_msh.py [--size 0.0625] [--output demos/bilayer.msh]
"""

from pathlib import Path

import gmsh
from physical_groups import msh_script, name_groups


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


if __name__ == "__main__":
    msh_script("bilayer", build, __doc__, 1 / 16,
               Path(__file__).resolve().parents[1] / "demos" / "bilayer.msh")
