"""Constraint_Joint and Constraint_Jprim: checks at load, and each type's equations.

Every type is a list of holonomic equations g(q) = 0 between marker I (on the first body) and
marker J (on the second), in the forms of ../shared/reference/elements.md section 1.2: ``d``
components (d = oI - oJ, global: the origins coincide), ``dJ`` components (d along one of J's
axes: I's origin on a line or in a plane of J), and ``dot`` products of an axis of I with an
axis of J (the "dot-1" form: two axes stay perpendicular). SCREW and RACK_PINION hold one
``lead`` equation, d . zJ = lead theta + offset, with theta tracked through every turn (a
"turned" node: csrc/elements/turn.c). The kernel holds each equation at the position and the
velocity level (csrc/elements/joint.c).
"""
import math

from ..catalogue import JOINT_EQUATIONS as EQUATIONS
from ..records import Coupler, GeneralConstraint, Joint
from . import expr as ex
from . import usersubs
from .motions import two_bodies

X, Y = 0, 1

def add_joint(model, ctx, a):
    """Validate one Constraint_Joint or Constraint_Jprim and add it to the model."""
    ctx.id = a["id"]
    kind = a["type"]
    bi, bj, _ = two_bodies(model, ctx, a, "a joint")
    lead = _lead(ctx, a)
    if any(e[0].startswith("dot") or e[0] == "lead" for e in EQUATIONS[kind]):
        for key, b in (("i_marker_id", bi), ("j_marker_id", bj)):
            if model.bodies[b].kind == "point":
                raise ctx.error(f"a {kind} joint holds orientations and needs rigid bodies; "
                                f"marker {a[key]} is on point body {b}", key)
    offset = _offset(model, a["i_marker_id"], a["j_marker_id"], lead, EQUATIONS[kind][0]) \
        if lead else 0.0
    model.joints[a["id"]] = Joint(a["id"], kind, a["i_marker_id"], a["j_marker_id"],
                                  a["label"], bool(a.get("is_virtual")), lead, offset,
                                  _initial(ctx, a))
    model._where[("joint", a["id"])] = ctx


#: The coordinates a joint's initial conditions may set: the free ones (Adams' IC on a
#: TRANSLATIONAL or REVOLUTE joint, ICTRAN and ICROT on a CYLINDRICAL one).
IC_COORDINATES = {"TRANSLATIONAL": ("T",), "REVOLUTE": ("R",), "CYLINDRICAL": ("T", "R")}


def _initial(ctx, a):
    """The joint's initial conditions (Joint.ic) from ic_tran_disp .. ic_rot_vel, on the
    joint types that leave that coordinate free (else a DeckError)."""
    out = []
    for coord, name in (("T", "tran"), ("R", "rot")):
        keys = (f"ic_{name}_disp", f"ic_{name}_vel")
        given = [k for k in keys if a.get(k) is not None]
        if not given:
            continue
        if coord not in IC_COORDINATES.get(a["type"], ()):
            what = "translation" if coord == "T" else "rotation"
            has = IC_COORDINATES.get(a["type"])
            raise ctx.error(f"a {a['type']} joint has no free {what} to start from an initial "
                            "condition" + (f" (its free coordinate is its "
                                           f"{'translation' if has == ('T',) else 'rotation'})"
                                           if has else "; initial conditions belong to "
                                           "TRANSLATIONAL, REVOLUTE and CYLINDRICAL joints"),
                            given[0])
        if a.get(keys[0]) is None:
            raise ctx.error(f"an initial velocity needs the initial displacement too "
                            f"({ctx.named(keys[0])})", keys[1])
        for k in given:
            if not math.isfinite(a[k]):
                raise ctx.error(f"got {a[k]!r}; expected a finite number", k)
        out.append((coord, a.get(keys[0]), a.get(keys[1])))
    return tuple(out)


def _lead(ctx, a):
    """A SCREW's pitch / 2 pi or a RACK_PINION's pitch_diameter / 2 (0 for other types)."""
    kind = a["type"]
    need = {"SCREW": "pitch", "RACK_PINION": "pitch_diameter"}.get(kind)
    for key in ("pitch", "pitch_diameter"):
        if a.get(key) is not None and key != need:
            raise ctx.error(f"{key} belongs to a "
                            f"{'SCREW' if key == 'pitch' else 'RACK_PINION'} joint, not a "
                            f"{kind}", key)
    if need is None:
        return 0.0
    v = a.get(need)
    if v is None:
        raise ctx.error(f"a {kind} joint needs {need}", need)
    if need == "pitch" and (v == 0 or not math.isfinite(v)):
        raise ctx.error("pitch is the translation per turn: a finite number, not 0", need)
    if need == "pitch_diameter" and not (v > 0 and math.isfinite(v)):
        raise ctx.error("pitch_diameter is a finite length > 0", need)
    return v / (2 * math.pi) if need == "pitch" else v / 2


def _offset(model, i, j, lead, eq):
    """d . zJ - lead theta of a lead equation at the deck's marker positions: the relation
    the joint keeps."""
    mi, mj = model.markers[i], model.markers[j]
    _, a, b, sign, c, d = eq
    theta = math.atan2(sign * float(mi.rot[:, a] @ mj.rot[:, b]),
                       float(mi.rot[:, c] @ mj.rot[:, d]))
    return float((mi.pos - mj.pos) @ mj.rot[:, 2]) - lead * theta


