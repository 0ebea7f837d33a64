"""A deck's elements written as an Adams dataset (.adm) and its command file (.acf).

Longer than 420 lines because it is the Adams reader's table read backwards: one small
translation per element (thirty), then the dataset's text (lines packed to 80 columns where
a statement may break, exact numbers, quoting).

Each element becomes the statement pysolver/deck/adams_statements.py reads back into the same
element, attribute for attribute: numbers with their shortest exact digits (``repr``),
markers placed as the deck placed them (every part's frame is the global frame, so QP is
the marker's place and REULER its angles; a marker given by its axes gets ZP/XP when they
give those axes exactly, else REULER, the same to rounding; a marker whose rm_id is on
another body, which Adams' RM cannot name, is placed in its part's frame instead), the
elements Adams has no statement for as pysolver's extension statements (PFORCE, LOADCONTROL,
SENSOR_EVALUATE, ...), and the attributes Adams has no keyword for as pysolver's extension
keywords (docs/adams.md, "pysolver extensions"). The statements (:class:`Statement`) are also
what the msolve class script writer (pysolver/convert.py) writes from.
"""
import dataclasses
import re

import numpy as np

from ..errors import DeckError
from ..rotations import angles_313, rot_313, rot_321, rot_from_e
from . import usersubs
from .adams import axes_from_points
from .adams_statements import JPRIM_TYPES
from .msolve import JOINT_IC_KEYS
from .requests import FORCE_NAMES, elemental_texts
from .tokens import _TOKEN
from .writer import relocate, typed

#: Lines are kept to Adams' 80 columns where a break is allowed.
WIDTH = 80


class Function(str):
    """An expression: written after its keyword and ended by a backslash."""


class Raw(str):
    """Text a statement kept as written reads back as written (GRAPHICS, RESOUTPUT): a
    plain token (a number too) goes bare, anything else in quotes."""


@dataclasses.dataclass(frozen=True)
class Ref:
    """A reference to another element: its kind (marker, body, joint, evaluate) and id."""
    kind: str
    id: int


@dataclasses.dataclass
class Statement:
    """One statement: name, id (None for UNITS/ and the like), arguments [(KEYWORD, value)]
    (value None: a flag; a number, a list, a str, a Function or a Ref), the label (written
    as Adams View's ``! adams_view_name=`` comment above it), and the deck line it comes
    from."""
    name: str
    id: object
    args: list
    label: str = ""
    line: object = None
    file: object = None

    def error(self, message, attribute=None):
        return DeckError(message, file=self.file, line=self.line, element=self.name, id=self.id,
                         attribute=attribute)


def statements(elements, model, file, out_dir=None):
    """(dataset statements, command statements) of a deck's elements.

    Parameters
    ----------
    elements : list of (tag, attrs, line, names)
        The deck as read (pysolver.deck.loader.deck_elements).
    model : pysolver.Model
        The same deck loaded (which body a marker is on, a coupler's coordinates, a
        spline's numbers).
    file : str
        The deck's file (errors name it; user subroutine files are relative to it).
    out_dir : str, optional
        Where the output goes: user subroutine files are named relative to it.
    """
    els = typed(elements, file)
    dataset, commands = [], []
    for k, el in enumerate(els):
        try:
            out = _TRANSLATE[el.tag](el, model, els, k)
        except ValueError as err:
            raise DeckError(str(err), file=el.file, line=el.line, element=el.tag,
                            id=el.a.get("id")) from None
        for st in out:
            st.line, st.file = el.line, el.file
            _subroutine(st, el, file, out_dir)
            (commands if st.name in ("SIMULATE", "STOP") else dataset).append(st)
    return dataset, commands


# ---- one translation per element ---------------------------------------------------------
def _args(el, pairs):
    """[(KEYWORD, value)] of the attributes the element gave, by (attribute, KEYWORD)."""
    return [(key, el.a[attr]) for attr, key in pairs if attr in el.given]


def _flags(el, pairs):
    """[(FLAG, None)] of the boolean attributes set, by (attribute, FLAG)."""
    return [(key, None) for attr, key in pairs if el.a.get(attr) is True]


def _marker_ref(el, attr, key):
    return [(key, Ref("marker", el.a[attr]))] if attr in el.given else []


def _label(el):
    return el.a.get("label") or ""


#: pysolver's unit names Adams spells otherwise (Adams Solver C++'s UNITS statement).
_ADAMS_UNITS = {"KILONEWTON": "KNEWTON", "MEGAGRAM": "TONNE", "MILLISECOND": "MILLISECONDS"}


