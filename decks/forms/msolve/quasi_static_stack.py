"""Quasi-static compression of a stack of five 0.5 kg particles (radius 0.05 m) on a
unilateral penalty floor, with unilateral penalty contacts between neighbours, under a
load on the top particle rising as 100 t N. FIM_D follows the equilibrium along time with
IDA; every output is an equilibrium. x and y are neutral (stability regularises them).

pysolver convert wrote this script of msolve classes from quasi_static_stack.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='quasi_static_stack')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1)
marker2 = Marker(id=2, body=body1, qp=[0.0, 0.0, 10.0], label='load anchor above the stack')
Accgrav(kgrav=-9.81)
marker10 = Marker(id=10, qp=[0.0, 0.0, 0.05])
body100 = PointMass(id=100, mass=0.5, cm=marker10)
marker10.body = body100
marker11 = Marker(id=11, qp=[0.0, 0.0, 0.15])
body101 = PointMass(id=101, mass=0.5, cm=marker11)
marker11.body = body101
marker12 = Marker(id=12, qp=[0.0, 0.0, 0.25])
body102 = PointMass(id=102, mass=0.5, cm=marker12)
marker12.body = body102
marker13 = Marker(id=13, qp=[0.0, 0.0, 0.35])
body103 = PointMass(id=103, mass=0.5, cm=marker13)
marker13.body = body103
marker14 = Marker(id=14, qp=[0.0, 0.0, 0.45])
body104 = PointMass(id=104, mass=0.5, cm=marker14)
marker14.body = body104
Pforce(id=1, function='0.05 - DZ(10)', penalty=100000.0, penalty1=50.0, smoothing_factor=0.0001,
       unilateral=True, label='floor')
Pforce(id=2, function='0.1 - DZ(11,10)', penalty=100000.0, penalty1=50.0, smoothing_factor=0.0001,
       unilateral=True, label='contact 0-1')
Pforce(id=3, function='0.1 - DZ(12,11)', penalty=100000.0, penalty1=50.0, smoothing_factor=0.0001,
       unilateral=True, label='contact 1-2')
Pforce(id=4, function='0.1 - DZ(13,12)', penalty=100000.0, penalty1=50.0, smoothing_factor=0.0001,
       unilateral=True, label='contact 2-3')
Pforce(id=5, function='0.1 - DZ(14,13)', penalty=100000.0, penalty1=50.0, smoothing_factor=0.0001,
       unilateral=True, label='contact 3-4')
Sforce(id=1, i=marker14, j=marker2, type='TRANSLATION', function='100*TIME', label='rising load')
Request(id=1, f1='DZ(10)', f2='DZ(11)', f3='DZ(12)', f4='DZ(13)', f5='DZ(14)', f6='PFORCE(1)',
        cnames=['', '', '', '', '', 'floor_force'])
Equilibrium(method='FIM_D', imbalance=1e-06, error=1e-06)
Integrator(error=1e-07)

if __name__ == "__main__":
    model.simulate(type="STATICS", end=1.0, dtout=0.01)
