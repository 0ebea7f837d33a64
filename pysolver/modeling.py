"""The msolve class API: build a model from Python objects, as Altair's msolve does.

Longer than 420 lines because it is an API: one small class per model element (thirty of
them), each a table from its attributes to the Adams statement it stands for.

::

    from pysolver.msolve import *
    model = Model()
    Units(length="MILLIMETER")
    Accgrav(jgrav=-9810)
    ground = Part(ground=True)
    pivot = Marker(body=ground)
    arm = Part(mass=1, ip=[1e3, 1e3, 1e3])
    arm.cm = Marker(body=arm, qp=Point(100, 0, 0))
    Joint(type="REVOLUTE", i=Marker(body=arm), j=pivot)
    Request(type="DISPLACEMENT", i=arm.cm)
    res = model.simulate(type="DYNAMICS", end=1, dtout=0.01, returnResults=True)

Each element registers with the model created last; ids are given in creation order per
kind unless an ``id`` is passed. The model is written as an Adams dataset (``model.adm()``),
which pysolver.deck.adams reads like any other, so placement (markers in their part's frame,
``qp``/``zp``/``xp``/``reuler``/``rm``), checks and messages are the dataset's. A DeckError
names the line of the Python script that created the element.
"""
import inspect
import itertools
import os
import threading

import numpy as np

from .errors import DeckError

__all__ = ["Model", "Units", "Accgrav", "Part", "PointMass", "Marker", "Point", "Vector",
           "Joint", "Jprim", "Gcon", "Coupler", "Motion", "Sforce", "SpringDamper",
           "Bushing", "Vforce", "Vtorque", "Gforce", "Variable", "Spline", "Sensor",
           "Request", "Output", "Integrator", "DaeIntegrator", "Equilibrium", "Graphics"]

_STATE = threading.local()
_COMMANDS = "<simulate commands>"        # the file the commands' errors name, then mapped


def _loading():
    """The recorder of the Python deck pysolver.load is reading, if any."""
    from .deck import msolve
    return getattr(msolve._STATE, "rec", None)


def _current():
    model = getattr(_STATE, "model", None)
    if model is None:
        raise RuntimeError("create a Model() first: msolve elements belong to the model "
                           "created last")
    return model


class Point(np.ndarray):
    """A point (x, y, z); points and vectors add and subtract as arrays."""

    def __new__(cls, x=0.0, y=0.0, z=0.0):
        return np.asarray([x, y, z], float).view(cls)


class Vector(Point):
    """A vector (x, y, z)."""


def _caller():
    """(file, line) of the user's code that created an element."""
    here = os.path.dirname(os.path.abspath(__file__))
    for frame in inspect.stack()[2:]:
        if not os.path.abspath(frame.filename).startswith(here):
            return frame.filename, frame.lineno
    return None, None


class _Element:
    """An element of the model: its Adams statement, its id and its attributes."""
    _statement = ""                # the Adams statement it becomes
    _keys = {}                     # attribute -> Adams keyword (or a function of the value)
    _counter = None

    def __init__(self, id=None, label="", **kw):
        unknown = sorted(set(kw) - set(self._keys) - {"id", "label"})
        file, line = _caller()
        if unknown:
            raise DeckError(f"unknown attribute {unknown[0]!r}; {type(self).__name__} takes "
                            f"{', '.join(sorted(self._keys))}", file=file, line=line,
                            element=type(self).__name__, attribute=unknown[0])
        object.__setattr__(self, "_where", (file, line))
        self.__dict__.update({k: None for k in self._keys})
        self.__dict__.update(kw)
        self.label = label
        self.model = _current()
        self.id = id if id is not None else self.model._next_id(self._kind())
        self.model._add(self)

    @classmethod
    def _kind(cls):
        return cls._statement

    def __setattr__(self, name, value):
        if name not in self._keys and name not in ("id", "label", "model"):
            raise AttributeError(f"{type(self).__name__} has no attribute {name!r}; it takes "
                                 f"{', '.join(sorted(self._keys))}")
        object.__setattr__(self, name, value)

    def _arguments(self):
        """[(Adams keyword, value)] of the statement (value None: a flag)."""
        out = []
        for attr, key in self._keys.items():
            val = getattr(self, attr)
            if val is None or val is False:
                continue
            if callable(key):
                out.extend(key(val))
            elif val is True:
                out.append((key, None))
            else:
                out.append((key, val))
        return out

    def _adm(self):
        """The element's Adams statement lines."""
        lines = [f"! adams_view_name='{self.label}'"] if self.label else []
        head = f"{self._statement}/{self.id}" if self.id is not None else f"{self._statement}/"
        parts = [head]
        for key, val in self._arguments():
            parts.append(key if val is None else f"{key} = {_value(key, val)}")
        lines.append(parts[0] + (", " + parts[1] if len(parts) > 1 else ""))
        lines.extend(", " + p for p in parts[2:])
        return lines


