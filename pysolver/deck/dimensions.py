"""Units of the numbers a run reports: request channels typed from their expressions.

A dimension is a vector of exponents over force, length, time, angle in radians and angle in
degrees (F, L, T, A, D). Mass never appears: no function of the expression language measures
a mass, and a kinetic energy is a force times a length. A request channel's dimension comes
from walking its parsed tree: DX is a length, VX a velocity, PFORCE a force, TIME a time;
``+``, ``-``, MAX, MIN, IF and STEP need equal dimensions; ``*`` and ``/`` add and subtract
exponents, ``**`` by a literal scales them. A number written in the deck adopts the dimension
it is added to (``1 + DX(10)`` is a length). In a product, the written numbers (and PI) make
one factor: a plain one (p/q with p, q up to 9; times pi unless the product is an angle)
keeps the unit (``2*DX(10)``, ``0.5*KE(0)``), 180/pi and pi/180 convert radians and degrees
as RTOD and DTOR do (``AZ(10)*180/PI`` is in degrees), and any other (``1000*DX(10)``, a
mass, ``WZ(10)*30/PI``) leaves the channel with no unit, since the number may be a unit
conversion or a constant with units of its own. An expression whose terms do not match
(``DX(10) + VX(10)``), a spline's value and a user subroutine's have no unit. Units are the
deck's ``Units`` (kg, m, s, N when it has none: what the loader assumes); angles are in
radians, as pysolver reports every angle (``RTOD * AZ(i, j)`` is in degrees). docs/usage.md,
"Units".
"""
import math
from collections import namedtuple
from fractions import Fraction

#: A channel's unit (str; "-" dimensionless; None: no unit) and kind of quantity (str or None).
Quantity = namedtuple("Quantity", "unit kind")

#: Unit symbols of the Units element's names.
SYMBOLS = {"METER": "m", "MILLIMETER": "mm", "CENTIMETER": "cm", "KILOMETER": "km",
           "MICROMETER": "um", "NANOMETER": "nm", "ANGSTROM": "angstrom",
           "INCH": "in", "MILS": "mil", "MICROINCH": "uin", "FOOT": "ft", "YARD": "yd",
           "MILE": "mi",
           "SECOND": "s", "MILLISECOND": "ms", "MICROSECOND": "us", "NANOSECOND": "ns",
           "MINUTE": "min", "HOUR": "h", "DAY": "d",
           "NEWTON": "N", "KILONEWTON": "kN", "MEGANEWTON": "MN", "CENTINEWTON": "cN",
           "MILLINEWTON": "mN", "MICRONEWTON": "uN", "NANONEWTON": "nN", "DYNE": "dyn",
           "POUND_FORCE": "lbf", "KPOUND_FORCE": "kip", "KILOGRAM_FORCE": "kgf",
           "OUNCE_FORCE": "ozf", "POUNDAL": "pdl"}

_F, _L, _T, _A, _D = range(5)


def _dim(**exps):
    v = [Fraction(0)] * 5
    for name, e in exps.items():
        v["FLTAD".index(name)] = Fraction(e)
    return tuple(v)


NONE = _dim()
LENGTH, VELOCITY, ACCELERATION = _dim(L=1), _dim(L=1, T=-1), _dim(L=1, T=-2)
ANGLE, ANGULAR_VELOCITY, ANGULAR_ACCELERATION = _dim(A=1), _dim(A=1, T=-1), _dim(A=1, T=-2)
FORCE, TORQUE, TIME = _dim(F=1), _dim(F=1, L=1), _dim(T=1)

#: Kinds of quantity by dimension (F*L: "torque" unless a KE made it an energy).
KINDS = {NONE: "dimensionless", LENGTH: "length", VELOCITY: "velocity",
         ACCELERATION: "acceleration", ANGLE: "angle", ANGULAR_VELOCITY: "angular velocity",
         ANGULAR_ACCELERATION: "angular acceleration", FORCE: "force", TORQUE: "torque",
         TIME: "time", _dim(D=1): "angle", _dim(D=1, T=-1): "angular velocity",
         _dim(D=1, T=-2): "angular acceleration"}


class Dim:
    """A dimension (exponents F, L, T, A, D) with the kind its measure names (``energy``
    for KE, else None); ``number`` marks a literal, which adopts what it is added to, and
    ``value`` its value when it is known (literals, PI and arithmetic of them)."""
    __slots__ = ("exps", "kind", "number", "value")

    def __init__(self, exps, kind=None, number=False, value=None):
        self.exps, self.kind, self.number, self.value = exps, kind, number, value


def _num(value=None):
    return Dim(NONE, number=True, value=value)


