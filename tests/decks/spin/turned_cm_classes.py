"""turned_cm.adm in msolve classes: Part's wx, wz along the cm marker's axes."""
import math

from pysolver.msolve import Marker, Model, Part, Request

model = Model(output="turned_cm_classes")
ground = Part(id=1, ground=True)
Marker(id=1, body=ground)
cm = Marker(id=20, qp=[0, 0, 1], reuler=[0, math.pi / 2, 0])
body = Part(id=2, mass=2, cm=cm, ip=[1, 2, 3], wx=0.3, wz=1)
cm.body = body
Request(id=1, f1="WX(20)", f2="WY(20)", f3="WZ(20)", f4="WX(20,0,20)", f5="WY(20,0,20)",
        f6="WZ(20,0,20)", f7="DX(20)", f8="DZ(20)")
model.simulate(type="DYNAMICS", end=1.0, dtout=0.05)