_FUNCTION_KEYS = {"FUNCTION", "FX", "FY", "FZ", "TX", "TY", "TZ", "EVALUATE",
                  *(f"F{k}" for k in range(1, 9))}


def _value(key, val):
    """An attribute value as dataset text."""
    if key in _FUNCTION_KEYS:
        text = str(val)
        if "\\" in text or "\n" in text:
            raise ValueError(f"{key}: a function holds no backslash or line break")
        return text + "\\"
    if isinstance(val, _Element):
        return str(val.id)
    if isinstance(val, str):
        return val
    if isinstance(val, (bool, np.bool_)):
        raise ValueError(f"{key}: {val!r} is not a number")
    arr = np.atleast_1d(np.asarray([v.id if isinstance(v, _Element) else v for v in val]
                                   if isinstance(val, (list, tuple)) else val))
    if arr.dtype.kind not in "iuf":
        return ", ".join(str(v) for v in arr)
    return ", ".join(repr(float(v)) if arr.dtype.kind == "f" else str(int(v))
                     for v in arr.ravel())


def _pair(name):
    return lambda v: [(name, v)]


class Units(_Element):
    """Units: mass, length, time, force (Adams names: KILOGRAM, MILLIMETER, ...) or system
    (MKS, MMKS, CGS, FPS, IPS); SI without arguments."""
    _statement = "UNITS"
    _keys = {"mass": "MASS", "length": "LENGTH", "time": "TIME", "force": "FORCE",
             "system": "SYSTEM"}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.id = None


class Accgrav(_Element):
    """Gravity: igrav, jgrav, kgrav (global x, y, z)."""
    _statement = "ACCGRAV"
    _keys = {"igrav": "IGRAV", "jgrav": "JGRAV", "kgrav": "KGRAV"}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.id = None


class Part(_Element):
    """A rigid body (or ground=True): mass, ip=[ixx, iyy, izz(, ixy, ixz, iyz)], cm (its
    centre-of-mass Marker), im, qg and reuler (its frame in ground; or zg and xg), vx, vy,
    vz, wx, wy, wz, vm, wm."""
    _statement = "PART"
    _keys = {"ground": "GROUND", "mass": "MASS", "cm": "CM", "im": "IM", "ip": "IP",
             "qg": "QG", "reuler": "REULER", "zg": "ZG", "xg": "XG", "vx": "VX", "vy": "VY",
             "vz": "VZ", "wx": "WX", "wy": "WY", "wz": "WZ", "vm": "VM", "wm": "WM"}


class PointMass(_Element):
    """A point mass: mass, cm, qg, vx, vy, vz."""
    _statement = "POINT_MASS"
    _keys = {"mass": "MASS", "cm": "CM", "qg": "QG", "vx": "VX", "vy": "VY", "vz": "VZ"}


class Marker(_Element):
    """A marker on `body` (or `part`): qp, and reuler or zp and xp (usexp), in its part's
    frame or in rm's; floating=True for a floating marker."""
    _statement = "MARKER"
    _keys = {"body": "PART", "part": "PART", "qp": "QP", "reuler": "REULER", "zp": "ZP",
             "xp": "XP", "usexp": "USEXP", "rm": "RM", "floating": "FLOATING"}

    def _arguments(self):
        out = super()._arguments()
        if isinstance(self.body or self.part, PointMass):
            out = [("POINT_MASS", v) if k == "PART" else (k, v) for k, v in out]
        return out


