"""LoadControl (seed 002) on a Hertz-like contact: the indenter of loadcontrol_indenter.xml on
a floor whose force grows as 100 (-z)^1.5 N (IMPACT with exponent 1.5, a little damping),
pushing along the line from a ground marker far below. The load/displacement ratio A_t
changes with depth (the secant 100 |z|^0.5); the same target: ramp to 20 N, hold, step to
40 N at t = 2 s. Units kg, mm, s, N; no gravity.

pysolver convert wrote this script of msolve classes from loadcontrol_hertz.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='loadcontrol_hertz')
Units(force='NEWTON', mass='KILOGRAM', length='MILLIMETER', time='SECOND')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1)
marker2 = Marker(id=2, body=body1, qp=[0.0, 0.0, -1000.0])
marker10 = Marker(id=10, qp=[0.0, 0.0, 0.0])
body2 = PointMass(id=2, mass=0.01, cm=marker10)
marker10.body = body2
Sforce(id=1, i=marker10, j=marker2, type='TRANSLATION',
       function='IMPACT(DZ(10), VZ(10), 0, 100, 1.5, 0.1, 0.01)')
Request(id=1, f1='DZ(10)', f2='SFORCE(1, 0, 1, 0)', cnames=['z', 'contact_force'])
Integrator(error=1e-08)
LoadControl(velocity=-0.1, material=body2, direction=3, maxvelocity=10.0,
            load_function='IF(t-1: 20*t, 20, IF(t-2: 20, 40, 40))', kp='AUTO', ki='AUTO',
            smooth=0.8, updatetime=0.01)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=3.0, dtout=0.01)
