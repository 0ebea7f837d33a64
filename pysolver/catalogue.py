"""The expression language's operations and functions, each declared once.

One :class:`Function` record per name a deck may write (``TIME``, ``+``, ``SIN``, ``DX``,
``STEP``, ``SFORCE``, ...) and per tape instruction no deck writes (``const``, ``gdot``, ...).
Everything else reads this table: the parser's names, arities and id arguments
(``deck/expr.py``), which functions read velocities (``deck/references.py``), the tracer's
``math`` stand-ins and ``py_sysfnc`` names (``deck/tracer.py``), the compiler's lowering and
tape basis (``build/compiler.py``), the generated C's tables (``build/codegen``) and the
function table of docs/deck-language.md (``python -m pysolver.catalogue``). C cannot read it:
tests/test_catalogue.py checks that ``csrc/include/pysolver.h``'s ``PS_OP_*`` and ``PS_M_*``
enums and ``csrc/usersub.c``'s c_sysfnc table agree with it. The functions of MotionSolve
and Adams that pysolver does not have (:data:`REFUSED`), the element kinds (their kernel
layouts) and the joint types' equations are declared here too.

Longer than 420 lines because it is a table: the functions, those it does not have, the
element kinds and the joint types, each a record or a row, are the one place they are
declared.
"""
import operator
import re
import sys
from dataclasses import dataclass
from typing import Callable, Optional

import numpy as np

#: What a function reads besides its arguments.
READS = ("time", "positions", "velocities", "accelerations", "forces", "variables", "stored")
#: Reads that make an expression more than a function of positions and time (a penalty
#: constraint's g may not have them).
DYNAMIC = frozenset({"velocities", "accelerations", "forces"})
#: Kinds of record.
KINDS = ("name", "arithmetic", "math1", "math2", "step", "expanded", "special", "measure",
         "internal")


@dataclass(frozen=True)
class Function:
    """One operation or function of the expression language.

    Attributes
    ----------
    name : str
        As a deck writes it (``"SIN"``, ``"DX"``, ``"+"``; ``"neg"`` for unary minus; lower
        case for internal instructions).
    kind : str
        One of :data:`KINDS`.
    args : tuple of str
        Argument names (a measure's marker roles i, j, k, l); the most it takes.
    c : str or None
        The C enum value it lowers to (``"PS_OP_SIN"``, ``"PS_M_DX"``); None when it is
        lowered to other operations (IMPACT) or is a number (PI).
    doc : str
        One line for the documentation's function table.
    required : int or None
        The fewest arguments (None: all of `args`).
    reads : frozenset of str
        What it reads besides its arguments (:data:`READS`).
    ids : tuple
        Per argument, the kind of element whose id it is (``"marker"``, ``"variable"``, ...),
        or None for a number.
    py : callable or None
        Its value on floats with C's IEEE rules when given NumPy float64 numbers (infinity or
        NaN rather than an exception), for the constant checks at load; a named number's
        takes no argument and returns it.
    fold : bool
        The compiler folds it on constant Python floats (exact and never raising).
    math : str or None
        The ``math`` module function a traced Python routine calls for it.
    libm : str or None
        The C library function generated C calls for it (one-argument functions).
    py_sysfnc, c_sysfnc : bool
        A user subroutine reads it through ``py_sysfnc`` / ``c_sysfnc`` (by this name).
    """

    name: str
    kind: str
    args: tuple
    c: Optional[str]
    doc: str
    required: Optional[int] = None
    reads: frozenset = frozenset()
    ids: tuple = ()
    py: Optional[Callable] = None
    fold: bool = False
    math: Optional[str] = None
    libm: Optional[str] = None
    py_sysfnc: bool = False
    c_sysfnc: bool = False

    @property
    def arity(self):
        """(fewest, most) arguments."""
        return (len(self.args) if self.required is None else self.required, len(self.args))

    @property
    def usage(self):
        """How a deck writes it: ``DX(i[, j[, k]])``, ``a + b``, ``TIME``."""
        if self.kind == "name":
            return self.name
        if self.kind == "arithmetic":
            return "-a" if self.name == "neg" else f"a {self.name} b"
        if self.name == "IF":
            return "IF(e1: e2, e3, e4)"
        lo, hi = self.arity
        if hi - lo > 3:                 # a series: its first optional argument and its last
            return f"{self.name}({', '.join(self.args[:lo])}[, {self.args[lo]}, ..., " \
                   f"{self.args[-1]}])"
        tail = "".join(f"[, {a}" for a in self.args[lo:]) + "]" * (hi - lo)
        return f"{self.name}({', '.join(self.args[:lo])}{tail})"


def _math1(name, py, libm, doc, math_name=None):
    return Function(name, "math1", ("x",), f"PS_OP_{name}", doc, py=py, libm=libm,
                    math=math_name)