def _units(el, model, els, k):
    names = _ADAMS_UNITS
    return [Statement("UNITS", None, [(key.upper(), names.get(el.a[key], el.a[key]))
                                      for key in ("force", "mass", "length", "time")
                                      if key in el.given], _label(el))]


def _gravity(el, model, els, k):
    return [Statement("ACCGRAV", None, _args(el, (("grav_x", "IGRAV"), ("grav_y", "JGRAV"),
                                                  ("grav_z", "KGRAV"))), _label(el))]


def _part(el, model, els, k):
    if el.a["isground"]:
        return [Statement("PART", el.a["id"], [("GROUND", None)], _label(el))]
    args = _args(el, (("mass", "MASS"),))
    for attr, key in (("cg_id", "CM"), ("im_id", "IM"), ("lprf_id", "LPRF")):
        args += _marker_ref(el, attr, key)
    ip = [el.a[f"inertia_{c}"] for c in ("xx", "yy", "zz", "xy", "xz", "yz")]
    if el.given & {"inertia_xy", "inertia_xz", "inertia_yz"}:
        args.append(("IP", ip))
    elif el.given & {"inertia_xx", "inertia_yy", "inertia_zz"}:
        args.append(("IP", ip[:3]))
    args += _velocities(el, _spin(el, model))
    return [Statement("PART", el.a["id"], args, _label(el))]


def _velocities(el, spin=None):
    """VX.. (WX.. of a part: `spin`), then VM (and WM)."""
    args = _args(el, [(f"v_ic_{c}", f"V{c.upper()}") for c in "xyz"])
    if spin is None:
        return args + _marker_ref(el, "vm_id", "VM")
    args += spin[0] + _marker_ref(el, "vm_id", "VM")
    return args + ([("WM", Ref("marker", spin[1]))] if spin[1] is not None else [])


def _spin(el, model):
    """([(WX.., value)], WM or None) of a part. Adams reads WX.. along the CM marker's axes
    without WM (the CM is its default WM), MotionSolve's w_ic_* about the global axes without
    wm_id: a spin about the global axes of a part whose CM marker is turned is written as
    the body's own components, the numbers the loaded model holds."""
    pairs = [(f"w_ic_{c}", f"W{c.upper()}") for c in "xyz"]
    wm = el.a["wm_id"] if "wm_id" in el.given else None
    if wm is None and el.given & {"w_ic_x", "w_ic_y", "w_ic_z"} and \
            not np.array_equal(model.markers[el.a["cg_id"]].rot, np.eye(3)):
        omega = model.bodies[el.a["id"]].omega
        return [(key, float(w)) for (_, key), w in zip(pairs, omega)], None
    return _args(el, pairs), (None if wm == el.a["cg_id"] else wm)


def _point(el, model, els, k):
    args = _args(el, (("mass", "MASS"),)) + _marker_ref(el, "cg_id", "CM") + _velocities(el)
    return [Statement("POINT_MASS", el.a["id"], args, _label(el))]


_MATRIX = ("a00", "a10", "a20", "a01", "a11", "a21", "a02", "a12", "a22")


def _marker(el, model, els, k):
    a = el.a
    on = "POINT_MASS" if model.bodies[a["body_id"]].kind == "point" else "PART"
    args = [(on, Ref("body", a["body_id"]))]
    floating = _flags(el, (("floating", "FLOATING"),))
    if "rm_id" in el.given and model.markers[a["rm_id"]].body != a["body_id"]:
        return [Statement("MARKER", a["id"], args + _in_part(el, model, els) + floating,
                          _label(el))]
    qp = [a["pos_x"], a["pos_y"], a["pos_z"]]
    if el.given & {"pos_x", "pos_y", "pos_z"}:
        args.append(("QP", qp))
    if el.given & {"psi", "theta", "phi"}:
        args.append(("REULER", [_angle(a, c) for c in ("psi", "theta", "phi")]))
    elif el.given & {"yaw", "pitch", "roll"}:
        args.append(("YPR", [_angle(a, c) for c in ("yaw", "pitch", "roll")]))
    elif el.given & {"e0", "e1", "e2", "e3"}:
        args.append(("EP", [a[f"e{c}"] for c in range(4)]))
    elif el.given & set(_MATRIX):
        args += _axes(qp, [a[c] for c in _MATRIX])
    args += _marker_ref(el, "rm_id", "RM") + floating
    return [Statement("MARKER", a["id"], args, _label(el))]


