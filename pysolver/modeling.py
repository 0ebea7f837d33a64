"""The msolve class API: build a model from Python objects, as Altair's msolve does.

Longer than 420 lines because it is an API: one small class per model element (forty
of them), each a table from its attributes to the Adams statement it stands for.

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
names the line of the Python script that created the element (a command's: its simulate()
call), the checks after the dataset reader's included. Each class's ``_keys`` maps an
attribute to its Adams keyword, or, for an attribute written as a flag (``type="REVOLUTE"``
is the flag ``REVOLUTE``), to the table of its values and flags; pysolver/convert.py reads
the same tables to write a deck as a script of these classes.
"""
import itertools
import os
import sys
import threading

import numpy as np

from .deck.adams_writer import SHAPES, Function, Raw, Statement, statement_lines, view_name
from .errors import DeckError

__all__ = ["Model", "Units", "Accgrav", "Part", "PointMass", "Marker", "Point", "Vector",
           "Joint", "Jprim", "Gcon", "Coupler", "Motion", "Sforce", "SpringDamper",
           "Bushing", "Vforce", "Vtorque", "Gforce", "Variable", "Spline", "Sensor",
           "SensorEvaluate", "Request", "Output", "Integrator", "DaeIntegrator", "Equilibrium",
           "Graphics", "Sphere", "Box", "Cylinder", "Frustum", "Ellipsoid", "Pforce",
           "LoadControl", "ResOutput", "H3DOutput"]

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


_HERE = os.path.dirname(os.path.abspath(__file__))


def _caller():
    """(file, line) of the user's code that created an element (the first frame outside
    pysolver)."""
    frame = sys._getframe(2)
    while frame is not None:
        if not os.path.abspath(frame.f_code.co_filename).startswith(_HERE):
            return frame.f_code.co_filename, frame.f_lineno
        frame = frame.f_back
    return None, None


def _choices(*names, **aliases):
    """An attribute written as a flag: {value: FLAG} for each name (its own flag) and alias
    (value=FLAG; None writes nothing)."""
    return {**{n: n for n in names}, **aliases}


#: Keywords whose value is an expression (written up to a backslash).
_FUNCTION_KEYS = {"FUNCTION", "FX", "FY", "FZ", "TX", "TY", "TZ", "EVALUATE", "LOAD_FUNCTION",
                  *(f"F{k}" for k in range(1, 9))}


class _Element:
    """An element of the model: its Adams statement, its id and its attributes."""
    _statement = ""                # the Adams statement it becomes
    _keys = {}                     # attribute -> Adams keyword, or {value: flag}
    _also = {}                     # keywords read back into an attribute (convert.py)
    _numbered = True               # has an id
    _any = False                   # takes any keyword (kept as written)

    def __init__(self, id=None, label="", **kw):
        unknown = sorted(set(kw) - set(self._keys)) if not self._any else []
        file, line = _caller()
        if unknown:
            raise DeckError(f"unknown attribute {unknown[0]!r}; {type(self).__name__} takes "
                            f"{', '.join(sorted(self._keys))}", file=file, line=line,
                            element=type(self).__name__, attribute=unknown[0])
        object.__setattr__(self, "_where", (file, line))
        object.__setattr__(self, "_extra", {})
        self.__dict__.update({k: None for k in self._keys})
        for key, value in kw.items():
            setattr(self, key, value)
        self.label = label
        self.model = _current()
        self.id = None if not self._numbered else \
            id if id is not None else self.model._next_id(self._kind())
        self.model._add(self)

    @classmethod
    def _kind(cls):
        return cls._statement

    def __setattr__(self, name, value):
        if self._any and name not in self._keys and name not in ("id", "label", "model"):
            self._extra[name] = value
            return
        if name not in self._keys and name not in ("id", "label", "model"):
            raise AttributeError(f"{type(self).__name__} has no attribute {name!r}; it takes "
                                 f"{', '.join(sorted(self._keys))}")
        object.__setattr__(self, name, value)

    def __getattr__(self, name):
        extra = self.__dict__.get("_extra") or {}
        if name in extra:
            return extra[name]
        raise AttributeError(name)

    def _arguments(self):
        """[(Adams keyword, value)] of the statement (value None: a flag)."""
        out = []
        for attr, key in self._keys.items():
            val = getattr(self, attr)
            if val is None or val is False:
                continue
            if isinstance(key, dict):
                flag = key.get(str(val).upper(), "")
                if flag == "":
                    raise ValueError(f"{attr}={val!r}; expected one of "
                                     f"{', '.join(v for v in key if key[v] is not None)}")
                if flag is not None:
                    out.append((flag, None))
            elif val is True:
                out.append((key, None))
            else:
                out.append((key, _plain(key, val)))
        out += [(k.upper(), _plain(k.upper(), v)) for k, v in self._extra.items()
                if v is not None]
        if self._any:               # kept as written: the text of each value
            out = [(k, v if v is None or isinstance(v, (list, Function)) else Raw(v))
                   for k, v in out]
        return out

    def _adm(self):
        """The element's Adams statement lines."""
        st = Statement(self._statement, self.id, self._arguments(), str(self.label or ""))
        return ([view_name(st)] if st.label else []) + statement_lines(st)


