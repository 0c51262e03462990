#!/usr/bin/python3
"""The half-section of a disc transducer for the axisymmetric formulation:
the rectangle 0 <= r <= 10 mm, 0 <= y <= 2 mm (x = r, y the axis), with
boundaries named by role: "bottom" (y = 0), "side" (r = R), "top" (y = T),
"axis" (r = 0, where the formulation holds u_r = 0 itself).

    /usr/bin/python3 meshes/disc.py --size 0.5e-3 --output meshes/out/disc.xdmf
"""

from polygon_mesh import main

R, T = 10e-3, 2e-3
POINTS = [(0.0, 0.0), (R, 0.0), (R, T), (0.0, T)]
EDGES = ["bottom", "side", "top", "axis"]

if __name__ == "__main__":
    main(POINTS, EDGES, __doc__.splitlines()[0])
