"""The validated scene: plain Python objects shared by both deck readers.

Both readers (``xmldeck`` and ``pydeck``) hand raw elements ``(tag, attributes, line)`` to
:func:`build_model`, which checks every attribute against :data:`SCHEMA`, resolves ids and
marker frames, parses expressions, and returns a :class:`Model`. Nothing runs until
:meth:`Model.run`.
"""
import dataclasses
import hashlib
import math

import numpy as np

from . import expr as ex
from . import units as un
from .errors import DeckError, ExpressionError

# Attribute kinds: a converter name, whether required, default.
REQ = True
OPT = False
_ORIENT = {k: ("float", OPT, None) for k in
           ("a00", "a10", "a20", "a01", "a11", "a21", "a02", "a12", "a22",
            "psi", "theta", "phi", "e0", "e1", "e2", "e3")}
_USERSUB = {"usrsub_dll_name": ("str", OPT, None), "usrsub_fnc_name": ("str", OPT, None),
            "usrsub_param_string": ("str", OPT, None), "script_name": ("str", OPT, None),
            "interpreter": (("PYTHON", "MATLAB"), OPT, None)}

#: Every element, its attributes, their kinds, whether required, and defaults.
SCHEMA = {
    "Units": {"mass": ("unit:mass", OPT, "KILOGRAM"), "length": ("unit:length", OPT, "METER"),
              "time": ("unit:time", OPT, "SECOND"), "force": ("unit:force", OPT, "NEWTON"),
              "angle": (("RADIAN",), OPT, "RADIAN"), "label": ("str", OPT, "")},
    "Force_Gravity": {"id": ("id", OPT, None), "grav_x": ("float", OPT, 0.0),
                      "grav_y": ("float", OPT, 0.0), "grav_z": ("float", OPT, 0.0),
                      "label": ("str", OPT, "")},
    "Reference_Marker": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                         "body_id": ("id", REQ, None),
                         "body_type": (("RIGIDBODY", "POINTBODY", "RIGID", "POINT"), OPT, None),
                         "pos_x": ("float", OPT, 0.0), "pos_y": ("float", OPT, 0.0),
                         "pos_z": ("float", OPT, 0.0), "rm_id": ("id", OPT, None), **_ORIENT},
    "Body_Rigid": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                   "isground": ("bool", OPT, False), "cg_id": ("id", OPT, None),
                   "im_id": ("id", OPT, None), "lprf_id": ("id", OPT, None),
                   "mass": ("pos", OPT, None),
                   **{f"inertia_{k}": ("float", OPT, 0.0)
                      for k in ("xx", "yy", "zz", "xy", "yz", "xz")},
                   **{f"{v}_ic_{c}": ("float", OPT, 0.0) for v in "vw" for c in "xyz"}},
    "Body_Point": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                   "cg_id": ("id", REQ, None), "mass": ("pos", REQ, None),
                   **{f"v_ic_{c}": ("float", OPT, 0.0) for c in "xyz"}},
    "Force_Penalty": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                      "type": (("EXPRESSION", "USERSUB"), OPT, "EXPRESSION"),
                      "expr": ("expr", OPT, None), "penalty": ("pos", REQ, None),
                      "penalty1": ("nonneg", OPT, 0.0), "unilateral": ("bool", OPT, False),
                      "smoothing_factor": ("pos", OPT, 1.0), **_USERSUB},
    "Force_Scalar_TwoBody": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                             "type": (("FORCE", "TORQUE"), REQ, None),
                             "i_marker_id": ("id", REQ, None), "j_marker_id": ("id", REQ, None),
                             "expr": ("expr", OPT, None), "val_expression": ("expr", OPT, None),
                             "val": ("float", OPT, None), **_USERSUB},
    "Reference_Variable": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                           "type": (("EXPRESSION",), OPT, "EXPRESSION"),
                           "expr": ("expr", REQ, None), "initial_value": ("float", OPT, 0.0)},
    "Param_Transient": {"integrator_type": (("IDA", "DSTIFF", "VSTIFF", "MSTIFF", "GSTIFF",
                                             "WSTIFF", "ABAM", "I3", "SI2"), OPT, "IDA"),
                        "integr_tol": ("pos", OPT, 1e-3), "h_max": ("pos", OPT, None),
                        "h_min": ("nonneg", OPT, 0.0), "h0_max": ("pos", OPT, None),
                        "dae_constr_tol": ("pos", OPT, None),
                        "max_num_steps": ("id", OPT, 1000000),
                        "max_step_growth": ("pos", OPT, None),
                        "nonlin_conv_coef": ("pos", OPT, None), "label": ("str", OPT, "")},
    "Post_Request": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                     "type": (("EXPRESSION",), OPT, "EXPRESSION"), "comment": ("str", OPT, ""),
                     **{f"expr{k}": ("expr?", OPT, None) for k in range(1, 9)},
                     **{f"name{k}": ("str", OPT, None) for k in range(1, 9)}},
    "Param_Static": {"method": (("FIM_D", "FIM_S", "MKEAM"), OPT, "FIM_D"),
                     "max_ke_tol": ("pos", OPT, 1e-5), "max_dq_tol": ("pos", OPT, 1e-3),
                     "max_num_iter": ("id", OPT, 100), "max_imbalance": ("pos", OPT, 1e-4),
                     "max_error": ("pos", OPT, 1e-4), "stability": ("nonneg", OPT, 1e-10),
                     "compliance_delta": ("pos", OPT, 1e-3), "tlimit": ("pos", OPT, 20.0),
                     "alimit": ("pos", OPT, 0.17453292519943295), "label": ("str", OPT, "")},
    "Simulate": {"analysis_type": (("TRANSIENT", "STATIC", "QUASI-STATIC"), REQ, None),
                 "start_time": ("float", OPT, None), "end_time": ("float", OPT, None),
                 "duration": ("pos", OPT, None), "print_interval": ("pos", OPT, None),
                 "num_step": ("id", OPT, None), "print_increment": ("id", OPT, None)},
    "Sensor_Event": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                     "type": (("EXPRESSION", "USERSUB"), OPT, "EXPRESSION"),
                     "expr": ("expr", OPT, None), "value": ("float", OPT, 0.0),
                     "compare": (("GE", "LT", "EQ", "LE"), OPT, "GE"),
                     "error_tol": ("nonneg", OPT, 1e-3), "evaluate_id": ("id", OPT, None),
                     "dt": ("pos", OPT, None), "stepsize": ("pos", OPT, None),
                     "zero_crossing": ("float", OPT, None), "hmax": ("pos", OPT, None),
                     "halt": ("bool", OPT, False), "print": ("bool", OPT, False),
                     "restart": ("bool", OPT, False), "verbose": ("bool", OPT, False),
                     "return": ("bool", OPT, False), **_USERSUB},
    "Sensor_Evaluate": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                        "type": (("EXPRESSION", "USERSUB"), OPT, "EXPRESSION"),
                        "expr": ("expr", OPT, None), **_USERSUB},
    "Stop": {},
}
COMMANDS = ("Simulate", "Stop")
CANONICAL = {name.lower(): name for name in SCHEMA}
_ID_KIND = {"Reference_Marker": "marker", "Body_Rigid": "body", "Body_Point": "body",
            "Force_Penalty": "penalty", "Force_Scalar_TwoBody": "sforce",
            "Reference_Variable": "variable", "Post_Request": "request",
            "Sensor_Event": "sensor", "Sensor_Evaluate": "evaluate"}


