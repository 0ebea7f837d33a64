"""IFToMM A05: stiff flyball governor (benchmark deck for Force_SpringDamper with
stiff, heavily damped couplers on an exact-joint mechanism). Written by
decks/joints/make_a05.py (its docstring has every source and decision; do not edit
by hand).

Source: IFToMM Library of Computational Benchmark Problems, problem A05,
http://lim.ii.udc.es/mbsbenchmark/dist/A05/A05_specification.xml (only its header
could be read when this deck was written); the numbers as in the OpenSim
implementation of the library (RehabEngGroup/MBSbenchmarksInOpenSim,
src/A05-FlyballGovernor, help/benchmarks/A05_FlyballGovernor.rst) and Exudyn's
stiffFlyballGovernorKT.py, which agree:
- shaft and rods 1.0 x 0.01 x 0.01 m, slider 0.1 m cube, density 3000 kg/m^3
(0.3, 0.3, 3 kg); two 5 kg point masses at the rods' far ends;
- coupler rods replaced by spring-dampers K = 8e5 N/m, C = 4e4 N s/m, rest length
0.5 m, from each rod's middle to the slider's side point (+-0.05, 0, s);
- shaft on a revolute about global z at the origin, slider on a translational joint
along it (centre height s = 0.5 m at t = 0), rods hinged at (+-0.05, 0, 1) about
the shaft's y axis, alpha = 30 deg below the horizontal; gravity -9.81 z;
- every body turning at 2 pi rad/s about z at t = 0, the shaft free (not driven);
10 s, output every 0.01 s.
Deck decisions: each rod and its ball are one body of 5.3 kg, cm 0.9716981132 m
from the hinge, inertia (principal axes on the im marker, x along the rod) axial
5e-06, transverse 0.09575721698 kg m^2; shaft axial 5e-06, transverse
0.0250025; slider 0.005 kg m^2.
Reference: make_a05.py reference(): Lagrange's equations in (s, theta1, theta2) with
the shaft's conserved momentum, SciPy Radau at rtol = atol = 1e-12; s oscillates
between 0.5 and about 0.744 m with a period of about 1.03 s; it agrees within
2.3e-4 m with the library's reference curve as plotted in the OpenSim docs
(help/images/5MBS_PlotResults.png, every 0.1 s to 3 s, digitized in
tests/test_iftomm_a05.py).
Compare: request 1 channel 1 (s = DZ of the slider on the shaft) against the
reference table in tests/test_iftomm_a05.py; channels 2-3 the spring lengths (within
about 1e-4 m of 0.5: the couplers are nearly rigid), 4 the shaft speed, 5-6 the rod
angles below the horizontal. Request 2: channel 1 the mechanical energy (kinetic +
gravity, zero at z = 0, + spring), which falls only by the dampers' work (integral
of C VR^2, channels 3-4); channel 2 the angular momentum about z, conserved exactly.

pysolver convert wrote this script of msolve classes from iftomm_a05_flyball.xml:
pysolver.load() reads it, python runs it.
"""
from pysolver.msolve import *

model = Model(output='iftomm_a05_flyball')
Units(force='NEWTON', mass='KILOGRAM', length='METER', time='SECOND')
body1 = Part(id=1, ground=True)
marker1 = Marker(id=1, body=body1, qp=[0.0, 0.0, 0.0], label='global')
marker2 = Marker(id=2, body=body1, qp=[0.0, 0.0, 0.0], label='shaft pivot on ground (J), z up')
marker20 = Marker(id=20, qp=[0.0, 0.0, 0.5], label='shaft cm')
marker21 = Marker(id=21, qp=[0.0, 0.0, 0.0], label='shaft pivot (I)')
marker22 = Marker(id=22, qp=[0.0, 0.0, 0.0], label='slide on shaft (J), z up: DZ(31, 22, 22) = s')
marker23 = Marker(id=23, qp=[0.05, 0.0, 1.0], zp=[0.05, 1.0, 1.0], xp=[0.05, 0.0, 2.0],
                  label='hinge A on shaft (J), z along +y')
marker24 = Marker(id=24, qp=[-0.05, 0.0, 1.0], zp=[-0.05, 1.0, 1.0], xp=[-0.05, 0.0, 2.0],
                  label='hinge B on shaft (J), z along +y')
body2 = Part(id=2, mass=0.3, cm=marker20, ip=[0.025002499999999997, 0.025002499999999997, 5e-06],
             wz=6.283185307179586, label='shaft')
marker20.body = body2
marker21.body = body2
marker22.body = body2
marker23.body = body2
marker24.body = body2
marker30 = Marker(id=30, qp=[0.0, 0.0, 0.5], label='slider cm')
marker31 = Marker(id=31, qp=[0.0, 0.0, 0.5], label='slider on shaft (I)')
marker32 = Marker(id=32, qp=[0.05, 0.0, 0.5], label='slider point E (spring 1, J)')
marker33 = Marker(id=33, qp=[-0.05, 0.0, 0.5], label='slider point F (spring 2, J)')
body3 = Part(id=3, mass=3.000000000000001, cm=marker30,
             ip=[0.005000000000000003, 0.005000000000000003, 0.005000000000000003],
             wz=6.283185307179586, label='slider')
marker30.body = body3
marker31.body = body3
marker32.body = body3
marker33.body = body3
marker40 = Marker(id=40, qp=[0.8915152508471434, 0.0, 0.5141509433962264],
                  label='rod 1 (+x) cm, global axes')
marker41 = Marker(id=41, qp=[0.05, 0.0, 1.0], zp=[0.05, 1.0, 1.0], xp=[0.05, 0.0, 2.0],
                  label='rod 1 (+x) hinge (I), z along +y')
