"""A free axisymmetric rigid body (no gravity) spinning about its symmetry axis z with a small
transverse angular velocity: torque-free precession. In the body frame w_z stays constant
and (w_x, w_y) rotates at Omega = (I3 - I1)/I1 * w_z.

pysolver convert wrote this script of msolve classes from torque_free_spin.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='torque_free_spin')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1)
marker20 = Marker(id=20, qp=[0.0, 0.0, 1.0], reuler=[0.2, 0.3, 0.1])
body2 = Part(id=2, mass=3.0, cm=marker20, ip=[0.1, 0.1, 0.18], vx=0.5, wx=1.0, wy=0.0, wz=20.0)
marker20.body = body2
Request(id=1, f1='WX(20,0,20)', f2='WY(20,0,20)', f3='WZ(20,0,20)', f4='WX(20)', f5='WY(20)',
        f6='WZ(20)', f7='DX(20)', f8='DZ(20)',
        cnames=['wx_body', 'wy_body', 'wz_body', 'wx', 'wy', 'wz', 'x', 'z'])
Integrator(error=1e-08)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=2.0, dtout=0.01)
