"""Converged reference solutions for the joint benchmark decks in decks/joints/, computed
without pysolver: closed forms where they exist, otherwise minimal- or joint-coordinate ODEs
integrated by SciPy's DOP853 at two tight tolerances (their difference is the accuracy
evidence), and Exudyn (PyPI ``exudyn``, the project's bench extra) as an independent
index-3 solver and as the comparator whose step counts and timings go to the README.

Run: ``python benchmarks/joint_references.py [--no-exudyn] [--out PATH]``; writes
benchmarks/data/joint_references.json (about 95 s on one core, 10 s with --no-exudyn;
Exudyn runs one thread). Every problem's parameters are the ones written in its deck's header comment.

Problems (deck in decks/joints/):
- pendulum_revolute: 1 kg point-like body (sphere inertia 1e-3 kg m^2) 2 m from a revolute
  pivot, released horizontally at rest, 5 s. Exact: Jacobi elliptic functions.
- spherical_pendulum: the same body 1 m from a spherical pivot, 60 deg from the downward
  vertical, 2 m/s azimuthal speed, 5 s. Exact reduction: a symmetric top with zero spin
  (two coordinates theta, phi; p_phi conserved).
- slider_crank: crank 0.1 m driven at 2 pi rad/s, rod 0.4 m, slider on x, 2 s. 0 DOF:
  closed-form kinematics; driving torque from the energy rate (complex-step derivative).
- iftomm_a02_fourbar: IFToMM A02, N = 40, 20 s. The parallelogram branch is a 1-DOF
  pendulum (rotating regime): closed form via Jacobi amplitude + DOP853.
- iftomm_a04_bricard: IFToMM A04, 10 s, from rest. Joint coordinates of the open chain with
  the loop closed at velocity/acceleration level (6x6 screw matrix of rank 5, null-space
  projection, Kane's equation for the one independent speed); Exudyn cross-check.
- iftomm_a03_andrews: Test Set for IVP solvers reference (PSIDE) reproduced by a planar
  absolute-coordinate index-1 ODE built from benchmarks/andrews.py's geometry (the same
  geometry decks/joints/make_a03.py writes into the deck).
"""
import argparse
import json
import math
import os
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp
from scipy.special import ellipj, ellipk

HERE = os.path.dirname(os.path.abspath(__file__))
G = 9.81
TOLS = (1e-10, 1e-12)          # the two DOP853 tolerances whose difference is reported


def _ivp(rhs, t_end, y0, times, rtol, method="DOP853"):
    sol = solve_ivp(rhs, (0.0, t_end), y0, method=method, t_eval=times, rtol=rtol,
                    atol=rtol * 1e-2, dense_output=False)
    if not sol.success:
        raise RuntimeError(sol.message)
    return sol


def _maxdiff(a, b):
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b))))


def _l(a):
    return [float(v) for v in np.asarray(a).ravel()]


# ---------------------------------------------------------------------------------------
# pendulum on a revolute joint
PEND = dict(m=1.0, L=2.0, I=1e-3, g=G, t_end=5.0, dt_out=0.05)


def pendulum_exact(t, p=PEND):
    """Closed form: phi (from the downward vertical) with sin(phi/2) = k sn(K - w0 t | k^2),
    k = sin(phi0/2), phi0 = pi/2 (released horizontally at rest). Returns x, y, vx, vy, phi."""
    w0 = math.sqrt(p["m"] * p["g"] * p["L"] / (p["m"] * p["L"] ** 2 + p["I"]))
    k = math.sin(math.pi / 4)
    K = ellipk(k * k)
    sn, cn, dn, _ = ellipj(K - w0 * np.asarray(t), k * k)
    phi = 2 * np.arcsin(k * sn)
    phid = -2 * k * w0 * cn * dn / np.cos(phi / 2)
    L = p["L"]
    return L * np.sin(phi), -L * np.cos(phi), L * np.cos(phi) * phid, L * np.sin(phi) * phid, phi


def pendulum_period(p=PEND):
    w0 = math.sqrt(p["m"] * p["g"] * p["L"] / (p["m"] * p["L"] ** 2 + p["I"]))
    return 4 * ellipk(0.5) / w0


def pendulum_ode(times, rtol, p=PEND):
    J = p["m"] * p["L"] ** 2 + p["I"]
    c = p["m"] * p["g"] * p["L"] / J

    def rhs(t, y):                      # y = (phi, phid), phi from the downward vertical
        return [y[1], -c * math.sin(y[0])]
    sol = _ivp(rhs, p["t_end"], [math.pi / 2, 0.0], times, rtol)
    phi = sol.y[0]
    return p["L"] * np.sin(phi), -p["L"] * np.cos(phi), sol.nfev


def pendulum():
    p = PEND
    times = np.round(np.arange(0, p["t_end"] + 1e-9, p["dt_out"]), 12)
    x, y, vx, vy, phi = pendulum_exact(times)
    J = p["m"] * p["L"] ** 2 + p["I"]
    phid = np.where(np.abs(np.cos(phi)) > 0.5, vx / (p["L"] * np.cos(phi) + 1e-300),
                    vy / (p["L"] * np.sin(phi) + 1e-300))
    energy = 0.5 * J * phid ** 2 + p["m"] * p["g"] * y
    ode = {r: pendulum_ode(times, r) for r in TOLS}
    d_ode = {str(r): max(_maxdiff(ode[r][0], x), _maxdiff(ode[r][1], y)) for r in TOLS}
    T = pendulum_period()
    # joint force on the body (Adams JOINT(1, 0, 2..3, 0): on the I marker's body)
    w0sq = p["m"] * p["g"] * p["L"] / J
    phidd = -w0sq * np.sin(phi)
    ax = p["L"] * (phidd * np.cos(phi) - phid ** 2 * np.sin(phi))
    ay = p["L"] * (phidd * np.sin(phi) + phid ** 2 * np.cos(phi))
    return dict(
        deck="decks/joints/pendulum_revolute.xml",
        description="1 kg body, centre of mass 2 m from a revolute pivot (axis global z), "
                    "sphere inertia 1e-3 kg m^2 about every axis (a 5 cm sphere), gravity "
                    "-9.81 y, released at rest with the centre of mass at (2, 0, 0); 5 s.",
        parameters=p,
        method="Closed form with Jacobi elliptic functions (scipy.special.ellipj): phi from "
               "the downward vertical, sin(phi/2) = k sn(K(k) - w0 t | k^2), k = sin(pi/4), "
               "w0^2 = m g L / (m L^2 + I). Cross-checked by DOP853 on phi'' = -w0^2 sin phi.",
        accuracy=dict(closed_form="machine precision (~1e-15 m)",
                      dop853_vs_closed_form_max_m=d_ode),
        period_s=T, period_formula="4 K(m=1/2) / w0",
        times=_l(times), x=_l(x), y=_l(y), vx=_l(vx), vy=_l(vy),
        energy=_l(energy),
        joint_force_on_body_x=_l(p["m"] * ax), joint_force_on_body_y=_l(p["m"] * (ay + p["g"])),
        compare="centre-of-mass position (x, y) and velocity at the output times; energy "
                "0.5 (m L^2 + I) phid^2 + m g y = 0 exactly; joint_force_on_body = m a - m g "
                "(the force the joint applies to the pendulum, global axes: Adams "
                "JOINT(1,0,2..3,0) with the I marker on the pendulum).",
    )


