"""Contact onset with zero crossing (seed 003 Comment 3): a 1 kg ball falls 1 m onto the ground
z = 0, modelled by a stiff unilateral Force_Penalty (1e6 N/m, 100 N s/m, smoothing 1e-4 m),
at MotionSolve's default integr_tol 1e-3. A sensor watches the contact force; at first
contact it sends the integrator back to the last converged step and re-approaches the onset
with hmax scaled by 0.01, then restores hmax and writes an output row, so the state at first
contact comes from small steps instead of the interpolant of a step that went deep into
contact. The flight time is sqrt(2/9.81) = 0.4515 s.

pysolver convert wrote this script of msolve classes from contact_onset_zero_crossing.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='contact_onset_zero_crossing')
body1 = Part(id=1, ground=True)
marker10 = Marker(id=10, qp=[0.0, 0.0, 1.0])
body2 = PointMass(id=2, mass=1.0, cm=marker10)
marker10.body = body2
Accgrav(kgrav=-9.81)
Pforce(id=1, function='-DZ(10)', penalty=1000000.0, penalty1=100.0, smoothing_factor=0.0001,
       unilateral=True, label='ground contact')
Sensor(id=1, function='-PFORCE(1)', value=0.001, error=1e-09, operator='GE', print_=True,
       zero_crossing=0.01, label='first contact')
Request(id=1, f1='DZ(10)', f2='VZ(10)', f3='-PFORCE(1)', cnames=['z', 'vz', 'contact_force'])
Integrator(error=0.001)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=0.6, dtout=0.01)