def _math2(name, args, py, doc, math_name=None):
    return Function(name, "math2", args, f"PS_OP_{name}", doc, py=py, math=math_name)


def _step(name, doc):
    return Function(name, "step", ("x", "x0", "h0", "x1", "h1"), "PS_OP_STEPC", doc)


def _expanded(name, args, doc, required=None):
    """A function the parser writes as other operations (pysolver.deck.series)."""
    return Function(name, "expanded", args, None, doc, required=required)


#: The coefficients of POLY, CHEBY, FORCOS and FORSIN: at most 31 (Adams, MotionSolve).
_COEFFICIENTS = tuple(f"a{j}" for j in range(31))


_POS = frozenset({"positions"})
_VEL = frozenset({"positions", "velocities"})
_ACC = frozenset({"positions", "velocities", "accelerations"})


def _measure(name, args, reads, doc):
    """A measure of markers: every argument a marker id (0 or omitted: the global frame)."""
    return Function(name, "measure", tuple(args), f"PS_M_{name}", doc, required=1, reads=reads,
                    ids=("marker",) * len(args), py_sysfnc=True, c_sysfnc=True)


def _element(name, kind, doc, reads, c=None):
    """A value of one element, named by its id."""
    return Function(name, "special", ("id",), c, doc, reads=frozenset({reads}), ids=(kind,),
                    py_sysfnc=True, c_sysfnc=True)


def _internal(name, doc):
    return Function(name, "internal", (), f"PS_OP_{name.upper()}", doc)


_PI = 3.141592653589793
_FORCE_ARGS = ("id", "jflag", "comp", "rm")

