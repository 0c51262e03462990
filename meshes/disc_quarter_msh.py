#!/usr/bin/python3
"""The disc of meshes/disc.py in 3D: a quarter of the cylinder r <= 10 mm,
0 <= y <= 2 mm (its axis is y, as in the axisymmetric section), x, z >= 0,
meshed in layers along y (its lateral facets are vertical: the mesh holds
the uniform-field solutions exactly). Named faces: "bottom", "top",
"side", and the symmetry planes "sym_x" (x = 0) and "sym_z" (z = 0); one
volume "disc". Written as a gmsh .msh file (config "type": "msh").

    /usr/bin/python3 meshes/disc_quarter_msh.py --size 1e-3 --output disc_quarter.msh
"""


import gmsh
from physical_groups import msh_script, name_groups

R, T = 10e-3, 2e-3


def build(size):
    occ = gmsh.model.occ
    # the quarter disc x, y >= 0 in the plane z = 0, turned onto the plane
    # y = 0 (x, z >= 0) by a quarter turn about x, extruded along y in layers
    disc = occ.addDisk(0, 0, 0, R, R)
    box = occ.addRectangle(0, 0, 0, R, R)
    quarter, _ = occ.intersect([(2, disc)], [(2, box)])
    occ.rotate(quarter, 0, 0, 0, 1, 0, 0, 3.141592653589793 / 2)
    layers = max(1, round(T / size))
    occ.extrude(quarter, 0, T, 0, numElements=[layers])
    occ.synchronize()
    gmsh.model.mesh.setSize(gmsh.model.getEntities(0), size)
    tol = 1e-6
    faces = {"bottom": [], "top": [], "side": [], "sym_x": [], "sym_z": []}
    for _, face in gmsh.model.getEntities(2):
        x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(2, face)
        if y1 < tol:
            faces["bottom"].append(face)
        elif y0 > T - tol:
            faces["top"].append(face)
        elif x1 < tol:
            faces["sym_x"].append(face)
        elif z1 < tol:
            faces["sym_z"].append(face)
        else:
            faces["side"].append(face)
    name_groups(2, dict(sorted(faces.items())))
    name_groups(3, {"disc": [v for _, v in gmsh.model.getEntities(3)]})
    gmsh.model.mesh.generate(3)


if __name__ == "__main__":
    msh_script("disc_quarter", build, __doc__, 1e-3, binary=True)
