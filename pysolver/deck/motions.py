"""Motion_Marker and Motion_Joint: checks at load.

A motion drives marker I relative to marker J along or about one axis of J; its expression
is a function of time only (the kernel differentiates it in time; splines and variables of
time included, checked with the references: references.time_only). At load: both markers
exist, they are not on one body (ground included), a rotation does not involve a point body,
and no two motions drive the same axis between the same two bodies. X, Y, Z drive DX, DY,
DZ(I, J, J); B1, B2, B3 the body-fixed 1-2-3 angles of I relative to J (Adams' MOTION
statement: "the first angle of the Body 1-2-3 Euler angle sequence"; MotionSolve's
Motion_Marker names them B1(I,J)..B3(I,J) the same way), so three driven angles give
R = Rx(B1) Ry(B2) Rz(B3). A Motion_Joint is the motion of its joint's markers along z of J
(T: DZ(I, J, J)) or about it (R: AZ(I, J)), allowed on the joint types that leave that
coordinate free.
"""
import dataclasses

from ..errors import DeckError
from ..model import Motion
from . import expr as ex
from . import usersubs
from .references import velocity_level

#: The motions that integrate from an initial condition, in words.
_TYPES = {"VA": "a V or A motion", "A": "an A motion"}


def two_bodies(model, ctx, a, noun):
    """(I's body, J's body, ground body ids) of an element holding marker I to marker J: both
    markers exist, on different bodies, not both on ground (else a DeckError)."""
    ctx.id = a["id"]
    for key in ("i_marker_id", "j_marker_id"):
        if a[key] not in model.markers:
            raise ctx.error(f"marker {a[key]} does not exist", key)
    bi, bj = (model.markers[a[k]].body for k in ("i_marker_id", "j_marker_id"))
    ground = {b.id for b in model.bodies.values() if b.kind == "ground"}
    if bi == bj or (bi in ground and bj in ground):
        where = "ground" if bi in ground else f"body {bi}"
        raise ctx.error(f"{noun} needs I and J on different bodies, one of them moving; "
                        f"both markers are on {where}", "j_marker_id")
    return bi, bj, ground


#: The coordinates a Motion_Joint may drive on each joint type (elements.md 3.1).
JOINT_COORDINATES = {"REVOLUTE": ("R",), "TRANSLATIONAL": ("T",), "CYLINDRICAL": ("R", "T")}


def add_joint_motion(model, ctx, a):
    """Validate one Motion_Joint and add it to the model as a motion of its joint's markers
    (after the joints are loaded)."""
    ctx.id = a["id"]
    joint = model.joints.get(a["joint_id"])
    if joint is None:
        raise ctx.error(f"joint {a['joint_id']} does not exist (a Constraint_Joint id)",
                        "joint_id")
    free = JOINT_COORDINATES.get(joint.type)
    if free is None:
        raise ctx.error(f"joint {joint.id} is {joint.type}; a Motion_Joint drives a "
                        "REVOLUTE (R), TRANSLATIONAL (T) or CYLINDRICAL (R or T) joint",
                        "joint_id")
    kind = a["motion_type"] or (free[0] if len(free) == 1 else None)
    if kind is None:
        raise ctx.error(f"joint {joint.id} is CYLINDRICAL: say which coordinate is driven, "
                        'motion_type="R" (rotation) or "T" (translation)', "motion_type")
    if kind not in free:
        raise ctx.error(f"motion_type {kind} is not a coordinate of {joint.type} joint "
                        f"{joint.id} (it has {' and '.join(free)})", "motion_type")
    add_motion(model, ctx, dict(a, i_marker_id=joint.i, j_marker_id=joint.j,
                                direction="B3" if kind == "R" else "Z"), joint.id)
    _motion_wins(model, ctx, joint, kind)


def _motion_wins(model, ctx, joint, kind):
    """Decision: a Motion_Joint on a coordinate the joint's initial conditions also set wins
    (MotionSolve's precedence: motions before joints' initial conditions); the joint's are
    dropped with a DeckWarning naming them (docs/deck-language.md, "Initial positions")."""
    ic = [c for c in joint.ic if c[0] == kind]
    if not ic:
        return
    name = "translation" if kind == "T" else "rotation"
    jctx = model._where[("joint", joint.id)]
    keys = [k for k, v in zip(("disp", "vel"), ic[0][1:]) if v is not None]
    attr = f"ic_{'tran' if kind == 'T' else 'rot'}_{keys[0]}"
    motion = ctx.names.get("#element") or f"{ctx.tag} {ctx.id}"
    jctx.warn(f"the initial {name} is not used: {motion} drives the joint's {name}, and a "
              "motion's own value at the start wins", attr)
    model.joints[joint.id] = dataclasses.replace(
        joint, ic=tuple(c for c in joint.ic if c[0] != kind))