#: Every operation and function, in the order of the documentation's table.
TABLE = (
    # names
    Function("TIME", "name", (), "PS_OP_TIME", "simulation time", reads=frozenset({"time"})),
    Function("PI", "name", (), None, "pi", py=lambda: _PI),
    Function("DTOR", "name", (), None, "pi / 180: degrees to radians", py=lambda: _PI / 180.0),
    Function("RTOD", "name", (), None, "180 / pi: radians to degrees", py=lambda: 180.0 / _PI),
    # arithmetic (FORTRAN precedence: -2**2 = -4, ** right-associative)
    Function("+", "arithmetic", ("a", "b"), "PS_OP_ADD", "sum", py=operator.add, fold=True),
    Function("-", "arithmetic", ("a", "b"), "PS_OP_SUB", "difference", py=operator.sub,
             fold=True),
    Function("*", "arithmetic", ("a", "b"), "PS_OP_MUL", "product", py=operator.mul, fold=True),
    Function("/", "arithmetic", ("a", "b"), "PS_OP_DIV", "quotient", py=operator.truediv),
    Function("**", "arithmetic", ("a", "b"), "PS_OP_POW",
             "a to the power b (right-associative, binds tighter than unary minus)",
             py=operator.pow),
    Function("neg", "arithmetic", ("a",), "PS_OP_NEG", "negation", py=operator.neg, fold=True),
    # functions of one number
    _math1("ABS", np.abs, "fabs", "absolute value", "fabs"),
    _math1("ACOS", np.arccos, "acos", "arc cosine (radians)", "acos"),
    _math1("ASIN", np.arcsin, "asin", "arc sine (radians)", "asin"),
    _math1("ATAN", np.arctan, "atan", "arc tangent (radians)", "atan"),
    _math1("COS", np.cos, "cos", "cosine", "cos"),
    _math1("COSH", np.cosh, "cosh", "hyperbolic cosine", "cosh"),
    _math1("SIN", np.sin, "sin", "sine", "sin"),
    _math1("SINH", np.sinh, "sinh", "hyperbolic sine", "sinh"),
    _math1("TAN", np.tan, "tan", "tangent", "tan"),
    _math1("TANH", np.tanh, "tanh", "hyperbolic tangent", "tanh"),
    _math1("EXP", np.exp, "exp", "e to the power x", "exp"),
    _math1("LOG", np.log, "log", "natural logarithm", "log"),
    _math1("LOG10", np.log10, "log10", "base-10 logarithm", "log10"),
    _math1("SQRT", np.sqrt, "sqrt", "square root", "sqrt"),
    _math1("AINT", np.trunc, "trunc", "x truncated toward zero (zero derivative)"),
    _math1("ANINT", lambda x: np.sign(x) * np.floor(np.abs(x) + 0.5), "round",
           "x rounded to the nearest whole number, halves away from zero (zero derivative)"),
    # functions of two numbers
    _math2("ATAN2", ("y", "x"), np.arctan2, "angle of the point (x, y), in (-pi, pi]", "atan2"),
    _math2("MOD", ("a", "b"), np.fmod, "a - b AINT(a / b): the remainder, with a's sign",
           "fmod"),
    _math2("MAX", ("a", "b"), np.maximum, "the larger (a when equal)"),
    _math2("MIN", ("a", "b"), np.minimum, "the smaller (a when equal)"),
    _math2("SIGN", ("a", "b"), lambda a, b: np.abs(a) * (1.0 if b >= 0 else -1.0),
           "|a| with the sign of b (b = 0 counts as positive)", "copysign"),
    _math2("DIM", ("a", "b"), lambda a, b: np.maximum(a - b, 0.0), "max(a - b, 0)"),
    # STEP family, in the order of PS_OP_STEPC's shape code
    _step("STEP", "h0 + (h1 - h0) D^2 (3 - 2 D), D = (x - x0) / (x1 - x0) clamped to [0, 1]"),
    _step("STEP5", "as STEP with D^3 (10 - 15 D + 6 D^2): smooth second derivative"),
    _step("HAVSIN", "as STEP with (1 - cos(pi D)) / 2"),
    # series and harmonics, written as arithmetic and SIN/COS when parsed
    _expanded("SHF", ("x", "x0", "a", "w", "phi", "b"),
              "simple harmonic function a SIN(w (x - x0) - phi) + b"),
    _expanded("POLY", ("x", "x0") + _COEFFICIENTS,
              "polynomial a0 + a1 u + a2 u^2 + ... + an u^n, u = x - x0", required=3),
    _expanded("CHEBY", ("x", "x0") + _COEFFICIENTS,
              "Chebyshev series a0 T0(u) + ... + an Tn(u), u = x - x0, T0 = 1, T1 = u, "
              "Tj = 2 u Tj-1 - Tj-2", required=3),
    _expanded("FORCOS", ("x", "x0", "w") + _COEFFICIENTS,
              "Fourier cosine series a0 + a1 COS(w u) + ... + an COS(n w u), u = x - x0",
              required=4),
    _expanded("FORSIN", ("x", "x0", "w") + _COEFFICIENTS,
              "Fourier sine series a0 + a1 SIN(w u) + ... + an SIN(n w u), u = x - x0",
              required=4),
    Function("IF", "special", ("e1", "e2", "e3", "e4"), "PS_OP_IF",
             "e2 where e1 < 0, e3 where e1 = 0, e4 where e1 > 0"),
    Function("IMPACT", "special", ("x", "dx", "x1", "k", "e", "cmax", "d"), None,
             "contact where x < x1: max(0, k (x1 - x)^e - STEP(x, x1 - d, cmax, x1, 0) dx)"),
    Function("BISTOP", "special", ("x", "dx", "x1", "x2", "k", "e", "cmax", "d"), None,
             "IMPACT-like walls at x1 (pushing up) and x2 (pushing down)"),
    # measures, in the order of enum psMeasure; marker roles: i from j, components in k's
    # axes, time derivatives in l's frame
    _measure("DX", "ijk", _POS, "x of the displacement of i from j, in k's axes"),
    _measure("DY", "ijk", _POS, "y of the displacement of i from j, in k's axes"),
    _measure("DZ", "ijk", _POS, "z of the displacement of i from j, in k's axes"),
    _measure("DM", "ij", _POS, "distance from j to i"),
    _measure("VX", "ijkl", _VEL, "x of the velocity of i relative to j, in k's axes, seen "
             "from l's frame"),
    _measure("VY", "ijkl", _VEL, "y of the velocity of i relative to j, in k's axes, seen "
             "from l's frame"),
    _measure("VZ", "ijkl", _VEL, "z of the velocity of i relative to j, in k's axes, seen "
             "from l's frame"),
    _measure("VM", "ijl", _VEL, "magnitude of the velocity of i relative to j, seen from l's "
             "frame"),
    _measure("VR", "ijl", _VEL, "radial velocity: the rate of DM(i, j), seen from l's frame"),
    _measure("ACCX", "ijkl", _ACC, "x of the acceleration of i relative to j, in k's axes, "
             "seen from l's frame"),
    _measure("ACCY", "ijkl", _ACC, "y of the acceleration of i relative to j, in k's axes, "
             "seen from l's frame"),
    _measure("ACCZ", "ijkl", _ACC, "z of the acceleration of i relative to j, in k's axes, "
             "seen from l's frame"),
    _measure("WX", "ijk", _VEL, "x of the angular velocity of i relative to j, in k's axes"),
    _measure("WY", "ijk", _VEL, "y of the angular velocity of i relative to j, in k's axes"),
    _measure("WZ", "ijk", _VEL, "z of the angular velocity of i relative to j, in k's axes"),
    *(Function(f"WDT{c}", "measure", tuple("ijkl"), f"PS_M_WDT{c}",
               f"{c.lower()} of the angular acceleration of i relative to j, in k's axes, seen "
               "from l's frame", required=1, reads=_ACC, ids=("marker",) * 4, py_sysfnc=True)
      for c in "XYZ"),
    # magnitudes of the angular velocity, acceleration and angular acceleration (0 at rest,
    # with zero derivatives there, like DM and VM)
    *(Function(name, "special", args, None, doc, required=1, reads=reads,
               ids=("marker",) * len(args), py_sysfnc=True) for name, args, reads, doc in (
        ("WM", ("i", "j"), _VEL, "magnitude of the angular velocity of i relative to j"),
        ("ACCM", ("i", "j", "l"), _ACC, "magnitude of the acceleration of i relative to j, "
         "seen from l's frame"),
        ("WDTM", ("i", "j", "l"), _ACC, "magnitude of the angular acceleration of i relative "
         "to j, seen from l's frame"))),
    _measure("AX", "ij", _POS, "angle of i's axes about j's x axis, in (-pi, pi]"),
    _measure("AY", "ij", _POS, "angle of i's axes about j's y axis, in (-pi, pi]"),
    _measure("AZ", "ij", _POS, "angle of i's axes about j's z axis, in (-pi, pi]"),
    Function("KE", "special", ("id",), None,
             "kinetic energy of body id (0: of every body), in force times length units",
             reads=_VEL, ids=("body",), py_sysfnc=True),
    *(Function(f"A{c}U", "special", ("i", "j"), None,
               f"A{c}(i, j) unwrapped: continuous through every turn from its value at the "
               "start (in (-pi, pi]; a tracked angle)", required=1, reads=_POS,
               ids=("marker", "marker"), py_sysfnc=True) for c in "XYZ"),
    *(Function(name, "special", ("x", "z", "id", "order"), None,
               f"{what} of Reference_Spline id at x (a surface: at x and z, linear in z), or "
               "a curve's derivative of order 1 or 2", required=3,
               ids=(None, None, "spline", None), py_sysfnc=False)
      for name, what in (("AKISPL", "Akima's cubic spline"),
                         ("CUBSPL", "the natural cubic spline"),
                         ("LINSPL", "the broken line"),
                         ("QUISPL", "the natural quintic spline (Herriot-Reinsch)"))),
    *(Function(name, "special", ("i", "j", "k"), None,
               f"{what} acting at marker i (from the elements between i and j when j is not 0), "
               "in k's axes: forces and constraint forces (pysolver.build.netforce)",
               required=1, reads=frozenset({"forces"}), ids=("marker",) * 3, py_sysfnc=True)
      for name, what in (("FX", "x of the net force"), ("FY", "y of the net force"),
                         ("FZ", "z of the net force"), ("FM", "magnitude of the net force"),
                         ("TX", "x of the net torque"), ("TY", "y of the net torque"),
                         ("TZ", "z of the net torque"), ("TM", "magnitude of the net torque"))),
    Function("ORIENT", "special", ("system", "comp", "i", "j"), None,
             "component comp of the orientation of i relative to j in convention system (27: "
             "the Euler parameters e0..e3 with e0 >= 0, the one pysolver computes)",
             required=3, reads=_POS, ids=(None, None, "marker", "marker"), py_sysfnc=True),
    # orientation angles of i relative to j, lowered to dot products of their axes
    *(Function(name, "special", ("i", "j"), None, doc, required=1, reads=_POS,
               ids=("marker", "marker"), py_sysfnc=True) for name, doc in (
        ("PSI", "first body-fixed 3-1-3 angle of i relative to j (0 where theta is 0 or pi)"),
        ("THETA", "second body-fixed 3-1-3 angle of i relative to j, in [0, pi]"),
        ("PHI", "third body-fixed 3-1-3 angle of i relative to j"),
        ("YAW", "first body-fixed 3-2-1 angle of i relative to j"),
        ("PITCH", "minus the second body-fixed 3-2-1 angle of i relative to j (Adams'), in "
                  "[-pi/2, pi/2]"),
        ("ROLL", "third body-fixed 3-2-1 angle of i relative to j"))),
    # values of other elements, named by id
    _element("VARVAL", "variable", "the value of Reference_Variable id", "variables"),
    _element("PFORCE", "penalty", "the scalar force -p g - p1 g' of Force_Penalty id",
             "forces"),
    Function("SFORCE", "special", _FORCE_ARGS, None,
             "force of Force_Scalar_TwoBody id: comp 1 |force|, 2-4 force in rm's axes, "
             "5 |torque|, 6-8 torque; on I (jflag 0) or J (1)", reads=frozenset({"forces"}),
             ids=("sforce", None, None, "marker"), py_sysfnc=True, c_sysfnc=True),
    _element("SENVAL", "evaluate", "the value Sensor_Evaluate id stored when its sensor last "
             "fired (0 before)", "stored", c="PS_OP_SENVAL"),
    Function("SPDP", "special", _FORCE_ARGS, None,
             "force of Force_SpringDamper id, as SFORCE's (a torque for a ROTATIONAL one)",
             reads=frozenset({"forces"}), ids=("springdamper", None, None, "marker"),
             py_sysfnc=True),
    Function("BUSH", "special", _FORCE_ARGS, None,
             "force and torque of Force_Bushing id: comp 1 |force|, 2-4 force in rm's axes, 5 "
             "|torque|, 6-8 torque; on I's body at I (jflag 0) or on J's at J (1)",
             reads=frozenset({"forces"}), ids=("bushing", None, None, "marker"),
             py_sysfnc=True),
    Function("FIELD", "special", _FORCE_ARGS, None,
             "force and torque of Force_Field id, as BUSH's", reads=frozenset({"forces"}),
             ids=("field", None, None, "marker"), py_sysfnc=True),
    Function("BEAM", "special", _FORCE_ARGS, None,
             "force and torque of Force_Beam id, as BUSH's", reads=frozenset({"forces"}),
             ids=("beam", None, None, "marker"), py_sysfnc=True),
    Function("JOINT", "special", _FORCE_ARGS, None,
             "reaction of Constraint_Joint id from its equations' multipliers: comp 1 |force|, "
             "2-4 force in rm's axes, 5 |torque|, 6-8 torque; on I's body at I (jflag 0) or "
             "on J's at J (1)", reads=frozenset({"forces"}),
             ids=("joint", None, None, "marker"), py_sysfnc=True),
    Function("JPRIM", "expanded", _FORCE_ARGS, None,
             "Adams' name of JOINT(id, jflag, comp, rm) for a Constraint_Jprim",
             reads=frozenset({"forces"}), ids=("joint", None, None, "marker")),
    Function("MOTION", "special", _FORCE_ARGS, None,
             "reaction of Motion_Marker or Motion_Joint id along its axis; with 4 arguments a "
             "component as SFORCE's", required=1, reads=frozenset({"forces"}),
             ids=("motion", None, None, "marker"), py_sysfnc=True),
    # tape instructions no deck writes
    _internal("const", "a number of the model (consts[a0])"),
    _internal("clamp01", "min(max(x, 0), 1): the STEP family's ramp"),
    _internal("measure", "a measure (a0, a PS_M_* value) of markers a1..a4"),
    _internal("gdot", "total time derivative of a displacement expression (g')"),
    _internal("axdot", "dot product of two markers' axes"),
    _internal("user", "a user subroutine the kernel calls"),
    _internal("state", "a state entry read with its derivative (a motion's reaction)"),
)

