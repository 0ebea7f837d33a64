"""Seed Sensor_Event example 2 made runnable (with an expression instead of SENSUB): a ball
falls from 10 m; when it passes z = 5 m (t = sqrt(10/9.81) s) the print interval changes
from 0.1 s to 0.01 s, an output row is written at the event, and Sensor_Evaluate 200 stores
the speed there.

pysolver convert wrote this script of msolve classes from sensor_output_interval.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='sensor_output_interval')
body1 = Part(id=1, ground=True)
marker10 = Marker(id=10, qp=[0.0, 0.0, 10.0])
body2 = PointMass(id=2, mass=1.0, cm=marker10)
marker10.body = body2
Accgrav(kgrav=-9.81)
Sensor(id=200, function='DZ(10)', value=5.0, error=0.0001, operator='LE', print_=True, dt=0.01,
       evaluate='VM(10)')
Request(id=1, f1='DZ(10)', f2='VZ(10)', f3='SENVAL(200)', cnames=['z', 'vz', 'speed_at_5m'])
Integrator(error=1e-09)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=1.3, dtout=0.1)
