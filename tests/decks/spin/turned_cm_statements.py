"""turned_cm.adm in Python statements: PART's WX, WZ along the CM marker's axes."""
import math

from pysolver.msolve import MARKER, PART, REQUEST, SIMULATE

PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(20, PART=2, QP=[0, 0, 1], REULER=[0, math.pi / 2, 0])
PART(2, MASS=2, CM=20, IP=[1, 2, 3], WX=0.3, WZ=1)
REQUEST(1, F1="WX(20)", F2="WY(20)", F3="WZ(20)", F4="WX(20,0,20)", F5="WY(20,0,20)",
        F6="WZ(20,0,20)", F7="DX(20)", F8="DZ(20)")
SIMULATE(TYPE="TRANSIENT", END=1.0, DTOUT=0.05)
