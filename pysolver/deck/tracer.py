"""Tracing a Python user subroutine into an expression tree of the deck language.

The routine is called once with symbolic stand-ins: ``time`` and every value ``py_sysfnc`` /
``py_sysary`` return are :class:`Sym` objects, and arithmetic and the ``math`` functions on
them build the same trees the expression parser builds (``('bin', '+', a, b)``,
``('call', 'SIN', [x], 0)``, ...). The result is compiled like any expression: it runs in C
with exact derivatives and no Python per evaluation.

Control flow that depends on the state (``if DZ < 0: ...``, ``min``, ``max``) is traced too: a
comparison of traced values is a :class:`Cond`, and each time the routine asks for its truth
value the tracer answers from a list of decisions. :func:`explore` runs the routine once per
path (depth first, at most ``MAX_PATHS``) and :func:`join` folds the paths' results into the
expression language's ``IF(a - b: neg, zero, pos)``, so every branch runs in C with the
derivatives of the branch taken. The ``math`` module's functions and NumPy's ufuncs build the
same trees (:mod:`.tracelib`). A routine that converts a traced value to a number
(``float()``, a float array), calls functions the expression language does not have, or has
too many paths cannot be traced: :class:`Untraceable` says where and why.
"""
import math
import numbers
import threading

import numpy as np

from .. import catalogue
from ..errors import DeckError, ExpressionError
from . import expr as ex

_ACTIVE = threading.local()


class Untraceable(Exception):
    """The routine did something a traced expression cannot represent."""


class SysfncError(Exception):
    """py_sysfnc / py_sysary was called with an unknown function or bad ids."""


class RoutineError(Exception):
    """An error a routine reported with py_errmes: like any exception it raises, it fails the
    trace only when no state-dependent branch leads to it."""


#: Most paths through a routine's state-dependent branches that are traced.
MAX_PATHS = 64


def _node(v):
    if isinstance(v, np.ndarray) and v.ndim == 0:
        v = v.item()                    # NumPy's 0-d result (np.where of one value)
    if isinstance(v, Sym):
        _fresh(v)
        return v.node
    return ("num", _number(v))


def _fresh(sym):
    """Refuse a traced value made on an earlier path (or call) of explore: the routine kept
    it between calls, so its expression would mix paths."""
    if sym.gen is not None and getattr(_ACTIVE, "paths", None) is not None \
            and sym.gen != _ACTIVE.gen:
        raise Untraceable("it keeps state between calls: a traced value from an earlier "
                          "call was used")


def _number(v):
    """A number (a NumPy scalar too) as a float; anything else is Untraceable."""
    if isinstance(v, (bool, np.bool_)) or not isinstance(v, numbers.Real):
        raise Untraceable(f"a {type(v).__name__} entered the computation; only numbers and "
                          "values from py_sysfnc can be traced")
    return float(v)


def _refuse(what):
    def method(self, *args):
        raise Untraceable(f"{what} of a state-dependent value: control flow or conversions "
                          "that depend on the state cannot be traced (math.fabs, math.copysign "
                          "and math.fmod can stand in for some)")
    return method


class Sym:
    """A state-dependent value being traced: wraps an expression tree."""
    __slots__ = ("node", "gen")

    def __init__(self, node):
        self.node = node
        # the explore path it was made on (None outside explore)
        self.gen = _ACTIVE.gen if getattr(_ACTIVE, "paths", None) is not None else None

    def _bin(self, op, other, swap=False):
        a, b = (_node(other), _node(self)) if swap else (_node(self), _node(other))
        return Sym(("bin", op, a, b))

    def __add__(self, o): return self._bin("+", o)
    def __radd__(self, o): return self._bin("+", o, True)
    def __sub__(self, o): return self._bin("-", o)
    def __rsub__(self, o): return self._bin("-", o, True)
    def __mul__(self, o): return self._bin("*", o)
    def __rmul__(self, o): return self._bin("*", o, True)
    def __truediv__(self, o): return self._bin("/", o)
    def __rtruediv__(self, o): return self._bin("/", o, True)
    def __pow__(self, o): return self._bin("**", o)
    def __rpow__(self, o): return self._bin("**", o, True)
    def __neg__(self): return Sym(("neg", _node(self)))
    def __pos__(self): return self
    def __abs__(self): return Sym(("call", "ABS", [_node(self)], 0))

    def _diff(self, o):
        """a - b of a comparison (a itself against zero)."""
        zero = isinstance(o, (int, float)) and not isinstance(o, bool) and o == 0
        return _node(self) if zero else self._bin("-", o).node

    def __bool__(self): return bool(Cond("!=", _node(self)))
    def __lt__(self, o): return Cond("<", self._diff(o))
    def __le__(self, o): return Cond("<=", self._diff(o))
    def __gt__(self, o): return Cond(">", self._diff(o))
    def __ge__(self, o): return Cond(">=", self._diff(o))
    def __eq__(self, o): return Cond("==", self._diff(o))
    def __ne__(self, o): return Cond("!=", self._diff(o))

    __float__ = _refuse("float()")
    __int__ = _refuse("int()")
    __index__ = _refuse("use as an index")
    __hash__ = None
    __floordiv__ = __rfloordiv__ = __mod__ = __rmod__ = _refuse("// or % (use math.fmod)")
    __round__ = _refuse("round()")

    def __repr__(self):
        return ex.unparse(self.node)

    # NumPy's ufuncs: tracelib, which imports this module, gives the class __array_ufunc__
    # and the methods an object array's ufunc calls


