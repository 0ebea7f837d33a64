"""Whether a run kept its constraints: the position rows' residuals at its output rows.

Each row holding a position, g = 0, holds g + c mu = 0 (docs/numerics.md, "Constraints"):
the position multiplier mu is zero on the exact solution and small on BDF's, so on a
converged step g = -c mu. Where no position meets the constraints (a motion driving a
mechanism past its lock-up, a Hooke joint at 90 degrees stepped across) the corrector still
converges, mu grows and the joint opens, and neither IDA's error test nor its convergence test
sees it: mu is left out of both. So each output row's |c mu|, the amount by which a
constraint is not met, is compared with what the tolerance allows a position there,
integr_tol (1 + |q|) (IDA's weights: rtol = atol = integr_tol, |q| the largest position
coordinate of the row), and a run past LIMIT times that is reported as failed (status -730)
naming the element, the equation, the time and the gap. One vectorised pass over the rows the
run kept, after it ends: nothing per step.

Equations left out as redundant at the start (solve.compiled) have no row in the run's
kernel: they hold only while the redundancy is consistent (an over-constrained loop a tenth
of a milliradian off is not, and swings with one of them open). They are evaluated on the
kernel that holds them all (the probe the redundancy was found on, given the run's numbers)
at SAMPLES of the rows, evenly spread, the first and last among them, and judged alike: a
violation that lasts less than a sixteenth of the run can be missed there.
"""
import numpy as np

from ..build.consistent import _positions
from ..build.kernel import follow

#: Largest |g| / (integr_tol (1 + |q|)) of a run that keeps its constraints. Measured (stop 45)
#: over the test suite's runs and the joint decks at integr_tol 1e-2..1e-12: at most 0.75
#: (IFToMM A04, Bricard's linkage, whose one redundant equation is left out, at 1e-3; every
#: other deck below 0.08); 1e3-1e4 on the numerical trial's lock-ups (a slider driven past a
#: link's reach, a four-bar driven through its toggle) and its four-bar with one pivot axis
#: 1e-4 rad off (at integr_tol 1e-8).
LIMIT = 10.0

STATUS = -730

#: Rows at which the equations left out as redundant are evaluated: a residual of the probe
#: each, about 12 us (0.2 ms a run; the slider-crank deck runs in 8 ms).
SAMPLES = 16


def gaps(kernel, y):
    """|g| of every position row at each row of the states y (rows x ny): (the rows' state
    indices, array rows x position rows), or None when the scene holds no position."""
    lay = kernel.layout
    mu = np.array([m for m in lay.mu if m >= 0], dtype=int)
    if not len(mu) or not len(y):
        return None
    c = kernel.arrays["compliance"][mu]
    return mu, np.abs(np.asarray(y)[:, mu] * c)


def removed_gaps(kernel, t, y):
    """|g| of the equations left out as redundant at rows of (t, y): (state names on the
    probe, row indices, array rows x equations), or None when none were left out."""
    held = getattr(kernel, "redundancy", None)
    if not held or not len(t):
        return None
    probe, removed = held
    names = probe.layout.names
    wanted = {f"{kind}{cid}.position_reaction" + (f"{k + 1}" if kind == "joint" else "")
              for kind, cid, k in removed}
    rows = [m for m in probe.layout.mu if m >= 0 and names[m] in wanted]
    if not rows:
        return None
    follow(probe, kernel)
    # the run's body states into the probe's layout, every multiplier zero
    index = {n: i for i, n in enumerate(kernel.layout.names)}
    take = np.array([index.get(n, -1) for n in names])
    where = take >= 0
    # the kept equations' multipliers zero too: the rows give g alone
    where[[m for m in probe.layout.mu if m >= 0]] = False
    picks = np.unique(np.linspace(0, len(t) - 1, min(SAMPLES, len(t))).round().astype(int))
    yp = np.zeros(probe.ny)
    g = np.empty((len(picks), len(rows)))
    for n, r in enumerate(picks):
        yq = np.zeros(probe.ny)
        yq[where] = y[r, take[where]]
        g[n] = np.abs(probe.residual_array(float(t[r]), yq, yp)[rows])
    return [names[m] for m in rows], picks, g


