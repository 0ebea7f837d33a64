"""Statement functions for Python-format decks, in the style of Adams/MotionSolve.

Longer than 420 lines because it is the statement language itself: one short function per
statement (forty of them), each a table from keywords to XML attributes; split by topic they
would only import each other.

A Python deck is a script that calls these functions::

    from pysolver.msolve import *
    UNITS(MASS="KILOGRAM", LENGTH="MILLIMETER", TIME="SECOND", FORCE="NEWTON")
    PART(1, GROUND=True)
    MARKER(9, PART=2, QP=[0, 1, 0])
    POINT_MASS(2, MASS=1, CM=9)
    PFORCE(1, LABEL="bead", FUNCTION="DY(9)-COSH(DX(9))", PENALTY=1e4, PENALTY1=1e2)
    REQUEST(1, F1="DX(9)", F2="DY(9)")
    INTEGRATOR(ERROR=1e-6)
    SIMULATE(TYPE="TRANSIENT", END=2.0, DTOUT=0.01)

Each call records one element with the same attributes as its XML counterpart, so both
formats build identical models. The import line is optional: ``pysolver.load`` provides the
statements. Keyword names are case-insensitive.
"""
import inspect
import os
import threading

import numpy as np

_STATE = threading.local()

__all__ = ["UNITS", "ACCGRAV", "PART", "POINT_MASS", "MARKER", "PFORCE", "SFORCE", "SPRINGDAMPER",
           "VFORCE", "VTORQUE", "GFORCE", "BUSHING", "FIELD", "BEAM", "GRAPHICS", "SPLINE",
           "MOTION", "JOINT", "JPRIM", "GCON", "COUPLER",
           "LOADCONTROL", "VARIABLE",
           "REQUEST", "INTEGRATOR", "SIMULATE", "STOP", "SENSOR", "SENSOR_EVALUATE", "EQUILIBRIUM",
           "RESOUTPUT", "H3DOUTPUT",
           "py_sysfnc", "py_sysary", "py_syspar", "py_errmes"]

#: User subroutines: ROUTINE= a Python function (or its name in SCRIPT=), SCRIPT=, INTERPRETER=;
#: FUNCTION="USER(p1, ..., pn)" gives its parameters.
_USERSUB = {"ROUTINE": "usrsub_fnc_name", "SCRIPT": "script_name",
            "INTERPRETER": "interpreter", "TYPE": "type"}


#: The public module pysolver.msolve (statements and msolve classes), set when it is imported:
#: the namespace a Python deck runs in.
PUBLIC = None


class _Recorder:
    def __init__(self, file):
        self.file = file
        self.elements = []
        self.models = []            # msolve class Models the script creates
        self.line = None            # the statement's line when the .adm reader calls


def _recorder():
    rec = getattr(_STATE, "rec", None)
    if rec is None:
        raise RuntimeError("pysolver.msolve statements only record inside pysolver.load()")
    return rec


def _line(rec):
    if getattr(rec, "line", None) is not None:     # set by the .adm reader
        return rec.line
    for frame in inspect.stack()[2:]:
        if os.path.abspath(frame.filename) == os.path.abspath(rec.file):
            return frame.lineno
    return None


def _emit(stmt, tag, mapping, id=None, extra=None, keywords=None, **kw):
    """Record element `tag`; mapping: statement keyword -> XML attribute (or a function);
    `extra` attributes the statement implies; `keywords` (attribute -> keyword) names in
    errors attributes the statement leaves out (its defaults)."""
    from ..errors import DeckError
    rec = _recorder()
    line = _line(rec)
    attrs, names = dict(extra or {}), {k: "ROUTINE" for k in extra or {}}
    names.update(keywords or {})
    if id is not None:
        attrs["id"], names["id"] = id, "ID"
    for key, val in kw.items():
        up = key.upper()
        if up not in mapping:
            raise DeckError(f"unknown argument; {stmt} accepts {', '.join(sorted(mapping))}",
                            file=rec.file, line=line, element=stmt, id=id, attribute=up)
        if val is None:
            continue
        target = mapping[up]
        if callable(target):
            try:
                pairs = target(val)
            except Expected as err:
                raise DeckError(f"got {val!r}; expected {err}", file=rec.file, line=line,
                                element=stmt, id=id, attribute=up) from None
            except (TypeError, ValueError):
                raise DeckError(f"got {val!r}; expected a list of numbers", file=rec.file,
                                line=line, element=stmt, id=id, attribute=up) from None
            for k, v in pairs.items():
                attrs[k], names[k] = v, up
        else:
            attrs[target], names[target] = val, up
    rec.elements.append((tag, attrs, line, names))


class Expected(ValueError):
    """A keyword's value is not of its form: the message says what it expects."""


def _vec(keys):
    def split(val):
        vals = list(val)
        if len(vals) != len(keys):
            raise ValueError
        return dict(zip(keys, vals))
    return split


