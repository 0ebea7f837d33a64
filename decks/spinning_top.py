"""Heavy symmetric top on a soft spherical joint, in the Python format (see spinning_top.xml)."""
from pysolver.msolve import *

UNITS(MASS="KILOGRAM", LENGTH="METER", TIME="SECOND", FORCE="NEWTON")
PART(1, GROUND=True)
MARKER(1, PART=1, LABEL="pivot")
MARKER(20, PART=2, QP=[0, -0.029552020666133956, 0.09553364891256061], REULER=[0, 0.3, 0],
       LABEL="cm")
MARKER(21, PART=2, QP=[0, 0, -0.1], RM=20, LABEL="tip")
PART(2, MASS=1.0, CM=20, IP=[0.004, 0.004, 0.00178], WZ=200.0, LABEL="top")
ACCGRAV(KGRAV=-9.81)
for k, axis in enumerate("XYZ", start=1):
    PFORCE(k, FUNCTION=f"D{axis}(21,1)", PENALTY=1e6, PENALTY1=500)
REQUEST(1, F1="DX(20)", F2="DY(20)", F3="DZ(20)", F4="DM(21,1)", F5="ATAN2(DY(20),DX(20))",
        F6="WZ(20,0,20)", F7="PFORCE(3)", NAME1="x_cm", NAME2="y_cm", NAME3="z_cm",
        NAME4="tip_gap", NAME5="azimuth", NAME6="spin", NAME7="pivot_fz")
INTEGRATOR(ERROR=1e-7)
SIMULATE(TYPE="TRANSIENT", END=2.0, DTOUT=0.005)
