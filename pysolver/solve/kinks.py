"""The knots of splines of time that drive motions, where a motion's velocity or acceleration
jumps: named in the message of an integration that fails there.

A spline is as smooth at its inner knots as its kind (LINSPL: continuous in value only,
AKISPL: in its first derivative, CUBSPL: in its second, QUISPL: in its fourth) and at its
first and last knots continuous in value only (Adams' extrapolation, the parabola or line
through the end points, meets the curve there with a slope of its own; LINSPL's own line with
``linear_extrap`` is the exception). A displacement motion through it asks for a velocity
jump where the spline's first derivative jumps, which no body makes: IDA shrinks its step
there and, at tight tolerances, gives up (docs/deck-language.md "Splines").
"""
from ..deck import expr as ex

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
    """(knot time, its index, spline id, kind, the spline's smoothness there, the rate that jumps,
    whether at the data's end) of each knot where a rate of `motion` up to its acceleration
    jumps."""
    for name, sid, order in _splines_of_time(model, motion.expr):
        sp = model.splines.get(sid)
        if sp is None or sp.z:
            continue
        # LINSPL's line past its ends is its last segment's: no knot there
        ends = None if name == "LINSPL" and sp.linear_extrap else 0
        for k, x in enumerate(sp.x):
            end = k in (0, len(sp.x) - 1)
            if k == 0 and x <= 0.0:
                continue            # runs start at t = 0: the curve is never left there
            smooth = ends if end else SMOOTHNESS[name]
            if smooth is None:
                continue
            # the first derivative of the spline that jumps, as a rate of the motion's measure
            rate = max(0, smooth + 1 - order) + _LEVEL[motion.val_type]
            if rate <= 2:
                yield x, k, sid, name, smooth, _RATES[rate], end


def knot_note(model, t, end_time):
    """A sentence naming the spline knot at t (within 1e-6 of the run's time scale) where a
    motion's velocity or acceleration jumps, or ''."""
    scale = 1e-6 * max(1.0, abs(end_time))
    for mo in model.motions.values():
        if mo.id <= 0 or mo.expr is None:
            continue
        for x, k, sid, name, smooth, rate, end in _jumps(model, mo):
            if abs(t - x) > scale:
                continue
            what = "Motion_Joint" if mo.joint else "Motion_Marker"
            if end:
                where = (f"the {'first' if k == 0 else 'last'} knot of Reference_Spline "
                         f"{sid}, where {name}'s extrapolation meets the curve with a slope of "
                         "its own")
                advice = "give the spline's data past the run's ends"
            else:
                where = (f"a knot of Reference_Spline {sid}, where {name} is continuous "
                         + ("in value only" if smooth == 0 else
                            f"in its derivatives up to order {smooth} only"))
                advice = "a spline smooth there, CUBSPL or QUISPL, does not"
            return (f"t = {x:.6g} is {where}: {what} {mo.id}'s {rate} jumps there, which "
                    f"IDA could not step across ({advice}; docs/deck-language.md, Splines)")
    return ""
