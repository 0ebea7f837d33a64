"""A joint's initial conditions (Joint.ic: Adams' IC on a TRANSLATIONAL or REVOLUTE joint,
ICTRAN and ICROT on a CYLINDRICAL one) as extra conditions of the initial-conditions
analysis alone (:func:`pysolver.build.consistent.consistent` at a run's initial state): the
assembly holds the joint's coordinate at its displacement, the velocity step its rate at its
velocity, and neither is a row of the kernel, so the run integrates the joint freely from
there (docs/deck-language.md, "Initial positions").

The coordinate of a translation is DZ(I, J, J) = (oI - oJ) . zJ, the distance of I's origin
from J's along J's z axis, 0 where the origins coincide; that of a rotation AZ(I, J), the
angle of I's x axis about J's z axis from J's x axis, in (-pi, pi] (its distance from the
target wrapped the same way, as a rotation motion's). Their rates are VZ(I, J, J, J) and
WZ(I, J, J), linear in the velocities, so the directions along which each moves with the
velocities (d rate / du) are their values at unit velocities, exactly.
"""
import numpy as np


def with_displacement(kernel):
    """The kernel's joint initial conditions that give a displacement (all of them)."""
    return [ic for ic in kernel.joint_ic if ic[2] is not None]


def with_velocity(kernel):
    """The kernel's joint initial conditions that give a velocity."""
    return [ic for ic in kernel.joint_ic if ic[3] is not None]


def gaps(kernel, t, y, ics):
    """Each coordinate's distance from its displacement (a rotation's wrapped to (-pi, pi])."""
    yp = np.zeros_like(y)
    out = []
    for _, coord, disp, _, slot, _, _ in ics:
        e = kernel.eval_tape(slot, t, y, yp) - disp
        out.append(float(np.angle(np.exp(1j * e))) if coord == "R" else e)
    return np.array(out, dtype=float)


def rate_gaps(kernel, t, y, ics):
    """Each coordinate's rate less its velocity."""
    yp = np.zeros_like(y)
    return np.array([kernel.eval_tape(rate, t, y, yp) - vel
                     for _, _, _, vel, _, rate, _ in ics], dtype=float)


def directions(kernel, t, y, ics, u_idx):
    """The matrix (one row per initial condition, one column per entry of u_idx) of d
    rate / du: each rate at a unit velocity of one of its bodies' entries, the others 0."""
    column = {int(s): n for n, s in enumerate(u_idx)}
    C = np.zeros((len(ics), len(u_idx)))
    work, yp = np.array(y, dtype=float), np.zeros_like(y)
    work[u_idx] = 0.0
    for r, (_, _, _, _, _, rate, entries) in enumerate(ics):
        base = kernel.eval_tape(rate, t, work, yp)
        for s in entries:
            work[s] = 1.0
            C[r, column[s]] = kernel.eval_tape(rate, t, work, yp) - base
            work[s] = 0.0
    return C


def unmet(ics, e, tol):
    """The AssemblyError's words when a joint's initial velocity is off by more than `tol`
    (`e`: :func:`rate_gaps` after the velocity step), else None."""
    if not len(ics) or np.abs(e).max() <= tol:
        return None
    bad = ics[int(np.argmax(np.abs(e)))]
    return (f"{name(bad)}'s initial velocity {bad[3]:g} cannot be had: the other joints "
            f"and motions fix that coordinate's rate (off by {np.abs(e).max():.3g})")


def name(ic):
    """An initial condition as the run's messages name it."""
    return (f"Constraint_Joint {ic[0]} (initial "
            f"{'translation' if ic[1] == 'T' else 'rotation'})")