@dataclasses.dataclass
class Marker:
    id: int
    body: int              # body id (ground id for ground markers)
    pos: np.ndarray        # global position at t = 0
    rot: np.ndarray        # global axes at t = 0 (columns x, y, z)
    label: str = ""


@dataclasses.dataclass
class Body:
    id: int
    kind: str              # "ground", "point" or "rigid"
    mass: float = 0.0
    inertia: np.ndarray = None   # body-frame inertia tensor (3 x 3)
    pos: np.ndarray = None       # initial position of the body frame origin (the cg marker)
    rot: np.ndarray = None       # initial body axes (columns)
    vel: np.ndarray = None       # initial velocity, global
    omega: np.ndarray = None     # initial angular velocity, body frame
    label: str = ""


@dataclasses.dataclass
class Penalty:
    id: int
    expr: tuple
    text: str
    penalty: float
    penalty1: float
    unilateral: bool
    smoothing: float
    label: str = ""


@dataclasses.dataclass
class ScalarForce:
    id: int
    torque: bool
    i: int
    j: int
    expr: tuple
    text: str
    label: str = ""


@dataclasses.dataclass
class Variable:
    id: int
    expr: tuple
    text: str
    label: str = ""


@dataclasses.dataclass
class Request:
    id: int
    exprs: list            # 8 entries: parse tree or None
    texts: list
    names: list
    label: str = ""


@dataclasses.dataclass
class Sensor:
    """A Sensor_Event: watch ``expr`` against ``value`` and act when it fires."""
    id: int
    expr: tuple
    text: str
    value: float
    compare: str           # "GE", "LT" or "EQ" (Adams' LE reads as LT)
    error_tol: float
    evaluate_id: int = None
    dt: float = None
    stepsize: float = None
    zero_crossing: float = None
    hmax: float = None
    halt: bool = False
    print: bool = False
    restart: bool = False
    verbose: bool = False
    ret: bool = False
    label: str = ""

    def actions(self):
        """Names of the actions this sensor takes when it fires, in the order they run."""
        names = []
        for key in ("evaluate_id", "dt", "stepsize", "hmax", "zero_crossing"):
            if getattr(self, key) is not None:
                names.append(key)
        for key in ("restart", "print", "verbose", "halt"):
            if getattr(self, key):
                names.append(key)
        if self.ret:
            names.append("return")
        return names


@dataclasses.dataclass
class Evaluate:
    """A Sensor_Evaluate: stored when a parent sensor fires, read by SENVAL(id)."""
    id: int
    expr: tuple
    text: str
    label: str = ""


