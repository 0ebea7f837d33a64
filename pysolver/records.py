"""The records a Model holds: one frozen dataclass per element kind (Body, Marker, Penalty,
Sensor, ...), read-only once loaded; an assignment says how a number is changed (``run(params=
...)`` or the deck). :mod:`pysolver.model` re-exports them.

Longer than 420 lines because it is the model's vocabulary: one short record per kind of
element (twenty of them), which every stage after the deck reads.
"""
import dataclasses
import functools
import hashlib

import numpy as np

#: Units of a deck without a ``Units`` element.
UNIT_DEFAULTS = {"mass": "KILOGRAM", "length": "METER", "time": "SECOND", "force": "NEWTON"}

#: What an assignment to a loaded model is told.
READ_ONLY = ("a loaded Model is what its deck says and does not change: give a number for one "
             "run with model.run(params={{'{example}': value}}) (every path: "
             "model.compile().parameters.paths()), or edit the deck and load it again")


def _read_only(self, name, value=None):
    kind = type(self).__name__
    example = "Body_Point/2/mass" if kind != "Model" else "Force_Gravity/grav_z"
    raise AttributeError(f"cannot set {kind}.{name}: " + READ_ONLY.format(example=example))


def record(cls):
    """A frozen dataclass whose assignments say how a number is changed."""
    cls = dataclasses.dataclass(frozen=True)(cls)
    cls.__setattr__ = _read_only
    cls.__delattr__ = _read_only
    return cls


@record
class Marker:
    id: int
    body: int              # body id (ground id for ground markers)
    pos: np.ndarray        # global position at t = 0
    rot: np.ndarray        # global axes at t = 0 (columns x, y, z)
    label: str = ""
    floating: bool = False # a floating marker (Adams' FLOATING): placed by the force using it
    at: int = 0            # a floating marker's place: the I marker of its vector forces


@record
class Placement:
    """How the deck places a marker, kept so that a sweep's ``Reference_Marker/ID/pos_*`` mean
    the deck's own numbers (pysolver.build.params): `local` (its pos_*, an Adams QP) are in
    the frame of marker `rm` (rm_id, RM: the marker moves with it; `axes` its axes as the
    loader used them) or, without one, in a fixed frame (`origin`, `axes`: an Adams part's),
    or global (both None). The global place is origin + axes @ local, as the loader made it."""
    local: np.ndarray
    rm: int = None
    origin: np.ndarray = None
    axes: np.ndarray = None


@record
class Rates:
    """A body's initial velocity and spin as the deck gives them (for a sweep's v_ic_* and
    w_ic_*, which mean the deck's numbers): `v` along marker `vm`'s axes (None: the global
    axes), `w` along marker `wm`'s (None: the global axes; an Adams or msolve PART's WX..
    without WM have wm = its CM marker)."""
    v: np.ndarray
    vm: int = None
    w: np.ndarray = None
    wm: int = None


@record
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
    cg: int = None               # its centre-of-mass marker (the body frame)
    im_rot: np.ndarray = None    # axes of the inertia marker in the body frame
    inertia_im: np.ndarray = None    # inertia tensor the deck gives, about the im origin and axes
    im: int = None               # its inertia marker (the cg marker when the deck names none)


@dataclasses.dataclass
class UserSub:
    """A user subroutine standing in for an element's expression (``type="USERSUB"``).

    Until it is resolved into an expression tree (pysolver.deck.usersub, when the model is first
    compiled) the element's ``expr`` is None.
    """
    name: str              # the conventional name: PFOSUB, SENSUB, SEVSUB, VARSUB, SFOSUB, REQSUB
    routine: object        # function name in the script or library, or a Python callable
    par: tuple             # the numbers of USER(p1, ..., pn)
    script: str = None     # path of a Python script defining the routine
    library: str = None    # path of a C shared library defining it
    attribute: str = "usrsub_fnc_name"   # the deck attribute to name in errors
    untraced: str = None   # why a Python routine could not be traced (it is called instead)

    @property
    def label(self):
        """The routine as the deck names it (``SFO_RAISE``, a function's name), for messages."""
        return self.routine if isinstance(self.routine, str) else \
            getattr(self.routine, "__name__", "routine")

    def describe(self):
        """A short text for summaries and logs."""
        where = self.script or self.library or "a Python callable"
        return f"USER({', '.join(f'{p:g}' for p in self.par)}) -> {self.label} ({where})"


@record
class Penalty:
    id: int
    expr: tuple
    text: str
    penalty: float
    penalty1: float
    unilateral: bool
    smoothing: float
    label: str = ""
    usersub: UserSub = None


