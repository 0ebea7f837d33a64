"""Whether a run's answer is within what double precision can carry.

A stiff element (a Force_Penalty of 1e15 on a bead of 1 kg) turns the rounding of the state
into forces: a position known to one unit in the last place, u |q|, moves a force row by
sum_j |dF_r/dy_j| u |y_j|. Where that is not small beside the forces the row carries (its
mass times gravity or its acceleration, and the net of its applied forces), the trajectory
follows rounding, not physics: seed example 1 with penalty 1e15 ends 20 % off with every
error test passed. IDA's tolerance cannot see this (the error is in the residual, not the
step), so the check is made on the final state of a run that succeeded, and such a run is
reported as failed (status -710) with the element and a coefficient that would work.

The check (``ps_precision`` in C: the iteration matrix at cj = 0 and one residual, about a
microsecond on the example decks) runs once per run, not per step. It
measures the translational rows of each moving body; a body with no force to compare with
(no gravity, no acceleration, no applied force) is skipped. Without gravity, a body that
fails the check is measured again against the most it carried, the magnitudes of the forces
on it summed (not their net), at the deck's initial state or an output row, where that is
larger; and it is left out when no force acted on it at the start and none above its
rounding change since (it has no load to resolve). A damped oscillator, or a spring at its
free length or at its static equilibrium, comes to rest with a net force of nothing (or a
static's leftover imbalance), and its rounding was measured against that (-710 for a right
answer); a 1e6 kg body between a 1e6 N/m spring and a 1e-6 kg body on a 1 N/m spring carries
the light spring's force, which passes through zero every cycle (trial 45: -710 at each such
end time for a run right to 1e-11; against 1e-3 of the most it carried, too); a stiff spring
holding a push still is measured against the push. With gravity a body carries its weight,
which the check keeps measuring against (a bead bouncing on a penalty of 1e15 carries far
more than that at impacts).
"""
import math

import numpy as np

from ..build.bindings import ffi, lib

#: Largest ratio of a row's rounding-driven force to the force it carries. On seed example 1
#: the final position's error from rounding is about 10-25 times this ratio (penalty 1e13:
#: ratio 8e-5; 1e14: 8e-4, 1.8 % off; 1e15: 7e-3, 20 % off), so 1e-5 keeps it near 1e-4.
LIMIT = 1e-5

#: The coefficient suggested is the one that gives this ratio (a factor of 10 inside LIMIT).
SUGGEST = 1e-6

STATUS = -710


def check(model, kernel, t, y, yp):
    """None, or the message of a run whose final state is past double precision; t, y, yp:
    the run's output rows (the last is the final state)."""
    if not kernel.layout.bodies or not (model.penalties or model.sforces or model.vforces):
        return None
    ratio, b = _ratio(kernel, t[-1], y[-1], yp[-1])
    if b >= 0 and ratio > LIMIT and not np.any(kernel.arrays["gravity"]):
        start = _carried(kernel, 0.0, kernel.layout.initial_state())
        carried = np.max([start] + [_carried(kernel, tk, yk) for tk, yk in zip(t, y)], axis=0)
        ratio, b = _ratio(kernel, t[-1], y[-1], yp[-1], (carried, start))
    if b < 0 or not ratio > LIMIT:
        return None
    lay = kernel.layout
    q = np.abs(y[-1][lay.qadr[b]:lay.qadr[b] + 3]).max()
    return _message(model, kernel, ratio, lay.bodies[b], t[-1], q)


#: Unit roundoff of a double's spacing, 2^-52: the gap between doubles near q is about EPS |q|.
EPS = 2.220446049250313e-16


