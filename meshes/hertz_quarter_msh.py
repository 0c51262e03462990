#!/usr/bin/python3
"""Hertz's sphere in 3D: a quarter of a 20 mm elastic block under a rigid
sphere touching its top at the origin, the box 0 <= x, z <= 20 mm,
-20 mm <= y <= 0, cells of --size within 0.6 mm of the origin, growing to
4 mm far from it. Named faces: "top" (y = 0, the contact boundary),
"bottom" (y = -20 mm), "sym_x" (x = 0) and "sym_z" (z = 0) (the symmetry
planes, on rollers), "sides" (x, z = 20 mm); one volume "block". Written as
a gmsh .msh file (config "type": "msh").

    /usr/bin/python3 meshes/hertz_quarter_msh.py --size 50e-6 --output hertz_quarter.msh
"""

import gmsh
from physical_groups import grade, msh_script, name_groups

L, FINE_RADIUS, COARSE = 20e-3, 0.6e-3, 4e-3


def build(size):
    gmsh.model.occ.addBox(0, -L, 0, L, L, L)
    gmsh.model.occ.synchronize()
    origin = [p for _, p in gmsh.model.getEntities(0)
              if max(abs(c) for c in gmsh.model.getValue(0, p, [])) < 1e-12]
    grade(origin, size, FINE_RADIUS, COARSE)
    tol = 1e-6  # OCC pads bounding boxes by about 1e-7
    faces = {"bottom": [], "sides": [], "sym_x": [], "sym_z": [], "top": []}
    for _, face in gmsh.model.getEntities(2):
        x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(2, face)
        if y0 > -tol:
            faces["top"].append(face)
        elif y1 < -L + tol:
            faces["bottom"].append(face)
        elif x1 < tol:
            faces["sym_x"].append(face)
        elif z1 < tol:
            faces["sym_z"].append(face)
        else:
            faces["sides"].append(face)
    name_groups(2, faces)
    name_groups(3, {"block": [v for _, v in gmsh.model.getEntities(3)]})
    gmsh.model.mesh.generate(3)


if __name__ == "__main__":
    msh_script("hertz_quarter", build, __doc__, 50e-6, binary=True)