def _plain(key, val):
    """An attribute value as the statement writer takes it: elements as their ids, points
    as lists, expressions as Function."""
    if key in _FUNCTION_KEYS:
        text = str(val)
        if "\\" in text or "\n" in text:
            raise ValueError(f"{key}: a function holds no backslash or line break")
        return Function(text)
    if isinstance(val, _Element):
        return val.id
    if callable(val):
        raise ValueError(f"{key}: a routine given as a Python function is not taken yet; "
                         "name it in a script (script=, routine=\"name\")")
    if isinstance(val, (bool, np.bool_)):
        raise ValueError(f"{key}: {val!r} is not a number")
    if isinstance(val, (list, tuple, np.ndarray)):
        return [_plain("", v) for v in (val.tolist() if isinstance(val, np.ndarray) else val)]
    if isinstance(val, np.generic):
        return val.item()
    return val


class _Settings(_Element):
    """An element with no id (UNITS/, ACCGRAV/, INTEGRATOR/, ...)."""
    _numbered = False


class Units(_Settings):
    """Units: mass, length, time, force (Adams names: KILOGRAM, MILLIMETER, ...) or system
    (MKS, MMKS, CGS, FPS, IPS); SI without arguments."""
    _statement = "UNITS"
    _keys = {"force": "FORCE", "mass": "MASS", "length": "LENGTH", "time": "TIME",
             "system": "SYSTEM"}


class Accgrav(_Settings):
    """Gravity: igrav, jgrav, kgrav (global x, y, z)."""
    _statement = "ACCGRAV"
    _keys = {"igrav": "IGRAV", "jgrav": "JGRAV", "kgrav": "KGRAV"}


class Part(_Element):
    """A rigid body (or ground=True): mass, ip=[ixx, iyy, izz(, ixy, ixz, iyz)], cm (its
    centre-of-mass Marker), im, qg and reuler (its frame in ground; or zg and xg), vx, vy,
    vz (along the global axes, or vm's), wx, wy, wz (along the cm marker's axes, or wm's),
    vm, wm; lprf (pysolver: MotionSolve's lprf_id, kept)."""
    _statement = "PART"
    _keys = {"ground": "GROUND", "mass": "MASS", "cm": "CM", "im": "IM", "lprf": "LPRF",
             "ip": "IP", "qg": "QG", "reuler": "REULER", "zg": "ZG", "xg": "XG", "vx": "VX",
             "vy": "VY", "vz": "VZ", "wx": "WX", "wy": "WY", "wz": "WZ", "vm": "VM",
             "wm": "WM"}