@record
class ScalarForce:
    """Force_Scalar_TwoBody (or, under the negative id, a Force_SpringDamper's law): a force
    along the line J to I (positive repels), or a torque about zJ. `turns`: its expression
    reads an angle tracked through every turn."""
    id: int
    torque: bool
    i: int
    j: int
    expr: tuple
    text: str
    label: str = ""
    usersub: UserSub = None
    turns: bool = False
    action_only: bool = False


@record
class SpringDamper:
    """Force_SpringDamper (pysolver.deck.springs): TRANSLATIONAL or ROTATIONAL; `length` the
    free length, or the reference angle of a ROTATIONAL one (radians)."""
    id: int
    type: str
    i: int
    j: int
    stiffness: float
    damping: float
    length: float
    preload: float
    label: str = ""


@record
class VectorForce:
    """Force_Vector_TwoBody or OneBody (or, under a negative key, the law of a Force_Bushing,
    Force_Field or Force_Beam: `owner` names it): a force and a torque with components exprs
    (fx, fy, fz, tx, ty, tz in marker `ref`'s axes; 0: global axes) on I's body at I, and
    their opposite on J's body at the same point (J is the floating marker: only its body
    matters, and a `floating` one is at I for measures, deck.floating; 0 for a OneBody force:
    no reaction)."""
    id: int
    i: int
    j: int
    ref: int
    exprs: list
    texts: list
    label: str = ""
    owner: tuple = ()          # (tag, id) of the element whose law it is; () for a deck's own


#: The elements held as a vector force (pysolver.deck.vectors, pysolver.deck.fields), each
#: with the offset of its laws' keys in Model.vforces (law_key).
LAW_OFFSETS = {"Force_Bushing": 0, "Force_Field": 2 ** 61, "Force_Beam": 2 ** 62}


def law_key(tag, eid):
    """The key in Model.vforces of the vector force that holds element `eid` of `tag` (a
    Force_Bushing, Force_Field or Force_Beam): negative, so it meets no deck vector force's
    id, and apart for each kind (a bushing's is -id)."""
    return -(LAW_OFFSETS[tag] + eid)


@record
class Spline:
    """Reference_Spline: the curve through the points (x, y), x strictly increasing; outside
    them a line (linear_extrap) or a parabola (pysolver.build.splines). A surface has z
    values (strictly increasing) and y holds one curve per z value, curve after curve
    (len(x) * len(z) values)."""
    id: int
    x: tuple
    y: tuple
    linear_extrap: bool = False
    label: str = ""
    z: tuple = ()

    def curve(self, k):
        """The curve at z[k] of a surface, as a Spline of its own."""
        n = len(self.x)
        return Spline(self.id, self.x, self.y[k * n:(k + 1) * n], self.linear_extrap,
                      self.label)


@record
class Graphic:
    """Post_Graphic (Adams GRAPHICS): geometry for the 3-D view, `attrs` its other attributes
    as written (their marker references checked at load); no effect on the motion."""
    id: int
    type: str
    attrs: dict
    label: str = ""


@record
class Bushing:
    """Force_Bushing (pysolver.deck.vectors): six stiffnesses, dampings and preloads (x, y,
    z, tx, ty, tz, in J's axes)."""
    id: int
    i: int
    j: int
    stiffness: tuple
    damping: tuple
    preload: tuple
    label: str = ""


@record
class Field:
    """Force_Field (pysolver.deck.fields): F = -K (X - length) - C V + preload in J's axes,
    X = (DX, DY, DZ, AX, AY, AZ) of I relative to J and V their rates; `stiffness` and
    `damping` the 36 entries of K and C row by row (K[r][c] multiplies X[c] in component r),
    C = cratio K when `cratio` is not None (then `damping` is all zero)."""
    id: int
    i: int
    j: int
    stiffness: tuple
    damping: tuple
    cratio: object
    length: tuple
    preload: tuple
    label: str = ""


@record
class Beam:
    """Force_Beam (pysolver.deck.fields): a massless uniform Timoshenko beam along J's x,
    I at `length` from J undeformed; the field of its closed-form stiffness (e: Young's
    modulus, g: shear modulus, ixx the torsion constant, iyy and izz the bending moments,
    asy and asz the shear area ratios) with damping C = cratio K or `damping` (36 entries row
    by row), and a preload (three forces, three torques in J's axes)."""
    id: int
    i: int
    j: int
    length: float
    e: float
    g: float
    area: float
    ixx: float
    iyy: float
    izz: float
    asy: float
    asz: float
    cratio: object
    damping: tuple
    preload: tuple
    label: str = ""