# the functions pysolver does not have -------------------------------------------------------
_NOT_MODELLED = "pysolver does not model the {} it reads"
#: Functions of MotionSolve or Adams that pysolver does not support, and why: the parser says
#: "not supported", never "unknown" (docs/deck-language.md, "Functions pysolver does not
#: have"); a function of the table above of the same name wins.
REFUSED = {
    "DELAY": "MotionSolve interpolates its history between the points where the solver "
             "happened to evaluate it, which is not exact and makes a run depend on its steps; "
             "pysolver keeps no history of past states",
    "SWEEP": "its public definitions disagree (MotionSolve's page and the Adams-derived ones "
             "differ in the chirp's phase and in where its STEP5 ramp starts); write the "
             "chirp with SIN, STEP5 and IF",
    "INVPSD": "the signal it rebuilds from a power spectral density depends on random phases "
              "drawn by a generator that is not public",
    "INTERP": "it reads SPLINEs of DAC or RPC III time-history files (Adams Durability), "
              "which pysolver does not read; use AKISPL, CUBSPL or LINSPL",
    "INCANG": "not yet; the included angle is ACOS of the dot product of the two "
              "displacements, written with DX, DY, DZ and DM",
    "TRIM": "MotionSolve's page does not give its formula",
    "FITSPL": "MotionSolve's pages do not say which FITPACK B-spline fit it is (its degree "
              "'3rd order' and 'of the 2nd degree' on one page; its knots and smoothing not "
              "at all); use CUBSPL or AKISPL of the same Reference_Spline",
    **dict.fromkeys(("VFORCE", "VTORQ", "VTORQUE", "GFORCE"),
                    "force functions of Force_Vector_TwoBody are not supported yet; FX..TZ(i, "
                    "j, k) give the net force and torque at a marker"),
    **{name: _NOT_MODELLED.format(what) for name, what in (
        ("FRICTION", "Force_Friction (Adams FRICTION)"), ("NFORCE", "Adams NFORCE"),
        ("CONTACT", "Force_Contact (Adams CONTACT)"), ("CVCV", "Adams CVCV"),
        ("PTCV", "Adams PTCV"), ("CURVE", "Reference_Curve (Adams CURVE)"),
        ("ARYVAL", "Reference_Array (Adams ARRAY)"), ("DIF", "Control_Diff (Adams DIFF)"),
        ("DIF1", "Control_Diff (Adams DIFF)"), ("PINVAL", "Control_PlantInput (Adams PINPUT)"),
        ("POUVAL", "Control_PlantOutput (Adams POUTPUT)"),
        ("FXFREQ", "flexible bodies"), ("FXMODE", "flexible bodies"))},
}
#: Names of Adams that pysolver does not support (a linear analysis' mode number).
REFUSED_NAMES = {"MODE": "pysolver runs no linear (modal) analysis"}