_JPRIMS = ("ATPOINT", "INLINE", "INPLANE", "ORIENTATION", "PARALLEL_AXES", "PERPENDICULAR")
_ADAMS_JOINT = {"CONSTANT_VELOCITY": "CONVEL", "RACK_PINION": "RACKPIN"}


class Joint(_Element):
    """A joint: type (REVOLUTE, TRANSLATIONAL, SPHERICAL, CYLINDRICAL, UNIVERSAL, HOOKE,
    FIXED, PLANAR, CONSTANT_VELOCITY, SCREW, RACK_PINION), i, j, pitch, pd."""
    _statement = "JOINT"
    _keys = {"type": lambda v: [(_ADAMS_JOINT.get(str(v).upper(), str(v).upper()), None)],
             "i": "I", "j": "J", "pitch": "PITCH", "pd": "PD"}

    def _adm(self):
        # MotionSolve's joint types include the primitives: Adams writes them as JPRIM
        if str(self.type).upper() in _JPRIMS:
            return [ln.replace(f"JOINT/{self.id}", f"JPRIM/{self.id}", 1)
                    for ln in super()._adm()]
        return super()._adm()


class Jprim(_Element):
    """A joint primitive: type (ATPOINT, INLINE, INPLANE, ORIENTATION, PARALLEL_AXES,
    PERPENDICULAR), i, j."""
    _statement = "JPRIM"
    _keys = {"type": lambda v: [(str(v).upper(), None)], "i": "I", "j": "J"}


class Gcon(_Element):
    """A general constraint: function (held at zero), i."""
    _statement = "GCON"
    _keys = {"function": "FUNCTION", "i": "I"}


class Coupler(_Element):
    """A coupler: joints (two or three Joints), type (["R", "T", ...] or "R:T"), scales."""
    _statement = "COUPLER"
    _keys = {"joints": "JOINTS", "scales": "SCALES",
             "type": lambda v: [("TYPE", v if isinstance(v, str) else ":".join(v))]}


class Motion(_Element):
    """A motion: on a joint (joint, jtype TRANSLATION or ROTATION) or of marker i relative
    to j (direction X, Y, Z, B1, B2, B3); dtype DISPLACEMENT, VELOCITY, ACCELERATION;
    function, icdisp, icvel."""
    _statement = "MOTION"
    _keys = {"joint": "JOINT", "i": "I", "j": "J",
             "jtype": lambda v: [(str(v).upper(), None)],
             "direction": lambda v: [(str(v).upper(), None)],
             "dtype": lambda v: [(str(v).upper(), None)],
             "function": "FUNCTION", "icdisp": "ICDISP", "icvel": "ICVEL"}


class Sforce(_Element):
    """A scalar force: type TRANSLATION or ROTATION, i, j, actiononly, function."""
    _statement = "SFORCE"
    _keys = {"type": lambda v: [(str(v).upper(), None)], "i": "I", "j": "J",
             "actiononly": "ACTIONONLY", "function": "FUNCTION"}


class SpringDamper(_Element):
    """A spring-damper: type TRANSLATION (k, c, length, force) or ROTATION (kt, ct, angle,
    torque), i, j."""
    _statement = "SPRINGDAMPER"
    _keys = {"type": lambda v: [(str(v).upper(), None)], "i": "I", "j": "J", "k": "K",
             "c": "C", "length": "LENGTH", "force": "FORCE", "kt": "KT", "ct": "CT",
             "angle": "ANGLE", "torque": "TORQUE"}


class Bushing(_Element):
    """A bushing: i, j, k, c, kt, ct, force, torque (three numbers each, in j's axes)."""
    _statement = "BUSHING"
    _keys = {"i": "I", "j": "J", "k": "K", "c": "C", "kt": "KT", "ct": "CT",
             "force": "FORCE", "torque": "TORQUE"}


class Vforce(_Element):
    """A vector force: i, jfloat, rm, fx, fy, fz."""
    _statement = "VFORCE"
    _keys = {"i": "I", "jfloat": "JFLOAT", "rm": "RM", "fx": "FX", "fy": "FY", "fz": "FZ"}