class PointMass(_Element):
    """A point mass: mass, cm, qg, vx, vy, vz, vm (pysolver: the marker whose axes vx, vy,
    vz are along)."""
    _statement = "POINT_MASS"
    _keys = {"mass": "MASS", "cm": "CM", "qg": "QG", "vx": "VX", "vy": "VY", "vz": "VZ",
             "vm": "VM"}

    @classmethod
    def _kind(cls):
        return "PART"               # parts and point masses share pysolver's body ids


class Marker(_Element):
    """A marker on `body` (or `part`): qp, and reuler or zp and xp (usexp), in its part's
    frame or in rm's; floating=True for a floating marker; pysolver's ypr (3-2-1 angles),
    ep (Euler parameters) and axes (the nine numbers of the columns x, y, z)."""
    _statement = "MARKER"
    _keys = {"body": "PART", "part": "PART", "qp": "QP", "reuler": "REULER", "zp": "ZP",
             "xp": "XP", "usexp": "USEXP", "ypr": "YPR", "ep": "EP", "axes": "AXES",
             "rm": "RM", "floating": "FLOATING"}
    _also = {"POINT_MASS": "body"}

    def _arguments(self):
        out = super()._arguments()
        if isinstance(self.body or self.part, PointMass):
            out = [("POINT_MASS", v) if k == "PART" else (k, v) for k, v in out]
        return out


_JPRIMS = ("ATPOINT", "INLINE", "INPLANE", "ORIENTATION", "PARALLEL_AXES", "PERPENDICULAR")
_JOINTS = _choices("REVOLUTE", "TRANSLATIONAL", "SPHERICAL", "CYLINDRICAL", "UNIVERSAL",
                   "HOOKE", "FIXED", "PLANAR", "SCREW", "FREE", *_JPRIMS,
                   CONSTANT_VELOCITY="CONVEL", CONVEL="CONVEL", RACK_PINION="RACKPIN",
                   RACKPIN="RACKPIN")


class Joint(_Element):
    """A joint: type (REVOLUTE, TRANSLATIONAL, SPHERICAL, CYLINDRICAL, UNIVERSAL, HOOKE,
    FIXED, PLANAR, CONSTANT_VELOCITY, SCREW, RACK_PINION, the primitives; pysolver's FREE),
    i, j, pitch, pd, virtual."""
    _statement = "JOINT"
    _keys = {"type": _JOINTS, "i": "I", "j": "J", "pitch": "PITCH", "pd": "PD",
             "virtual": "VIRTUAL"}

    def _adm(self):
        # MotionSolve's joint types include the primitives: Adams writes them as JPRIM
        if str(self.type).upper() in _JPRIMS:
            return [ln.replace(f"JOINT/{self.id}", f"JPRIM/{self.id}", 1)
                    for ln in super()._adm()]
        return super()._adm()


class Jprim(_Element):
    """A joint primitive: type (ATPOINT, INLINE, INPLANE, ORIENTATION, PARALLEL_AXES,
    PERPENDICULAR), i, j, virtual."""
    _statement = "JPRIM"
    _keys = {"type": _choices(*_JPRIMS), "i": "I", "j": "J", "virtual": "VIRTUAL"}

    @classmethod
    def _kind(cls):
        return "JOINT"              # joints and primitives share pysolver's joint ids


_SUB = {"routine": "ROUTINE", "script": "SCRIPT", "interpreter": "INTERPRETER"}


class Gcon(_Element):
    """A general constraint: function (held at zero), i, virtual; routine, script,
    interpreter (a GCOSUB: function="USER(...)")."""
    _statement = "GCON"
    _keys = {"function": "FUNCTION", "i": "I", "virtual": "VIRTUAL", **_SUB}


class Coupler(_Element):
    """A coupler: joints (two or three Joints), type (["R", "T", ...] or "R:T"), scales,
    virtual."""
    _statement = "COUPLER"
    _keys = {"joints": "JOINTS", "type": "TYPE", "scales": "SCALES", "virtual": "VIRTUAL"}


_TR = _choices("TRANSLATION", "ROTATION", TRANSLATIONAL="TRANSLATION", ROTATIONAL="ROTATION",
               T="TRANSLATION", R="ROTATION")


