"""The statements of an Adams dataset and command file, each translated into the call of its
pysolver.deck.msolve statement function (pysolver/deck/adams.py reads the text and calls
these).

Longer than 420 lines because it is a table of the language: one small translation per
statement (thirty of them) and the keywords each takes, Adams' own and pysolver's
extensions (docs/adams.md, "pysolver extensions"), which are matched by their full name
only, so that they never make an abbreviation of an Adams keyword ambiguous.
"""
import re

from . import msolve


def _label(stmt):
    return {"LABEL": stmt.label} if stmt.label else {}


def _pick(vals, mapping):
    """Keyword arguments of a statement function from an .adm statement's values."""
    return {new: vals[old] for old, new in mapping.items() if old in vals}


def _same(vals, keys):
    return _pick(vals, {k: k for k in keys})


def _refuse(r, stmt, vals, lines, keys, why):
    for k in keys:
        if k in vals:
            raise r.error(stmt, f"{k} is not supported: {why}", k, lines[k])


def _one_flag(r, stmt, vals, flags, what):
    given = [f for f in flags if vals.get(f)]
    if len(given) != 1:
        raise r.error(stmt, f"give one of {', '.join(flags)} ({what})")
    return given[0]


def _list(value):
    return value if isinstance(value, list) else [value]


def _units(r, stmt, vals, lines):
    _refuse(r, stmt, vals, lines, ("UCF",), "give FORCE, MASS, LENGTH and TIME")
    system = str(vals.pop("SYSTEM", "")).upper() if "SYSTEM" in vals else None
    if system == "NONE":
        # nondimensional (Adams: UCF = 1): a dataset without UNITS
        _refuse(r, stmt, vals, lines, ("FORCE", "MASS", "LENGTH", "TIME"),
                "SYSTEM=NONE is a nondimensional dataset")
        return
    kw = dict(_SYSTEMS.get(system, {})) if system is not None else {}
    if system is not None and not kw:
        raise r.error(stmt, f"unknown SYSTEM; expected {', '.join(_SYSTEMS)}, NONE", "SYSTEM")
    for key in ("FORCE", "MASS", "LENGTH", "TIME"):
        if key in vals:
            kw[key] = UNIT_NAMES.get(str(vals[key]).upper(), str(vals[key]).upper())
    msolve.UNITS(**kw, **_label(stmt))


_SYSTEMS = {"MKS": dict(FORCE="NEWTON", MASS="KILOGRAM", LENGTH="METER", TIME="SECOND"),
            "MMKS": dict(FORCE="NEWTON", MASS="KILOGRAM", LENGTH="MILLIMETER", TIME="SECOND"),
            "CGS": dict(FORCE="DYNE", MASS="GRAM", LENGTH="CENTIMETER", TIME="SECOND"),
            "FPS": dict(FORCE="POUND_FORCE", MASS="POUND_MASS", LENGTH="FOOT", TIME="SECOND"),
            "IPS": dict(FORCE="POUND_FORCE", MASS="POUND_MASS", LENGTH="INCH", TIME="SECOND")}
#: Adams' unit names that are not pysolver's (docs/adams.md).
UNIT_NAMES = {"KNEWTON": "KILONEWTON", "MNEWTON": "MILLINEWTON", "TONNE": "MEGAGRAM",
              "KG": "KILOGRAM", "MM": "MILLIMETER", "M": "METER", "SEC": "SECOND",
              "S": "SECOND", "N": "NEWTON", "LBF": "POUND_FORCE", "LBM": "POUND_MASS",
              "POUND": "POUND_FORCE", "MSEC": "MILLISECOND", "MS": "MILLISECOND"}


def _part(r, stmt, vals, lines):
    r.need_id(stmt)
    if vals.get("GROUND"):
        msolve.PART(stmt.id, GROUND=True, **_label(stmt))
        return
    if "EXACT" in vals:
        r.warn(stmt, "EXACT (coordinates the assembly keeps) is set aside: pysolver's "
               "assembly changes the initial positions least (docs/joints.md)", lines["EXACT"])
    kw = _same(vals, ("MASS", "CM", "IM", "LPRF", "VX", "VY", "VZ", "WX", "WY", "WZ", "VM",
                      "WM"))
    if "IP" in vals:
        ip = _list(vals["IP"])
        if len(ip) not in (3, 6):
            raise r.error(stmt, "IP takes xx, yy, zz[, xy, xz, yz]", "IP", lines["IP"])
        kw["IP"] = ip[:3] + ([ip[3], ip[5], ip[4]] if len(ip) == 6 else [])
    msolve.PART(stmt.id, **kw, **_label(stmt))