# ---------------------------------------------------------------------------------------
# spherical pendulum
SPH = dict(m=1.0, L=1.0, I=1e-3, g=G, theta0_deg=60.0, v0=2.0, t_end=5.0, dt_out=0.05)


def spherical_state0(p=SPH):
    th = math.radians(p["theta0_deg"])
    L, v = p["L"], p["v0"]
    r = np.array([L * math.sin(th), -L * math.cos(th), 0.0])
    vel = np.array([0.0, 0.0, v])
    w = np.cross(r, vel) / L ** 2             # no spin about the rod
    return r, vel, w


def spherical_ode(times, rtol, p=SPH):
    """theta from the downward vertical (-y), phi azimuth from +x towards +z:
    r = L (sin th cos ph, -cos th, sin th sin ph). Symmetric top about the pivot with
    I1 = I + m L^2, spin 0: I1 th'' = I1 sin th cos th ph'^2 - m g L sin th,
    p_phi = I1 sin^2 th ph' constant."""
    L, m, g = p["L"], p["m"], p["g"]
    I1 = p["I"] + m * L * L
    th0 = math.radians(p["theta0_deg"])
    phd0 = p["v0"] / (L * math.sin(th0))
    pphi = I1 * math.sin(th0) ** 2 * phd0

    def rhs(t, y):
        th, thd, ph = y
        s = math.sin(th)
        phd = pphi / (I1 * s * s)
        return [thd, s * math.cos(th) * phd * phd - m * g * L * s / I1, phd]
    sol = _ivp(rhs, p["t_end"], [th0, 0.0, 0.0], times, rtol)
    th, thd, ph = sol.y
    phd = pphi / (I1 * np.sin(th) ** 2)
    x = L * np.sin(th) * np.cos(ph)
    y = -L * np.cos(th)
    z = L * np.sin(th) * np.sin(ph)
    energy = 0.5 * I1 * (thd ** 2 + np.sin(th) ** 2 * phd ** 2) + m * g * y
    return dict(th=th, x=x, y=y, z=z, energy=energy, pphi=pphi, nfev=sol.nfev)


def spherical_turning_points(p=SPH):
    """theta range from energy and p_phi conservation: roots of E - V_eff(theta) = 0."""
    from scipy.optimize import brentq
    L, m, g = p["L"], p["m"], p["g"]
    I1 = p["I"] + m * L * L
    th0 = math.radians(p["theta0_deg"])
    phd0 = p["v0"] / (L * math.sin(th0))
    pphi = I1 * math.sin(th0) ** 2 * phd0

    def veff(th):
        return pphi ** 2 / (2 * I1 * math.sin(th) ** 2) - m * g * L * math.cos(th)
    E = veff(th0)
    f = lambda th: veff(th) - E
    # th0 is one turning point (th' = 0 there); the other is on the side where f < 0
    lo = brentq(f, 1e-6, th0 - 1e-9) if f(th0 - 1e-3) < 0 else th0
    hi = brentq(f, th0 + 1e-9, math.pi - 1e-6) if f(th0 + 1e-3) < 0 else th0
    return lo, hi


def spherical():
    p = SPH
    times = np.round(np.arange(0, p["t_end"] + 1e-9, p["dt_out"]), 12)
    runs = {r: spherical_ode(times, r) for r in TOLS}
    a, b = runs[TOLS[0]], runs[TOLS[1]]
    d = max(_maxdiff(a[k], b[k]) for k in "xyz")
    lo, hi = spherical_turning_points()
    r0, v0, w0 = spherical_state0()
    return dict(
        deck="decks/joints/spherical_pendulum.xml",
        description="1 kg body (sphere inertia 1e-3 kg m^2), centre 1 m from a spherical "
                    "pivot at the origin, started 60 deg from the downward vertical (-y) at "
                    "r0 = (sin 60, -cos 60, 0) m with velocity (0, 0, 2) m/s and angular "
                    "velocity r0 x v0 / L^2 (no spin about the rod); gravity -9.81 y; 5 s.",
        parameters=p,
        initial_state=dict(r0=_l(r0), v0=_l(v0), w0=_l(w0)),
        method="Exact reduction to two coordinates: with isotropic central inertia the body "
               "about the pivot is a symmetric top (I3 = I along the rod, I1 = I + m L^2) "
               "whose spin stays 0, i.e. a spherical pendulum of inertia I1; p_phi = I1 "
               "sin^2(theta) phi' conserved. DOP853 at rtol 1e-10 and 1e-12.",
        accuracy={"dop853_1e-10_vs_1e-12_max_m": d,
                  "energy_drift_1e-12_J": float(np.ptp(b["energy"]))},
        theta_range_deg=[math.degrees(lo), math.degrees(hi)],
        theta_range_from="roots of E = p_phi^2/(2 I1 sin^2 th) - m g L cos th (brentq)",
        theta_range_seen_deg=[math.degrees(b["th"].min()), math.degrees(b["th"].max())],
        p_phi=b["pphi"], p_phi_is="I1 sin^2(theta) phi' = -(angular momentum about +y, "
                                   "about the pivot): phi turns +x towards +z",
        times=_l(times), x=_l(b["x"]), y=_l(b["y"]), z=_l(b["z"]),
        energy=_l(b["energy"]),
        compare="centre position (x, y, z); energy and the y angular momentum constant; "
                "|r| = 1 m; theta stays in theta_range_deg.",
    )


# ---------------------------------------------------------------------------------------
# slider-crank driven at constant speed
SC = dict(r=0.1, l=0.4, omega=2 * math.pi, g=G, t_end=2.0, dt_out=0.02,
          m_crank=1.0, I_crank=1e-3, m_rod=1.0, I_rod=0.4 ** 2 / 12, m_slider=1.0)


def slider_crank_kinematics(t, p=SC):
    """Crank O(0,0)-A, rod A-B, slider B on the x axis (no offset), gravity -y.
    Works for real or complex t (complex step)."""
    r, l, w = p["r"], p["l"], p["omega"]
    th = w * t
    sa, ca = np.sin(th), np.cos(th)
    s = np.sqrt(l * l - r * r * sa * sa)
    xB = r * ca + s
    # rod angle: from B to A is (r ca - xB, r sa) = (-s, r sa); rod axis A->B angle
    beta = np.arcsin(-r * sa / l)             # angle of A->B measured from +x
    xBd = -r * w * sa - r * r * sa * ca * w / s
    betad = -r * ca * w / (l * np.cos(beta))
    return dict(th=th, xA=r * ca, yA=r * sa, xB=xB, beta=beta, xBd=xBd, betad=betad,
                vA=(-r * w * sa, r * w * ca))