#: Callable functions of the deck language by name (not names, arithmetic or instructions).
#: WM, ACCM and WDTM: the three components whose norm each is (in the global axes).
MAGNITUDES = {"WM": ("WX", "WY", "WZ"), "ACCM": ("ACCX", "ACCY", "ACCZ"),
              "WDTM": ("WDTX", "WDTY", "WDTZ")}

FUNCTIONS = {f.name: f for f in TABLE if f.kind not in ("name", "arithmetic", "internal")}
#: Names (TIME and the named numbers) by name.
NAMES = {f.name: f for f in TABLE if f.kind == "name"}
#: Arithmetic by its symbol (``neg``: unary minus).
ARITHMETIC = {f.name: f for f in TABLE if f.kind == "arithmetic"}
#: The STEP family in the order of PS_OP_STEPC's shape code (0 STEP, 1 STEP5, 2 HAVSIN).
STEP_SHAPES = tuple(f.name for f in TABLE if f.kind == "step")
#: The C enum values the table names: opcodes, then measures, each in table order.
OPCODES = tuple(dict.fromkeys(f.c for f in TABLE if f.c and f.c.startswith("PS_OP_")))
MEASURE_CODES = tuple(f.c for f in TABLE if f.c and f.c.startswith("PS_M_"))
#: What c_sysfnc answers, in its function-code order (csrc/usersub.c FUNCTIONS).
C_SYSFNC = tuple(f.name for f in TABLE if f.c_sysfnc)

