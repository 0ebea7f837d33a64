"""The times where a function of time alone has a kink or a jump: the run stops there and
restarts (:class:`TimeBreaks`), so that a force pulse shorter than IDA's step is not stepped
over.

A variable-step integrator sees a force only where it evaluates it: a pulse of 1 ms between
two steps of 0.1 s leaves no trace (trial 45: 1000 N for 1 ms never moved a free body, at
every tolerance). Where the pulse's ends are known at load, IDA can be made to stop at them
(its tstop) and restart there: its first step after a restart is sized from the distance to
the next stop, so the pulse is resolved. Found, in the force, motion, penalty and
Constraint_General expressions and the Reference_Variables they read (VARVAL):

- STEP, STEP5 and HAVSIN: where the argument x meets x0 and where it meets x1,
- IF: where its first expression is zero,
- ABS(a): where a is zero; SIGN(a, b): where b is; MIN, MAX and DIM(a, b): where a = b,
- IMPACT(x, ...): where x meets x1; BISTOP(x, ...): where x meets x1 and x2,

each only where the difference is an affine function of TIME with constant coefficients
(``2*(TIME - 1)``, ``TIME - PI/2``; numbers, PI, DTOR, RTOD and math functions of them;
a Reference_Variable that is such a function). Not found: a kink in a function of the state
(a contact, ``STEP(DZ(2), ...)``: IDA's error test has to find it), one whose bounds read a
Reference_Variable that is a plain number (a sweep may change it), the periodic jumps of MOD,
AINT and ANINT, and the knots of splines of TIME in forces (a motion's are
:mod:`.kinks`'s). docs/deck-language.md, "Functions of time".
"""
import math

import numpy as np

from .. import catalogue
from ..deck import expr as ex
from ..options import SPARSE_THRESHOLD
from .actors import Actor, Flow
from .kinks import impulse

#: Functions whose kinks are where argument 0 meets the arguments at these indices.
_MEETS = {"STEP": (1, 3), "STEP5": (1, 3), "HAVSIN": (1, 3), "IMPACT": (2,), "BISTOP": (2, 3)}
#: Functions whose kink is where the argument at this index is zero.
_ZERO = {"IF": 0, "ABS": 0, "SIGN": 1}
#: Functions of two arguments whose kink is where they are equal.
_EQUAL = ("MIN", "MAX", "DIM")


def _constant(f, *vals):
    """f of constant arguments by the language's rules (NumPy's), or None when not finite."""
    with np.errstate(all="ignore"):
        v = float(f(*[np.float64(x) for x in vals]))
    return v if math.isfinite(v) else None


def affine(tree, model, seen=()):
    """(a, b) when `tree` is a TIME + b with constant a and b, else None (a == 0: a constant).
    A VARVAL reads its variable's expression, unless that is a plain number (a sweep case may
    change it)."""
    tag = tree[0]
    if tag == "num":
        return 0.0, float(tree[1])
    if tag == "name":
        if tree[1] == "TIME":
            return 1.0, 0.0
        return (0.0, ex.CONSTANTS[tree[1]]) if tree[1] in ex.CONSTANTS else None
    if tag == "neg":
        p = affine(tree[1], model, seen)
        return None if p is None else (-p[0], -p[1])
    if tag == "bin":
        p, q = affine(tree[2], model, seen), affine(tree[3], model, seen)
        if p is None or q is None:
            return None
        op = tree[1]
        if op in "+-":
            s = 1.0 if op == "+" else -1.0
            return p[0] + s * q[0], p[1] + s * q[1]
        if op == "*" and (p[0] == 0.0 or q[0] == 0.0):
            return p[0] * q[1] + q[0] * p[1], p[1] * q[1]
        if op == "/" and q[0] == 0.0 and q[1] != 0.0:
            return p[0] / q[1], p[1] / q[1]
        if op == "**" and p[0] == 0.0 and q[0] == 0.0:
            v = _constant(catalogue.ARITHMETIC["**"].py, p[1], q[1])
            return None if v is None else (0.0, v)
        return None
    if tag != "call":
        return None
    if tree[1] == "VARVAL" and tree[2][0][0] == "num":
        vid = int(tree[2][0][1])
        var = model.variables.get(vid)
        if var is None or var.expr is None or var.expr[0] == "num" or vid in seen:
            return None
        return affine(var.expr, model, seen + (vid,))
    f = catalogue.FUNCTIONS.get(tree[1])
    if f is None or f.kind not in ("math1", "math2"):
        return None
    args = [affine(a, model, seen) for a in tree[2]]
    if any(a is None or a[0] != 0.0 for a in args):
        return None
    v = _constant(f.py, *[a[1] for a in args])
    return None if v is None else (0.0, v)