def _in_part(el, model, els):
    """QP and axes of a marker whose rm_id is a marker of another body, which Adams' RM
    cannot name (RM is a marker of the same part: docs/adams.md, "Placement"): its global
    place (the part's frame is the global frame) and its global axes, given as the one marker
    of its rm_id chain whose own angles make exactly those axes gives them (REULER, YPR or
    EP as written), else as a marker given by its axes (_axes: ZP/XP or REULER)."""
    marker = model.markers[el.a["id"]]
    qp = [float(v) for v in marker.pos]
    args = [("QP", qp)] if any(qp) or np.signbit(qp).any() else []
    if np.array_equal(marker.rot, np.eye(3)):
        return args
    markers = {e.a["id"]: e for e in els if e.tag == "Reference_Marker"}
    mid, seen = el.a["id"], set()
    while mid is not None and mid not in seen:       # the loader refused a loop
        seen.add(mid)
        own = _own_axes(markers[mid])
        if own is not None and np.array_equal(own[1], marker.rot):
            return args + [own[0]]
        mid = markers[mid].a["rm_id"]
    return args + _axes(qp, marker.rot.T.ravel().tolist())


def _own_axes(el):
    """((keyword, numbers), axes) of a marker's own angles, the axes as deck/bodies.py makes
    them of the numbers; None for a marker given by none or by the nine numbers of its
    axes."""
    a = el.a
    if el.given & {"psi", "theta", "phi"}:
        angles = [_angle(a, c) for c in ("psi", "theta", "phi")]
        return ("REULER", angles), rot_313(*angles)
    if el.given & {"yaw", "pitch", "roll"}:
        angles = [_angle(a, c) for c in ("yaw", "pitch", "roll")]
        return ("YPR", angles), rot_321(*angles)
    if el.given & {"e0", "e1", "e2", "e3"}:
        e = np.array([a[f"e{c}"] for c in range(4)])
        return ("EP", e.tolist()), rot_from_e(e / np.linalg.norm(e))
    return None


def _angle(a, key):
    return 0.0 if a[key] is None else a[key]        # an angle left out is 0


def _axes(qp, columns):
    """ZP and XP (Adams' points on z and in the x-z plane), taken on the axes as given or on
    the rotation the loader makes of them (deck/bodies.py: the nearest rotation), when the
    dataset reader and the loader make exactly that rotation of them again, else REULER: its
    3-1-3 angles, the same to rounding (a few units in the last place)."""
    axes = _nearest(np.array(columns, float).reshape(3, 3).T)   # what the loader makes
    origin = np.array(qp, float)
    for near in (np.array(columns, float).reshape(3, 3).T, axes):
        zp, xp = origin + near[:, 2], origin + near[:, 0]
        try:
            back = _nearest(axes_from_points(zp - origin, xp - origin))
        except ValueError:
            continue
        if np.array_equal(back, axes):        # (a -0.0 for a 0.0 is equal)
            return [("ZP", zp.tolist()), ("XP", xp.tolist())]
    return [("REULER", list(angles_313(axes)))]


def _nearest(A):
    """The rotation deck/bodies.py makes of nine numbers (the nearest, by the SVD)."""
    u, _, vt = np.linalg.svd(A)
    return u @ vt


_JOINT_NAMES = {"CONSTANT_VELOCITY": "CONVEL", "RACK_PINION": "RACKPIN"}


def _joint(el, model, els, k):
    kind = el.a["type"]
    name = "JPRIM" if kind in JPRIM_TYPES else "JOINT"
    args = [(_JOINT_NAMES.get(kind, kind), None)] + _marker_ref(el, "i_marker_id", "I") + \
        _marker_ref(el, "j_marker_id", "J") + _args(el, (("pitch", "PITCH"),
                                                         ("pitch_diameter", "PD")))
    for key, coord in JOINT_IC_KEYS.get(kind, {}).items():       # IC, or ICTRAN and ICROT
        values = [el.a[f"ic_{coord}_{n}"] for n in ("disp", "vel")
                  if el.a.get(f"ic_{coord}_{n}") is not None]
        if values:
            args.append((key, values if len(values) > 1 else values[0]))
    return [Statement(name, el.a["id"], args + _flags(el, (("is_virtual", "VIRTUAL"),)),
                      _label(el))]


_VAL = {"D": "DISPLACEMENT", "V": "VELOCITY", "A": "ACCELERATION"}


def _motion(el, model, els, k):
    a = el.a
    if el.tag == "Motion_Joint":
        args = [("JOINT", Ref("joint", a["joint_id"]))]
        if "motion_type" in el.given:
            args.append(({"R": "ROTATION", "T": "TRANSLATION"}[a["motion_type"]], None))
    else:
        args = _marker_ref(el, "i_marker_id", "I") + _marker_ref(el, "j_marker_id", "J") + \
            [(a["direction"], None)]
    if "val_type" in el.given:
        args.append((_VAL[a["val_type"]], None))
    args += _function(el, "expr") + _args(el, (("ic_disp", "ICDISP"), ("ic_vel", "ICVEL")))
    return [Statement("MOTION", a["id"], args, _label(el))]


