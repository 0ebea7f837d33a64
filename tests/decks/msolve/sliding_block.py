"""Altair's msolve example "XML Syntax Alternative" (a block on a translational joint pushed by
an action-only force, 3 sin(2 pi t) N along global x), as a script of msolve classes with
its own main block; tests/test_msolve_classes.py."""
from msolve import *


def sliding_block(out_name):
    m = Model(output=out_name)
    Accgrav(jgrav=-9.800)
    Integrator(type="DSTIFF", error=1e-7)
    p0 = Point(10, 0, 0)
    ux = Vector(1, 0, 0)
    uz = Vector(0, 0, 1)
    grnd = Part(ground=True)
    Marker(body=grnd, label="Global CS")
    blk1 = Part(label="Block-1", mass=1, ip=[4.9e-4, 4.9e-4, 4.9e-4])
    blk1.cm = Marker(label="Block-1 CM", body=blk1, qp=p0, zp=p0 + ux, xp=p0 + uz)
    im1 = Marker(label="Joint-1 I", body=blk1, qp=p0, zp=p0 + ux, xp=p0 + uz)
    jm1 = Marker(label="Joint-1 J", body=grnd, qp=p0, zp=p0 + ux, xp=p0 + uz)
    Joint(label="Joint-1", type="TRANSLATIONAL", i=im1, j=jm1)
    Sforce(type="TRANSLATION", actiononly=True, i=im1, j=jm1,
           label="Actuation Force-1", function="3*sin(2*pi*time)")
    Request(type="DISPLACEMENT", i=im1, j=jm1, rm=jm1)
    Output(reqsave=True)
    return m


if __name__ == "__main__":
    model = sliding_block("One-Sliding-Block")
    model.simulate(type="DYNAMICS", end=4, dtout=.01)