def _valued(d):
    """Whether `d` is a written number whose value is known (literals, PI, and sums,
    products and powers of them)."""
    return d is not None and d.number and d.value is not None


_MEASURES = {**dict.fromkeys(("DX", "DY", "DZ", "DM"), LENGTH),
             **dict.fromkeys(("VX", "VY", "VZ", "VM", "VR"), VELOCITY),
             **dict.fromkeys(("ACCX", "ACCY", "ACCZ", "ACCM"), ACCELERATION),
             **dict.fromkeys(("WX", "WY", "WZ", "WM"), ANGULAR_VELOCITY),
             **dict.fromkeys(("WDTX", "WDTY", "WDTZ", "WDTM"), ANGULAR_ACCELERATION),
             **dict.fromkeys(("AX", "AY", "AZ", "AXU", "AYU", "AZU", "PSI", "THETA", "PHI",
                              "YAW", "PITCH", "ROLL", "ACOS", "ASIN", "ATAN", "ATAN2"), ANGLE),
             **dict.fromkeys(("FX", "FY", "FZ", "FM", "PFORCE", "IMPACT", "BISTOP"), FORCE),
             **dict.fromkeys(("TX", "TY", "TZ", "TM"), TORQUE)}
#: Functions whose value is a number whatever their argument's dimension.
_PURE = ("SIN", "COS", "TAN", "SINH", "COSH", "TANH", "EXP", "LOG", "LOG10")
#: Functions whose value has the dimension of their first argument.
_SAME = ("ABS", "AINT", "ANINT", "SIGN")
#: Functions whose arguments must agree: the indices of the ones that do.
_AGREE = {"MAX": (0, 1), "MIN": (0, 1), "MOD": (0, 1), "DIM": (0, 1), "IF": (1, 2, 3),
          "STEP": (2, 4), "STEP5": (2, 4), "HAVSIN": (2, 4)}
#: Reaction and element force functions: comp 1-4 a force, 5-8 a torque.
_ELEMENT_FORCES = ("SFORCE", "SPDP", "BUSH", "FIELD", "BEAM", "JOINT", "MOTION")


def _add(a, b):
    """The dimension of a + b (or MAX(a, b), ...): None unless they agree."""
    if a is None or b is None:
        return None
    if a.number:
        return b
    if b.number:
        return a
    if a.exps != b.exps:
        return None
    return Dim(a.exps, a.kind if a.kind == b.kind else None)


#: 180/pi and pi/180: a written factor within :data:`CLOSE` of either turns radians into
#: degrees or degrees into radians, as RTOD and DTOR do (``AZ(i)*180/PI``, ``57.29578*AZ(i)``).
_RTOD, _DTOR = 180 / math.pi, math.pi / 180
#: How near (relative) a written factor must be to a value above to count as it.
CLOSE = 1e-6
#: Largest numerator and denominator of a plain factor (``2*DX``, ``DX/2``, ``0.5*...``,
#: ``4/3``); other written factors (``1000*DX``, a mass, a stiffness) change the unit.
PLAIN = 9


def _near(x, y):
    return abs(x - y) <= CLOSE * abs(y)


def _plain(c):
    """Whether |c| is p/q with p, q whole numbers 1..PLAIN (or zero)."""
    if c == 0:
        return True
    f = Fraction(c).limit_denominator(PLAIN)
    return 0 < f.numerator <= PLAIN and _near(c, float(f))


def _scale(exps, c):
    """The dimension `exps` (not dimensionless) times the written factor c: the same for a
    plain factor, or one with pi in it (``2*PI*DX``, ``PI*DX**2/4``) unless `exps` is an
    angle (``WZ/(2*PI)`` is in turns); degrees or radians for 180/pi and pi/180; None
    otherwise (no unit: ``1000*DX`` in a metre deck is in mm, ``WZ*30/PI`` in rpm)."""
    c = abs(c)
    if _near(c, _RTOD):
        return tuple(e + d for e, d in zip(exps, _dim(A=-1, D=1)))
    if _near(c, _DTOR):
        return tuple(e + d for e, d in zip(exps, _dim(A=1, D=-1)))
    angle = exps[_A] != 0 or exps[_D] != 0
    if _plain(c) or not angle and (_plain(c / math.pi) or _plain(c * math.pi)):
        return exps
    return None


def _fold(op, a, b):
    """The value of a number a op b (both with values), or None when it has none."""
    try:
        v = {"+": a + b, "-": a - b}[op] if op in "+-" else a ** b
    except (OverflowError, ZeroDivisionError):
        return None
    return v if isinstance(v, float) and math.isfinite(v) else None


