"""tumbler.adm in Python statements: PART's IP lists xx, yy, zz, xy, yz, xz (MotionSolve's
order: the last two are swapped against Adams')."""
import math

from pysolver.msolve import MARKER, PART, REQUEST, SIMULATE, UNITS

UNITS(MASS="KILOGRAM", LENGTH="METER", TIME="SECOND", FORCE="NEWTON")
PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(20, PART=2, QP=[0, 0, 1])
MARKER(21, PART=2, QP=[0, 0.5, 1], REULER=[math.pi / 2, 0, 0])
PART(2, MASS=2, CM=20, IM=21, IP=[3, 2.5, 4.5, -0.5, -0.3, 0.2], WX=1, WY=0.2, WZ=-0.4)
REQUEST(1, F1="WX(20, 1, 20)", F2="WY(20, 1, 20)", F3="WZ(20, 1, 20)")
SIMULATE(TYPE="TRANSIENT", END=2, DTOUT=0.02)