def slider_crank_energy(t, p=SC):
    k = slider_crank_kinematics(t, p)
    w = p["omega"]
    # crank: uniform-ish: centre of mass at r/2, inertia I_crank about its centre
    vcr = (np.asarray(k["vA"][0]) / 2, np.asarray(k["vA"][1]) / 2)
    T = 0.5 * p["m_crank"] * (vcr[0] ** 2 + vcr[1] ** 2) + 0.5 * p["I_crank"] * w * w
    # rod centre of mass at the middle of A-B
    vrx = (k["vA"][0] + k["xBd"]) / 2
    vry = k["vA"][1] / 2
    T = T + 0.5 * p["m_rod"] * (vrx ** 2 + vry ** 2) + 0.5 * p["I_rod"] * k["betad"] ** 2
    T = T + 0.5 * p["m_slider"] * k["xBd"] ** 2
    V = p["g"] * (p["m_crank"] * k["yA"] / 2 + p["m_rod"] * k["yA"] / 2)
    return T + V


def slider_crank():
    p = SC
    times = np.round(np.arange(0, p["t_end"] + 1e-9, p["dt_out"]), 12)
    k = slider_crank_kinematics(times)
    h = 1e-30
    dEdt = np.imag(slider_crank_energy(times + 1j * h)) / h
    torque = dEdt / p["omega"]
    # check the complex step against a central difference
    fd = (slider_crank_energy(times + 1e-6) - slider_crank_energy(times - 1e-6)) / 2e-6
    return dict(
        deck="decks/joints/slider_crank.xml",
        description="Crank O-A (r = 0.1 m) on a revolute to ground at O, driven by a "
                    "Motion_Joint AZ = 2 pi TIME; connecting rod A-B (l = 0.4 m) with "
                    "revolutes at A and B; slider at B on a translational joint along "
                    "global x through O; gravity -9.81 y; 2 s. Masses: crank 1 kg (centre of "
                    "mass at r/2, Izz 1e-3), rod 1 kg (centre at mid-length, Izz l^2/12), "
                    "slider 1 kg.",
        parameters=p,
        method="Closed-form kinematics (0 DOF): xB = r cos th + sqrt(l^2 - r^2 sin^2 th), "
               "rod angle asin(-r sin th / l). Driving torque about +z on the crank = "
               "dE/dt / omega (E = kinetic + gravity potential of the three bodies; dE/dt "
               "by complex step, checked against a central difference).",
        accuracy=dict(kinematics="machine precision",
                      torque_complex_step_vs_central_difference_max_Nm=_maxdiff(
                          dEdt, fd) / p["omega"]),
        times=_l(times), slider_x=_l(k["xB"]), slider_vx=_l(k["xBd"]),
        crank_tip_x=_l(k["xA"]), crank_tip_y=_l(k["yA"]), rod_angle=_l(k["beta"]),
        drive_torque_z=_l(torque), energy=_l(slider_crank_energy(times)),
        compare="slider x and vx (DX, VX of the slider marker), crank tip, rod angle (angle "
                "of A->B from +x); drive_torque_z is the torque the motion applies to the "
                "crank about +z (its sign in MOTION() depends on the reaction convention).",
    )


# ---------------------------------------------------------------------------------------
# IFToMM A02: N four-bar mechanism, parallelogram branch
A02 = dict(N=40, m=1.0, L=1.0, g=G, vB0x=1.0, t_end=20.0, dt_out=0.05)


def a02_constants(p=A02):
    N, m, L, g = p["N"], p["m"], p["L"], p["g"]
    M = (N + 1) * m * L * L / 3 + N * m * L * L     # about the pivots / translating couplers
    K = g * ((N + 1) * m * L / 2 + N * m * L)
    return M, K


def a02_exact(t, p=A02):
    """Crank angle theta from +x, theta(0) = pi/2, theta'(0) = -vB0x/L. phi = theta + pi/2
    is a pendulum angle, phi'' = -w0^2 sin phi, in the rotating regime:
    phi = 2 am(K(k) - phib t / 2 | k^2), phib^2 = phid0^2 + 4 w0^2, k = 2 w0 / phib."""
    M, K = a02_constants(p)
    w0 = math.sqrt(K / M)
    phid0 = p["vB0x"] / p["L"]
    phib = math.sqrt(phid0 ** 2 + 4 * w0 * w0)
    k = 2 * w0 / phib
    Kk = ellipk(k * k)
    sn, cn, dn, am = ellipj(Kk - phib * np.asarray(t) / 2, k * k)
    phi = 2 * am
    phid = -phib * dn
    L = p["L"]
    # B0 = L (cos theta, sin theta) = L (sin phi, -cos phi)
    return L * np.sin(phi), -L * np.cos(phi), L * np.cos(phi) * phid, L * np.sin(phi) * phid, \
        phi - math.pi / 2, phid


def a02_ode(times, rtol, p=A02):
    M, K = a02_constants(p)

    def rhs(t, y):
        return [y[1], -K / M * math.cos(y[0])]
    sol = _ivp(rhs, p["t_end"], [math.pi / 2, -p["vB0x"] / p["L"]], times, rtol)
    th = sol.y[0]
    return p["L"] * np.cos(th), p["L"] * np.sin(th), sol.nfev


