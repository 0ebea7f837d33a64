"""The run log's line on the initial positions the assembly changed
(:func:`pysolver.build.consistent.consistent` at a run's initial state): which constraints
the deck's positions violate, and how far each body was moved, as Adams reports its
initial-conditions displacements (docs/deck-language.md, "Joints").

Decision: a body counts as moved when the assembly translated its centre of mass by more
than ``moved_limit(tol) x`` the scene's size (:func:`scene_size`) or turned it by more than
``moved_limit(tol)`` rad, where moved_limit(tol) = max(integr_tol, FLOOR): a change the run's
own tolerance allows, or the rounding of coordinates a deck prints to six or seven digits,
stays silent (a 1 m bar on a REVOLUTE whose J is 3 mm off is named at the default integr_tol
1e-3, 0.1 mm off at 1e-6). A constraint is named when its violation passes the same limits
(a distance, an angle; a general constraint's or coupler's g in its own units against the
larger of the two), or, when none does, the one that comes closest; a body when its move
or its turn passes them.
"""
import numpy as np

from . import icjoint

#: The least relative change noted, whatever integr_tol: coordinates printed to six or seven
#: digits (decks written by other tools) leave up to about 5e-7 of the scene; 1e-6 keeps them
#: silent.
FLOOR = 1e-6

_TAG = {"joint": "Constraint_Joint", "gcon": "Constraint_General",
        "coupler": "Constraint_Coupler"}


def moved_limit(tol):
    """The relative change (of the scene's size, or in rad) the log notes at integr_tol `tol`
    (None: the default 1e-3)."""
    return max(1e-3 if tol is None else float(tol), FLOOR)


def scene_size(kernel):
    """The scene's size: the larger of the diagonal of the box holding the bodies' initial
    centres of mass and the ground markers, and the farthest a body's marker lies from its
    centre of mass (in model length units)."""
    lay, a = kernel.layout, kernel.arrays
    pos = np.asarray(a["marker_pos"], float).reshape(-1, 3)
    ground = np.asarray(a["marker_body"]) < 0
    points = [np.asarray(b.pos, float) for b in lay.bodies] + list(pos[ground])
    box = np.ptp(np.array(points), axis=0) if points else np.zeros(3)
    return max(_length(box), max((_length(p) for p in pos[~ground]), default=0.0))


def _length(v):
    """|v| without overflow (a marker at 1e300)."""
    big = float(np.max(np.abs(v)))
    return big * float(np.linalg.norm(v / big)) if 0.0 < big < np.inf else big


def body_moves(lay, before, after):
    """[(body id, translation, rotation in rad or None for a point body)] of every body from
    the state `before` to `after`."""
    out = []
    for b, qa in zip(lay.bodies, lay.qadr):
        if b.id in lay.planar:              # (x, y, rz)
            out.append((b.id, float(np.linalg.norm(after[qa:qa + 2] - before[qa:qa + 2])),
                        float(abs(after[qa + 2] - before[qa + 2]))))
            continue
        shift = float(np.linalg.norm(after[qa:qa + 3] - before[qa:qa + 3]))
        if b.kind != "rigid":
            out.append((b.id, shift, None))
            continue
        # the turn from e to f: the Euler parameters of f conj(e)
        e, f = before[qa + 3:qa + 7], after[qa + 3:qa + 7]
        scalar = f[0] * e[0] + f[1:] @ e[1:]
        vec = e[0] * f[1:] - f[0] * e[1:] - np.cross(f[1:], e[1:])
        out.append((b.id, shift, float(2.0 * np.arctan2(np.linalg.norm(vec), abs(scalar)))))
    return out


def violations(kernel, rows, g, ndisp):
    """{(tag, id): (distance, angle, other)} of the held equations `rows` (indices into
    layout.lam, the first `ndisp` held by a mu, the rest motions' ic_disp) with their values
    g (after them those of the joints' initial displacements, :mod:`.icjoint`): the root
    sum of squares of the equations that hold a distance; the angle whose sine is
    that of the equations that hold a dot product of axes (the tilt of a REVOLUTE's zI from
    zJ), or a rotation motion's angle from its expression; a general constraint's or
    coupler's |g|."""
    lay = kernel.layout
    nmot = len(lay.motion_ids)
    sums = {}
    for n, (k, value) in enumerate(zip(rows, g)):
        if k < nmot:                          # a motion: its measure from its expression
            mid = lay.motion_ids[k]
            key = (kernel.motion_tags[mid] + " ic_disp" * (n >= ndisp), mid)
            part = 3 if lay.motion_ic[k][2] else 0
        else:
            kind, eid, _ = row = lay.constraint_rows[k - nmot]
            key = (_TAG[kind], eid)
            part = 2 if kind != "joint" else 1 if row in lay.angular_rows else 0
        acc = sums.setdefault(key, [0.0, 0.0, 0.0, 0.0])
        acc[part] += float(value) ** 2
    # then the joints' initial displacements (icjoint), the distance or angle from each
    for ic, value in zip(icjoint.with_displacement(kernel), g[len(rows):]):
        key = ("Constraint_Joint initial " + ("translation" if ic[1] == "T" else "rotation"),
               ic[0])
        sums.setdefault(key, [0.0, 0.0, 0.0, 0.0])[3 if ic[1] == "R" else 0] += float(value) ** 2
    return {key: (np.sqrt(d), np.arcsin(min(1.0, np.sqrt(a))) if a else np.sqrt(turn),
                  np.sqrt(o)) for key, (d, a, o, turn) in sums.items()}


def _named(found, length, angle):
    """The (tag, id) of `found` (:func:`violations`) to name, each with its words."""
    ratio = {key: max(d / length, a / angle, o / max(length, angle))
             for key, (d, a, o) in found.items()}
    keys = [key for key in sorted(ratio, key=lambda k: (k[0].split()[0], k[1])) if ratio[key] > 1]
    if not keys and ratio:
        keys = [max(ratio, key=ratio.get)]
    words = []
    for key in keys:
        d, a, o = found[key]
        parts = (([f"distance {d:.4g}"] if d > 0 else []) + ([f"angle {a:.4g} rad"] if a > 0
                                                             else [])
                 + ([f"g = {o:.4g}"] if o > 0 else []))
        tag, sep, extra = key[0].partition(" ")
        words.append(f"{tag} {key[1]} ({extra + ', ' if sep else ''}{', '.join(parts)})")
    return words


def moved_note(kernel, before, after, rows, g, ndisp, tol):
    """The run log's line (a list of none or one) on the assembly that took the initial state
    `before` to `after`, when it moved a body past the limits of the module's decision; `rows`,
    `g` and `ndisp` as :func:`violations` takes them, at `before`."""
    lay = kernel.layout
    rel = moved_limit(tol)
    length, angle = rel * (scene_size(kernel) or 1.0), rel
    moved = [(bid, s, r) for bid, s, r in body_moves(lay, before, after)
             if s > length or (r is not None and r > angle)]
    if not moved:
        return []
    bodies = ", ".join(f"body{bid} " + " and ".join(
        ([f"moved by {s:.4g}"] if s > length else [])
        + ([f"turned by {r:.4g} rad"] if r is not None and r > angle else []))
        for bid, s, r in moved)
    named = _named(violations(kernel, rows, g, ndisp), length, angle)
    return ["initial conditions: the positions the deck gives violate "
            f"{', '.join(named)} and were assembled, the least change: {bodies} "
            "(docs/deck-language.md, \"Joints\")"]
