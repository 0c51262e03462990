#!/usr/bin/python3
"""The half-section of a piezoelectric disc indented at its centre, for the
axisymmetric formulation: the rectangle 0 <= r <= 10 mm, -4 mm <= y <= 0
(x = r, y the axis), cells of --size within 0.4 mm of the centre of the top
face, growing to 1 mm. Boundaries named by role: "top" (y = 0, indented),
"bottom" (y = -4 mm), "side" (r = 10 mm), "axis" (r = 0).

    /usr/bin/python3 meshes/indented_disc.py --size 20e-6 --output meshes/out/indented_disc.xdmf
"""

from polygon_mesh import main

R, T = 10e-3, 4e-3
POINTS = [(0.0, 0.0), (0.0, -T), (R, -T), (R, 0.0)]
EDGES = ["axis", "bottom", "side", "top"]
FINE_RADIUS, COARSE = 0.4e-3, 1e-3

if __name__ == "__main__":
    main(POINTS, EDGES, __doc__.splitlines()[0], graded=(0, FINE_RADIUS, COARSE))