def a02():
    p = A02
    times = np.round(np.arange(0, p["t_end"] + 1e-9, p["dt_out"]), 12)
    x, y, vx, vy, th, thd = a02_exact(times)
    M, K = a02_constants(p)
    energy = 0.5 * M * thd ** 2 + K * np.sin(th)
    ode = {r: a02_ode(times, r) for r in TOLS}
    d_ode = {str(r): max(_maxdiff(ode[r][0], x), _maxdiff(ode[r][1], y)) for r in TOLS}
    w0 = math.sqrt(K / M)
    phib = math.sqrt((p["vB0x"] / p["L"]) ** 2 + 4 * w0 * w0)
    k = 2 * w0 / phib
    T = 4 * ellipk(k * k) / phib
    # horizontal (singular) crossings: theta = 0 mod pi
    crossings = []
    for n in range(1, 400):
        # theta = pi/2 - n pi/2 ... solve phi = theta + pi/2 = pi - n pi/2 on the exact branch
        target = math.pi - n * math.pi / 2
        if n % 2 == 0:
            continue
        lo, hi = 0.0, p["t_end"]
        # phi decreases monotonically: bisection on the exact phi
        f = lambda t: float(a02_exact(t)[4] + math.pi / 2) - target
        if f(hi) > 0:
            break
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if f(mid) > 0:
                lo = mid
            else:
                hi = mid
        crossings.append(0.5 * (lo + hi))
    return dict(
        deck="decks/joints/iftomm_a02_fourbar.xml",
        description="IFToMM A02 N-four-bar, N = 40: 2N+1 = 81 uniform links of 1 m and 1 kg "
                    "(41 cranks pivoted on ground at x = 0..40, 40 couplers at y = 1), "
                    "gravity -9.81 y, cranks vertical at t = 0, point B0 (top of the crank "
                    "at x = 0) moving at +1 m/s in x; 20 s.",
        parameters=p,
        method="On the parallelogram branch all cranks share one angle theta and the "
               "couplers translate: M theta'' = -K cos theta with M = (N+1) m L^2/3 + N m L^2 "
               "and K = g ((N+1) m L/2 + N m L), a pendulum in the rotating regime; closed "
               "form phi = theta + pi/2 = 2 am(K(k) - phib t/2 | k^2) (scipy ellipj), "
               "cross-checked by DOP853.",
        accuracy=dict(closed_form="machine precision to rounding of K(k) near k = 1 "
                                  "(k = %.6f); see the DOP853 agreement" % k,
                      dop853_vs_closed_form_max_m=d_ode),
        rotation_period_s=T, modulus_k=k,
        horizontal_crossing_times_s=crossings,
        spec_tolerances=dict(low=1e-1, high=1e-3, output_steps=400, threshold=1e-3),
        times=_l(times), B0_x=_l(x), B0_y=_l(y), B0_vx=_l(vx), B0_vy=_l(vy),
        energy=_l(energy),
        compare="B0 position and velocity (x, y) at the 401 output times (the spec's 400 "
                "output steps); energy (kinetic + gravity, zero level y = 0) constant. "
                "The mechanism passes the singular horizontal position at each "
                "horizontal_crossing_times_s; a solver that leaves the parallelogram branch "
                "there diverges from this reference.",
    )


# ---------------------------------------------------------------------------------------
# IFToMM A04: Bricard mechanism
A04 = dict(m=1.0, L=1.0, side=0.1, g=G, t_end=10.0, dt_out=0.05)
_EX, _EY, _EZ = np.eye(3)
# joint points and axes at t = 0 (A..F), the chain ground-1-2-3-4-5-ground
A04_POINTS = np.array([[0, 0, 0], [1, 0, 0], [1, -1, 0], [1, -1, 1], [0, -1, 1], [0, 0, 1.0]])
A04_AXES = np.array([_EY, _EZ, _EX, _EY, _EZ, _EX])


def _rot(u, a):
    u = np.asarray(u, float)
    K = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    return np.eye(3) + math.sin(a) * K + (1 - math.cos(a)) * K @ K


def a04_inertia(p=A04):
    m, L, a = p["m"], p["L"], p["side"]
    long_ = m * (a * a + a * a) / 12
    tr = m * (L * L + a * a) / 12
    out = []
    for k in range(5):
        d = A04_POINTS[k + 1] - A04_POINTS[k]
        out.append(np.diag([long_ if abs(d[i]) > 0.5 else tr for i in range(3)]))
    return out


def a04_kin(q):
    """Poses of rods 1..5 (R, translation) for joint angles q[0:5] (product of
    exponentials from the reference configuration), current joint axes u_i and points p_i
    (i = 0..5, the last one F on ground)."""
    R, d = np.eye(3), np.zeros(3)
    Rs, ds, u, pt = [], [], [], []
    for i in range(5):
        u.append(R @ A04_AXES[i])
        pt.append(R @ A04_POINTS[i] + d)
        Ri = _rot(A04_AXES[i], q[i])
        # g_i(x) = Ri (x - p_i0) + p_i0, composed: x -> R (Ri (x - p0) + p0) + d
        d = R @ (A04_POINTS[i] - Ri @ A04_POINTS[i]) + d
        R = R @ Ri
        Rs.append(R.copy())
        ds.append(d.copy())
    u.append(A04_AXES[5].copy())
    pt.append(A04_POINTS[5].copy())
    return Rs, ds, np.array(u), np.array(pt)


def a04_rhs_factory(p=A04):
    m, g = p["m"], p["g"]
    I0 = a04_inertia(p)
    c0 = [(A04_POINTS[k] + A04_POINTS[k + 1]) / 2 for k in range(5)]
    gvec = np.array([0, -g, 0])
    P5 = A04_POINTS[5]

    def rhs(t, y):
        q, qd = y[:6], y[6:]
        Rs, ds, u, pt = a04_kin(q)
        # screw matrix of the loop: rod 5 moves as a rotation about F
        x5 = Rs[4] @ P5 + ds[4]        # rod 5's copy of F (= F up to the drift)
        J = np.zeros((6, 6))
        for i in range(5):
            J[:3, i] = u[i]
            J[3:, i] = np.cross(u[i], x5 - pt[i])
        J[:3, 5] = -u[5]
        J[3:, 5] = 0.0
        _, sv, Vt = np.linalg.svd(J)
        s = Vt[-1]
        # velocities: angular velocity of body k (k = 0..4) and joint point rates
        om = np.zeros((6, 3))          # om[k] = angular velocity of rod k (om[-1] ground)
        acc = np.zeros(3)
        for i in range(5):
            acc = acc + qd[i] * u[i]
            om[i] = acc

        def vpoint(k, x):               # velocity of point x fixed on rod k (k=-1: ground)
            v = np.zeros(3)
            for i in range(k + 1):
                v += qd[i] * np.cross(u[i], x - pt[i])
            return v

        ud = np.zeros((6, 3))
        pd = np.zeros((6, 3))
        for i in range(1, 5):
            ud[i] = np.cross(om[i - 1], u[i])
            pd[i] = vpoint(i - 1, pt[i])
        # bias of the loop closure at acceleration level (rod 5's point at F, angular)
        v5 = vpoint(4, x5)
        b = np.zeros(6)
        for i in range(5):
            b[:3] += qd[i] * ud[i]
            b[3:] += qd[i] * (np.cross(ud[i], x5 - pt[i]) + np.cross(u[i], v5 - pd[i]))
        qdd_p = np.linalg.lstsq(J, -b, rcond=1e-12)[0]
        qdd_p -= s * (s @ qdd_p)
        # Kane's equation along s
        lhs = 0.0
        rhs_ = 0.0
        for k in range(5):
            c = Rs[k] @ c0[k] + ds[k]
            Ik = Rs[k] @ I0[k] @ Rs[k].T
            vs = sum(s[i] * np.cross(u[i], c - pt[i]) for i in range(k + 1))
            ws = sum(s[i] * u[i] for i in range(k + 1))
            vc = vpoint(k, c)
            ab = sum(qdd_p[i] * np.cross(u[i], c - pt[i])
                     + qd[i] * (np.cross(ud[i], c - pt[i]) + np.cross(u[i], vc - pd[i]))
                     for i in range(k + 1))
            alb = sum(qdd_p[i] * u[i] + qd[i] * ud[i] for i in range(k + 1))
            lhs += m * vs @ vs + ws @ Ik @ ws
            rhs_ += -(m * (ab - gvec) @ vs + (Ik @ alb + np.cross(om[k], Ik @ om[k])) @ ws)
        zdd = rhs_ / lhs
        return np.concatenate([qd, s * zdd + qdd_p])
    return rhs


