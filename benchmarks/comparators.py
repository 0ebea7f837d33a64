"""Seed example 3 written by hand, as a user would without pysolver, for comparison.

The same equations as decks/particle_between_lines.xml (kg, mm, s, N: force scale 1000):
m x'' = -1000 dPhi/dx, with two unilateral penalties g1 = 1 + x - z, g2 = 1 - x - z,
F_i = -k S(g_i) g_i - c S(g_i) g_i', S = STEP(g, 0, 0, 1, 1), acting along grad g_i.
"""
import numpy as np

K, C, M, GRAV, CF, S = 1e4, 1e2, 1.0, 9810.0, 1000.0, 1.0


def _step(g):
    d = np.clip(g / S, 0.0, 1.0)
    return d * d * (3 - 2 * d)


def forces(x, z, vx, vz):
    """Generalized force (fx, fz) of the two smoothed unilateral penalties, in N."""
    fx = 0.0
    fz = 0.0
    for sx in (1.0, -1.0):                 # g = 1 + sx x - z, grad = (sx, -1)
        g = 1.0 + sx * x - z
        if g > 0:
            s = _step(g)
            gd = sx * vx - vz
            f = -K * s * g - C * s * gd
            fx += f * sx
            fz -= f
    return fx, fz


def residual(t, y, yp, res):
    """IDA residual of the particle between two lines: y = (x, z, vx, vz)."""
    x, z, vx, vz = y
    fx, fz = forces(x, z, vx, vz)
    res[0] = yp[0] - vx
    res[1] = yp[1] - vz
    res[2] = M * yp[2] - CF * fx
    res[3] = M * (yp[3] + GRAV) - CF * fz


def rhs(t, y):
    """The same equations as an explicit ODE y' = f(t, y), for SciPy's solve_ivp."""
    x, z, vx, vz = y
    fx, fz = forces(x, z, vx, vz)
    return [vx, vz, CF * fx / M, CF * fz / M - GRAV]


def initial_state():
    y0 = np.array([100.0, 120.0, 0.0, 0.0])
    return y0, np.array([0.0, 0.0, 0.0, -GRAV])