#: Which sign of d = a - b makes each comparison true: (d < 0, d == 0, d > 0).
_TRUE_WHEN = {"<": (1, 0, 0), "<=": (1, 1, 0), ">": (0, 0, 1), ">=": (0, 1, 1),
              "==": (0, 1, 0), "!=": (1, 0, 1)}


class Cond(Sym):
    """A comparison of traced values (``a < b`` as d = a - b and "<"). As a number it is 1 or 0;
    its truth value is a branch, decided by the path being traced."""
    __slots__ = ("op", "diff")

    def __init__(self, op, diff):
        self.op, self.diff = op, diff
        super().__init__(self.select(("num", 1.0), ("num", 0.0)))

    def select(self, yes, no):
        """The tree IF(d: ...) that is `yes` where the comparison holds and `no` elsewhere."""
        return ("call", "IF", [self.diff] + [yes if t else no for t in _TRUE_WHEN[self.op]], 0)

    def __bool__(self):
        paths = getattr(_ACTIVE, "paths", None)
        if paths is None:
            raise Untraceable("truth value of a state-dependent value outside a traced call")
        _fresh(self)
        return paths.decide(self)


# the name Python's and NumPy's own messages give these types ("unhashable type: ...")
for _t in (Sym, Cond):
    _t.__name__ = _t.__qualname__ = "traced value"


def untraceable_in(err):
    """The Untraceable that `err` is, or was raised from or while handling (NumPy turns one
    raised in an element's method into a TypeError), or None."""
    seen = set()
    while err is not None and id(err) not in seen:
        if isinstance(err, Untraceable):
            return err
        seen.add(id(err))
        err = err.__cause__ or (None if err.__suppress_context__ else err.__context__)
    return None


class _Paths:
    """The decisions of one traced run: a given prefix, then True for every new branch."""

    def __init__(self, prefix):
        self.prefix, self.taken, self.conds = prefix, [], []

    def decide(self, cond):
        i = len(self.taken)
        choice = self.prefix[i] if i < len(self.prefix) else True
        self.taken.append(choice)
        self.conds.append(cond)
        return choice


def explore(run):
    """Run ``run()`` along every path of its state-dependent branches, depth first.

    Returns a list of ``(decisions, conditions, result)``, one per path. Raises Untraceable when
    there are more than MAX_PATHS paths, or when a path with branches raises, reports an error
    (py_errmes) or exits (the exception is chained): a routine that fails on some branch runs
    from the kernel instead, where it fails only if the state takes that branch. A failure on
    no branch (every state would meet it) and a misuse of py_sysfnc are raised as they are.
    """
    leaves, prefix = [], []
    while True:
        paths = _Paths(prefix)
        prev, _ACTIVE.paths = getattr(_ACTIVE, "paths", None), paths
        _ACTIVE.gen = getattr(_ACTIVE, "gen", 0) + 1
        try:
            result = run()
        except (Exception, SystemExit) as err:
            if isinstance(err, (Untraceable, SysfncError, DeckError)):
                raise
            inner = untraceable_in(err)
            if inner is not None:
                raise Untraceable(str(inner)) from err
            if not paths.taken:
                raise
            what = (f"reports an error with py_errmes: {err}" if isinstance(err, RoutineError)
                    else f"raises {type(err).__name__}: {err}")
            raise Untraceable(f"the branch {_describe(paths)} {what}") from err
        finally:
            _ACTIVE.paths = prev
        leaves.append((paths.taken, paths.conds, result))
        if len(leaves) > MAX_PATHS:
            raise Untraceable(f"more than {MAX_PATHS} paths through state-dependent branches")
        # the next path: the last True decision taken the other way
        last = max((i for i, d in enumerate(paths.taken) if d), default=-1)
        if last < 0:
            return leaves
        prefix = paths.taken[:last] + [False]


def _describe(paths):
    return " and ".join(f"{'' if d else 'not '}{ex.unparse(c.diff)} {c.op} 0"
                        for d, c in zip(paths.taken, paths.conds))


def join(leaves, depth=0):
    """Fold explore's paths (their results already trees) into one tree with IF nodes."""
    if len(leaves) == 1 and len(leaves[0][0]) == depth:
        return leaves[0][2]
    cond = leaves[0][1][depth]
    if any(len(d) <= depth or c[depth].op != cond.op or c[depth].diff != cond.diff
           for d, c, _ in leaves):
        raise Untraceable("the routine's branches differ between runs on the same path "
                          "(it depends on something other than its arguments)")
    yes = join([leaf for leaf in leaves if leaf[0][depth]], depth + 1)
    no = join([leaf for leaf in leaves if not leaf[0][depth]], depth + 1)
    return cond.select(yes, no)