def a04_observe(y, p=A04):
    q, qd = y[:6], y[6:]
    Rs, ds, u, pt = a04_kin(q)
    I0 = a04_inertia(p)
    P3 = Rs[1] @ A04_POINTS[2] + ds[1]       # joint C on rod 2 (BC)
    # closure residual: rod 5's copy of F and of F's axis
    res = np.concatenate([Rs[4] @ A04_POINTS[5] + ds[4] - A04_POINTS[5],
                          [(Rs[4] @ _EX) @ _EY, (Rs[4] @ _EX) @ _EZ]])
    # energy
    E = 0.0
    om = np.zeros(3)
    for k in range(5):
        om = om + qd[k] * u[k]
        c = Rs[k] @ ((A04_POINTS[k] + A04_POINTS[k + 1]) / 2) + ds[k]
        vc = sum(qd[i] * np.cross(u[i], c - pt[i]) for i in range(k + 1))
        Ik = Rs[k] @ I0[k] @ Rs[k].T
        E += 0.5 * p["m"] * vc @ vc + 0.5 * om @ Ik @ om + p["m"] * p["g"] * c[1]
    return P3, res, E


def a04_solve(times, rtol, p=A04):
    t0 = time.perf_counter()
    sol = _ivp(a04_rhs_factory(p), p["t_end"], np.zeros(12), times, rtol)
    wall = time.perf_counter() - t0
    obs = [a04_observe(sol.y[:, j]) for j in range(len(times))]
    P3 = np.array([o[0] for o in obs])
    res = max(float(np.abs(o[1]).max()) for o in obs)
    E = np.array([o[2] for o in obs])
    return dict(P3=P3, residual=res, energy=E, nfev=sol.nfev, wall=wall, y=sol.y)


def a04():
    p = A04
    times = np.round(np.arange(0, p["t_end"] + 1e-9, p["dt_out"]), 12)
    runs = {r: a04_solve(times, r) for r in TOLS}
    a, b = runs[TOLS[0]], runs[TOLS[1]]
    return dict(
        deck="decks/joints/iftomm_a04_bricard.xml",
        description="IFToMM A04 Bricard mechanism: five rods of 1 m, 1 kg, square section "
                    "0.1 m (Ixx long = m (2 a^2)/12, transverse m (L^2 + a^2)/12), six "
                    "revolutes at A(0,0,0) axis y, B(1,0,0) z, C(1,-1,0) x, D(1,-1,1) y, "
                    "E(0,-1,1) z, F(0,0,1) x; rods A-B, B-C, C-D, D-E, E-F; ground closes "
                    "F-A; gravity -9.81 y; starts at rest; 10 s. Over-constrained: 30 "
                    "equations on 30 coordinates, rank 29, 1 DOF.",
        parameters=p,
        method="Joint coordinates of the open chain ground-A-1-B-2-C-3-D-4-E-5 plus F's "
               "angle; loop closed at velocity and acceleration level by the 6x6 screw "
               "matrix J (rank 5) of the six joints; the acceleration is s z'' + a "
               "particular solution (s = null vector of J), z'' from Kane's equation along "
               "s with the bodies' Newton-Euler terms. DOP853 at rtol 1e-10 and 1e-12; the "
               "position-level loop residual is monitored, not enforced.",
        accuracy={"dop853_1e-10_vs_1e-12_max_m": _maxdiff(a["P3"], b["P3"]),
                  "loop_residual_max_1e-12": b["residual"],
                  "energy_drift_1e-12_J": float(np.ptp(b["energy"])),
                  "loop_residual_max_1e-10": a["residual"]},
        P3_is="joint C, the end of rod 2 (B-C), at (1, -1, 0) at t = 0: the point the "
              "OpenSim and Chrono A04 models report as P3",
        times=_l(times), P3_x=_l(b["P3"][:, 0]), P3_y=_l(b["P3"][:, 1]),
        P3_z=_l(b["P3"][:, 2]), energy=_l(b["energy"]),
        compare="P3 position (x, y, z) at the output times; energy constant (gravity zero "
                "level y = 0).",
        _state=b["y"],
    )


# ---------------------------------------------------------------------------------------
# IFToMM A03 / Test Set: Andrews' squeezing mechanism with exact joints (planar)
def andrews_planar(rtol):
    sys.path.insert(0, HERE)
    import andrews
    p = andrews.P
    angles, com, pts = andrews.geometry()
    mass = np.array([p[f"m{k}"] for k in range(1, 8)])
    inertia = np.array([p[f"i{k}"] for k in range(1, 8)])
    joints = [("O", 1, 0), ("P", 1, 2), ("D", 2, 3), ("D", 2, 4), ("D", 2, 6), ("B", 3, 0),
              ("E", 4, 5), ("A", 5, 0), ("A", 7, 0), ("F", 6, 7)]

    def A(th):
        c, s = math.cos(th), math.sin(th)
        return np.array([[c, -s], [s, c]])

    def B(th):
        c, s = math.cos(th), math.sin(th)
        return np.array([[-s, -c], [c, -s]])
    # local joint vectors
    loc = []
    for name, bi, bj in joints:
        P = pts[name]
        si = A(angles[bi]).T @ (P - com[bi])
        sj = A(angles[bj]).T @ (P - com[bj]) if bj else P.copy()
        loc.append((bi, bj, si, sj))
    S3 = A(angles[3]).T @ (pts["S"] - com[3])
    C = pts["C"]
    n = 21
    Mv = np.concatenate([[mass[k], mass[k], inertia[k]] for k in range(7)])

    def rhs(t, y):
        q, qd = y[:n], y[n:]
        th = q[2::3]
        thd = qd[2::3]
        Phq = np.zeros((20, n))
        gam = np.zeros(20)
        for r, (bi, bj, si, sj) in enumerate(loc):
            i = bi - 1
            Phq[2 * r:2 * r + 2, 3 * i:3 * i + 2] = np.eye(2)
            Phq[2 * r:2 * r + 2, 3 * i + 2] = B(th[i]) @ si
            gam[2 * r:2 * r + 2] += A(th[i]) @ si * thd[i] ** 2
            if bj:
                j = bj - 1
                Phq[2 * r:2 * r + 2, 3 * j:3 * j + 2] = -np.eye(2)
                Phq[2 * r:2 * r + 2, 3 * j + 2] = -(B(th[j]) @ sj)
                gam[2 * r:2 * r + 2] -= A(th[j]) @ sj * thd[j] ** 2
        Q = np.zeros(n)
        Q[2] += p["mom"]                       # driving torque on the crank
        # spring from C (ground) to S on body 3, force -c0 (l - l0) along C->S on body 3
        r3 = q[6:8]
        S = r3 + A(th[2]) @ S3
        d = S - C
        L = math.hypot(*d)
        F = -p["c0"] * (L - p["l0"]) * d / L
        Q[6:8] += F
        Q[8] += (B(th[2]) @ S3) @ F
        K = np.zeros((n + 20, n + 20))
        K[:n, :n] = np.diag(Mv)
        K[:n, n:] = Phq.T
        K[n:, :n] = Phq
        sol = np.linalg.solve(K, np.concatenate([Q, gam]))
        return np.concatenate([qd, sol[:n]])
    q0 = np.concatenate([[com[k][0], com[k][1], angles[k]] for k in range(1, 8)])
    t0 = time.perf_counter()
    sol = solve_ivp(rhs, (0, 0.03), np.concatenate([q0, np.zeros(n)]), method="DOP853",
                    rtol=rtol, atol=rtol * 1e-3)
    wall = time.perf_counter() - t0
    th = sol.y[2:n:3, -1]
    thd = sol.y[n + 2::3, -1]
    ang = dict(beta=th[0], Theta=th[1] - th[0], gamma=th[2], Phi=th[3] - th[4], delta=th[4],
               Omega=th[5] - th[6], epsilon=th[6])
    rate = dict(beta=thd[0], Theta=thd[1] - thd[0], gamma=thd[2], Phi=thd[3] - thd[4],
                delta=thd[4], Omega=thd[5] - thd[6], epsilon=thd[6])
    return ang, rate, sol.nfev, wall, andrews.REFERENCE


