"""The deck language's elements: every attribute, its kind, whether required, its default; and
the conversion of raw attribute values (XML strings or Python values) to those kinds.

Both deck readers produce raw elements; :func:`attributes` checks one against :data:`SCHEMA`
and raises a :class:`~pysolver.DeckError` that names file, line, element, id and attribute.
"""
import math
import re

from .. import catalogue
from ..errors import DeckError, ExpressionError
from ..options import DECK_NAMES, rule_problem
from . import expr as ex
from . import units as un

# Attribute kinds: a converter name, whether required, default.
REQ = True
OPT = False
_ORIENT = {k: ("float", OPT, None) for k in
           ("a00", "a10", "a20", "a01", "a11", "a21", "a02", "a12", "a22",
            "psi", "theta", "phi", "yaw", "pitch", "roll", "e0", "e1", "e2", "e3")}
_USERSUB = {"usrsub_dll_name": ("str", OPT, None), "usrsub_fnc_name": ("routine", OPT, None),
            "usrsub_param_string": ("user", OPT, None), "script_name": ("str", OPT, None),
            "interpreter": (("PYTHON", "MATLAB"), OPT, None)}

_VTYPES = ("FORCEONLY", "TORQUEONLY", "FORCEANDTORQUE")
#: The six components of a field, a bushing, a beam: forces along and torques about J's axes.
SIX = ("x", "y", "z", "tx", "ty", "tz")
_PRELOADS = {f"preload_{c}": ("float", OPT, 0.0) for c in SIX}
#: A 6x6 matrix's entries: k11..k66 (row, column; MotionSolve's K11..K66).
_MATRIX = {f"{m}{r}{c}": ("float", OPT, 0.0) for m in "kc" for r in range(1, 7)
           for c in range(1, 7)}
