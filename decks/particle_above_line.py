"""Seed Force_Penalty example 2 in the Python format: a particle above the line y = 1 + x."""
from pysolver.msolve import *

PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(10, PART=2, QP=[0, 3, 0])
POINT_MASS(2, MASS=1.0, CM=10)
ACCGRAV(JGRAV=-9.81)
PFORCE(10, LABEL="Enforce 1+x <= y", FUNCTION="1+DX(10)-DY(10)", PENALTY=1e4, PENALTY1=1e2,
       UNILATERAL=True, SMOOTHING_FACTOR=1)
REQUEST(1, F1="DX(10)", F2="DY(10)", F3="1+DX(10)-DY(10)", F4="PFORCE(10)", NAME1="x",
        NAME2="y", NAME3="g", NAME4="contact_force")
INTEGRATOR(ERROR=1e-6)
SIMULATE(TYPE="TRANSIENT", END=2.0, DTOUT=0.005)
STOP()