class Motion(_Element):
    """A motion: on a joint (joint, jtype TRANSLATION or ROTATION) or of marker i relative
    to j (direction X, Y, Z, B1, B2, B3); dtype DISPLACEMENT, VELOCITY, ACCELERATION;
    function, icdisp, icvel; routine, script, interpreter (a MOTSUB)."""
    _statement = "MOTION"
    _keys = {"joint": "JOINT", "i": "I", "j": "J", "jtype": _TR,
             "direction": _choices("X", "Y", "Z", "B1", "B2", "B3"),
             "dtype": _choices("DISPLACEMENT", "VELOCITY", "ACCELERATION", D="DISPLACEMENT",
                               V="VELOCITY", A="ACCELERATION"),
             "function": "FUNCTION", "icdisp": "ICDISP", "icvel": "ICVEL", **_SUB}


class Sforce(_Element):
    """A scalar force: type TRANSLATION or ROTATION, i, j, actiononly, function; routine,
    script, interpreter (an SFOSUB)."""
    _statement = "SFORCE"
    _keys = {"type": _TR, "i": "I", "j": "J", "actiononly": "ACTIONONLY",
             "function": "FUNCTION", **_SUB}


class SpringDamper(_Element):
    """A spring-damper: type TRANSLATION (k, c, length, force) or ROTATION (kt, ct, angle,
    torque), i, j."""
    _statement = "SPRINGDAMPER"
    _keys = {"type": _TR, "i": "I", "j": "J", "k": "K", "c": "C", "length": "LENGTH",
             "force": "FORCE", "kt": "KT", "ct": "CT", "angle": "ANGLE", "torque": "TORQUE"}


class Bushing(_Element):
    """A bushing: i, j, k, c, kt, ct, force, torque (three numbers each, in j's axes)."""
    _statement = "BUSHING"
    _keys = {"i": "I", "j": "J", "k": "K", "c": "C", "kt": "KT", "ct": "CT",
             "force": "FORCE", "torque": "TORQUE"}


class Vforce(_Element):
    """A vector force: i, jfloat, rm, fx, fy, fz; actiononly=True (pysolver: no jfloat, on
    i's body alone)."""
    _statement = "VFORCE"
    _keys = {"i": "I", "jfloat": "JFLOAT", "rm": "RM", "fx": "FX", "fy": "FY", "fz": "FZ",
             "actiononly": "ACTIONONLY"}


class Vtorque(_Element):
    """A vector torque: i, jfloat, rm, tx, ty, tz; actiononly."""
    _statement = "VTORQUE"
    _keys = {"i": "I", "jfloat": "JFLOAT", "rm": "RM", "tx": "TX", "ty": "TY", "tz": "TZ",
             "actiononly": "ACTIONONLY"}

    @classmethod
    def _kind(cls):
        return "VFORCE"


class Gforce(_Element):
    """A force and torque: i, jfloat, rm, fx, fy, fz, tx, ty, tz; actiononly."""
    _statement = "GFORCE"
    _keys = {"i": "I", "jfloat": "JFLOAT", "rm": "RM", "fx": "FX", "fy": "FY", "fz": "FZ",
             "tx": "TX", "ty": "TY", "tz": "TZ", "actiononly": "ACTIONONLY"}

    @classmethod
    def _kind(cls):
        return "VFORCE"


class Variable(_Element):
    """A variable read with VARVAL(id): function, ic; routine, script, interpreter (a
    VARSUB)."""
    _statement = "VARIABLE"
    _keys = {"function": "FUNCTION", "ic": "IC", **_SUB}


