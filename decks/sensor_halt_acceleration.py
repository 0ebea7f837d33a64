"""Seed SENSOR example 1 in the Python format (see sensor_halt_acceleration.xml). EVALUATE
stores an expression under the sensor's own id, read with SENVAL(100)."""
from pysolver.msolve import *

PART(1, GROUND=True)
MARKER(11, PART=1)
MARKER(21, PART=2, QP=[1, 0, 0])
PART(2, MASS=1, CM=21, IP=[0.1, 0.1, 0.1])
SFORCE(1, I=21, J=11, TRANSLATION=True, FUNCTION="2*TIME")
SENSOR(100, FUNCTION="ABS(ACCX(21,11,21,11))", VALUE=5, ERROR=0.0001, OPERATOR="GE", HALT=True,
       EVALUATE="VX(21,11,11)")
REQUEST(1, F1="DX(21,11)", F2="VX(21,11)", F3="ACCX(21,11,21,11)", F4="SENVAL(100)", NAME1="x",
        NAME2="vx", NAME3="ax", NAME4="stored_vx")
INTEGRATOR(ERROR=1e-8)
SIMULATE(TYPE="TRANSIENT", END=10, DTOUT=0.1)
