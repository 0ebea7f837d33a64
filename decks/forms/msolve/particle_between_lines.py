"""Seed Force_Penalty example 3: a particle P (marker 10) bouncing between the lines
z = 1 + x and z = 1 - x, starting at (100, 120) mm and falling under -9810 mm/s^2.
Units kg, mm, s, N: penalty 1e4 N/mm, penalty1 1e2 N s/mm. It comes to rest at x = 0,
slightly below z = 1 where 2 k g STEP(g, 0, 0, 1, 1) = m grav.

pysolver convert wrote this script of msolve classes from particle_between_lines.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='particle_between_lines')
Units(force='NEWTON', mass='KILOGRAM', length='MILLIMETER', time='SECOND')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1)
marker10 = Marker(id=10, qp=[100.0, 0.0, 120.0])
body2 = PointMass(id=2, mass=1.0, cm=marker10)
marker10.body = body2
Accgrav(igrav=0.0, jgrav=0.0, kgrav=-9810.0)
Pforce(id=1, function='1+dx(10)-dz(10)', penalty=10000.0, penalty1=100.0, smoothing_factor=1.0,
       unilateral=True, label='Enforce 1+x<=z')
Pforce(id=2, function='1-dx(10)-dz(10)', penalty=10000.0, penalty1=100.0, smoothing_factor=1.0,
       unilateral=True, label='Enforce 1-x<=z')
Request(id=1, f1='DX(10)', f2='DZ(10)', f3='PFORCE(1)', f4='PFORCE(2)',
        cnames=['x', 'z', 'force_L1', 'force_L2'])
Integrator(error=1e-06)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=3.0, dtout=0.005)