def check(model, kernel, t, y, tol):
    """None, or the message of a run whose output rows (t, y) miss a constraint by more than
    LIMIT times what integr_tol `tol` allows a position there."""
    t, y = np.asarray(t), np.asarray(y)
    if y.ndim != 2 or not len(t) or not (any(m >= 0 for m in kernel.layout.mu) or
                                         getattr(kernel, "redundancy", None)):
        return None
    q = np.abs(y[:, _positions(kernel.layout)]) if len(kernel.layout.bodies) else \
        np.zeros((len(t), 0))
    allowed = tol * (1.0 + (q.max(axis=1) if q.shape[1] else 0.0))
    found = []                       # (ratio, gap, t, element) of the first and worst rows
    got = gaps(kernel, y)
    if got is not None:
        mu, g = got
        found.append((g / allowed[:, None], g, t,
                      [kernel.layout.names[m] for m in mu], ""))
    left = removed_gaps(kernel, t, y)
    if left is not None:
        names, picks, g = left
        found.append((g / allowed[picks][:, None], g, t[picks], names,
                      ", left out as redundant at the start,"))
    bad = [f for f in found if not np.all(ratio_ok(f[0]))]
    if not bad:
        return None
    ratio, g, times, names, how = bad[0]
    over = ~ratio_ok(ratio)
    first = int(np.argmax(over.any(axis=1)))
    k = int(np.argmax(np.where(over[first], ratio[first], -np.inf)))
    worst = int(np.nanargmax(np.where(np.isfinite(ratio), ratio, np.inf).max(axis=1)))
    kw = int(np.nanargmax(np.where(np.isfinite(ratio[worst]), ratio[worst], np.inf)))
    return (f"the constraints are not kept: {_describe(model, names[k])}{how} misses by "
            f"{g[first, k]:.3g} at t = {times[first]:.6g} ({ratio[first, k]:.3g} times what "
            f"integr_tol = {tol:g} allows a position there; {g[worst, kw]:.3g} at "
            f"t = {times[worst]:.6g}, {_describe(model, names[kw])}): no position meets "
            "them there (a motion driving the mechanism past its lock-up, or a singular "
            "or inconsistent configuration)")


def ratio_ok(ratio):
    """Whether each gap ratio is within LIMIT (a non-finite one is not)."""
    return np.isfinite(ratio) & (ratio <= LIMIT)


def _describe(model, name):
    """An element's name for a position row's state name ("joint2.position_reaction1")."""
    owner, _, row = name.partition(".")
    kind = owner.rstrip("0123456789")
    eid = owner[len(kind):]
    what = {"joint": "Constraint_Joint", "motion": "the motion", "jprim": "Constraint_Jprim",
            "coupler": "Constraint_Coupler", "gcon": "Constraint_General"}.get(kind, kind)
    if kind == "motion" and model is not None and eid.isdigit() and int(eid) in model.motions:
        m = model.motions[int(eid)]
        what = "Motion_Joint" if m.joint else "Motion_Marker"
    equation = row.replace("position_reaction", "equation ").strip()
    return f"{what} {eid}" + (f" ({equation})" if equation != "equation" else "")


def at_start(kernel, t, y, tol):
    """None, or why the assembled initial state (t, y) misses an equation left out as
    redundant by more than integr_tol `tol` allows a position there: the redundancy was found
    on the deck's numbers, and a run's own (a sweep case's) may break it."""
    left = removed_gaps(kernel, np.array([t]), np.asarray(y)[None, :])
    if left is None:
        return None
    names, _, g = left
    q = np.abs(np.asarray(y)[_positions(kernel.layout)]) if len(kernel.layout.bodies) else ()
    allowed = tol * (1.0 + (max(q) if len(q) else 0.0))
    k = int(np.argmax(g[0]))
    if g[0, k] <= allowed:
        return None
    return (f"{_describe(None, names[k])}, left out as redundant for the deck's numbers, "
            f"misses by {g[0, k]:.3g} at the assembled start (integr_tol = {tol:g} allows "
            f"{allowed:.3g}): with this run's numbers the loop is not consistent")
