"""Static equilibrium of seed Force_Penalty example 3 (kg, mm, s, N), started 100 mm from the
rest point (at x = 60, z = 81 against about x = 0, z = 0.945): FIM_S finds the rest point
where 2 k g STEP(g, 0, 0, 1, 1) = m grav; a short transient from it stays at rest.

pysolver convert wrote this script of msolve classes from static_seed3.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='static_seed3')
Units(force='NEWTON', mass='KILOGRAM', length='MILLIMETER', time='SECOND')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1)
marker10 = Marker(id=10, qp=[60.0, 0.0, 81.0])
body2 = PointMass(id=2, mass=1.0, cm=marker10)
marker10.body = body2
Accgrav(kgrav=-9810.0)
Pforce(id=1, function='1+dx(10)-dz(10)', penalty=10000.0, penalty1=100.0, smoothing_factor=1.0,
       unilateral=True)
Pforce(id=2, function='1-dx(10)-dz(10)', penalty=10000.0, penalty1=100.0, smoothing_factor=1.0,
       unilateral=True)
Request(id=1, f1='DX(10)', f2='DZ(10)', f3='PFORCE(1)', f4='PFORCE(2)',
        cnames=['x', 'z', 'force_L1', 'force_L2'])
Equilibrium(method='FIM_S', imbalance=1e-08, error=1e-10)
Integrator(error=1e-08)

if __name__ == "__main__":
    model.simulate(type="STATICS")
    model.simulate(type="DYNAMICS", end=0.1, dtout=0.01)