def _function(el, attr, key="FUNCTION"):
    return [(key, Function(el.a[attr]))] if attr in el.given else []


def _gcon(el, model, els, k):
    args = _function(el, "expr") + _marker_ref(el, "i_marker_id", "I") + \
        _flags(el, (("is_virtual", "VIRTUAL"),))
    return [Statement("GCON", el.a["id"], args, _label(el))]


def _coupler(el, model, els, k):
    a = el.a
    joints = [Ref("joint", a[f"joint{n}_id"]) for n in (1, 2, 3) if f"joint{n}_id" in el.given]
    args = [("JOINTS", joints)]
    if el.given & {"freedom_1", "freedom_2", "freedom_3"}:
        args.append(("TYPE", ":".join(model.couplers[a["id"]].freedoms)))
    args.append(("SCALES", [float(v) for v in a["coefficients"].replace(",", " ").split()]))
    return [Statement("COUPLER", a["id"], args + _flags(el, (("is_virtual", "VIRTUAL"),)),
                      _label(el))]


def _sforce(el, model, els, k):
    a = el.a
    args = _marker_ref(el, "i_marker_id", "I") + _marker_ref(el, "j_marker_id", "J")
    args.append(("ROTATION" if a["type"] == "TORQUE" else "TRANSLATION", None))
    args += _flags(el, (("is_action_only", "ACTIONONLY"),))
    if "val" in el.given:
        args.append(("FUNCTION", Function(repr(a["val"]))))
    args += _function(el, "expr") + _function(el, "val_expression")
    return [Statement("SFORCE", a["id"], args, _label(el))]


def _springdamper(el, model, els, k):
    rot = el.a["type"] == "ROTATIONAL"
    keys = ("KT", "CT", "ANGLE", "TORQUE") if rot else ("K", "C", "LENGTH", "FORCE")
    args = _marker_ref(el, "i_marker_id", "I") + _marker_ref(el, "j_marker_id", "J") + \
        [("ROTATION" if rot else "TRANSLATION", None)] + \
        _args(el, zip(("stiffness", "damping", "length", "preload"), keys))
    return [Statement("SPRINGDAMPER", el.a["id"], args, _label(el))]


_VECTOR = {"FORCEONLY": ("VFORCE", "f"), "TORQUEONLY": ("VTORQUE", "t"),
           "FORCEANDTORQUE": ("GFORCE", "ft")}


def _vforce(el, model, els, k):
    a = el.a
    name, leads = _VECTOR[a["type"]]
    if el.tag == "Force_Vector_OneBody":
        args = _marker_ref(el, "marker_id", "I") + [("ACTIONONLY", None)]
    else:
        args = _marker_ref(el, "i_marker_id", "I") + \
            _marker_ref(el, "j_floating_marker_id", "JFLOAT")
    args += _marker_ref(el, "ref_marker_id", "RM")
    for lead in leads:
        for c in "xyz":
            args += _function(el, f"{lead}{c}_expression", f"{lead.upper()}{c.upper()}")
    return [Statement(name, a["id"], args, _label(el))]


def _bushing(el, model, els, k):
    args = _marker_ref(el, "i_marker_id", "I") + _marker_ref(el, "j_marker_id", "J")
    for key, attrs in (("K", ("kx", "ky", "kz")), ("C", ("cx", "cy", "cz")),
                       ("KT", ("ktx", "kty", "ktz")), ("CT", ("ctx", "cty", "ctz")),
                       ("FORCE", ("preload_x", "preload_y", "preload_z")),
                       ("TORQUE", ("preload_tx", "preload_ty", "preload_tz"))):
        if el.given & set(attrs):
            args.append((key, [el.a[c] for c in attrs]))
    return [Statement("BUSHING", el.a["id"], args, _label(el))]


def _columns(el, prefix):
    """The 36 entries of matrix `prefix` (k, c) column by column (Adams' KMATRIX order), or
    None when the element gave none of them."""
    keys = [f"{prefix}{r}{c}" for c in range(1, 7) for r in range(1, 7)]
    return [el.a[key] for key in keys] if el.given & set(keys) else None


def _six(el, prefix, keys=("x", "y", "z", "tx", "ty", "tz")):
    attrs = [f"{prefix}{c}" for c in keys]
    return [el.a[c] for c in attrs] if el.given & set(attrs) else None