def equation_tree(joint, eq):
    """One equation of a joint as an expression tree the compiler lowers: measures for the
    ``d`` and ``dJ`` forms, ``("axdot", i, axis, j, axis)`` nodes for the dot products."""
    kind = eq[0]
    if kind == "d":
        return ex.call("DX DY DZ".split()[eq[1]], joint.i, joint.j)
    if kind == "dJ":
        return ex.call("DX DY DZ".split()[eq[1]], joint.i, joint.j, joint.j)
    if kind == "dot":
        return ("axdot", joint.i, eq[1], joint.j, eq[2])
    if kind == "lead":
        # d . zJ - lead theta - offset, theta unwrapped by the joint's tracked angle
        along = ex.call("DZ", joint.i, joint.j, joint.j)
        turned = ("turned", lead_angle(joint.i, joint.j, eq), ("joint", joint.id, 0))
        return ("bin", "-", ("bin", "-", along, ("bin", "*", ("num", joint.lead), turned)),
                ("num", joint.offset))
    # CONSTANT_VELOCITY: xI.yJ + yI.xJ
    return ("bin", "+", ("axdot", joint.i, X, joint.j, Y), ("axdot", joint.i, Y, joint.j, X))


def lead_angle(i, j, eq):
    """theta = atan2(sign a_I . b_J, c_I . d_J) of a ("lead", a, b, sign, c, d) equation, in
    (-pi, pi]."""
    _, a, b, sign, c, d = eq
    s = ("axdot", i, a, j, b)
    return ("call", "ATAN2", [s if sign > 0 else ("neg", s), ("axdot", i, c, j, d)], 0)


def add_gcon(model, ctx, a):
    """Validate one Constraint_General and add it to the model (that it reads displacements
    and time only is checked with the other expressions: deck.references)."""
    ctx.id = a["id"]
    tree, text, sub = usersubs.expression_or_routine(model, ctx, a, "GCOSUB")
    if a["i_marker_id"] is not None and a["i_marker_id"] not in model.markers:
        raise ctx.error(f"marker {a['i_marker_id']} does not exist", "i_marker_id")
    model.gcons[a["id"]] = GeneralConstraint(a["id"], tree, text, a["i_marker_id"] or 0,
                                             a["label"], bool(a["is_virtual"]), sub)
    model._where[("gcon", a["id"])] = ctx


#: The coordinates a coupler may relate on each joint type (elements.md 2.2).
COUPLED = {"REVOLUTE": ("R",), "TRANSLATIONAL": ("T",), "CYLINDRICAL": ("T", "R")}


def add_coupler(model, ctx, a):
    """Validate one Constraint_Coupler (after the joints) and add it with its relation as an
    expression: r1 q1 + r2 q2 [+ r3 q3], q = DZ(I, J, J) (T) or AZ(I, J) (R) of each joint.
    Coefficients as Adams' SCALES: one fewer than the joints means r1 = 1."""
    ctx.id = a["id"]
    ids = [a[f"joint{k}_id"] for k in (1, 2, 3) if a[f"joint{k}_id"] is not None]
    joints, freedoms = [], []
    for k, jid in enumerate(ids, 1):
        jo = model.joints.get(jid)
        if jo is None:
            raise ctx.error(f"joint {jid} does not exist (a Constraint_Joint id)", f"joint{k}_id")
        free = COUPLED.get(jo.type)
        if free is None:
            raise ctx.error(f"joint {jid} is {jo.type}; a coupler relates REVOLUTE (R), "
                            "TRANSLATIONAL (T) or CYLINDRICAL (R or T) joints", f"joint{k}_id")
        kind = a[f"freedom_{k}"] or (free[0] if len(free) == 1 else None)
        if kind is None:
            raise ctx.error(f"joint {jid} is CYLINDRICAL: say which coordinate is coupled, "
                            f'freedom_{k}="R" or "T"', f"freedom_{k}")
        if kind not in free:
            raise ctx.error(f"freedom {kind} is not a coordinate of {jo.type} joint {jid}",
                            f"freedom_{k}")
        joints.append(jo)
        freedoms.append(kind)
    try:
        scales = [float(v) for v in a["coefficients"].replace(",", " ").split()]
    except ValueError:
        scales = []
    if len(scales) == len(ids) - 1:
        scales = [1.0] + scales
    if len(scales) != len(ids) or not all(map(_finite, scales)) or not any(scales):
        raise ctx.error(f"got {a['coefficients']!r}; expected {len(ids)} numbers (or "
                        f"{len(ids) - 1}, r1 = 1), not all zero", "coefficients")
    expr = None
    for k, (jo, kind, r) in enumerate(zip(joints, freedoms, scales)):
        # a rotation through every turn: AZ unwrapped by the coupler's tracked angle k
        q = (("turned", ex.call("AZ", jo.i, jo.j), ("coupler", a["id"], k)) if kind == "R"
             else ex.call("DZ", jo.i, jo.j, jo.j))
        term = ("bin", "*", ("num", r), q)
        expr = term if expr is None else ("bin", "+", expr, term)
    model.couplers[a["id"]] = Coupler(a["id"], tuple(ids), tuple(freedoms), tuple(scales),
                                      expr, a["label"], bool(a["is_virtual"]))
    model._where[("coupler", a["id"])] = ctx


def _finite(v):
    return v == v and abs(v) != float("inf")
