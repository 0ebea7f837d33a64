"""A point indenter (0.1 kg, marker 10) starting 2 mm above a floor z >= 0 (a unilateral
penalty, 100 N/mm, 1 N s/mm) and driven down at 1 mm/s by a velocity motion; units kg, mm,
s, N, gravity -9810 mm/s^2. The motion's reaction, res.motion(1), carries the weight
(0.981 N) until contact at t = 2 s and then presses into the floor.

pysolver convert wrote this script of msolve classes from driven_indenter.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='driven_indenter')
Units(force='NEWTON', mass='KILOGRAM', length='MILLIMETER', time='SECOND')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1)
marker10 = Marker(id=10, qp=[0.0, 0.0, 2.0])
body2 = PointMass(id=2, mass=0.1, cm=marker10)
marker10.body = body2
Accgrav(igrav=0.0, jgrav=0.0, kgrav=-9810.0)
Pforce(id=1, function='-DZ(10)', penalty=100.0, penalty1=1.0, smoothing_factor=0.01,
       unilateral=True, label='floor z >= 0')
Motion(id=1, i=marker10, j=marker1, direction='Z', dtype='VELOCITY', function='-1',
       label='drive down')
Request(id=1, f1='DZ(10)', f2='PFORCE(1)', cnames=['z', 'floor_force'])
Integrator(error=1e-08)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=3.0, dtout=0.01)