@dataclasses.dataclass
class Transient:
    """Integrator settings of ``Param_Transient``; see the README for the mapping to IDA."""
    integr_tol: float = 1e-3
    h_max: float = None
    h_min: float = 0.0
    h0_max: float = None
    max_num_steps: int = 1000000
    max_step_growth: float = None
    nonlin_conv_coef: float = None


@dataclasses.dataclass
class Static:
    """Settings of ``Param_Static`` (seed 004 defaults); see :mod:`pysolver.statics`."""
    method: str = "FIM_D"
    max_ke_tol: float = 1e-5
    max_dq_tol: float = 1e-3
    max_num_iter: int = 100
    max_imbalance: float = 1e-4
    max_error: float = 1e-4
    stability: float = 1e-10
    compliance_delta: float = 1e-3
    tlimit: float = 20.0               # pysolver extension: Adams' TLIMIT, length units
    alimit: float = 0.17453292519943295  # pysolver extension: Adams' ALIMIT (10 deg), radians


@dataclasses.dataclass
class Simulate:
    analysis: str
    end_time: float
    print_interval: float
    line: int = None


@dataclasses.dataclass
class Source:
    """Where a deck came from, for error messages and result metadata."""
    file: str
    text: str
    fmt: str

    @property
    def sha256(self):
        return hashlib.sha256(self.text.encode()).hexdigest()


class _Ctx:
    """Location of the element being built, for DeckError."""

    def __init__(self, file, tag, attrs, line, names):
        self.file, self.tag, self.attrs, self.line, self.names = file, tag, attrs, line, names
        self.id = None

    def error(self, msg, attribute=None):
        shown = self.names.get(attribute, attribute) if attribute else None
        return DeckError(msg, file=self.file, line=self.line, element=self.tag, id=self.id,
                         attribute=shown)

    def where(self):
        return dict(file=self.file, line=self.line, element=self.tag, id=self.id)


def _convert(ctx, name, kind, raw):
    """Convert one attribute value to its kind or raise DeckError."""
    if isinstance(kind, tuple):
        val = str(raw).strip().upper()
        if val not in kind:
            raise ctx.error(f"got {raw!r}; expected one of {', '.join(kind)}", name)
        return val
    if kind.startswith("unit:"):
        return _unit(ctx, name, kind[5:], raw)
    if kind == "str":
        return str(raw)
    if kind == "bool":
        if isinstance(raw, bool):
            return raw
        val = str(raw).strip().upper()
        if val in ("TRUE", "YES", "1", "ON"):
            return True
        if val in ("FALSE", "NO", "0", "OFF"):
            return False
        raise ctx.error(f"got {raw!r}; expected TRUE or FALSE", name)
    if kind == "id":
        try:
            val = int(str(raw).strip()) if not isinstance(raw, (int, float)) else raw
            if isinstance(val, float) and val != int(val):
                raise ValueError
            val = int(val)
        except (TypeError, ValueError):
            raise ctx.error(f"got {raw!r}; expected a positive integer", name) from None
        if val <= 0:
            raise ctx.error(f"got {val}; expected a positive integer", name)
        return val
    if kind in ("float", "pos", "nonneg"):
        try:
            val = float(str(raw).strip().replace("d", "e").replace("D", "e")) \
                if not isinstance(raw, (int, float)) or isinstance(raw, bool) else float(raw)
            if isinstance(raw, bool):
                raise ValueError
        except (TypeError, ValueError):
            raise ctx.error(f"got {raw!r}; expected a real number", name) from None
        if not math.isfinite(val):
            raise ctx.error(f"got {raw!r}; expected a finite real number", name)
        if kind == "pos" and val <= 0:
            raise ctx.error(f"got {val:g}; expected a value > 0", name)
        if kind == "nonneg" and val < 0:
            raise ctx.error(f"got {val:g}; expected a value >= 0", name)
        return val
    if kind in ("expr", "expr?"):
        text = str(raw)
        if kind == "expr?" and text.strip().upper() in ("NULL", ""):
            return None
        try:
            return (ex.parse(text), text)
        except ExpressionError as err:
            raise ctx.error(f"bad expression {text!r}: {err}", name) from None
    raise AssertionError(kind)


def _unit(ctx, name, kind, raw):
    val = str(raw).strip().upper()
    if val not in un.TABLES[kind]:
        raise ctx.error(f"unknown {kind} unit {raw!r}; expected one of "
                        f"{', '.join(sorted(un.TABLES[kind]))}", name)
    return val


def _attributes(ctx):
    """Check names, presence and kinds of the element's attributes; return converted values."""
    schema = SCHEMA[ctx.tag]
    if "id" in schema and "id" in ctx.attrs:
        ctx.id = _convert(ctx, "id", "id", ctx.attrs["id"])
    for key in ctx.attrs:
        if key not in schema:
            raise ctx.error(f"unknown attribute; {ctx.tag} accepts "
                            f"{', '.join(sorted(schema)) or 'no attributes'}", key)
    out = {}
    for key, (kind, required, default) in schema.items():
        if key in ctx.attrs:
            out[key] = _convert(ctx, key, kind, ctx.attrs[key])
        elif required:
            raise ctx.error("missing required attribute", key)
        else:
            out[key] = default
    return out


