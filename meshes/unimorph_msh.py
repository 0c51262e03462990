"""Write demos/unimorph.msh: a 3D unimorph actuator, a PZT film (volume
"piezo", 0.25 mm) on a substrate ("substrate", 0.5 mm), 10 mm long along x
and 2 mm wide along y, z up. Named faces: "clamp" (x = 0, both layers),
"electrode_top" (the film's top), "electrode_mid" (the film/substrate
interface, an interior face), "contact" (the substrate's bottom, z = 0).

    /usr/bin/python3 meshes/unimorph_msh.py [--size 0.5e-3] [--output demos/unimorph.msh]
"""

from pathlib import Path

import gmsh
from physical_groups import msh_script, name_groups

L, W, T_SUB, T_PZT = 10e-3, 2e-3, 0.5e-3, 0.25e-3


def build(size):
    occ = gmsh.model.occ
    substrate = occ.addBox(0, 0, 0, L, W, T_SUB)
    piezo = occ.addBox(0, 0, T_SUB, L, W, T_PZT)
    occ.fragment([(3, substrate)], [(3, piezo)])  # one conforming interface
    occ.synchronize()
    gmsh.model.mesh.setSize(gmsh.model.getEntities(0), size)
    tol = 1e-6  # m: OCC bounding boxes are padded by its tolerance
    faces = {"clamp": [], "electrode_top": [], "electrode_mid": [], "contact": []}
    for _, face in gmsh.model.getEntities(2):
        x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(2, face)
        if x1 < tol:
            faces["clamp"].append(face)
        elif z0 > T_SUB + T_PZT - tol:
            faces["electrode_top"].append(face)
        elif abs(z0 - T_SUB) < tol and abs(z1 - T_SUB) < tol:
            faces["electrode_mid"].append(face)
        elif z1 < tol:
            faces["contact"].append(face)
    name_groups(2, dict(sorted(faces.items())))
    name_groups(3, {"substrate": [substrate], "piezo": [piezo]})
    gmsh.model.mesh.generate(3)


if __name__ == "__main__":
    msh_script("unimorph", build, __doc__, 0.5e-3,
               Path(__file__).resolve().parents[1] / "demos" / "unimorph.msh", binary=True)
