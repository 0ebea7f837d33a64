"""Constraint_Joint and Constraint_Jprim: checks at load, and each type's equations.

Every type is a list of holonomic equations g(q) = 0 between marker I (on the first body) and
marker J (on the second), in the forms of ../shared/reference/elements.md section 1.2: ``d``
components (d = oI - oJ, global: the origins coincide), ``dJ`` components (d along one of J's
axes: I's origin on a line or in a plane of J), and ``dot`` products of an axis of I with an
axis of J (the "dot-1" form: two axes stay perpendicular). The kernel holds each equation at
the position and the velocity level (csrc/elements/joint.c).
"""
from ..catalogue import JOINT_EQUATIONS as EQUATIONS
from ..catalogue import JOINTS_NOT_YET as NOT_YET
from ..records import Coupler, GeneralConstraint, Joint
from .motions import two_bodies

X, Y = 0, 1

def add_joint(model, ctx, a):
    """Validate one Constraint_Joint or Constraint_Jprim and add it to the model."""
    ctx.id = a["id"]
    kind = a["type"]
    if kind in NOT_YET:
        raise ctx.error(f"type {kind} is not supported yet: {NOT_YET[kind]}", "type")
    bi, bj, _ = two_bodies(model, ctx, a, "a joint")
    if any(e[0].startswith("dot") for e in EQUATIONS[kind]):
        for key, b in (("i_marker_id", bi), ("j_marker_id", bj)):
            if model.bodies[b].kind == "point":
                raise ctx.error(f"a {kind} joint holds orientations and needs rigid bodies; "
                                f"marker {a[key]} is on point body {b}", key)
    model.joints[a["id"]] = Joint(a["id"], kind, a["i_marker_id"], a["j_marker_id"],
                                  a["label"], bool(a.get("is_virtual")))
    model._where[("joint", a["id"])] = ctx


def equation_tree(joint, eq):
    """One equation of a joint as an expression tree the compiler lowers: measures for the
    ``d`` and ``dJ`` forms, ``("axdot", i, axis, j, axis)`` nodes for the dot products."""
    kind = eq[0]
    if kind == "d":
        return _call("DX DY DZ".split()[eq[1]], joint.i, joint.j)
    if kind == "dJ":
        return _call("DX DY DZ".split()[eq[1]], joint.i, joint.j, joint.j)
    if kind == "dot":
        return ("axdot", joint.i, eq[1], joint.j, eq[2])
    # CONSTANT_VELOCITY: xI.yJ + yI.xJ
    return ("bin", "+", ("axdot", joint.i, X, joint.j, Y), ("axdot", joint.i, Y, joint.j, X))


def _call(name, *ids):
    return ("call", name, [("num", float(i)) for i in ids], 0)


def add_gcon(model, ctx, a):
    """Validate one Constraint_General and add it to the model (that it reads displacements
    and time only is checked with the other expressions: deck.references)."""
    ctx.id = a["id"]
    tree, text = a["expr"]
    if tree[0] == "user":
        raise ctx.error("a GCOSUB user subroutine for Constraint_General is not supported "
                        "yet: give the expression", "expr")
    if a["i_marker_id"] is not None and a["i_marker_id"] not in model.markers:
        raise ctx.error(f"marker {a['i_marker_id']} does not exist", "i_marker_id")
    model.gcons[a["id"]] = GeneralConstraint(a["id"], tree, text, a["i_marker_id"] or 0,
                                             a["label"], bool(a["is_virtual"]))
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
    for jo, kind, r in zip(joints, freedoms, scales):
        q = (_call("AZ", jo.i, jo.j) if kind == "R" else _call("DZ", jo.i, jo.j, jo.j))
        term = ("bin", "*", ("num", r), q)
        expr = term if expr is None else ("bin", "+", expr, term)
    model.couplers[a["id"]] = Coupler(a["id"], tuple(ids), tuple(freedoms), tuple(scales),
                                      expr, a["label"], bool(a["is_virtual"]))
    model._where[("coupler", a["id"])] = ctx


def _finite(v):
    return v == v and abs(v) != float("inf")
