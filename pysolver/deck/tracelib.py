"""The ``math`` module and NumPy's ufuncs on the values a user subroutine is traced with.

A traced routine sees :data:`SHIM` for the ``math`` module: its functions build the
expression language's calls on traced values (``math.sin(x)`` is ``SIN(x)``) and are
``math``'s on numbers. NumPy's ufuncs reach a traced value through its ``__array_ufunc__``
(:func:`ufunc`): ``np.sin(time)``, ``np.sqrt(z * z)``, and ``np.linalg.norm(p)`` of
``py_sysary``'s list (through the object array ``[x, y, z]``: ``x*x + y*y + z*z`` by
Python's operators, then ``np.sqrt``). Each ufunc with an exact counterpart in the expression
language builds that counterpart's tree, as the ``math`` function does, so a NumPy routine
traces into the expression written by hand: exact derivatives, no Python per evaluation. Any
other ufunc (``np.expm1``, ``np.floor``, ``np.isfinite``, ...) makes the routine untraceable:
it is then called from the kernel, as a routine that converts a traced value with ``float()``
is. :data:`OPERATORS`, :data:`FUNCTIONS` and :data:`SPECIAL` are NumPy's table.
"""
import math
import operator

import numpy as np

from .. import catalogue
from .tracer import Sym, Untraceable, _node, _number

# ---------------------------------------------------------------------------------------------
# the math module


def _call(name, *args):
    """The traced call NAME(args) of an expression-language function."""
    return Sym(("call", name, [_node(a) for a in args], 0))


def _math_function(real, name, arity=1):
    """A math-module function that builds NAME(...) on traced values and is math's otherwise."""
    def fn(*args):
        if any(isinstance(a, Sym) for a in args):
            if len(args) != arity:
                raise Untraceable(f"math.{real.__name__} with {len(args)} arguments")
            return _call(name, *args)
        return real(*args)
    fn.__name__ = real.__name__
    return fn


def _log(x, base=None):
    if base is None:
        return _math_function(math.log, "LOG")(x)
    return _math_function(math.log, "LOG")(x) / _math_function(math.log, "LOG")(base)


def _hypot(*args):
    if any(isinstance(a, Sym) for a in args):
        total = 0.0
        for a in args:
            total = total + a * a
        return _call("SQRT", total)
    return math.hypot(*args)


class _MathShim:
    """Stands in for the math module while a routine is traced."""

    def __getattr__(self, attr):
        return getattr(math, attr)      # constants and functions with no traced form


SHIM = _MathShim()
# the catalogue's math-module stand-ins; then math.log with its optional base, math.hypot of any
# number of arguments and math.pow as **
_NAMES = [f.math for f in catalogue.TABLE if f.math] + ["hypot", "pow"]
for _f in catalogue.TABLE:
    if _f.math:
        setattr(SHIM, _f.math, _math_function(getattr(math, _f.math), _f.name, _f.arity[1]))
SHIM.log = _log
SHIM.hypot = _hypot
SHIM.pow = lambda x, y: x ** y
_REPLACED = {getattr(math, n): getattr(SHIM, n) for n in _NAMES}


def shim_globals(namespace):
    """A copy of a namespace with the math module and its functions replaced by SHIM's."""
    out = dict(namespace)
    for key, val in namespace.items():
        if val is math:
            out[key] = SHIM
        elif callable(val):
            try:
                out[key] = _REPLACED.get(val, val)
            except TypeError:           # an unhashable callable: not a math function
                pass
    return out


# ---------------------------------------------------------------------------------------------
# NumPy's ufuncs

#: ufuncs a traced value takes through Python's operator (its own methods build the tree; a
#: comparison is a branch, as ``x < 0`` is)
OPERATORS = {
    np.add: operator.add, np.subtract: operator.sub, np.multiply: operator.mul,
    np.true_divide: operator.truediv, np.power: operator.pow, np.float_power: operator.pow,
    np.negative: operator.neg, np.positive: operator.pos, np.absolute: abs, np.fabs: abs,
    np.square: lambda x: x * x, np.reciprocal: lambda x: 1.0 / x,
    np.deg2rad: lambda x: x * (math.pi / 180.0), np.rad2deg: lambda x: x * (180.0 / math.pi),
    np.less: operator.lt, np.less_equal: operator.le, np.greater: operator.gt,
    np.greater_equal: operator.ge, np.equal: operator.eq, np.not_equal: operator.ne,
}

#: ufuncs that are a function of the expression language: the catalogue's (np.sin is SIN,
#: np.arctan2 ATAN2, np.maximum MAX, ...), fmax / fmin (maximum / minimum but for NaN) and
#: copysign (SIGN, as math.copysign is traced)
FUNCTIONS = {f.py: f.name for f in catalogue.TABLE
             if f.kind in ("math1", "math2") and isinstance(f.py, np.ufunc)
             and f.py not in OPERATORS}
FUNCTIONS.update({np.fmax: "MAX", np.fmin: "MIN", np.copysign: "SIGN"})

#: ufuncs written with the expression language's functions
SPECIAL = {
    np.hypot: lambda a, b: _call("SQRT", a * a + b * b),      # as math.hypot is traced
    np.sign: lambda x: _call("IF", x, -1.0, 0.0, 1.0),
}


def ufunc(fn, method, inputs, kwargs):
    """NumPy's ufunc `fn` called (``method``) on `inputs`, one of them a traced value: the
    traced value of its counterpart in the expression language; Untraceable when it has none
    (or is not a plain call)."""
    what = f"NumPy's {fn.__name__}" + ("" if method == "__call__" else f".{method}")
    if method != "__call__" or kwargs:
        raise Untraceable(f"{what} with {', '.join(kwargs) or 'that method'} of a "
                          "state-dependent value")
    if any(isinstance(x, np.ndarray) for x in inputs):
        # with an array: NumPy's object loops, element by element
        return fn(*[np.asarray(x, dtype=object) if isinstance(x, Sym) else x for x in inputs])
    args = [x if isinstance(x, Sym) else _number(x) for x in inputs]
    if fn in OPERATORS:
        return OPERATORS[fn](*args)
    if fn in FUNCTIONS:
        return _call(FUNCTIONS[fn], *args)
    if fn in SPECIAL:
        return SPECIAL[fn](*args)
    raise Untraceable(f"{what} of a state-dependent value: the expression language has no "
                      "such function")


def _element_method(fn):
    def method(self, *others):
        return ufunc(fn, "__call__", (self, *others), {})
    method.__name__ = fn.__name__
    return method


# Sym takes NumPy's ufuncs through __array_ufunc__; an object array's ufunc
# (np.sin(np.array([x, y]))) calls each element's method of the ufunc's name (the arithmetic
# ones it applies as Python's operators). Given here, where the table is: the tracer does not
# import this module.
Sym.__array_ufunc__ = lambda self, fn, method, *inputs, **kwargs: ufunc(fn, method, inputs,
                                                                        kwargs)
for _u in (*FUNCTIONS, *SPECIAL, np.fabs, np.square, np.reciprocal, np.deg2rad, np.rad2deg):
    setattr(Sym, _u.__name__, _element_method(_u))
