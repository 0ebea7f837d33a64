"""LoadControl with a noisy load: an indenter (a sphere of radius 3 mm on a point body) pressed
into a hexagonally packed bed of particles (radius 1 mm, 1 g each, 2D in x-z; 53 with the
default 11 x 5) in a box, every contact a unilateral penalty (10 N/mm, damping 0.01 N s/mm). Units kg, mm, s, N; gravity -9810 mm/s^2. The load is
the contact force on the indenter (load="contact"), which jumps as particles slip and
rearrange: the seed's fat-tailed contact noise. Target: a ramp of 0.6 N/s. Change NX, NZ for
bigger beds (benchmarks/loadcontrol.py runs 53 and 195 particles), and MEDIAN_WINDOW to filter
the load.

pysolver convert wrote this script of msolve classes from loadcontrol_bed.py:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='loadcontrol_bed')
Units(force='NEWTON', mass='KILOGRAM', length='MILLIMETER', time='SECOND')
Accgrav(kgrav=-9810.0)
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1)
marker100 = Marker(id=100, qp=[1.0, 0.0, 1.0])
body100 = PointMass(id=100, mass=0.001, cm=marker100)
marker100.body = body100
marker101 = Marker(id=101, qp=[3.0, 0.0, 1.0])
body101 = PointMass(id=101, mass=0.001, cm=marker101)
marker101.body = body101
marker102 = Marker(id=102, qp=[5.0, 0.0, 1.0])
body102 = PointMass(id=102, mass=0.001, cm=marker102)
marker102.body = body102
marker103 = Marker(id=103, qp=[7.0, 0.0, 1.0])
body103 = PointMass(id=103, mass=0.001, cm=marker103)
marker103.body = body103
marker104 = Marker(id=104, qp=[9.0, 0.0, 1.0])
body104 = PointMass(id=104, mass=0.001, cm=marker104)
marker104.body = body104
marker105 = Marker(id=105, qp=[11.0, 0.0, 1.0])
body105 = PointMass(id=105, mass=0.001, cm=marker105)
marker105.body = body105
marker106 = Marker(id=106, qp=[13.0, 0.0, 1.0])
body106 = PointMass(id=106, mass=0.001, cm=marker106)
marker106.body = body106
marker107 = Marker(id=107, qp=[15.0, 0.0, 1.0])
body107 = PointMass(id=107, mass=0.001, cm=marker107)
marker107.body = body107
marker108 = Marker(id=108, qp=[17.0, 0.0, 1.0])
body108 = PointMass(id=108, mass=0.001, cm=marker108)
marker108.body = body108
marker109 = Marker(id=109, qp=[19.0, 0.0, 1.0])
body109 = PointMass(id=109, mass=0.001, cm=marker109)
marker109.body = body109
marker110 = Marker(id=110, qp=[21.0, 0.0, 1.0])
body110 = PointMass(id=110, mass=0.001, cm=marker110)
marker110.body = body110
marker111 = Marker(id=111, qp=[2.0, 0.0, 2.732050807568877])
body111 = PointMass(id=111, mass=0.001, cm=marker111)
marker111.body = body111
marker112 = Marker(id=112, qp=[4.0, 0.0, 2.732050807568877])
body112 = PointMass(id=112, mass=0.001, cm=marker112)
marker112.body = body112
marker113 = Marker(id=113, qp=[6.0, 0.0, 2.732050807568877])
body113 = PointMass(id=113, mass=0.001, cm=marker113)
marker113.body = body113
marker114 = Marker(id=114, qp=[8.0, 0.0, 2.732050807568877])
body114 = PointMass(id=114, mass=0.001, cm=marker114)
marker114.body = body114
marker115 = Marker(id=115, qp=[10.0, 0.0, 2.732050807568877])
body115 = PointMass(id=115, mass=0.001, cm=marker115)
marker115.body = body115
marker116 = Marker(id=116, qp=[12.0, 0.0, 2.732050807568877])
body116 = PointMass(id=116, mass=0.001, cm=marker116)
marker116.body = body116
marker117 = Marker(id=117, qp=[14.0, 0.0, 2.732050807568877])
body117 = PointMass(id=117, mass=0.001, cm=marker117)
marker117.body = body117
marker118 = Marker(id=118, qp=[16.0, 0.0, 2.732050807568877])
body118 = PointMass(id=118, mass=0.001, cm=marker118)
marker118.body = body118
marker119 = Marker(id=119, qp=[18.0, 0.0, 2.732050807568877])
body119 = PointMass(id=119, mass=0.001, cm=marker119)
marker119.body = body119
marker120 = Marker(id=120, qp=[20.0, 0.0, 2.732050807568877])
body120 = PointMass(id=120, mass=0.001, cm=marker120)
marker120.body = body120
marker122 = Marker(id=122, qp=[1.0, 0.0, 4.464101615137754])
body122 = PointMass(id=122, mass=0.001, cm=marker122)
marker122.body = body122
marker123 = Marker(id=123, qp=[3.0, 0.0, 4.464101615137754])
body123 = PointMass(id=123, mass=0.001, cm=marker123)
marker123.body = body123
marker124 = Marker(id=124, qp=[5.0, 0.0, 4.464101615137754])
body124 = PointMass(id=124, mass=0.001, cm=marker124)
marker124.body = body124
marker125 = Marker(id=125, qp=[7.0, 0.0, 4.464101615137754])
body125 = PointMass(id=125, mass=0.001, cm=marker125)
marker125.body = body125
marker126 = Marker(id=126, qp=[9.0, 0.0, 4.464101615137754])
body126 = PointMass(id=126, mass=0.001, cm=marker126)
marker126.body = body126
marker127 = Marker(id=127, qp=[11.0, 0.0, 4.464101615137754])
body127 = PointMass(id=127, mass=0.001, cm=marker127)
marker127.body = body127
marker128 = Marker(id=128, qp=[13.0, 0.0, 4.464101615137754])
body128 = PointMass(id=128, mass=0.001, cm=marker128)
marker128.body = body128
marker129 = Marker(id=129, qp=[15.0, 0.0, 4.464101615137754])
body129 = PointMass(id=129, mass=0.001, cm=marker129)
marker129.body = body129
marker130 = Marker(id=130, qp=[17.0, 0.0, 4.464101615137754])
body130 = PointMass(id=130, mass=0.001, cm=marker130)
marker130.body = body130
marker131 = Marker(id=131, qp=[19.0, 0.0, 4.464101615137754])
body131 = PointMass(id=131, mass=0.001, cm=marker131)
marker131.body = body131
marker132 = Marker(id=132, qp=[21.0, 0.0, 4.464101615137754])
body132 = PointMass(id=132, mass=0.001, cm=marker132)
marker132.body = body132
marker133 = Marker(id=133, qp=[2.0, 0.0, 6.196152422706632])
body133 = PointMass(id=133, mass=0.001, cm=marker133)
marker133.body = body133
marker134 = Marker(id=134, qp=[4.0, 0.0, 6.196152422706632])
body134 = PointMass(id=134, mass=0.001, cm=marker134)
marker134.body = body134
marker135 = Marker(id=135, qp=[6.0, 0.0, 6.196152422706632])
body135 = PointMass(id=135, mass=0.001, cm=marker135)
marker135.body = body135
marker136 = Marker(id=136, qp=[8.0, 0.0, 6.196152422706632])
body136 = PointMass(id=136, mass=0.001, cm=marker136)
marker136.body = body136
marker137 = Marker(id=137, qp=[10.0, 0.0, 6.196152422706632])
body137 = PointMass(id=137, mass=0.001, cm=marker137)
marker137.body = body137
marker138 = Marker(id=138, qp=[12.0, 0.0, 6.196152422706632])
body138 = PointMass(id=138, mass=0.001, cm=marker138)
marker138.body = body138
marker139 = Marker(id=139, qp=[14.0, 0.0, 6.196152422706632])
body139 = PointMass(id=139, mass=0.001, cm=marker139)
marker139.body = body139
marker140 = Marker(id=140, qp=[16.0, 0.0, 6.196152422706632])
body140 = PointMass(id=140, mass=0.001, cm=marker140)
marker140.body = body140
marker141 = Marker(id=141, qp=[18.0, 0.0, 6.196152422706632])
body141 = PointMass(id=141, mass=0.001, cm=marker141)
marker141.body = body141
marker142 = Marker(id=142, qp=[20.0, 0.0, 6.196152422706632])
body142 = PointMass(id=142, mass=0.001, cm=marker142)
marker142.body = body142
marker144 = Marker(id=144, qp=[1.0, 0.0, 7.928203230275509])
body144 = PointMass(id=144, mass=0.001, cm=marker144)
marker144.body = body144
marker145 = Marker(id=145, qp=[3.0, 0.0, 7.928203230275509])
body145 = PointMass(id=145, mass=0.001, cm=marker145)
marker145.body = body145
marker146 = Marker(id=146, qp=[5.0, 0.0, 7.928203230275509])
body146 = PointMass(id=146, mass=0.001, cm=marker146)
marker146.body = body146
marker147 = Marker(id=147, qp=[7.0, 0.0, 7.928203230275509])
body147 = PointMass(id=147, mass=0.001, cm=marker147)
marker147.body = body147
marker148 = Marker(id=148, qp=[9.0, 0.0, 7.928203230275509])
body148 = PointMass(id=148, mass=0.001, cm=marker148)
marker148.body = body148
marker149 = Marker(id=149, qp=[11.0, 0.0, 7.928203230275509])
body149 = PointMass(id=149, mass=0.001, cm=marker149)
marker149.body = body149
marker150 = Marker(id=150, qp=[13.0, 0.0, 7.928203230275509])
body150 = PointMass(id=150, mass=0.001, cm=marker150)
marker150.body = body150
marker151 = Marker(id=151, qp=[15.0, 0.0, 7.928203230275509])
body151 = PointMass(id=151, mass=0.001, cm=marker151)
marker151.body = body151
marker152 = Marker(id=152, qp=[17.0, 0.0, 7.928203230275509])
body152 = PointMass(id=152, mass=0.001, cm=marker152)
marker152.body = body152
marker153 = Marker(id=153, qp=[19.0, 0.0, 7.928203230275509])
body153 = PointMass(id=153, mass=0.001, cm=marker153)
marker153.body = body153
marker154 = Marker(id=154, qp=[21.0, 0.0, 7.928203230275509])
body154 = PointMass(id=154, mass=0.001, cm=marker154)
marker154.body = body154
marker10 = Marker(id=10, qp=[11.0, 0.0, 12.128203230275508])
body2 = PointMass(id=2, mass=0.005, cm=marker10)
marker10.body = body2
Pforce(id=1, function='1.0-DZ(100)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=2, function='1.0-DX(100)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=3, function='DX(100)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=4, function='2.0-DM(100,101)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=5, function='2.0-DM(100,111)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=6, function='1.0-DZ(101)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=7, function='1.0-DX(101)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=8, function='DX(101)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=9, function='2.0-DM(101,102)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=10, function='2.0-DM(101,111)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=11, function='2.0-DM(101,112)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=12, function='1.0-DZ(102)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=13, function='1.0-DX(102)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=14, function='DX(102)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=15, function='2.0-DM(102,103)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=16, function='2.0-DM(102,112)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=17, function='2.0-DM(102,113)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=18, function='1.0-DZ(103)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=19, function='1.0-DX(103)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=20, function='DX(103)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=21, function='2.0-DM(103,104)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=22, function='2.0-DM(103,113)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=23, function='2.0-DM(103,114)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=24, function='1.0-DZ(104)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=25, function='1.0-DX(104)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=26, function='DX(104)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=27, function='2.0-DM(104,105)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=28, function='2.0-DM(104,114)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=29, function='2.0-DM(104,115)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=30, function='1.0-DZ(105)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=31, function='1.0-DX(105)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=32, function='DX(105)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=33, function='2.0-DM(105,106)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=34, function='2.0-DM(105,115)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=35, function='2.0-DM(105,116)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=36, function='1.0-DZ(106)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=37, function='1.0-DX(106)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=38, function='DX(106)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=39, function='2.0-DM(106,107)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=40, function='2.0-DM(106,116)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=41, function='2.0-DM(106,117)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=42, function='1.0-DZ(107)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=43, function='1.0-DX(107)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=44, function='DX(107)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=45, function='2.0-DM(107,108)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=46, function='2.0-DM(107,117)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=47, function='2.0-DM(107,118)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=48, function='1.0-DZ(108)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=49, function='1.0-DX(108)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=50, function='DX(108)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=51, function='2.0-DM(108,109)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=52, function='2.0-DM(108,118)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=53, function='2.0-DM(108,119)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=54, function='1.0-DZ(109)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=55, function='1.0-DX(109)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=56, function='DX(109)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=57, function='2.0-DM(109,110)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=58, function='2.0-DM(109,119)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=59, function='2.0-DM(109,120)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=60, function='1.0-DZ(110)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=61, function='1.0-DX(110)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=62, function='DX(110)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=63, function='2.0-DM(110,120)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=64, function='1.0-DZ(111)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=65, function='1.0-DX(111)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=66, function='DX(111)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=67, function='2.0-DM(111,112)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=68, function='2.0-DM(111,122)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=69, function='2.0-DM(111,123)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=70, function='1.0-DZ(112)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=71, function='1.0-DX(112)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=72, function='DX(112)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=73, function='2.0-DM(112,113)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=74, function='2.0-DM(112,123)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=75, function='2.0-DM(112,124)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=76, function='1.0-DZ(113)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=77, function='1.0-DX(113)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=78, function='DX(113)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=79, function='2.0-DM(113,114)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=80, function='2.0-DM(113,124)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=81, function='2.0-DM(113,125)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=82, function='1.0-DZ(114)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=83, function='1.0-DX(114)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=84, function='DX(114)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=85, function='2.0-DM(114,115)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=86, function='2.0-DM(114,125)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=87, function='2.0-DM(114,126)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=88, function='1.0-DZ(115)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=89, function='1.0-DX(115)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=90, function='DX(115)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=91, function='2.0-DM(115,116)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=92, function='2.0-DM(115,126)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=93, function='2.0-DM(115,127)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=94, function='1.0-DZ(116)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=95, function='1.0-DX(116)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=96, function='DX(116)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=97, function='2.0-DM(116,117)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=98, function='2.0-DM(116,127)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=99, function='2.0-DM(116,128)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=100, function='1.0-DZ(117)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=101, function='1.0-DX(117)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=102, function='DX(117)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=103, function='2.0-DM(117,118)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=104, function='2.0-DM(117,128)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=105, function='2.0-DM(117,129)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=106, function='1.0-DZ(118)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=107, function='1.0-DX(118)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=108, function='DX(118)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=109, function='2.0-DM(118,119)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=110, function='2.0-DM(118,129)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=111, function='2.0-DM(118,130)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=112, function='1.0-DZ(119)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=113, function='1.0-DX(119)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=114, function='DX(119)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=115, function='2.0-DM(119,120)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=116, function='2.0-DM(119,130)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=117, function='2.0-DM(119,131)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=118, function='1.0-DZ(120)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=119, function='1.0-DX(120)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=120, function='DX(120)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=121, function='2.0-DM(120,131)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=122, function='2.0-DM(120,132)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=123, function='1.0-DZ(122)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=124, function='1.0-DX(122)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=125, function='DX(122)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=126, function='2.0-DM(122,123)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=127, function='2.0-DM(122,133)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=128, function='1.0-DZ(123)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=129, function='1.0-DX(123)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=130, function='DX(123)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=131, function='2.0-DM(123,124)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=132, function='2.0-DM(123,133)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=133, function='2.0-DM(123,134)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=134, function='1.0-DZ(124)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=135, function='1.0-DX(124)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=136, function='DX(124)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=137, function='2.0-DM(124,125)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=138, function='2.0-DM(124,134)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=139, function='2.0-DM(124,135)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=140, function='1.0-DZ(125)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=141, function='1.0-DX(125)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=142, function='DX(125)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=143, function='2.0-DM(125,126)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=144, function='2.0-DM(125,135)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=145, function='2.0-DM(125,136)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=146, function='4.0-DM(125,10)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=147, function='1.0-DZ(126)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=148, function='1.0-DX(126)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=149, function='DX(126)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=150, function='2.0-DM(126,127)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=151, function='2.0-DM(126,136)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=152, function='2.0-DM(126,137)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=153, function='4.0-DM(126,10)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=154, function='1.0-DZ(127)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=155, function='1.0-DX(127)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=156, function='DX(127)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=157, function='2.0-DM(127,128)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=158, function='2.0-DM(127,137)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=159, function='2.0-DM(127,138)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=160, function='4.0-DM(127,10)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=161, function='1.0-DZ(128)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=162, function='1.0-DX(128)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=163, function='DX(128)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=164, function='2.0-DM(128,129)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=165, function='2.0-DM(128,138)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=166, function='2.0-DM(128,139)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=167, function='4.0-DM(128,10)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=168, function='1.0-DZ(129)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=169, function='1.0-DX(129)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=170, function='DX(129)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=171, function='2.0-DM(129,130)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=172, function='2.0-DM(129,139)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=173, function='2.0-DM(129,140)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=174, function='4.0-DM(129,10)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=175, function='1.0-DZ(130)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=176, function='1.0-DX(130)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=177, function='DX(130)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=178, function='2.0-DM(130,131)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=179, function='2.0-DM(130,140)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=180, function='2.0-DM(130,141)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=181, function='1.0-DZ(131)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=182, function='1.0-DX(131)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=183, function='DX(131)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=184, function='2.0-DM(131,132)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=185, function='2.0-DM(131,141)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=186, function='2.0-DM(131,142)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=187, function='1.0-DZ(132)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=188, function='1.0-DX(132)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=189, function='DX(132)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=190, function='2.0-DM(132,142)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=191, function='1.0-DZ(133)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=192, function='1.0-DX(133)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=193, function='DX(133)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=194, function='2.0-DM(133,134)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=195, function='2.0-DM(133,144)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=196, function='2.0-DM(133,145)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=197, function='1.0-DZ(134)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=198, function='1.0-DX(134)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=199, function='DX(134)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=200, function='2.0-DM(134,135)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=201, function='2.0-DM(134,145)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=202, function='2.0-DM(134,146)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=203, function='1.0-DZ(135)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=204, function='1.0-DX(135)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=205, function='DX(135)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=206, function='2.0-DM(135,136)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=207, function='2.0-DM(135,146)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=208, function='2.0-DM(135,147)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=209, function='4.0-DM(135,10)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=210, function='1.0-DZ(136)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=211, function='1.0-DX(136)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=212, function='DX(136)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=213, function='2.0-DM(136,137)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=214, function='2.0-DM(136,147)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=215, function='2.0-DM(136,148)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=216, function='4.0-DM(136,10)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=217, function='1.0-DZ(137)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=218, function='1.0-DX(137)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=219, function='DX(137)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=220, function='2.0-DM(137,138)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=221, function='2.0-DM(137,148)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=222, function='2.0-DM(137,149)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=223, function='4.0-DM(137,10)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=224, function='1.0-DZ(138)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=225, function='1.0-DX(138)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=226, function='DX(138)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=227, function='2.0-DM(138,139)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=228, function='2.0-DM(138,149)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=229, function='2.0-DM(138,150)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=230, function='4.0-DM(138,10)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=231, function='1.0-DZ(139)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=232, function='1.0-DX(139)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=233, function='DX(139)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=234, function='2.0-DM(139,140)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=235, function='2.0-DM(139,150)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=236, function='2.0-DM(139,151)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=237, function='4.0-DM(139,10)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=238, function='1.0-DZ(140)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=239, function='1.0-DX(140)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=240, function='DX(140)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=241, function='2.0-DM(140,141)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=242, function='2.0-DM(140,151)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=243, function='2.0-DM(140,152)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=244, function='4.0-DM(140,10)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=245, function='1.0-DZ(141)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=246, function='1.0-DX(141)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=247, function='DX(141)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=248, function='2.0-DM(141,142)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=249, function='2.0-DM(141,152)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=250, function='2.0-DM(141,153)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=251, function='1.0-DZ(142)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=252, function='1.0-DX(142)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=253, function='DX(142)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=254, function='2.0-DM(142,153)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=255, function='2.0-DM(142,154)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=256, function='1.0-DZ(144)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=257, function='1.0-DX(144)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=258, function='DX(144)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=259, function='2.0-DM(144,145)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=260, function='1.0-DZ(145)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=261, function='1.0-DX(145)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=262, function='DX(145)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=263, function='2.0-DM(145,146)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=264, function='1.0-DZ(146)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=265, function='1.0-DX(146)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=266, function='DX(146)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=267, function='2.0-DM(146,147)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=268, function='1.0-DZ(147)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=269, function='1.0-DX(147)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=270, function='DX(147)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=271, function='2.0-DM(147,148)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=272, function='4.0-DM(147,10)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=273, function='1.0-DZ(148)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=274, function='1.0-DX(148)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=275, function='DX(148)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=276, function='2.0-DM(148,149)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=277, function='4.0-DM(148,10)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=278, function='1.0-DZ(149)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=279, function='1.0-DX(149)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=280, function='DX(149)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=281, function='2.0-DM(149,150)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=282, function='4.0-DM(149,10)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=283, function='1.0-DZ(150)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=284, function='1.0-DX(150)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=285, function='DX(150)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=286, function='2.0-DM(150,151)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=287, function='4.0-DM(150,10)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=288, function='1.0-DZ(151)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=289, function='1.0-DX(151)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=290, function='DX(151)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=291, function='2.0-DM(151,152)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=292, function='4.0-DM(151,10)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=293, function='1.0-DZ(152)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=294, function='1.0-DX(152)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=295, function='DX(152)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=296, function='2.0-DM(152,153)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=297, function='1.0-DZ(153)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=298, function='1.0-DX(153)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=299, function='DX(153)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=300, function='2.0-DM(153,154)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=301, function='1.0-DZ(154)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=302, function='1.0-DX(154)', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
Pforce(id=303, function='DX(154)-21.0', penalty=10.0, penalty1=0.01, smoothing_factor=0.0001,
       unilateral=True)
LoadControl(id=1, velocity=-2.0, material=body2, direction=3, maxvelocity=20.0,
            load_function='0.6*t', kp='AUTO', ki='AUTO', smooth=0.8, updatetime=0.005,
            median_window=1, load='CONTACT')
Request(id=1, f1='DZ(10)', cnames=['indenter_z'])
Integrator(error=1e-05)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=0.6, dtout=0.005)