def _field(el, model, els, k):
    args = _marker_ref(el, "i_marker_id", "I") + _marker_ref(el, "j_marker_id", "J")
    for key, value in (("KMATRIX", _columns(el, "k")), ("CMATRIX", _columns(el, "c")),
                       ("CRATIO", el.get("cratio")), ("LENGTH", _six(el, "length_")),
                       ("FORCE", _six(el, "preload_"))):
        if value is not None:
            args.append((key, value))
    return [Statement("FIELD", el.a["id"], args, _label(el))]


def _beam(el, model, els, k):
    args = _marker_ref(el, "i_marker_id", "I") + _marker_ref(el, "j_marker_id", "J") + \
        _args(el, (("length", "LENGTH"), ("ixx", "IXX"), ("iyy", "IYY"), ("izz", "IZZ"),
                   ("area", "AREA"), ("asy", "ASY"), ("asz", "ASZ"), ("e", "EMODULUS"),
                   ("g", "GMODULUS"), ("cratio", "CRATIO")))
    damping = _columns(el, "c")
    if damping is not None:
        square = np.reshape(damping, (6, 6))           # columns as rows: C transposed
        col, row = np.triu_indices(6)
        # Adams' 21 numbers, the lower half column by column, when C is symmetric
        half = [float(square[c, r]) for c, r in zip(col, row)]
        args.append(("CMATRIX", half if np.array_equal(square, square.T) else damping))
    for key, value in (("FORCE", _six(el, "preload_", ("x", "y", "z"))),
                       ("TORQUE", _six(el, "preload_", ("tx", "ty", "tz")))):
        if value is not None:
            args.append((key, value))
    return [Statement("BEAM", el.a["id"], args, _label(el))]


def _penalty(el, model, els, k):
    args = _function(el, "expr") + _args(el, (("penalty", "PENALTY"),
                                              ("penalty1", "PENALTY1"),
                                              ("smoothing_factor", "SMOOTHING_FACTOR"))) + \
        _flags(el, (("unilateral", "UNILATERAL"),))
    return [Statement("PFORCE", el.a["id"], args, _label(el))]


def _loadcontrol(el, model, els, k):
    a = el.a
    args = []
    for attr in ("velocity", "material", "direction", "maxvelocity", "load_function", "kp",
                 "ki", "smooth", "updatetime", "median_window", "load"):
        if attr not in el.given:
            continue
        value = a[attr]
        if attr == "material":
            value = Ref("body", value)
        elif attr == "load_function":
            value = Function(value)
        elif attr == "direction":
            value = int(value)
        elif isinstance(value, str):
            value = value.upper()
        args.append((attr.upper(), value))
    return [Statement("LOADCONTROL", a["id"] if "id" in el.given else None, args,
                      _label(el))]


def _variable(el, model, els, k):
    args = _function(el, "expr") + _args(el, (("initial_value", "IC"),))
    return [Statement("VARIABLE", el.a["id"], args, _label(el))]


def _spline(el, model, els, k):
    sp = model.splines[el.a["id"]]
    args = [("X", list(sp.x))]
    if sp.z:
        ys = np.asarray(sp.y, float).reshape(len(sp.z), len(sp.x))
        args += [("Y", [z, *row]) for z, row in zip(sp.z, ys.tolist())]
    else:
        args.append(("Y", list(sp.y)))
    if el.a["linear_extrap"] or el.a["linear_extrapolate"]:
        args.append(("LINEAR_EXTRAPOLATE", None))
    return [Statement("SPLINE", el.a["id"], args, _label(el))]


def _sensor(el, model, els, k):
    a = el.a
    args = _function(el, "expr") + _args(el, (("value", "VALUE"), ("error_tol", "ERROR")))
    args.append(({"LT": "LE", "LE": "LE"}.get(a["compare"], a["compare"]), None))
    args += _flags(el, (("halt", "HALT"), ("print", "PRINT"), ("restart", "RESTART"),
                        ("return", "RETURN"), ("verbose", "VERBOSE")))
    args += _args(el, (("dt", "DT"), ("stepsize", "STEPSIZE"), ("hmax", "HMAX"),
                       ("zero_crossing", "ZERO_CROSSING")))
    if "evaluate_id" in el.given:
        inline = _inline_evaluate(el, els, k)
        args += [("EVALUATE", Function(inline.a["expr"]))] if inline else \
            [("EVALUATE_ID", Ref("evaluate", a["evaluate_id"]))]
    return [Statement("SENSOR", a["id"], args, _label(el))]


