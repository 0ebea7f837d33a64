"""FX, FY, FZ, FM, TX, TY, TZ, TM(I[, J][, K]): the net force and torque acting at marker I.

The sum of the forces and constraint forces of the elements that act at I (MotionSolve's
reading of the Adams functions, ../shared/reference/elements.md section 7.2): every element
whose I marker is I contributes its action on I's body (jflag 0 of its force function), every
element whose J marker is I its reaction there (jflag 1); with J given (not 0) only the
elements between I and J. Counted: scalar forces and spring-dampers (SFORCE, SPDP), vector
forces, bushings, fields and beams (BUSH, FIELD, BEAM), joints (JOINT), motions (MOTION).
Not counted: penalties, general constraints and couplers, which have no marker of their own.
Components in K's axes (0 or omitted: global); FM and TM are the magnitudes.
"""
from .bindings import lib

NAMES = ("FX", "FY", "FZ", "FM", "TX", "TY", "TZ", "TM")


def _contributions(comp, i, j):
    """(measure, id, jflag) of every element force acting at marker i (from j, when j)."""
    m = comp.model
    out = []
    pairs = [("sforce", sid, sf.i, sf.j, sf.action_only) for sid, sf in m.sforces.items()]
    pairs += [("vforce", vid, vf.i, vf.j, not vf.j) for vid, vf in m.vforces.items()]
    pairs += [("joint", jid, jo.i, jo.j, False) for jid, jo in m.joints.items()]
    pairs += [("motion", mid, mo.i, mo.j, False) for mid, mo in m.motions.items()]
    for kind, eid, ei, ej, action_only in sorted(pairs, key=lambda p: (p[0], p[1])):
        if ei == i and (not j or ej == j):
            out.append((kind, eid, 0))
        if ej == i and not action_only and (not j or ei == j):
            out.append((kind, eid, 1))
    return out


def lower_net(comp, tape, name, ids):
    """Slot of `name`(ids) on `tape`."""
    i = ids[0]
    j = ids[1] if len(ids) > 1 else 0
    k = ids[2] if len(ids) > 2 else 0
    first = 2 if name.startswith("F") else 6
    parts = _contributions(comp, i, j)

    def component(c):
        total = tape.const(0.0)
        for kind, eid, jflag in parts:
            if kind == "sforce":
                v = comp.sforce_measure(tape, eid, jflag, c, k)
            elif kind == "vforce":
                v = comp.vforce_measure(tape, eid, jflag, c, k)
            elif kind == "joint":
                v = comp.joint_measure(tape, eid, jflag, c, k)
            else:
                v = comp.motion_measure(tape, eid, jflag, c, k)
            total = tape.op(lib.PS_OP_ADD, total, v)
        return total
    if name[1] != "M":
        return component(first + "XYZ".index(name[1]))
    xyz = [component(first + c) for c in range(3)]
    sq = [tape.op(lib.PS_OP_MUL, v, v) for v in xyz]
    return norm_slot(tape, tape.op(lib.PS_OP_ADD, sq[0], tape.op(lib.PS_OP_ADD, sq[1], sq[2])))


def norm_slot(tape, total):
    """The slot of sqrt(total), a sum of squares: 0 with zero derivatives where it is 0 (a
    force or a distance of nothing, where sqrt's derivative is infinite: a force that read
    JOINT(id, 0, 1, 0) of a joint carrying nothing started with a NaN)."""
    zero = tape.const(0.0)
    return tape.op(lib.PS_OP_IF, total, zero, zero, tape.op(lib.PS_OP_SQRT, total))