class Spline(_Element):
    """Spline data: x, y (a surface: z, and y one curve per z value), linear_extrapolate."""
    _statement = "SPLINE"
    _keys = {"x": "X", "y": "Y", "z": "Z", "linear_extrapolate": "LINEAR_EXTRAPOLATE"}

    def _arguments(self):
        out = [("X", _plain("X", self.x))]
        if self.z is None:
            out.append(("Y", _plain("Y", self.y)))
        else:
            ys = np.asarray(self.y, float).reshape(len(self.z), -1)
            out.extend(("Y", [float(z), *row]) for z, row in zip(self.z, ys.tolist()))
        return out + ([("LINEAR_EXTRAPOLATE", None)] if self.linear_extrapolate else [])


_COMPARE = _choices("GE", "EQ", "LE", LT="LE")


class Sensor(_Element):
    """An event sensor: function, value, error, operator (GE, EQ, LE; compare= too), halt,
    print_ (print= too), restart, return_, stepsize, dt, hmax, zero_crossing, evaluate (an
    expression SENVAL(id) reads), routine, script, interpreter (a SENSUB); pysolver's
    verbose and evaluate_id (a SensorEvaluate instead of evaluate)."""
    _statement = "SENSOR"
    _keys = {"function": "FUNCTION", "value": "VALUE", "error": "ERROR",
             "operator": _COMPARE, "compare": _COMPARE, "halt": "HALT", "print_": "PRINT",
             "print": "PRINT", "restart": "RESTART", "return_": "RETURN",
             "stepsize": "STEPSIZE", "dt": "DT", "hmax": "HMAX",
             "zero_crossing": "ZERO_CROSSING", "verbose": "VERBOSE", "evaluate": "EVALUATE",
             "evaluate_id": "EVALUATE_ID", **_SUB}


class SensorEvaluate(_Element):
    """pysolver: a Sensor_Evaluate of its own (a Sensor's evaluate= makes one with the
    sensor's id): function, routine, script, interpreter (a SEVSUB); a Sensor names it with
    evaluate_id."""
    _statement = "SENSOR_EVALUATE"
    _keys = {"function": "FUNCTION", **_SUB}


class Request(_Element):
    """An output request: type DISPLACEMENT, VELOCITY, ACCELERATION or FORCE with i, j, rm;
    or f1..f8 (expressions), or function="USER(...)" with routine, script, interpreter (a
    REQSUB); comment; cnames (the channels' names)."""
    _statement = "REQUEST"
    _keys = {"type": _choices("DISPLACEMENT", "VELOCITY", "ACCELERATION", "FORCE",
                              EXPRESSION=None, USERSUB=None,
                              MARKER_DISPLACEMENT="DISPLACEMENT",
                              MARKER_VELOCITY="VELOCITY", MARKER_ACCELERATION="ACCELERATION",
                              MARKER_FORCE="FORCE"),
             "i": "I", "j": "J", "rm": "RM", **{f"f{k}": f"F{k}" for k in range(1, 9)},
             "function": "FUNCTION", "comment": "COMMENT", "cnames": "CNAMES", **_SUB}


class Graphics(_Element):
    """Geometry kept for the 3-D view: type (Adams' CYLINDER, BOX, SPHERE, ... or
    MotionSolve's Post_Graphic types) and any other attribute (cm, length, radius, ...),
    kept as written."""
    _statement = "GRAPHICS"
    _keys = {"type": "TYPE"}
    _any = True

    def _arguments(self):
        out = super()._arguments()
        kind = str(self.type or "OUTLINE")
        if kind in SHAPES:          # Adams' shape flag; MotionSolve's types as TYPE=
            out = [(kind, None) if k == "TYPE" else (k, v) for k, v in out]
        return out


class _Shape(Graphics):
    """A Graphics of one shape (msolve's shape classes): its attributes are the Adams
    GRAPHICS keywords of that shape, kept as written like any Graphics'."""
    _shape = ""

    def __init__(self, id=None, label="", **kw):
        if "type" in kw:
            file, line = _caller()
            raise DeckError(f"{type(self).__name__} is a {self._shape} (type is not taken; "
                            "Graphics(type=...) draws another shape)", file=file, line=line,
                            element=type(self).__name__, attribute="type")
        super().__init__(id, label, type=self._shape, **kw)


