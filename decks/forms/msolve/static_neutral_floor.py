"""A ball resting on a flat unilateral penalty floor z = 0: the equilibrium is neutral in x and
y (no force resists a horizontal shift), so the Newton matrix of FIM_S is singular unless
Param_Static stability > 0; the answer (x, y unchanged, z from k g STEP = m g) does not
depend on it.

pysolver convert wrote this script of msolve classes from static_neutral_floor.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='static_neutral_floor')
body1 = Part(id=1, ground=True)
marker10 = Marker(id=10, qp=[0.3, -0.2, 0.05])
body2 = PointMass(id=2, mass=2.0, cm=marker10)
marker10.body = body2
Accgrav(kgrav=-9.81)
Pforce(id=1, function='-DZ(10)', penalty=100000.0, penalty1=100.0, smoothing_factor=0.001,
       unilateral=True)
Request(id=1, f1='DX(10)', f2='DY(10)', f3='DZ(10)', f4='PFORCE(1)')
Equilibrium(method='FIM_S', imbalance=1e-09, error=1e-12, stability=1e-10)

if __name__ == "__main__":
    model.simulate(type="STATICS")
