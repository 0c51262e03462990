#!/usr/bin/python3
"""The contactor of example 2 (paper, section 4.3): the polygon P1..P6 with
boundaries named by role.

    /usr/bin/python3 meshes/contactor.py --size 0.1 --output meshes/out/contactor.xdmf
"""

from polygon_mesh import main

# P1 = (0,1), P2 = (1,0), P3 = (3,1), P4 = (1.5,1), P5 = (1,1.5), P6 = (1,4)
POINTS = [(0.0, 1.0), (1.0, 0.0), (3.0, 1.0), (1.5, 1.0), (1.0, 1.5), (1.0, 4.0)]
# edge i joins POINTS[i] and POINTS[i+1]; the last closes P6 -> P1
EDGES = ["contact",           # [P1,P2]  Gamma_C, facing the foundation
         "free_lower",        # [P2,P3]  traction- and charge-free
         "electrode_high",    # [P3,P4]  phi = 20 V
         "clamp",             # [P4,P5]  Gamma_D, u = 0
         "electrode_ground",  # [P5,P6]  phi = 0 V
         "free_upper"]        # [P6,P1]  traction- and charge-free

if __name__ == "__main__":
    main(POINTS, EDGES, __doc__.splitlines()[0])