def _zero(p, q=(0.0, 0.0)):
    """The time where p - q (results of affine) is zero, or None."""
    if p is None or q is None:
        return None
    a, b = p[0] - q[0], p[1] - q[1]
    if a == 0.0:
        return None
    t = -b / a
    return t if math.isfinite(t) else None


def _in_tree(model, tree, seen=()):
    """(time, function) of every kink or jump in time of `tree`, through the variables it
    reads."""
    for n in ex.nodes(tree):
        if n[0] != "call":
            continue
        name, args = n[1], n[2]
        if name == "VARVAL" and args[0][0] == "num":
            vid = int(args[0][1])
            var = model.variables.get(vid)
            if var is not None and var.expr is not None and vid not in seen:
                yield from _in_tree(model, var.expr, seen + (vid,))
            continue
        pairs = []
        if name in _MEETS:
            pairs = [(args[0], args[k]) for k in _MEETS[name]]
        elif name in _ZERO:
            pairs = [(args[_ZERO[name]], None)]
        elif name in _EQUAL:
            pairs = [(args[0], args[1])]
        for x, x0 in pairs:
            t = _zero(affine(x, model, seen),
                      (0.0, 0.0) if x0 is None else affine(x0, model, seen))
            if t is not None:
                yield t, name


def _expressions(model):
    """Every expression that acts on the motion: forces, penalties, motions, general
    constraints (variables are read through them)."""
    for table in (model.sforces, model.penalties, model.motions, model.gcons):
        for el in table.values():
            if el.expr is not None:
                yield el.expr
    for vf in model.vforces.values():
        yield from (e for e in vf.exprs if e is not None)


def break_times(model, trees=None):
    """The ascending times after 0 where a function of TIME alone in the model's forces,
    motions and constraints (or in `trees`) has a kink or jump (the module's list)."""
    found = set()
    for tree in _expressions(model) if trees is None else trees:
        found.update(t for t, _ in _in_tree(model, tree) if t > 0.0)
    return sorted(found)


#: Where the rates of a restart at a break are taken, past it by SIDE max(1, |t|) (csrc/ida.c's
#: PS_BREAK_SIDE): a force that jumps there starts IDA with its value after the jump.
SIDE = 1e-12


class TimeBreaks(Actor):
    """Stops IDA at every time of :func:`break_times` and restarts it there (a cold restart,
    order 1, its first step sized from the distance to the next stop) with the consistent
    rates just past it. The batched path does the same in C (``ps_ida_breaks``; csrc/ida.c)
    for scenes whose rates C makes consistent alone (no motions, constraints or tracked
    angles, dense), so there this actor has no instants of its own."""

    def __init__(self, model, kernel):
        self.kernel = kernel
        self.times = break_times(model)
        # where a motion's or general constraint's rate may jump: restarts take the impulse
        self.jumps = set(break_times(model, [el.expr for table in (model.motions, model.gcons)
                                             for el in table.values() if el.expr is not None]))
        self.next = 0
        lay = kernel.layout
        self.in_c = not (lay.lam or lay.turns) and kernel.ny < SPARSE_THRESHOLD

    @property
    def instants(self):
        """False where the batched path stops at the same times in C."""
        return not self.in_c

    def next_time(self, t):
        while self.next < len(self.times) and self.times[self.next] < t:
            self.next += 1
        return self.times[self.next] if self.next < len(self.times) else math.inf

    def on_time(self, run):
        self.next += 1
        k, t = self.kernel, run.t
        side = t + SIDE * max(1.0, abs(t))
        k.d.last_t = side               # these evaluations are not step attempts
        y = np.array(run.y, dtype=float)
        if t in self.jumps:
            # a motion's velocity may jump here (a kink of its function of time): the
            # velocities of the impulse, as at a spline knot (kinks.KnotRestarts)
            impulse(k, side, y, np.asarray(run.yp, dtype=float))
            run.y = y
        run.yp = k.consistent_yp(side, y)
        return Flow(restart=True)

    def save(self):
        return self.next

    def restore(self, snapshot, t):
        self.next = snapshot