class Typer:
    """Types expression trees of one model (Reference_Variables through their expressions)."""

    def __init__(self, model):
        self.model = model
        self._variables = {}

    def of(self, node):
        """The :class:`Dim` of a parsed expression, or None (no unit)."""
        kind = node[0]
        if kind == "num":
            return _num(float(node[1]))
        if kind == "name":
            name = node[1]
            return (Dim(TIME) if name == "TIME" else
                    Dim(_dim(A=1, D=-1)) if name == "DTOR" else
                    Dim(_dim(A=-1, D=1)) if name == "RTOD" else
                    _num(math.pi) if name == "PI" else _num())
        if kind == "neg":
            a = self.of(node[1])
            return _num(-a.value) if _valued(a) else a
        if kind == "bin":
            op = node[1]
            if op in ("*", "/"):
                return self._product(node)
            a, b = self.of(node[2]), self.of(node[3])
            out = _add(a, b) if op in "+-" else self._power(a, b)
            if _valued(a) and _valued(b):
                return _num(_fold(op, a.value, b.value))
            return out
        return self._call(node[1], node[2])

    def _product(self, node):
        """The dimension of a chain of ``*`` and ``/``: its factors' exponents combined, and
        its written numbers multiplied into one factor that keeps, converts (180/pi) or
        drops the unit (:func:`_scale`). A number times dimensionless values stays a number
        (``5 * SIN(TIME)`` is an amplitude of the deck's choosing)."""
        factors, stack = [], [(node, 1)]
        while stack:
            n, sign = stack.pop()
            if n[0] == "bin" and n[1] in ("*", "/"):
                stack += [(n[2], sign), (n[3], sign if n[1] == "*" else -sign)]
            else:
                factors.append((self.of(n), sign))
        if any(d is None for d, _ in factors):
            return None
        coef, numbers, dims = 1.0, [d for d, _ in factors if d.number], []
        for d, sign in factors:
            if d.number and d.value is not None:
                if sign < 0 and d.value == 0:
                    return None
                coef = coef * d.value if sign > 0 else coef / d.value
            elif not d.number:
                dims.append((d, sign))
        if all(d.exps == NONE for d, _ in dims):
            if numbers:
                valued = len(dims) == 0 and all(d.value is not None for d in numbers)
                return _num(coef if valued and math.isfinite(coef) else None)
            return Dim(NONE)
        exps = tuple(sum(sign * d.exps[i] for d, sign in dims) for i in range(5))
        if exps == NONE:
            return Dim(NONE)
        scaled = _scale(exps, coef)
        if scaled is None:
            return None
        shaped = [(d, sign) for d, sign in dims if d.exps != NONE]
        kind = shaped[0][0].kind if len(shaped) == 1 and shaped[0][1] > 0 and \
            scaled == exps else None
        return Dim(scaled, kind)

    @staticmethod
    def _power(a, b):
        if a is None or b is None:
            return None
        if a.number or (a.exps == NONE and b.exps == NONE):
            return _num() if a.number else Dim(NONE)
        if not b.number or b.value is None:
            return None
        p = Fraction(b.value).limit_denominator(1000)
        return Dim(tuple(x * p for x in a.exps))

    def _call(self, name, args):
        if name in _MEASURES:
            return Dim(_MEASURES[name])
        if name == "KE":
            return Dim(TORQUE, "energy")
        if name == "ORIENT":
            return Dim(NONE) if args[0][1] == 27 else Dim(ANGLE)
        if name in _ELEMENT_FORCES:
            if len(args) == 4:
                return Dim(FORCE if args[2][1] <= 4 else TORQUE)
            motion = self.model.motions.get(int(args[0][1]))
            return Dim(TORQUE if motion and motion.direction.startswith("B") else FORCE)
        if name == "VARVAL":
            return self._variable(int(args[0][1]))
        if name == "SENVAL":
            ev = self.model.evaluates.get(int(args[0][1]))
            return self.of(ev.expr) if ev is not None and ev.usersub is None else None
        if name in _PURE:
            arg = self.of(args[0])
            return _num() if arg is not None and arg.number else Dim(NONE)
        if name in _SAME:
            return self.of(args[0])
        if name == "SQRT":
            return self._power(self.of(args[0]), _num(0.5))
        if name in _AGREE:
            out = _num()
            for i in _AGREE[name]:
                out = _add(out, self.of(args[i]))
            return out
        return None                     # splines, and anything not typed above

    def _variable(self, vid):
        if vid not in self._variables:
            self._variables[vid] = None             # a cycle (refused at load) has no unit
            var = self.model.variables.get(vid)
            if var is not None and var.usersub is None:
                self._variables[vid] = self.of(var.expr)
        return self._variables[vid]


