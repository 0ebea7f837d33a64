"""Rotation math shared by the deck reader, the compiler and the solvers: 3-1-3 angles, Euler
parameters and their rate matrix G(e)."""
import math

import numpy as np

#: e' = 1/2 G(e) w for body-frame angular velocity w: entry (a, k) of G is
#: G_SIGN[a][k] * e[G_INDEX[a][k]]. The kernel's C (csrc/tape.c, ps_rate_coeff) writes the same
#: matrix; the generator (build/codegen/scene.py) reads this table.
G_INDEX = ((1, 2, 3), (0, 3, 2), (3, 0, 1), (2, 1, 0))
G_SIGN = ((-1, -1, -1), (1, -1, 1), (1, 1, -1), (-1, 1, 1))


def G(e):
    """The 4 x 3 matrix G(e) of e' = 1/2 G(e) w (w in the body frame)."""
    return np.array([[sign * e[i] for i, sign in zip(index, signs)]
                     for index, signs in zip(G_INDEX, G_SIGN)], dtype=float)


def rot_313(psi, theta, phi):
    """Body 3-1-3 rotation: A = Rz(psi) Rx(theta) Rz(phi)."""
    def rz(a):
        c, s = math.cos(a), math.sin(a)
        return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])

    c, s = math.cos(theta), math.sin(theta)
    rx = np.array([[1.0, 0, 0], [0, c, -s], [0, s, c]])
    return rz(psi) @ rx @ rz(phi)


def angles_313(A):
    """Body 3-1-3 angles (psi, theta, phi) of a rotation matrix, theta in [0, pi], so that
    rot_313(psi, theta, phi) is A to rounding (a few units in the last place of its entries).

    psi and phi come from the third column and row (sin(theta) times their sine and cosine)
    where sin(theta) > 1/2; nearer theta = 0 or pi, where those lose their digits, their sum
    (theta < pi/2) or difference comes from the upper 2 x 2 block, which holds it times
    1 +- cos(theta), and only one of them from the third column. At theta = 0 or pi (gimbal
    lock: psi and phi turn about one axis), or sin(theta) within rounding of it (two units
    of 1), theta is 0 or pi and phi 0.
    """
    A = np.asarray(A, dtype=float)
    s = math.hypot(A[0, 2], A[1, 2])
    if s > 0.5:
        return (math.atan2(A[0, 2], -A[1, 2]), math.atan2(s, A[2, 2]),
                math.atan2(A[2, 0], A[2, 1]))
    if A[2, 2] > 0:                 # near theta = 0: psi + phi
        turn, sign, lock = math.atan2(A[1, 0] - A[0, 1], A[0, 0] + A[1, 1]), 1.0, 0.0
    else:                           # near theta = pi: psi - phi
        turn, sign, lock = math.atan2(A[1, 0] + A[0, 1], A[0, 0] - A[1, 1]), -1.0, math.pi
    if s <= 2 * np.finfo(float).eps:
        return turn, lock, 0.0
    psi = math.atan2(A[0, 2], -A[1, 2])
    phi = math.remainder(sign * (turn - psi), 2 * math.pi)
    return psi, math.atan2(s, A[2, 2]), phi


def rot_321(yaw, pitch, roll):
    """Body 3-2-1 rotation with Adams' PITCH (the negated second angle):
    A = Rz(yaw) Ry(-pitch) Rx(roll), so YAW, PITCH and ROLL read the angles back."""
    cy, sy = math.cos(yaw), math.sin(yaw)
    cp, sp = math.cos(-pitch), math.sin(-pitch)
    cr, sr = math.cos(roll), math.sin(roll)
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1.0]])
    ry = np.array([[cp, 0, sp], [0, 1.0, 0], [-sp, 0, cp]])
    rx = np.array([[1.0, 0, 0], [0, cr, -sr], [0, sr, cr]])
    return rz @ ry @ rx


def rot_from_e(e):
    """Rotation matrix of unit Euler parameters (e0, e1, e2, e3)."""
    e0, e1, e2, e3 = e
    return np.array([
        [e0 * e0 + e1 * e1 - e2 * e2 - e3 * e3, 2 * (e1 * e2 - e0 * e3), 2 * (e1 * e3 + e0 * e2)],
        [2 * (e1 * e2 + e0 * e3), e0 * e0 - e1 * e1 + e2 * e2 - e3 * e3, 2 * (e2 * e3 - e0 * e1)],
        [2 * (e1 * e3 - e0 * e2), 2 * (e2 * e3 + e0 * e1), e0 * e0 - e1 * e1 - e2 * e2 + e3 * e3]])


def e_from_rot(A):
    """Euler parameters (e0 >= 0) of a rotation matrix."""
    tr = np.trace(A)
    cands = [tr, A[0, 0], A[1, 1], A[2, 2]]
    k = int(np.argmax(cands))
    if k == 0:
        e0 = 0.5 * math.sqrt(max(1 + tr, 0))
        e = [e0, (A[2, 1] - A[1, 2]) / (4 * e0), (A[0, 2] - A[2, 0]) / (4 * e0),
             (A[1, 0] - A[0, 1]) / (4 * e0)]
    else:
        i = k - 1
        j, m = (i + 1) % 3, (i + 2) % 3
        ei = 0.5 * math.sqrt(max(1 + 2 * A[i, i] - tr, 0))
        e = [0.0] * 4
        e[1 + i] = ei
        e[0] = (A[m, j] - A[j, m]) / (4 * ei)
        e[1 + j] = (A[j, i] + A[i, j]) / (4 * ei)
        e[1 + m] = (A[m, i] + A[i, m]) / (4 * ei)
    e = np.array(e)
    return e if e[0] >= 0 else -e



def along(R, v):
    """The vector whose components along the columns of R are v (R @ v, in the frame R is
    given in); components below 16 machine epsilons of |v|, the rounding a turn leaves (a
    cos(pi/2) of 6e-17), are exactly 0, and v is kept as it is when R is exactly the
    identity."""
    v = np.asarray(v, dtype=float)
    R = np.asarray(R, dtype=float)
    if np.array_equal(R, np.eye(3)):
        return v.copy()
    out = R @ v
    out[np.abs(out) <= 16 * np.finfo(float).eps * np.linalg.norm(v)] = 0.0
    return out
