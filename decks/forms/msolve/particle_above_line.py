"""Seed Force_Penalty example 2: a particle P (marker 10) must stay above the line
y = 1 + x of marker J (here the global frame): unilateral g = 1 + x - y <= 0.
The particle is dropped from (0, 3) under gravity -9.81 along y (consistent SI units).
The seed prints "penalty" twice; the second is penalty1 = 1e2.

pysolver convert wrote this script of msolve classes from particle_above_line.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='particle_above_line')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1)
marker10 = Marker(id=10, qp=[0.0, 3.0, 0.0])
body2 = PointMass(id=2, mass=1.0, cm=marker10)
marker10.body = body2
Accgrav(jgrav=-9.81)
Pforce(id=10, function='1 + dx(10) - dy(10)', penalty=10000.0, penalty1=100.0,
       smoothing_factor=1.0, unilateral=True, label='Enforce 1+x <= y')
Request(id=1, f1='DX(10)', f2='DY(10)', f3='1+DX(10)-DY(10)', f4='PFORCE(10)',
        cnames=['x', 'y', 'g', 'contact_force'])
Integrator(error=1e-06)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=2.0, dtout=0.005)