class Sphere(_Shape):
    """A sphere drawn in the 3-D view: cm (the Marker at its centre), radius."""
    _shape = "SPHERE"


class Box(_Shape):
    """A box drawn in the 3-D view: corner (the Marker at a corner), x, y, z (its sides
    along the marker's axes)."""
    _shape = "BOX"


class Cylinder(_Shape):
    """A cylinder drawn in the 3-D view: cm (the Marker at the centre of one end), radius,
    length (along the marker's z)."""
    _shape = "CYLINDER"


class Frustum(_Shape):
    """A cone frustum drawn in the 3-D view: cm (the Marker at the centre of its bottom),
    bottom and top (radii), length (along the marker's z)."""
    _shape = "FRUSTUM"


class Ellipsoid(_Shape):
    """An ellipsoid drawn in the 3-D view: cm (the Marker at its centre), xscale, yscale,
    zscale (its diameters along the marker's axes)."""
    _shape = "ELLIPSOID"


class ResOutput(_Settings):
    """pysolver: MotionSolve's ResOutput settings, any attribute, kept (not used)."""
    _statement = "RESOUTPUT"
    _any = True


class H3DOutput(_Settings):
    """pysolver: MotionSolve's H3DOutput settings, any attribute, kept (not used)."""
    _statement = "H3DOUTPUT"
    _any = True


class Output(_Settings):
    """Output settings (reqsave, grsave): accepted, not used (pysolver writes its own)."""
    _statement = "OUTPUT"
    _keys = {"reqsave": "REQSAVE", "grsave": "GRSAVE"}


class Integrator(_Settings):
    """Integrator settings: type (DSTIFF, GSTIFF, ...: pysolver integrates with IDA's BDF),
    error, hmax, hmin, hinit; pysolver's max_num_steps, max_step_growth, nonlin_conv_coef,
    dae_constr_tol."""
    _statement = "INTEGRATOR"
    _keys = {"type": _choices("IDA", "DSTIFF", "VSTIFF", "MSTIFF", "GSTIFF", "WSTIFF", "ABAM",
                              "I3", "SI2"),
             "error": "ERROR", "hmax": "HMAX", "hmin": "HMIN", "hinit": "HINIT",
             "max_num_steps": "MAX_NUM_STEPS", "max_step_growth": "MAX_STEP_GROWTH",
             "nonlin_conv_coef": "NONLIN_CONV_COEF", "dae_constr_tol": "DAE_CONSTR_TOL"}


DaeIntegrator = Integrator


class Equilibrium(_Settings):
    """Static settings: error, imbalance, maxit, stability, tlimit, alimit; pysolver's
    method (FIM_D, FIM_S, MKEAM), max_ke_tol, max_dq_tol, compliance_delta."""
    _statement = "EQUILIBRIUM"
    _keys = {"error": "ERROR", "imbalance": "IMBALANCE", "maxit": "MAXIT",
             "stability": "STABILITY", "tlimit": "TLIMIT", "alimit": "ALIMIT",
             "method": "METHOD", "max_ke_tol": "MAX_KE_TOL", "max_dq_tol": "MAX_DQ_TOL",
             "compliance_delta": "COMPLIANCE_DELTA"}


class Pforce(_Element):
    """pysolver: a penalty force (Force_Penalty, the PFORCE statement): function (g),
    penalty, penalty1, unilateral, smoothing_factor; routine, script, interpreter (a
    PFOSUB)."""
    _statement = "PFORCE"
    _keys = {"function": "FUNCTION", "penalty": "PENALTY", "penalty1": "PENALTY1",
             "unilateral": "UNILATERAL", "smoothing_factor": "SMOOTHING_FACTOR", **_SUB}