def UNITS(**kw):
    """Units: MASS, LENGTH, TIME, FORCE (names as in the XML Units element)."""
    _emit("UNITS", "Units", {"MASS": "mass", "LENGTH": "length", "TIME": "time",
                             "FORCE": "force", "LABEL": "label"}, **kw)


def ACCGRAV(**kw):
    """Gravity: IGRAV, JGRAV, KGRAV (global x, y, z components), LABEL."""
    _emit("ACCGRAV", "Force_Gravity", {"IGRAV": "grav_x", "JGRAV": "grav_y", "KGRAV": "grav_z",
                                       "LABEL": "label"}, **kw)


def PART(id, **kw):
    """Rigid body (or ground with GROUND=True): MASS, CM, IM, LPRF, IP=[ixx, iyy, izz
    (, ixy, iyz, ixz)] (about IM's origin along its axes, default CM; products as positive
    integrals, ixy = +integral of x*y dm, as Adams defines them), VX VY VZ (global), WX WY WZ
    (in the CM marker's axes, as Adams' PART reads them), VM and WM (markers whose axes VX..
    and WX.. are along instead), LABEL.

    WX.. without WM are recorded with wm_id = CM: the element's w_ic_* without wm_id are
    about the global axes (MotionSolve's Body_Rigid)."""
    def ip(val):
        vals = [float(v) for v in val]
        if len(vals) not in (3, 6):
            raise ValueError
        keys = ["inertia_xx", "inertia_yy", "inertia_zz", "inertia_xy", "inertia_yz",
                "inertia_xz"]
        return dict(zip(keys, vals))
    given = {k.upper(): v for k, v in kw.items()}
    spun = any(given.get(k) is not None for k in ("WX", "WY", "WZ"))
    along_cm = given.get("WM") is None and given.get("CM") is not None
    if spun and along_cm:
        kw = {k: v for k, v in kw.items() if k.upper() != "WM"}
        kw["WM"] = given["CM"]
    _emit("PART", "Body_Rigid", {"GROUND": "isground", "MASS": "mass", "CM": "cg_id",
                                 "IM": "im_id", "LPRF": "lprf_id", "IP": ip, "VX": "v_ic_x",
                                 "VY": "v_ic_y", "VZ": "v_ic_z", "WX": "w_ic_x",
                                 "WY": "w_ic_y", "WZ": "w_ic_z", "VM": "vm_id", "WM": "wm_id",
                                 "LABEL": "label"}, id,
          keywords={"mass": "MASS", "cg_id": "CM", "im_id": "IM", "inertia_xx": "IP"}, **kw)
    if along_cm and not spun:           # WX.. a sweep gives are along CM too (Rates.wm)
        _recorder().elements[-1][3]["#wm"] = given["CM"]


def POINT_MASS(id, **kw):
    """Point body with 3 translational DOF: MASS, CM, VX VY VZ (global, or along the axes of
    the VM marker), LABEL."""
    _emit("POINT_MASS", "Body_Point", {"MASS": "mass", "CM": "cg_id", "VX": "v_ic_x",
                                       "VY": "v_ic_y", "VZ": "v_ic_z", "VM": "vm_id",
                                       "LABEL": "label"}, id, **kw)


def MARKER(id, **kw):
    """Marker: PART, QP=[x, y, z], one of REULER=[psi, theta, phi] (3-1-3),
    YPR=[yaw, pitch, roll] (3-2-1), EP=[e0, e1, e2, e3] or
    AXES=[a00, a10, a20, a01, a11, a21, a02, a12, a22]; RM, FLOATING=True (a floating
    marker: a vector force's JFLOAT, at its I marker), LABEL."""
    _emit("MARKER", "Reference_Marker",
          {"PART": "body_id", "QP": _vec(["pos_x", "pos_y", "pos_z"]),
           "REULER": _vec(["psi", "theta", "phi"]), "YPR": _vec(["yaw", "pitch", "roll"]),
           "EP": _vec(["e0", "e1", "e2", "e3"]),
           "AXES": _vec(["a00", "a10", "a20", "a01", "a11", "a21", "a02", "a12", "a22"]),
           "RM": "rm_id", "FLOATING": "floating", "LABEL": "label"}, id, **kw)


#: The keywords that name a user subroutine, on a statement whose TYPE means something else.
_ROUTINE = {k: v for k, v in _USERSUB.items() if k != "TYPE"}


def _routine_type(kw):
    """type="USERSUB" when the statement names its routine."""
    return {"type": "USERSUB"} if any(k.upper() in _ROUTINE for k in kw) else None


def _usersub(kw, typed=True):
    """A statement with ROUTINE, SCRIPT or INTERPRETER calls a user subroutine."""
    if typed and any(k.upper() in ("ROUTINE", "SCRIPT", "INTERPRETER") for k in kw):
        kw.setdefault("TYPE", "USERSUB")
    return kw


