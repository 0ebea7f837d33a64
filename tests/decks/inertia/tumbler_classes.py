"""tumbler.adm in msolve classes: Part's ip lists xx, yy, zz, xy, xz, yz (Adams' order)."""
import math

from pysolver.msolve import Marker, Model, Part, Request, Units

model = Model(output="tumbler_classes")
Units(mass="KILOGRAM", length="METER", time="SECOND", force="NEWTON")
ground = Part(id=1, ground=True)
Marker(id=1, body=ground)
body = Part(id=2, mass=2, ip=[3, 2.5, 4.5, -0.5, 0.2, -0.3], qg=[0, 0, 1], wx=1, wy=0.2,
            wz=-0.4)
body.cm = Marker(id=20, body=body)
body.im = Marker(id=21, body=body, qp=[0, 0.5, 0], reuler=[math.pi / 2, 0, 0])
Request(id=1, f1="WX(20, 1, 20)", f2="WY(20, 1, 20)", f3="WZ(20, 1, 20)")
model.simulate(type="DYNAMICS", end=2, dtout=0.02)
