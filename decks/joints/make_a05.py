"""Write the IFToMM A05 stiff flyball governor as a MotionSolve XML deck, and compute its
reference solution with an independent minimal-coordinate model.

Spec: IFToMM Library of Computational Benchmark Problems, problem A05 "Stiff flyball
governor" (http://lim.ii.udc.es/mbsbenchmark/dist/A05/A05_specification.xml, M. Gonzalez,
2005; https://www.iftomm-multibody.org/benchmark/problem/Stiff_flyball_governor/). The
specification file's body could not be read when this was written (only its header), so the data
below are those of two public implementations that cite it and agree with each other:
- the OpenSim implementation of the library (RehabEngGroup/MBSbenchmarksInOpenSim,
  help/benchmarks/A05_FlyballGovernor.rst and src/A05-FlyballGovernor/createModel.cpp,
  modelProperties.h): shaft, rods 1.0 x 0.01 x 0.01 m, slider 0.1 x 0.1 x 0.1 m, density
  3000 kg/m^3, two 5 kg point masses, spring-dampers K = 8e5 N/m, C = 4e4 N s/m, rest length
  0.5 m, s = 0.5 m, alpha = 30 deg, shaft speed 2 pi rad/s, gravity -9.81 z, 10 s;
- Exudyn's stiffFlyballGovernorKT.py (jgerstmayr/EXUDYN, main/pythonDev/Examples; the same
  numbers with k = 8e5, c = 4e4, omega0 = 2 pi, tEnd = 10 s).
(numerics.md section 7 of the shared reference confirms K, C, rest length and the 5 kg
masses.)

Geometry (both implementations): the shaft (0.3 kg) turns freely about global z on a
revolute at the ground origin, its centre at z = 0.5; the slider (3 kg, centre at height s,
s(0) = 0.5) slides on it (translational joint: it turns with the shaft). The rods (0.3 kg
each) hang from revolutes at (+-0.05, 0, 1) on the shaft whose axes are the shaft's y, each
30 deg below the horizontal, pointing outwards; a 5 kg point mass sits at each rod's far end
(1 m from the hinge). Each spring-damper joins the middle of a rod (0.5 m from its hinge)
to the slider's side point (+-0.05, 0, s): at t = 0 hinge, rod middle and slider point form
an equilateral triangle of 0.5 m sides, so the springs start at their rest length.
Initial velocities: every body turns with the shaft at 2 pi rad/s about z, nothing else
moves (OpenSim: the shaft coordinate's speed 2 pi, the others 0; Exudyn KT: the same).
The shaft is not driven: its speed changes as the balls rise (angular momentum about z is
conserved exactly: gravity is along z and no joint resists a turn about z).

Decisions (this deck):
- each rod and its point mass are one rigid body of 5.3 kg, centre of mass
  d = (0.3 * 0.5 + 5 * 1) / 5.3 m from the hinge, inertia about it: axial that of the rod
  (0.3 (0.01^2 + 0.01^2) / 12), transverse the rod's 0.3 (1 + 0.01^2) / 12 plus the
  parallel-axis shifts of rod and point mass; given on an im marker along the rod while
  the cg marker keeps global axes (so w_ic_z = 2 pi is the global spin);
- shaft, slider inertias of the uniform boxes about their centres;
- the quantity compared: s(t), the slider centre's height (OpenSim's coordinate s; Exudyn's
  slider position), at the output times over 10 s.

Reference (reference() below): Lagrange's equations in (s, theta1, theta2) with the shaft
angle eliminated through its conserved momentum p = J(theta1, theta2) Omega (Routh), the
springs' length and rate written out in closed form; solved with SciPy's Radau at rtol =
atol = 1e-12 (the run at 1e-11 agrees to 1.6e-12 m). It shares nothing with pysolver but
the numbers above. It agrees within 2.3e-4 m (less than a pixel) with the library's own
reference s(t) as plotted in the OpenSim docs (help/images/5MBS_PlotResults.png, every
0.1 s to 3 s; digitized in tests/test_iftomm_a05.py), which checks the data and geometry.

Run: ``python decks/joints/make_a05.py`` writes iftomm_a05_flyball.xml here;
``--reference`` prints the reference table (times, s, theta1, theta2, Omega) used by
tests/test_iftomm_a05.py.
"""
import argparse
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))

