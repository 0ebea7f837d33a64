"""IFToMM A02 N-four-bar mechanism, N = 40, written by decks/joints/make_a02.py
(its docstring has the spec and every decision; do not edit by hand).
Source: http://lim.ii.udc.es/mbsbenchmark/dist/A02/A02_specification.xml : 2N+1 = 81
links of 1 m and 1 kg (uniform; transverse inertia 1/12 kg m^2, axial 0.0001 by
decision), gravity -9.81 y, 20 s, B0 (top of crank 0, marker 22) starts at +1 m/s in x.
Cranks: bodies 2..42 pivoted on ground at x = 0..40; couplers: bodies 1001..1040.
Joints: all REVOLUTE about global z; 605 equations on 486 coordinates
(120 redundant), 1 DOF away from the horizontal singular positions.
Compare: B0 position and velocity (channels 1-4) against iftomm_a02_fourbar in
benchmarks/data/joint_references.json (exact 1-DOF solution of the parallelogram
branch, 401 outputs every 0.05 s); spec tolerances 1e-1 / 1e-3. The singular horizontal
position is first reached at t = 0.7216 s; a solver that switches branch there departs
from the reference.

pysolver convert wrote this script of msolve classes from iftomm_a02_fourbar.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='iftomm_a02_fourbar')
Units(force='NEWTON', mass='KILOGRAM', length='METER', time='SECOND')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1, label='global')
Accgrav(igrav=0.0, jgrav=-9.81, kgrav=0.0)
marker1000 = Marker(id=1000, body=body1, qp=[0.0, 0.0, 0.0], label='ground pivot 0 (J)')
marker20 = Marker(id=20, qp=[0.0, 0.5, 0.0], label='crank 0 cm')
marker21 = Marker(id=21, qp=[0.0, 0.0, 0.0], label='crank 0 bottom (I)')
marker22 = Marker(id=22, qp=[0.0, 1.0, 0.0], label='crank 0 top = B0 (J)')
body2 = Part(id=2, mass=1.0, cm=marker20, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
             vx=0.5, wz=-1.0, label='crank 0')
marker20.body = body2
marker21.body = body2
marker22.body = body2
joint1 = Joint(id=1, type='REVOLUTE', i=marker21, j=marker1000, label='ground-crank 0')
marker1001 = Marker(id=1001, body=body1, qp=[1.0, 0.0, 0.0], label='ground pivot 1 (J)')
marker30 = Marker(id=30, qp=[1.0, 0.5, 0.0], label='crank 1 cm')
marker31 = Marker(id=31, qp=[1.0, 0.0, 0.0], label='crank 1 bottom (I)')
marker32 = Marker(id=32, qp=[1.0, 1.0, 0.0], label='crank 1 top (J)')
body3 = Part(id=3, mass=1.0, cm=marker30, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
             vx=0.5, wz=-1.0, label='crank 1')
marker30.body = body3
marker31.body = body3
marker32.body = body3
joint2 = Joint(id=2, type='REVOLUTE', i=marker31, j=marker1001, label='ground-crank 1')
marker1002 = Marker(id=1002, body=body1, qp=[2.0, 0.0, 0.0], label='ground pivot 2 (J)')
marker40 = Marker(id=40, qp=[2.0, 0.5, 0.0], label='crank 2 cm')
marker41 = Marker(id=41, qp=[2.0, 0.0, 0.0], label='crank 2 bottom (I)')
marker42 = Marker(id=42, qp=[2.0, 1.0, 0.0], label='crank 2 top (J)')
body4 = Part(id=4, mass=1.0, cm=marker40, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
             vx=0.5, wz=-1.0, label='crank 2')
marker40.body = body4
marker41.body = body4
marker42.body = body4
joint3 = Joint(id=3, type='REVOLUTE', i=marker41, j=marker1002, label='ground-crank 2')
marker1003 = Marker(id=1003, body=body1, qp=[3.0, 0.0, 0.0], label='ground pivot 3 (J)')
marker50 = Marker(id=50, qp=[3.0, 0.5, 0.0], label='crank 3 cm')
marker51 = Marker(id=51, qp=[3.0, 0.0, 0.0], label='crank 3 bottom (I)')
marker52 = Marker(id=52, qp=[3.0, 1.0, 0.0], label='crank 3 top (J)')
body5 = Part(id=5, mass=1.0, cm=marker50, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
             vx=0.5, wz=-1.0, label='crank 3')
marker50.body = body5
marker51.body = body5
marker52.body = body5
joint4 = Joint(id=4, type='REVOLUTE', i=marker51, j=marker1003, label='ground-crank 3')
marker1004 = Marker(id=1004, body=body1, qp=[4.0, 0.0, 0.0], label='ground pivot 4 (J)')
marker60 = Marker(id=60, qp=[4.0, 0.5, 0.0], label='crank 4 cm')
marker61 = Marker(id=61, qp=[4.0, 0.0, 0.0], label='crank 4 bottom (I)')
marker62 = Marker(id=62, qp=[4.0, 1.0, 0.0], label='crank 4 top (J)')
body6 = Part(id=6, mass=1.0, cm=marker60, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
             vx=0.5, wz=-1.0, label='crank 4')
marker60.body = body6
marker61.body = body6
marker62.body = body6
joint5 = Joint(id=5, type='REVOLUTE', i=marker61, j=marker1004, label='ground-crank 4')
marker1005 = Marker(id=1005, body=body1, qp=[5.0, 0.0, 0.0], label='ground pivot 5 (J)')
marker70 = Marker(id=70, qp=[5.0, 0.5, 0.0], label='crank 5 cm')
marker71 = Marker(id=71, qp=[5.0, 0.0, 0.0], label='crank 5 bottom (I)')
marker72 = Marker(id=72, qp=[5.0, 1.0, 0.0], label='crank 5 top (J)')
body7 = Part(id=7, mass=1.0, cm=marker70, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
             vx=0.5, wz=-1.0, label='crank 5')
marker70.body = body7
marker71.body = body7
marker72.body = body7
joint6 = Joint(id=6, type='REVOLUTE', i=marker71, j=marker1005, label='ground-crank 5')
marker1006 = Marker(id=1006, body=body1, qp=[6.0, 0.0, 0.0], label='ground pivot 6 (J)')
marker80 = Marker(id=80, qp=[6.0, 0.5, 0.0], label='crank 6 cm')
marker81 = Marker(id=81, qp=[6.0, 0.0, 0.0], label='crank 6 bottom (I)')
marker82 = Marker(id=82, qp=[6.0, 1.0, 0.0], label='crank 6 top (J)')
body8 = Part(id=8, mass=1.0, cm=marker80, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
             vx=0.5, wz=-1.0, label='crank 6')
marker80.body = body8
marker81.body = body8
marker82.body = body8
joint7 = Joint(id=7, type='REVOLUTE', i=marker81, j=marker1006, label='ground-crank 6')
marker1007 = Marker(id=1007, body=body1, qp=[7.0, 0.0, 0.0], label='ground pivot 7 (J)')
marker90 = Marker(id=90, qp=[7.0, 0.5, 0.0], label='crank 7 cm')
marker91 = Marker(id=91, qp=[7.0, 0.0, 0.0], label='crank 7 bottom (I)')
marker92 = Marker(id=92, qp=[7.0, 1.0, 0.0], label='crank 7 top (J)')
body9 = Part(id=9, mass=1.0, cm=marker90, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
             vx=0.5, wz=-1.0, label='crank 7')
marker90.body = body9
marker91.body = body9
marker92.body = body9
joint8 = Joint(id=8, type='REVOLUTE', i=marker91, j=marker1007, label='ground-crank 7')
marker1008 = Marker(id=1008, body=body1, qp=[8.0, 0.0, 0.0], label='ground pivot 8 (J)')
marker100 = Marker(id=100, qp=[8.0, 0.5, 0.0], label='crank 8 cm')
marker101 = Marker(id=101, qp=[8.0, 0.0, 0.0], label='crank 8 bottom (I)')
marker102 = Marker(id=102, qp=[8.0, 1.0, 0.0], label='crank 8 top (J)')
body10 = Part(id=10, mass=1.0, cm=marker100, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 8')
marker100.body = body10
marker101.body = body10
marker102.body = body10
joint9 = Joint(id=9, type='REVOLUTE', i=marker101, j=marker1008, label='ground-crank 8')
marker1009 = Marker(id=1009, body=body1, qp=[9.0, 0.0, 0.0], label='ground pivot 9 (J)')
marker110 = Marker(id=110, qp=[9.0, 0.5, 0.0], label='crank 9 cm')
marker111 = Marker(id=111, qp=[9.0, 0.0, 0.0], label='crank 9 bottom (I)')
marker112 = Marker(id=112, qp=[9.0, 1.0, 0.0], label='crank 9 top (J)')
body11 = Part(id=11, mass=1.0, cm=marker110, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 9')
marker110.body = body11
marker111.body = body11
marker112.body = body11
joint10 = Joint(id=10, type='REVOLUTE', i=marker111, j=marker1009, label='ground-crank 9')
marker1010 = Marker(id=1010, body=body1, qp=[10.0, 0.0, 0.0], label='ground pivot 10 (J)')
marker120 = Marker(id=120, qp=[10.0, 0.5, 0.0], label='crank 10 cm')
marker121 = Marker(id=121, qp=[10.0, 0.0, 0.0], label='crank 10 bottom (I)')
marker122 = Marker(id=122, qp=[10.0, 1.0, 0.0], label='crank 10 top (J)')
body12 = Part(id=12, mass=1.0, cm=marker120, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 10')
marker120.body = body12
marker121.body = body12
marker122.body = body12
joint11 = Joint(id=11, type='REVOLUTE', i=marker121, j=marker1010, label='ground-crank 10')
marker1011 = Marker(id=1011, body=body1, qp=[11.0, 0.0, 0.0], label='ground pivot 11 (J)')
marker130 = Marker(id=130, qp=[11.0, 0.5, 0.0], label='crank 11 cm')
marker131 = Marker(id=131, qp=[11.0, 0.0, 0.0], label='crank 11 bottom (I)')
marker132 = Marker(id=132, qp=[11.0, 1.0, 0.0], label='crank 11 top (J)')
body13 = Part(id=13, mass=1.0, cm=marker130, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 11')
marker130.body = body13
marker131.body = body13
marker132.body = body13
joint12 = Joint(id=12, type='REVOLUTE', i=marker131, j=marker1011, label='ground-crank 11')
marker1012 = Marker(id=1012, body=body1, qp=[12.0, 0.0, 0.0], label='ground pivot 12 (J)')
marker140 = Marker(id=140, qp=[12.0, 0.5, 0.0], label='crank 12 cm')
marker141 = Marker(id=141, qp=[12.0, 0.0, 0.0], label='crank 12 bottom (I)')
marker142 = Marker(id=142, qp=[12.0, 1.0, 0.0], label='crank 12 top (J)')
body14 = Part(id=14, mass=1.0, cm=marker140, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 12')
marker140.body = body14
marker141.body = body14
marker142.body = body14
joint13 = Joint(id=13, type='REVOLUTE', i=marker141, j=marker1012, label='ground-crank 12')
marker1013 = Marker(id=1013, body=body1, qp=[13.0, 0.0, 0.0], label='ground pivot 13 (J)')
marker150 = Marker(id=150, qp=[13.0, 0.5, 0.0], label='crank 13 cm')
marker151 = Marker(id=151, qp=[13.0, 0.0, 0.0], label='crank 13 bottom (I)')
marker152 = Marker(id=152, qp=[13.0, 1.0, 0.0], label='crank 13 top (J)')
body15 = Part(id=15, mass=1.0, cm=marker150, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 13')
marker150.body = body15
marker151.body = body15
marker152.body = body15
joint14 = Joint(id=14, type='REVOLUTE', i=marker151, j=marker1013, label='ground-crank 13')
marker1014 = Marker(id=1014, body=body1, qp=[14.0, 0.0, 0.0], label='ground pivot 14 (J)')
marker160 = Marker(id=160, qp=[14.0, 0.5, 0.0], label='crank 14 cm')
marker161 = Marker(id=161, qp=[14.0, 0.0, 0.0], label='crank 14 bottom (I)')
marker162 = Marker(id=162, qp=[14.0, 1.0, 0.0], label='crank 14 top (J)')
body16 = Part(id=16, mass=1.0, cm=marker160, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 14')
marker160.body = body16
marker161.body = body16
marker162.body = body16
joint15 = Joint(id=15, type='REVOLUTE', i=marker161, j=marker1014, label='ground-crank 14')
marker1015 = Marker(id=1015, body=body1, qp=[15.0, 0.0, 0.0], label='ground pivot 15 (J)')
marker170 = Marker(id=170, qp=[15.0, 0.5, 0.0], label='crank 15 cm')
marker171 = Marker(id=171, qp=[15.0, 0.0, 0.0], label='crank 15 bottom (I)')
marker172 = Marker(id=172, qp=[15.0, 1.0, 0.0], label='crank 15 top (J)')
body17 = Part(id=17, mass=1.0, cm=marker170, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 15')
marker170.body = body17
marker171.body = body17
marker172.body = body17
joint16 = Joint(id=16, type='REVOLUTE', i=marker171, j=marker1015, label='ground-crank 15')
marker1016 = Marker(id=1016, body=body1, qp=[16.0, 0.0, 0.0], label='ground pivot 16 (J)')
marker180 = Marker(id=180, qp=[16.0, 0.5, 0.0], label='crank 16 cm')
marker181 = Marker(id=181, qp=[16.0, 0.0, 0.0], label='crank 16 bottom (I)')
marker182 = Marker(id=182, qp=[16.0, 1.0, 0.0], label='crank 16 top (J)')
body18 = Part(id=18, mass=1.0, cm=marker180, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 16')
marker180.body = body18
marker181.body = body18
marker182.body = body18
joint17 = Joint(id=17, type='REVOLUTE', i=marker181, j=marker1016, label='ground-crank 16')
marker1017 = Marker(id=1017, body=body1, qp=[17.0, 0.0, 0.0], label='ground pivot 17 (J)')
marker190 = Marker(id=190, qp=[17.0, 0.5, 0.0], label='crank 17 cm')
marker191 = Marker(id=191, qp=[17.0, 0.0, 0.0], label='crank 17 bottom (I)')
marker192 = Marker(id=192, qp=[17.0, 1.0, 0.0], label='crank 17 top (J)')
body19 = Part(id=19, mass=1.0, cm=marker190, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 17')
marker190.body = body19
marker191.body = body19
marker192.body = body19
joint18 = Joint(id=18, type='REVOLUTE', i=marker191, j=marker1017, label='ground-crank 17')
marker1018 = Marker(id=1018, body=body1, qp=[18.0, 0.0, 0.0], label='ground pivot 18 (J)')
marker200 = Marker(id=200, qp=[18.0, 0.5, 0.0], label='crank 18 cm')
marker201 = Marker(id=201, qp=[18.0, 0.0, 0.0], label='crank 18 bottom (I)')
marker202 = Marker(id=202, qp=[18.0, 1.0, 0.0], label='crank 18 top (J)')
body20 = Part(id=20, mass=1.0, cm=marker200, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 18')
marker200.body = body20
marker201.body = body20
marker202.body = body20
joint19 = Joint(id=19, type='REVOLUTE', i=marker201, j=marker1018, label='ground-crank 18')
marker1019 = Marker(id=1019, body=body1, qp=[19.0, 0.0, 0.0], label='ground pivot 19 (J)')
marker210 = Marker(id=210, qp=[19.0, 0.5, 0.0], label='crank 19 cm')
marker211 = Marker(id=211, qp=[19.0, 0.0, 0.0], label='crank 19 bottom (I)')
marker212 = Marker(id=212, qp=[19.0, 1.0, 0.0], label='crank 19 top (J)')
body21 = Part(id=21, mass=1.0, cm=marker210, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 19')
marker210.body = body21
marker211.body = body21
marker212.body = body21
joint20 = Joint(id=20, type='REVOLUTE', i=marker211, j=marker1019, label='ground-crank 19')
marker1020 = Marker(id=1020, body=body1, qp=[20.0, 0.0, 0.0], label='ground pivot 20 (J)')
marker220 = Marker(id=220, qp=[20.0, 0.5, 0.0], label='crank 20 cm')
marker221 = Marker(id=221, qp=[20.0, 0.0, 0.0], label='crank 20 bottom (I)')
marker222 = Marker(id=222, qp=[20.0, 1.0, 0.0], label='crank 20 top (J)')
body22 = Part(id=22, mass=1.0, cm=marker220, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 20')
marker220.body = body22
marker221.body = body22
marker222.body = body22
joint21 = Joint(id=21, type='REVOLUTE', i=marker221, j=marker1020, label='ground-crank 20')
marker1021 = Marker(id=1021, body=body1, qp=[21.0, 0.0, 0.0], label='ground pivot 21 (J)')
marker230 = Marker(id=230, qp=[21.0, 0.5, 0.0], label='crank 21 cm')
marker231 = Marker(id=231, qp=[21.0, 0.0, 0.0], label='crank 21 bottom (I)')
marker232 = Marker(id=232, qp=[21.0, 1.0, 0.0], label='crank 21 top (J)')
body23 = Part(id=23, mass=1.0, cm=marker230, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 21')
marker230.body = body23
marker231.body = body23
marker232.body = body23
joint22 = Joint(id=22, type='REVOLUTE', i=marker231, j=marker1021, label='ground-crank 21')
marker1022 = Marker(id=1022, body=body1, qp=[22.0, 0.0, 0.0], label='ground pivot 22 (J)')
marker240 = Marker(id=240, qp=[22.0, 0.5, 0.0], label='crank 22 cm')
marker241 = Marker(id=241, qp=[22.0, 0.0, 0.0], label='crank 22 bottom (I)')
marker242 = Marker(id=242, qp=[22.0, 1.0, 0.0], label='crank 22 top (J)')
body24 = Part(id=24, mass=1.0, cm=marker240, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 22')
marker240.body = body24
marker241.body = body24
marker242.body = body24
joint23 = Joint(id=23, type='REVOLUTE', i=marker241, j=marker1022, label='ground-crank 22')
marker1023 = Marker(id=1023, body=body1, qp=[23.0, 0.0, 0.0], label='ground pivot 23 (J)')
marker250 = Marker(id=250, qp=[23.0, 0.5, 0.0], label='crank 23 cm')
marker251 = Marker(id=251, qp=[23.0, 0.0, 0.0], label='crank 23 bottom (I)')
marker252 = Marker(id=252, qp=[23.0, 1.0, 0.0], label='crank 23 top (J)')
body25 = Part(id=25, mass=1.0, cm=marker250, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 23')
marker250.body = body25
marker251.body = body25
marker252.body = body25
joint24 = Joint(id=24, type='REVOLUTE', i=marker251, j=marker1023, label='ground-crank 23')
marker1024 = Marker(id=1024, body=body1, qp=[24.0, 0.0, 0.0], label='ground pivot 24 (J)')
marker260 = Marker(id=260, qp=[24.0, 0.5, 0.0], label='crank 24 cm')
marker261 = Marker(id=261, qp=[24.0, 0.0, 0.0], label='crank 24 bottom (I)')
marker262 = Marker(id=262, qp=[24.0, 1.0, 0.0], label='crank 24 top (J)')
body26 = Part(id=26, mass=1.0, cm=marker260, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 24')
marker260.body = body26
marker261.body = body26
marker262.body = body26
joint25 = Joint(id=25, type='REVOLUTE', i=marker261, j=marker1024, label='ground-crank 24')
marker1025 = Marker(id=1025, body=body1, qp=[25.0, 0.0, 0.0], label='ground pivot 25 (J)')
marker270 = Marker(id=270, qp=[25.0, 0.5, 0.0], label='crank 25 cm')
marker271 = Marker(id=271, qp=[25.0, 0.0, 0.0], label='crank 25 bottom (I)')
marker272 = Marker(id=272, qp=[25.0, 1.0, 0.0], label='crank 25 top (J)')
body27 = Part(id=27, mass=1.0, cm=marker270, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 25')
marker270.body = body27
marker271.body = body27
marker272.body = body27
joint26 = Joint(id=26, type='REVOLUTE', i=marker271, j=marker1025, label='ground-crank 25')
marker1026 = Marker(id=1026, body=body1, qp=[26.0, 0.0, 0.0], label='ground pivot 26 (J)')
marker280 = Marker(id=280, qp=[26.0, 0.5, 0.0], label='crank 26 cm')
marker281 = Marker(id=281, qp=[26.0, 0.0, 0.0], label='crank 26 bottom (I)')
marker282 = Marker(id=282, qp=[26.0, 1.0, 0.0], label='crank 26 top (J)')
body28 = Part(id=28, mass=1.0, cm=marker280, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 26')
marker280.body = body28
marker281.body = body28
marker282.body = body28
joint27 = Joint(id=27, type='REVOLUTE', i=marker281, j=marker1026, label='ground-crank 26')
marker1027 = Marker(id=1027, body=body1, qp=[27.0, 0.0, 0.0], label='ground pivot 27 (J)')
marker290 = Marker(id=290, qp=[27.0, 0.5, 0.0], label='crank 27 cm')
marker291 = Marker(id=291, qp=[27.0, 0.0, 0.0], label='crank 27 bottom (I)')
marker292 = Marker(id=292, qp=[27.0, 1.0, 0.0], label='crank 27 top (J)')
body29 = Part(id=29, mass=1.0, cm=marker290, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 27')
marker290.body = body29
marker291.body = body29
marker292.body = body29
joint28 = Joint(id=28, type='REVOLUTE', i=marker291, j=marker1027, label='ground-crank 27')
marker1028 = Marker(id=1028, body=body1, qp=[28.0, 0.0, 0.0], label='ground pivot 28 (J)')
marker300 = Marker(id=300, qp=[28.0, 0.5, 0.0], label='crank 28 cm')
marker301 = Marker(id=301, qp=[28.0, 0.0, 0.0], label='crank 28 bottom (I)')
marker302 = Marker(id=302, qp=[28.0, 1.0, 0.0], label='crank 28 top (J)')
body30 = Part(id=30, mass=1.0, cm=marker300, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 28')
marker300.body = body30
marker301.body = body30
marker302.body = body30
joint29 = Joint(id=29, type='REVOLUTE', i=marker301, j=marker1028, label='ground-crank 28')
marker1029 = Marker(id=1029, body=body1, qp=[29.0, 0.0, 0.0], label='ground pivot 29 (J)')
marker310 = Marker(id=310, qp=[29.0, 0.5, 0.0], label='crank 29 cm')
marker311 = Marker(id=311, qp=[29.0, 0.0, 0.0], label='crank 29 bottom (I)')
marker312 = Marker(id=312, qp=[29.0, 1.0, 0.0], label='crank 29 top (J)')
body31 = Part(id=31, mass=1.0, cm=marker310, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 29')
marker310.body = body31
marker311.body = body31
marker312.body = body31
joint30 = Joint(id=30, type='REVOLUTE', i=marker311, j=marker1029, label='ground-crank 29')
marker1030 = Marker(id=1030, body=body1, qp=[30.0, 0.0, 0.0], label='ground pivot 30 (J)')
marker320 = Marker(id=320, qp=[30.0, 0.5, 0.0], label='crank 30 cm')
marker321 = Marker(id=321, qp=[30.0, 0.0, 0.0], label='crank 30 bottom (I)')
marker322 = Marker(id=322, qp=[30.0, 1.0, 0.0], label='crank 30 top (J)')
body32 = Part(id=32, mass=1.0, cm=marker320, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 30')
marker320.body = body32
marker321.body = body32
marker322.body = body32
joint31 = Joint(id=31, type='REVOLUTE', i=marker321, j=marker1030, label='ground-crank 30')
marker1031 = Marker(id=1031, body=body1, qp=[31.0, 0.0, 0.0], label='ground pivot 31 (J)')
marker330 = Marker(id=330, qp=[31.0, 0.5, 0.0], label='crank 31 cm')
marker331 = Marker(id=331, qp=[31.0, 0.0, 0.0], label='crank 31 bottom (I)')
marker332 = Marker(id=332, qp=[31.0, 1.0, 0.0], label='crank 31 top (J)')
body33 = Part(id=33, mass=1.0, cm=marker330, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 31')
marker330.body = body33
marker331.body = body33
marker332.body = body33
joint32 = Joint(id=32, type='REVOLUTE', i=marker331, j=marker1031, label='ground-crank 31')
marker1032 = Marker(id=1032, body=body1, qp=[32.0, 0.0, 0.0], label='ground pivot 32 (J)')
marker340 = Marker(id=340, qp=[32.0, 0.5, 0.0], label='crank 32 cm')
marker341 = Marker(id=341, qp=[32.0, 0.0, 0.0], label='crank 32 bottom (I)')
marker342 = Marker(id=342, qp=[32.0, 1.0, 0.0], label='crank 32 top (J)')
body34 = Part(id=34, mass=1.0, cm=marker340, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 32')
marker340.body = body34
marker341.body = body34
marker342.body = body34
joint33 = Joint(id=33, type='REVOLUTE', i=marker341, j=marker1032, label='ground-crank 32')
marker1033 = Marker(id=1033, body=body1, qp=[33.0, 0.0, 0.0], label='ground pivot 33 (J)')
marker350 = Marker(id=350, qp=[33.0, 0.5, 0.0], label='crank 33 cm')
marker351 = Marker(id=351, qp=[33.0, 0.0, 0.0], label='crank 33 bottom (I)')
marker352 = Marker(id=352, qp=[33.0, 1.0, 0.0], label='crank 33 top (J)')
body35 = Part(id=35, mass=1.0, cm=marker350, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 33')
marker350.body = body35
marker351.body = body35
marker352.body = body35
joint34 = Joint(id=34, type='REVOLUTE', i=marker351, j=marker1033, label='ground-crank 33')
marker1034 = Marker(id=1034, body=body1, qp=[34.0, 0.0, 0.0], label='ground pivot 34 (J)')
marker360 = Marker(id=360, qp=[34.0, 0.5, 0.0], label='crank 34 cm')
marker361 = Marker(id=361, qp=[34.0, 0.0, 0.0], label='crank 34 bottom (I)')
marker362 = Marker(id=362, qp=[34.0, 1.0, 0.0], label='crank 34 top (J)')
body36 = Part(id=36, mass=1.0, cm=marker360, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 34')
marker360.body = body36
marker361.body = body36
marker362.body = body36
joint35 = Joint(id=35, type='REVOLUTE', i=marker361, j=marker1034, label='ground-crank 34')
marker1035 = Marker(id=1035, body=body1, qp=[35.0, 0.0, 0.0], label='ground pivot 35 (J)')
marker370 = Marker(id=370, qp=[35.0, 0.5, 0.0], label='crank 35 cm')
marker371 = Marker(id=371, qp=[35.0, 0.0, 0.0], label='crank 35 bottom (I)')
marker372 = Marker(id=372, qp=[35.0, 1.0, 0.0], label='crank 35 top (J)')
body37 = Part(id=37, mass=1.0, cm=marker370, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 35')
marker370.body = body37
marker371.body = body37
marker372.body = body37
joint36 = Joint(id=36, type='REVOLUTE', i=marker371, j=marker1035, label='ground-crank 35')
marker1036 = Marker(id=1036, body=body1, qp=[36.0, 0.0, 0.0], label='ground pivot 36 (J)')
marker380 = Marker(id=380, qp=[36.0, 0.5, 0.0], label='crank 36 cm')
marker381 = Marker(id=381, qp=[36.0, 0.0, 0.0], label='crank 36 bottom (I)')
marker382 = Marker(id=382, qp=[36.0, 1.0, 0.0], label='crank 36 top (J)')
body38 = Part(id=38, mass=1.0, cm=marker380, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 36')
marker380.body = body38
marker381.body = body38
marker382.body = body38
joint37 = Joint(id=37, type='REVOLUTE', i=marker381, j=marker1036, label='ground-crank 36')
marker1037 = Marker(id=1037, body=body1, qp=[37.0, 0.0, 0.0], label='ground pivot 37 (J)')
marker390 = Marker(id=390, qp=[37.0, 0.5, 0.0], label='crank 37 cm')
marker391 = Marker(id=391, qp=[37.0, 0.0, 0.0], label='crank 37 bottom (I)')
marker392 = Marker(id=392, qp=[37.0, 1.0, 0.0], label='crank 37 top (J)')
body39 = Part(id=39, mass=1.0, cm=marker390, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 37')
marker390.body = body39
marker391.body = body39
marker392.body = body39
joint38 = Joint(id=38, type='REVOLUTE', i=marker391, j=marker1037, label='ground-crank 37')
marker1038 = Marker(id=1038, body=body1, qp=[38.0, 0.0, 0.0], label='ground pivot 38 (J)')
marker400 = Marker(id=400, qp=[38.0, 0.5, 0.0], label='crank 38 cm')
marker401 = Marker(id=401, qp=[38.0, 0.0, 0.0], label='crank 38 bottom (I)')
marker402 = Marker(id=402, qp=[38.0, 1.0, 0.0], label='crank 38 top (J)')
body40 = Part(id=40, mass=1.0, cm=marker400, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 38')
marker400.body = body40
marker401.body = body40
marker402.body = body40
joint39 = Joint(id=39, type='REVOLUTE', i=marker401, j=marker1038, label='ground-crank 38')
marker1039 = Marker(id=1039, body=body1, qp=[39.0, 0.0, 0.0], label='ground pivot 39 (J)')
marker410 = Marker(id=410, qp=[39.0, 0.5, 0.0], label='crank 39 cm')
marker411 = Marker(id=411, qp=[39.0, 0.0, 0.0], label='crank 39 bottom (I)')
marker412 = Marker(id=412, qp=[39.0, 1.0, 0.0], label='crank 39 top (J)')
body41 = Part(id=41, mass=1.0, cm=marker410, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 39')
marker410.body = body41
marker411.body = body41
marker412.body = body41
joint40 = Joint(id=40, type='REVOLUTE', i=marker411, j=marker1039, label='ground-crank 39')
marker1040 = Marker(id=1040, body=body1, qp=[40.0, 0.0, 0.0], label='ground pivot 40 (J)')
marker420 = Marker(id=420, qp=[40.0, 0.5, 0.0], label='crank 40 cm')
marker421 = Marker(id=421, qp=[40.0, 0.0, 0.0], label='crank 40 bottom (I)')
marker422 = Marker(id=422, qp=[40.0, 1.0, 0.0], label='crank 40 top (J)')
body42 = Part(id=42, mass=1.0, cm=marker420, ip=[0.08333333333333333, 0.0001, 0.08333333333333333],
              vx=0.5, wz=-1.0, label='crank 40')
marker420.body = body42
marker421.body = body42
marker422.body = body42
joint41 = Joint(id=41, type='REVOLUTE', i=marker421, j=marker1040, label='ground-crank 40')
marker10010 = Marker(id=10010, qp=[0.5, 1.0, 0.0], label='coupler 1 cm')
marker10011 = Marker(id=10011, qp=[0.0, 1.0, 0.0], label='coupler 1 left (I)')
marker10012 = Marker(id=10012, qp=[1.0, 1.0, 0.0], label='coupler 1 right (I)')
body1001 = Part(id=1001, mass=1.0, cm=marker10010,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 1')
marker10010.body = body1001
marker10011.body = body1001
marker10012.body = body1001
joint42 = Joint(id=42, type='REVOLUTE', i=marker10011, j=marker22, label='crank 0-coupler 1')
joint43 = Joint(id=43, type='REVOLUTE', i=marker10012, j=marker32, label='coupler 1-crank 1')
marker10020 = Marker(id=10020, qp=[1.5, 1.0, 0.0], label='coupler 2 cm')
marker10021 = Marker(id=10021, qp=[1.0, 1.0, 0.0], label='coupler 2 left (I)')
marker10022 = Marker(id=10022, qp=[2.0, 1.0, 0.0], label='coupler 2 right (I)')
body1002 = Part(id=1002, mass=1.0, cm=marker10020,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 2')
marker10020.body = body1002
marker10021.body = body1002
marker10022.body = body1002
joint44 = Joint(id=44, type='REVOLUTE', i=marker10021, j=marker32, label='crank 1-coupler 2')
joint45 = Joint(id=45, type='REVOLUTE', i=marker10022, j=marker42, label='coupler 2-crank 2')
marker10030 = Marker(id=10030, qp=[2.5, 1.0, 0.0], label='coupler 3 cm')
marker10031 = Marker(id=10031, qp=[2.0, 1.0, 0.0], label='coupler 3 left (I)')
marker10032 = Marker(id=10032, qp=[3.0, 1.0, 0.0], label='coupler 3 right (I)')
body1003 = Part(id=1003, mass=1.0, cm=marker10030,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 3')
marker10030.body = body1003
marker10031.body = body1003
marker10032.body = body1003
joint46 = Joint(id=46, type='REVOLUTE', i=marker10031, j=marker42, label='crank 2-coupler 3')
joint47 = Joint(id=47, type='REVOLUTE', i=marker10032, j=marker52, label='coupler 3-crank 3')
marker10040 = Marker(id=10040, qp=[3.5, 1.0, 0.0], label='coupler 4 cm')
marker10041 = Marker(id=10041, qp=[3.0, 1.0, 0.0], label='coupler 4 left (I)')
marker10042 = Marker(id=10042, qp=[4.0, 1.0, 0.0], label='coupler 4 right (I)')
body1004 = Part(id=1004, mass=1.0, cm=marker10040,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 4')
marker10040.body = body1004
marker10041.body = body1004
marker10042.body = body1004
joint48 = Joint(id=48, type='REVOLUTE', i=marker10041, j=marker52, label='crank 3-coupler 4')
joint49 = Joint(id=49, type='REVOLUTE', i=marker10042, j=marker62, label='coupler 4-crank 4')
marker10050 = Marker(id=10050, qp=[4.5, 1.0, 0.0], label='coupler 5 cm')
marker10051 = Marker(id=10051, qp=[4.0, 1.0, 0.0], label='coupler 5 left (I)')
marker10052 = Marker(id=10052, qp=[5.0, 1.0, 0.0], label='coupler 5 right (I)')
body1005 = Part(id=1005, mass=1.0, cm=marker10050,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 5')
marker10050.body = body1005
marker10051.body = body1005
marker10052.body = body1005
joint50 = Joint(id=50, type='REVOLUTE', i=marker10051, j=marker62, label='crank 4-coupler 5')
joint51 = Joint(id=51, type='REVOLUTE', i=marker10052, j=marker72, label='coupler 5-crank 5')
marker10060 = Marker(id=10060, qp=[5.5, 1.0, 0.0], label='coupler 6 cm')
marker10061 = Marker(id=10061, qp=[5.0, 1.0, 0.0], label='coupler 6 left (I)')
marker10062 = Marker(id=10062, qp=[6.0, 1.0, 0.0], label='coupler 6 right (I)')
body1006 = Part(id=1006, mass=1.0, cm=marker10060,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 6')
marker10060.body = body1006
marker10061.body = body1006
marker10062.body = body1006
joint52 = Joint(id=52, type='REVOLUTE', i=marker10061, j=marker72, label='crank 5-coupler 6')
joint53 = Joint(id=53, type='REVOLUTE', i=marker10062, j=marker82, label='coupler 6-crank 6')
marker10070 = Marker(id=10070, qp=[6.5, 1.0, 0.0], label='coupler 7 cm')
marker10071 = Marker(id=10071, qp=[6.0, 1.0, 0.0], label='coupler 7 left (I)')
marker10072 = Marker(id=10072, qp=[7.0, 1.0, 0.0], label='coupler 7 right (I)')
body1007 = Part(id=1007, mass=1.0, cm=marker10070,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 7')
marker10070.body = body1007
marker10071.body = body1007
marker10072.body = body1007
joint54 = Joint(id=54, type='REVOLUTE', i=marker10071, j=marker82, label='crank 6-coupler 7')
joint55 = Joint(id=55, type='REVOLUTE', i=marker10072, j=marker92, label='coupler 7-crank 7')
marker10080 = Marker(id=10080, qp=[7.5, 1.0, 0.0], label='coupler 8 cm')
marker10081 = Marker(id=10081, qp=[7.0, 1.0, 0.0], label='coupler 8 left (I)')
marker10082 = Marker(id=10082, qp=[8.0, 1.0, 0.0], label='coupler 8 right (I)')
body1008 = Part(id=1008, mass=1.0, cm=marker10080,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 8')
marker10080.body = body1008
marker10081.body = body1008
marker10082.body = body1008
joint56 = Joint(id=56, type='REVOLUTE', i=marker10081, j=marker92, label='crank 7-coupler 8')
joint57 = Joint(id=57, type='REVOLUTE', i=marker10082, j=marker102, label='coupler 8-crank 8')
marker10090 = Marker(id=10090, qp=[8.5, 1.0, 0.0], label='coupler 9 cm')
marker10091 = Marker(id=10091, qp=[8.0, 1.0, 0.0], label='coupler 9 left (I)')
marker10092 = Marker(id=10092, qp=[9.0, 1.0, 0.0], label='coupler 9 right (I)')
body1009 = Part(id=1009, mass=1.0, cm=marker10090,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 9')
marker10090.body = body1009
marker10091.body = body1009
marker10092.body = body1009
joint58 = Joint(id=58, type='REVOLUTE', i=marker10091, j=marker102, label='crank 8-coupler 9')
joint59 = Joint(id=59, type='REVOLUTE', i=marker10092, j=marker112, label='coupler 9-crank 9')
marker10100 = Marker(id=10100, qp=[9.5, 1.0, 0.0], label='coupler 10 cm')
marker10101 = Marker(id=10101, qp=[9.0, 1.0, 0.0], label='coupler 10 left (I)')
marker10102 = Marker(id=10102, qp=[10.0, 1.0, 0.0], label='coupler 10 right (I)')
body1010 = Part(id=1010, mass=1.0, cm=marker10100,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 10')
marker10100.body = body1010
marker10101.body = body1010
marker10102.body = body1010
joint60 = Joint(id=60, type='REVOLUTE', i=marker10101, j=marker112, label='crank 9-coupler 10')
joint61 = Joint(id=61, type='REVOLUTE', i=marker10102, j=marker122, label='coupler 10-crank 10')
marker10110 = Marker(id=10110, qp=[10.5, 1.0, 0.0], label='coupler 11 cm')
marker10111 = Marker(id=10111, qp=[10.0, 1.0, 0.0], label='coupler 11 left (I)')
marker10112 = Marker(id=10112, qp=[11.0, 1.0, 0.0], label='coupler 11 right (I)')
body1011 = Part(id=1011, mass=1.0, cm=marker10110,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 11')
marker10110.body = body1011
marker10111.body = body1011
marker10112.body = body1011
joint62 = Joint(id=62, type='REVOLUTE', i=marker10111, j=marker122, label='crank 10-coupler 11')
joint63 = Joint(id=63, type='REVOLUTE', i=marker10112, j=marker132, label='coupler 11-crank 11')
marker10120 = Marker(id=10120, qp=[11.5, 1.0, 0.0], label='coupler 12 cm')
marker10121 = Marker(id=10121, qp=[11.0, 1.0, 0.0], label='coupler 12 left (I)')
marker10122 = Marker(id=10122, qp=[12.0, 1.0, 0.0], label='coupler 12 right (I)')
body1012 = Part(id=1012, mass=1.0, cm=marker10120,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 12')
marker10120.body = body1012
marker10121.body = body1012
marker10122.body = body1012
joint64 = Joint(id=64, type='REVOLUTE', i=marker10121, j=marker132, label='crank 11-coupler 12')
joint65 = Joint(id=65, type='REVOLUTE', i=marker10122, j=marker142, label='coupler 12-crank 12')
marker10130 = Marker(id=10130, qp=[12.5, 1.0, 0.0], label='coupler 13 cm')
marker10131 = Marker(id=10131, qp=[12.0, 1.0, 0.0], label='coupler 13 left (I)')
marker10132 = Marker(id=10132, qp=[13.0, 1.0, 0.0], label='coupler 13 right (I)')
body1013 = Part(id=1013, mass=1.0, cm=marker10130,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 13')
marker10130.body = body1013
marker10131.body = body1013
marker10132.body = body1013
joint66 = Joint(id=66, type='REVOLUTE', i=marker10131, j=marker142, label='crank 12-coupler 13')
joint67 = Joint(id=67, type='REVOLUTE', i=marker10132, j=marker152, label='coupler 13-crank 13')
marker10140 = Marker(id=10140, qp=[13.5, 1.0, 0.0], label='coupler 14 cm')
marker10141 = Marker(id=10141, qp=[13.0, 1.0, 0.0], label='coupler 14 left (I)')
marker10142 = Marker(id=10142, qp=[14.0, 1.0, 0.0], label='coupler 14 right (I)')
body1014 = Part(id=1014, mass=1.0, cm=marker10140,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 14')
marker10140.body = body1014
marker10141.body = body1014
marker10142.body = body1014
joint68 = Joint(id=68, type='REVOLUTE', i=marker10141, j=marker152, label='crank 13-coupler 14')
joint69 = Joint(id=69, type='REVOLUTE', i=marker10142, j=marker162, label='coupler 14-crank 14')
marker10150 = Marker(id=10150, qp=[14.5, 1.0, 0.0], label='coupler 15 cm')
marker10151 = Marker(id=10151, qp=[14.0, 1.0, 0.0], label='coupler 15 left (I)')
marker10152 = Marker(id=10152, qp=[15.0, 1.0, 0.0], label='coupler 15 right (I)')
body1015 = Part(id=1015, mass=1.0, cm=marker10150,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 15')
marker10150.body = body1015
marker10151.body = body1015
marker10152.body = body1015
joint70 = Joint(id=70, type='REVOLUTE', i=marker10151, j=marker162, label='crank 14-coupler 15')
joint71 = Joint(id=71, type='REVOLUTE', i=marker10152, j=marker172, label='coupler 15-crank 15')
marker10160 = Marker(id=10160, qp=[15.5, 1.0, 0.0], label='coupler 16 cm')
marker10161 = Marker(id=10161, qp=[15.0, 1.0, 0.0], label='coupler 16 left (I)')
marker10162 = Marker(id=10162, qp=[16.0, 1.0, 0.0], label='coupler 16 right (I)')
body1016 = Part(id=1016, mass=1.0, cm=marker10160,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 16')
marker10160.body = body1016
marker10161.body = body1016
marker10162.body = body1016
joint72 = Joint(id=72, type='REVOLUTE', i=marker10161, j=marker172, label='crank 15-coupler 16')
joint73 = Joint(id=73, type='REVOLUTE', i=marker10162, j=marker182, label='coupler 16-crank 16')
marker10170 = Marker(id=10170, qp=[16.5, 1.0, 0.0], label='coupler 17 cm')
marker10171 = Marker(id=10171, qp=[16.0, 1.0, 0.0], label='coupler 17 left (I)')
marker10172 = Marker(id=10172, qp=[17.0, 1.0, 0.0], label='coupler 17 right (I)')
body1017 = Part(id=1017, mass=1.0, cm=marker10170,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 17')
marker10170.body = body1017
marker10171.body = body1017
marker10172.body = body1017
joint74 = Joint(id=74, type='REVOLUTE', i=marker10171, j=marker182, label='crank 16-coupler 17')
joint75 = Joint(id=75, type='REVOLUTE', i=marker10172, j=marker192, label='coupler 17-crank 17')
marker10180 = Marker(id=10180, qp=[17.5, 1.0, 0.0], label='coupler 18 cm')
marker10181 = Marker(id=10181, qp=[17.0, 1.0, 0.0], label='coupler 18 left (I)')
marker10182 = Marker(id=10182, qp=[18.0, 1.0, 0.0], label='coupler 18 right (I)')
body1018 = Part(id=1018, mass=1.0, cm=marker10180,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 18')
marker10180.body = body1018
marker10181.body = body1018
marker10182.body = body1018
joint76 = Joint(id=76, type='REVOLUTE', i=marker10181, j=marker192, label='crank 17-coupler 18')
joint77 = Joint(id=77, type='REVOLUTE', i=marker10182, j=marker202, label='coupler 18-crank 18')
marker10190 = Marker(id=10190, qp=[18.5, 1.0, 0.0], label='coupler 19 cm')
marker10191 = Marker(id=10191, qp=[18.0, 1.0, 0.0], label='coupler 19 left (I)')
marker10192 = Marker(id=10192, qp=[19.0, 1.0, 0.0], label='coupler 19 right (I)')
body1019 = Part(id=1019, mass=1.0, cm=marker10190,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 19')
marker10190.body = body1019
marker10191.body = body1019
marker10192.body = body1019
joint78 = Joint(id=78, type='REVOLUTE', i=marker10191, j=marker202, label='crank 18-coupler 19')
joint79 = Joint(id=79, type='REVOLUTE', i=marker10192, j=marker212, label='coupler 19-crank 19')
marker10200 = Marker(id=10200, qp=[19.5, 1.0, 0.0], label='coupler 20 cm')
marker10201 = Marker(id=10201, qp=[19.0, 1.0, 0.0], label='coupler 20 left (I)')
marker10202 = Marker(id=10202, qp=[20.0, 1.0, 0.0], label='coupler 20 right (I)')
body1020 = Part(id=1020, mass=1.0, cm=marker10200,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 20')
marker10200.body = body1020
marker10201.body = body1020
marker10202.body = body1020
joint80 = Joint(id=80, type='REVOLUTE', i=marker10201, j=marker212, label='crank 19-coupler 20')
joint81 = Joint(id=81, type='REVOLUTE', i=marker10202, j=marker222, label='coupler 20-crank 20')
marker10210 = Marker(id=10210, qp=[20.5, 1.0, 0.0], label='coupler 21 cm')
marker10211 = Marker(id=10211, qp=[20.0, 1.0, 0.0], label='coupler 21 left (I)')
marker10212 = Marker(id=10212, qp=[21.0, 1.0, 0.0], label='coupler 21 right (I)')
body1021 = Part(id=1021, mass=1.0, cm=marker10210,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 21')
marker10210.body = body1021
marker10211.body = body1021
marker10212.body = body1021
joint82 = Joint(id=82, type='REVOLUTE', i=marker10211, j=marker222, label='crank 20-coupler 21')
joint83 = Joint(id=83, type='REVOLUTE', i=marker10212, j=marker232, label='coupler 21-crank 21')
marker10220 = Marker(id=10220, qp=[21.5, 1.0, 0.0], label='coupler 22 cm')
marker10221 = Marker(id=10221, qp=[21.0, 1.0, 0.0], label='coupler 22 left (I)')
marker10222 = Marker(id=10222, qp=[22.0, 1.0, 0.0], label='coupler 22 right (I)')
body1022 = Part(id=1022, mass=1.0, cm=marker10220,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 22')
marker10220.body = body1022
marker10221.body = body1022
marker10222.body = body1022
joint84 = Joint(id=84, type='REVOLUTE', i=marker10221, j=marker232, label='crank 21-coupler 22')
joint85 = Joint(id=85, type='REVOLUTE', i=marker10222, j=marker242, label='coupler 22-crank 22')
marker10230 = Marker(id=10230, qp=[22.5, 1.0, 0.0], label='coupler 23 cm')
marker10231 = Marker(id=10231, qp=[22.0, 1.0, 0.0], label='coupler 23 left (I)')
marker10232 = Marker(id=10232, qp=[23.0, 1.0, 0.0], label='coupler 23 right (I)')
body1023 = Part(id=1023, mass=1.0, cm=marker10230,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 23')
marker10230.body = body1023
marker10231.body = body1023
marker10232.body = body1023
joint86 = Joint(id=86, type='REVOLUTE', i=marker10231, j=marker242, label='crank 22-coupler 23')
joint87 = Joint(id=87, type='REVOLUTE', i=marker10232, j=marker252, label='coupler 23-crank 23')
marker10240 = Marker(id=10240, qp=[23.5, 1.0, 0.0], label='coupler 24 cm')
marker10241 = Marker(id=10241, qp=[23.0, 1.0, 0.0], label='coupler 24 left (I)')
marker10242 = Marker(id=10242, qp=[24.0, 1.0, 0.0], label='coupler 24 right (I)')
body1024 = Part(id=1024, mass=1.0, cm=marker10240,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 24')
marker10240.body = body1024
marker10241.body = body1024
marker10242.body = body1024
joint88 = Joint(id=88, type='REVOLUTE', i=marker10241, j=marker252, label='crank 23-coupler 24')
joint89 = Joint(id=89, type='REVOLUTE', i=marker10242, j=marker262, label='coupler 24-crank 24')
marker10250 = Marker(id=10250, qp=[24.5, 1.0, 0.0], label='coupler 25 cm')
marker10251 = Marker(id=10251, qp=[24.0, 1.0, 0.0], label='coupler 25 left (I)')
marker10252 = Marker(id=10252, qp=[25.0, 1.0, 0.0], label='coupler 25 right (I)')
body1025 = Part(id=1025, mass=1.0, cm=marker10250,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 25')
marker10250.body = body1025
marker10251.body = body1025
marker10252.body = body1025
joint90 = Joint(id=90, type='REVOLUTE', i=marker10251, j=marker262, label='crank 24-coupler 25')
joint91 = Joint(id=91, type='REVOLUTE', i=marker10252, j=marker272, label='coupler 25-crank 25')
marker10260 = Marker(id=10260, qp=[25.5, 1.0, 0.0], label='coupler 26 cm')
marker10261 = Marker(id=10261, qp=[25.0, 1.0, 0.0], label='coupler 26 left (I)')
marker10262 = Marker(id=10262, qp=[26.0, 1.0, 0.0], label='coupler 26 right (I)')
body1026 = Part(id=1026, mass=1.0, cm=marker10260,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 26')
marker10260.body = body1026
marker10261.body = body1026
marker10262.body = body1026
joint92 = Joint(id=92, type='REVOLUTE', i=marker10261, j=marker272, label='crank 25-coupler 26')
joint93 = Joint(id=93, type='REVOLUTE', i=marker10262, j=marker282, label='coupler 26-crank 26')
marker10270 = Marker(id=10270, qp=[26.5, 1.0, 0.0], label='coupler 27 cm')
marker10271 = Marker(id=10271, qp=[26.0, 1.0, 0.0], label='coupler 27 left (I)')
marker10272 = Marker(id=10272, qp=[27.0, 1.0, 0.0], label='coupler 27 right (I)')
body1027 = Part(id=1027, mass=1.0, cm=marker10270,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 27')
marker10270.body = body1027
marker10271.body = body1027
marker10272.body = body1027
joint94 = Joint(id=94, type='REVOLUTE', i=marker10271, j=marker282, label='crank 26-coupler 27')
joint95 = Joint(id=95, type='REVOLUTE', i=marker10272, j=marker292, label='coupler 27-crank 27')
marker10280 = Marker(id=10280, qp=[27.5, 1.0, 0.0], label='coupler 28 cm')
marker10281 = Marker(id=10281, qp=[27.0, 1.0, 0.0], label='coupler 28 left (I)')
marker10282 = Marker(id=10282, qp=[28.0, 1.0, 0.0], label='coupler 28 right (I)')
body1028 = Part(id=1028, mass=1.0, cm=marker10280,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 28')
marker10280.body = body1028
marker10281.body = body1028
marker10282.body = body1028
joint96 = Joint(id=96, type='REVOLUTE', i=marker10281, j=marker292, label='crank 27-coupler 28')
joint97 = Joint(id=97, type='REVOLUTE', i=marker10282, j=marker302, label='coupler 28-crank 28')
marker10290 = Marker(id=10290, qp=[28.5, 1.0, 0.0], label='coupler 29 cm')
marker10291 = Marker(id=10291, qp=[28.0, 1.0, 0.0], label='coupler 29 left (I)')
marker10292 = Marker(id=10292, qp=[29.0, 1.0, 0.0], label='coupler 29 right (I)')
body1029 = Part(id=1029, mass=1.0, cm=marker10290,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 29')
marker10290.body = body1029
marker10291.body = body1029
marker10292.body = body1029
joint98 = Joint(id=98, type='REVOLUTE', i=marker10291, j=marker302, label='crank 28-coupler 29')
joint99 = Joint(id=99, type='REVOLUTE', i=marker10292, j=marker312, label='coupler 29-crank 29')
marker10300 = Marker(id=10300, qp=[29.5, 1.0, 0.0], label='coupler 30 cm')
marker10301 = Marker(id=10301, qp=[29.0, 1.0, 0.0], label='coupler 30 left (I)')
marker10302 = Marker(id=10302, qp=[30.0, 1.0, 0.0], label='coupler 30 right (I)')
body1030 = Part(id=1030, mass=1.0, cm=marker10300,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 30')
marker10300.body = body1030
marker10301.body = body1030
marker10302.body = body1030
joint100 = Joint(id=100, type='REVOLUTE', i=marker10301, j=marker312, label='crank 29-coupler 30')
joint101 = Joint(id=101, type='REVOLUTE', i=marker10302, j=marker322, label='coupler 30-crank 30')
marker10310 = Marker(id=10310, qp=[30.5, 1.0, 0.0], label='coupler 31 cm')
marker10311 = Marker(id=10311, qp=[30.0, 1.0, 0.0], label='coupler 31 left (I)')
marker10312 = Marker(id=10312, qp=[31.0, 1.0, 0.0], label='coupler 31 right (I)')
body1031 = Part(id=1031, mass=1.0, cm=marker10310,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 31')
marker10310.body = body1031
marker10311.body = body1031
marker10312.body = body1031
joint102 = Joint(id=102, type='REVOLUTE', i=marker10311, j=marker322, label='crank 30-coupler 31')
joint103 = Joint(id=103, type='REVOLUTE', i=marker10312, j=marker332, label='coupler 31-crank 31')
marker10320 = Marker(id=10320, qp=[31.5, 1.0, 0.0], label='coupler 32 cm')
marker10321 = Marker(id=10321, qp=[31.0, 1.0, 0.0], label='coupler 32 left (I)')
marker10322 = Marker(id=10322, qp=[32.0, 1.0, 0.0], label='coupler 32 right (I)')
body1032 = Part(id=1032, mass=1.0, cm=marker10320,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 32')
marker10320.body = body1032
marker10321.body = body1032
marker10322.body = body1032
joint104 = Joint(id=104, type='REVOLUTE', i=marker10321, j=marker332, label='crank 31-coupler 32')
joint105 = Joint(id=105, type='REVOLUTE', i=marker10322, j=marker342, label='coupler 32-crank 32')
marker10330 = Marker(id=10330, qp=[32.5, 1.0, 0.0], label='coupler 33 cm')
marker10331 = Marker(id=10331, qp=[32.0, 1.0, 0.0], label='coupler 33 left (I)')
marker10332 = Marker(id=10332, qp=[33.0, 1.0, 0.0], label='coupler 33 right (I)')
body1033 = Part(id=1033, mass=1.0, cm=marker10330,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 33')
marker10330.body = body1033
marker10331.body = body1033
marker10332.body = body1033
joint106 = Joint(id=106, type='REVOLUTE', i=marker10331, j=marker342, label='crank 32-coupler 33')
joint107 = Joint(id=107, type='REVOLUTE', i=marker10332, j=marker352, label='coupler 33-crank 33')
marker10340 = Marker(id=10340, qp=[33.5, 1.0, 0.0], label='coupler 34 cm')
marker10341 = Marker(id=10341, qp=[33.0, 1.0, 0.0], label='coupler 34 left (I)')
marker10342 = Marker(id=10342, qp=[34.0, 1.0, 0.0], label='coupler 34 right (I)')
body1034 = Part(id=1034, mass=1.0, cm=marker10340,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 34')
marker10340.body = body1034
marker10341.body = body1034
marker10342.body = body1034
joint108 = Joint(id=108, type='REVOLUTE', i=marker10341, j=marker352, label='crank 33-coupler 34')
joint109 = Joint(id=109, type='REVOLUTE', i=marker10342, j=marker362, label='coupler 34-crank 34')
marker10350 = Marker(id=10350, qp=[34.5, 1.0, 0.0], label='coupler 35 cm')
marker10351 = Marker(id=10351, qp=[34.0, 1.0, 0.0], label='coupler 35 left (I)')
marker10352 = Marker(id=10352, qp=[35.0, 1.0, 0.0], label='coupler 35 right (I)')
body1035 = Part(id=1035, mass=1.0, cm=marker10350,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 35')
marker10350.body = body1035
marker10351.body = body1035
marker10352.body = body1035
joint110 = Joint(id=110, type='REVOLUTE', i=marker10351, j=marker362, label='crank 34-coupler 35')
joint111 = Joint(id=111, type='REVOLUTE', i=marker10352, j=marker372, label='coupler 35-crank 35')
marker10360 = Marker(id=10360, qp=[35.5, 1.0, 0.0], label='coupler 36 cm')
marker10361 = Marker(id=10361, qp=[35.0, 1.0, 0.0], label='coupler 36 left (I)')
marker10362 = Marker(id=10362, qp=[36.0, 1.0, 0.0], label='coupler 36 right (I)')
body1036 = Part(id=1036, mass=1.0, cm=marker10360,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 36')
marker10360.body = body1036
marker10361.body = body1036
marker10362.body = body1036
joint112 = Joint(id=112, type='REVOLUTE', i=marker10361, j=marker372, label='crank 35-coupler 36')
joint113 = Joint(id=113, type='REVOLUTE', i=marker10362, j=marker382, label='coupler 36-crank 36')
marker10370 = Marker(id=10370, qp=[36.5, 1.0, 0.0], label='coupler 37 cm')
marker10371 = Marker(id=10371, qp=[36.0, 1.0, 0.0], label='coupler 37 left (I)')
marker10372 = Marker(id=10372, qp=[37.0, 1.0, 0.0], label='coupler 37 right (I)')
body1037 = Part(id=1037, mass=1.0, cm=marker10370,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 37')
marker10370.body = body1037
marker10371.body = body1037
marker10372.body = body1037
joint114 = Joint(id=114, type='REVOLUTE', i=marker10371, j=marker382, label='crank 36-coupler 37')
joint115 = Joint(id=115, type='REVOLUTE', i=marker10372, j=marker392, label='coupler 37-crank 37')
marker10380 = Marker(id=10380, qp=[37.5, 1.0, 0.0], label='coupler 38 cm')
marker10381 = Marker(id=10381, qp=[37.0, 1.0, 0.0], label='coupler 38 left (I)')
marker10382 = Marker(id=10382, qp=[38.0, 1.0, 0.0], label='coupler 38 right (I)')
body1038 = Part(id=1038, mass=1.0, cm=marker10380,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 38')
marker10380.body = body1038
marker10381.body = body1038
marker10382.body = body1038
joint116 = Joint(id=116, type='REVOLUTE', i=marker10381, j=marker392, label='crank 37-coupler 38')
joint117 = Joint(id=117, type='REVOLUTE', i=marker10382, j=marker402, label='coupler 38-crank 38')
marker10390 = Marker(id=10390, qp=[38.5, 1.0, 0.0], label='coupler 39 cm')
marker10391 = Marker(id=10391, qp=[38.0, 1.0, 0.0], label='coupler 39 left (I)')
marker10392 = Marker(id=10392, qp=[39.0, 1.0, 0.0], label='coupler 39 right (I)')
body1039 = Part(id=1039, mass=1.0, cm=marker10390,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 39')
marker10390.body = body1039
marker10391.body = body1039
marker10392.body = body1039
joint118 = Joint(id=118, type='REVOLUTE', i=marker10391, j=marker402, label='crank 38-coupler 39')
joint119 = Joint(id=119, type='REVOLUTE', i=marker10392, j=marker412, label='coupler 39-crank 39')
marker10400 = Marker(id=10400, qp=[39.5, 1.0, 0.0], label='coupler 40 cm')
marker10401 = Marker(id=10401, qp=[39.0, 1.0, 0.0], label='coupler 40 left (I)')
marker10402 = Marker(id=10402, qp=[40.0, 1.0, 0.0], label='coupler 40 right (I)')
body1040 = Part(id=1040, mass=1.0, cm=marker10400,
                ip=[0.0001, 0.08333333333333333, 0.08333333333333333], vx=1.0, label='coupler 40')
marker10400.body = body1040
marker10401.body = body1040
marker10402.body = body1040
joint120 = Joint(id=120, type='REVOLUTE', i=marker10401, j=marker412, label='crank 39-coupler 40')
joint121 = Joint(id=121, type='REVOLUTE', i=marker10402, j=marker422, label='coupler 40-crank 40')
Request(id=1, f1='DX(22)', f2='DY(22)', f3='VX(22)', f4='VY(22)', f5='AZ(21,1000)',
        cnames=['B0_x', 'B0_y', 'B0_vx', 'B0_vy', 'crank0_rotation'])
Integrator(error=1e-08)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=20.0, dtout=0.05)
