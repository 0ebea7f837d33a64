"""A heavy symmetric top: a rigid body whose tip (marker 21) is held at the ground pivot
(marker 1) by three bilateral Force_Penalty elements (a soft spherical joint). The top
spins at 200 rad/s about its symmetry axis, tilted 0.3 rad from vertical, and precesses
under gravity at about 3.1 rad/s on average (fast-top approximation m g l / (I3 w3):
2.76).

pysolver convert wrote this script of msolve classes from spinning_top.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='spinning_top')
Units(force='NEWTON', mass='KILOGRAM', length='METER', time='SECOND')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1, label='pivot')
marker20 = Marker(id=20, qp=[0.0, -0.029552020666133955, 0.09553364891256061],
                  reuler=[0.0, 0.3, 0.0], label='cm')
marker21 = Marker(id=21, qp=[0.0, 0.0, -0.1], rm=marker20, label='tip')
body2 = Part(id=2, mass=1.0, cm=marker20, ip=[0.004, 0.004, 0.00178], wz=200.0, label='top')
marker20.body = body2
marker21.body = body2
Accgrav(kgrav=-9.81)
Pforce(id=1, function='DX(21,1)', penalty=1000000.0, penalty1=500.0)
Pforce(id=2, function='DY(21,1)', penalty=1000000.0, penalty1=500.0)
Pforce(id=3, function='DZ(21,1)', penalty=1000000.0, penalty1=500.0)
Request(id=1, f1='DX(20)', f2='DY(20)', f3='DZ(20)', f4='DM(21,1)', f5='ATAN2(DY(20),DX(20))',
        f6='WZ(20,0,20)', f7='PFORCE(3)',
        cnames=['x_cm', 'y_cm', 'z_cm', 'tip_gap', 'azimuth', 'spin', 'pivot_fz'])
Integrator(error=1e-07)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=2.0, dtout=0.005)