@record
class Motion:
    """Motion_Marker: the displacement (D), velocity (V) or acceleration (A) of marker I
    relative to J along one axis of J (X, Y, Z: DX/DY/DZ(I, J, J)) or its angle B1, B2, B3
    (the body-fixed 1-2-3 angles of I relative to J, ORIENT(1, k, I, J)) follows expr, a
    function of time. A Motion_Joint is one on its joint's
    markers (`joint` its id; 0 for a Motion_Marker): Z for a translation, B3 for a rotation.
    ic_disp (V or A) and ic_vel (A): the driven measure and its rate at t = 0 (None: the
    bodies' initial state decides)."""
    id: int
    i: int
    j: int
    direction: str
    val_type: str
    expr: tuple
    text: str
    label: str = ""
    joint: int = 0
    ic_disp: float = None
    ic_vel: float = None
    usersub: UserSub = None


@record
class Joint:
    """Constraint_Joint (or Constraint_Jprim): marker I's body held to marker J's by the
    equations of `type` (pysolver.deck.joints.EQUATIONS). The reactions are res.joint(id).
    A SCREW or RACK_PINION holds d . zJ = lead theta + offset (catalogue, "lead").
    ``ic``: the joint's initial conditions, one (coordinate, displacement, velocity) per
    coordinate given, "T" (DZ(I, J, J)) or "R" (AZ(I, J)), either number None when not given:
    held by the initial-conditions analysis only (pysolver.build.icjoint)."""
    id: int
    type: str
    i: int
    j: int
    label: str = ""
    virtual: bool = False
    lead: float = 0.0      # SCREW pitch / 2 pi, RACK_PINION pitch_diameter / 2: d per radian
    offset: float = 0.0    # SCREW, RACK_PINION: d - lead theta at the deck's positions
    ic: tuple = ()


@record
class GeneralConstraint:
    """Constraint_General: the expression `expr` of displacements and time held at zero (one
    equation, like a joint's: its reaction res.motion-like state gcon<id>.reaction); `i` the
    marker MotionSolve reports the reaction at (recorded; 0 when none)."""
    id: int
    expr: tuple
    text: str
    i: int = 0
    label: str = ""
    virtual: bool = False
    usersub: UserSub = None


@record
class Coupler:
    """Constraint_Coupler: sum_k scales[k] q_k = 0 over the coordinates q_k of `joints` (T: DZ
    of the joint's I along zJ; R: its rotation AZ about zJ), `freedoms` their kinds; `expr` the
    relation as an expression tree (pysolver.deck.joints.add_coupler)."""
    id: int
    joints: tuple
    freedoms: tuple
    scales: tuple
    expr: tuple
    label: str = ""
    virtual: bool = False


@record
class LoadControl:
    """The LoadControl task (seed 002): every update_time, the velocity of `body` along global
    axis `direction` (0, 1, 2) is set so that the load on it follows `load_expr` (a function of
    time). The body is driven by the velocity motion `motion` (a Motion in Model.motions whose
    expression is the controller's output)."""
    id: int
    body: int
    direction: int
    velocity: float
    max_velocity: float
    load_expr: tuple
    load_text: str
    kp: object                  # a number or "auto"
    ki: object
    smooth: float
    update_time: float
    median_window: int
    motion: int
    load: str = "REACTION"      # or "CONTACT": the penalties' force on the body
    label: str = ""


@record
class Variable:
    id: int
    expr: tuple
    text: str
    label: str = ""
    usersub: UserSub = None


@record
class Request:
    id: int
    exprs: list            # 8 entries: parse tree or None
    texts: list
    names: list
    label: str = ""
    usersub: UserSub = None


@record
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
    usersub: UserSub = None

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


@record
class Evaluate:
    """A Sensor_Evaluate: stored when a parent sensor fires, read by SENVAL(id)."""
    id: int
    expr: tuple
    text: str
    label: str = ""
    usersub: UserSub = None


@record
class Static:
    """Settings of ``Param_Static`` (seed 004 defaults); see :mod:`pysolver.solve.statics`."""
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


@record
class Simulate:
    analysis: str
    end_time: float
    print_interval: float
    line: int = None
    file: str = None            # the file of its line (a command file's), None: the deck's


@dataclasses.dataclass
class Source:
    """Where a deck came from, for error messages and result metadata."""
    file: str
    text: str
    fmt: str
    user_code: bool = True      # False: loaded with user_code=False (it names no code to run)
    simulate: dict = None       # Simulate attributes that replace the deck's commands
    built: str = None           # a Python deck: a hash of the elements it recorded
    modules: tuple = ()         # a Python deck: (path, sha256) of the user's modules it imports

    @functools.cached_property
    def sha256(self):
        return hashlib.sha256(self.text.encode()).hexdigest()


def _copy(rec):
    """A record with writable copies of its arrays (and of its user subroutine)."""
    changes = {f.name: getattr(rec, f.name).copy() for f in dataclasses.fields(rec)
               if isinstance(getattr(rec, f.name), np.ndarray)}
    if getattr(rec, "usersub", None) is not None:
        changes["usersub"] = dataclasses.replace(rec.usersub)
    return dataclasses.replace(rec, **changes)
