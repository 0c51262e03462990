#!/usr/bin/python3
"""A block pressed by a rigid indenter at the origin, for Hertz's problems:
the square 0 <= x <= 40 mm, -40 mm <= y <= 0 (x = r in axisymmetry), cells
of --size within 1 mm of the origin growing to 4 mm far from it. Boundaries
named by role: "top" (y = 0, the contact boundary), "axis" (x = 0: the
symmetry plane, or the axis), "side" (x = 40 mm), "bottom" (y = -40 mm).

    /usr/bin/python3 meshes/hertz_block.py --size 0.02e-3 --output meshes/out/hertz_block.xdmf
"""

from polygon_mesh import main

L = 40e-3
POINTS = [(0.0, 0.0), (0.0, -L), (L, -L), (L, 0.0)]
EDGES = ["axis", "bottom", "side", "top"]
FINE_RADIUS, COARSE = 1e-3, 4e-3

if __name__ == "__main__":
    main(POINTS, EDGES, __doc__.splitlines()[0], graded=(0, FINE_RADIUS, COARSE))