def PFORCE(id, **kw):
    """Penalty force: FUNCTION, PENALTY, PENALTY1, UNILATERAL, SMOOTHING_FACTOR, LABEL;
    ROUTINE (PFOSUB), SCRIPT, INTERPRETER and FUNCTION="USER(...)" for a user subroutine."""
    _emit("PFORCE", "Force_Penalty",
          {"FUNCTION": "expr", "PENALTY": "penalty", "PENALTY1": "penalty1",
           "UNILATERAL": "unilateral", "SMOOTHING_FACTOR": "smoothing_factor",
           "LABEL": "label", **_USERSUB}, id, **_usersub(kw))


def SFORCE(id, I=None, J=None, TRANSLATION=False, ROTATION=False, **kw):  # noqa: E741
    """Scalar two-body force: I, J markers, TRANSLATION=True (force along J->I) or
    ROTATION=True (torque about z of J), ACTIONONLY=True (on I alone, a force along z of J),
    FUNCTION, LABEL."""
    if bool(TRANSLATION) == bool(ROTATION):
        kw["TYPE"] = "missing: TRANSLATION=True or ROTATION=True"
    else:
        kw["TYPE"] = "TORQUE" if ROTATION else "FORCE"
    _emit("SFORCE", "Force_Scalar_TwoBody",
          {"I": "i_marker_id", "J": "j_marker_id", "FUNCTION": "expr", "LABEL": "label",
           "ACTIONONLY": "is_action_only", **_USERSUB}, id, I=I, J=J, **kw)


def SPRINGDAMPER(id, I=None, J=None, TRANSLATION=False, ROTATION=False,  # noqa: E741
                 **kw):
    """Spring and damper (Force_SpringDamper): I, J markers; TRANSLATION=True with K, C,
    LENGTH, FORCE (the force at LENGTH, positive repels), or ROTATION=True with KT, CT, ANGLE
    (radians), TORQUE (about z of J); LABEL. Adams' SPRINGDAMPER keywords."""
    if bool(TRANSLATION) == bool(ROTATION):
        kw["TYPE"] = "missing: TRANSLATION=True or ROTATION=True"
    else:
        kw["TYPE"] = "ROTATIONAL" if ROTATION else "TRANSLATIONAL"
    # a torsion spring takes KT, CT, ANGLE, TORQUE; a translational one K, C, LENGTH, FORCE
    mine = ("KT", "CT", "ANGLE", "TORQUE") if ROTATION else ("K", "C", "LENGTH", "FORCE")
    keys = dict(zip(mine, ("stiffness", "damping", "length", "preload")))
    _emit("SPRINGDAMPER", "Force_SpringDamper",
          {"I": "i_marker_id", "J": "j_marker_id", "TYPE": "type", "LABEL": "label", **keys},
          id, I=I, J=J, **kw)


def _vector(stmt, kind, comps, id, kw):
    comps = {c: f"{c.lower()}_expression" for c in comps}
    if any(k.upper() == "ACTIONONLY" and v for k, v in kw.items()):   # on I alone: no JFLOAT
        kw = {k: v for k, v in kw.items() if k.upper() != "ACTIONONLY"}
        _emit(stmt, "Force_Vector_OneBody", {"I": "marker_id", "RM": "ref_marker_id", **comps,
                                              "LABEL": "label"}, id, {"type": kind}, **kw)
        return
    _emit(stmt, "Force_Vector_TwoBody",
          {"I": "i_marker_id", "JFLOAT": "j_floating_marker_id", "RM": "ref_marker_id",
           **comps, "LABEL": "label", "ACTIONONLY": lambda v: {}}, id, {"type": kind}, **kw)


def VFORCE(id, **kw):
    """Vector force (Force_Vector_TwoBody): I (where it acts), JFLOAT (the body taking the
    reaction, at the same point), RM (the marker whose axes resolve FX, FY, FZ; global if
    omitted), FX, FY, FZ, LABEL; ACTIONONLY=True (no JFLOAT) acts on I's body alone
    (Force_Vector_OneBody). VTORQUE takes TX, TY, TZ instead, GFORCE all six."""
    _vector("VFORCE", "FORCEONLY", ("FX", "FY", "FZ"), id, kw)


def VTORQUE(id, **kw):
    """Vector torque (Force_Vector_TwoBody, TORQUEONLY): I, JFLOAT, RM, TX, TY, TZ, LABEL."""
    _vector("VTORQUE", "TORQUEONLY", ("TX", "TY", "TZ"), id, kw)


def GFORCE(id, **kw):
    """General force (FORCEANDTORQUE): I, JFLOAT, RM, FX, FY, FZ, TX, TY, TZ, LABEL."""
    _vector("GFORCE", "FORCEANDTORQUE", ("FX", "FY", "FZ", "TX", "TY", "TZ"), id, kw)