ANDREWS_RATE_REF = dict(beta=0.1139920302151208e+4, Theta=-0.1424379294994111e+4,
                        gamma=0.1103291221937134e+2, Phi=0.1929337464421385e+2,
                        delta=0.5735699284790808, Omega=-0.1929337464421385e+2,
                        epsilon=0.3231791658026955)


def andrews_ref():
    runs = {r: andrews_planar(r) for r in TOLS}
    ang, rate, nfev, wall, ref = runs[TOLS[1]]
    err = max(abs(ang[k] - ref[k]) for k in ref)
    err_rate = max(abs(rate[k] - ANDREWS_RATE_REF[k]) / max(1, abs(ANDREWS_RATE_REF[k]))
                   for k in ref)
    d = max(abs(runs[TOLS[0]][0][k] - ang[k]) for k in ref)
    return dict(
        deck="decks/joints/iftomm_a03_andrews.xml",
        description="Andrews' squeezing mechanism (IFToMM A03 / Test Set for IVP solvers): "
                    "7 planar bodies, 10 revolute joints (axes global z), driving torque "
                    "0.033 N m on the crank, spring c0 = 4530 N/m, l0 = 0.07785 m, no "
                    "gravity, at rest at t = 0; 0.03 s. Geometry and mass data from "
                    "benchmarks/andrews.py (shared/reference/numerics.md section 2).",
        method="Reference = the Test Set's PSIDE solution at rtol = atol = 1e-14 (angles "
               "and rates at t = 0.03, numerics.md). Reproduced here by an independent "
               "planar absolute-coordinate index-1 ODE (KKT solve per evaluation) built "
               "from the same geometry the deck generator uses, DOP853 at 1e-10 and 1e-12.",
        reference_angles_t003=ref, reference_rates_t003=ANDREWS_RATE_REF,
        this_script_angles_t003=ang, this_script_rates_t003=rate,
        accuracy={"this_script_vs_test_set_max_rad": err,
                  "this_script_vs_test_set_rates_max_rel": err_rate,
                  "dop853_1e-10_vs_1e-12_max_rad": d},
        compare="the seven angles at t = 0.03 (beta = crank angle; Theta, Phi, Omega are "
                "relative angles: body 2 - body 1, body 4 - body 5, body 6 - body 7), "
                "error as in benchmarks/andrews.py: max |got - ref| / max(1, |ref|).",
    )


# ---------------------------------------------------------------------------------------
# static checks of the decks themselves (no pysolver): joint geometry at t = 0, velocity
# consistency of the v_ic / w_ic initial conditions with every joint, initial energy
def _rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def _rx(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0, 0], [0, c, -s], [0, s, c]])


def read_deck(path):
    """Markers (body, position, axes), bodies (cg, mass, inertia, v, w), joints, gravity
    of a deck in the subset the decks here use (global poses, no rm_id)."""
    from lxml import etree
    root = etree.parse(path).getroot()
    model = root.find("Model")
    f = lambda e, k, d=0.0: float(e.get(k, d))
    markers, bodies, joints, motions = {}, {}, [], []
    grav = np.zeros(3)
    for e in model:
        if not isinstance(e.tag, str):
            continue
        tag = e.tag.lower()
        if tag == "reference_marker":
            assert e.get("rm_id") is None
            if e.get("a00") is not None:
                A = np.array([[f(e, f"a{r}{c}") for c in range(3)] for r in range(3)])
            elif e.get("psi") is not None:
                A = _rz(f(e, "psi")) @ _rx(f(e, "theta")) @ _rz(f(e, "phi"))
            else:
                A = np.eye(3)
            markers[int(e.get("id"))] = (int(e.get("body_id")),
                                         np.array([f(e, "pos_x"), f(e, "pos_y"), f(e, "pos_z")]),
                                         A)
        elif tag == "body_rigid":
            if e.get("isground", "FALSE").upper() == "TRUE":
                bodies[int(e.get("id"))] = None
            else:
                bodies[int(e.get("id"))] = dict(
                    cg=int(e.get("cg_id")), m=f(e, "mass"),
                    I=np.diag([f(e, "inertia_xx"), f(e, "inertia_yy"), f(e, "inertia_zz")]),
                    v=np.array([f(e, "v_ic_x"), f(e, "v_ic_y"), f(e, "v_ic_z")]),
                    w=np.array([f(e, "w_ic_x"), f(e, "w_ic_y"), f(e, "w_ic_z")]))
        elif tag == "constraint_joint":
            joints.append((e.get("type").upper(), int(e.get("i_marker_id")),
                           int(e.get("j_marker_id"))))
        elif tag == "motion_joint":
            motions.append((int(e.get("joint_id")), e.get("expr")))
        elif tag == "force_gravity":
            grav = np.array([f(e, "grav_x"), f(e, "grav_y"), f(e, "grav_z")])
    return markers, bodies, joints, motions, grav


