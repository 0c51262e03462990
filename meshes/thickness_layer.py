#!/usr/bin/python3
"""A thickness-mode layer for the exact 1D resonators (IEEE Std 176-1987):
1 mm thick along y, 0.1 mm wide (its lateral modes ten times above the
thickness modes of interest). Boundaries: "bottom" (y = 0) and "top"
(y = 1 mm), the electrodes; "left" and "right" (x = 0, 0.1 mm), on rollers
in the tests, which makes the thickness modes exactly 1D.

    /usr/bin/python3 meshes/thickness_layer.py --size 50e-6 --output meshes/out/layer.xdmf
"""

from polygon_mesh import main

T, W = 1e-3, 0.1e-3
POINTS = [(0.0, 0.0), (W, 0.0), (W, T), (0.0, T)]
EDGES = ["bottom", "right", "top", "left"]

if __name__ == "__main__":
    main(POINTS, EDGES, __doc__.splitlines()[0])