def _point_mass(r, stmt, vals, lines):
    r.need_id(stmt)
    msolve.POINT_MASS(r.id(stmt), **_same(vals, ("MASS", "CM", "VX", "VY", "VZ", "VM")),
                      **_label(stmt))


def _marker(r, stmt, vals, lines):
    _refuse(r, stmt, vals, lines, ("FLEX_BODY", "FE_PART", "NODE_ID", "NODE_LABEL"),
            "pysolver has rigid bodies only")
    if "PART" not in vals and "POINT_MASS" not in vals:
        raise r.error(stmt, "a marker needs PART= (or POINT_MASS=)")
    key = "PART" if "PART" in vals else "POINT_MASS"
    body = r.id(vals[key], key)
    floating = {"FLOATING": True} if vals.get("FLOATING") else {}
    msolve.MARKER(stmt.id, PART=body, **r.marker_placement(stmt.id), **floating,
                  **_label(stmt))
    placed = r.marker_reference(stmt.id)
    if placed is not None:              # QP in a part's frame: what a sweep's pos_* mean
        msolve._recorder().elements[-1][3]["#placement"] = placed


_JOINT_TYPES = ("CONVEL", "CYLINDRICAL", "FIXED", "HOOKE", "PLANAR", "RACKPIN", "REVOLUTE",
                "SCREW", "SPHERICAL", "TRANSLATIONAL", "UNIVERSAL")
JPRIM_TYPES = ("ATPOINT", "INLINE", "INPLANE", "ORIENTATION", "PARALLEL_AXES",
               "PERPENDICULAR")


def _joint(r, stmt, vals, lines):
    r.need_id(stmt)
    kind = _one_flag(r, stmt, vals, _JOINT_TYPES + ("FREE",), "the joint type")
    ic = {k: vals[k] for k in ("IC", "ICTRAN", "ICROT") if k in vals}
    try:
        msolve.joint_ic(msolve._joint_type(kind)["type"], ic)
    except msolve.BadJointIC as err:
        raise r.error(stmt, err.args[1], err.args[0], lines[err.args[0]]) from None
    msolve.JOINT(stmt.id, TYPE=kind, **_same(vals, ("I", "J", "PD", "PITCH", "VIRTUAL")),
                 **ic, **_label(stmt))
    names = msolve._recorder().elements[-1][3]
    for attr, key in list(names.items()):         # the load's checks name IC's own line
        if key in ic:
            names.setdefault("#lines", {})[attr] = lines[key]


def _jprim(r, stmt, vals, lines):
    r.need_id(stmt)
    kind = _one_flag(r, stmt, vals, JPRIM_TYPES, "the primitive")
    msolve.JPRIM(r.id(stmt), TYPE=kind, **_same(vals, ("I", "J", "VIRTUAL")), **_label(stmt))


#: A user subroutine: Adams' ROUTINE (name, or library::name) and pysolver's SCRIPT and
#: INTERPRETER (a Python script's routine).
_SUB = ("ROUTINE", "SCRIPT", "INTERPRETER")


def _routine(r, stmt, vals, lines, default):
    """The user subroutine keywords of a statement. ``FUNCTION = USER(...)`` without ROUTINE
    (or SCRIPT) calls Adams' `default` subroutine (VARSUB, SFOSUB, ...) of the user library
    linked into Adams, which pysolver has not: a DeckError saying what to give."""
    if "ROUTINE" not in vals and "SCRIPT" not in vals and \
            re.match(r"\s*USER\s*\(", str(vals.get("FUNCTION", "")), re.I):
        raise r.error(stmt, f"FUNCTION = USER(...) without ROUTINE calls Adams' default "
                      f"{default}, the one linked into Adams' user library, and pysolver links "
                      f"no library: give ROUTINE = library::{default} (a C library), or "
                      "SCRIPT = file.py and ROUTINE = the name of its Python function "
                      "(docs/adams.md, \"User subroutines\")", "FUNCTION", lines["FUNCTION"])
    return _same(vals, _SUB)