def check_deck(path):
    markers, bodies, joints, motions, grav = read_deck(path)

    def vel(mid):
        b, pos, A = markers[mid]
        B = bodies[b]
        if B is None:
            return np.zeros(3), np.zeros(3)
        cg = markers[B["cg"]][1]
        return B["v"] + np.cross(B["w"], pos - cg), B["w"]
    worst = dict(position=0.0, axes=0.0, velocity=0.0, angular_velocity=0.0)
    for kind, i, j in joints:
        (_, pi, Ai), (_, pj, Aj) = markers[i], markers[j]
        vi, wi = vel(i)
        vj, wj = vel(j)
        d, dv, dw = pi - pj, vi - vj, wi - wj
        zj = Aj[:, 2]
        if kind in ("REVOLUTE", "SPHERICAL", "FIXED", "HOOKE", "UNIVERSAL"):
            worst["position"] = max(worst["position"], np.abs(d).max())
            worst["velocity"] = max(worst["velocity"], np.abs(dv).max())
        if kind in ("INLINE", "TRANSLATIONAL", "CYLINDRICAL"):
            worst["position"] = max(worst["position"], np.abs(d - (d @ zj) * zj).max())
            worst["velocity"] = max(worst["velocity"], np.abs(dv - (dv @ zj) * zj).max())
        if kind in ("REVOLUTE", "TRANSLATIONAL", "CYLINDRICAL"):
            worst["axes"] = max(worst["axes"], 1 - Ai[:, 2] @ zj)
        if kind == "REVOLUTE":
            worst["angular_velocity"] = max(worst["angular_velocity"],
                                            np.abs(dw - (dw @ zj) * zj).max())
        if kind == "TRANSLATIONAL":
            worst["axes"] = max(worst["axes"], 1 - Ai[:, 0] @ Aj[:, 0])
            worst["angular_velocity"] = max(worst["angular_velocity"], np.abs(dw).max())
    drive = {}
    for jid, expr in motions:
        kind, i, j = joints[jid - 1]
        drive[jid] = dict(expr=expr, joint_rate=float((vel(i)[1] - vel(j)[1]) @ markers[j][2][:, 2]))
    E = 0.0
    for B in bodies.values():
        if B is None:
            continue
        _, cg, A = markers[B["cg"]]
        wl = A.T @ B["w"]
        E += 0.5 * B["m"] * B["v"] @ B["v"] + 0.5 * wl @ B["I"] @ wl - B["m"] * grav @ cg
    return dict(deck=os.path.relpath(path, os.path.dirname(HERE)), joints=len(joints),
                max_joint_gap_m=float(worst["position"]),
                max_axis_misalignment=float(worst["axes"]),
                max_joint_velocity_mismatch=float(worst["velocity"]),
                max_joint_angular_velocity_mismatch=float(worst["angular_velocity"]),
                motion_joint_rates_at_t0=drive, initial_energy_J=float(E))


# ---------------------------------------------------------------------------------------
# Exudyn comparators
def _exu_settings(h, t_end, out_dt):
    import exudyn as exu
    s = exu.SimulationSettings()
    s.timeIntegration.numberOfSteps = int(round(t_end / h))
    s.timeIntegration.endTime = t_end
    s.timeIntegration.verboseMode = 0
    s.displayComputationTime = False
    s.displayStatistics = False
    s.solutionSettings.writeSolutionToFile = False
    s.solutionSettings.sensorsWritePeriod = out_dt
    return s


def exudyn_pendulum(h, repeat=2):
    """3D rigid body (Euler parameters) on a revolute joint, generalized-alpha at fixed
    step h (Exudyn defaults: spectral radius 0.9, Newton relTol 1e-8)."""
    import exudyn as exu
    import exudyn.utilities as eu
    p = PEND
    best, data = np.inf, None
    for _ in range(repeat):
        sc = exu.SystemContainer()
        mbs = sc.AddSystem()
        ground = mbs.CreateGround()
        inertia = eu.RigidBodyInertia(mass=p["m"], inertiaTensor=np.eye(3) * p["I"])
        body = mbs.CreateRigidBody(inertia=inertia, referencePosition=[p["L"], 0, 0],
                                   gravity=[0, -p["g"], 0])
        mbs.CreateRevoluteJoint(bodyNumbers=[ground, body], position=[0, 0, 0],
                                axis=[0, 0, 1])
        sens = mbs.AddSensor(eu.SensorBody(bodyNumber=body, storeInternal=True,
                                           outputVariableType=exu.OutputVariableType.Position))
        mbs.Assemble()
        s = _exu_settings(h, p["t_end"], p["dt_out"])
        t0 = time.perf_counter()
        mbs.SolveDynamic(s)
        best = min(best, time.perf_counter() - t0)
        data = mbs.GetSensorStoredData(sens)
    t = data[:, 0]
    x, y, *_ = pendulum_exact(t)
    err = np.hypot(data[:, 1] - x, data[:, 2] - y)
    return dict(h=h, steps=int(round(p["t_end"] / h)), wall_s=best,
                max_err_m=float(err.max()), end_err_m=float(err[-1]))


def exudyn_a02(h, solver="EigenSparse", p=A02):
    """Planar model (NodeRigidBody2D + RevoluteJoint2D, no 3D redundancy), generalized
    alpha at fixed step h. Returns error of B0 against the parallelogram branch."""
    import exudyn as exu
    import exudyn.itemInterface as ei
    N, m, L, g = p["N"], p["m"], p["L"], p["g"]
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    og = mbs.AddObject(ei.ObjectGround())
    Jc = m * L * L / 12
    cranks, coup = [], []
    w = -p["vB0x"] / L
    for i in range(N + 1):
        nd = mbs.AddNode(ei.NodeRigidBody2D(referenceCoordinates=[i * L, L / 2, math.pi / 2],
                                            initialVelocities=[-w * L / 2, 0, w]))
        cranks.append(mbs.AddObject(ei.ObjectRigidBody2D(physicsMass=m, physicsInertia=Jc,
                                                         nodeNumber=nd)))
        mbs.AddLoad(ei.LoadForceVector(markerNumber=mbs.AddMarker(
            ei.MarkerNodePosition(nodeNumber=nd)), loadVector=[0, -m * g, 0]))
    for i in range(N):
        nd = mbs.AddNode(ei.NodeRigidBody2D(referenceCoordinates=[(i + 0.5) * L, L, 0],
                                            initialVelocities=[p["vB0x"], 0, 0]))
        coup.append(mbs.AddObject(ei.ObjectRigidBody2D(physicsMass=m, physicsInertia=Jc,
                                                       nodeNumber=nd)))
        mbs.AddLoad(ei.LoadForceVector(markerNumber=mbs.AddMarker(
            ei.MarkerNodePosition(nodeNumber=nd)), loadVector=[0, -m * g, 0]))

    def mk(body, loc):
        return mbs.AddMarker(ei.MarkerBodyPosition(bodyNumber=body, localPosition=loc))
    for i in range(N + 1):
        mbs.AddObject(ei.RevoluteJoint2D(markerNumbers=[mk(og, [i * L, 0, 0]),
                                                        mk(cranks[i], [-L / 2, 0, 0])]))
    for i in range(N):
        mbs.AddObject(ei.RevoluteJoint2D(markerNumbers=[mk(cranks[i], [L / 2, 0, 0]),
                                                        mk(coup[i], [-L / 2, 0, 0])]))
        mbs.AddObject(ei.RevoluteJoint2D(markerNumbers=[mk(cranks[i + 1], [L / 2, 0, 0]),
                                                        mk(coup[i], [L / 2, 0, 0])]))
    sens = mbs.AddSensor(ei.SensorBody(bodyNumber=cranks[0], localPosition=[L / 2, 0, 0],
                                       storeInternal=True,
                                       outputVariableType=exu.OutputVariableType.Position))
    mbs.Assemble()
    s = _exu_settings(h, p["t_end"], p["dt_out"])
    s.linearSolverType = getattr(exu.LinearSolverType, solver)
    s.linearSolverSettings.ignoreSingularJacobian = True
    t0 = time.perf_counter()
    ok, msg = True, ""
    try:
        mbs.SolveDynamic(s)
    except Exception as e:                    # noqa: BLE001 - report any solver failure
        ok, msg = False, str(e).splitlines()[0][:200]
    wall = time.perf_counter() - t0
    data = mbs.GetSensorStoredData(sens)
    t = data[:, 0]
    x, y, *_ = a02_exact(t)
    err = np.hypot(data[:, 1] - x, data[:, 2] - y)
    return dict(h=h, steps=int(round(p["t_end"] / h)), wall_s=wall, linear_solver=solver,
                completed=ok,
                reached_t=float(t[-1]), message=msg,
                max_err_m=float(err.max()), end_err_m=float(err[-1]))


