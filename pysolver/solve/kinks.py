"""The knots of splines of time that drive motions, where a motion's velocity or acceleration
jumps: the run stops at each knot where a velocity jumps and restarts with the impulse's
velocities (:class:`KnotRestarts`).

A spline is as smooth at its inner knots as its kind (LINSPL: continuous in value only,
AKISPL: in its first derivative, CUBSPL: in its second, QUISPL: in its fourth) and at its
first and last knots continuous in value only (Adams' extrapolation, the parabola or line
through the end points, meets the curve there with a slope of its own; LINSPL's own line with
``linear_extrap`` is the exception). A displacement motion through it asks for a velocity
jump where the spline's first derivative jumps, which no body makes: IDA shrinks its step
there and, from integr_tol 1e-8 on the slider pendulum of tests/test_spline_motions.py,
gave up (docs/deck-language.md "Splines"). An ideal
constraint whose velocity jumps acts on the bodies by an impulse, the velocity change that is
the least in kinetic energy among those that meet it (Lagrange's impulse equations,
M dv = C^T P with C v+ = b+), which is what the restart gives them.
"""
import math

import numpy as np

from ..build.consistent import _Jac, _velocities, consistent
from ..build.planar import global_inertia
from ..deck import expr as ex
from .actors import Actor, Flow

#: The highest derivative of each interpolation that is continuous at its inner knots.
SMOOTHNESS = {"LINSPL": 0, "AKISPL": 1, "CUBSPL": 2, "QUISPL": 4}

#: The rate of a motion's measure that the first jump of its expression's own value makes
#: jump: its value for a displacement motion is 0 (the displacement), one more for V, A.
_LEVEL = {"D": 0, "V": 1, "A": 2}
_RATES = ("displacement", "velocity", "acceleration")


def _splines_of_time(model, tree, seen=()):
    """(name, spline id, derivative order) of each spline call of TIME in tree, through the
    variables it reads."""
    for n in ex.nodes(tree):
        if n[0] != "call":
            continue
        if n[1] in SMOOTHNESS and n[2][0][:2] == ("name", "TIME"):
            order = int(n[2][3][1]) if len(n[2]) > 3 and n[2][3][0] == "num" else 0
            yield n[1], int(n[2][2][1]), order
        elif n[1] == "VARVAL" and n[2][0][0] == "num":
            vid = int(n[2][0][1])
            var = model.variables.get(vid)
            if var is not None and var.expr is not None and vid not in seen:
                yield from _splines_of_time(model, var.expr, seen + (vid,))


def _jumps(model, motion):
    """(knot time, spline id, kind, the rate that jumps) of each knot where a rate of `motion`
    up to its acceleration jumps (the knot at the run's start, t <= 0, left out)."""
    for name, sid, order in _splines_of_time(model, motion.expr):
        sp = model.splines.get(sid)
        if sp is None or sp.z:
            continue
        # LINSPL's line past its ends is its last segment's: no knot there
        ends = None if name == "LINSPL" and sp.linear_extrap else 0
        for k, x in enumerate(sp.x):
            if k == 0 and x <= 0.0:
                continue            # runs start at t = 0: the curve is never left there
            smooth = ends if k in (0, len(sp.x) - 1) else SMOOTHNESS[name]
            if smooth is None:
                continue
            # the first derivative of the spline that jumps, as a rate of the motion's measure
            rate = max(0, smooth + 1 - order) + _LEVEL[motion.val_type]
            if rate <= 2:
                yield x, sid, name, _RATES[rate]


class KnotRestarts(Actor):
    """Stops IDA at every knot inside the run where a displacement motion's velocity jumps
    (:func:`_jumps`) and restarts it from the velocities of the impulse: the least change in
    kinetic energy that meets the velocity constraints after the knot, then the accelerations
    and reactions of the new state. The run's log names the first knot and how many there
    are."""

    def __init__(self, model, kernel, log):
        self.kernel, self.log = kernel, log
        end = max((c.end_time for c in model.commands), default=0.0)
        found = {}
        for mo in model.motions.values():
            if mo.id > 0 and mo.expr is not None:
                for x, sid, name, rate in _jumps(model, mo):
                    if rate == "velocity" and 0.0 < x < end:
                        found.setdefault(x, (mo, sid, name))
        self.times = sorted(found)
        self.what = found
        self.next = 0
        self.noted = False

    def next_time(self, t):
        while self.next < len(self.times) and self.times[self.next] < t:
            self.next += 1
        return self.times[self.next] if self.next < len(self.times) else math.inf

    def on_time(self, run):
        t, k = run.t, self.kernel
        y = np.array(run.y, dtype=float)
        impulse(k, t, y, np.asarray(run.yp, dtype=float))
        run.y, run.yp = y, consistent(k, t, y)
        if not self.noted:
            mo, sid, name = self.what[t]
            what = "Motion_Joint" if mo.joint else "Motion_Marker"
            self.log.append(
                f"t = {t:.6g}: {what} {mo.id}'s velocity jumps at a knot of Reference_Spline "
                f"{sid} ({name}); the run stops there and restarts with the impulse's "
                f"velocities, the least change in kinetic energy ({len(self.times)} such "
                "knots before the run's end; docs/deck-language.md, Splines)")
            self.noted = True
        self.next += 1
        return Flow(restart=True)

    def notes(self):
        """No lines on the run as a whole (LoadControl's protocol)."""
        return []

    def save(self):
        return self.next, self.noted

    def restore(self, snapshot, t):
        self.next, self.noted = snapshot


def _mass_inverse(lay):
    """The inverse of the bodies' mass matrix over their velocities (block diagonal)."""
    blocks = []
    for b, (_, nu) in zip(lay.bodies, lay.sizes):
        if nu == 6:                          # (v in global axes, w in body axes)
            blocks += [np.eye(3) / b.mass, np.linalg.inv(np.asarray(b.inertia, float))]
        elif b.kind == "point":
            blocks.append(np.eye(3) / b.mass)
        else:                                # planar: (vx, vy, wz about the global z)
            blocks.append(np.diag([1 / b.mass, 1 / b.mass, 1 / global_inertia(b)[2, 2]]))
    n = sum(len(m) for m in blocks)
    out, at = np.zeros((n, n)), 0
    for m in blocks:
        out[at:at + len(m), at:at + len(m)] = m
        at += len(m)
    return out


def impulse(kernel, t, y, yp, iters=3):
    """Move the velocities in y onto the rate rows at t by the least change in kinetic energy
    (an acceleration motion's driven velocity takes the new rate), in place."""
    lay = kernel.layout
    lam, rate = np.array(lay.lam, dtype=int), np.array(lay.rate, dtype=int)
    u = _velocities(lay)
    Minv = _mass_inverse(lay)
    held = np.flatnonzero(rate < 0)
    for _ in range(iters):
        r = kernel.residual_array(t, y, yp)[lam]
        for k in np.flatnonzero(rate >= 0):
            y[rate[k]] += r[k]
        if not len(held) or np.abs(r[held]).max() <= 1e-14 * (1.0 + np.abs(y[u]).max()):
            return
        C = _Jac(kernel, t, y, yp, 0.0).block(lam[held], u)
        P = np.linalg.lstsq(C @ Minv @ C.T, -r[held], rcond=None)[0]
        y[u] += Minv @ C.T @ P
