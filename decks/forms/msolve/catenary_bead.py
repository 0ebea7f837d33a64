"""Seed Force_Penalty example 1: a bead (point mass) sliding on the catenary y = cosh(x),
enforced by a bilateral penalty g = y - cosh(x) with penalty 1e4 and penalty1 1e2.
Consistent SI units; gravity along -y.

pysolver convert wrote this script of msolve classes from catenary_bead.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='catenary_bead')
body1 = Part(id=1, ground=True, label='Ground')
marker1 = Marker(id=1, body=body1, label='origin')
marker9 = Marker(id=9, qp=[0.5, 1.1276259652063807, 0.0], label='bead')
body2 = PointMass(id=2, mass=1.0, cm=marker9, label='bead')
marker9.body = body2
Accgrav(igrav=0.0, jgrav=-9.81, kgrav=0.0)
Pforce(id=1, function='dy(9) - cosh(dx(9))', penalty=10000.0, penalty1=100.0,
       label='Particle sliding on a catenary')
Request(id=1, f1='DX(9)', f2='DY(9)', f3='VX(9)', f4='VY(9)', f5='DY(9)-COSH(DX(9))',
        f6='PFORCE(1)', cnames=['x', 'y', 'vx', 'vy', 'g', 'penalty_force'])
Integrator(error=1e-06)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=3.0, dtout=0.01)
