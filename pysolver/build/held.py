"""Held states: a point body's coordinate that nothing in the scene moves, and its velocity.

A point body whose start velocity, gravity and every force leave one of its global axes alone
stays where it started along that axis: seed example 3's particle, held between two lines in
the x-z plane, keeps y = 0 and vy = 0 exactly. Its equations there are y' = vy and m vy' = 0,
whatever the rest of the scene does. IDA then integrates the other states only: the held ones
are left out of its vectors, its error test and its matrix (``ps_ida_hold``), while the kernel
and every result still see the full state (the held entries at their start values). Seed
example 3 integrates 4 states instead of 6, as a hand-written program would.

Which axes are held is decided from the model, strictly (:func:`held_axes`): the scene's
elements may only be ones that read a point body (requests, sensors, variables, graphics) or
penalties, and an axis is held when no penalty's expression reads it (a penalty's generalized
force acts along the coordinates its expression reads); gravity and the body's start velocity
along it must be zero. At run time the start must be at rest in the held states (a sweep case
with a gravity along the axis integrates all of them), and each residual checks that their
equations hold exactly. ``PYSOLVER_HELD=off`` integrates every state. Decision and
alternatives: docs/numerics.md, "Held states".
"""
from .. import catalogue, settings
from ..deck import expr as ex

#: Tables a scene with held states may have: records that only read the bodies, and the
#: penalties, whose expressions say which coordinates they move. Anything else (a joint, a
#: spring, a vector force, a motion, a LoadControl task) keeps every state integrated.
ALLOWED = frozenset({"markers", "bodies", "penalties", "requests", "graphics", "variables",
                     "sensors", "evaluates", "splines"})

#: Measures that read one global axis of their markers' bodies: the axis of each name.
AXIS_OF = {"DX": 0, "DY": 1, "DZ": 2, "VX": 0, "VY": 1, "VZ": 2,
           "ACCX": 0, "ACCY": 1, "ACCZ": 2}


def scene_held(model):
    """:func:`held_axes`, or none when ``PYSOLVER_HELD=off``."""
    return held_axes(model) if settings.held() else {}


def held_axes(model):
    """{point body id: the global axes (0, 1, 2) it is held along}; empty when none is.

    An axis of a point body is held when the scene has only the element kinds in
    :data:`ALLOWED`, gravity and the body's start velocity have no component along it, and no
    penalty's expression (through its variables and the penalties it reads) reads that
    coordinate of a marker on the body: ``DX``, ``DY``, ``DZ`` and their velocity and
    acceleration forms in global axes read one axis; any other function of the body's markers
    reads all three; a user subroutine reads the values its iflag call declared (C's TDISP
    array: all three).
    """
    points = {b.id: b for b in model.bodies.values() if b.kind == "point"}
    if not points:
        return {}
    for element in catalogue.ELEMENTS:
        if element.table not in ALLOWED and getattr(model, element.table):
            return {}
    reads = {}
    for pen in model.penalties.values():
        _reads(model, pen.expr, reads, set())
    held = {}
    for bid, b in points.items():
        axes = tuple(a for a in range(3) if model.gravity[a] == 0.0 and b.vel[a] == 0.0
                     and a not in reads.get(bid, ()))
        if axes:
            held[bid] = axes
    return held


def _reads(model, tree, out, seen):
    """Add to out {body id: axes} the coordinates an expression reads (through VARVAL and
    PFORCE); a subroutine reads the values it declared; a tree not compiled yet (None) or a
    computed marker id marks every body as read on every axis."""
    every = (0, 1, 2)
    if tree is None:                    # a user subroutine not compiled yet: anything
        for bid in model.bodies:
            out.setdefault(bid, set()).update(every)
        return
    # a user subroutine's node has the values its iflag call declared as its inputs (it can
    # read no other, deck/usersubs.py): they are walked like any other call
    for node in ex.nodes(tree):
        if node[0] != "call":
            continue
        name, args = node[1], node[2]
        if name in ("VARVAL", "PFORCE"):
            key = (name, _number(args[0]) if args else None)
            if key in seen:
                continue
            seen.add(key)
            table = model.variables if name == "VARVAL" else model.penalties
            if key[1] in table:
                _reads(model, table[key[1]].expr, out, seen)
            continue
        fn = catalogue.FUNCTIONS.get(name)
        if fn is None or not any(kind == "marker" for kind in fn.ids):
            continue
        markers = [a for a, kind in zip(args, fn.ids) if kind == "marker"]
        # one axis for DX..ACCZ of i (and j) in global axes; else all three
        one = name in AXIS_OF and all(_number(a) == 0 for a in args[2:])
        axes = (AXIS_OF[name],) if one else every
        for i, a in enumerate(markers):
            if one and i >= 2:
                break
            mid = _number(a)
            if mid is None:                     # a computed marker id: anything
                for bid in model.bodies:
                    out.setdefault(bid, set()).update(every)
                continue
            if mid in model.markers:
                out.setdefault(model.markers[mid].body, set()).update(axes)


def _number(node):
    """The integer a literal argument node holds, else None."""
    return int(node[1]) if node[0] == "num" else None


def held_states(layout, held):
    """The state indices of the held axes {body id: axes} in `layout` (positions and their
    velocities), ascending."""
    out = []
    for bid, axes in held.items():
        i = layout.index[bid]
        out += [layout.qadr[i] + a for a in axes] + [layout.uadr[i] + a for a in axes]
    return tuple(sorted(out))