_VCOMPS = {f"{lead}{c}_expression": ("expr?", OPT, None) for lead in "ft" for c in "xyz"}

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
                         "pos_z": ("float", OPT, 0.0), "rm_id": ("id", OPT, None),
                         "floating": ("bool", OPT, False), **_ORIENT},
    "Body_Rigid": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                   "isground": ("bool", OPT, False), "cg_id": ("id", OPT, None),
                   "im_id": ("id", OPT, None), "lprf_id": ("id", OPT, None),
                   "vm_id": ("id", OPT, None), "wm_id": ("id", OPT, None),
                   "mass": ("pos", OPT, None),
                   **{f"inertia_{k}": ("float", OPT, 0.0)
                      for k in ("xx", "yy", "zz", "xy", "yz", "xz")},
                   **{f"{v}_ic_{c}": ("float", OPT, 0.0) for v in "vw" for c in "xyz"}},
    "Body_Point": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                   "cg_id": ("id", REQ, None), "mass": ("pos", REQ, None),
                   "vm_id": ("id", OPT, None),
                   **{f"v_ic_{c}": ("float", OPT, 0.0) for c in "xyz"}},
    "Force_Penalty": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                      "type": (("EXPRESSION", "USERSUB"), OPT, "EXPRESSION"),
                      "expr": ("expr", OPT, None), "penalty": ("pos", REQ, None),
                      "penalty1": ("nonneg", OPT, 0.0), "unilateral": ("bool", OPT, False),
                      "smoothing_factor": ("pos", OPT, 1.0), **_USERSUB},
    "Force_Scalar_TwoBody": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                             "type": (("FORCE", "TORQUE"), REQ, None),
                             "i_marker_id": ("id", REQ, None), "j_marker_id": ("id", REQ, None),
                             # Altair's examples repeat the markers' bodies: checked
                             "body1_id": ("id", OPT, None), "body2_id": ("id", OPT, None),
                             "expr": ("expr", OPT, None), "val_expression": ("expr", OPT, None),
                             "val": ("float", OPT, None),
                             "is_action_only": ("bool", OPT, False), **_USERSUB},
    "Force_SpringDamper": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                           "type": (("TRANSLATIONAL", "ROTATIONAL"), REQ, None),
                           "i_marker_id": ("id", REQ, None), "j_marker_id": ("id", REQ, None),
                           "stiffness": ("nonneg", OPT, 0.0), "damping": ("nonneg", OPT, 0.0),
                           "length": ("float", OPT, 0.0), "preload": ("float", OPT, 0.0)},
    "Force_Vector_TwoBody": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                             "type": (_VTYPES, OPT, "FORCEONLY"),
                             "i_marker_id": ("id", REQ, None),
                             "j_floating_marker_id": ("id", REQ, None),
                             "ref_marker_id": ("id", OPT, None), **_VCOMPS},
    "Force_Vector_OneBody": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                             "type": (_VTYPES, OPT, "FORCEONLY"),
                             "marker_id": ("id", REQ, None),
                             "ref_marker_id": ("id", OPT, None), **_VCOMPS},
    "Force_Bushing": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                      "i_marker_id": ("id", REQ, None), "j_marker_id": ("id", REQ, None),
                      **{k: ("nonneg", OPT, 0.0) for k in ("kx", "ky", "kz", "ktx", "kty",
                                                           "ktz", "cx", "cy", "cz", "ctx",
                                                           "cty", "ctz")},
                      **{f"preload_{c}": ("float", OPT, 0.0)
                         for c in ("x", "y", "z", "tx", "ty", "tz")}},
    # Force_Field: K and C entry by entry (c11..c66 or cratio); nonlinear (FIESUB) refused
    "Force_Field": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                    "i_marker_id": ("id", REQ, None), "j_marker_id": ("id", REQ, None),
                    **_MATRIX, "cratio": ("nonneg", OPT, None),
                    **{f"length_{c}": ("float", OPT, 0.0) for c in SIX}, **_PRELOADS,
                    **_USERSUB},
    # Force_Beam: MotionSolve's attributes (E, G, ASY, ASZ in any case), and pysolver's
    # c11..c66 for Adams' CMATRIX
    "Force_Beam": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                   "i_marker_id": ("id", REQ, None), "j_marker_id": ("id", REQ, None),
                   **{k: ("pos", REQ, None) for k in ("length", "e", "g", "area", "ixx",
                                                      "iyy", "izz")},
                   "asy": ("nonneg", OPT, 0.0), "asz": ("nonneg", OPT, 0.0),
                   "cratio": ("nonneg", OPT, None),
                   **{k: v for k, v in _MATRIX.items() if k[0] == "c"}, **_PRELOADS},
    "Constraint_Joint": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                         "type": (("CONSTANT_VELOCITY", "CYLINDRICAL", "FIXED", "FREE", "HOOKE",
                                   "INLINE", "INPLANE", "ORIENTATION", "PARALLEL_AXES",
                                   "PERPENDICULAR", "PLANAR", "RACK_PINION", "REVOLUTE", "SCREW",
                                   "SPHERICAL", "TRANSLATIONAL", "UNIVERSAL", "ATPOINT"),
                                  REQ, None),
                         "i_marker_id": ("id", REQ, None), "j_marker_id": ("id", REQ, None),
                         "pitch": ("float", OPT, None), "pitch_diameter": ("float", OPT, None),
                         "is_virtual": ("bool", OPT, False),
                         # pysolver's: Adams' IC, ICTRAN, ICROT (the initial conditions)
                         **{f"ic_{c}_{n}": ("float", OPT, None) for c in ("tran", "rot")
                            for n in ("disp", "vel")}},
    "Constraint_Jprim": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                         "type": (("ATPOINT", "INLINE", "INPLANE", "ORIENTATION",
                                   "PARALLEL_AXES", "PERPENDICULAR"), REQ, None),
                         "i_marker_id": ("id", REQ, None), "j_marker_id": ("id", REQ, None),
                         "is_virtual": ("bool", OPT, False)},
    "Motion_Marker": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                      "type": (("EXPRESSION", "USERSUB"), OPT, "EXPRESSION"),
                      "i_marker_id": ("id", REQ, None), "j_marker_id": ("id", REQ, None),
                      "direction": (("X", "Y", "Z", "B1", "B2", "B3"), REQ, None),
                      "val_type": (("D", "V", "A"), OPT, "D"), "expr": ("expr", OPT, None),
                      "ic_disp": ("float", OPT, None), "ic_vel": ("float", OPT, None),
                      **_USERSUB},
    "Constraint_General": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                           "expr": ("expr", OPT, None), "i_marker_id": ("id", OPT, None),
                           "is_virtual": ("bool", OPT, False), **_USERSUB},
    "Constraint_Coupler": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                           "joint1_id": ("id", REQ, None), "joint2_id": ("id", REQ, None),
                           "joint3_id": ("id", OPT, None),
                           "freedom_1": (("T", "R"), OPT, None),
                           "freedom_2": (("T", "R"), OPT, None),
                           "freedom_3": (("T", "R"), OPT, None),
                           "coefficients": ("str", REQ, None),
                           "is_virtual": ("bool", OPT, False)},
    "Motion_Joint": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                     "type": (("EXPRESSION", "USERSUB"), OPT, "EXPRESSION"),
                     "joint_id": ("id", REQ, None), "motion_type": (("R", "T"), OPT, None),
                     "val_type": (("D", "V", "A"), OPT, "D"), "expr": ("expr", OPT, None),
                     "ic_disp": ("float", OPT, None), "ic_vel": ("float", OPT, None),
                     **_USERSUB},
    # a <CustomTasks><Schedule name="LoadControl"> block (seed 002), its Parameters flattened
    "LoadControl": {"id": ("id", OPT, None), "label": ("str", OPT, ""),
                    "velocity": ("float", REQ, None), "material": ("id", REQ, None),
                    "direction": (("1", "2", "3"), REQ, None),
                    "maxvelocity": ("pos", OPT, 1000.0), "load_function": ("str", REQ, None),
                    "kp": ("gain", OPT, 0.1), "ki": ("gain", OPT, 0.001),
                    "smooth": ("float", OPT, 0.95), "updatetime": ("pos", REQ, None),
                    "median_window": ("id", OPT, 1),
                    "load": (("REACTION", "CONTACT"), OPT, "REACTION")},
    "Reference_Variable": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                           "type": (("EXPRESSION", "USERSUB"), OPT, "EXPRESSION"),
                           "expr": ("expr", OPT, None), "initial_value": ("float", OPT, 0.0),
                           **_USERSUB},
    "Param_Transient": {"integrator_type": (("IDA", "DSTIFF", "VSTIFF", "MSTIFF", "GSTIFF",
                                             "WSTIFF", "ABAM", "I3", "SI2"), OPT, "IDA"),
                        # defaults of the integrator options: pysolver.options.Options
                        "integr_tol": ("pos", OPT, None), "h_max": ("pos", OPT, None),
                        "h_min": ("nonneg", OPT, None), "h0_max": ("pos", OPT, None),
                        "dae_constr_tol": ("pos", OPT, None),
                        "max_num_steps": ("id", OPT, None),
                        "max_step_growth": ("pos", OPT, None),
                        "nonlin_conv_coef": ("pos", OPT, None), "label": ("str", OPT, "")},
    "Post_Request": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                     "type": (("EXPRESSION", "USERSUB", "MARKER_DISPLACEMENT", "MARKER_VELOCITY",
                               "MARKER_ACCELERATION", "MARKER_FORCE", "ELEMENTAL_FORCE"), OPT,
                              "EXPRESSION"),
                     "elem_type": ("str", OPT, None), "elem_id": ("id", OPT, None),
                     "jflag": (("0", "1"), OPT, None),
                     "i_marker_id": ("id", OPT, None), "j_marker_id": ("id", OPT, None),
                     "ref_marker_id": ("id", OPT, None),
                     "comment": ("str", OPT, ""), **_USERSUB,
                     **{f"expr{k}": ("expr?", OPT, None) for k in range(1, 9)},
                     **{f"name{k}": ("str", OPT, None) for k in range(1, 9)}},
    "Param_Static": {"method": (("FIM_D", "FIM_S", "MKEAM"), OPT, "FIM_D"),
                     "max_ke_tol": ("pos", OPT, 1e-5), "max_dq_tol": ("pos", OPT, 1e-3),
                     "max_num_iter": ("id", OPT, 100), "max_imbalance": ("pos", OPT, 1e-4),
                     "max_error": ("pos", OPT, 1e-4), "stability": ("nonneg", OPT, 1e-10),
                     "compliance_delta": ("pos", OPT, 1e-3), "tlimit": ("pos", OPT, 20.0),
                     "alimit": ("pos", OPT, 0.17453292519943295), "label": ("str", OPT, "")},
    "Simulate": {"analysis_type": (("TRANSIENT", "STATIC", "QUASI-STATIC", "ASSEMBLY"), REQ,
                                   None),
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
    "Reference_Spline": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                         "num_xy_pair": ("id", OPT, None), "num_z": ("id", OPT, None),
                         "linear_extrap": ("bool", OPT, False),
                         "linear_extrapolate": ("bool", OPT, False),
                         "#text": ("str", OPT, None)},
    # kept for the 3-D view and the output settings: the attributes named are checked, the
    # rest ("*") kept as written (docs/deck-language.md, "Kept, not simulated")
    "Post_Graphic": {"id": ("id", REQ, None), "label": ("str", OPT, ""),
                     "type": ("str", REQ, None), "*": None},
    "ResOutput": {"*": None},
    "H3DOutput": {"*": None},
}
COMMANDS = ("Simulate", "Stop", "ResOutput", "H3DOutput")
#: Attributes MotionSolve spells in capitals (names are read in any case; XML is written so).
SPELLING = {"Force_Beam": {"e": "E", "g": "G", "asy": "ASY", "asz": "ASZ",
                           **{k: k.upper() for k in _MATRIX if k[0] == "c"}},
            "Force_Field": {k: k.upper() for k in _MATRIX}}