def header(name, unit):
    """A column's name with its unit, ``z [mm]`` (CSV headers, DataFrames); the bare name
    when it has none."""
    return f"{name} [{unit}]" if unit else name


def unit_text(exps, units):
    """Print a dimension in a model's units: ``mm/s``, ``N*mm``, ``rad/s^2``, ``1/s``;
    ``-`` when dimensionless."""
    syms = (SYMBOLS[units["force"]], SYMBOLS[units["length"]], SYMBOLS[units["time"]], "rad",
            "deg")

    def part(pairs):
        return "*".join(s if e == 1 else f"{s}^{e}" if e.denominator == 1 else f"{s}^({e})"
                        for s, e in pairs)
    num = [(s, e) for s, e in zip(syms, exps) if e > 0]
    den = [(s, -e) for s, e in zip(syms, exps) if e < 0]
    if not num and not den:
        return "-"
    text = part(num) or "1"
    if den:
        text += "/" + (part(den) if len(den) == 1 else f"({part(den)})")
    return text


def quantity(dim, units):
    """The :class:`Quantity` of a :class:`Dim` (or None: no unit) in a model's units."""
    if dim is None:
        return Quantity(None, None)
    return Quantity(unit_text(dim.exps, units), dim.kind or KINDS.get(dim.exps))


#: Fields of a LoadControl record and their dimensions (pysolver/solve/loadlaw.py: e, Ie and
#: De are displacements; A a load per displacement; clamped a flag, no unit).
CONTROLLER = {"time": TIME, "target": FORCE, "measured": FORCE, "filtered": FORCE,
              "displacement": LENGTH, "A": _dim(F=1, L=-1), "e": LENGTH, "Ie": LENGTH,
              "De": LENGTH, "velocity": VELOCITY, "clamped": None}


def channel_units(model):
    """Units of a model's outputs, worked out once per model.

    Returns
    -------
    dict
        ``(request id, channel index 0..7)`` -> :class:`Quantity` for every channel with an
        expression, ``"time"`` and ``"force"`` -> the time's and the force's (static
        imbalances), ``"controller"`` -> {field: Quantity} of the
        LoadControl records (:data:`CONTROLLER`).
    """
    cached = model.__dict__.get("_channel_units")
    if cached is not None:
        return cached
    typer, units = Typer(model), model.units
    out = {"time": quantity(Dim(TIME), units), "force": quantity(Dim(FORCE), units),
           "controller": {k: quantity(d and Dim(d), units) for k, d in CONTROLLER.items()}}
    for req in model.requests.values():
        for k, tree in enumerate(req.exprs):
            if tree is not None:
                out[(req.id, k)] = quantity(None if req.usersub else typer.of(tree), units)
    model._channel_units = out
    return out


#: Units of a body's coordinates by the name's last part (Euler parameters have none; a
#: planar scene's body turns by rz, an angle).
_BODY_STATES = {**dict.fromkeys(("x", "y", "z"), LENGTH),
                **dict.fromkeys(("vx", "vy", "vz"), VELOCITY),
                **dict.fromkeys(("e0", "e1", "e2", "e3"), NONE), "rz": ANGLE,
                **dict.fromkeys(("wx", "wy", "wz"), ANGULAR_VELOCITY)}


def state_unit(model, name):
    """The unit of state `name` (as ``Result.state_names`` names it) in the model's units:
    bodies' coordinates and velocities, a motion's reaction (a force, a torque for B1..B3)
    and driven velocity, tracked angles (``rad``); None for the multipliers that hold
    constraints at the position level (``position_reaction``) and for a joint equation's
    multiplier, whose unit is the equation's (``res.joint(id)`` gives the reactions)."""
    owner, _, part = name.partition(".")
    dim = None
    if owner.startswith("body"):
        dim = _BODY_STATES.get(part)
    elif owner.startswith("motion") and part in ("reaction", "velocity"):
        turns = model.motions[int(owner[6:])].direction.startswith("B")
        dim = ((TORQUE if turns else FORCE) if part == "reaction" else
               (ANGULAR_VELOCITY if turns else VELOCITY))
    elif part.startswith("angle"):
        dim = ANGLE
    return quantity(None if dim is None else Dim(dim), model.units).unit


def unit_of(model, kind):
    """The unit of a kind of quantity (``"force"``, ``"torque"``, ``"length"``, ...; a key
    of :data:`KINDS`' values) in the model's units."""
    dim = next(d for d, k in KINDS.items() if k == kind)
    return quantity(Dim(dim), model.units).unit
