"""Spherical pendulum on a SPHERICAL joint, started with an azimuthal velocity
(benchmark deck for Constraint_Joint).

Model (numbers chosen by the project):
- body 2: 1 kg, centre of mass 1 m from the pivot; inertia 1e-3 kg m^2 about every
axis (a 5 cm solid sphere);
- spherical joint 1: J = marker 2 on ground at the origin, I = marker 21 on the body at
the origin (orientations irrelevant for SPHERICAL; both identity);
- gravity -9.81 m/s^2 along y; the rod starts 60 deg from the downward vertical in the
x-y plane: centre at (sin 60, -cos 60, 0) = (0.8660254037844386, -0.5, 0) m;
- initial velocity of the centre (0, 0, 2) m/s (azimuthal, horizontal) and angular
velocity w = r0 x v0 / L^2 = (-1, -1.7320508075688772, 0) rad/s, so that the velocity
is consistent with the joint and the body has no spin about the rod. The cg marker
has global axes, so w_ic reads the same whether taken along global or cg axes.
- 5 s, output every 0.05 s.
Reference (benchmarks/joint_references.py, problem spherical_pendulum): with isotropic
central inertia the body about the pivot is a symmetric top of zero spin, i.e. a
spherical pendulum with I1 = I + m L^2; theta swings between 31.674 and 60 deg from the
downward vertical; converged ODE solution tabulated.
Compare: DX/DY/DZ(20) against the table; DM(20,2) = 1; energy (channel 5) and the
angular momentum about +y at the pivot (channel 6, -1.7337828583764459 kg m^2/s)
constant; the joint gap DM(21,2) (channel 7) at 0.

pysolver convert wrote this script of msolve classes from spherical_pendulum.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='spherical_pendulum')
Units(force='NEWTON', mass='KILOGRAM', length='METER', time='SECOND')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1, label='global')
marker2 = Marker(id=2, body=body1, qp=[0.0, 0.0, 0.0], label='pivot J (ground)')
marker20 = Marker(id=20, qp=[0.8660254037844386, -0.5, 0.0], label='cm')
marker21 = Marker(id=21, qp=[0.0, 0.0, 0.0], label='pivot I (body)')
body2 = Part(id=2, mass=1.0, cm=marker20, ip=[0.001, 0.001, 0.001], vx=0.0, vy=0.0, vz=2.0,
             wx=-1.0, wy=-1.7320508075688772, wz=0.0, label='bob')
marker20.body = body2
marker21.body = body2
Accgrav(igrav=0.0, jgrav=-9.81, kgrav=0.0)
joint1 = Joint(id=1, type='SPHERICAL', i=marker21, j=marker2, label='ball')
Request(id=1, f1='DX(20)', f2='DY(20)', f3='DZ(20)', f4='DM(20,2)',
        f5='0.5*(VX(20)**2 + VY(20)**2 + VZ(20)**2) + 0.5*1E-3*(WX(20)**2 + WY(20)**2 + WZ(20)**2) + 9.81*DY(20)',
        f6='DZ(20)*VX(20) - DX(20)*VZ(20) + 1E-3*WY(20)', f7='DM(21,2)',
        cnames=['x', 'y', 'z', 'radius', 'energy', 'angular_momentum_y', 'joint_gap'])
Integrator(error=1e-08)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=5.0, dtout=0.05)