def _rot_313(psi, theta, phi):
    """Body 3-1-3 rotation: A = Rz(psi) Rx(theta) Rz(phi)."""
    def rz(a):
        c, s = math.cos(a), math.sin(a)
        return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])

    c, s = math.cos(theta), math.sin(theta)
    rx = np.array([[1.0, 0, 0], [0, c, -s], [0, s, c]])
    return rz(psi) @ rx @ rz(phi)


def _rot_from_e(e):
    e0, e1, e2, e3 = e
    return np.array([
        [e0 * e0 + e1 * e1 - e2 * e2 - e3 * e3, 2 * (e1 * e2 - e0 * e3), 2 * (e1 * e3 + e0 * e2)],
        [2 * (e1 * e2 + e0 * e3), e0 * e0 - e1 * e1 + e2 * e2 - e3 * e3, 2 * (e2 * e3 - e0 * e1)],
        [2 * (e1 * e3 - e0 * e2), 2 * (e2 * e3 + e0 * e1), e0 * e0 - e1 * e1 - e2 * e2 + e3 * e3]])


def e_from_rot(A):
    """Euler parameters (e0 >= 0) of a rotation matrix."""
    tr = np.trace(A)
    cands = [tr, A[0, 0], A[1, 1], A[2, 2]]
    k = int(np.argmax(cands))
    if k == 0:
        e0 = 0.5 * math.sqrt(max(1 + tr, 0))
        e = [e0, (A[2, 1] - A[1, 2]) / (4 * e0), (A[0, 2] - A[2, 0]) / (4 * e0),
             (A[1, 0] - A[0, 1]) / (4 * e0)]
    else:
        i = k - 1
        j, l = (i + 1) % 3, (i + 2) % 3
        ei = 0.5 * math.sqrt(max(1 + 2 * A[i, i] - tr, 0))
        e = [0.0] * 4
        e[1 + i] = ei
        e[0] = (A[l, j] - A[j, l]) / (4 * ei)
        e[1 + j] = (A[j, i] + A[i, j]) / (4 * ei)
        e[1 + l] = (A[l, i] + A[i, l]) / (4 * ei)
    e = np.array(e)
    return e if e[0] >= 0 else -e


def _orientation(ctx, a):
    """Marker axes (relative to its rm frame) from one of the orientation forms."""
    forms = {"matrix": ["a00", "a10", "a20", "a01", "a11", "a21", "a02", "a12", "a22"],
             "313": ["psi", "theta", "phi"], "euler": ["e0", "e1", "e2", "e3"]}
    given = [f for f, keys in forms.items() if any(a[k] is not None for k in keys)]
    if len(given) > 1:
        raise ctx.error("give one orientation form only: a00..a22, psi/theta/phi or e0..e3",
                        forms[given[1]][0])
    if not given:
        return np.eye(3)
    form = given[0]
    missing = [k for k in forms[form] if a[k] is None and form != "313"]
    if missing:
        raise ctx.error(f"orientation form {', '.join(forms[form])} is incomplete", missing[0])
    if form == "313":
        return _rot_313(*(a[k] or 0.0 for k in forms["313"]))
    if form == "euler":
        e = np.array([a[k] for k in forms["euler"]])
        n = np.linalg.norm(e)
        if n == 0:
            raise ctx.error("Euler parameters are all zero", "e0")
        return _rot_from_e(e / n)
    A = np.array([a[k] for k in forms["matrix"]]).reshape(3, 3).T
    if not np.allclose(A.T @ A, np.eye(3), atol=1e-6) or np.linalg.det(A) < 0:
        raise ctx.error("a00..a22 is not a proper rotation (orthonormal, right-handed)", "a00")
    u, _, vt = np.linalg.svd(A)
    return u @ vt


