#!/usr/bin/python3
"""The unit square of example 1 as a gmsh (unstructured) mesh, with the same
boundary names as the built-in one: left, right, bottom, top.

    /usr/bin/python3 meshes/square.py --size 0.05 --output meshes/out/square.xdmf
"""

from polygon_mesh import main

POINTS = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
EDGES = ["bottom", "right", "top", "left"]

if __name__ == "__main__":
    main(POINTS, EDGES, __doc__.splitlines()[0])
