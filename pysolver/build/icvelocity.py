"""Which initial velocities the consistent start keeps, and the metric of its least change
(:func:`pysolver.build.consistent.consistent` at a run's initial state).

The velocities a deck gives (nonzero ``v_ic_*``, ``w_ic_*``) are kept; the joints, motions
and general constraints take what they need from those it leaves at zero; among velocities of
one kind the change is the least in kinetic energy, so the start does not depend on the units
(docs/deck-language.md, "Initial velocities").
"""
import numpy as np

from .planar import global_inertia

#: A velocity component counts as given when it is more than this part of its body's velocity
#: (or angular velocity) vector: the rounding left by a change of axes (w_ic along wm_id's axes)
#: does not.
GIVEN = 1e-12


def velocity_scale(lay, y, u_idx):
    """(scale, free) of the velocities y[u_idx] at a run's initial state: the scale of each
    one's change, 1 / sqrt(its body's mass, or for an angular velocity the body's inertia
    about that axis), so that a change is the least in kinetic energy (the diagonal of the
    mass matrix) whatever the units; and which ones the deck leaves at zero (free), which
    the constraints change first (a pendulum given only its spin starts with that spin and
    the matching velocity of its centre of mass)."""
    metric, blocks = [], []
    for b in lay.bodies:
        if b.id in lay.planar:              # (vx, vy, wz), wz about the global z
            metric += [b.mass, b.mass, global_inertia(b)[2, 2]]
            blocks += [2, 1]
        else:                               # (vx, vy, vz), then (wx, wy, wz) in body axes
            metric += [b.mass] * 3 + (list(np.diag(b.inertia)) if b.kind == "rigid" else [])
            blocks += [3, 3] if b.kind == "rigid" else [3]
    metric = np.asarray(metric, float)
    metric = np.where(metric > 0, metric, 1.0)
    u = np.abs(y[u_idx])
    size = np.concatenate([np.full(n, np.linalg.norm(part))
                           for n, part in zip(blocks, np.split(u, np.cumsum(blocks)[:-1]))])
    return 1.0 / np.sqrt(metric), ~(u > GIVEN * size)


def changed_given(lay, u_idx, deck, now, given):
    """The run log's line naming the velocities the deck gives (`given`, as
    :func:`velocity_scale` found them) that the constraints made change (by more than 1e-9
    relative), with their values before and after; none when they all stayed."""
    moved = given & (np.abs(now - deck) > 1e-9 * np.abs(deck))
    if not moved.any():
        return []
    names = [lay.names[i] for i in u_idx]
    changes = ", ".join(f"{names[i]} {deck[i]:.6g} -> {now[i]:.6g}" for i in np.flatnonzero(moved))
    return ["initial conditions: velocities the deck gives conflict with its constraints and "
            f"were changed, the least in kinetic energy: {changes} (docs/deck-language.md, "
            "\"Initial velocities\")"]
