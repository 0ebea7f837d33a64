"""IFToMM A04: Bricard's mechanism (benchmark deck for Constraint_Joint: an
over-constrained loop).

Source: IFToMM Library of Computational Benchmark Problems, problem A04,
http://lim.ii.udc.es/mbsbenchmark/dist/A04/A04_specification.xml (five rods, six
revolute joints, gravity -y, 10 s; Gruebler counts 0 DOF, the joint directions give 1);
rod data and the initial position as in the OpenSim implementation of the library
(RehabEngGroup/MBSbenchmarksInOpenSim, src/A04-BricardsMechanism: rods 1 m, 1 kg, square
section 0.1 m, gravity -9.81 y, started at rest; P3 = the end of rod 2) and in Exudyn's
bricardMechanism.py (same points and axes).
- rods along the edges of the unit cube: A (0,0,0) - B (1,0,0) - C (1,-1,0) -
D (1,-1,1) - E (0,-1,1) - F (0,0,1); ground closes F - A;
- revolute axes: A y, B z, C x, D y, E z, F x (the joint markers' z axes; J marker on
the rod nearer ground along the chain A..E, or on ground for A and F);
- inertia of a 1 m x 0.1 m x 0.1 m box of 1 kg about its centre: long axis
m (0.1^2 + 0.1^2)/12 = 0.0016667, transverse m (1 + 0.01)/12 = 0.0841667 kg m^2;
the cg markers have global axes (every rod is axis-aligned at t = 0);
- at rest at t = 0, 10 s, output every 0.05 s.
Constraints: 6 x 5 = 30 equations on 5 x 6 = 30 coordinates with rank 29: one
redundant equation everywhere along the motion (Adams removes one row).
Reference (benchmarks/joint_references.py, problem iftomm_a04_bricard): joint-coordinate
ODE with the loop closed at velocity/acceleration level, DOP853 at rtol 1e-12, agreeing
with Exudyn to O(h^2); the motion is a swing of period about 5 s (P3 returns near
(1, -1, 0) at t = 5 and 10).
Compare: P3 = marker 32 (joint C on rod 2), channels 1-3, against the table; energy
(channel 4, kinetic + gravity with zero level y = 0) constant at -29.43 J.

pysolver convert wrote this script of msolve classes from iftomm_a04_bricard.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='iftomm_a04_bricard')
Units(force='NEWTON', mass='KILOGRAM', length='METER', time='SECOND')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1, label='global')
marker2 = Marker(id=2, body=body1, qp=[0.0, 0.0, 0.0], zp=[0.0, 1.0, 0.0], xp=[0.0, 0.0, 1.0],
                 label='A on ground (J), z along +y')
marker3 = Marker(id=3, body=body1, qp=[0.0, 0.0, 1.0], zp=[1.0, 0.0, 1.0], xp=[0.0, 1.0, 1.0],
                 label='F on ground (J), z along +x')
marker20 = Marker(id=20, qp=[0.5, 0.0, 0.0], label='rod 1 cm')
marker21 = Marker(id=21, qp=[0.0, 0.0, 0.0], zp=[0.0, 1.0, 0.0], xp=[0.0, 0.0, 1.0],
                  label='A on rod 1 (I), z along +y')
marker22 = Marker(id=22, qp=[1.0, 0.0, 0.0], label='B on rod 1 (J), z along +z')
body2 = Part(id=2, mass=1.0, cm=marker20,
             ip=[0.0016666666666666668, 0.08416666666666667, 0.08416666666666667],
             label='rod 1 AB')
marker20.body = body2
marker21.body = body2
marker22.body = body2
marker30 = Marker(id=30, qp=[1.0, -0.5, 0.0], label='rod 2 cm')
marker31 = Marker(id=31, qp=[1.0, 0.0, 0.0], label='B on rod 2 (I), z along +z')
marker32 = Marker(id=32, qp=[1.0, -1.0, 0.0], zp=[2.0, -1.0, 0.0], xp=[1.0, 0.0, 0.0],
                  label='C on rod 2 (J), z along +x = P3')
body3 = Part(id=3, mass=1.0, cm=marker30,
             ip=[0.08416666666666667, 0.0016666666666666668, 0.08416666666666667],
             label='rod 2 BC')
marker30.body = body3
marker31.body = body3
marker32.body = body3
marker40 = Marker(id=40, qp=[1.0, -1.0, 0.5], label='rod 3 cm')
marker41 = Marker(id=41, qp=[1.0, -1.0, 0.0], zp=[2.0, -1.0, 0.0], xp=[1.0, 0.0, 0.0],
                  label='C on rod 3 (I), z along +x')
marker42 = Marker(id=42, qp=[1.0, -1.0, 1.0], zp=[1.0, 0.0, 1.0], xp=[1.0, -1.0, 2.0],
                  label='D on rod 3 (J), z along +y')
body4 = Part(id=4, mass=1.0, cm=marker40,
             ip=[0.08416666666666667, 0.08416666666666667, 0.0016666666666666668],
             label='rod 3 CD')
marker40.body = body4
marker41.body = body4
marker42.body = body4
marker50 = Marker(id=50, qp=[0.5, -1.0, 1.0], label='rod 4 cm')
marker51 = Marker(id=51, qp=[1.0, -1.0, 1.0], zp=[1.0, 0.0, 1.0], xp=[1.0, -1.0, 2.0],
                  label='D on rod 4 (I), z along +y')
marker52 = Marker(id=52, qp=[0.0, -1.0, 1.0], label='E on rod 4 (J), z along +z')
body5 = Part(id=5, mass=1.0, cm=marker50,
             ip=[0.0016666666666666668, 0.08416666666666667, 0.08416666666666667],
             label='rod 4 DE')
marker50.body = body5
marker51.body = body5
marker52.body = body5
marker60 = Marker(id=60, qp=[0.0, -0.5, 1.0], label='rod 5 cm')
marker61 = Marker(id=61, qp=[0.0, -1.0, 1.0], label='E on rod 5 (I), z along +z')
marker62 = Marker(id=62, qp=[0.0, 0.0, 1.0], zp=[1.0, 0.0, 1.0], xp=[0.0, 1.0, 1.0],
                  label='F on rod 5 (I), z along +x')
body6 = Part(id=6, mass=1.0, cm=marker60,
             ip=[0.08416666666666667, 0.0016666666666666668, 0.08416666666666667],
             label='rod 5 EF')
marker60.body = body6
marker61.body = body6
marker62.body = body6
Accgrav(igrav=0.0, jgrav=-9.81, kgrav=0.0)
joint1 = Joint(id=1, type='REVOLUTE', i=marker21, j=marker2, label='A ground-rod 1 (axis y)')
joint2 = Joint(id=2, type='REVOLUTE', i=marker31, j=marker22, label='B rod 1-rod 2 (axis z)')
joint3 = Joint(id=3, type='REVOLUTE', i=marker41, j=marker32, label='C rod 2-rod 3 (axis x)')
joint4 = Joint(id=4, type='REVOLUTE', i=marker51, j=marker42, label='D rod 3-rod 4 (axis y)')
joint5 = Joint(id=5, type='REVOLUTE', i=marker61, j=marker52, label='E rod 4-rod 5 (axis z)')
joint6 = Joint(id=6, type='REVOLUTE', i=marker62, j=marker3, label='F rod 5-ground (axis x)')
Request(id=1, f1='DX(32)', f2='DY(32)', f3='DZ(32)',
        f4='0.5*(VX(20)**2+VY(20)**2+VZ(20)**2)+0.5*(0.0016666666666666668*WX(20,0,20)**2+0.08416666666666667*WY(20,0,20)**2+0.08416666666666667*WZ(20,0,20)**2)+9.81*DY(20) + 0.5*(VX(30)**2+VY(30)**2+VZ(30)**2)+0.5*(0.08416666666666667*WX(30,0,30)**2+0.0016666666666666668*WY(30,0,30)**2+0.08416666666666667*WZ(30,0,30)**2)+9.81*DY(30) + 0.5*(VX(40)**2+VY(40)**2+VZ(40)**2)+0.5*(0.08416666666666667*WX(40,0,40)**2+0.08416666666666667*WY(40,0,40)**2+0.0016666666666666668*WZ(40,0,40)**2)+9.81*DY(40) + 0.5*(VX(50)**2+VY(50)**2+VZ(50)**2)+0.5*(0.0016666666666666668*WX(50,0,50)**2+0.08416666666666667*WY(50,0,50)**2+0.08416666666666667*WZ(50,0,50)**2)+9.81*DY(50) + 0.5*(VX(60)**2+VY(60)**2+VZ(60)**2)+0.5*(0.08416666666666667*WX(60,0,60)**2+0.0016666666666666668*WY(60,0,60)**2+0.08416666666666667*WZ(60,0,60)**2)+9.81*DY(60)',
        cnames=['P3_x', 'P3_y', 'P3_z', 'energy'])
Integrator(error=1e-08)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=10.0, dtout=0.05)