def unresolved(kernel, tol):
    """The advice for a run stopped by max_num_steps whose integr_tol is below what its
    coordinates resolve (EPS |q| > tol / 10 for the largest coordinate of a body at the
    deck's start: a revolute pendulum 1e9 m from the origin at 1e-9, trial 45), or None. IDA's
    tolerance is absolute in model units as well as relative (docs/usage.md), and a joint's
    equations are differences of coordinates, each rounded to EPS |q|."""
    lay = kernel.layout
    if not lay.bodies:
        return None
    y0 = lay.initial_state()
    q = max(abs(float(y0[lay.qadr[b] + c])) for b in range(len(lay.bodies)) for c in range(3))
    if not EPS * q > tol / 10:
        return None
    loose = 10.0 ** math.ceil(math.log10(10 * EPS * q))
    return (f"loosen integr_tol = {tol:g} to {loose:g} or more, or place the scene nearer the "
            f"origin: its coordinates reach {q:.3g}, where doubles are {EPS * q:.2g} apart, "
            "not small beside the tolerance")


def _penalty(model, kernel, pid):
    """Force_Penalty pid's penalty in this run: the kernel's constant slot, which a run's
    ``params`` may have changed, else the deck's."""
    slot = kernel.params.get(f"Force_Penalty/{pid}/penalty")
    return model.penalties[pid].penalty if slot is None else float(kernel.arrays["consts"][slot])


def _message(model, kernel, ratio, body, t, q):
    what = (f"at t = {t:.6g} the rounding of the state moves the forces on body {body.id} by "
            f"{ratio:.2g} of the forces it carries (more than {LIMIT:g}): the result follows "
            "rounding, not the model")
    if model.penalties:
        pid, pen = max(((p, _penalty(model, kernel, p)) for p in model.penalties),
                       key=lambda kv: kv[1])
        better = pen * SUGGEST / ratio
        better = 10.0 ** math.floor(math.log10(better)) if better > 0 else 0.0
        return (f"{what}; Force_Penalty {pid}'s penalty = {pen:g} is past what double "
                f"precision can carry here: use penalty <= {better:.0e} (or make the "
                "constraint exact)")
    # the change is sum_j |dF/dy_j| u |y_j|: stiffness (or damping) times the coordinates
    return (f"{what}; the forces on body {body.id} are stiffer than the rounding of its "
            f"coordinates (up to {q:.3g}) resolves: lower the stiffness or damping of the "
            "force elements acting on it, or place the scene nearer the origin")


def _carried(kernel, t, y):
    """The forces on each body at (t, y) without reactions, their magnitudes summed
    (ps_carried)."""
    out, work = np.zeros(max(len(kernel.layout.bodies), 1)), np.zeros(3 * kernel.ny)
    fb = ffi.from_buffer
    lib.ps_carried(kernel.m, kernel.d, t, fb("double[]", np.ascontiguousarray(y, float)),
                   fb("double[]", work), fb("double[]", out))
    return out


def _ratio(kernel, t, y, yp, carried=None):
    """(ratio, body index or -1) of ps_precision at (t, y, yp); `carried`: (the most each
    body carried over the run, what it carried at the deck's start), ps_carried's sums, or
    None."""
    got = kernel.__dict__.get("_precision_work")
    if got is None:                       # the arrays, and the C pointers into them
        if kernel.codegen["kernel"] == "generated":
            rows = cols = np.zeros(1, np.int32)     # the library has its own pattern
        else:
            kernel.sparsity()                       # the tapes' pattern, and room for it
            rows, cols = kernel._triplets
        work = np.zeros(4 * kernel.ny)
        got = kernel.__dict__["_precision_work"] = (
            (rows, cols, work), ffi.cast("int *", ffi.from_buffer(rows)),
            ffi.cast("int *", ffi.from_buffer(cols)), len(rows),
            ffi.from_buffer("double[]", work), ffi.new("int *"))
    _, rows, cols, n, work, body = got
    fb = ffi.from_buffer
    ratio = lib.ps_precision(kernel.m, kernel.d, t, fb("double[]", np.ascontiguousarray(y, float)),
                             fb("double[]", np.ascontiguousarray(yp, float)), rows, cols, n,
                             *((ffi.NULL, ffi.NULL) if carried is None else
                               [fb("double[]", np.ascontiguousarray(c, float)) for c in carried]),
                             work, body)
    return ratio, body[0]
