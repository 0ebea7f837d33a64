"""A 1 kg point mass on a bilateral penalty rod of length 1 m (penalty 1e8 N/m, critical
damping penalty1 2e4 N s/m), under gravity, released horizontally at rest (issue 5's stiff
penalty problem). IDA as shipped fails its error test after almost every step here; the C
driver limits the step growth by itself (res.stats["growth_limited_at"]). At
integr_tol 1e-10 the motion stays within 1e-5 of the rigid pendulum over 10 s.

pysolver convert wrote this script of msolve classes from stiff_penalty_pendulum.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='stiff_penalty_pendulum')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1)
marker10 = Marker(id=10, qp=[1.0, 0.0, 0.0])
body2 = PointMass(id=2, mass=1.0, cm=marker10)
marker10.body = body2
Accgrav(jgrav=-9.81)
Pforce(id=1, function='DM(10,1) - 1', penalty=100000000.0, penalty1=20000.0, label='rod')
Request(id=1, f1='DX(10)', f2='DY(10)', f3='PFORCE(1)', cnames=['x', 'y', 'rod_force'])
Integrator(error=1e-10)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=10.0, dtout=0.01)
