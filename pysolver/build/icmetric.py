"""The metric of the initial-conditions assembly (:func:`pysolver.build.consistent._assemble`,
and its C twin ``assemble`` in csrc/control.c, which the restarts run): the positions are
moved onto the position constraints by the least change in the mass metric, so that a deck
written in millimetres assembles to the same pose as the deck in metres (docs/deck-language.md,
"Joints"; docs/numerics.md, "Constraints").

Decision: the change of a body from the positions the assembly started from is its centre of
mass's translation dc and its turn phi (the rotation vector of its new orientation relative to
the old, in body axes; a planar body's turn about z), and its size is

    m |dc|^2 + phi' D phi,

D the diagonal of the body's inertia about its centre of mass (in body axes; a planar body's
about the global z): the velocity step's kinetic-energy metric (:mod:`.icvelocity`), over
the positions. A mass or an inertia that is not positive weighs 1. The assembly finds the
least of the sum over the bodies with the constraints held (a local least: the one the
Newton steps reach from the deck's positions).

How: each Newton step (in the bodies' velocity coordinates: translations and body-axes
rotations) is the least change in the metric that zeroes the constraints' linearization
g + C dx, plus a pull along the constraints, -alpha P x: x is the change so far as
:func:`change` gives it (the metric's gradient, over the metric), P the projection along the
constraints (x less its least change, x - W C' (C W C')^-1 C x; W the inverse metric). At a
fixed point g = 0 and x = W C' nu for some nu: the conditions of the least change, exactly.
alpha = 1 is the Gauss-Newton step, which ignores the constraints' curvature: its pulls
converge linearly, slowly or not at all where the deck's positions are as far from the
constraints as their radius of curvature (a 1 m bar whose joint is 1.5 m off). So from the
second pull alpha is the secant (Barzilai-Borwein) length of the last two pulls p, q:
alpha_q = alpha_p (p.p) / (p.(p - q)) in the metric, within [0.05, 20] (1 when
p.(p - q) <= 0). Measured on such bars (tests/test_initial_positions.py), 6 to 12 steps
reach the least change to 1e-12 where Gauss-Newton took up to 46, or swung between two
poses. The last 5 of the 50 steps allowed drop the pull, so that the constraints hold
however the pulls went.
"""
import math

import numpy as np


def weights(kernel):
    """(ny,) each body velocity's inverse weight 1 / (its body's mass, or for an angular
    velocity the body's inertia about that axis), read from the kernel's arrays (so a sweep's
    masses count), zero at every other state: the least change in the metric is
    ``least_change(..., scale=sqrt(w[u]))``."""
    lay, a = kernel.layout, kernel.arrays
    mass, inertia = np.asarray(a["body_mass"], float), np.asarray(a["body_inertia"], float)
    w = np.zeros(kernel.ny)
    for k, (b, ua) in enumerate(zip(lay.bodies, lay.uadr)):
        diag = inertia[9 * k:9 * k + 9:4]
        metric = ([mass[k]] * 2 + [diag[2]] if b.id in lay.planar
                  else [mass[k]] * 3 + (list(diag) if b.kind == "rigid" else []))
        w[ua:ua + len(metric)] = [1.0 / v if v > 0 else 1.0 for v in metric]
    return w


def change(kernel, y0, y, w):
    """(ny,) at each body velocity the change from the positions of `y0` to those of `y` whose
    least size the assembly seeks, as a velocity-like increment: the translation, and for a
    turn phi the increment x with the metric's gradient along a body angular velocity,
    J_r(phi)^-T D phi, equal to D x (J_r the right Jacobian of the rotation group: the turn
    after a further body-axes rotation dw is phi + J_r(phi)^-1 dw); x = phi when phi is along
    a principal axis. `w` as :func:`weights` gives it."""
    lay = kernel.layout
    out = np.zeros(kernel.ny)
    for b, qa, ua in zip(lay.bodies, lay.qadr, lay.uadr):
        if b.id in lay.planar:              # (x, y, rz): every coordinate adds
            out[ua:ua + 3] = y[qa:qa + 3] - y0[qa:qa + 3]
            continue
        out[ua:ua + 3] = y[qa:qa + 3] - y0[qa:qa + 3]
        if b.kind != "rigid":
            continue
        phi = turn(y0[qa + 3:qa + 7], y[qa + 3:qa + 7])
        d = 1.0 / w[ua + 3:ua + 6]
        out[ua + 3:ua + 6] = w[ua + 3:ua + 6] * jr_inv_t(phi, d * phi)
    return out


def turn(e, f):
    """The rotation vector (body axes, angle in [0, pi]) that takes Euler parameters e to f:
    the logarithm of conj(e) f."""
    s = e[0] * f[0] + e[1:] @ f[1:]
    v = e[0] * f[1:] - f[0] * e[1:] - np.cross(e[1:], f[1:])
    if s < 0.0:
        s, v = -s, -v
    n = math.sqrt(v @ v)
    return v * (2.0 * math.atan2(n, s) / n) if n > 0.0 else np.zeros(3)


def jr_inv_t(phi, v):
    """J_r(phi)^-T v = v - phi x v / 2 + c phi x (phi x v), c = 1/theta^2 - cot(theta/2) /
    (2 theta) (its series below theta = 0.01: 1/12 + theta^2/720 + theta^4/30240)."""
    theta = math.sqrt(phi @ phi)
    t2 = theta * theta
    c = (1.0 / 12.0 + t2 / 720.0 + t2 * t2 / 30240.0 if theta < 0.01
         else 1.0 / t2 - math.cos(0.5 * theta) / (2.0 * theta * math.sin(0.5 * theta)))
    pv = np.cross(phi, v)
    return v - 0.5 * pv + c * np.cross(phi, pv)