class Model:
    """A validated scene, ready to run.

    Build one with :func:`pysolver.load`. Attributes hold the elements by id; ``commands``
    lists the Simulate commands in deck order.
    """

    def __init__(self, source):
        self.source = source
        self.units = dict(un.DEFAULTS)
        self.force_scale = 1.0
        self.gravity = np.zeros(3)
        self.markers = {}
        self.bodies = {}
        self.penalties = {}
        self.sforces = {}
        self.variables = {}
        self.requests = {}
        self.sensors = {}
        self.evaluates = {}
        self.transient = Transient()
        self.static = Static()
        self.commands = []
        self.has_units = False
        self._compiled = None
        self._where = {}          # (kind, id) -> location of the element, for errors

    # public API -------------------------------------------------------------------------
    def run(self, progress=None, **options):
        """Run the deck's commands in order and return a :class:`pysolver.Result`.

        Parameters
        ----------
        progress : bool or None, optional
            Show a progress bar on standard error. None (default) shows one only when standard
            error is a terminal and the run takes longer than one second.
        **options
            Override ``Param_Transient`` for this run: ``integr_tol``, ``h_max``, ``h_min``,
            ``h0_max``, ``max_num_steps`` (same meaning and units as in the deck). Also
            ``linsolver``: ``"auto"`` (default: dense below 300 states, sparse CSC from 300),
            ``"dense"`` or ``"sparse"``; ``jacobian``: ``"exact"`` (default, the kernel's) or
            ``"dq"`` (IDA's difference quotients, for comparison only); ``backend``:
            ``"auto"``, ``"c"`` or ``"sksundae"``; ``max_step_growth``: largest factor by which
            IDA may grow its step (C driver; default: IDA's 2 until its error test fails in
            most of 50 steps, the mark of a stiff penalty mode, then 1.1; give 2 for IDA's
            plain behaviour); ``nonlin_conv_coef``: IDA's Newton convergence coefficient (C
            driver; default 0.033, IDA's own 0.33 on scikit-sundae).

        Returns
        -------
        Result
            ``success=False`` with a message when the integration fails; never raises for
            that. Can be called repeatedly; each call starts from the deck's initial state.
        """
        from .simulate import run_model
        return run_model(self, progress=progress, **options)

    def _kernel(self, conservative=False):
        """The compiled kernel of this model, built on first use and reused by every run
        (a second one without damping for MKEAM)."""
        if self._compiled is None:
            self._compiled = {}
        if conservative not in self._compiled:
            from .kernel import Kernel
            self._compiled[conservative] = Kernel(self, conservative)
        return self._compiled[conservative]

    def summary(self):
        """Return a short human-readable listing of what the deck contains."""
        lines = [f"deck: {self.source.file} ({self.source.fmt})"]
        if self.has_units:
            lines.append("units: " + " ".join(f"{k}={v}" for k, v in self.units.items()))
        else:
            lines.append("units: consistent (no Units element)")
        lines.append(f"gravity: {self.gravity.tolist()}")
        moving = [b for b in self.bodies.values() if b.kind != "ground"]
        lines.append(f"bodies: {len(moving)} moving "
                     f"({sum(b.kind == 'point' for b in moving)} point, "
                     f"{sum(b.kind == 'rigid' for b in moving)} rigid), "
                     f"{len(self.bodies) - len(moving)} ground")
        lines.append(f"markers: {len(self.markers)}")
        for p in self.penalties.values():
            kind = "unilateral" if p.unilateral else "bilateral"
            lines.append(f"Force_Penalty {p.id} ({kind}): g = {p.text}")
        for s in self.sforces.values():
            lines.append(f"Force_Scalar_TwoBody {s.id} ({'torque' if s.torque else 'force'} "
                         f"I={s.i} J={s.j}): {s.text}")
        for v in self.variables.values():
            lines.append(f"Reference_Variable {v.id}: {v.text}")
        for r in self.requests.values():
            used = [t for t in r.texts if t]
            lines.append(f"Post_Request {r.id}: {len(used)} channel(s)")
        for se in self.sensors.values():
            lines.append(f"Sensor_Event {se.id}: {se.text} {se.compare} {se.value:g} "
                         f"(error_tol {se.error_tol:g}) -> {', '.join(se.actions()) or 'log'}")
        for ev in self.evaluates.values():
            lines.append(f"Sensor_Evaluate {ev.id}: {ev.text}")
        t = self.transient
        lines.append(f"Param_Transient: integr_tol={t.integr_tol:g} h_max={t.h_max} "
                     f"h_min={t.h_min:g} h0_max={t.h0_max}")
        st = self.static
        if any(c.analysis != "TRANSIENT" for c in self.commands):
            lines.append(f"Param_Static: method={st.method} max_imbalance={st.max_imbalance:g} "
                         f"max_error={st.max_error:g} stability={st.stability:g}")
        for c in self.commands:
            lines.append(f"Simulate {c.analysis.lower()}: end_time={c.end_time:g}"
                         + (f" print_interval={c.print_interval:g}" if c.print_interval else ""))
        lines.append(f"states: {self.num_states()}")
        return "\n".join(lines)

    def num_states(self):
        """Number of IDA states: 6 per point body, 13 per rigid body."""
        return sum({"point": 6, "rigid": 13}.get(b.kind, 0) for b in self.bodies.values())

    def __reduce__(self):
        return (_rebuild, (self.source.file, self.source.text, self.source.fmt))


def _rebuild(file, text, fmt):
    from .loader import loads
    return loads(text, fmt=fmt, file=file)


