"""Slider-crank driven at constant crank speed (benchmark deck for Constraint_Joint and
Motion_Joint).

Model (numbers chosen by the project): plane x-y, gravity -9.81 m/s^2 along y.
- crank (body 2): O = (0, 0, 0) to A = (0.1, 0, 0); 1 kg, centre of mass at r/2,
inertia 1e-3 kg m^2 about every axis; revolute joint 1 to ground at O
(I = 21 on the crank, J = 2 on ground, z axes along global z);
- Motion_Joint 1 on joint 1: AZ(21, 2) = 2 pi TIME (displacement, 1 rev/s; the angle
passes pi at t = 0.5 s, so AZ must be tracked through full turns);
- connecting rod (body 3): A to B = (0.5, 0, 0), l = 0.4 m; 1 kg, centre of mass at
mid-length (0.3, 0, 0), Iyy = Izz = l^2/12 = 0.013333333333333334 kg m^2, axial
Ixx = 1e-4; revolute joint 2 at A (I = 31 on the rod, J = 22 on the crank);
- slider (body 4) at B: 1 kg, inertia 1e-3 about every axis; revolute joint 3 at B
(I = 41 on the slider, J = 32 on the rod); translational joint 4 along global x
(I = 42 on the slider, J = 3 on ground at O, both with z along +x: columns
x = (0, 1, 0), y = (0, 0, 1), z = (1, 0, 0)), so DZ(42, 3, 3) is the slider's x.
- initial velocities consistent with the motion at t = 0 (crank angle 0):
crank w_z = 2 pi, its centre v_y = pi/10; rod w_z = -r w / l = -pi/2, its centre
v_y = pi/10; slider at rest. 2 s, output every 0.02 s.
Note: as a planar loop written with four full 3D joints it has 3 redundant
constraint equations (18 coordinates, 20 + 1 equations, 0 DOF), the usual Adams /
MotionSolve situation (Adams removes the redundant rows).
Reference (benchmarks/joint_references.py, problem slider_crank): closed-form
kinematics xB = r cos(th) + sqrt(l^2 - r^2 sin^2(th)), th = 2 pi t; the driving torque
about +z on the crank = dE/dt / omega.
Compare: channels 1-6 against the table (slider_x, slider_vx, crank_tip_x/y, rod_angle,
crank angle); channel 7 (DZ of the translational joint) equals channel 1.

pysolver convert wrote this script of msolve classes from slider_crank.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='slider_crank')
Units(force='NEWTON', mass='KILOGRAM', length='METER', time='SECOND')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1, label='global')
marker2 = Marker(id=2, body=body1, label='O on ground (J of the crank revolute)')
marker3 = Marker(id=3, body=body1, zp=[1.0, 0.0, 0.0], xp=[0.0, 1.0, 0.0],
                 label='slide line on ground (J, z along +x)')
marker20 = Marker(id=20, qp=[0.05, 0.0, 0.0], label='crank cm')
marker21 = Marker(id=21, label='O on the crank (I)')
marker22 = Marker(id=22, qp=[0.1, 0.0, 0.0], label='A on the crank (J)')
body2 = Part(id=2, mass=1.0, cm=marker20, ip=[0.001, 0.001, 0.001], vy=0.3141592653589793,
             wz=6.283185307179586, label='crank')
marker20.body = body2
marker21.body = body2
marker22.body = body2
marker30 = Marker(id=30, qp=[0.3, 0.0, 0.0], label='rod cm')
marker31 = Marker(id=31, qp=[0.1, 0.0, 0.0], label='A on the rod (I)')
marker32 = Marker(id=32, qp=[0.5, 0.0, 0.0], label='B on the rod (J)')
body3 = Part(id=3, mass=1.0, cm=marker30, ip=[0.0001, 0.013333333333333334, 0.013333333333333334],
             vy=0.3141592653589793, wz=-1.5707963267948966, label='connecting rod')
marker30.body = body3
marker31.body = body3
marker32.body = body3
marker40 = Marker(id=40, qp=[0.5, 0.0, 0.0], label='slider cm')
marker41 = Marker(id=41, qp=[0.5, 0.0, 0.0], label='B on the slider (I)')
marker42 = Marker(id=42, qp=[0.5, 0.0, 0.0], zp=[1.5, 0.0, 0.0], xp=[0.5, 1.0, 0.0],
                  label='slider on the line (I, z along +x)')
body4 = Part(id=4, mass=1.0, cm=marker40, ip=[0.001, 0.001, 0.001], label='slider')
marker40.body = body4
marker41.body = body4
marker42.body = body4
Accgrav(igrav=0.0, jgrav=-9.81, kgrav=0.0)
joint1 = Joint(id=1, type='REVOLUTE', i=marker21, j=marker2, label='crank pivot O')
joint2 = Joint(id=2, type='REVOLUTE', i=marker31, j=marker22, label='crank pin A')
joint3 = Joint(id=3, type='REVOLUTE', i=marker41, j=marker32, label='wrist pin B')
joint4 = Joint(id=4, type='TRANSLATIONAL', i=marker42, j=marker3, label='slide')
Motion(id=1, joint=joint1, dtype='DISPLACEMENT', function='2*PI*TIME', label='crank drive')
Request(id=1, f1='DX(40)', f2='VX(40)', f3='DX(22)', f4='DY(22)', f5='ATAN2(DY(32,31), DX(32,31))',
        f6='AZ(21,2)', f7='DZ(42,3,3)',
        cnames=['slider_x', 'slider_vx', 'crank_tip_x', 'crank_tip_y', 'rod_angle', 'crank_angle', 'slide_dz'])
Integrator(error=1e-08)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=2.0, dtout=0.02)
