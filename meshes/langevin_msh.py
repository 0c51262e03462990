#!/usr/bin/python3
"""The half-section of the aluminium / NEPEC 6 / aluminium sandwich
transducer of ANSYS VM176 (Kagawa & Yamabuchi, IEEE SU-26, 1979), for the
axisymmetric formulation (x = r, y the axis), cut at its mid-plane: the
ceramic 0 <= y <= 5 mm, the adhesive to 5.275 mm, the aluminium to
15.275 mm, radius 27.5 mm. Regions "ceramic", "adhesive", "aluminium";
boundaries "midplane" (y = 0), "electrode" (y = 5 mm, between the ceramic
and the adhesive), "side" (r = 27.5 mm), "top" (y = 15.275 mm), "axis".

    /usr/bin/python3 meshes/langevin_msh.py --size 1e-3 --output meshes/out/langevin.msh
"""

import gmsh
from physical_groups import msh_script, name_groups

R = 27.5e-3
LAYERS = (("ceramic", 0.0, 5e-3), ("adhesive", 5e-3, 5.275e-3),
          ("aluminium", 5.275e-3, 15.275e-3))


def build(size):
    occ = gmsh.model.occ
    surfaces = {name: occ.addRectangle(0, y0, 0, R, y1 - y0) for name, y0, y1 in LAYERS}
    occ.fragment([(2, surfaces["ceramic"])], [(2, s) for n, s in surfaces.items()
                                             if n != "ceramic"])
    occ.synchronize()
    gmsh.model.mesh.setSize(gmsh.model.getEntities(0), size)
    tol = 1e-6  # m: OCC bounding boxes are padded by its tolerance (1e-7)
    top = LAYERS[-1][2]
    edges = {"axis": [], "electrode": [], "midplane": [], "side": [], "top": []}
    for _, curve in gmsh.model.getEntities(1):
        x0, y0, _, x1, y1, _ = gmsh.model.getBoundingBox(1, curve)
        if x1 < tol:
            edges["axis"].append(curve)
        elif x0 > R - tol:
            edges["side"].append(curve)
        elif y1 < tol:
            edges["midplane"].append(curve)
        elif abs(y0 - 5e-3) < tol and abs(y1 - 5e-3) < tol:
            edges["electrode"].append(curve)
        elif y0 > top - tol:
            edges["top"].append(curve)
    name_groups(1, edges)
    name_groups(2, {name: [tag] for name, tag in surfaces.items()})
    gmsh.model.mesh.generate(2)


if __name__ == "__main__":
    msh_script("langevin", build, __doc__, 1e-3)