def _motion(r, stmt, vals, lines):
    r.need_id(stmt)
    sub = _routine(r, stmt, vals, lines, "MOTSUB")
    kw = _pick(vals, {"FUNCTION": "FUNCTION", "ICDISP": "IC_DISP", "ICVEL": "IC_VEL"})
    given = [k for k in ("DISPLACEMENT", "VELOCITY", "ACCELERATION") if vals.get(k)]
    if len(given) > 1:
        raise r.error(stmt, "give one of DISPLACEMENT, VELOCITY, ACCELERATION")
    kw["VAL_TYPE"] = given[0][0] if given else "D"
    if "JOINT" in vals:
        kinds = [k for k in ("TRANSLATION", "ROTATION") if vals.get(k)]
        if len(kinds) > 1:
            raise r.error(stmt, "give TRANSLATION or ROTATION, not both")
        if kinds:
            kw["TYPE"] = kinds[0]
        msolve.MOTION(stmt.id, JOINT=vals["JOINT"], **kw, **sub, **_label(stmt))
        return
    direction = _one_flag(r, stmt, vals, ("X", "Y", "Z", "B1", "B2", "B3"),
                          "the direction of a marker motion, or JOINT=")
    msolve.MOTION(stmt.id, **_same(vals, ("I", "J")), DIRECTION=direction, **kw,
                  **sub, **_label(stmt))


def _gcon(r, stmt, vals, lines):
    r.need_id(stmt)
    sub = _routine(r, stmt, vals, lines, "GCOSUB")
    msolve.GCON(stmt.id, **_same(vals, ("FUNCTION", "I", "VIRTUAL")), **sub, **_label(stmt))


def _coupler(r, stmt, vals, lines):
    r.need_id(stmt)
    _refuse(r, stmt, vals, lines, ("FUNCTION", "ROUTINE"), "COUSUB, a coupler's user "
            "subroutine, is not supported yet")
    kw = {k: _list(v) for k, v in _same(vals, ("JOINTS", "SCALES")).items()}
    if "TYPE" in vals:
        kw["TYPE"] = ":".join(map(str, _list(vals["TYPE"])))
    msolve.COUPLER(stmt.id, **kw, **_same(vals, ("VIRTUAL",)), **_label(stmt))


def _sforce(r, stmt, vals, lines):
    r.need_id(stmt)
    sub = _routine(r, stmt, vals, lines, "SFOSUB")
    msolve.SFORCE(stmt.id, **_same(vals, ("I", "J", "TRANSLATION", "ROTATION", "ACTIONONLY",
                                          "FUNCTION")), **sub, **_label(stmt))


def _springdamper(r, stmt, vals, lines):
    r.need_id(stmt)
    msolve.SPRINGDAMPER(stmt.id, **_same(vals, (
        "I", "J", "TRANSLATION", "ROTATION", "K", "C", "LENGTH", "FORCE", "KT", "CT",
        "ANGLE", "TORQUE")), **_label(stmt))


def _bushing(r, stmt, vals, lines):
    r.need_id(stmt)
    kw = _same(vals, ("I", "J", "K", "C", "KT", "CT", "FORCE", "TORQUE"))
    for k in ("K", "C", "KT", "CT", "FORCE", "TORQUE"):
        if k in kw and not isinstance(kw[k], list):
            raise r.error(stmt, f"{k} takes three numbers", k, lines[k])
    msolve.BUSHING(stmt.id, **kw, **_label(stmt))


def _counted(r, stmt, vals, lines, keys):
    """{KEY: numbers} of the list keywords `keys` ({KEY: the counts it takes}) given."""
    out = {}
    for key, counts in keys.items():
        if key not in vals:
            continue
        value = _list(vals[key])
        if len(value) not in counts or not all(isinstance(v, (int, float)) for v in value):
            want = " or ".join(str(n) for n in counts)
            raise r.error(stmt, f"{key} takes {want} numbers, got {len(value)}", key,
                          lines[key])
        out[key] = [float(v) for v in value]
    return out