marker42 = Marker(id=42, qp=[0.48301270189221934, 0.0, 0.75], label='rod 1 (+x) middle (spring I)')
marker43 = Marker(id=43, qp=[0.9160254037844388, 0.0, 0.5], label='rod 1 (+x) ball')
marker44 = Marker(id=44, qp=[0.8915152508471434, 0.0, 0.5141509433962264],
                  reuler=[1.5707963267948966, 0.5235987755982988, -1.5707963267948966],
                  label='rod 1 (+x) principal axes, x along the rod')
body4 = Part(id=4, mass=5.3, cm=marker40, im=marker44,
             ip=[5e-06, 0.09575721698113207, 0.09575721698113207], vy=5.601555525249295,
             wz=6.283185307179586, label='rod 1 (+x)')
marker40.body = body4
marker41.body = body4
marker42.body = body4
marker43.body = body4
marker44.body = body4
marker50 = Marker(id=50, qp=[-0.8915152508471434, 0.0, 0.5141509433962264],
                  label='rod 2 (-x) cm, global axes')
marker51 = Marker(id=51, qp=[-0.05, 0.0, 1.0], zp=[-0.05, 1.0, 1.0], xp=[-0.05, 0.0, 2.0],
                  label='rod 2 (-x) hinge (I), z along +y')
marker52 = Marker(id=52, qp=[-0.48301270189221934, 0.0, 0.75],
                  label='rod 2 (-x) middle (spring I)')
marker53 = Marker(id=53, qp=[-0.9160254037844388, 0.0, 0.5], label='rod 2 (-x) ball')
marker54 = Marker(id=54, qp=[-0.8915152508471434, 0.0, 0.5141509433962264],
                  zp=[-0.3915152508471435, 0.0, -0.35187446038821235],
                  xp=[-1.7575406546315822, 0.0, 0.014150943396226412],
                  label='rod 2 (-x) principal axes, x along the rod')
body5 = Part(id=5, mass=5.3, cm=marker50, im=marker54,
             ip=[5e-06, 0.09575721698113207, 0.09575721698113207], vy=-5.601555525249295,
             wz=6.283185307179586, label='rod 2 (-x)')
marker50.body = body5
marker51.body = body5
marker52.body = body5
marker53.body = body5
marker54.body = body5
Accgrav(igrav=0.0, jgrav=0.0, kgrav=-9.81)
joint1 = Joint(id=1, type='REVOLUTE', i=marker21, j=marker2, label='shaft on ground (z)')
joint2 = Joint(id=2, type='TRANSLATIONAL', i=marker31, j=marker22, label='slider on shaft (z)')
joint3 = Joint(id=3, type='REVOLUTE', i=marker41, j=marker23, label='rod 1 on shaft (hinge A)')
joint4 = Joint(id=4, type='REVOLUTE', i=marker51, j=marker24, label='rod 2 on shaft (hinge B)')
SpringDamper(id=1, i=marker42, j=marker32, type='TRANSLATION', k=800000.0, c=40000.0, length=0.5,
             force=0.0, label='coupler 1')
SpringDamper(id=2, i=marker52, j=marker33, type='TRANSLATION', k=800000.0, c=40000.0, length=0.5,
             force=0.0, label='coupler 2')
Request(id=1, f1='DZ(31,22,22)', f2='DM(42,32)', f3='DM(52,33)', f4='WZ(20)',
        f5='-ASIN(DZ(43,41))', f6='-ASIN(DZ(53,51))',
        cnames=['s', 'spring1_length', 'spring2_length', 'shaft_wz', 'theta1', 'theta2'])
Request(id=2,
        f1='0.5*0.3*(VX(20)**2+VY(20)**2+VZ(20)**2)+0.5*(0.025002499999999997*WX(20,0,20)**2+0.025002499999999997*WY(20,0,20)**2+5e-06*WZ(20,0,20)**2)+0.5*3.000000000000001*(VX(30)**2+VY(30)**2+VZ(30)**2)+0.5*(0.005000000000000003*WX(30,0,30)**2+0.005000000000000003*WY(30,0,30)**2+0.005000000000000003*WZ(30,0,30)**2)+0.5*5.3*(VX(40)**2+VY(40)**2+VZ(40)**2)+0.5*(5e-06*WX(40,0,44)**2+0.09575721698113207*WY(40,0,44)**2+0.09575721698113207*WZ(40,0,44)**2)+0.5*5.3*(VX(50)**2+VY(50)**2+VZ(50)**2)+0.5*(5e-06*WX(50,0,54)**2+0.09575721698113207*WY(50,0,54)**2+0.09575721698113207*WZ(50,0,54)**2)+9.81*(0.3*DZ(20)+3.000000000000001*DZ(30)+5.3*(DZ(40)+DZ(50)))+0.5*800000.0*((DM(42,32)-0.5)**2+(DM(52,33)-0.5)**2)',
        f2='0.3*(DX(20)*VY(20)-DY(20)*VX(20))+5e-06*WZ(20)+3.000000000000001*(DX(30)*VY(30)-DY(30)*VX(30))+0.005000000000000003*WZ(30)+5.3*(DX(40)*VY(40)-DY(40)*VX(40))+0.09575721698113207*WZ(40)+-0.09575221698113207*WX(40,0,44)*DZ(43,41)+5.3*(DX(50)*VY(50)-DY(50)*VX(50))+0.09575721698113207*WZ(50)+-0.09575221698113207*WX(50,0,54)*DZ(53,51)',
        f3='VR(42,32)', f4='VR(52,33)', cnames=['energy', 'Hz', 'spring1_rate', 'spring2_rate'])
Integrator(error=1e-06)

if __name__ == "__main__":
    model.simulate(type="DYNAMICS", end=10.0, dtout=0.01)
