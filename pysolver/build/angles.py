"""Orientation angles of one marker relative to another, lowered to tape instructions.

PSI, THETA, PHI (body-fixed 3-1-3) and YAW, PITCH, ROLL (body-fixed 3-2-1, PITCH negated as
Adams' function returns it) of marker i relative to marker j (0: the global frame), from the
relative rotation R = A_J^T A_I, whose entry R[a][b] is axis a of J dotted with axis b of I
(one AXDOT instruction), so their derivatives are exact like every measure's
(../shared/reference/elements.md sections 0 and 7.3; docs/deck-language.md, "Angles").

- THETA = atan2(sqrt(R13^2 + R23^2), R33), in [0, pi]; PSI = atan2(R13, -R23) and
  PHI = atan2(R31, R32), except where sin(theta) < 1e-12 (psi and phi then turn about one axis):
  PSI = 0 and PHI = atan2(R33 R21, R11).
- YAW = atan2(R21, R11), PITCH = atan2(R31, sqrt(R32^2 + R33^2)), ROLL = atan2(R32, R33);
  YAW and ROLL are not defined where PITCH = +-pi/2.
- ORIENT(system, k, i, j) for systems 1..12, Adams' body-fixed sequences (1..6: 1-2-3,
  2-3-1, 3-1-2, 1-3-2, 2-1-3, 3-2-1; 7..12: 1-2-1, 1-3-1, 2-1-2, 2-3-2, 3-1-3, 3-2-3), the
  angles (k = 1, 2, 3) with R = R_a(alpha) R_b(beta) R_c(gamma): for three different axes,
  beta = atan2(e R[a][c], sqrt(R[a][a]^2 + R[a][b]^2)) in [-pi/2, pi/2], alpha =
  atan2(-e R[b][c], R[c][c]), gamma = atan2(-e R[a][b], R[a][a]) (e = +1 for a cyclic order,
  -1 otherwise); for a repeated axis (a, b, a) with d the third, beta = atan2(sqrt(R[a][b]^2
  + R[a][d]^2), R[a][a]) in [0, pi], alpha = atan2(R[b][a], -e R[d][a]), gamma =
  atan2(R[a][b], e R[a][d]) (e of (a, b, d)). As SciPy's Rotation.as_euler with upper-case
  (intrinsic) axes; alpha and gamma are not defined at the singular beta.
- ORIENT(27, k, i, j), Adams' Euler parameters of R (e0 >= 0): e0 = sqrt(max(0, 1 + tr R))
  / 2, e1 = SIGN(sqrt(max(0, 1 + R11 - R22 - R33)) / 2, R32 - R23), and likewise e2 (sign of
  R13 - R31) and e3 (R21 - R12); exact values everywhere, derivatives singular where a
  parameter passes 0.
"""
from .bindings import lib

#: sin(theta)^2 under which the 3-1-3 angles are taken as a single turn about z.
_GIMBAL = 1e-24

NAMES = ("PSI", "THETA", "PHI", "YAW", "PITCH", "ROLL")


def lower_angle(comp, tape, name, ids):
    """Slot of angle `name` of marker ids[0] relative to ids[1] (default 0) on `tape`."""
    mi, si = comp.marker(tape, ids[0])
    mj, sj = comp.marker(tape, ids[1] if len(ids) > 1 else 0)
    op = tape.op

    def R(a, b):                          # rows a, columns b from 1, as in the formulas
        return tape.emit(lib.PS_OP_AXDOT, mi, b - 1, mj, a - 1, si, sj)

    def atan2(y, x):
        return op(lib.PS_OP_ATAN2, y, x)

    def hypot(x, y):
        return op(lib.PS_OP_SQRT, op(lib.PS_OP_ADD, op(lib.PS_OP_MUL, x, x),
                                     op(lib.PS_OP_MUL, y, y)))
    if name == "THETA":
        return atan2(hypot(R(1, 3), R(2, 3)), R(3, 3))
    if name in ("PSI", "PHI"):
        s2 = op(lib.PS_OP_ADD, op(lib.PS_OP_MUL, R(1, 3), R(1, 3)),
                op(lib.PS_OP_MUL, R(2, 3), R(2, 3)))
        regular = (atan2(R(1, 3), op(lib.PS_OP_NEG, R(2, 3))) if name == "PSI"
                   else atan2(R(3, 1), R(3, 2)))
        single = (tape.const(0.0) if name == "PSI"
                  else atan2(op(lib.PS_OP_MUL, R(3, 3), R(2, 1)), R(1, 1)))
        flag = op(lib.PS_OP_SUB, s2, tape.const(_GIMBAL))
        return op(lib.PS_OP_IF, flag, single, single, regular)
    if name == "YAW":
        return atan2(R(2, 1), R(1, 1))
    if name == "PITCH":
        return atan2(R(3, 1), hypot(R(3, 2), R(3, 3)))
    return atan2(R(3, 2), R(3, 3))       # ROLL


