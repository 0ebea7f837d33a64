"""Andrews' squeezing mechanism (Test Set for IVP solvers) as a pysolver deck: seven rigid
bodies in the plane, the revolute joints as stiff bilateral Force_Penalty pairs (DX, DY of
coincident markers), the driving torque and the spring as Force_Scalar_TwoBody.

Run: ``python benchmarks/andrews.py [--growth=G] [--newton=C] [penalty ...]`` (run options
max_step_growth, nonlin_conv_coef): the angles at t = 0.03 against
the Test Set reference (PSIDE, rtol = atol = 1e-14; see shared/reference/numerics.md), for each penalty.
Geometry (Hairer & Wanner, Solving ODEs II, sec. VII.7): crank 1 about O; rod 2 from P on the
crank to D; body 3 about B, body 5 and body 7 about A; rod 4 from E on body 5 to D; rod 6 from F
on body 7 to D. Centres of mass and inertias reproduce the Test Set's mass matrix.
"""
import math
import sys

import numpy as np

P = dict(m1=.04325, m2=.00365, m3=.02373, m4=.00706, m5=.07050, m6=.00706, m7=.05498,
         xa=-.06934, ya=-.00227, xb=-.03635, yb=.03273, xc=.014, yc=.072,
         i1=2.194e-6, i2=4.410e-7, i3=5.255e-6, i4=5.667e-7, i5=1.169e-5, i6=5.667e-7,
         i7=1.912e-5, d=28e-3, da=115e-4, e=2e-2, ea=1421e-5, rr=7e-3, ra=92e-5, ss=35e-3,
         sa=1874e-5, sb=1043e-5, sc=18e-3, sd=2e-2, ta=2308e-5, tb=916e-5, u=4e-2, ua=1228e-5,
         ub=449e-5, zf=2e-2, zt=4e-2, fa=1421e-5, mom=0.033, c0=4530., l0=0.07785)
Q0 = dict(beta=-0.0617138900142764496358948458001, Theta=0.0,
          gamma=0.455279819163070380255912382449, Phi=0.222668390165885884674473185609,
          delta=0.487364979543842550225598953530, Omega=-0.222668390165885884674473185609,
          epsilon=1.23054744454982119249735015568)
#: Angles at t = 0.03 (Test Set, PSIDE at rtol = atol = 1e-14).
REFERENCE = dict(beta=0.1581077119629904e+2, Theta=-0.1575637105984298e+2,
                 gamma=0.4082224013073101e-1, Phi=-0.5347301163226948, delta=0.5244099658805304,
                 Omega=0.5347301163226948, epsilon=0.1048080741042263e+1)


def _e(a):
    return np.array([math.cos(a), math.sin(a)])


def _n(a):
    return np.array([math.sin(a), -math.cos(a)])


def geometry(q=Q0, p=P):
    """Body angles, centres of mass and joint points at the configuration q."""
    b, T, g, F, dl, O, ep = (q[k] for k in ("beta", "Theta", "gamma", "Phi", "delta", "Omega",
                                              "epsilon"))
    A, B, C = np.array([p["xa"], p["ya"]]), np.array([p["xb"], p["yb"]]), \
        np.array([p["xc"], p["yc"]])
    Pj = p["rr"] * _e(b)
    D = Pj - p["d"] * _e(b + T)
    E = A + p["zt"] * _e(dl)
    Fj = A + p["u"] * _n(ep)
    angles = {1: b, 2: b + T, 3: g, 4: F + dl, 5: dl, 6: O + ep, 7: ep}
    com = {1: p["ra"] * _e(b), 2: Pj - p["da"] * _e(b + T),
           3: B + p["sa"] * _n(g) + p["sb"] * _e(g), 4: E + (p["e"] - p["ea"]) * _n(F + dl),
           5: A + p["ta"] * _e(dl) + p["tb"] * _n(dl), 6: Fj + (p["zf"] - p["fa"]) * _e(O + ep),
           7: A + p["ua"] * _n(ep) + p["ub"] * _e(ep)}
    spring = B + p["sd"] * _e(g) + p["sc"] * _n(g)
    pts = dict(O=np.zeros(2), P=Pj, D=D, B=B, E=E, A=A, F=Fj, C=C, S=spring)
    return angles, com, pts