# ---- data (see the module docstring for the sources) -------------------------------------
RHO = 3000.0
G = 9.81
L_ROD = 1.0
W = 0.01                       # rod and shaft section side
M_ROD = RHO * L_ROD * W * W    # 0.3 kg
M_SHAFT = M_ROD                # 0.3 kg
M_SLIDER = RHO * 0.1 ** 3      # 3 kg
M_BALL = 5.0
A = 0.05                       # hinge offset from the axis, = slider half width
H = 1.0                        # hinge height (top of the shaft)
S0 = 0.5
ALPHA = math.radians(30.0)     # rods below the horizontal at t = 0
OMEGA0 = 2 * math.pi
K = 8e5
C = 4e4
L0 = 0.5
L_SPRING_AT = 0.5              # spring point on the rod, from the hinge

M_R = M_ROD + M_BALL                                   # rod + ball
D = (M_ROD * 0.5 * L_ROD + M_BALL * L_ROD) / M_R      # cm from the hinge
I_AX = M_ROD * (W * W + W * W) / 12                    # about the rod axis
I_TR = (M_ROD * (L_ROD ** 2 + W * W) / 12 + M_ROD * (0.5 * L_ROD - D) ** 2
        + M_BALL * (L_ROD - D) ** 2)                   # transverse, about the cm
I_SHAFT_AX = M_SHAFT * (W * W + W * W) / 12
I_SHAFT_TR = M_SHAFT * (1.0 + W * W) / 12
I_SLIDER = M_SLIDER * (0.1 ** 2 + 0.1 ** 2) / 12


def _f(x):
    return repr(float(x))