def exudyn_a04(h, ref, p=A04):
    """The Bricard mechanism in Exudyn as its own example builds it (rigid 3D bodies,
    five revolutes and one generic joint with the rotation about x free, dense solver
    tolerating the redundant constraint); P3 against this script's reference."""
    import exudyn as exu
    import exudyn.utilities as eu
    L, a = p["L"], p["side"]
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    inertia = eu.InertiaCuboid(density=p["m"] / (L * a * a), sideLengths=[L, a, a])
    inertia = inertia.Translated([L / 2, 0, 0])
    rots = [np.eye(3), eu.RotationMatrixZ(-math.pi / 2), eu.RotationMatrixY(-math.pi / 2),
            eu.RotationMatrixZ(math.pi), eu.RotationMatrixZ(math.pi / 2)]
    og = mbs.CreateGround()
    bodies = [og]
    for i in range(6):
        P = A04_POINTS[i]
        if i < 5:
            b = mbs.CreateRigidBody(inertia=inertia, referencePosition=P,
                                    referenceRotationMatrix=rots[i], gravity=[0, -p["g"], 0])
            mbs.CreateRevoluteJoint(bodyNumbers=[bodies[-1], b], position=P,
                                    axis=A04_AXES[i])
        else:
            b = og
            mbs.CreateGenericJoint(bodyNumbers=[bodies[-1], b], position=P,
                                   constrainedAxes=[1, 1, 1, 0, 1, 1])
        bodies.append(b)
    sens = mbs.AddSensor(eu.SensorBody(bodyNumber=bodies[2], localPosition=[L, 0, 0],
                                       storeInternal=True,
                                       outputVariableType=exu.OutputVariableType.Position))
    mbs.Assemble()
    s = _exu_settings(h, p["t_end"], p["dt_out"])
    s.linearSolverType = exu.LinearSolverType.EigenDense
    s.linearSolverSettings.ignoreSingularJacobian = True
    t0 = time.perf_counter()
    mbs.SolveDynamic(s)
    wall = time.perf_counter() - t0
    data = mbs.GetSensorStoredData(sens)
    n = min(len(data), len(ref["times"]))
    refP = np.column_stack([ref["P3_x"], ref["P3_y"], ref["P3_z"]])[:n]
    err = np.linalg.norm(data[:n, 1:4] - refP, axis=1)
    return dict(h=h, steps=int(round(p["t_end"] / h)), wall_s=wall,
                max_err_m=float(err.max()), end_err_m=float(err[-1]))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--no-exudyn", action="store_true")
    ap.add_argument("--out", default=os.path.join(HERE, "data", "joint_references.json"))
    args = ap.parse_args(argv)
    out = dict(generated_by="benchmarks/joint_references.py",
               units="SI (kg, m, s, N); angles in radians unless named _deg",
               problems={})
    t_start = time.perf_counter()
    for name, fn in [("pendulum_revolute", pendulum), ("spherical_pendulum", spherical),
                     ("slider_crank", slider_crank), ("iftomm_a02_fourbar", a02),
                     ("iftomm_a04_bricard", a04), ("iftomm_a03_andrews", andrews_ref)]:
        t0 = time.perf_counter()
        out["problems"][name] = fn()
        out["problems"][name].pop("_state", None)
        print(f"{name}: {time.perf_counter() - t0:.1f} s  "
              f"accuracy {out['problems'][name]['accuracy']}", flush=True)
    decks = os.path.join(os.path.dirname(HERE), "decks", "joints")
    for name, prob in out["problems"].items():
        prob["deck_check"] = check_deck(os.path.join(os.path.dirname(HERE), prob["deck"]))
        if "energy" in prob:
            prob["deck_check"]["reference_energy_at_t0_J"] = prob["energy"][0]
        print(f"deck check {name}: {prob['deck_check']}", flush=True)
    # the Bricard deck's rod inertias against the ones the reference integrates
    m_, b_, *_ = read_deck(os.path.join(decks, "iftomm_a04_bricard.xml"))
    rods = [b_[k] for k in sorted(b_) if b_[k] is not None]
    out["problems"]["iftomm_a04_bricard"]["deck_check"]["max_inertia_mismatch"] = max(
        float(np.abs(r["I"] - I).max()) for r, I in zip(rods, a04_inertia()))
    out["deck_check_inline_a02"] = check_deck(os.path.join(decks,
                                                           "iftomm_a02_fourbar_inline.xml"))
    if not args.no_exudyn:
        import exudyn
        ex = dict(version=exudyn.__version__,
                  solver="generalized-alpha (index 3), fixed step, Exudyn defaults "
                         "(spectral radius 0.9, Newton relTol 1e-8); wall time of "
                         "SolveDynamic only, best of 2 for the pendulum, 1 run otherwise; "
                         "machine: 2 cores, one used")
        ex["pendulum_revolute"] = [exudyn_pendulum(h) for h in (1e-2, 1e-3, 2e-4)]
        print("exudyn pendulum", ex["pendulum_revolute"], flush=True)
        ex["iftomm_a02_fourbar"] = [exudyn_a02(h) for h in (2.5e-3, 1e-3, 5e-4, 2.5e-4, 1e-4)]
        print("exudyn a02", ex["iftomm_a02_fourbar"], flush=True)
        ref = out["problems"]["iftomm_a04_bricard"]
        ex["iftomm_a04_bricard"] = [exudyn_a04(h, ref) for h in (2e-3, 1e-3, 5e-4)]
        print("exudyn a04", ex["iftomm_a04_bricard"], flush=True)
        out["exudyn"] = ex
    out["runtime_s"] = time.perf_counter() - t_start
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")
    print("wrote", args.out, f"in {out['runtime_s']:.0f} s")


if __name__ == "__main__":
    main()