def _inline_evaluate(el, els, k):
    """The Sensor_Evaluate written as the sensor's EVALUATE= (as SENSOR(..., EVALUATE=)
    reads it back): the one just before the sensor, with its id, an expression and no
    label; else None (SENSOR_EVALUATE and EVALUATE_ID)."""
    prev = els[k - 1] if k else None
    if prev is not None and prev.tag == "Sensor_Evaluate" and \
            prev.a["id"] == el.a["id"] == el.a["evaluate_id"] and not _label(prev) and \
            "expr" in prev.given and not _is_user(prev):
        return prev
    return None


_USER_ATTRS = ("usrsub_dll_name", "usrsub_fnc_name", "usrsub_param_string", "script_name",
               "interpreter")


def _is_user(el):
    """The element calls a user subroutine."""
    return el.a.get("type") == "USERSUB" or \
        any(el.a.get(k) is not None for k in _USER_ATTRS) or \
        str(el.a.get("expr") or "").strip().upper().startswith("USER")


def _evaluate(el, model, els, k):
    nxt = els[k + 1] if k + 1 < len(els) else None
    if nxt is not None and nxt.tag == "Sensor_Event" and _inline_evaluate(nxt, els, k + 1):
        return []                       # written as the next sensor's EVALUATE=
    return [Statement("SENSOR_EVALUATE", el.a["id"], _function(el, "expr"), _label(el))]


_REQUESTS = {"MARKER_DISPLACEMENT": "DISPLACEMENT", "MARKER_VELOCITY": "VELOCITY",
             "MARKER_ACCELERATION": "ACCELERATION", "MARKER_FORCE": "FORCE"}


def _request(el, model, els, k):
    a = el.a
    args = []
    if a["type"] == "ELEMENTAL_FORCE":
        # no Adams form of its own: the element's force function in F1..F8, named
        args += [(f"F{n}", Function(t)) for n, t in enumerate(elemental_texts(a), 1)]
        args.append(("CNAMES", [a.get(f"name{n}") or FORCE_NAMES[n - 1] for n in range(1, 9)]))
        return [Statement("REQUEST", a["id"], args + _args(el, (("comment", "COMMENT"),)),
                          _label(el))]
    if a["type"] in _REQUESTS:
        args.append((_REQUESTS[a["type"]], None))
        args += _marker_ref(el, "i_marker_id", "I") + _marker_ref(el, "j_marker_id", "J") + \
            _marker_ref(el, "ref_marker_id", "RM")
    for n in range(1, 9):
        args += _function(el, f"expr{n}", f"F{n}")
    args += _args(el, (("comment", "COMMENT"),))
    named = [n for n in range(1, 9) if f"name{n}" in el.given]
    if named:
        args.append(("CNAMES", [a[f"name{n}"] if f"name{n}" in el.given else ""
                                for n in range(1, max(named) + 1)]))
    return [Statement("REQUEST", a["id"], args, _label(el))]


_INTEGRATOR = (("integr_tol", "ERROR"), ("h_max", "HMAX"), ("h_min", "HMIN"),
               ("h0_max", "HINIT"), ("max_num_steps", "MAX_NUM_STEPS"),
               ("max_step_growth", "MAX_STEP_GROWTH"), ("nonlin_conv_coef", "NONLIN_CONV_COEF"),
               ("dae_constr_tol", "DAE_CONSTR_TOL"))


def _transient(el, model, els, k):
    args = [(el.a["integrator_type"], None)] if "integrator_type" in el.given else []
    return [Statement("INTEGRATOR", None, args + _args(el, _INTEGRATOR), _label(el))]


_STATIC = (("method", "METHOD"), ("max_ke_tol", "MAX_KE_TOL"), ("max_dq_tol", "MAX_DQ_TOL"),
           ("max_num_iter", "MAXIT"), ("max_imbalance", "IMBALANCE"), ("max_error", "ERROR"),
           ("stability", "STABILITY"), ("compliance_delta", "COMPLIANCE_DELTA"),
           ("tlimit", "TLIMIT"), ("alimit", "ALIMIT"))


def _static(el, model, els, k):
    return [Statement("EQUILIBRIUM", None, _args(el, _STATIC), _label(el))]


_ANALYSES = {"TRANSIENT": "DYNAMICS", "STATIC": "STATICS", "QUASI-STATIC": "STATICS",
             "ASSEMBLY": "INITIAL_CONDITIONS"}
_SIMULATE = (("start_time", "START"), ("end_time", "END"), ("duration", "DURATION"),
             ("print_interval", "DTOUT"), ("num_step", "STEPS"),
             ("print_increment", "PRINT_INCREMENT"))