def deck(tol=1e-6, end=10.0, dt=0.01):
    ca, sa = math.cos(ALPHA), math.sin(ALPHA)
    els = []
    add = els.append

    def marker(mid, body, pos, axes=None, label=""):
        s = (f'<Reference_Marker id="{mid}" body_id="{body}" pos_x="{_f(pos[0])}" '
             f'pos_y="{_f(pos[1])}" pos_z="{_f(pos[2])}"')
        if axes is not None:       # columns x, y, z
            (x, y, z) = axes
            s += (f' a00="{_f(x[0])}" a10="{_f(x[1])}" a20="{_f(x[2])}"'
                  f' a01="{_f(y[0])}" a11="{_f(y[1])}" a21="{_f(y[2])}"'
                  f' a02="{_f(z[0])}" a12="{_f(z[1])}" a22="{_f(z[2])}"')
        add(s + f' label="{label}"/>')

    hinge_axes = ((0, 0, 1), (1, 0, 0), (0, 1, 0))    # z along +y (the hinge axis)
    add('<Units mass="KILOGRAM" length="METER" time="SECOND" force="NEWTON"/>')
    add('<Body_Rigid id="1" isground="TRUE"/>')
    marker(1, 1, (0, 0, 0), label="global")
    marker(2, 1, (0, 0, 0), label="shaft pivot on ground (J), z up")
    # shaft
    add('<!-- shaft: 1 x 0.01 x 0.01 m, 0.3 kg, free to turn about z -->')
    marker(20, 2, (0, 0, 0.5), label="shaft cm")
    marker(21, 2, (0, 0, 0), label="shaft pivot (I)")
    marker(22, 2, (0, 0, 0), label="slide on shaft (J), z up: DZ(31, 22, 22) = s")
    marker(23, 2, (A, 0, H), hinge_axes, "hinge A on shaft (J), z along +y")
    marker(24, 2, (-A, 0, H), hinge_axes, "hinge B on shaft (J), z along +y")
    add(f'<Body_Rigid id="2" cg_id="20" mass="{_f(M_SHAFT)}" inertia_xx="{_f(I_SHAFT_TR)}" '
        f'inertia_yy="{_f(I_SHAFT_TR)}" inertia_zz="{_f(I_SHAFT_AX)}" w_ic_z="{_f(OMEGA0)}" '
        'label="shaft"/>')
    # slider
    add('<!-- slider: 0.1 m cube, 3 kg, centre at height s -->')
    marker(30, 3, (0, 0, S0), label="slider cm")
    marker(31, 3, (0, 0, S0), label="slider on shaft (I)")
    marker(32, 3, (A, 0, S0), label="slider point E (spring 1, J)")
    marker(33, 3, (-A, 0, S0), label="slider point F (spring 2, J)")
    add(f'<Body_Rigid id="3" cg_id="30" mass="{_f(M_SLIDER)}" inertia_xx="{_f(I_SLIDER)}" '
        f'inertia_yy="{_f(I_SLIDER)}" inertia_zz="{_f(I_SLIDER)}" w_ic_z="{_f(OMEGA0)}" '
        'label="slider"/>')
    # rods with their balls
    for b, sign in ((4, 1), (5, -1)):
        u = (sign * ca, 0.0, -sa)                       # along the rod, outwards
        y = (0.0, 1.0, 0.0)
        n = (u[1] * y[2] - u[2] * y[1], u[2] * y[0] - u[0] * y[2], u[0] * y[1] - u[1] * y[0])
        hinge = (sign * A, 0.0, H)

        def along(r, hinge=hinge, u=u):
            return tuple(hinge[i] + r * u[i] for i in range(3))
        cm = along(D)
        name = "rod 1 (+x)" if sign > 0 else "rod 2 (-x)"
        add(f'<!-- {name}: rod 0.3 kg + 5 kg ball at its end, one body -->')
        marker(10 * b, b, cm, label=f"{name} cm, global axes")
        marker(10 * b + 1, b, hinge, hinge_axes, f"{name} hinge (I), z along +y")
        marker(10 * b + 2, b, along(L_SPRING_AT), label=f"{name} middle (spring I)")
        marker(10 * b + 3, b, along(L_ROD), label=f"{name} ball")
        marker(10 * b + 4, b, cm, (u, y, n), f"{name} principal axes, x along the rod")
        add(f'<Body_Rigid id="{b}" cg_id="{10 * b}" im_id="{10 * b + 4}" mass="{_f(M_R)}" '
            f'inertia_xx="{_f(I_AX)}" inertia_yy="{_f(I_TR)}" inertia_zz="{_f(I_TR)}" '
            f'v_ic_y="{_f(OMEGA0 * cm[0])}" w_ic_z="{_f(OMEGA0)}" label="{name}"/>')
    add(f'<Force_Gravity grav_x="0" grav_y="0" grav_z="{_f(-G)}"/>')
    add('<Constraint_Joint id="1" label="shaft on ground (z)" type="REVOLUTE" '
        'i_marker_id="21" j_marker_id="2"/>')
    add('<Constraint_Joint id="2" label="slider on shaft (z)" type="TRANSLATIONAL" '
        'i_marker_id="31" j_marker_id="22"/>')
    add('<Constraint_Joint id="3" label="rod 1 on shaft (hinge A)" type="REVOLUTE" '
        'i_marker_id="41" j_marker_id="23"/>')
    add('<Constraint_Joint id="4" label="rod 2 on shaft (hinge B)" type="REVOLUTE" '
        'i_marker_id="51" j_marker_id="24"/>')
    for sid, i_m, j_m in ((1, 42, 32), (2, 52, 33)):
        add(f'<Force_SpringDamper id="{sid}" label="coupler {sid}" type="TRANSLATIONAL" '
            f'i_marker_id="{i_m}" j_marker_id="{j_m}" stiffness="{_f(K)}" damping="{_f(C)}" '
            f'length="{_f(L0)}" preload="0"/>')

    # requests: 1 = s, spring lengths, shaft speed, rod angles below the horizontal;
    # 2 = energy, angular momentum about z, spring rates
    def ke(cm, Ixx, Iyy, Izz, ax):
        return (f"0.5*{_f(M_R if cm in (40, 50) else (M_SHAFT if cm == 20 else M_SLIDER))}"
                f"*(VX({cm})**2+VY({cm})**2+VZ({cm})**2)"
                f"+0.5*({_f(Ixx)}*WX({cm},0,{ax})**2+{_f(Iyy)}*WY({cm},0,{ax})**2"
                f"+{_f(Izz)}*WZ({cm},0,{ax})**2)")
    energy = "+".join([
        ke(20, I_SHAFT_TR, I_SHAFT_TR, I_SHAFT_AX, 20),
        ke(30, I_SLIDER, I_SLIDER, I_SLIDER, 30),
        ke(40, I_AX, I_TR, I_TR, 44),
        ke(50, I_AX, I_TR, I_TR, 54),
        f"{_f(G)}*({_f(M_SHAFT)}*DZ(20)+{_f(M_SLIDER)}*DZ(30)+{_f(M_R)}*(DZ(40)+DZ(50)))",
        f"0.5*{_f(K)}*((DM(42,32)-{_f(L0)})**2+(DM(52,33)-{_f(L0)})**2)"])

    def hz(cm, m):
        return f"{_f(m)}*(DX({cm})*VY({cm})-DY({cm})*VX({cm}))"
    # rod: I w = I_TR w + (I_AX - I_TR) (w . e) e, e along the rod, e_z = DZ(ball, hinge) / 1
    momentum = "+".join([
        hz(20, M_SHAFT) + f"+{_f(I_SHAFT_AX)}*WZ(20)",
        hz(30, M_SLIDER) + f"+{_f(I_SLIDER)}*WZ(30)",
        hz(40, M_R) + f"+{_f(I_TR)}*WZ(40)+{_f(I_AX - I_TR)}*WX(40,0,44)*DZ(43,41)",
        hz(50, M_R) + f"+{_f(I_TR)}*WZ(50)+{_f(I_AX - I_TR)}*WX(50,0,54)*DZ(53,51)"])
    add('<Post_Request id="1" expr1="DZ(31,22,22)" expr2="DM(42,32)" expr3="DM(52,33)" '
        'expr4="WZ(20)" expr5="-ASIN(DZ(43,41))" expr6="-ASIN(DZ(53,51))" '
        'name1="s" name2="spring1_length" name3="spring2_length" name4="shaft_wz" '
        'name5="theta1" name6="theta2"/>')
    add(f'<Post_Request id="2" expr1="{energy}" expr2="{momentum}" expr3="VR(42,32)" '
        'expr4="VR(52,33)" name1="energy" name2="Hz" name3="spring1_rate" '
        'name4="spring2_rate"/>')
    add(f'<Param_Transient integr_tol="{tol!r}"/>')
    model = "\n    ".join(els)
    header = HEADER.format(d=D, i_ax=I_AX, i_tr=I_TR, m_r=M_R, i_sl=I_SLIDER,
                           i_sh=I_SHAFT_AX, i_sht=I_SHAFT_TR)
    return (f'<?xml version="1.0"?>\n{header}\n<MotionSolve>\n  <Model>\n    {model}\n'
            f'  </Model>\n  <Simulate analysis_type="Transient" end_time="{end!r}" '
            f'print_interval="{dt!r}"/>\n</MotionSolve>\n')