CANONICAL = {name.lower(): name for name in SCHEMA}
#: The id namespace of each element with a required id (the catalogue's kinds; a LoadControl's
#: id is optional and its tasks are numbered by deck.tasks).
_ID_KIND = {tag: e.kind for e in catalogue.ELEMENTS for tag in e.tags
            if e.kind != "loadcontrol"}



def element_file(names, file):
    """The file an element comes from: the deck's `file`, or the one its reader named in
    ``names["#file"]`` (an Adams command file's commands, an msolve class made in another
    module)."""
    return names.get("#file") or file


class Ctx:
    """Location of the element being built, for DeckError."""

    def __init__(self, file, tag, attrs, line, names):
        self.file, self.tag, self.attrs, self.line = element_file(names, file), tag, attrs, line
        self.names = names
        self.id = None

    def error(self, msg, attribute=None):
        shown = self.names.get(attribute, attribute) if attribute else None
        return DeckError(msg, **self.where(attribute), attribute=shown)

    def named(self, attribute):
        """An attribute as the deck names it (an .adm statement's keyword, END for end_time),
        for messages that name attributes."""
        return self.names.get(attribute, attribute)

    def where(self, attribute=None):
        # an .adm statement shows as written (MARKER/9), the element it became after it; an
        # attribute written on a line of its own (a <Parameter> of a task) is found there
        shown = self.names.get("#element")
        element = f"{shown} ({self.tag})" if shown else self.tag
        line = self.names.get("#lines", {}).get(attribute, self.line)
        file = self.names.get("#files", {}).get(attribute, self.file)
        return dict(file=file, line=line, element=element, id=None if shown else self.id)

    def warn(self, msg, attribute=None):
        """Issue a DeckWarning located at this element."""
        from ..errors import DeckWarning, warn
        shown = self.names.get(attribute, attribute) if attribute else None
        warn(DeckWarning(msg, **self.where(attribute), attribute=shown))