def _triple(prefix):
    def split(val):
        vals = [float(v) for v in val]
        if len(vals) != 3:
            raise ValueError
        return {f"{prefix}{c}": v for c, v in zip("xyz", vals)}
    return split


def BUSHING(id, **kw):
    """Bushing (Force_Bushing): I, J, K, C, KT, CT, FORCE, TORQUE (three numbers each, in J's
    axes), LABEL; Adams' BUSHING keywords."""
    _emit("BUSHING", "Force_Bushing",
          {"I": "i_marker_id", "J": "j_marker_id", "K": _triple("k"), "C": _triple("c"),
           "KT": _triple("kt"), "CT": _triple("ct"), "FORCE": _triple("preload_"),
           "TORQUE": _triple("preload_t"), "LABEL": "label"}, id, **kw)


_SIX = ("x", "y", "z", "tx", "ty", "tz")


def _six(prefix, count=6):
    """The first `count` of the six components (x, y, z, tx, ty, tz) as attributes."""
    def split(val):
        vals = [float(v) for v in val]
        if len(vals) != count:
            raise Expected(f"{count} numbers")
        return {f"{prefix}{c}": v for c, v in zip(_SIX, vals)}
    return split


def matrix(val, half=False):
    """The 6x6 matrix (rows) of a KMATRIX or CMATRIX value: 36 numbers column by column, as
    Adams enters them; a 6x6 nested list (or array) by rows; with `half` also Adams' BEAM
    CMATRIX, 21 numbers of the symmetric matrix (its lower half column by column)."""
    arr = np.asarray(val, dtype=float)
    if arr.shape == (6, 6):
        return arr
    flat = arr.ravel() if arr.ndim == 1 else None
    if flat is not None and flat.size == 36:
        return flat.reshape(6, 6).T
    if half and flat is not None and flat.size == 21:
        out = np.zeros((6, 6))
        col, row = np.triu_indices(6)           # column by column, rows from the diagonal
        out[row, col] = out[col, row] = flat
        return out
    half_text = ", 21 (the lower half, column by column)" if half else ""
    raise Expected(f"36 numbers (column by column){half_text} or a 6x6 matrix (rows)")


def _entries(prefix, half=False):
    def split(val):
        m = matrix(val, half)
        return {f"{prefix}{r + 1}{c + 1}": float(m[r, c]) for r in range(6) for c in range(6)}
    return split


def FIELD(id, **kw):
    """Field (Force_Field): I, J, KMATRIX (the 6x6 stiffness: 36 numbers column by column, as
    Adams enters them, or a 6x6 matrix by rows), CMATRIX (the damping, the same) or CRATIO
    (C = CRATIO K), LENGTH (x, y, z, a, b, c: where the field gives FORCE), FORCE (three
    forces and three torques, in J's axes), LABEL; Adams' FIELD keywords."""
    _emit("FIELD", "Force_Field",
          {"I": "i_marker_id", "J": "j_marker_id", "KMATRIX": _entries("k"),
           "CMATRIX": _entries("c"), "CRATIO": "cratio", "LENGTH": _six("length_"),
           "FORCE": _six("preload_"), "LABEL": "label"}, id, **kw)


def BEAM(id, **kw):
    """Beam (Force_Beam): I, J, LENGTH, IXX (torsion constant), IYY, IZZ (bending moments
    about J's y and z), AREA, ASY, ASZ (shear area ratios), EMODULUS, GMODULUS, CRATIO or
    CMATRIX (21 numbers: the lower half column by column, as Adams; or 36, or a 6x6 matrix,
    as FIELD's), pysolver's FORCE and TORQUE (preloads, three numbers each in J's axes),
    LABEL; Adams' BEAM keywords."""
    _emit("BEAM", "Force_Beam",
          {"I": "i_marker_id", "J": "j_marker_id", "LENGTH": "length", "IXX": "ixx",
           "IYY": "iyy", "IZZ": "izz", "AREA": "area", "ASY": "asy", "ASZ": "asz",
           "EMODULUS": "e", "GMODULUS": "g", "CRATIO": "cratio",
           "CMATRIX": _entries("c", half=True), "FORCE": _six("preload_", 3),
           "TORQUE": lambda v: {k.replace("preload_", "preload_t"): x
                                for k, x in _six("preload_", 3)(v).items()},
           "LABEL": "label"}, id, **kw)


def GRAPHICS(id, TYPE=None, **kw):
    """Geometry kept for the 3-D view (Post_Graphic): TYPE (Cylinder, Sphere,
    BoxDefinedFromCenter, ...) and its attributes as Post_Graphic names them (CENTER_MARKER_ID=,
    RADIUS=, LENGTH=, ...), LABEL."""
    _emit("GRAPHICS", "Post_Graphic", {"TYPE": "type", "LABEL": "label",
                                       **{k.upper(): k.lower() for k in kw}},
          id, TYPE=TYPE, **kw)