#: SYSARY arrays (Adams/MotionSolve): name -> the SYSFNC functions of its entries
#: (csrc/usersub.c ARRAYS).
SYSARY = {"TDISP": ("DX", "DY", "DZ"), "TVEL": ("VX", "VY", "VZ"), "RVEL": ("WX", "WY", "WZ"),
          "VEL": ("VX", "VY", "VZ", "WX", "WY", "WZ"), "TACC": ("ACCX", "ACCY", "ACCZ")}


def of_kind(*kinds):
    """The records of the given kinds, in table order."""
    return tuple(f for f in TABLE if f.kind in kinds)


# element kinds -----------------------------------------------------------------------------
@dataclass(frozen=True)
class Element:
    """One kind of deck element: how a deck names it and where a Model keeps it.

    Attributes
    ----------
    tags : tuple of str
        Its XML element names (Body_Rigid and Body_Point are both bodies).
    kind : str
        Its id namespace: what expressions and errors call it (``"penalty"``).
    table : str
        The Model attribute holding its records by id (``"penalties"``).
    statement : str or None
        Its statement in a Python deck (pysolver.msolve).
    usersub : tuple or None
        (routine name, arguments, values) when a user subroutine may define it, with
        MotionSolve's calling convention.
    bad : str or None
        The ``psData.bad_kind`` value (``PS_BAD_*``) of a non-finite value in it, when the
        kernel diagnoses its expressions outside the element table (sensors); its records are
        in id order in the kernel.
    c : str or None
        Its kind (``PS_EL_*``) in the kernel's element table, when it contributes rows there
        (csrc/elements/<kind>.c); a non-finite value in it is ``PS_BAD_ELEMENT``.
    ints : tuple of str
        Its ints in ``psModel.el_int``, in order, as ``name:role``; the role says what the
        int is and how a part of looped C renumbers it: ``slot`` (a tape slot: the first
        `values` are its values, checked by the diagnosis), ``flag`` (a number), ``marker``,
        ``bslot`` (a body slot of its tape, -1 ground) or ``state`` (an index into y, -1
        none).
    values : int
        How many leading `ints` are the slots of its values.
    order : int
        The least derivative order its tape runs at (1: its contribution reads rates of g).
    doc : str
    """
    tags: tuple
    kind: str
    table: str
    statement: Optional[str]
    doc: str
    usersub: Optional[tuple] = None
    bad: Optional[str] = None
    c: Optional[str] = None
    ints: tuple = ()
    values: int = 0
    order: int = 0

    def field(self, name):
        """The position of int `name` in its layout."""
        return [i.split(":")[0] for i in self.ints].index(name)


