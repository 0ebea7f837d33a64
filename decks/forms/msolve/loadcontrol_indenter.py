"""LoadControl (seed 002) on a linear floor: a point indenter (10 g, marker 10) resting on a
unilateral penalty floor z >= 0 of stiffness 100 N/mm is driven along z so that its load
follows a ramp to 20 N (t = 0..1 s), a hold, and a step to 40 N at t = 2 s. Units kg, mm,
s, N; no gravity. The load/displacement ratio A_t is -100 N/mm from the first loaded update
(the load is positive, the displacement negative); Kp and Ki are chosen by the controller.

pysolver convert wrote this script of msolve classes from loadcontrol_indenter.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='loadcontrol_indenter')
Units(force='NEWTON', mass='KILOGRAM', length='MILLIMETER', time='SECOND')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1)
marker10 = Marker(id=10, qp=[0.0, 0.0, 0.0])
body2 = PointMass(id=2, mass=0.01, cm=marker10)
marker10.body = body2
Pforce(id=1, function='-DZ(10)', penalty=100.0, penalty1=0.0, smoothing_factor=0.0001,
       unilateral=True, label='floor z >= 0')
Request(id=1, f1='DZ(10)', f2='PFORCE(1)', cnames=['z', 'floor_force'])
Integrator(error=1e-08)
LoadControl(velocity=-0.1, material=body2, direction=3, maxvelocity=10.0,
            load_function='IF(t-1: 20*t, 20, IF(t-2: 20, 40, 40))', kp='AUTO', ki='AUTO',
            smooth=0.8, updatetime=0.01)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=3.0, dtout=0.01)
