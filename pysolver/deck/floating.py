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

Decisions: the forces that use one floating marker share their I marker (else a DeckError:
the marker would be in two places); a floating marker no force uses stays at its part's
frame, as placed; a floating marker anywhere else (a body's cg or inertia marker, a joint's,
motion's, spring's, bushing's or scalar force's marker, a vector force's I or reference
marker) is a DeckError: Adams takes floating markers on vector forces (and curve contacts,
which pysolver does not model) only.
"""
import dataclasses

from ..errors import DeckError


def placed(model, mid):
    """The marker whose frame marker `mid` is in a measure: a floating marker's I marker,
    else `mid` itself (0, the global frame, stays 0)."""
    return (model.markers[mid].at or mid) if mid else 0


def place_floating(model):
    """Put each floating marker at the I marker of the vector forces that use it (its
    ``at``), after every element is loaded; DeckError for a floating marker used elsewhere
    or by forces with different I markers."""
    floating = {mid for mid, m in model.markers.items() if m.floating}
    if not floating:
        return
    _refuse_elsewhere(model, floating)
    at = {}
    for vid in sorted(model.vforces):
        vf = model.vforces[vid]
        if vid < 0 or vf.j not in floating:
            continue
        first = at.setdefault(vf.j, (vf.i, vid))
        if first[0] != vf.i:
            raise model._where[("vforce", vid)].error(
                f"floating marker {vf.j} is the JFLOAT of vector force {first[1]} (I = "
                f"{first[0]}) and of this one (I = {vf.i}); a floating marker sits on its "
                "force's I marker, one place: give each I marker its own floating marker",
                "j_floating_marker_id")
    for mid, (i, _) in at.items():
        model.markers[mid] = dataclasses.replace(model.markers[mid], at=i)


def _refuse_elsewhere(model, floating):
    """DeckError for a floating marker that is not a two-body vector force's JFLOAT."""
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
            ("bushing", model.bushings, ("i", "j")),
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