# ---------------------------------------------------------------------------------------------
# py_sysfnc and py_sysary: what a routine reads

#: SYSARY arrays (Adams/MotionSolve): name -> the SYSFNC functions of its entries.
SYSARY = catalogue.SYSARY
#: What py_sysfnc reads.
SYSFNC = frozenset(f.name for f in catalogue.TABLE if f.py_sysfnc)


def _ids(fnc, ids):
    try:
        out = [int(i) for i in ids]
        if any(o != i for o, i in zip(out, ids)):
            raise ValueError
    except (TypeError, ValueError):
        raise SysfncError(f"{fnc}: ids must be whole numbers, got {list(ids)!r}") from None
    return out


def measure(fnc, ids):
    """The traced value of one SYSFNC function (e.g. "DZ", [10, 1])."""
    name = str(fnc).upper()
    if name not in SYSFNC:
        raise SysfncError(f"unknown function {fnc!r}; py_sysfnc reads "
                          f"{', '.join(sorted(SYSFNC))}")
    node = ("call", name, [("num", float(i)) for i in _ids(name, ids)], 0)
    try:
        ex._check(node)
    except ExpressionError as err:
        raise SysfncError(f"{name}{tuple(ids)}: {err.reason}") from None
    return Sym(node)


def py_sysfnc(fnc, ids):
    """One system value for a user subroutine: ``[value, errflg]`` (MotionSolve's py_sysfnc).

    Valid only inside a user subroutine that pysolver calls (to trace it, or from the kernel).
    """
    live_fn = _mode("py_sysfnc")
    if live_fn is not None:
        return live_fn(fnc, ids)
    return [measure(fnc, ids), 0]


def py_sysary(fnc, ids):
    """An array of system values: ``[values, errflg]`` for TDISP, TVEL, RVEL, VEL, TACC."""
    live_fn = _mode("py_sysary")
    name = str(fnc).upper()
    if name not in SYSARY:
        raise SysfncError(f"unknown array {fnc!r}; py_sysary reads {', '.join(SYSARY)}")
    ids = list(ids)
    # angular velocities take at most three ids (i, j, k)
    parts = [(f, ids[:3] if f.startswith("W") else ids) for f in SYSARY[name]]
    if live_fn is not None:
        values = [live_fn(f, i) for f, i in parts]
        return [[v for v, _ in values], max(e for _, e in values)]
    return [[measure(f, i) for f, i in parts], 0]


def py_syspar(fnc, ids, partials):
    """Give the partials of the routine's result in values it read (Adams' SYSPAR): `fnc` and
    `ids` as in the py_sysfnc / py_sysary call, `partials` one number per value it returned.
    Returns errflg (0). A routine called from the kernel is then not differenced in those
    values; while a routine is traced it does nothing (tracing differentiates exactly).
    """
    mode = getattr(_ACTIVE, "mode", None)
    if mode is not None and mode is not _TRACING and mode[1] is not None:
        return mode[1](fnc, ids, partials)
    _mode("py_syspar")              # tracing: nothing to do; outside a routine: the error
    return 0


def py_errmes(errflg, message, id, endflag="STOP"):
    """Report a user subroutine's error (MotionSolve's py_errmes).

    When `errflg` is set, raises :class:`RoutineError` ``"message (id id)"``, whatever
    `endflag` says: the routine stops there and, called from the kernel, so does the run
    (status -400). While the routine is traced, a call on a state-dependent branch makes it
    run from the kernel instead, so the error is reported only if the state takes that branch.
    """
    if errflg:
        raise RoutineError(f"{message} (id {id})")


#: The thread's mode (``_ACTIVE.mode``) while a routine is traced; inside a kernel call it is
#: the pair (reader, syspar) of :func:`enter_live`, outside both None. One attribute, so a
#: kernel call switches it with one read and one write.
_TRACING = ("tracing",)


def _mode(what):
    """None while tracing; the live reader inside a kernel call; else an error."""
    mode = getattr(_ACTIVE, "mode", None)
    if mode is _TRACING:
        return None
    if mode is None:
        raise RuntimeError(f"{what} works only inside a user subroutine that pysolver calls")
    return mode[0]


class active:
    """Context in which py_sysfnc and friends build traced values."""

    def __enter__(self):
        self.prev = getattr(_ACTIVE, "mode", None)
        _ACTIVE.mode = _TRACING
        return self

    def __exit__(self, *exc):
        _ACTIVE.mode = self.prev
        return False


def enter_live(reader, syspar=None):
    """Make py_sysfnc read real values through `reader(fnc, ids)` and py_syspar give partials
    through `syspar(fnc, ids, partials)` (a routine called from the kernel) until
    :func:`leave_live` restores what this returns."""
    prev = getattr(_ACTIVE, "mode", None)
    _ACTIVE.mode = (reader, syspar)
    return prev


def leave_live(prev):
    _ACTIVE.mode = prev


def tree_of(value):
    """The expression tree of a routine's return value (a number or a traced value)."""
    tree = _node(value)
    if tree[0] == "num" and not math.isfinite(tree[1]):
        raise Untraceable(f"the routine returned {tree[1]}")
    return tree
