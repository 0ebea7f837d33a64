"""Floating markers: Adams' ``MARKER/id, ..., FLOATING`` (XML ``Reference_Marker
floating="TRUE"``, msolve ``MARKER(..., FLOATING=True)``).

A two-body vector force (VFORCE, VTORQUE, GFORCE; Force_Vector_TwoBody) applies its reaction
at a floating marker JFLOAT of the reaction part, and Adams "moves the JFLOAT marker to keep it
superimposed on the I marker, meaning the point of application of the reaction force may move
with respect to its part" (Adams Solver's VFORCE and GFORCE pages; MotionView's marker page:
the J marker of such a force must coincide with the I marker, so it floats). The kernel
applies the reaction at I's point already; here the marker itself is put there
(:func:`place_floating`): its ``at`` is the I marker, whose frame it is for every measure
(DX(9) = DX(20), VX, ACCX, its axes in AX..AZ, PSI.., ORIENT, and as a resolution or
derivative frame), and a force function's value at it (VFORCE(id, 1, ...), FX(9), TZ(9, 20))
is the reaction at I's point: -F and -T.

Decisions: each force's reaction is at its own I point, whatever else uses the marker; a
floating marker whose forces have different I markers has no one place (``at`` is -1) and an
expression that names it is a DeckError (give each I marker its own floating marker); a
floating marker no force uses stays at its part's frame, as placed; a floating marker
anywhere else (a body's cg or inertia marker, a joint's, motion's, spring's, bushing's,
field's, beam's or scalar force's marker, a vector force's I or reference marker) is a
DeckError: Adams takes
floating markers on vector forces (and curve contacts, which pysolver does not model) only.
"""
import dataclasses

from ..errors import DeckError


def placed(model, mid):
    """The marker whose frame marker `mid` is in a measure: a floating marker's I marker,
    else `mid` itself (0, the global frame, stays 0)."""
    return (max(model.markers[mid].at, 0) or mid) if mid else 0


def users(model, mid):
    """[(vector force id, its I marker)] of the two-body vector forces whose JFLOAT is mid."""
    return [(vid, vf.i) for vid, vf in sorted(model.vforces.items()) if vid > 0 and vf.j == mid]


def place_floating(model):
    """Put each floating marker at the I marker of the vector forces that use it (its
    ``at``; -1 where they have different I markers), after every element is loaded;
    DeckError for a floating marker used elsewhere."""
    floating = {mid for mid, m in model.markers.items() if m.floating}
    _refuse_elsewhere(model, floating)
    for mid in sorted(floating):
        places = {i for _, i in users(model, mid)}
        if places:
            at = places.pop() if len(places) == 1 else -1
            model.markers[mid] = dataclasses.replace(model.markers[mid], at=at)


def unplaced(model, mid):
    """The reason an expression may not name marker `mid` (a floating marker with no one
    place), or None."""
    if mid not in model.markers or model.markers[mid].at >= 0:
        return None
    forces = ", ".join(f"{vid} (I = {i})" for vid, i in users(model, mid))
    return (f"marker {mid} floats with vector forces {forces}, at more than one place, so an "
            "expression cannot read it; give each I marker its own floating marker")


def _refuse_elsewhere(model, floating):
    """DeckError for a floating marker that is not a two-body vector force's JFLOAT."""
    if not floating:
        return
    for b in model.bodies.values():
        for role, mid in (("cg_id", b.cg), ("im_id", b.im)):
            if mid in floating:
                tag = "Body_Point" if b.kind == "point" else "Body_Rigid"
                raise DeckError(f"marker {mid} is FLOATING; a body's {role} is a fixed marker",
                                file=model.source.file, element=tag, id=b.id,
                                attribute=role)
    uses = [("joint", model.joints, ("i", "j")), ("motion", model.motions, ("i", "j")),
            ("sforce", {k: v for k, v in model.sforces.items() if k > 0}, ("i", "j")),
            ("springdamper", model.springdampers, ("i", "j")),
            ("bushing", model.bushings, ("i", "j")), ("field", model.fields, ("i", "j")),
            ("beam", model.beams, ("i", "j")),
            ("vforce", {k: v for k, v in model.vforces.items() if k > 0}, ("i", "ref")),
            ("gcon", model.gcons, ("i",))]
    for kind, table, roles in uses:
        for eid in sorted(table):
            for role in roles:
                mid = getattr(table[eid], role)
                if mid in floating:
                    ctx = model._where[(kind, eid)]
                    attribute = {"i": "i_marker_id", "j": "j_marker_id",
                                 "ref": "ref_marker_id"}[role]
                    if kind == "vforce" and role == "i" and ctx.tag == "Force_Vector_OneBody":
                        attribute = "marker_id"
                    raise ctx.error(f"marker {mid} is FLOATING; a floating marker is the "
                                    "reaction marker (JFLOAT, j_floating_marker_id) of a "
                                    "two-body vector force only", attribute)