def _field(r, stmt, vals, lines):
    r.need_id(stmt)
    _refuse(r, stmt, vals, lines, ("FUNCTION", "ROUTINE"), "a nonlinear field (a FIESUB "
            "user subroutine); give KMATRIX, CMATRIX or CRATIO, LENGTH and FORCE")
    kw = _same(vals, ("I", "J", "CRATIO"))
    kw.update(_counted(r, stmt, vals, lines, {"KMATRIX": (36,), "CMATRIX": (36,),
                                              "LENGTH": (6,), "FORCE": (6,)}))
    msolve.FIELD(stmt.id, **kw, **_label(stmt))


def _beam(r, stmt, vals, lines):
    r.need_id(stmt)
    form = str(vals.get("FORMULATION", "LINEAR")).upper()
    if form != "LINEAR":
        raise r.error(stmt, f"FORMULATION = {form} is not supported: pysolver's BEAM is the "
                      "linear Timoshenko beam (FORMULATION = LINEAR)", "FORMULATION",
                      lines["FORMULATION"])
    kw = _same(vals, ("I", "J", "LENGTH", "IXX", "IYY", "IZZ", "AREA", "ASY", "ASZ",
                      "EMODULUS", "GMODULUS", "CRATIO"))
    kw.update(_counted(r, stmt, vals, lines, {"CMATRIX": (21, 36), "FORCE": (3,),
                                              "TORQUE": (3,)}))
    msolve.BEAM(stmt.id, **kw, **_label(stmt))


def _vector(function, comps):
    def emit(r, stmt, vals, lines):
        r.need_id(stmt)
        kw = _same(vals, ("I", "JFLOAT", "RM", "ACTIONONLY", *comps))
        if "FUNCTION" in vals:
            raise r.error(stmt, "FUNCTION=USER(...) (a VFOSUB, VTOSUB or GFOSUB) is not "
                          "supported yet: give the components", "FUNCTION", lines["FUNCTION"])
        if vals.get("ACTIONONLY") and "JFLOAT" in vals:
            raise r.error(stmt, "an ACTIONONLY force has no JFLOAT (nothing takes its "
                          "reaction)", "JFLOAT", lines["JFLOAT"])
        function(r.id(stmt), **kw, **_label(stmt))
    return emit


def _variable(r, stmt, vals, lines):
    r.need_id(stmt)
    sub = _routine(r, stmt, vals, lines, "VARSUB")
    msolve.VARIABLE(stmt.id, **_same(vals, ("FUNCTION", "IC")), **sub, **_label(stmt))


def _spline(r, stmt, vals, lines):
    r.need_id(stmt)
    _refuse(r, stmt, vals, lines, ("FILE", "CHANNEL", "BLOCK"), "spline data from files; "
            "give X= and Y=")
    x = _list(vals.get("X", []))
    ys = vals.get("Y", [])
    kw = {"LINEAR_EXTRAPOLATE": bool(vals.get("LINEAR_EXTRAPOLATE"))}
    if len(ys) == 1:                            # a curve
        msolve.SPLINE(stmt.id, X=x, Y=ys[0], **kw, **_label(stmt))
        return
    # a surface: one Y= per z value, its first number the z value
    msolve.SPLINE(stmt.id, X=x, Y=[y[1:] for y in ys], Z=[y[0] for y in ys], **kw,
                  **_label(stmt))


def _sensor(r, stmt, vals, lines):
    r.need_id(stmt)
    for k in ("CODGEN", "YYDUMP", "DUMP"):
        if vals.get(k):
            r.warn(stmt, f"{k} is an Adams diagnostic; set aside", lines[k])
    kw = _same(vals, ("FUNCTION", "VALUE", "ERROR", "HALT", "RETURN", "PRINT", "RESTART",
                      "STEPSIZE", "EVALUATE", "DT", "HMAX", "ZERO_CROSSING", "VERBOSE"))
    if "EVALUATE_ID" in vals:
        if "EVALUATE" in vals:
            raise r.error(stmt, "give EVALUATE= or EVALUATE_ID=, not both", "EVALUATE_ID",
                          lines["EVALUATE_ID"])
        kw["EVALUATE_ID"] = vals["EVALUATE_ID"]
    ops = [k for k in ("EQ", "GE", "LE") if vals.get(k)]
    if len(ops) > 1:
        raise r.error(stmt, "give one of EQ, GE, LE")
    kw["OPERATOR"] = ops[0] if ops else "EQ"
    kw.update(_evaluate_routine(r, stmt, vals, lines))
    msolve.SENSOR(stmt.id, **kw, **_routine(r, stmt, vals, lines, "SENSUB"), **_label(stmt))