def build_model(elements, source):
    """Validate raw elements and return a :class:`Model`.

    Parameters
    ----------
    elements : list of (tag, attrs, line, names)
        ``tag`` any capitalisation of an element name; ``attrs`` maps lower-case attribute
        names to raw values; ``names`` maps attribute names to how the deck spelled them.
    source : Source
    """
    model = Model(source)
    seen = {}
    markers_raw = {}
    bodies_raw = []
    later = []
    sim_t = 0.0
    for tag, attrs, line, names in elements:
        canon = CANONICAL.get(tag.lower())
        if canon is None:
            raise DeckError(f"unknown element <{tag}>; known elements: "
                            f"{', '.join(sorted(SCHEMA))}", file=source.file, line=line,
                            element=tag)
        ctx = _Ctx(source.file, canon, attrs, line, names)
        a = _attributes(ctx)
        kind = _ID_KIND.get(canon)
        if kind:
            key = (kind, a["id"])
            if key in seen:
                raise ctx.error(f"duplicate {kind} id {a['id']} (first defined on line "
                                f"{seen[key]})", "id")
            seen[key] = line
        if canon == "Units":
            model.units = {k: a[k] for k in ("mass", "length", "time", "force")}
            model.force_scale = un.force_scale(**model.units)
            model.has_units = True
        elif canon == "Force_Gravity":
            model.gravity = np.array([a["grav_x"], a["grav_y"], a["grav_z"]])
        elif canon == "Reference_Marker":
            markers_raw[a["id"]] = (ctx, a)
        elif canon in ("Body_Rigid", "Body_Point"):
            bodies_raw.append((ctx, a))
        elif canon == "Param_Static":
            model.static = Static(**{k: a[k] for k in SCHEMA["Param_Static"] if k != "label"})
        elif canon == "Param_Transient":
            if a["max_step_growth"] is not None and a["max_step_growth"] <= 1:
                raise ctx.error(f"got {a['max_step_growth']:g}; expected a value > 1",
                                "max_step_growth")
            if a["nonlin_conv_coef"] is not None and a["nonlin_conv_coef"] >= 1:
                raise ctx.error(f"got {a['nonlin_conv_coef']:g}; expected a value in (0, 1)",
                                "nonlin_conv_coef")
            model.transient = Transient(**{f.name: a[f.name]
                                           for f in dataclasses.fields(Transient)})
        elif canon == "Simulate":
            sim_t = _simulate(ctx, a, model, sim_t)
        elif canon == "Stop":
            break
        else:
            later.append((ctx, a))
    _bodies(model, bodies_raw, markers_raw)
    for cmd in model.commands:
        if cmd.analysis == "QUASI-STATIC" and model.static.method == "MKEAM":
            raise DeckError("MKEAM does not do quasi-static analyses (seed 004); use FIM_D or "
                            "FIM_S in Param_Static", file=source.file, line=cmd.line,
                            element="Simulate", attribute="analysis_type")
    for ctx, a in later:
        _force_like(model, ctx, a)
    _check_references(model)
    if not model.commands:
        model.commands.append(Simulate("TRANSIENT", 1.0, 0.01))
        model.default_command = True
    return model


def _simulate(ctx, a, model, t_prev):
    if a["analysis_type"] == "STATIC":
        # an equilibrium at the current time, or at end_time when given
        given = [k for k in ("duration", "print_interval", "num_step", "print_increment")
                 if a[k] is not None]
        if given:
            raise ctx.error("a Static analysis takes no duration or output interval", given[0])
        end = t_prev if a["end_time"] is None else a["end_time"]
        if end < t_prev:
            raise ctx.error(f"end_time {end:g} is before the current time {t_prev:g}",
                            "end_time")
        model.commands.append(Simulate("STATIC", end, 0.0, ctx.line))
        return end
    if a["start_time"] is not None and abs(a["start_time"] - t_prev) > 1e-12:
        raise ctx.error(f"start_time must equal the time the previous command ended "
                        f"({t_prev:g})", "start_time")
    if (a["end_time"] is None) == (a["duration"] is None):
        raise ctx.error("give exactly one of end_time and duration", "end_time")
    end = a["end_time"] if a["end_time"] is not None else t_prev + a["duration"]
    if end <= t_prev:
        raise ctx.error(f"end_time {end:g} must be after the start time {t_prev:g}", "end_time")
    given = [k for k in ("print_interval", "num_step", "print_increment") if a[k] is not None]
    if len(given) > 1:
        raise ctx.error("give one of print_interval and num_step", given[1])
    if a["print_interval"] is not None:
        dt = a["print_interval"]
    elif a["num_step"] is not None:
        dt = (end - t_prev) / a["num_step"]
    else:
        dt = (end - t_prev) / 100.0
    model.commands.append(Simulate(a["analysis_type"], end, dt, ctx.line))
    return end


