"""A rigid rod pendulum (1 kg, 1 m, rod axis z) whose end (marker 21) is held at the pivot by
three bilateral Force_Penalty elements, started 0.2 rad from upright. FIM_S finds the
nearest equilibrium, the unstable upright one; with method="MKEAM" the rod falls and comes
to rest hanging down. The spin about the rod's own axis is neutral: stability keeps the
Newton matrix regular.

pysolver convert wrote this script of msolve classes from static_pendulum.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='static_pendulum')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1, label='pivot')
marker20 = Marker(id=20, qp=[0.0, -0.09933466539753061, 0.4900332889206208],
                  reuler=[0.0, 0.2, 0.0], label='cm')
marker21 = Marker(id=21, qp=[0.0, 0.0, -0.5], rm=marker20, label='end')
body2 = Part(id=2, mass=1.0, cm=marker20, ip=[0.0834, 0.0834, 0.001])
marker20.body = body2
marker21.body = body2
Accgrav(kgrav=-9.81)
Pforce(id=1, function='DX(21,1)', penalty=1000000.0, penalty1=1000.0)
Pforce(id=2, function='DY(21,1)', penalty=1000000.0, penalty1=1000.0)
Pforce(id=3, function='DZ(21,1)', penalty=1000000.0, penalty1=1000.0)
Request(id=1, f1='DX(20)', f2='DY(20)', f3='DZ(20)', f4='DM(21,1)',
        cnames=['x_cm', 'y_cm', 'z_cm', 'joint_gap'])
Equilibrium(method='FIM_S', imbalance=1e-08, error=1e-10)
Integrator(error=1e-06)

if __name__ == "__main__":
    model.simulate(type="STATICS")