def _evaluate_routine(r, stmt, vals, lines):
    """A sensor's SEVSUB: ``EVALUATE = USER(...)`` with ``EVALUATE_ROUTINE = library::name``
    (or a function of the sensor's SCRIPT); without EVALUATE_ROUTINE Adams calls its default
    SEVSUB of the user library linked into Adams, which pysolver has not: a DeckError."""
    user = re.match(r"\s*USER\s*\(", str(vals.get("EVALUATE", "")), re.I)
    if "EVALUATE_ROUTINE" in vals:
        if not user:
            raise r.error(stmt, "EVALUATE_ROUTINE names the SEVSUB that EVALUATE = USER(...) "
                          "calls: give EVALUATE = USER(...) with its parameters",
                          "EVALUATE_ROUTINE", lines["EVALUATE_ROUTINE"])
        return {"EVALUATE_ROUTINE": vals["EVALUATE_ROUTINE"]}
    if user:
        raise r.error(stmt, "EVALUATE = USER(...) without EVALUATE_ROUTINE calls Adams' "
                      "default SEVSUB, the one linked into Adams' user library, and pysolver "
                      "links no library: give EVALUATE_ROUTINE = library::SEVSUB (a C "
                      "library), or SCRIPT = file.py and EVALUATE_ROUTINE = the name of its "
                      "Python function (docs/adams.md, \"User subroutines\")", "EVALUATE",
                      lines["EVALUATE"])
    return {}


def _sensor_evaluate(r, stmt, vals, lines):
    r.need_id(stmt)
    sub = _routine(r, stmt, vals, lines, "SEVSUB")
    msolve.SENSOR_EVALUATE(stmt.id, **_same(vals, ("FUNCTION",)), **sub, **_label(stmt))


REQUEST_TYPES = {"DISPLACEMENT": "MARKER_DISPLACEMENT", "VELOCITY": "MARKER_VELOCITY",
                 "ACCELERATION": "MARKER_ACCELERATION", "FORCE": "MARKER_FORCE"}


def _request(r, stmt, vals, lines):
    r.need_id(stmt)
    _refuse(r, stmt, vals, lines, ("VARIABLES",), "a request of variables; use F1..F8 with "
            "VARVAL()")
    kinds = [k for k in REQUEST_TYPES if vals.get(k)]
    if len(kinds) > 1:
        raise r.error(stmt, f"give one of {', '.join(REQUEST_TYPES)}")
    kw = _same(vals, [f"F{k}" for k in range(1, 9)])
    if "COMMENT" in vals or "TITLE" in vals:
        kw["COMMENT"] = str(vals.get("COMMENT", vals.get("TITLE")))
    if "CNAMES" in vals:            # "" leaves a channel its default name
        names = _list(vals["CNAMES"])
        if len(names) > 8:
            raise r.error(stmt, f"CNAMES names {len(names)} channels; a request has 8",
                          "CNAMES", lines["CNAMES"])
        kw.update({f"NAME{k}": str(n) for k, n in enumerate(names, 1) if str(n)})
    if kinds:
        kw.update(TYPE=REQUEST_TYPES[kinds[0]], **_same(vals, ("I", "J", "RM")))
    if "FUNCTION" in vals:
        kw["FUNCTION"] = vals["FUNCTION"]
    msolve.REQUEST(stmt.id, **kw, **_routine(r, stmt, vals, lines, "REQSUB"), **_label(stmt))


def _accgrav(r, stmt, vals, lines):
    msolve.ACCGRAV(**_same(vals, ("IGRAV", "JGRAV", "KGRAV")), **_label(stmt))


_GRAPHIC_TYPES = ("CYLINDER", "BOX", "FRUSTUM", "SPHERE", "ELLIPSOID", "CIRCLE", "ARC",
                  "OUTLINE", "PLANE", "TORUS", "LINK", "EXTERNAL", "POINT", "FORCE",
                  "SPDP", "BLOCK", "REVOLUTION", "EXTRUSION")


