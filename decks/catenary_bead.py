"""Seed Force_Penalty example 1 in the Python format: a bead on the catenary y = cosh(x)."""
from pysolver.msolve import *

PART(1, GROUND=True, LABEL="Ground")
MARKER(1, PART=1, LABEL="origin")
MARKER(9, PART=2, QP=[0.5, 1.1276259652063807, 0], LABEL="bead")
POINT_MASS(2, MASS=1.0, CM=9, LABEL="bead")
ACCGRAV(IGRAV=0, JGRAV=-9.81, KGRAV=0)
PFORCE(1, LABEL="Particle sliding on a catenary", FUNCTION="DY(9)-COSH(DX(9))",
       PENALTY=1e4, PENALTY1=1e2)
REQUEST(1, F1="DX(9)", F2="DY(9)", F3="VX(9)", F4="VY(9)", F5="DY(9)-COSH(DX(9))",
        F6="PFORCE(1)", NAME1="x", NAME2="y", NAME3="vx", NAME4="vy", NAME5="g",
        NAME6="penalty_force")
INTEGRATOR(ERROR=1e-6)
SIMULATE(TYPE="TRANSIENT", END=3.0, DTOUT=0.01)
STOP()