def convert(ctx, name, kind, raw):
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
    if kind == "routine":
        # a function name, or (Python decks) the function itself
        return raw if callable(raw) else str(raw)
    if kind == "user":
        return _user_params(ctx, name, raw)
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
            if isinstance(raw, (int, float)) and not isinstance(raw, bool):
                val = raw
            else:
                text = str(raw).strip()
                # whole numbers in E notation too (max_num_steps="1e8")
                val = int(text) if text.lstrip("+-").isdigit() else float(text)
            if isinstance(val, float) and (not math.isfinite(val) or val != int(val)):
                raise ValueError
            val = int(val)
        except (TypeError, ValueError, OverflowError):
            raise ctx.error(f"got {raw!r}; expected a positive integer", name) from None
        if val <= 0:
            raise ctx.error(f"got {val}; expected a positive integer", name)
        return val
    if kind == "gain":               # a number >= 0, or AUTO (chosen by the controller)
        if str(raw).strip().upper() == "AUTO":
            return "auto"
        kind = "nonneg"
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
        if text.strip().upper().startswith("USER"):
            # the parameters of a user subroutine (Python decks: FUNCTION="USER(...)")
            return (("user", _user_params(ctx, name, text)), text)
        try:
            return (ex.parse(text), text)
        except ExpressionError as err:
            raise ctx.error(f"bad expression {text!r}: {err}", name) from None
    raise AssertionError(kind)