def _graphics(r, stmt, vals, lines):
    """Kept as written: Adams' flag for the shape (CYLINDER, ...) or a TYPE= keyword
    (MotionSolve's Post_Graphic types), every other keyword with its text."""
    r.need_id(stmt)
    raw = r.raw_values(stmt)
    kinds = [k for k in _GRAPHIC_TYPES if raw.get(k.lower()) is True]
    kind = raw.pop("type", None)
    if kind is None:
        kind = kinds[0] if kinds else "OUTLINE"
    else:
        kinds = []
    kw = {k: v for k, v in raw.items() if v is not True or k.upper() not in kinds}
    msolve.GRAPHICS(stmt.id, TYPE=kind, **{k: ("TRUE" if v is True else v)
                                           for k, v in kw.items()}, **_label(stmt))


def _settings(function):
    def emit(r, stmt, vals, lines):
        function(**{k: ("TRUE" if v is True else v) for k, v in r.raw_values(stmt).items()})
    return emit


_INTEGRATORS = ("GSTIFF", "WSTIFF", "CONSTANT_BDF", "HHT", "NEWMARK", "HASTIFF", "ABAM",
                "RKF45", "I3", "SI2", "SI1")
#: MotionSolve's integrator names (pysolver extensions: Param_Transient integrator_type)
INTEGRATOR_TYPES = ("IDA", "DSTIFF", "VSTIFF", "MSTIFF", "GSTIFF", "WSTIFF", "ABAM", "I3",
                    "SI2")


def _integrator(r, stmt, vals, lines):
    other = [k for k in ("HHT", "NEWMARK", "HASTIFF", "RKF45") if k in vals]
    if other:
        r.warn(stmt, f"{other[0]} is not pysolver's integrator: it integrates with IDA's "
               "variable-order BDF (as GSTIFF) and its own formulation (docs/numerics.md); "
               "ERROR, HMAX, HMIN and HINIT are used")
    kinds = [k for k in INTEGRATOR_TYPES if vals.get(k) is True]
    if len(kinds) > 1 and not set(kinds) <= {"GSTIFF", "WSTIFF", "I3", "SI2"}:
        raise r.error(stmt, f"give one integrator, not {', '.join(kinds)}")
    kw = {"TYPE": kinds[0]} if kinds else {}
    msolve.INTEGRATOR(**_same(vals, ("ERROR", "HMAX", "HMIN", "HINIT", "MAX_NUM_STEPS",
                                     "MAX_STEP_GROWTH", "NONLIN_CONV_COEF", "DAE_CONSTR_TOL")),
                      **kw, **_label(stmt))


def _equilibrium(r, stmt, vals, lines):
    # STATIC is the static equilibrium pysolver finds; DYNAMIC and PATTERN tune Adams' own
    other = [k for k in ("PATTERN", "DYNAMIC") if k in vals]
    if other:
        r.warn(stmt, f"{', '.join(other)} set aside: pysolver's statics are its own Newton "
               "methods (docs/statics.md)")
    msolve.EQUILIBRIUM(**_same(vals, ("ERROR", "IMBALANCE", "MAXIT", "STABILITY", "TLIMIT",
                                      "ALIMIT", "METHOD", "MAX_KE_TOL", "MAX_DQ_TOL",
                                      "COMPLIANCE_DELTA")), **_label(stmt))


def _pforce(r, stmt, vals, lines):
    r.need_id(stmt)
    sub = _routine(r, stmt, vals, lines, "PFOSUB")
    msolve.PFORCE(stmt.id, **_same(vals, ("FUNCTION", "PENALTY", "PENALTY1", "UNILATERAL",
                                          "SMOOTHING_FACTOR")), **sub, **_label(stmt))


_LOADCONTROL = ("VELOCITY", "MATERIAL", "DIRECTION", "MAXVELOCITY", "LOAD_FUNCTION", "KP",
                "KI", "SMOOTH", "UPDATETIME", "MEDIAN_WINDOW", "LOAD")


def _loadcontrol(r, stmt, vals, lines):
    msolve.LOADCONTROL(stmt.id, **_same(vals, _LOADCONTROL), **_label(stmt))


_ANALYSES = {"DYNAMICS": "TRANSIENT", "TRANSIENT": "TRANSIENT", "KINEMATICS": "TRANSIENT",
             "STATICS": "STATIC", "INITIAL_CONDITIONS": "ASSEMBLY"}