def SPLINE(id, X=None, Y=None, Z=None, LINEAR_EXTRAPOLATE=False, LABEL=""):
    """Curve data (Reference_Spline) for AKISPL, CUBSPL, LINSPL, QUISPL: X (strictly
    increasing) and Y, LINEAR_EXTRAPOLATE, LABEL. A surface: Z (strictly increasing) and Y
    one curve per z value, curve after curve (len(X) * len(Z) values, or a list of lists)."""
    X = list(X or ())
    if Z is not None:
        Z = [float(z) for z in (Z if np.ndim(Z) else [Z])]
        ys = np.asarray(Y if Y is not None else [], float).ravel()
        if ys.size != len(X) * len(Z):
            text = " ".join(map(repr, Z + X + ys.tolist())) + " 0"   # the loader says how
        else:
            table = np.column_stack([X, ys.reshape(len(Z), len(X)).T])
            text = " ".join(map(repr, Z + table.ravel().tolist()))
    else:
        text = " ".join(f"{float(a)!r} {float(b)!r}" for a, b in zip(X, Y or ()))
        if len(X) != len(Y or ()):
            text += " 0"                  # an odd count: the loader says x and y differ
    _emit("SPLINE", "Reference_Spline", {"LINEAR_EXTRAPOLATE": "linear_extrap",
                                         "LABEL": "label", "Z": lambda z: {"num_z": len(z)}},
          id, {"#text": text} if text else None, LINEAR_EXTRAPOLATE=LINEAR_EXTRAPOLATE,
          LABEL=LABEL, Z=Z)


def _motion_type(val):
    """TYPE of a joint's MOTION: R or T, or Adams' ROTATION and TRANSLATION."""
    name = str(val).upper()
    return {"motion_type": {"ROTATION": "R", "TRANSLATION": "T"}.get(name, name)}


def MOTION(id, **kw):
    """Motion of marker I relative to J (Motion_Marker): DIRECTION (X, Y, Z translations along
    J's axes; B1, B2, B3 the body-fixed 1-2-3 angles of I relative to J), VAL_TYPE (D
    displacement, V velocity, A acceleration), FUNCTION (a function of time), IC_DISP,
    IC_VEL, LABEL. With JOINT= the motion of a joint's coordinate instead (Motion_Joint):
    TYPE (R or ROTATION, T or TRANSLATION; needed on a CYLINDRICAL joint), VAL_TYPE,
    FUNCTION, IC_DISP, IC_VEL, LABEL.
    ROUTINE (MOTSUB), SCRIPT, INTERPRETER and FUNCTION="USER(...)" for a user subroutine.
    The reaction is res.motion(id)."""
    if "JOINT" in {k.upper() for k in kw}:
        _emit("MOTION", "Motion_Joint",
              {"JOINT": "joint_id", "TYPE": _motion_type, "VAL_TYPE": "val_type",
               "FUNCTION": "expr", "IC_DISP": "ic_disp", "IC_VEL": "ic_vel", "LABEL": "label",
               **_ROUTINE}, id, _routine_type(kw), **kw)
        return
    _emit("MOTION", "Motion_Marker",
          {"I": "i_marker_id", "J": "j_marker_id", "DIRECTION": "direction",
           "VAL_TYPE": "val_type", "FUNCTION": "expr", "IC_DISP": "ic_disp",
           "IC_VEL": "ic_vel", "LABEL": "label", **_ROUTINE}, id, _routine_type(kw), **kw)


def _joint_type(val):
    """TYPE of a JOINT statement: MotionSolve's names, or Adams' CONVEL and RACKPIN."""
    name = str(val).upper()
    return {"type": {"CONVEL": "CONSTANT_VELOCITY", "RACKPIN": "RACK_PINION"}.get(name, name)}


class BadJointIC(ValueError):
    """A joint's IC, ICTRAN or ICROT that its type cannot take: (keyword, message)."""


#: Which of IC, ICTRAN, ICROT each joint type takes, and the coordinate each sets.
JOINT_IC_KEYS = {"TRANSLATIONAL": {"IC": "tran"}, "REVOLUTE": {"IC": "rot"},
                 "CYLINDRICAL": {"ICTRAN": "tran", "ICROT": "rot"}}


