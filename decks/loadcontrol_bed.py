"""LoadControl with a noisy load: an indenter (a sphere of radius 3 mm on a point body) pressed
into a hexagonally packed bed of particles (radius 1 mm, 1 g each, 2D in x-z; 53 with the
default 11 x 5) in a box, every contact a unilateral penalty (10 N/mm, damping 0.01 N s/mm). Units kg, mm, s, N; gravity -9810 mm/s^2. The load is
the contact force on the indenter (load="contact"), which jumps as particles slip and
rearrange: the seed's fat-tailed contact noise. Target: a ramp of 0.6 N/s. Change NX, NZ for
bigger beds (benchmarks/loadcontrol.py runs 53 and 195 particles), and MEDIAN_WINDOW to filter
the load."""
import math

from pysolver.msolve import *

NX, NZ = 11, 5                 # particles per row (odd rows one fewer), rows
MEDIAN_WINDOW = 1
R, RI, GAP = 1.0, 3.0, 2.0     # particle radius, indenter radius, particle spacing
K, C = 10.0, 0.01              # contact stiffness (N/mm) and damping (N s/mm)
W = NX * GAP                   # box width

UNITS(MASS="KILOGRAM", LENGTH="MILLIMETER", TIME="SECOND", FORCE="NEWTON")
ACCGRAV(KGRAV=-9810)
PART(1, GROUND=True)
MARKER(1, PART=1)
centres = {}
for r in range(NZ):
    # hexagonal packing: odd rows shifted by a radius (one particle fewer), rows sqrt(3) R
    # apart, so the bed stands under gravity
    for c in range(NX - r % 2):
        pid = 100 + r * NX + c
        x = R + c * GAP + (R if r % 2 else 0.0)
        z = R + r * math.sqrt(3.0) * R
        MARKER(pid, PART=pid, QP=[x, 0, z])
        POINT_MASS(pid, MASS=1e-3, CM=pid)
        centres[pid] = (x, z)
top = max(z for _, z in centres.values())
MARKER(10, PART=2, QP=[W / 2, 0, top + R + RI + 0.2])
POINT_MASS(2, MASS=5e-3, CM=10)


def contact(fid, g):
    PFORCE(fid, FUNCTION=g, PENALTY=K, PENALTY1=C, UNILATERAL=True, SMOOTHING_FACTOR=1e-4)


fid = 1
for pid, (x, z) in centres.items():
    for g in (f"{R}-DZ({pid})", f"{R}-DX({pid})", f"DX({pid})-{W - R}"):   # floor and walls
        contact(fid, g)
        fid += 1
    for qid, (x2, z2) in centres.items():             # neighbours: within 1.5 spacings
        if qid > pid and math.hypot(x2 - x, z2 - z) < 1.5 * GAP:
            contact(fid, f"{2 * R}-DM({pid},{qid})")
            fid += 1
    if z > top - 2.5 * GAP and abs(x - W / 2) < 3 * GAP:    # the indenter on the top rows
        contact(fid, f"{R + RI}-DM({pid},10)")
        fid += 1
LOADCONTROL(1, VELOCITY=-2.0, MATERIAL=2, DIRECTION=3, MAXVELOCITY=20,
            LOAD_FUNCTION="0.6*t", KP="auto", KI="auto", SMOOTH=0.8,
            UPDATETIME=0.005, MEDIAN_WINDOW=MEDIAN_WINDOW, LOAD="contact")
REQUEST(1, F1="DZ(10)", NAME1="indenter_z")
INTEGRATOR(ERROR=1e-5)
SIMULATE(TYPE="TRANSIENT", END=0.6, DTOUT=0.005)
