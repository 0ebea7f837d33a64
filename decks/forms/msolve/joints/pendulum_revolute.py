"""Simple pendulum on a revolute joint (benchmark deck for Constraint_Joint).

Model (numbers chosen by the project, matching shared/reference/numerics.md section 7's
Exudyn anchor "a 2 m revolute pendulum over 5 s"; the IFToMM A01 pendulum is the same
problem with 1 m and 10 s):
- body 2: 1 kg, centre of mass 2 m from the pivot; inertia 1e-3 kg m^2 about every
axis (a solid sphere of radius 5 cm, 2/5 m r^2), so it is point-like but a regular
rigid body;
- revolute joint 1: J = marker 2 on ground at the origin, I = marker 21 on the body at
the origin; both z axes along global z (the rotation axis), x axes along global x;
- gravity -9.81 m/s^2 along y; released at rest with the centre of mass at (2, 0, 0)
(horizontal), 5 s, output every 0.05 s.
Exact solution (benchmarks/joint_references.py, problem pendulum_revolute): the
physical pendulum phi'' = -w0^2 sin phi, w0^2 = m g L / (m L^2 + I) = 19.62 / 4.001,
in closed form with Jacobi elliptic functions; period 4 K(1/2) / w0 = 3.34905275 s.
Compare: DX(20), DY(20), VX(20), VY(20) against the reference table
(benchmarks/data/joint_references.json); energy (channel 6) constant at 0 J; DM(21,2)
(channel 7, the joint gap) at 0. Joint reaction on the body (Adams JOINT(1,0,..)):
m a - m g, also tabulated.

pysolver convert wrote this script of msolve classes from pendulum_revolute.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='pendulum_revolute')
Units(force='NEWTON', mass='KILOGRAM', length='METER', time='SECOND')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1, label='global')
marker2 = Marker(id=2, body=body1, qp=[0.0, 0.0, 0.0], label='pivot J (ground)')
marker20 = Marker(id=20, qp=[2.0, 0.0, 0.0], label='cm')
marker21 = Marker(id=21, qp=[0.0, 0.0, 0.0], label='pivot I (body)')
body2 = Part(id=2, mass=1.0, cm=marker20, ip=[0.001, 0.001, 0.001], label='bob')
marker20.body = body2
marker21.body = body2
Accgrav(igrav=0.0, jgrav=-9.81, kgrav=0.0)
joint1 = Joint(id=1, type='REVOLUTE', i=marker21, j=marker2, label='pivot')
Request(id=1, f1='DX(20)', f2='DY(20)', f3='VX(20)', f4='VY(20)', f5='WZ(20)',
        f6='0.5*(VX(20)**2 + VY(20)**2) + 0.5*1E-3*WZ(20)**2 + 9.81*DY(20)', f7='DM(21,2)',
        cnames=['x', 'y', 'vx', 'vy', 'wz', 'energy', 'joint_gap'])
Integrator(error=1e-08)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=5.0, dtout=0.05)