def joint_ic(kind, values):
    """The Constraint_Joint attributes (ic_tran_disp .. ic_rot_vel) of a JOINT statement's
    IC, ICTRAN and ICROT (`values`: keyword -> one or two numbers, the displacement and the
    velocity; None for one not given) on a joint of type `kind` (Adams: IC on a
    TRANSLATIONAL or REVOLUTE joint, ICTRAN and ICROT on a CYLINDRICAL one). Raises
    BadJointIC(keyword, message)."""
    takes = JOINT_IC_KEYS.get(str(kind).upper(), {})
    given = [k for k in ("IC", "ICTRAN", "ICROT") if values.get(k) is not None]
    if "IC" in given and len(given) > 1:
        raise BadJointIC(given[1], "give IC (a TRANSLATIONAL or REVOLUTE joint) or ICTRAN and "
                         "ICROT (a CYLINDRICAL joint), not both")
    attrs = {}
    for key in given:
        if key not in takes:
            if not takes:
                why = (f"a {kind} joint has no free coordinate to start from an initial "
                       "condition; IC belongs to TRANSLATIONAL and REVOLUTE joints, ICTRAN and "
                       "ICROT to CYLINDRICAL ones")
            elif key == "IC":
                why = "a CYLINDRICAL joint takes ICTRAN and ICROT (its two coordinates)"
            else:
                why = f"{key} belongs to a CYLINDRICAL joint; a {kind} joint takes IC"
            raise BadJointIC(key, why)
        val = values[key]
        nums = list(val) if isinstance(val, (list, tuple, np.ndarray)) else [val]
        if not 1 <= len(nums) <= 2 or nums[0] is None:
            raise BadJointIC(key, f"{key} takes one or two numbers (the initial displacement, "
                             "then the velocity), got " + (str(len(nums)) if nums and nums[0]
                                                          is not None else "no displacement"))
        try:
            nums = [None if v is None else float(v) for v in nums]
        except (TypeError, ValueError):
            raise BadJointIC(key, f"got {val!r}; expected one or two numbers (the initial "
                             "displacement, then the velocity)") from None
        for name, v in zip(("disp", "vel"), nums):
            if v is not None:
                attrs[f"ic_{takes[key]}_{name}"] = v
    return attrs


def JOINT(id, **kw):
    """Joint (Constraint_Joint): TYPE (REVOLUTE, SPHERICAL, TRANSLATIONAL, CYLINDRICAL,
    UNIVERSAL, HOOKE, FIXED, PLANAR, CONSTANT_VELOCITY or CONVEL, SCREW, RACK_PINION or
    RACKPIN, the primitives INLINE, INPLANE, ORIENTATION, PARALLEL_AXES, PERPENDICULAR,
    FREE), I, J (markers: I on the first body, J on the second), PITCH (SCREW: translation
    per turn), PD (RACK_PINION: pitch diameter), VIRTUAL (is_virtual), LABEL; IC (a
    TRANSLATIONAL or REVOLUTE joint), ICTRAN and ICROT (a CYLINDRICAL joint): the initial
    displacement and velocity of its coordinate, (d, v) or d, held by the initial
    conditions only (docs/deck-language.md, "Initial positions"). The reactions are
    res.joint(id)."""
    from ..errors import DeckError
    values = {k.upper(): kw.pop(k) for k in list(kw) if k.upper() in ("IC", "ICTRAN", "ICROT")}
    kind = next((v for k, v in kw.items() if k.upper() == "TYPE"), "")
    kind = _joint_type(kind)["type"] if kind else ""
    try:
        extra = joint_ic(kind, values)
    except BadJointIC as err:
        rec = _recorder()
        raise DeckError(err.args[1], file=rec.file, line=_line(rec), element="JOINT", id=id,
                        attribute=err.args[0]) from None
    names = {a: next(k for k in values if values[k] is not None and
                     JOINT_IC_KEYS[kind][k] == a.split("_")[1]) for a in extra}
    _emit("JOINT", "Constraint_Joint",
          {"TYPE": _joint_type, "I": "i_marker_id", "J": "j_marker_id", "PITCH": "pitch",
           "PD": "pitch_diameter", "VIRTUAL": "is_virtual", "LABEL": "label"}, id, extra,
          names, **kw)


def _coupled_joints(val):
    return {f"joint{k}_id": int(j) for k, j in enumerate(val, 1)}


def _coupled_types(val):
    kinds = val.split(":") if isinstance(val, str) else list(val)
    return {f"freedom_{k}": str(t).upper()[:1] for k, t in enumerate(kinds, 1)}


def COUPLER(id, **kw):
    """Coupler (Constraint_Coupler): JOINTS (two or three joint ids), TYPE ("T:R", or a list;
    T translation, R rotation; needed for CYLINDRICAL joints), SCALES (r1, r2[, r3], or one
    fewer with r1 = 1: r1 q1 + r2 q2 [+ r3 q3] = 0), LABEL."""
    _emit("COUPLER", "Constraint_Coupler",
          {"JOINTS": _coupled_joints, "TYPE": _coupled_types,
           "SCALES": lambda v: {"coefficients": ", ".join(str(float(x)) for x in v)},
           "VIRTUAL": "is_virtual", "LABEL": "label"}, id, **kw)