def _bodies(model, bodies_raw, markers_raw):
    ground_ids = set()
    for ctx, a in bodies_raw:
        ctx.id = a["id"]
        if ctx.tag == "Body_Rigid" and a["isground"]:
            ground_ids.add(a["id"])
            model.bodies[a["id"]] = Body(a["id"], "ground", label=a["label"])
    # markers: global frames, resolving rm_id chains
    frames = {}

    def frame(mid, stack=()):
        if mid in frames:
            return frames[mid]
        ctx, a = markers_raw[mid]
        ctx.id = mid
        R = _orientation(ctx, a)
        p = np.array([a["pos_x"], a["pos_y"], a["pos_z"]])
        if a["rm_id"] is not None:
            if a["rm_id"] not in markers_raw:
                raise ctx.error(f"rm_id {a['rm_id']} is not a Reference_Marker", "rm_id")
            if a["rm_id"] in stack:
                raise ctx.error("rm_id chain refers back to this marker", "rm_id")
            p0, R0 = frame(a["rm_id"], stack + (mid,))
            p, R = p0 + R0 @ p, R0 @ R
        frames[mid] = (p, R)
        return frames[mid]

    for mid, (_, a) in markers_raw.items():
        p, R = frame(mid)
        model.markers[mid] = Marker(mid, a["body_id"], p, R, a["label"])

    def marker_of(ctx, a, key):
        mid = a[key]
        if mid is None:
            return None
        if mid not in model.markers:
            raise ctx.error(f"marker {mid} does not exist", key)
        if model.markers[mid].body != a["id"]:
            raise ctx.error(f"marker {mid} belongs to body {model.markers[mid].body}, not to "
                            f"this body", key)
        return model.markers[mid]

    for ctx, a in bodies_raw:
        ctx.id = a["id"]
        if ctx.tag == "Body_Rigid" and a["isground"]:
            continue
        if a["cg_id"] is None:
            raise ctx.error("missing required attribute (the centre-of-mass marker)", "cg_id")
        if a["mass"] is None:
            raise ctx.error("missing required attribute", "mass")
        cg = marker_of(ctx, a, "cg_id")
        vel = np.array([a["v_ic_x"], a["v_ic_y"], a["v_ic_z"]])
        if ctx.tag == "Body_Point":
            model.bodies[a["id"]] = Body(a["id"], "point", a["mass"], None, cg.pos.copy(),
                                         np.eye(3), vel, np.zeros(3), a["label"])
            continue
        im = marker_of(ctx, a, "im_id") or cg
        marker_of(ctx, a, "lprf_id")
        Iim = np.array([[a["inertia_xx"], a["inertia_xy"], a["inertia_xz"]],
                        [a["inertia_xy"], a["inertia_yy"], a["inertia_yz"]],
                        [a["inertia_xz"], a["inertia_yz"], a["inertia_zz"]]])
        ev = np.linalg.eigvalsh(Iim)
        if ev.min() <= 0 or ev[2] > ev[0] + ev[1] + 1e-12 * ev[2]:
            raise ctx.error("inertia tensor must be positive definite and satisfy the "
                            "triangle inequality", "inertia_xx")
        Rb = cg.rot.T @ im.rot      # im axes in the body (cg) frame
        model.bodies[a["id"]] = Body(a["id"], "rigid", a["mass"], Rb @ Iim @ Rb.T,
                                     cg.pos.copy(), cg.rot.copy(), vel,
                                     np.array([a["w_ic_x"], a["w_ic_y"], a["w_ic_z"]]),
                                     a["label"])
    for mid, (ctx, a) in markers_raw.items():
        ctx.id = mid
        if a["body_id"] not in model.bodies:
            raise ctx.error(f"body {a['body_id']} does not exist (declare it with Body_Rigid, "
                            "Body_Point or a ground Body_Rigid isground=\"TRUE\")", "body_id")


def _parsed(val):
    return val if val is None else val[0]


def _reject_usersub(ctx, a):
    if a.get("type") == "USERSUB":
        if a.get("interpreter") == "MATLAB":
            raise ctx.error("MATLAB user subroutines are not supported; use a C shared "
                            "library or a Python script", "interpreter")
        raise ctx.error("type USERSUB is not supported yet; use type EXPRESSION", "type")


