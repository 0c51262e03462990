"""The contactor of example 2 with a sensing electrode: the upper free side
[P6, P1] is cut at its midpoint P7, the lower half [P7, P1] being the
electrode `sensor` (apart from the other electrodes: the rest of the side,
`free_upper`, separates it from `electrode_ground`).

    /usr/bin/python3 meshes/contactor_sensor.py --size 0.05 --output meshes/out/contactor_sensor.xdmf
"""

from contactor import EDGES, POINTS
from polygon_mesh import main

P7 = (0.5 * (POINTS[5][0] + POINTS[0][0]), 0.5 * (POINTS[5][1] + POINTS[0][1]))

if __name__ == "__main__":
    main(POINTS + [P7], EDGES + ["sensor"], __doc__.splitlines()[0])