def deck(penalty, penalty1=None, tol=1e-9, end=0.03, dt=1e-4):
    """The mechanism as MotionSolve XML text."""
    p = P
    c = 2 * math.sqrt(penalty * 0.01) if penalty1 is None else penalty1
    angles, com, pts = geometry()
    mass = {k: p[f"m{k}"] for k in range(1, 8)}
    inertia = {k: p[f"i{k}"] for k in range(1, 8)}
    els = ['<Body_Rigid id="100" isground="TRUE"/>']
    mid = [1000]

    def marker(body, xy, psi=0.0):
        mid[0] += 1
        els.append(f'<Reference_Marker id="{mid[0]}" body_id="{body}" pos_x="{float(xy[0])!r}" '
                   f'pos_y="{float(xy[1])!r}" psi="{float(psi)!r}"/>')
        return mid[0]

    cm = {}
    for k in range(1, 8):
        cm[k] = marker(k, com[k], angles[k])
        ik = inertia[k]
        els.append(f'<Body_Rigid id="{k}" cg_id="{cm[k]}" mass="{mass[k]!r}" '
                   f'inertia_xx="{ik!r}" inertia_yy="{ik!r}" inertia_zz="{ik!r}"/>')
    # joints: (point, body, body) with 100 = ground
    joints = [("O", 1, 100), ("P", 1, 2), ("D", 2, 3), ("D", 2, 4), ("D", 2, 6), ("B", 3, 100),
              ("E", 4, 5), ("A", 5, 100), ("A", 7, 100), ("F", 6, 7)]
    pid = 0
    for name, bi, bj in joints:
        mi, mj = marker(bi, pts[name]), marker(bj, pts[name])
        for axis in "XY":
            pid += 1
            els.append(f'<Force_Penalty id="{pid}" label="joint {name} {bi}-{bj} {axis}" '
                       f'expr="D{axis}({mi},{mj})" penalty="{penalty!r}" penalty1="{c!r}"/>')
    crank, ground = marker(1, pts["O"]), marker(100, pts["O"])
    els.append(f'<Force_Scalar_TwoBody id="1" label="driving torque" type="Torque" '
               f'i_marker_id="{crank}" j_marker_id="{ground}" val="{p["mom"]!r}"/>')
    sp, sc = marker(3, pts["S"]), marker(100, pts["C"])
    els.append(f'<Force_Scalar_TwoBody id="2" label="spring" type="Force" i_marker_id="{sp}" '
               f'j_marker_id="{sc}" expr="-{p["c0"]!r}*(DM({sp},{sc}) - {p["l0"]!r})"/>')
    chans = " ".join(f'expr{k}="AZ({cm[k]})"' for k in range(1, 8))
    els.append(f'<Post_Request id="1" {chans}/>')
    els.append(f'<Param_Transient integr_tol="{tol!r}"/>')
    return ("<MotionSolve><Model>\n" + "\n".join(els) + "\n</Model>\n"
            f'<Simulate analysis_type="Transient" end_time="{end!r}" print_interval="{dt!r}"/>\n'
            "</MotionSolve>\n")


def angles_at_end(res):
    """The seven Test Set angles at the last output, from the unwrapped body angles."""
    th = {k: np.unwrap(res.request(1)[:, k - 1])[-1] for k in range(1, 8)}
    return dict(beta=th[1], Theta=th[2] - th[1], gamma=th[3], Phi=th[4] - th[5], delta=th[5],
                Omega=th[6] - th[7], epsilon=th[7])


def error(res):
    """Largest error of the seven angles against the reference, relative to max(1, |ref|)."""
    got = angles_at_end(res)
    return max(abs(got[k] - REFERENCE[k]) / max(1.0, abs(REFERENCE[k])) for k in REFERENCE)


def main(penalties, **options):
    """Print error, steps, Jacobians and seconds for each penalty; options go to run()."""
    import time

    import pysolver
    print(f"{'penalty':>9} {'error':>9} {'steps':>7} {'njac':>6} {'s':>7}")
    for k in penalties:
        model = pysolver.loads(deck(k))
        t0 = time.perf_counter()
        res = model.run(**options)
        dt = time.perf_counter() - t0
        print(f"{k:9.0e} {error(res):9.2e} {res.stats['steps']:7d} {res.stats['njac']:6d} "
              f"{dt:7.2f}  {res.message if not res.success else ''}", flush=True)


if __name__ == "__main__":
    args = sys.argv[1:]
    opts = {}
    flags = {"--growth": "max_step_growth", "--newton": "nonlin_conv_coef"}
    while args and args[0].split("=")[0] in flags:
        key, value = args.pop(0).split("=")
        opts[flags[key]] = float(value)
    main([float(a) for a in args] or [1e6, 1e7, 1e8], **opts)