def _force_like(model, ctx, a):
    ctx.id = a.get("id")
    tag = ctx.tag
    if tag == "Force_Penalty":
        _reject_usersub(ctx, a)
        if a["expr"] is None:
            raise ctx.error("missing required attribute for type EXPRESSION", "expr")
        model.penalties[a["id"]] = Penalty(a["id"], a["expr"][0], a["expr"][1], a["penalty"],
                                           a["penalty1"], a["unilateral"],
                                           a["smoothing_factor"], a["label"])
        model._where[("penalty", a["id"])] = ctx
    elif tag == "Force_Scalar_TwoBody":
        if a["usrsub_dll_name"] or a["script_name"]:
            _reject_usersub(ctx, {"type": "USERSUB", "interpreter": a["interpreter"]})
        given = [k for k in ("expr", "val_expression", "val") if a[k] is not None]
        if len(given) != 1:
            raise ctx.error("give exactly one of expr, val_expression and val", "expr")
        val = a[given[0]]
        if given[0] == "val":
            val = (("num", val), repr(val))
        for key in ("i_marker_id", "j_marker_id"):
            if a[key] not in model.markers:
                raise ctx.error(f"marker {a[key]} does not exist", key)
        model.sforces[a["id"]] = ScalarForce(a["id"], a["type"] == "TORQUE", a["i_marker_id"],
                                             a["j_marker_id"], val[0], val[1], a["label"])
        model._where[("sforce", a["id"])] = ctx
    elif tag == "Reference_Variable":
        model.variables[a["id"]] = Variable(a["id"], a["expr"][0], a["expr"][1], a["label"])
        model._where[("variable", a["id"])] = ctx
    elif tag == "Sensor_Event":
        _reject_usersub(ctx, a)
        if a["expr"] is None:
            raise ctx.error("missing required attribute for type EXPRESSION", "expr")
        zc = a["zero_crossing"]
        if zc is not None and not 0 < zc < 1:
            raise ctx.error(f"got {zc:g}; expected 0 < zero_crossing < 1", "zero_crossing")
        compare = "LT" if a["compare"] == "LE" else a["compare"]
        model.sensors[a["id"]] = Sensor(a["id"], a["expr"][0], a["expr"][1], a["value"], compare,
                                        a["error_tol"], a["evaluate_id"], a["dt"],
                                        a["stepsize"], zc, a["hmax"], a["halt"], a["print"],
                                        a["restart"], a["verbose"], a["return"], a["label"])
        model._where[("sensor", a["id"])] = ctx
    elif tag == "Sensor_Evaluate":
        _reject_usersub(ctx, a)
        if a["expr"] is None:
            raise ctx.error("missing required attribute for type EXPRESSION", "expr")
        model.evaluates[a["id"]] = Evaluate(a["id"], a["expr"][0], a["expr"][1], a["label"])
        model._where[("evaluate", a["id"])] = ctx
    elif tag == "Post_Request":
        exprs = [a[f"expr{k}"] for k in range(1, 9)]
        model.requests[a["id"]] = Request(a["id"], [_parsed(e) for e in exprs],
                                          [e[1] if e else None for e in exprs],
                                          [a[f"name{k}"] for k in range(1, 9)], a["label"])
        model._where[("request", a["id"])] = ctx


def _check_references(model):
    """Every id an expression names must exist; penalty g must depend on displacements only."""
    tables = {"marker": model.markers, "variable": model.variables,
              "penalty": model.penalties, "sforce": model.sforces,
              "evaluate": model.evaluates}
    where = model._where
    items = []
    for p in model.penalties.values():
        items.append((("penalty", p.id), "expr", p.expr))
    for s in model.sforces.values():
        items.append((("sforce", s.id), "expr", s.expr))
    for v in model.variables.values():
        items.append((("variable", v.id), "expr", v.expr))
    for r in model.requests.values():
        for k, e in enumerate(r.exprs):
            if e is not None:
                items.append((("request", r.id), f"expr{k + 1}", e))
    for se in model.sensors.values():
        items.append((("sensor", se.id), "expr", se.expr))
        if se.evaluate_id is not None and se.evaluate_id not in model.evaluates:
            ctx = where[("sensor", se.id)]
            ctx.id = se.id
            raise ctx.error(f"Sensor_Evaluate {se.evaluate_id} does not exist", "evaluate_id")
    for ev in model.evaluates.values():
        items.append((("evaluate", ev.id), "expr", ev.expr))
    for key, attr, tree in items:
        ctx = where[key]
        ctx.id = key[1]
        for kind, ids in ex.references(tree).items():
            for i in sorted(ids):
                if i not in tables[kind]:
                    raise ctx.error(f"the expression refers to {kind} id {i}, which does not "
                                    "exist", attr)
    # variable cycles and penalty dependence on velocities
    for key, attr, tree in items:
        ctx = where[key]
        ctx.id = key[1]
        try:
            dyn = _dynamic(model, tree, ())
        except _Cycle as cyc:
            raise ctx.error(f"VARVAL cycle through variables {cyc.args[0]}", attr) from None
        if key[0] == "penalty" and dyn:
            raise ctx.error("a penalty constraint g(q, t) may use displacement measures only "
                            f"(found {dyn}); velocities enter through penalty1", attr)


class _Cycle(Exception):
    pass


_DYNAMIC = {"VX", "VY", "VZ", "VM", "VR", "ACCX", "ACCY", "ACCZ", "WX", "WY", "WZ", "PFORCE",
            "SFORCE"}


def _dynamic(model, node, stack):
    """Return the name of a velocity-dependent function used by the tree, or None."""
    tag = node[0]
    if tag == "neg":
        return _dynamic(model, node[1], stack)
    if tag == "bin":
        return _dynamic(model, node[2], stack) or _dynamic(model, node[3], stack)
    if tag == "call":
        name, args = node[1], node[2]
        if name == "VARVAL":
            vid = int(args[0][1])
            if vid in stack:
                raise _Cycle(" -> ".join(map(str, stack + (vid,))))
            return _dynamic(model, model.variables[vid].expr, stack + (vid,))
        if name in _DYNAMIC:
            found = name
            if name in ("PFORCE", "SFORCE"):
                table = model.penalties if name == "PFORCE" else model.sforces
                _dynamic(model, table[int(args[0][1])].expr, stack)
            return found
        if name not in ex.ID_ARGS:
            for a in args:
                r = _dynamic(model, a, stack)
                if r:
                    return r
    return None