def _simulate(r, stmt, vals, lines):
    kind = _ANALYSES[_one_flag(r, stmt, vals, tuple(_ANALYSES), "the analysis")]
    if kind == "STATIC" and vals.get("DTOUT") == 0:
        # no output step (as Inspire writes SIMULATE/STATICS, END = 0, DTOUT = 0): one
        # equilibrium at END
        vals = {k: v for k, v in vals.items() if k != "DTOUT"}
    if kind == "STATIC" and any(k in vals for k in ("STEPS", "DTOUT", "DURATION")):
        kind = "QUASI-STATIC"       # Adams: STATICS to END with output steps
    msolve.SIMULATE(TYPE=kind, **_same(vals, ("END", "DURATION", "STEPS", "DTOUT", "START",
                                              "PRINT_INCREMENT")))


#: Statements that share one pysolver id space, and the one of each that keeps its ids.
SHARED = {"PART": "body", "POINT_MASS": "body", "JOINT": "joint", "JPRIM": "joint",
          "VFORCE": "vforce", "VTORQUE": "vforce", "GFORCE": "vforce"}
PRIMARY = ("PART", "JOINT", "VFORCE")
_V = ("VIRTUAL",)
#: Statement -> (Adams' keywords, pysolver's extension keywords, its translation); None for
#: a statement that takes any keyword. PFORCE, LOADCONTROL, SENSOR_EVALUATE, RESOUTPUT and
#: H3DOUTPUT are pysolver's own statements (EXTENSIONS).
DATASET = {
    "UNITS": (("FORCE", "MASS", "LENGTH", "TIME", "SYSTEM", "UCF"), (), _units),
    "PART": (("GROUND", "MASS", "CM", "IM", "IP", "QG", "REULER", "XG", "ZG", "VX", "VY",
              "VZ", "WX", "WY", "WZ", "VM", "WM", "EXACT", "MATERIAL", "PLANAR"), ("LPRF",),
             _part),
    "POINT_MASS": (("MASS", "CM", "QG", "REULER", "XG", "ZG", "VX", "VY", "VZ", "EXACT"),
                   ("VM",), _point_mass),
    "MARKER": (("PART", "POINT_MASS", "FLEX_BODY", "FE_PART", "NODE_ID", "NODE_LABEL", "QP",
                "REULER", "ZP", "XP", "USEXP", "RM", "FLOATING"), ("AXES", "EP", "YPR"),
               _marker),
    "JOINT": (_JOINT_TYPES + ("I", "J", "PD", "PITCH", "IC", "ICTRAN", "ICROT"),
              ("FREE",) + _V, _joint),
    "JPRIM": (JPRIM_TYPES + ("I", "J"), _V, _jprim),
    "MOTION": (("JOINT", "I", "J", "TRANSLATION", "ROTATION", "X", "Y", "Z", "B1", "B2", "B3",
                "DISPLACEMENT", "VELOCITY", "ACCELERATION", "FUNCTION", "ICDISP", "ICVEL",
                "ROUTINE"), _SUB[1:], _motion),
    "GCON": (("FUNCTION", "I", "ROUTINE"), _SUB[1:] + _V, _gcon),
    "COUPLER": (("JOINTS", "TYPE", "SCALES", "FUNCTION", "ROUTINE"), _V, _coupler),
    "SFORCE": (("I", "J", "TRANSLATION", "ROTATION", "ACTIONONLY", "FUNCTION", "ROUTINE"),
               _SUB[1:], _sforce),
    "SPRINGDAMPER": (("I", "J", "TRANSLATION", "ROTATION", "K", "C", "LENGTH", "FORCE", "KT",
                      "CT", "ANGLE", "TORQUE"), (), _springdamper),
    "BUSHING": (("I", "J", "K", "C", "KT", "CT", "FORCE", "TORQUE"), (), _bushing),
    "FIELD": (("I", "J", "KMATRIX", "CMATRIX", "CRATIO", "LENGTH", "FORCE", "FUNCTION",
               "ROUTINE"), (), _field),
    "BEAM": (("I", "J", "LENGTH", "IXX", "IYY", "IZZ", "AREA", "ASY", "ASZ", "EMODULUS",
              "GMODULUS", "CRATIO", "CMATRIX", "FORMULATION"), ("FORCE", "TORQUE"), _beam),
    "VFORCE": (("I", "JFLOAT", "RM", "FX", "FY", "FZ", "FUNCTION", "ROUTINE"), ("ACTIONONLY",),
               _vector(msolve.VFORCE, ("FX", "FY", "FZ"))),
    "VTORQUE": (("I", "JFLOAT", "RM", "TX", "TY", "TZ", "FUNCTION", "ROUTINE"),
                ("ACTIONONLY",), _vector(msolve.VTORQUE, ("TX", "TY", "TZ"))),
    "GFORCE": (("I", "JFLOAT", "RM", "FX", "FY", "FZ", "TX", "TY", "TZ", "FUNCTION", "ROUTINE"),
               ("ACTIONONLY",), _vector(msolve.GFORCE, ("FX", "FY", "FZ", "TX", "TY", "TZ"))),
    "VARIABLE": (("FUNCTION", "IC", "ROUTINE"), _SUB[1:], _variable),
    "SPLINE": (("X", "Y", "LINEAR_EXTRAPOLATE", "FILE", "CHANNEL", "BLOCK"), (), _spline),
    "SENSOR": (("FUNCTION", "VALUE", "ERROR", "EQ", "GE", "LE", "HALT", "RETURN", "PRINT",
                "RESTART", "STEPSIZE", "EVALUATE", "CODGEN", "YYDUMP", "DUMP", "DT",
                "ROUTINE", "EVALUATE_ROUTINE"),
               _SUB[1:] + ("HMAX", "ZERO_CROSSING", "VERBOSE", "EVALUATE_ID"), _sensor),
    "REQUEST": (tuple(REQUEST_TYPES) + ("I", "J", "RM", "FUNCTION", "TITLE", "COMMENT",
                                        "CNAMES", "VARIABLES", *(f"F{k}" for k in range(1, 9)),
                                        "ROUTINE"), _SUB[1:], _request),
    "ACCGRAV": (("IGRAV", "JGRAV", "KGRAV"), (), _accgrav),
    "GRAPHICS": (None, (), _graphics),          # kept as written, for the 3-D view
    "INTEGRATOR": (_INTEGRATORS + ("ERROR", "HMAX", "HMIN", "HINIT", "MAXIT", "KMAX",
                                   "PATTERN", "CORRECTOR", "INTERPOLATE", "ALPHA", "BETA",
                                   "GAMMA"),
                   ("IDA", "DSTIFF", "VSTIFF", "MSTIFF", "MAX_NUM_STEPS", "MAX_STEP_GROWTH",
                    "NONLIN_CONV_COEF", "DAE_CONSTR_TOL"), _integrator),
    "EQUILIBRIUM": (("ERROR", "IMBALANCE", "MAXIT", "STABILITY", "TLIMIT", "ALIMIT",
                     "PATTERN", "DYNAMIC", "STATIC"),
                    ("METHOD", "MAX_KE_TOL", "MAX_DQ_TOL", "COMPLIANCE_DELTA"), _equilibrium),
    # pysolver's statements (its elements Adams has no statement for)
    "PFORCE": ((), ("FUNCTION", "PENALTY", "PENALTY1", "UNILATERAL", "SMOOTHING_FACTOR")
               + _SUB, _pforce),
    "LOADCONTROL": ((), _LOADCONTROL, _loadcontrol),
    "SENSOR_EVALUATE": ((), ("FUNCTION",) + _SUB, _sensor_evaluate),
    "RESOUTPUT": (None, (), _settings(msolve.RESOUTPUT)),
    "H3DOUTPUT": (None, (), _settings(msolve.H3DOUTPUT)),
}
#: pysolver's own statements: matched by their full name only.
EXTENSIONS = ("PFORCE", "LOADCONTROL", "SENSOR_EVALUATE", "RESOUTPUT", "H3DOUTPUT")
#: Commands of a command file (after the dataset's and output's names).
COMMANDS = {
    "SIMULATE": (tuple(_ANALYSES) + ("END", "DURATION", "STEPS", "DTOUT"),
                 ("START", "PRINT_INCREMENT"), _simulate),
    "INTEGRATOR": DATASET["INTEGRATOR"],
    "EQUILIBRIUM": DATASET["EQUILIBRIUM"],
}