def GCON(id, **kw):
    """General constraint (Constraint_General): FUNCTION (an expression of displacements and
    time held at zero), I (the marker MotionSolve reports its reaction at), LABEL; ROUTINE
    (GCOSUB), SCRIPT, INTERPRETER and FUNCTION="USER(...)" for a user subroutine."""
    _emit("GCON", "Constraint_General",
          {"FUNCTION": "expr", "I": "i_marker_id", "VIRTUAL": "is_virtual", "LABEL": "label",
           **_ROUTINE}, id, **kw)


def JPRIM(id, **kw):
    """Joint primitive (Constraint_Jprim): TYPE (ATPOINT, INLINE, INPLANE, ORIENTATION,
    PARALLEL_AXES, PERPENDICULAR), I, J, LABEL."""
    _emit("JPRIM", "Constraint_Jprim",
          {"TYPE": _joint_type, "I": "i_marker_id", "J": "j_marker_id",
           "VIRTUAL": "is_virtual", "LABEL": "label"}, id, **kw)


def LOADCONTROL(id=None, **kw):
    """The LoadControl task (seed 002): MATERIAL (the body's id), DIRECTION (1, 2, 3),
    VELOCITY (starting), MAXVELOCITY, LOAD_FUNCTION (target load, an expression of time; `t`
    reads as TIME), KP, KI (numbers or "auto"), SMOOTH, UPDATETIME, MEDIAN_WINDOW, LOAD
    ("reaction": the drive's, default; "contact": the penalties' force on the body), LABEL.
    Per-update records: res.controller(id)."""
    names = ("VELOCITY", "MATERIAL", "DIRECTION", "MAXVELOCITY", "LOAD_FUNCTION", "KP", "KI",
             "SMOOTH", "UPDATETIME", "MEDIAN_WINDOW", "LOAD", "LABEL")
    _emit("LOADCONTROL", "LoadControl", {n: n.lower() for n in names}, id, **kw)


def SENSOR(id, EVALUATE=None, **kw):
    """Event sensor: FUNCTION, VALUE, ERROR, OPERATOR (GE, LT, EQ; LE reads as LT),
    ZERO_CROSSING, DT, HMAX, STEPSIZE, HALT, PRINT, RESTART, RETURN, VERBOSE, LABEL. EVALUATE is
    an expression stored when the sensor fires and read with SENVAL(id) (a Sensor_Evaluate with
    the sensor's id; EVALUATE_ROUTINE= a Python SEVSUB with EVALUATE="USER(...)"); ROUTINE
    (SENSUB), SCRIPT, INTERPRETER for a user subroutine."""
    routine = kw.pop("EVALUATE_ROUTINE", None)
    script = {k: kw[k] for k in kw if k.upper() in ("SCRIPT", "INTERPRETER")}
    if EVALUATE not in (None, "") or routine is not None:
        sub = {"ROUTINE": routine, "TYPE": "USERSUB"} if routine is not None else {}
        if isinstance(routine, str) and "::" not in routine and "\u2237" not in routine:
            sub.update(script)          # a function of the sensor's SCRIPT
        _emit("SENSOR", "Sensor_Evaluate", {"FUNCTION": "expr", **_USERSUB}, id,
              FUNCTION=EVALUATE, **sub)
        # errors name the sensor's keywords of its evaluate
        _recorder().elements[-1][3].update(
            expr="EVALUATE", **dict.fromkeys(("usrsub_fnc_name", "usrsub_dll_name", "type"),
                                             "EVALUATE_ROUTINE"))
        kw["EVALUATE_ID"] = id
        own = str(kw.get("FUNCTION", "")).lstrip().upper().startswith("USER")
        if "ROUTINE" in sub and not own and not any(k.upper() == "ROUTINE" for k in kw):
            kw = {k: v for k, v in kw.items() if k not in script}    # the evaluate's alone
    _usersub(kw)
    _emit("SENSOR", "Sensor_Event",
          {"FUNCTION": "expr", "VALUE": "value", "ERROR": "error_tol", "OPERATOR": "compare",
           "ZERO_CROSSING": "zero_crossing", "DT": "dt", "HMAX": "hmax", "STEPSIZE": "stepsize",
           "HALT": "halt", "PRINT": "print", "RESTART": "restart", "RETURN": "return",
           "VERBOSE": "verbose", "LABEL": "label", "EVALUATE_ID": "evaluate_id",
           **_USERSUB}, id, **kw)


def SENSOR_EVALUATE(id, **kw):
    """Sensor_Evaluate on its own (SENSOR(..., EVALUATE=) makes one with the sensor's id):
    FUNCTION, LABEL; ROUTINE (SEVSUB), SCRIPT, INTERPRETER. A sensor names it with
    EVALUATE_ID=."""
    _emit("SENSOR_EVALUATE", "Sensor_Evaluate", {"FUNCTION": "expr", "LABEL": "label",
                                                 **_USERSUB}, id, **_usersub(kw))