_PLAIN = ("id", "time", "par", "npar", "iflag")
_DFLAG = ("id", "time", "par", "npar", "dflag", "iflag")

ELEMENTS = (
    Element(("Reference_Marker",), "marker", "markers", "MARKER", "a frame on a body"),
    Element(("Body_Rigid", "Body_Point"), "body", "bodies", "PART", "a rigid body or point mass"),
    Element(("Force_Penalty",), "penalty", "penalties", "PFORCE",
            "a penalty constraint g(q, t) = 0 or >= 0", ("PFOSUB", _DFLAG, 1),
            c="PS_EL_PENALTY", ints=("g:slot", "f:slot"), values=2, order=1),
    Element(("Force_Scalar_TwoBody",), "sforce", "sforces", "SFORCE",
            "a force along the line of two markers, or a torque", ("SFOSUB", _DFLAG, 1),
            c="PS_EL_SFORCE", ints=("f:slot", "mode:flag", "i:marker", "j:marker"), values=1),
    Element(("Force_SpringDamper",), "springdamper", "springdampers", "SPRINGDAMPER",
            "a translational or rotational spring and damper between two markers (held as "
            "a scalar force: pysolver.deck.springs)"),
    Element(("Force_Bushing",), "bushing", "bushings", "BUSHING",
            "six linear springs and dampers in J's axes between two markers (held as a vector "
            "force: pysolver.deck.vectors)"),
    Element(("Force_Field",), "field", "fields", "FIELD",
            "a linear 6x6 stiffness and damping in J's axes between two markers (held as a "
            "vector force: pysolver.deck.fields)"),
    Element(("Force_Beam",), "beam", "beams", "BEAM",
            "a massless Timoshenko beam along J's x between two markers (held as a vector "
            "force: pysolver.deck.fields)"),
    Element(("Force_Vector_TwoBody", "Force_Vector_OneBody"), "vforce", "vforces", "VFORCE",
            "a force and a torque by their components, between two bodies or on one",
            c="PS_EL_VFORCE",
            ints=("fx:slot", "fy:slot", "fz:slot", "tx:slot", "ty:slot", "tz:slot", "i:marker",
                  "si:bslot", "sj:bslot", "r:marker", "sr:bslot"), values=6),
    Element(("Motion_Marker", "Motion_Joint"), "motion", "motions", "MOTION",
            "a driven displacement, velocity or acceleration",
            ("MOTSUB", ("id", "time", "par", "npar", "iord", "iflag"), 1), c="PS_EL_MOTION",
            ints=("f:slot", "gd:slot", "g:slot", "kind:flag", "lam:state", "w:state",
                  "mu:state"), values=2, order=1),
    Element(("Constraint_Joint", "Constraint_Jprim"), "joint", "joints", "JOINT",
            "a joint: equations that hold two markers' bodies together", c="PS_EL_JOINT",
            ints=("g:slot", "gd:slot", "lam:state", "mu:state"), values=2, order=1),
    Element(("Constraint_General",), "gcon", "gcons", "GCON",
            "an expression of displacements and time held at zero", ("GCOSUB", _DFLAG, 1),
            c="PS_EL_GCON",
            ints=("g:slot", "gd:slot", "lam:state", "mu:state"), values=2, order=1),
    Element(("Constraint_Coupler",), "coupler", "couplers", "COUPLER",
            "a linear relation between the coordinates of two or three joints",
            c="PS_EL_COUPLER", ints=("g:slot", "gd:slot", "lam:state", "mu:state"), values=2,
            order=1),
    Element((), "turn", "turns", None,
            "the tracked angle of a rotation held through any number of turns (a SCREW or "
            "RACK_PINION joint, a coupler's rotation): no deck element of its own",
            c="PS_EL_TURN", ints=("w:slot", "s:state"), values=1),
    Element(("Reference_Spline",), "spline", "splines", "SPLINE",
            "x-y data of a curve for AKISPL, CUBSPL, LINSPL, QUISPL"),
    Element(("Post_Graphic",), "graphic", "graphics", "GRAPHICS",
            "geometry kept for the 3-D view (no effect on the motion)"),
    Element(("LoadControl",), "loadcontrol", "controls", "LOADCONTROL",
            "the LoadControl task (seed 002)"),
    Element(("Reference_Variable",), "variable", "variables", "VARIABLE",
            "a named expression", ("VARSUB", _DFLAG, 1)),
    Element(("Post_Request",), "request", "requests", "REQUEST", "up to 8 output channels",
            ("REQSUB", _PLAIN, 8)),
    Element(("Sensor_Event",), "sensor", "sensors", "SENSOR", "a condition watched, and actions",
            ("SENSUB", _PLAIN, 1), "PS_BAD_SENSOR"),
    Element(("Sensor_Evaluate",), "evaluate", "evaluates", "SENSOR",
            "a value stored when a sensor fires", ("SEVSUB", _PLAIN, 1)),
)
#: Element kinds by XML tag and by kind.
ELEMENT_OF_TAG = {tag: e for e in ELEMENTS for tag in e.tags}
ELEMENT_OF_KIND = {e.kind: e for e in ELEMENTS}
#: The kinds of the kernel's element table, in the order of its PS_EL_* values.
TABLE_KINDS = tuple(e for e in ELEMENTS if e.c)


