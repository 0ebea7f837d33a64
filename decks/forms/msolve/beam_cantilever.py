"""A cantilever: a 40 mm square steel bar 0.2 m long (Force_Beam, Timoshenko: shear area
ratios 6/5) clamped to ground at marker 1, its free end marker 21 on a 1 kg body, loaded
at the end by 5 kN along the bar, 1 kN and -2 kN across it and 50 N m about it
(Force_Vector_OneBody, global axes). The static deflections are the closed forms:
DX - L = Fx L / (E A), DY = Fy L^3 / (3 E Izz) + Fy L ASY / (G A), AZ = Fy L^2 / (2 E Izz),
DZ = Fz L^3 / (3 E Iyy) + Fz L ASZ / (G A), AY = -Fz L^2 / (2 E Iyy), AX = Tx L / (G Ixx).
The transient after it starts at rest in that equilibrium and stays there.

pysolver convert wrote this script of msolve classes from beam_cantilever.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='beam_cantilever')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1, label='clamp')
marker20 = Marker(id=20, qp=[0.2, 0.0, 0.0], label='end')
marker21 = Marker(id=21, qp=[0.2, 0.0, 0.0])
body2 = Part(id=2, mass=1.0, cm=marker20, ip=[0.001, 0.001, 0.001])
marker20.body = body2
marker21.body = body2
Beam(id=1, i=marker21, j=marker1, length=0.2, ixx=3.6e-07, iyy=2.1333e-07, izz=2.1333e-07,
     area=0.0016, asy=1.2, asz=1.2, emodulus=210000000000.0, gmodulus=81000000000.0, cratio=0.0001,
     label='bar')
Gforce(id=1, i=marker21, actiononly=True, fx='5000', fy='1000', fz='-2000', tx='50',
       label='end load')
Request(id=1, f1='DX(21,1,1) - 0.2', f2='DY(21,1,1)', f3='DZ(21,1,1)', f4='AX(21,1)',
        f5='AY(21,1)', f6='AZ(21,1)', f7='BEAM(1,1,3,0)', f8='BEAM(1,1,8,0)',
        cnames=['stretch', 'dy', 'dz', 'twist', 'ay', 'az', 'clamp_fy', 'clamp_tz'])
Equilibrium(method='FIM_S', imbalance=1e-06, error=1e-14)
Integrator(error=1e-08)

if __name__ == "__main__":
    model.simulate(type="STATICS")
    model.simulate(type="DYNAMICS", end=0.01, dtout=0.005)