def _settings(stmt, tag, kw):
    _emit(stmt, tag, {k.upper(): k.lower() for k in kw}, **kw)


def RESOUTPUT(**kw):
    """MotionSolve's ResOutput settings, kept as written (not used: pysolver writes its own
    outputs)."""
    _settings("RESOUTPUT", "ResOutput", kw)


def H3DOUTPUT(**kw):
    """MotionSolve's H3DOutput settings, kept as written (not used)."""
    _settings("H3DOUTPUT", "H3DOutput", kw)


def VARIABLE(id, **kw):
    """Variable read with VARVAL(id): FUNCTION, IC (initial_value: kept, not used: variables
    are explicit), LABEL; ROUTINE (VARSUB), SCRIPT, INTERPRETER."""
    _emit("VARIABLE", "Reference_Variable", {"FUNCTION": "expr", "IC": "initial_value",
                                             "LABEL": "label", **_USERSUB},
          id, **_usersub(kw))


def REQUEST(id, FUNCTION=None, **kw):
    """Output request: F1..F8 (or FUNCTION=[up to 8 expressions]), LABEL, COMMENT; or
    FUNCTION="USER(...)" with ROUTINE (REQSUB returning 8 values), SCRIPT, INTERPRETER; or
    TYPE (MARKER_DISPLACEMENT, MARKER_VELOCITY, MARKER_ACCELERATION, MARKER_FORCE) with the
    markers I, J and RM (the axes of the components)."""
    if isinstance(FUNCTION, str):         # FUNCTION="USER(...)" with ROUTINE (REQSUB)
        kw["PARAMS"] = FUNCTION
    elif FUNCTION is not None:
        for k, f in enumerate(FUNCTION, 1):
            kw.setdefault(f"F{k}", f)
    mapping = {f"F{k}": f"expr{k}" for k in range(1, 9)}
    mapping.update({f"NAME{k}": f"name{k}" for k in range(1, 9)})
    mapping.update({"LABEL": "label", "COMMENT": "comment", "PARAMS": "usrsub_param_string",
                    "I": "i_marker_id", "J": "j_marker_id", "RM": "ref_marker_id",
                    **_USERSUB})
    _usersub(kw)
    _emit("REQUEST", "Post_Request", mapping, id, **kw)


def INTEGRATOR(**kw):
    """Integrator settings: ERROR (integr_tol), HMAX, HMIN, HINIT (h0_max), MAX_NUM_STEPS,
    TYPE, DAE_CONSTR_TOL, pysolver's MAX_STEP_GROWTH and NONLIN_CONV_COEF, LABEL."""
    _emit("INTEGRATOR", "Param_Transient", {"ERROR": "integr_tol", "HMAX": "h_max",
                                            "HMIN": "h_min", "HINIT": "h0_max",
                                            "MAX_NUM_STEPS": "max_num_steps",
                                            "TYPE": "integrator_type",
                                            "DAE_CONSTR_TOL": "dae_constr_tol",
                                            "MAX_STEP_GROWTH": "max_step_growth",
                                            "NONLIN_CONV_COEF": "nonlin_conv_coef",
                                            "LABEL": "label"}, **kw)


def EQUILIBRIUM(**kw):
    """Static settings (Param_Static): METHOD (FIM_D, FIM_S, MKEAM), MAX_KE_TOL, MAX_DQ_TOL,
    MAXIT (max_num_iter), IMBALANCE (max_imbalance), ERROR (max_error), STABILITY,
    COMPLIANCE_DELTA, TLIMIT, ALIMIT (radians), LABEL."""
    _emit("EQUILIBRIUM", "Param_Static",
          {"METHOD": "method", "MAX_KE_TOL": "max_ke_tol", "MAX_DQ_TOL": "max_dq_tol",
           "MAXIT": "max_num_iter", "IMBALANCE": "max_imbalance", "ERROR": "max_error",
           "STABILITY": "stability", "COMPLIANCE_DELTA": "compliance_delta",
           "TLIMIT": "tlimit", "ALIMIT": "alimit", "LABEL": "label"}, **kw)


def SIMULATE(**kw):
    """Run: TYPE (TRANSIENT, STATIC, QUASI-STATIC, ASSEMBLY), START, END or DURATION, DTOUT or
    STEPS (ASSEMBLY takes neither: the initial-conditions analysis alone), PRINT_INCREMENT."""
    _emit("SIMULATE", "Simulate", {"TYPE": "analysis_type", "END": "end_time",
                                   "DURATION": "duration", "DTOUT": "print_interval",
                                   "STEPS": "num_step", "START": "start_time",
                                   "PRINT_INCREMENT": "print_increment"}, **kw)


def STOP():
    """End of the command list."""
    _emit("STOP", "Stop", {})


from .tracer import py_errmes, py_sysary, py_sysfnc, py_syspar  # noqa: E402  (user subroutine data access)