def _simulate(el, model, els, k):
    kind = el.a["analysis_type"]
    args = [(_ANALYSES[kind], None)] + _args(el, _SIMULATE)
    if kind == "QUASI-STATIC" and not el.given & {"duration", "print_interval", "num_step",
                                                  "print_increment"}:
        args.append(("STEPS", 100))     # STATICS with steps is quasi-static (the default 100)
    return [Statement("SIMULATE", None, args)]


def _stop(el, model, els, k):
    return [Statement("STOP", None, [])]


#: Adams' GRAPHICS shapes, written as its flag when a Post_Graphic's type is one of them.
SHAPES = ("CYLINDER", "BOX", "FRUSTUM", "SPHERE", "ELLIPSOID", "CIRCLE", "ARC", "OUTLINE",
           "PLANE", "TORUS", "LINK", "EXTERNAL", "POINT", "FORCE", "SPDP", "BLOCK",
           "REVOLUTION", "EXTRUSION")


def _graphic(el, model, els, k):
    kind = str(el.a["type"])
    args = [(kind, None)] if kind in SHAPES else [("TYPE", kind)]
    args += [(key.upper(), Raw(v)) for key, v in el.raw.items()
             if key not in ("id", "type", "label") and v is not None]
    return [Statement("GRAPHICS", el.a["id"], args, _label(el))]


def _settings(name):
    def translate(el, model, els, k):
        return [Statement(name, None, [(key.upper(), Raw(v)) for key, v in el.raw.items()
                                       if v is not None])]
    return translate


_TRANSLATE = {
    "Units": _units, "Force_Gravity": _gravity, "Body_Rigid": _part, "Body_Point": _point,
    "Reference_Marker": _marker, "Constraint_Joint": _joint, "Constraint_Jprim": _joint,
    "Motion_Marker": _motion, "Motion_Joint": _motion, "Constraint_General": _gcon,
    "Constraint_Coupler": _coupler, "Force_Scalar_TwoBody": _sforce,
    "Force_SpringDamper": _springdamper, "Force_Vector_TwoBody": _vforce,
    "Force_Vector_OneBody": _vforce, "Force_Bushing": _bushing, "Force_Field": _field,
    "Force_Beam": _beam, "Force_Penalty": _penalty,
    "LoadControl": _loadcontrol, "Reference_Variable": _variable, "Reference_Spline": _spline,
    "Sensor_Event": _sensor, "Sensor_Evaluate": _evaluate, "Post_Request": _request,
    "Param_Transient": _transient, "Param_Static": _static, "Simulate": _simulate,
    "Stop": _stop, "Post_Graphic": _graphic, "ResOutput": _settings("RESOUTPUT"),
    "H3DOutput": _settings("H3DOUTPUT"),
}


def _subroutine(st, el, file, out_dir):
    """A user subroutine's keywords: FUNCTION=USER(...) with ROUTINE (name, or
    library::name), and pysolver's SCRIPT and INTERPRETER."""
    if st.name not in ("PFORCE", "SFORCE", "MOTION", "GCON", "VARIABLE", "SENSOR",
                       "SENSOR_EVALUATE", "REQUEST") or not _is_user(el):
        return
    a = el.a
    routine = a.get("usrsub_fnc_name")
    if callable(routine):
        raise DeckError("a routine given as a Python function cannot be written to a file; "
                        "give its name and script instead", file=el.file, line=el.line,
                        element=el.tag, id=a.get("id"), attribute="ROUTINE")
    if a.get("usrsub_dll_name") is not None:
        name = routine or usersubs.CONVENTIONS[el.tag][0]
        routine = f"{relocate(a['usrsub_dll_name'], file, out_dir)}::{name}"
    if a.get("usrsub_param_string") is not None:
        st.args = [(k, v) for k, v in st.args if k != "FUNCTION"]
        st.args.append(("FUNCTION", Function(a["usrsub_param_string"])))
    for key, value in (("ROUTINE", routine), ("INTERPRETER", a.get("interpreter")),
                       ("SCRIPT", a.get("script_name") and
                        relocate(a["script_name"], file, out_dir))):
        if value is not None:
            st.args.append((key, value))


# ---- text --------------------------------------------------------------------------------
def dataset_text(dataset, title, description=""):
    """The .adm text: the title line, the description as comments, the statements, END."""
    lines = [title.replace("\n", " ")]
    # the description as comments (one naming adams_view_name would label a statement)
    lines += [f"! {ln}".rstrip().replace("adams_view_name", "adams view name")
              for ln in description.splitlines()]
    for st in dataset:
        if st.label:
            lines.append(view_name(st))
        lines += statement_lines(st)
    lines.append("END")
    return "\n".join(lines) + "\n"


