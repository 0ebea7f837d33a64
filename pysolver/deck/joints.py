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
from ..records import GeneralConstraint, Joint
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
