"""Andrews' squeezing mechanism with exact joints (IFToMM A03 / Test Set for IVP solvers),
written by decks/joints/make_a03.py from benchmarks/andrews.py's data (its docstring
has the model and every decision; do not edit by hand). 7 planar bodies, 10 REVOLUTE
joints about global z (9 redundant equations in 3D), driving torque 0.033 N m, spring
c0 = 4530 N/m, l0 = 0.07785 m, no gravity, at rest, 0.03 s.
Compare: channels 1-7 (body angles AZ) through benchmarks/andrews.py's angles_at_end()
and error() against the Test Set reference at t = 0.03 (shared/reference/numerics.md
section 2; beta = 15.81077119629904, Theta = -15.75637105984298, ...); this project's
independent exact-joint solution (benchmarks/data/joint_references.json,
iftomm_a03_andrews) differs from the Test Set's by up to 1.4e-9 rad, so errors below
about 2e-9 rad against the Test Set are not meaningful.

pysolver convert wrote this script of msolve classes from iftomm_a03_andrews.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='iftomm_a03_andrews')
Units(force='NEWTON', mass='KILOGRAM', length='METER', time='SECOND')
body100 = Part(id=100, ground=True)
marker1001 = Marker(id=1001, qp=[0.0009182485980307614, -5.674074562905483e-05, 0.0],
                    reuler=[-0.06171389001427645, 0.0, 0.0], label='body 1 cm')
body1 = Part(id=1, mass=0.04325, cm=marker1001, ip=[2.194e-06, 2.194e-06, 2.194e-06],
             label='body 1')
marker1001.body = body1
marker1002 = Marker(id=1002, qp=[-0.0044914333599330725, 0.0002775362557942899, 0.0],
                    reuler=[-0.06171389001427645, 0.0, 0.0], label='body 2 cm')
body2 = Part(id=2, mass=0.00365, cm=marker1002, ip=[4.41e-07, 4.41e-07, 4.41e-07], label='body 2')
marker1002.body = body2
marker1003 = Marker(id=1003, qp=[-0.018742186670315457, 0.020485106789073934, 0.0],
                    reuler=[0.45527981916307037, 0.0, 0.0], label='body 3 cm')
body3 = Part(id=3, mass=0.02373, cm=marker1003, ip=[5.255e-06, 5.255e-06, 5.255e-06],
             label='body 3')
marker1003.body = body3
marker1004 = Marker(id=1004, qp=[-0.030222939830158887, 0.012071182356663938, 0.0],
                    reuler=[0.7100333697097284, 0.0, 0.0], label='body 4 cm')
body4 = Part(id=4, mass=0.00706, cm=marker1004, ip=[5.667e-07, 5.667e-07, 5.667e-07],
             label='body 4')
marker1004.body = body4
marker1005 = Marker(id=1005, qp=[-0.0446575851285552, 0.00044484734633101937, 0.0],
                    reuler=[0.48736497954384256, 0.0, 0.0], label='body 5 cm')
body5 = Part(id=5, mass=0.0705, cm=marker1005, ip=[1.169e-05, 1.169e-05, 1.169e-05],
             label='body 5')
marker1005.body = body5
marker1006 = Marker(id=1006, qp=[-0.028543268536783597, -0.010722254707252287, 0.0],
                    reuler=[1.0078790543839353, 0.0, 0.0], label='body 6 cm')
body6 = Part(id=6, mass=0.00706, cm=marker1006, ip=[5.667e-07, 5.667e-07, 5.667e-07],
             label='body 6')
marker1006.body = body6
marker1007 = Marker(id=1007, qp=[-0.05626558178575735, -0.002135507029626142, 0.0],
                    reuler=[1.2305474445498212, 0.0, 0.0], label='body 7 cm')
body7 = Part(id=7, mass=0.05498, cm=marker1007, ip=[1.912e-05, 1.912e-05, 1.912e-05],
             label='body 7')
marker1007.body = body7
marker1008 = Marker(id=1008, body=body1, qp=[0.0, 0.0, 0.0], label='O on 1 (I)')
marker1009 = Marker(id=1009, body=body100, qp=[0.0, 0.0, 0.0], label='O on ground (J)')
joint1 = Joint(id=1, type='REVOLUTE', i=marker1008, j=marker1009, label='O 1-100')
marker1010 = Marker(id=1010, body=body1, qp=[0.006986674115451445, -0.0004317230645688955, 0.0],
                    label='P on 1 (I)')
marker1011 = Marker(id=1011, body=body2, qp=[0.006986674115451445, -0.0004317230645688955, 0.0],
                    label='P on 2 (J)')
joint2 = Joint(id=2, type='REVOLUTE', i=marker1010, j=marker1011, label='P 1-2')
marker1012 = Marker(id=1012, body=body2, qp=[-0.020960022346354336, 0.0012951691937066864, 0.0],
                    label='D on 2 (I)')
marker1013 = Marker(id=1013, body=body3, qp=[-0.020960022346354336, 0.0012951691937066864, 0.0],
                    label='D on 3 (J)')
joint3 = Joint(id=3, type='REVOLUTE', i=marker1012, j=marker1013, label='D 2-3')
marker1014 = Marker(id=1014, body=body2, qp=[-0.020960022346354336, 0.0012951691937066864, 0.0],
                    label='D on 2 (I)')
marker1015 = Marker(id=1015, body=body4, qp=[-0.020960022346354336, 0.0012951691937066864, 0.0],
                    label='D on 4 (J)')
joint4 = Joint(id=4, type='REVOLUTE', i=marker1014, j=marker1015, label='D 2-4')
marker1016 = Marker(id=1016, body=body2, qp=[-0.020960022346354336, 0.0012951691937066864, 0.0],
                    label='D on 2 (I)')
marker1017 = Marker(id=1017, body=body6, qp=[-0.020960022346354336, 0.0012951691937066864, 0.0],
                    label='D on 6 (J)')
joint5 = Joint(id=5, type='REVOLUTE', i=marker1016, j=marker1017, label='D 2-6')
marker1018 = Marker(id=1018, body=body3, qp=[-0.03635, 0.03273, 0.0], label='B on 3 (I)')
marker1019 = Marker(id=1019, body=body100, qp=[-0.03635, 0.03273, 0.0], label='B on ground (J)')
joint6 = Joint(id=6, type='REVOLUTE', i=marker1018, j=marker1019, label='B 3-100')
marker1020 = Marker(id=1020, body=body4, qp=[-0.03399720388583998, 0.01646197167499768, 0.0],
                    label='E on 4 (I)')
marker1021 = Marker(id=1021, body=body5, qp=[-0.03399720388583998, 0.01646197167499768, 0.0],
                    label='E on 5 (J)')
joint7 = Joint(id=7, type='REVOLUTE', i=marker1020, j=marker1021, label='E 4-5')
marker1022 = Marker(id=1022, body=body5, qp=[-0.06934, -0.00227, 0.0], label='A on 5 (I)')
marker1023 = Marker(id=1023, body=body100, qp=[-0.06934, -0.00227, 0.0], label='A on ground (J)')
joint8 = Joint(id=8, type='REVOLUTE', i=marker1022, j=marker1023, label='A 5-100')
marker1024 = Marker(id=1024, body=body7, qp=[-0.06934, -0.00227, 0.0], label='A on 7 (I)')
marker1025 = Marker(id=1025, body=body100, qp=[-0.06934, -0.00227, 0.0], label='A on ground (J)')
joint9 = Joint(id=9, type='REVOLUTE', i=marker1024, j=marker1025, label='A 7-100')
marker1026 = Marker(id=1026, body=body6, qp=[-0.03163313450740889, -0.015618868668304536, 0.0],
                    label='F on 6 (I)')
marker1027 = Marker(id=1027, body=body7, qp=[-0.03163313450740889, -0.015618868668304536, 0.0],
                    label='F on 7 (J)')
joint10 = Joint(id=10, type='REVOLUTE', i=marker1026, j=marker1027, label='F 6-7')
marker1028 = Marker(id=1028, body=body1, qp=[0.0, 0.0, 0.0], label='O on the crank (torque I)')
marker1029 = Marker(id=1029, body=body100, qp=[0.0, 0.0, 0.0], label='O on ground (torque J)')
Sforce(id=1, i=marker1028, j=marker1029, type='ROTATION', function='0.033', label='driving torque')
marker1030 = Marker(id=1030, body=body3, qp=[-0.010472393888814624, 0.025357788530275253, 0.0],
                    label='spring end S on body 3')
marker1031 = Marker(id=1031, body=body100, qp=[0.014, 0.072, 0.0],
                    label='spring anchor C on ground')
Sforce(id=2, i=marker1030, j=marker1031, type='TRANSLATION',
       function='-4530.0*(DM(1030,1031) - 0.07785)', label='spring')
Request(id=1, f1='AZ(1001)', f2='AZ(1002)', f3='AZ(1003)', f4='AZ(1004)', f5='AZ(1005)',
        f6='AZ(1006)', f7='AZ(1007)',
        cnames=['theta1', 'theta2', 'theta3', 'theta4', 'theta5', 'theta6', 'theta7'])
Integrator(error=1e-09)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=0.03, dtout=0.0001)
