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

simulate() runs every command from t = 0 with the model as it is, so the model must not change
between analyses: an element created or changed after a simulate() is a DeckError at the line
that did it (the next simulate(), load() or adm()), and a simulate() that raises records no
command. Checks that need msolve's attribute names (a Marker's owner, a Motion's attributes)
are the classes' own, made when the model is written.
"""
import itertools
import os
import sys
import threading
import warnings

import numpy as np

from .deck.adams_writer import SHAPES, Function, Raw, Statement, statement_lines, view_name
from .errors import DeckError, DeckWarning, warn

__all__ = ["Model", "Units", "Accgrav", "Part", "PointMass", "Marker", "Point", "Vector",
           "Joint", "Jprim", "Gcon", "Coupler", "Motion", "Sforce", "SpringDamper",
           "Bushing", "Field", "Beam", "Vforce", "Vtorque", "Gforce", "Variable", "Spline",
           "Sensor", "SensorEvaluate", "Request", "Output", "Integrator", "DaeIntegrator",
           "Equilibrium", "Graphics", "Sphere", "Box", "Cylinder", "Frustum", "Ellipsoid",
           "External", "Pforce", "LoadControl", "ResOutput", "H3DOutput", "H3dOutput", "Pinput",
           "Poutput"]

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
    """A point (x, y, z); points and vectors add and subtract as arrays, and ``.x``, ``.y``,
    ``.z`` read and set their coordinates (msolve's Location)."""

    def __new__(cls, x=0.0, y=0.0, z=0.0):
        return np.asarray([x, y, z], float).view(cls)

    x = property(lambda self: float(self[0]), lambda self, v: self.__setitem__(0, v),
                 doc="The x coordinate.")
    y = property(lambda self: float(self[1]), lambda self, v: self.__setitem__(1, v),
                 doc="The y coordinate.")
    z = property(lambda self: float(self[2]), lambda self, v: self.__setitem__(2, v),
                 doc="The z coordinate.")


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


#: Attributes every element takes besides its table: its id and label, msolve's name (kept;
#: the label when no label is given) and active (False leaves it out of the model).
_BASE = ("id", "label", "model", "active", "name")


def _bad(attribute, reason):
    """A DeckError about an element's attribute (Model.adm locates it at the element)."""
    return DeckError(reason, attribute=attribute)


class _Element:
    """An element of the model: its Adams statement, its id and its attributes."""
    _statement = ""                # the Adams statement it becomes
    _keys = {}                     # attribute -> Adams keyword, or {value: flag}
    _also = {}                     # keywords read back into an attribute (convert.py)
    _shown = {}                    # element attribute -> the name its errors give it
    _numbered = True               # has an id
    _any = False                   # takes any keyword (kept as written)
    _refused = {}                  # msolve attributes pysolver does not take -> why
    _kept = ()                     # msolve attributes taken and kept, not written: not used

    def __init__(self, id=None, label="", active=True, name=None, **kw):
        unknown = sorted(set(kw) - set(self._keys) - set(self._kept)) if not self._any else []
        file, line = _caller()
        if unknown and unknown[0] in self._refused:
            raise DeckError(f"{unknown[0]} is not supported: {self._refused[unknown[0]]}",
                            file=file, line=line, element=type(self).__name__,
                            attribute=unknown[0])
        if unknown:
            raise DeckError(f"unknown attribute {unknown[0]!r}; {type(self).__name__} takes "
                            f"{', '.join(sorted(self._keys))}", file=file, line=line,
                            element=type(self).__name__, attribute=unknown[0])
        if not isinstance(active, (bool, np.bool_)):
            raise DeckError(f"active={active!r}; expected True or False", file=file,
                            line=line, element=type(self).__name__, attribute="active")
        object.__setattr__(self, "_where", (file, line))
        object.__setattr__(self, "_extra", {})
        self.__dict__.update({k: None for k in (*self._keys, *self._kept)})
        for key, value in kw.items():
            setattr(self, key, value)
        self.label, self.active, self.name = label, bool(active), name
        self.model = _current()
        self.id = None if not self._numbered else \
            id if id is not None else self.model._next_id(self._kind())
        self.model._add(self)

    @classmethod
    def _kind(cls):
        return cls._statement

    def __setattr__(self, name, value):
        if name in self._kept:              # not part of the model: never a change
            object.__setattr__(self, name, value)
            return
        if name not in self._keys and name not in _BASE and not self._any:
            raise AttributeError(f"{type(self).__name__} has no attribute {name!r}; it takes "
                                 f"{', '.join(sorted(self._keys))}")
        model = self.__dict__.get("model")
        if model is not None:
            model._assigned(self, name)
        if name not in self._keys and name not in _BASE:
            self._extra[name] = value
            return
        object.__setattr__(self, name, value)

    def __getattr__(self, name):
        extra = self.__dict__.get("_extra") or {}
        if name in extra:
            return extra[name]
        raise AttributeError(name)

    def _flag(self, attr):
        """The flag a flag attribute's value stands for (None when not given)."""
        val = getattr(self, attr)
        return None if val is None else self._keys[attr].get(str(val).upper())

    def _arguments(self):
        """[(Adams keyword, value)] of the statement (value None: a flag)."""
        out = []
        for attr, key in self._keys.items():
            val = getattr(self, attr)
            if val is None or val is False:
                continue
            _active_refs(attr, val)
            if isinstance(key, dict):
                flag = key.get(str(val).upper(), "")
                if flag == "":
                    raise _bad(attr, f"{attr}={val!r}; expected one of "
                               f"{', '.join(v for v in key if key[v] is not None)}")
                if flag is not None:
                    out.append((flag, None))
            elif val is True:
                out.append((key, None))
            else:
                out.append((key, _plain(key, val)))
        for k, v in self._extra.items():       # an element kept as written (_any)
            if isinstance(v, (bool, np.bool_)):
                out.append((k.upper(), None if v else Raw("FALSE")))   # a flag, or FALSE
            elif v is not None:
                _active_refs(k, v)
                out.append((k.upper(), _plain(k.upper(), v)))
        if self._any:               # kept as written: the text of each value
            out = [(k, v if v is None or isinstance(v, (list, Function)) else Raw(v))
                   for k, v in out]
        return out

    def _adm(self):
        """The element's Adams statement lines."""
        label = self.label or self.name or ""
        st = Statement(self._statement, self.id, self._arguments(), str(label))
        return ([view_name(st)] if st.label else []) + statement_lines(st)


def _active_refs(attr, val):
    """A DeckError when attribute `attr` refers to an element made inactive."""
    for ref in val if isinstance(val, (list, tuple)) else [val]:
        if isinstance(ref, _Element) and not ref.active:
            raise _bad(attr, f"{type(ref).__name__} {ref.id} is inactive (active=False); "
                       "an inactive element is left out of the model, so what refers to it "
                       "must be inactive too")


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


class _Body(_Element):
    """A Part or PointMass: a Marker made without an owner becomes its own when it is made
    its cm (msolve's ``Part(cm=Marker())`` and ``part.cm = Marker(qp=...)``)."""

    def __setattr__(self, name, value):
        if name == "cm" and isinstance(value, Marker) and value._owner() is None:
            value.body = self
        super().__setattr__(name, value)


class Part(_Body):
    """A rigid body (or ground=True): mass, ip=[ixx, iyy, izz(, ixy, ixz, iyz)], cm (its
    centre-of-mass Marker; one made without body= becomes the part's), im, qg and reuler
    (its frame in ground; or zg and xg), vx, vy, vz (along the global axes, or vm's), wx,
    wy, wz (along the cm marker's axes, or wm's), vm, wm; lprf (pysolver: MotionSolve's
    lprf_id, kept)."""
    _statement = "PART"
    _keys = {"ground": "GROUND", "mass": "MASS", "cm": "CM", "im": "IM", "lprf": "LPRF",
             "ip": "IP", "qg": "QG", "reuler": "REULER", "zg": "ZG", "xg": "XG", "vx": "VX",
             "vy": "VY", "vz": "VZ", "wx": "WX", "wy": "WY", "wz": "WZ", "vm": "VM",
             "wm": "WM"}


class PointMass(_Body):
    """A point mass: mass, cm (one made without body= becomes the point mass's), qg, vx,
    vy, vz, vm (pysolver: the marker whose axes vx, vy, vz are along)."""
    _statement = "POINT_MASS"
    _keys = {"mass": "MASS", "cm": "CM", "qg": "QG", "vx": "VX", "vy": "VY", "vz": "VZ",
             "vm": "VM"}

    @classmethod
    def _kind(cls):
        return "PART"               # parts and point masses share pysolver's body ids


#: A Marker's owner: body and part are msolve's two names for its Part; point_mass its
#: PointMass.
_OWNERS = ("body", "part", "point_mass")
#: A Marker's orientation forms (zv, xv: msolve's vectors along z and in the x-z plane).
_ORIENTATIONS = ("reuler", "zp", "zv", "ypr", "ep", "axes")


class Marker(_Element):
    """A marker on `body` (or `part`, or `point_mass`; a marker made without one becomes
    its Part's when it is made a cm): qp, and reuler, or zp and xp (points; usexp), or zv
    and xv (msolve's vectors along z and in the x-z plane; usexv), in its part's frame or in
    rm's; floating=True for a floating marker; pysolver's ypr (3-2-1 angles), ep (Euler
    parameters) and axes (the nine numbers of the columns x, y, z)."""
    _statement = "MARKER"
    _keys = {"body": "PART", "part": "PART", "point_mass": "POINT_MASS", "qp": "QP",
             "reuler": "REULER", "zp": "ZP", "xp": "XP", "usexp": "USEXP", "zv": "ZV",
             "xv": "XV", "usexv": "USEXV", "ypr": "YPR", "ep": "EP", "axes": "AXES",
             "rm": "RM", "floating": "FLOATING"}
    _also = {"POINT_MASS": "body"}
    _refused = {"flex_body": "pysolver has rigid bodies only"}

    def __setattr__(self, name, value):
        if name in _OWNERS and value is not None:
            other = next((o for o in _OWNERS if o != name and
                          self.__dict__.get(o) is not None), None)
            if other is not None:
                file, line = _caller()
                raise DeckError(f"{other}= and {name}= both give the marker's owner (body and "
                                "part are msolve's two names for its Part); give one",
                                file=file, line=line, element="Marker", attribute=name)
        super().__setattr__(name, value)

    def _owner(self):
        return next((o for o in (self.body, self.part, self.point_mass) if o is not None),
                    None)

    def _arguments(self):
        owner = self._owner()
        if owner is None:
            raise _bad("body", "a Marker needs its owner: body= (or part=, point_mass=), or "
                       "to be made a Part's cm (Part(cm=Marker(...)), part.cm = Marker(...))")
        if self.point_mass is not None and not isinstance(owner, PointMass):
            raise _bad("point_mass", f"point_mass= takes a PointMass, got "
                       f"{type(owner).__name__} (a Part is given with body= or part=)")
        out = [(k, v) for k, v in super()._arguments() if k not in ("ZV", "XV", "USEXV")]
        if isinstance(owner, PointMass):
            out = [("POINT_MASS", v) if k == "PART" else (k, v) for k, v in out]
        if self.zv is not None or self.xv is not None:
            out += self._vectors()
        return out

    def _vectors(self):
        """zv and xv as the points ZP and XP (qp plus each vector; USEXP for usexv)."""
        if self.zv is None:
            raise _bad("xv", "xv (a vector in the x-z plane) needs zv (the z axis)")
        given = [a for a in _ORIENTATIONS + ("xp",) if a != "zv" and
                 getattr(self, a) is not None]
        if given:
            raise _bad("zv", f"give one orientation: zv (with xv), not {given[0]} too")
        try:
            origin = np.zeros(3) if self.qp is None else np.asarray(_plain("", self.qp), float)
            out = [("ZP", (origin + np.asarray(_plain("", self.zv), float)).tolist())]
            if self.xv is not None:
                out.append(("XP", (origin + np.asarray(_plain("", self.xv), float)).tolist()))
        except (TypeError, ValueError):
            raise _bad("zv", "qp, zv and xv take three numbers each") from None
        if any(len(v) != 3 for _, v in out):
            raise _bad("zv", "qp, zv and xv take three numbers each")
        return out + ([("USEXP", None)] if self.usexv else [])


_JPRIMS = ("ATPOINT", "INLINE", "INPLANE", "ORIENTATION", "PARALLEL_AXES", "PERPENDICULAR")
_JOINTS = _choices("REVOLUTE", "TRANSLATIONAL", "SPHERICAL", "CYLINDRICAL", "UNIVERSAL",
                   "HOOKE", "FIXED", "PLANAR", "SCREW", "FREE", *_JPRIMS,
                   CONSTANT_VELOCITY="CONVEL", CONVEL="CONVEL", RACK_PINION="RACKPIN",
                   RACKPIN="RACKPIN")


class Joint(_Element):
    """A joint: type (REVOLUTE, TRANSLATIONAL, SPHERICAL, CYLINDRICAL, UNIVERSAL, HOOKE,
    FIXED, PLANAR, CONSTANT_VELOCITY, SCREW, RACK_PINION, the primitives; pysolver's FREE),
    i, j, pitch, pd, virtual; ic (a TRANSLATIONAL or REVOLUTE joint), ictran and icrot (a
    CYLINDRICAL joint): the initial displacement of its coordinate, or (displacement,
    velocity), held by the initial conditions only."""
    _statement = "JOINT"
    _keys = {"type": _JOINTS, "i": "I", "j": "J", "pitch": "PITCH", "pd": "PD",
             "virtual": "VIRTUAL", "ic": "IC", "ictran": "ICTRAN", "icrot": "ICROT"}

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


#: The coordinates a joint Motion drives on each joint type (jtype's flags).
_DRIVEN = {"REVOLUTE": ("ROTATION",), "TRANSLATIONAL": ("TRANSLATION",),
           "CYLINDRICAL": ("ROTATION", "TRANSLATION")}


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
    _shown = {"motion_type": "JTYPE", "val_type": "DTYPE", "ic_disp": "ICDISP",
              "ic_vel": "ICVEL", "expr": "FUNCTION"}

    def _arguments(self):
        out = super()._arguments()          # the flags' values checked first
        if self.joint is not None:
            self._joint_motion()
        else:
            if self.jtype is not None:
                raise _bad("jtype", "jtype= is a joint motion's (joint=); a marker motion "
                           "takes direction=")
            missing = next((a for a in ("i", "j", "direction") if getattr(self, a) is None),
                           None)
            if missing is not None:
                raise _bad(missing, "a Motion drives joint= (jtype= its coordinate), or "
                           "marker i= relative to j= along or about direction= (X, Y, Z, B1, "
                           "B2, B3)")
        if self.function is None and self.routine is None:
            raise _bad("function", "give function= (an expression of time), or routine= (a "
                       'MOTSUB, with function="USER(...)")')
        return out

    def _joint_motion(self):
        """A joint motion's checks in msolve's names: no marker attributes, and jtype a
        coordinate its Joint leaves free (a joint given by id: the dataset's checks)."""
        given = next((a for a in ("i", "j", "direction") if getattr(self, a) is not None),
                     None)
        if given is not None:
            raise _bad(given, f"{given}= is a marker motion's; this one drives joint= (its "
                       "coordinate: jtype=)")
        if not isinstance(self.joint, Joint) or self.joint._flag("type") is None:
            return
        kind, jtype = self.joint._flag("type"), self._flag("jtype")
        free = _DRIVEN.get(kind)
        if free is None:
            raise _bad("joint", f"Joint {self.joint.id} is {kind}; a Motion drives a REVOLUTE "
                       "(jtype ROTATION), TRANSLATIONAL (TRANSLATION) or CYLINDRICAL (either) "
                       "joint")
        if jtype is None and len(free) > 1:
            raise _bad("jtype", f"Joint {self.joint.id} is {kind}: give jtype=\"ROTATION\" or "
                       "\"TRANSLATION\"")
        if jtype is not None and jtype not in free:
            raise _bad("jtype", f"jtype={jtype} is not a coordinate of {kind} Joint "
                       f"{self.joint.id} (it has {free[0]})")


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


class _Matrices(_Element):
    """An element whose 6x6 matrices may be given by rows: written as Adams' 36 numbers,
    column by column."""
    _matrices = ("KMATRIX", "CMATRIX")

    def _arguments(self):
        out = []
        for key, val in super()._arguments():
            if key in self._matrices and np.shape(val) == (6, 6):
                val = np.asarray(val, dtype=float).T.ravel().tolist()
            out.append((key, val))
        return out


class Field(_Matrices):
    """A field: i, j, kmatrix, cmatrix (36 numbers each, column by column as Adams enters
    them, or 6x6 matrices by rows) or cratio, length and force (six numbers each: x, y, z and
    the rotations a, b, c; three forces and three torques, in j's axes)."""
    _statement = "FIELD"
    _keys = {"i": "I", "j": "J", "kmatrix": "KMATRIX", "cmatrix": "CMATRIX",
             "cratio": "CRATIO", "length": "LENGTH", "force": "FORCE"}


class Beam(_Matrices):
    """A massless Timoshenko beam along j's x: i, j, length, ixx, iyy, izz, area, asy, asz,
    emodulus, gmodulus, cratio or cmatrix (21 numbers as Adams, 36, or a 6x6 matrix), force
    and torque (preloads, three numbers each in j's axes)."""
    _statement = "BEAM"
    _keys = {"i": "I", "j": "J", "length": "LENGTH", "ixx": "IXX", "iyy": "IYY",
             "izz": "IZZ", "area": "AREA", "asy": "ASY", "asz": "ASZ",
             "emodulus": "EMODULUS", "gmodulus": "GMODULUS", "cratio": "CRATIO",
             "cmatrix": "CMATRIX", "force": "FORCE", "torque": "TORQUE"}


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
    VARSUB). msolve's implicit (False; an implicit variable is not supported), and
    auto_balance, penalty, penalty1 (an implicit variable's: taken, not used)."""
    _statement = "VARIABLE"
    _keys = {"function": "FUNCTION", "ic": "IC", **_SUB}
    _kept = ("implicit", "auto_balance", "penalty", "penalty1")

    def _arguments(self):
        if self.implicit:
            raise _bad("implicit", "an implicit Variable (its function held at zero by a "
                       "constraint or a penalty) is not supported: pysolver's variables are "
                       "explicit, VARVAL(id) the function's value (docs/msolve.md)")
        return super()._arguments()


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
    REQSUB); comment; cnames (the channels' names); msolve's results_name (taken, not used:
    pysolver names a request's results by its id and label)."""
    _statement = "REQUEST"
    _keys = {"type": _choices("DISPLACEMENT", "VELOCITY", "ACCELERATION", "FORCE",
                              EXPRESSION=None, USERSUB=None,
                              MARKER_DISPLACEMENT="DISPLACEMENT",
                              MARKER_VELOCITY="VELOCITY", MARKER_ACCELERATION="ACCELERATION",
                              MARKER_FORCE="FORCE"),
             "i": "I", "j": "J", "rm": "RM", **{f"f{k}": f"F{k}" for k in range(1, 9)},
             "function": "FUNCTION", "comment": "COMMENT", "cnames": "CNAMES", **_SUB}
    _kept = ("results_name",)


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


class External(_Shape):
    """Graphics from a CAD file (msolve's External, which Inspire writes for every part):
    file, element, rm, color, refinement_level, ..., kept as written (the 3-D view does not
    read CAD files)."""
    _shape = "EXTERNAL"


class ResOutput(_Settings):
    """pysolver: MotionSolve's ResOutput settings, any attribute, kept (not used)."""
    _statement = "RESOUTPUT"
    _any = True


class H3DOutput(_Settings):
    """MotionSolve's H3D output settings (save, linear_anim, format, ...), any attribute,
    kept (not used: pysolver writes no H3D file)."""
    _statement = "H3DOUTPUT"
    _any = True


#: msolve's spelling of the class (Altair's H3dOutput).
H3dOutput = H3DOutput


class Output(_Settings):
    """Output settings (reqsave, grsave, req_angle_radians, capture_max_pd, req_comment_only,
    azero, dzero, fzero, vzero, ..., any attribute): accepted, not used (pysolver writes its
    own outputs)."""
    _statement = "OUTPUT"
    _keys = {"reqsave": "REQSAVE", "grsave": "GRSAVE"}
    _any = True


class Pinput(_Element):
    """A plant's inputs (variables: the Variables) for linearization and control
    co-simulation: accepted, set aside with a DeckWarning (the dataset's PINPUT)."""
    _statement = "PINPUT"
    _keys = {"variables": "VARIABLES"}


class Poutput(_Element):
    """A plant's outputs (variables: the Variables): set aside as Pinput (POUTPUT)."""
    _statement = "POUTPUT"
    _keys = {"variables": "VARIABLES"}


class Integrator(_Settings):
    """Integrator settings: type (DSTIFF, GSTIFF, ...: pysolver integrates with IDA's BDF),
    error, hmax, hmin, hinit; pysolver's max_num_steps, max_step_growth, nonlin_conv_coef,
    dae_constr_tol. kmax, maxit, pattern (Adams' INTEGRATOR keywords) and msolve's dae_index,
    dae_jacob_init are taken and not used (IDA chooses its own order, iterations and
    formulation: docs/numerics.md)."""
    _statement = "INTEGRATOR"
    _keys = {"type": _choices("IDA", "DSTIFF", "VSTIFF", "MSTIFF", "GSTIFF", "WSTIFF", "ABAM",
                              "I3", "SI2"),
             "error": "ERROR", "hmax": "HMAX", "hmin": "HMIN", "hinit": "HINIT",
             "max_num_steps": "MAX_NUM_STEPS", "max_step_growth": "MAX_STEP_GROWTH",
             "nonlin_conv_coef": "NONLIN_CONV_COEF", "dae_constr_tol": "DAE_CONSTR_TOL",
             "kmax": "KMAX", "maxit": "MAXIT", "pattern": "PATTERN"}
    _kept = ("dae_index", "dae_jacob_init")


DaeIntegrator = Integrator


class Equilibrium(_Settings):
    """Static settings: error, imbalance, maxit, stability, tlimit, alimit, type (STATIC, the
    static equilibrium pysolver finds; DYNAMIC is set aside with a DeckWarning),
    kinetic_energy_error (MKEAM's max_ke_tol); pysolver's method (FIM_D, FIM_S, MKEAM),
    max_ke_tol, max_dq_tol, compliance_delta; msolve's skip_mkeam is taken and not used
    (pysolver runs the one method `method` names)."""
    _statement = "EQUILIBRIUM"
    _keys = {"error": "ERROR", "imbalance": "IMBALANCE", "maxit": "MAXIT",
             "stability": "STABILITY", "tlimit": "TLIMIT", "alimit": "ALIMIT",
             "type": _choices("STATIC", "DYNAMIC"), "method": "METHOD",
             "max_ke_tol": "MAX_KE_TOL", "kinetic_energy_error": "MAX_KE_TOL",
             "max_dq_tol": "MAX_DQ_TOL", "compliance_delta": "COMPLIANCE_DELTA"}
    _kept = ("skip_mkeam",)


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


def _signature(el):
    """{attribute: its value as a comparable token} of an element (a change after a
    simulate() is told by them)."""
    names = [*el._keys, *el._extra, "id", "label", "active", "name"]
    return {n: _token(el._extra[n] if n in el._extra else el.__dict__.get(n)) for n in names}


def _token(value):
    """A value as a comparable token: elements by identity, numbers by value, arrays and
    lists item by item."""
    if isinstance(value, (bool, np.bool_, str)) or value is None:
        return value
    if isinstance(value, (int, float, np.integer, np.floating)):
        return repr(float(value))
    if isinstance(value, np.ndarray):
        return tuple(_token(v) for v in value.tolist())
    if isinstance(value, (list, tuple)):
        return tuple(_token(v) for v in value)
    if isinstance(value, Function):
        return str(value)
    return ("object", id(value))     # an element, a routine: by identity


_ANALYSES = {"DYNAMICS": "DYNAMICS", "TRANSIENT": "DYNAMICS", "KINEMATICS": "KINEMATICS",
             "STATICS": "STATICS", "STATIC": "STATICS", "QUASI-STATIC": "STATICS",
             "QUASISTATIC": "STATICS", "ASSEMBLY": "INITIAL_CONDITIONS"}


class Model:
    """A model: the container every element created after it joins.

    Parameters
    ----------
    output : str, optional
        The output name (kept as ``model.output``; pysolver writes no files unless told).
    label : str, optional
        The model's label (kept as ``model.label``; the title line of ``model.adm()``).
    """

    def __init__(self, output=None, label=None):
        self.output, self.label = output, label
        self.entities = []          # the elements, in the order they were created
        self.commands = []
        self._ids = {}
        self._where = _caller()
        # after a simulate(): every element's attributes then and that call's (file, line);
        # then the changes since, in order: (element, attribute or None when created, where)
        self._ran, self._changes = None, []
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
        if self._ran is not None:
            self._changes.append((element, None, element._where))

    def _assigned(self, element, name):
        """Note an attribute set after a simulate() (checked by _check_unchanged)."""
        if self._ran is not None and name != "model":
            self._changes.append((element, name, _caller()))

    def _snapshot(self, where):
        """After a simulate() at `where`: the model as it ran."""
        self._ran = ({el: _signature(el) for el in self.entities}, where)
        self._changes = []

    def _check_unchanged(self):
        """A DeckError when an element was created or changed after the last simulate():
        every command runs from t = 0 with the model as it is, so the change would rewrite
        the analyses before it too (msolve's changes between analyses are not supported)."""
        if self._ran is None:
            return
        before, (file, line) = self._ran
        changes = list(self._changes) + [(el, None, el._where) for el in self.entities
                                         if el not in before]
        for el in self.entities:            # changed in place (a list or Point's item)
            if el in before:
                now = _signature(el)
                changes += [(el, k, (None, None)) for k in now if now[k] != before[el].get(k)]
        for el, attr, (cfile, cline) in changes:
            if el not in self.entities:
                continue
            if attr is None:
                what = "created"
            elif el not in before or _signature(el)[attr] == before[el].get(attr):
                continue
            else:
                what = "changed" if cline is not None else "changed in place"
            at = f"line {line}" if file == (cfile or el._where[0]) else f"{file}:{line}"
            raise DeckError(
                f"{what} after the simulate() at {at}; pysolver runs every command from "
                "t = 0 with the model as it is, so this would rewrite the analyses before it "
                "too: build a new Model for the new values, or vary a number with "
                "model.load().run(params=...) or pysolver.sweep (docs/msolve.md)",
                file=cfile or el._where[0], line=cline or el._where[1],
                element=type(el).__name__, id=el.id, attribute=attr)

    def adm(self):
        """The model as an Adams dataset (text), its commands after END as a command file
        would give them (pysolver.deck.adams); an inactive element is left out.

        Raises
        ------
        DeckError
            An element is wrong (at the line that made it), or was created or changed
            after a simulate() (at the line that did).
        """
        from .deck.adams import COMMANDS_MARK
        self._check_unchanged()
        title = " ".join(str(self.label).split()) if self.label else ""
        lines, self._lines, self._made = [title or "pysolver msolve model"], {}, {}
        for el in self.entities:
            if not el.active:
                continue
            try:
                text = el._adm()
            except (ValueError, DeckError) as err:
                raise DeckError(getattr(err, "reason", str(err)), file=el._where[0],
                                line=el._where[1], element=type(el).__name__, id=el.id,
                                attribute=getattr(err, "attribute", None)) from None
            for _ in text:
                self._lines[len(lines) + 1] = el._where
                self._made[len(lines) + 1] = el
                lines.append(_)
        lines.append("END")
        if self.commands:
            lines.append(f"{COMMANDS_MARK} {_COMMANDS}")
            for k, (cmd, where) in enumerate(self.commands):
                self._lines[(_COMMANDS, 3 + k)] = where     # a command file's lines from 3
                lines.append(cmd)
        return "\n".join(lines) + "\n"

    def load(self):
        """The pysolver Model of this model and its simulate commands so far.

        Raises
        ------
        DeckError
            As :meth:`adm`, and for what the dataset's checks find (at the Python line).
        """
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
        caught = []
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                elements = read_elements(text, self._file())
        except DeckError as err:
            where = self._python(err.file, err.line)
            if where is None:
                raise
            raise DeckError(err.reason, file=where[0], line=where[1], element=err.element,
                            attribute=err.attribute) from None
        finally:
            self._warn_again(caught)
        return text, [self._located(el) for el in elements]

    def _warn_again(self, caught):
        """The reader's warnings, each DeckWarning at the Python file and line that made its
        statement."""
        for w in caught:
            msg = w.message
            if not isinstance(msg, DeckWarning):
                warnings.warn_explicit(msg, w.category, w.filename, w.lineno)
                continue
            where = self._python(msg.file, msg.line) or (msg.file, msg.line)
            warn(DeckWarning(msg.reason, file=where[0], line=where[1], element=msg.element,
                             id=msg.id, attribute=msg.attribute))

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
        made = self._made.get(line) if "#file" not in names else None
        shown = made._shown if made is not None else {}
        return tag, attrs, where[1], {**names, **shown, "#file": where[0]}

    def simulate(self, type="DYNAMICS", end=None, dtout=None, steps=None, duration=None,
                 start=None, print_increment=None, returnResults=True,
                 active_contact_iteration=None, **options):
        """Add a simulation command and run every command so far from the start.

        The model must not have changed since the previous simulate(): every command runs
        from t = 0 with the model as it is (a DeckError names the change). A call that
        raises leaves ``model.commands`` as it was.

        Parameters
        ----------
        type : {"DYNAMICS", "TRANSIENT", "KINEMATICS", "STATICS", "ASSEMBLY"}
            STATICS with dtout or steps is a quasi-static analysis (as Adams' SIMULATE);
            with dtout=0 (no output step, as Inspire writes it) one equilibrium at end.
        end, duration : float
            The end time (or the duration after the previous command's end).
        dtout, steps : float, int
            The output interval, or the number of output steps.
        start, print_increment : float, int
            pysolver: MotionSolve's start_time (where the run is: 0 on the first command,
            the previous command's end after; another value is a DeckError) and
            print_increment (not used: a DeckWarning alone; with dtout or steps a DeckError).
        returnResults : bool
            Return the Result (else None).
        active_contact_iteration : bool, optional
            msolve's contact iteration switch: taken, not used (pysolver has no contact).
        **options
            Run options (``integr_tol=``, ``kernel=``, ...: :meth:`pysolver.Model.run`).

        Returns
        -------
        pysolver.Result or None
            The whole run, every command so far. When pysolver.load reads a script, the
            command is recorded and nothing runs (None).

        Raises
        ------
        DeckError
            A bad command or element, or an element created or changed since the previous
            simulate() (at the line that did it).
        """
        self._check_unchanged()
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
            self._snapshot((file, line))
            return None
        try:
            res = self.load().run(**options)
        except BaseException:
            self.commands.pop()             # a corrected call can follow
            raise
        self._snapshot((file, line))
        return res if returnResults else None
