"""Torque-free axisymmetric rigid body in the Python format (see torque_free_spin.xml)."""
from pysolver.msolve import *

PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(20, PART=2, QP=[0, 0, 1], REULER=[0.2, 0.3, 0.1])
PART(2, MASS=3.0, CM=20, IP=[0.1, 0.1, 0.18], VX=0.5, WX=1.0, WY=0.0, WZ=20.0)
REQUEST(1, F1="WX(20,0,20)", F2="WY(20,0,20)", F3="WZ(20,0,20)", F4="WX(20)", F5="WY(20)",
        F6="WZ(20)", F7="DX(20)", F8="DZ(20)", NAME1="wx_body", NAME2="wy_body",
        NAME3="wz_body", NAME4="wx", NAME5="wy", NAME6="wz", NAME7="x", NAME8="z")
INTEGRATOR(ERROR=1e-8)
SIMULATE(TYPE="TRANSIENT", END=2.0, DTOUT=0.01)