# joint types -----------------------------------------------------------------------------
#: The equations g(q) = 0 of each Constraint_Joint / Constraint_Jprim type (elements.md 1.2):
#: ("d", axis) a global component of d = oI - oJ, ("dJ", axis) d along an axis of J, ("dot",
#: a, b) axis a of I dotted with axis b of J, ("dot2", a, b) that plus axis b of I with axis a
#: of J; axes 0, 1, 2 are x, y, z. pysolver.deck.joints lowers them.
_X, _Y, _Z = 0, 1, 2
_D = [("d", _X), ("d", _Y), ("d", _Z)]

JOINT_EQUATIONS = {
    "SPHERICAL": _D,
    "ATPOINT": _D,
    "FIXED": _D + [("dot", _X, _Y), ("dot", _Y, _Z), ("dot", _Z, _X)],
    "REVOLUTE": _D + [("dot", _X, _Z), ("dot", _Y, _Z)],
    "TRANSLATIONAL": [("dot", _X, _Z), ("dot", _Y, _Z), ("dot", _X, _Y), ("dJ", _X), ("dJ", _Y)],
    "CYLINDRICAL": [("dot", _X, _Z), ("dot", _Y, _Z), ("dJ", _X), ("dJ", _Y)],
    "PLANAR": [("dot", _X, _Z), ("dot", _Y, _Z), ("dJ", _Z)],
    "UNIVERSAL": _D + [("dot", _Z, _Z)],
    "HOOKE": _D + [("dot", _X, _Y)],
    "CONSTANT_VELOCITY": _D + [("dot2", _X, _Y)],
    "INLINE": [("dJ", _X), ("dJ", _Y)],
    "INPLANE": [("dJ", _Z)],
    "ORIENTATION": [("dot", _X, _Y), ("dot", _Y, _Z), ("dot", _Z, _X)],
    "PARALLEL_AXES": [("dot", _Z, _X), ("dot", _Z, _Y)],
    "PERPENDICULAR": [("dot", _Z, _Z)],
    "FREE": [],
    # d along zJ led by an angle theta = atan2(sign a_I . b_J, c_I . d_J), tracked through
    # every turn: ("lead", a, b, sign, c, d); docs/deck-language.md, "Joints"
    "SCREW": [("lead", _X, _Y, 1.0, _X, _X)],
    "RACK_PINION": [("lead", _Y, _Z, -1.0, _X, _Z)],
}


# the documentation's function table -----------------------------------------------------------
#: Lines around the generated table in docs/deck-language.md.
TABLE_BEGIN = "<!-- functions: generated by python -m pysolver.catalogue docs/deck-language.md -->"
TABLE_END = "<!-- end of functions -->"


def markdown():
    """The Markdown table of every name, operation and function a deck may write."""
    def cell(text):
        return text.replace("|", "\\|")
    lines = ["| expression | reads | gives |", "|---|---|---|"]
    for f in TABLE:
        if f.kind != "internal":
            reads = ", ".join(r for r in READS if r in f.reads)
            lines.append(f"| `{cell(f.usage)}` | {reads} | {cell(f.doc)} |")
    return "\n".join(lines) + "\n"


def splice(text):
    """`text` (a Markdown page) with the part between TABLE_BEGIN and TABLE_END replaced by
    :func:`markdown`."""
    pattern = re.compile(re.escape(TABLE_BEGIN) + r"\n.*?" + re.escape(TABLE_END), re.S)
    if not pattern.search(text):
        raise ValueError("the page has no generated function table")
    return pattern.sub(lambda _: f"{TABLE_BEGIN}\n{markdown()}{TABLE_END}", text)


if __name__ == "__main__":
    # python -m pysolver.catalogue [page.md]: print the table, or rewrite it in the page
    if len(sys.argv) > 1:
        with open(sys.argv[1]) as fh:
            page = fh.read()
        with open(sys.argv[1], "w") as fh:
            fh.write(splice(page))
    else:
        sys.stdout.write(markdown())