def add_motion(model, ctx, a, joint=0):
    """Validate one Motion_Marker's attributes (or a Motion_Joint's, on its joint's markers)
    and add it to the model."""
    bi, bj, ground = two_bodies(model, ctx, a, "a motion")
    rotation = a["direction"].startswith("B")
    if rotation:
        for key, b in (("i_marker_id", bi), ("j_marker_id", bj)):
            if model.bodies[b].kind == "point":
                raise ctx.error(f"a rotation ({a['direction']}) needs rigid bodies; marker "
                                f"{a[key]} is on point body {b}", key)
    tree, text, sub = usersubs.expression_or_routine(model, ctx, a, "MOTSUB")
    # the integration constants: a displacement for V and A, a velocity for A; one a motion
    # does not integrate is not used (Adams and MotionSolve take it only for those types;
    # MotionView and Inspire write ic_disp = ic_vel = 0 on every motion): a DeckWarning when
    # it is not 0
    a = dict(a)
    for key, kinds in (("ic_disp", "VA"), ("ic_vel", "A")):
        if a.get(key) is not None and a["val_type"] not in kinds:
            if a[key] != 0:
                ctx.warn(f"{ctx.names.get(key, key)} = {a[key]:g} is not used: it is the "
                         f"integration constant of {_TYPES[kinds]}, and this one is val_type "
                         f"{a['val_type']}, whose function gives the "
                         f"{'displacement' if a['val_type'] == 'D' else 'velocity'} itself",
                         key)
            a[key] = None
    other = clashes(model, bi, bj, a["direction"], ground)
    if other is not None:
        tag = "Motion_Joint" if other > 0 and model.motions[other].joint else "Motion_Marker"
        what = f"{tag} {other}" if other > 0 else f"LoadControl {-other}"
        coordinate = (("R" if a["direction"] == "B3" else "T") + f" of joint {joint}" if joint
                      else a["direction"])
        raise ctx.error(f"{what} already drives {coordinate} between these bodies; two "
                        f"motions would fight over one coordinate",
                        "motion_type" if joint else "direction")
    model.motions[a["id"]] = Motion(a["id"], a["i_marker_id"], a["j_marker_id"],
                                    a["direction"], a["val_type"], tree, text, a["label"],
                                    joint, a.get("ic_disp"), a.get("ic_vel"), sub)
    model._where[("motion", a["id"])] = ctx


def measure(motion):
    """The expression tree of the driven quantity: DX/DY/DZ(I, J, J) along J's axes; for a
    Motion_Marker's B1, B2, B3 the first, second, third angle of the body-fixed 1-2-3 sequence
    of I relative to J (ORIENT(1, k, I, J): R = Rx(B1) Ry(B2) Rz(B3), as Adams' MOTION
    statement defines them); for a Motion_Joint's rotation AZ(I, J), its value in (-pi, pi]
    (the motion wraps its error: Compiler.motion)."""
    if motion.direction.startswith("B"):
        if motion.joint:
            return ex.call("AZ", motion.i, motion.j)
        k = int(motion.direction[1])
        return ex.call("ORIENT", 1, k, motion.i, motion.j)
    return ex.call("D" + motion.direction, motion.i, motion.j, motion.j)


def clashes(model, bi, bj, direction, ground):
    """The id of a motion already driving `direction` between bodies bi and bj (a body id 0
    or one in `ground` stands for ground), or None."""
    def side(b):
        return 0 if b == 0 or (ground and b in ground) or model.bodies[b].kind == "ground" else b
    pair = frozenset((side(bi), side(bj)))
    for other in model.motions.values():
        bodies = frozenset(side(model.markers[m].body) if m else 0 for m in (other.i, other.j))
        if bodies == pair and other.direction == direction:
            return other.id
    return None


def check_static_motions(model):
    """Statics hold a motion's displacement; a velocity or acceleration motion gives none to
    hold (docs/deck-language.md, "Statics with constraints")."""
    static = [c for c in model.commands if c.analysis in ("STATIC", "QUASI-STATIC")]
    moving = [gc for gc in model.gcons.values() if velocity_level(gc)]
    if static and moving:
        raise DeckError(f"{static[0].analysis.lower()} analyses hold positions, and "
                        f"Constraint_General {moving[0].id} is a relation of velocities "
                        "(non-holonomic); run the scene as a transient", file=static[0].file,
                        line=static[0].line, element="Simulate", attribute="analysis_type")
    rated = [mo for mo in model.motions.values() if mo.val_type != "D"]
    if static and rated:
        mo = rated[0]
        kind = "velocity" if mo.val_type == "V" else "acceleration"
        what = (f"LoadControl {-mo.id} drives its body through a {kind}" if mo.id < 0 else
                f"{'Motion_Joint' if mo.joint else 'Motion_Marker'} {mo.id} gives a {kind} "
                f"(val_type {mo.val_type}); write it as a displacement (val_type D)")
        raise DeckError(f"{static[0].analysis.lower()} analyses hold each motion's "
                        f"displacement, and {what}, or run the scene as a transient",
                        file=static[0].file, line=static[0].line, element="Simulate",
                        attribute="analysis_type")