class Vtorque(_Element):
    """A vector torque: i, jfloat, rm, tx, ty, tz."""
    _statement = "VTORQUE"
    _keys = {"i": "I", "jfloat": "JFLOAT", "rm": "RM", "tx": "TX", "ty": "TY", "tz": "TZ"}


class Gforce(_Element):
    """A force and torque: i, jfloat, rm, fx, fy, fz, tx, ty, tz."""
    _statement = "GFORCE"
    _keys = {"i": "I", "jfloat": "JFLOAT", "rm": "RM", "fx": "FX", "fy": "FY", "fz": "FZ",
             "tx": "TX", "ty": "TY", "tz": "TZ"}


class Variable(_Element):
    """A variable read with VARVAL(id): function, ic."""
    _statement = "VARIABLE"
    _keys = {"function": "FUNCTION", "ic": "IC"}


class Spline(_Element):
    """Spline data: x, y (a surface: z, and y one curve per z value), linear_extrapolate."""
    _statement = "SPLINE"
    _keys = {"x": "X", "y": "Y", "z": "Z", "linear_extrapolate": "LINEAR_EXTRAPOLATE"}

    def _arguments(self):
        out = [("X", self.x)]
        if self.z is None:
            out.append(("Y", self.y))
        else:
            ys = np.asarray(self.y, float).reshape(len(self.z), -1)
            out.extend(("Y", [z, *row]) for z, row in zip(self.z, ys))
        return out + ([("LINEAR_EXTRAPOLATE", None)] if self.linear_extrapolate else [])


class Sensor(_Element):
    """An event sensor: function, value, error, compare (GE, EQ, LE), halt, print, restart,
    return_, stepsize, evaluate."""
    _statement = "SENSOR"
    _keys = {"function": "FUNCTION", "value": "VALUE", "error": "ERROR",
             "compare": lambda v: [(str(v).upper(), None)], "halt": "HALT",
             "print": "PRINT", "restart": "RESTART", "return_": "RETURN",
             "stepsize": "STEPSIZE", "evaluate": "EVALUATE"}


class Request(_Element):
    """An output request: type DISPLACEMENT, VELOCITY, ACCELERATION or FORCE with i, j, rm;
    or f1..f8 (expressions); comment."""
    _statement = "REQUEST"
    _keys = {"type": lambda v: [] if str(v).upper() == "EXPRESSION" else
             [(str(v).upper(), None)], "i": "I", "j": "J", "rm": "RM", "comment": "COMMENT",
             **{f"f{k}": f"F{k}" for k in range(1, 9)}}


class Graphics(_Element):
    """Geometry kept for the 3-D view: type (CYLINDER, BOX, SPHERE, ...), cm, length,
    radius, corner, x, y, z."""
    _statement = "GRAPHICS"
    _keys = {"type": lambda v: [(str(v).upper(), None)], "cm": "CM", "length": "LENGTH",
             "radius": "RADIUS", "corner": "CORNER", "x": "X", "y": "Y", "z": "Z"}


class Output(_Element):
    """Output settings (reqsave, grsave): accepted, not used (pysolver writes its own)."""
    _statement = "OUTPUT"
    _keys = {"reqsave": "REQSAVE", "grsave": "GRSAVE"}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.id = None


class Integrator(_Element):
    """Integrator settings: type (DSTIFF, GSTIFF, ...: pysolver integrates with IDA's BDF),
    error, hmax, hmin, hinit."""
    _statement = "INTEGRATOR"
    _keys = {"type": lambda v: [], "error": "ERROR", "hmax": "HMAX", "hmin": "HMIN",
             "hinit": "HINIT"}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.id = None


DaeIntegrator = Integrator


class Equilibrium(_Element):
    """Static settings: error, imbalance, maxit, stability."""
    _statement = "EQUILIBRIUM"
    _keys = {"error": "ERROR", "imbalance": "IMBALANCE", "maxit": "MAXIT",
             "stability": "STABILITY"}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.id = None