def command_text(commands, dataset_name, output_name=None):
    """The .acf text: the dataset's name, the output's name (the dataset's when None), the
    commands, STOP."""
    lines = [dataset_name, output_name or dataset_name]
    for st in commands:
        if st.name == "STOP":
            break
        lines += statement_lines(st)
    return "\n".join(lines + ["STOP"]) + "\n"


def view_name(st):
    """The adams_view_name comment line of a statement's label."""
    quote = "'" if "'" not in st.label else '"'
    if quote in st.label or "\n" in st.label or "\r" in st.label:
        raise st.error(f"the label {st.label!r} cannot be written to a dataset's "
                       "adams_view_name comment (it holds both quotes or a line break)",
                       "label")
    return f"! adams_view_name={quote}{st.label}{quote}"


def statement_lines(st):
    """A statement's lines: arguments packed into lines of at most WIDTH columns where
    they can break, continuation lines starting with a comma."""
    lines = [f"{st.name}/{st.id}" if st.id is not None else f"{st.name}/"]
    first = True
    for key, value in st.args:
        pieces, joiner = _pieces(key, value, st)
        whole = joiner.join(pieces)
        sep = "" if first and st.id is None else ", "
        first = False
        if len(lines[-1]) + len(sep) + len(whole) <= WIDTH:
            lines[-1] += sep + whole
            continue
        lines.append(", " + pieces[0])
        for piece in pieces[1:]:
            if len(lines[-1]) + len(joiner) + len(piece) <= WIDTH:
                lines[-1] += joiner + piece
            else:           # a continuation line: the list's next item, or the expression
                lines.append(", " + piece if joiner else "," + piece)
    return lines


def _pieces(key, value, st):
    """(pieces, joiner): the argument's text in the pieces it may break between."""
    if value is None:
        return [key], ""
    if isinstance(value, Function):
        text = function_text(value)
        if "\\" in text or "!" in text:
            raise st.error(f"the expression {text!r} holds a backslash or '!'", key)
        parts = _breaks(text)
        parts[0] = f"{key} = {parts[0]}"
        parts[-1] += "\\"
        return parts, ""
    values = value if isinstance(value, (list, tuple)) else [value]
    texts = [_value(v, st, key) for v in values]
    texts[0] = f"{key} = {texts[0]}"
    return texts, ", "


def _value(v, st, key):
    if isinstance(v, Ref):
        return str(v.id)
    if isinstance(v, (bool, np.bool_)):
        raise AssertionError(key)
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    if isinstance(v, (float, np.floating)):
        return repr(float(v))
    text = str(v)
    if re.fullmatch(r"[A-Za-z_][A-Za-z0-9_.:/\-]*", text) or \
            (isinstance(v, Raw) and re.fullmatch(r"[A-Za-z0-9_.+\-]+", text)):
        return text
    quote = '"' if '"' not in text else "'"
    if quote in text or "\n" in text:
        raise st.error(f"{text!r} holds both quotes or a line break: it cannot be written to "
                       "a dataset", key)
    return quote + text + quote


def function_text(text):
    """An expression as a dataset writes it: on one line (a line break becomes a space, so
    each character keeps its column), numbers with a D exponent written with E (in a
    dataset a trailing D means degrees, as in every deck's expressions: those stay)."""
    text = str(text).strip().translate({ord(c): " " for c in "\n\r\t\f\v"})
    out, pos = [], 0
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if not m or m.end() == pos:
            out.append(text[pos:])
            break
        tok = m.group(0)
        if m.group(1) and tok[-1] not in "dD":      # a trailing D (degrees) stays
            tok = tok.replace("d", "e").replace("D", "e")
        out.append(tok)
        pos = m.end()
    return "".join(out)


def _breaks(text):
    """The expression split where a continuation line may continue it (the dataset
    reader's rule): between tokens inside parentheses, or beside an operator; a piece takes
    the spaces before its token, so no line ends in one."""
    cuts, depth, prev, pos = [], 0, None, 0
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if not m or m.end() == pos:
            break                   # not the expression language: no more cuts
        tok = m.group(m.lastindex)
        op = m.lastindex == 3
        if prev is not None and tok not in (",", ")", ":") and \
                (depth > 0 or prev in ("+", "-", "*", "/", "**", ",", ":")
                 or (op and tok in ("+", "-", "*", "/", "**"))):
            cuts.append(pos)
        depth += (tok == "(") - (tok == ")") if op else 0
        prev = tok if op else ""
        pos = m.end()
    pieces = [text[a:b] for a, b in zip([0] + cuts, cuts + [len(text)])]
    return [p for p in pieces if p]
