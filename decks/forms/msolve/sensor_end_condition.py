"""A sensor as an end condition (seed 003 Comment 2): seed Force_Penalty example 3 (kg, mm,
s, N), stopped as soon as the particle has come within 2 mm of the vertex of the two lines,
which Param_Transient cannot express.

pysolver convert wrote this script of msolve classes from sensor_end_condition.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='sensor_end_condition')
Units(force='NEWTON', mass='KILOGRAM', length='MILLIMETER', time='SECOND')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1)
marker10 = Marker(id=10, qp=[100.0, 0.0, 120.0])
body2 = PointMass(id=2, mass=1.0, cm=marker10)
marker10.body = body2
Accgrav(kgrav=-9810.0)
Pforce(id=1, function='1+dx(10)-dz(10)', penalty=10000.0, penalty1=100.0, smoothing_factor=1.0,
       unilateral=True)
Pforce(id=2, function='1-dx(10)-dz(10)', penalty=10000.0, penalty1=100.0, smoothing_factor=1.0,
       unilateral=True)
Sensor(id=1, function='DZ(10)', value=3.0, error=1e-06, operator='LE', halt=True,
       label='near the vertex')
Request(id=1, f1='DX(10)', f2='DZ(10)', cnames=['x', 'z'])
Integrator(error=1e-06)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=3.0, dtout=0.005)