class LoadControl(_Element):
    """pysolver: the LoadControl task (MotionSolve XML's <CustomTasks>, the LOADCONTROL
    statement): material (the Part or PointMass driven), direction (1, 2, 3), velocity,
    maxvelocity, load_function, kp, ki (numbers or "AUTO"), smooth, updatetime,
    median_window, load ("REACTION" or "CONTACT")."""
    _statement = "LOADCONTROL"
    _keys = {"velocity": "VELOCITY", "material": "MATERIAL", "direction": "DIRECTION",
             "maxvelocity": "MAXVELOCITY", "load_function": "LOAD_FUNCTION", "kp": "KP",
             "ki": "KI", "smooth": "SMOOTH", "updatetime": "UPDATETIME",
             "median_window": "MEDIAN_WINDOW", "load": "LOAD"}


_ANALYSES = {"DYNAMICS": "DYNAMICS", "TRANSIENT": "DYNAMICS", "KINEMATICS": "KINEMATICS",
             "STATICS": "STATICS", "STATIC": "STATICS", "QUASI-STATIC": "STATICS",
             "QUASISTATIC": "STATICS", "ASSEMBLY": "INITIAL_CONDITIONS"}


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
            except (ValueError, DeckError) as err:
                raise DeckError(getattr(err, "reason", str(err)), file=el._where[0],
                                line=el._where[1], element=type(el).__name__,
                                id=el.id) from None
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
        from .deck.validate import build_model
        from .records import Source
        text, elements = self._read()
        return build_model(elements, Source(self._file(), text, "adm"))

    def elements(self):
        """The deck elements of this model (what a deck file is read into), each at the
        Python line that created it."""
        return self._read()[1]

    def _file(self):
        return self._where[0] or "<msolve model>"

    def _read(self):
        """(dataset text, its elements): the reader's DeckError and each element located at
        the Python file and line of the element or simulate() call that made it, so the
        checks after the reader name them too."""
        from .deck.adams import read_elements
        text = self.adm()
        try:
            elements = read_elements(text, self._file())
        except DeckError as err:
            where = self._python(err.file, err.line)
            if where is None:
                raise
            raise DeckError(err.reason, file=where[0], line=where[1], element=err.element,
                            attribute=err.attribute) from None
        return text, [self._located(el) for el in elements]

    def _python(self, file, line):
        """(file, line) of the Python code behind line `line` of the dataset (`file` the
        model's) or of its commands (`file` _COMMANDS); None when no Python line made it."""
        if file not in (self._file(), _COMMANDS):
            return None
        where = self._lines.get((_COMMANDS, line) if file == _COMMANDS else line)
        return where if where is not None and where[0] is not None else None

    def _located(self, element):
        """An element read from the dataset, at the Python file and line that made it."""
        tag, attrs, line, names = element
        where = self._python(names.get("#file", self._file()), line)
        if where is None:
            return element
        return tag, attrs, where[1], {**names, "#file": where[0]}

    def simulate(self, type="DYNAMICS", end=None, dtout=None, steps=None, duration=None,
                 start=None, print_increment=None, returnResults=True, **options):
        """Add a simulation command and run every command so far from the start.

        Parameters
        ----------
        type : {"DYNAMICS", "TRANSIENT", "KINEMATICS", "STATICS", "ASSEMBLY"}
            STATICS with dtout or steps is a quasi-static analysis (as Adams' SIMULATE).
        end, duration : float
            The end time (or the duration after the previous command's end).
        dtout, steps : float, int
            The output interval, or the number of output steps.
        start, print_increment : float, int
            pysolver: MotionSolve's start_time (the previous command's end) and
            print_increment (accepted, not used).
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
        args = [(kind, None)]
        for key, val in (("START", start), ("END", end), ("DURATION", duration),
                         ("DTOUT", dtout), ("STEPS", steps),
                         ("PRINT_INCREMENT", print_increment)):
            if val is not None:
                args.append((key, _plain(key, val)))
        try:
            text = statement_lines(Statement("SIMULATE", None, args))
        except DeckError as err:
            raise DeckError(err.reason, file=file, line=line, element="simulate") from None
        self.commands.append((" ".join(text), (file, line)))
        if _loading() is not None:
            return None
        res = self.load().run(**options)
        return res if returnResults else None