_ANALYSES = {"DYNAMICS": "DYNAMICS", "TRANSIENT": "DYNAMICS", "KINEMATICS": "KINEMATICS",
             "STATICS": "STATICS", "STATIC": "STATICS", "ASSEMBLY": "INITIAL_CONDITIONS"}


class Model:
    """A model: the container every element created after it joins.

    Parameters
    ----------
    output : str, optional
        The output name (kept as ``model.output``; pysolver writes no files unless told).
    """

    def __init__(self, output=None):
        self.output = output
        self.entities = []          # the elements, in the order they were created
        self.commands = []
        self._ids = {}
        self._where = _caller()
        _STATE.model = self
        rec = _loading()
        if rec is not None:
            rec.models.append(self)

    def _next_id(self, kind):
        counter = self._ids.setdefault(kind, itertools.count(1))
        taken = {e.id for e in self.entities if e._kind() == kind}
        while True:
            i = next(counter)
            if i not in taken:
                return i

    def _add(self, element):
        self.entities.append(element)

    def adm(self):
        """The model as an Adams dataset (text), its commands after END as a command file
        would give them (pysolver.deck.adams)."""
        from .deck.adams import COMMANDS_MARK
        lines, self._lines = ["pysolver msolve model"], {}
        for el in self.entities:
            try:
                text = el._adm()
            except ValueError as err:
                raise DeckError(str(err), file=el._where[0], line=el._where[1],
                                element=type(el).__name__, id=el.id) from None
            for _ in text:
                self._lines[len(lines) + 1] = el._where
                lines.append(_)
        lines.append("END")
        if self.commands:
            lines.append(f"{COMMANDS_MARK} {_COMMANDS}")
            for k, (cmd, where) in enumerate(self.commands):
                self._lines[(_COMMANDS, 3 + k)] = where     # a command file's lines from 3
                lines.append(cmd)
        return "\n".join(lines) + "\n"

    def load(self):
        """The pysolver Model of this model and its simulate commands so far."""
        from .deck.loader import loads
        return self._mapped(lambda text: loads(text, fmt="adm", file=self._file()))

    def elements(self):
        """The deck elements of this model (what a deck file is read into)."""
        from .deck.adams import read_elements
        return self._mapped(lambda text: read_elements(text, self._file()))

    def _file(self):
        return self._where[0] or "<msolve model>"

    def _mapped(self, build):
        """build(dataset text), its DeckError located at the Python line of the element."""
        text = self.adm()
        try:
            return build(text)
        except DeckError as err:
            where = self._lines.get((_COMMANDS, err.line) if err.file == _COMMANDS
                                    else err.line)
            if where is None:
                raise
            raise DeckError(err.reason, file=where[0], line=where[1], element=err.element,
                            attribute=err.attribute) from None

    def simulate(self, type="DYNAMICS", end=None, dtout=None, steps=None, duration=None,
                 returnResults=True, **options):
        """Add a simulation command and run every command so far from the start.

        Parameters
        ----------
        type : {"DYNAMICS", "TRANSIENT", "KINEMATICS", "STATICS", "ASSEMBLY"}
        end, duration : float
            The end time (or the duration after the previous command's end).
        dtout, steps : float, int
            The output interval, or the number of output steps.
        returnResults : bool
            Return the Result (else None).
        **options
            Run options (``integr_tol=``, ``kernel=``, ...: :meth:`pysolver.Model.run`).

        Returns
        -------
        pysolver.Result or None
            The whole run, every command so far. When pysolver.load reads a script, the
            command is recorded and nothing runs (None).
        """
        kind = _ANALYSES.get(str(type).upper())
        file, line = _caller()
        if kind is None:
            raise DeckError(f"unknown simulate type {type!r}; expected "
                            f"{', '.join(_ANALYSES)}", file=file, line=line,
                            element="simulate", attribute="type")
        args = [f"SIMULATE/{kind}"]
        for key, val in (("END", end), ("DURATION", duration), ("DTOUT", dtout),
                         ("STEPS", steps)):
            if val is not None:
                args.append(f"{key} = {val!r}")
        self.commands.append((", ".join(args), (file, line)))
        if _loading() is not None:
            return None
        res = self.load().run(**options)
        return res if returnResults else None