#: ORIENT's body-fixed sequences (systems 1..12), axes from 1.
SEQUENCES = ((1, 2, 3), (2, 3, 1), (3, 1, 2), (1, 3, 2), (2, 1, 3), (3, 2, 1),
             (1, 2, 1), (1, 3, 1), (2, 1, 2), (2, 3, 2), (3, 1, 3), (3, 2, 3))


def lower_orient(comp, tape, system, k, i, j=0):
    """Slot of ORIENT(system, k, i, j): component k of the orientation of marker i relative
    to marker j, an angle of a body-fixed sequence (systems 1..12, k 1..3) or an Euler
    parameter (system 27, k 1..4); the parser refuses others."""
    mi, si = comp.marker(tape, i)
    mj, sj = comp.marker(tape, j)
    op = tape.op

    def R(a, b):
        return tape.emit(lib.PS_OP_AXDOT, mi, b - 1, mj, a - 1, si, sj)
    if system != 27:
        return _sequence_angle(tape, R, SEQUENCES[system - 1], k)
    signs = [(1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)][k - 1]
    total = tape.const(1.0)
    for n, sgn in enumerate(signs, 1):
        total = op(lib.PS_OP_ADD if sgn > 0 else lib.PS_OP_SUB, total, R(n, n))
    half = op(lib.PS_OP_MUL, tape.const(0.5),
              op(lib.PS_OP_SQRT, op(lib.PS_OP_MAX, tape.const(0.0), total)))
    if k == 1:
        return half
    a, b = [(3, 2), (1, 3), (2, 1)][k - 2]
    return op(lib.PS_OP_SIGN, half, op(lib.PS_OP_SUB, R(a, b), R(b, a)))


def _sequence_angle(tape, R, seq, k):
    """Angle k (1..3) of the body-fixed sequence seq of R (see the module's formulas)."""
    op = tape.op
    a, b, c = seq

    def neg(x):
        return op(lib.PS_OP_NEG, x)

    def hypot(x, y):
        return op(lib.PS_OP_SQRT, op(lib.PS_OP_ADD, op(lib.PS_OP_MUL, x, x),
                                     op(lib.PS_OP_MUL, y, y)))
    if a != c:
        e = 1 if (a, b, c) in ((1, 2, 3), (2, 3, 1), (3, 1, 2)) else -1
        sgn = (lambda x: x) if e > 0 else neg
        if k == 2:
            return op(lib.PS_OP_ATAN2, sgn(R(a, c)), hypot(R(a, a), R(a, b)))
        if k == 1:
            return op(lib.PS_OP_ATAN2, neg(sgn(R(b, c))), R(c, c))
        return op(lib.PS_OP_ATAN2, neg(sgn(R(a, b))), R(a, a))
    d = 6 - a - b
    e = 1 if (a, b, d) in ((1, 2, 3), (2, 3, 1), (3, 1, 2)) else -1
    sgn = (lambda x: x) if e > 0 else neg
    if k == 2:
        return op(lib.PS_OP_ATAN2, hypot(R(a, b), R(a, d)), R(a, a))
    if k == 1:
        return op(lib.PS_OP_ATAN2, R(b, a), neg(sgn(R(d, a))))
    return op(lib.PS_OP_ATAN2, R(a, b), sgn(R(a, d)))