HEADER = """<!-- IFToMM A05: stiff flyball governor (benchmark deck for Force_SpringDamper with
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
     Deck decisions: each rod and its ball are one body of {m_r:.10g} kg, cm {d:.10g} m
     from the hinge, inertia (principal axes on the im marker, x along the rod) axial
     {i_ax:.10g}, transverse {i_tr:.10g} kg m^2; shaft axial {i_sh:.10g}, transverse
     {i_sht:.10g}; slider {i_sl:.10g} kg m^2.
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
     -->"""


# ---- reference: minimal coordinates ------------------------------------------------------
def _spring(s, th, sd, thd):
    """Length, rate and gradient (d/ds, d/dtheta) of one coupler."""
    dx = L_SPRING_AT * math.cos(th)
    dz = H - L_SPRING_AT * math.sin(th) - s
    ell = math.hypot(dx, dz)
    dl_ds = -dz / ell
    dl_dth = (dx * (-L_SPRING_AT * math.sin(th)) + dz * (-L_SPRING_AT * math.cos(th))) / ell
    return ell, dl_ds * sd + dl_dth * thd, dl_ds, dl_dth


def inertia_z(th1, th2):
    """J: the moment of inertia of the whole governor about z for rod angles th1, th2."""
    j = I_SHAFT_AX + I_SLIDER
    for th in (th1, th2):
        j += M_R * (A + D * math.cos(th)) ** 2 + I_AX * math.sin(th) ** 2 \
            + I_TR * math.cos(th) ** 2
    return j


