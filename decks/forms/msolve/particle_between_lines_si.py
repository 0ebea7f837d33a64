"""Seed Force_Penalty example 3 in consistent SI units (m, kg, s, N; no Units element): the same scene as
particle_between_lines.xml, every length scaled by 1e-3, so penalty 1e7 N/m,
penalty1 1e5 N s/m, smoothing factor 1e-3 m, lines z = 0.001 + x and z = 0.001 - x.

pysolver convert wrote this script of msolve classes from particle_between_lines_si.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='particle_between_lines_si')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1)
marker10 = Marker(id=10, qp=[0.1, 0.0, 0.12])
body2 = PointMass(id=2, mass=1.0, cm=marker10)
marker10.body = body2
Accgrav(igrav=0.0, jgrav=0.0, kgrav=-9.81)
Pforce(id=1, function='0.001+dx(10)-dz(10)', penalty=10000000.0, penalty1=100000.0,
       smoothing_factor=0.001, unilateral=True, label='Enforce 0.001+x<=z')
Pforce(id=2, function='0.001-dx(10)-dz(10)', penalty=10000000.0, penalty1=100000.0,
       smoothing_factor=0.001, unilateral=True, label='Enforce 0.001-x<=z')
Request(id=1, f1='DX(10)', f2='DZ(10)', f3='PFORCE(1)', f4='PFORCE(2)',
        cnames=['x', 'z', 'force_L1', 'force_L2'])
Integrator(error=1e-09)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=3.0, dtout=0.005)