_USER = re.compile(r"^\s*USER\s*\((.*)\)\s*$", re.I | re.S)


def _user_params(ctx, name, raw):
    """The numbers of ``USER(p1, ..., pn)`` as a tuple of floats."""
    m = _USER.match(str(raw))
    if not m:
        raise ctx.error(f"got {raw!r}; expected USER(p1, ..., pn) with numbers", name)
    inner = m.group(1).strip()
    out = []
    for item in inner.split(",") if inner else []:
        try:
            val = float(item.strip().replace("d", "e").replace("D", "e"))
        except ValueError:
            raise ctx.error(f"USER(...) parameter {item.strip()!r} is not a number", name) \
                from None
        if not math.isfinite(val):
            raise ctx.error(f"USER(...) parameter {item.strip()!r} is not finite", name)
        out.append(val)
    return tuple(out)


def _unit(ctx, name, kind, raw):
    val = str(raw).strip().upper()
    val = un.ALIASES.get(val, val)
    if val not in un.TABLES[kind]:
        raise ctx.error(f"unknown {kind} unit {raw!r}; expected one of "
                        f"{', '.join(sorted(un.TABLES[kind]))}", name)
    return val


def attributes(ctx):
    """Check names, presence and kinds of the element's attributes; return converted values."""
    schema = SCHEMA[ctx.tag]
    if "id" in schema and "id" in ctx.attrs:
        ctx.id = convert(ctx, "id", "id", ctx.attrs["id"])
    keep = "*" in schema                 # an element kept as written: others allowed
    for key in ctx.attrs:
        if key not in schema and not keep:
            raise ctx.error(f"unknown attribute; {ctx.tag} accepts "
                            f"{', '.join(sorted(schema)) or 'no attributes'}", key)
    out = {key: str(v) for key, v in ctx.attrs.items() if key not in schema} if keep else {}
    for key, spec in schema.items():
        if spec is None:
            continue
        kind, required, default = spec
        if key in ctx.attrs:
            out[key] = convert(ctx, key, kind, ctx.attrs[key])
            if ctx.tag == "Param_Transient" and key in DECK_NAMES:
                problem = rule_problem(key, out[key])
                if problem:
                    raise ctx.error(f"got {out[key]:g}; expected a value {problem}", key)
        elif required:
            raise ctx.error("missing required attribute", key)
        else:
            out[key] = default
    return out