def momentum0():
    return inertia_z(ALPHA, ALPHA) * OMEGA0


def rhs(t, x, p):
    s, th1, th2, sd, thd1, thd2 = x
    J = inertia_z(th1, th2)
    om = p / J
    m_th = M_R * D * D + I_TR                        # about the hinge
    fs = -M_SLIDER * G
    acc = []
    for th, thd in ((th1, thd1), (th2, thd2)):
        ell, rate, dl_ds, dl_dth = _spring(s, th, sd, thd)
        f = K * (ell - L0) + C * rate                 # tension
        fs -= f * dl_ds
        dJ = -2 * M_R * (A + D * math.cos(th)) * D * math.sin(th) \
            + 2 * (I_AX - I_TR) * math.sin(th) * math.cos(th)
        # Routh: m_th th'' = 1/2 dJ/dth Omega^2 - dV/dth - f dl/dth
        acc.append((0.5 * dJ * om * om + M_R * G * D * math.cos(th) - f * dl_dth) / m_th)
    return [sd, thd1, thd2, fs / M_SLIDER, acc[0], acc[1]]


def reference(times, rtol=1e-12, atol=1e-12):
    """(s, theta1, theta2, Omega) at the given times from the minimal-coordinate model."""
    import numpy as np
    from scipy.integrate import solve_ivp
    p = momentum0()
    sol = solve_ivp(rhs, (0.0, float(times[-1])), [S0, ALPHA, ALPHA, 0.0, 0.0, 0.0],
                    method="Radau", t_eval=times, rtol=rtol, atol=atol, args=(p,))
    assert sol.success, sol.message
    s, th1, th2 = sol.y[0], sol.y[1], sol.y[2]
    om = p / np.array([inertia_z(a, b) for a, b in zip(th1, th2)])
    return s, th1, th2, om


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("-o", default=os.path.join(HERE, "iftomm_a05_flyball.xml"))
    ap.add_argument("--reference", action="store_true",
                    help="print the reference table instead of writing the deck")
    args = ap.parse_args()
    if args.reference:
        import numpy as np
        times = np.arange(0, 10.0 + 1e-9, 0.25)
        s, th1, th2, om = reference(times)
        s2 = reference(times, 1e-11, 1e-11)[0]
        print(f"# max |s(1e-12) - s(1e-11)| = {np.abs(s - s2).max():.3e} m")
        print("# t, s, theta1, theta2, Omega")
        for row in zip(times, s, th1, th2, om):
            print("(" + ", ".join(f"{v!r}" for v in map(float, row)) + "),")
        return
    with open(args.o, "w") as fh:
        fh.write(deck())
    print("wrote", args.o)


if __name__ == "__main__":
    main()
