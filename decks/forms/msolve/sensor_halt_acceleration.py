"""Seed Sensor_Event example 1 made runnable: a block (marker 21) pushed away from the ground
marker 11 by a force 2*TIME N; its acceleration ACCX(21,11,21,11) = 2 t reaches 5 m/s^2 at
t = 2.5 s, when Sensor_Evaluate 100 stores the velocity (t^2 = 6.25 m/s) and the run halts.

pysolver convert wrote this script of msolve classes from sensor_halt_acceleration.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='sensor_halt_acceleration')
body1 = Part(id=1, ground=True)
marker11 = Marker(id=11, body=body1)
marker21 = Marker(id=21, qp=[1.0, 0.0, 0.0])
body2 = Part(id=2, mass=1.0, cm=marker21, ip=[0.1, 0.1, 0.1])
marker21.body = body2
Sforce(id=1, i=marker21, j=marker11, type='TRANSLATION', function='2*TIME')
Sensor(id=100, function='ABS( ACCX(21,11,21,11) )', value=5.0, error=0.0001, operator='GE',
       halt=True, evaluate='VX(21,11,11)')
Request(id=1, f1='DX(21,11)', f2='VX(21,11)', f3='ACCX(21,11,21,11)', f4='SENVAL(100)',
        cnames=['x', 'vx', 'ax', 'stored_vx'])
Integrator(error=1e-08)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=10.0, dtout=0.1)
