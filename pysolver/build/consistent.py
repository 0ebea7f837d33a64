"""Consistent initial conditions for scenes with motions (Motion_Marker) and joints, and the
joint equations that repeat others (:func:`redundant`).

A motion or a joint equation adds a reaction lam (algebraic) and a row holding a rate g' to its
target; a displacement motion and a joint equation also hold g = 0 itself (with mu). Before
IDA starts (and at restarts) the state is made consistent in three steps, each the smallest
change that does it:

1. positions (the assembly): every held g = 0 by Newton steps moving the bodies along the
   reactions' own rate directions c = d(g')/du (the velocity that changes g fastest);
2. velocities: the rate rows g' = target by the least-norm change of u along the same
   directions; an acceleration motion's driven velocity w takes the current g';
3. accelerations and reactions: yp and lam from the residual rows and the time derivative of
   the rate rows (index reduction: d/dt (g' - target) = 0), which together are linear in them.
"""
import numpy as np

from ..options import SPARSE_THRESHOLD
from ..rotations import G
from . import icjoint
from .icmetric import change, weights
from .icposition import moved_note
from .icvelocity import changed_given, velocity_scale


class _Jac:
    """The iteration matrix at cj, dense or (from SPARSE_THRESHOLD states) sparse, with the
    few block operations the steps below need."""

    def __init__(self, kernel, t, y, yp, cj):
        self.sparse = kernel.ny >= SPARSE_THRESHOLD
        self.J = (kernel.jacobian_csc_array(t, y, yp, cj) if self.sparse
                  else kernel.jacobian_array(t, y, yp, cj))

    def block(self, rows, cols):
        """J[rows, cols] as a dense array (a few rows or columns)."""
        if self.sparse:
            return self.J[:, cols].tocsr()[rows].toarray()
        return self.J[np.ix_(rows, cols)]

    def diagonal(self):
        """The matrix's diagonal."""
        return self.J.diagonal() if self.sparse else np.diag(self.J).copy()

    def least_change(self, rows, cols, rhs, scale=None, extra=None):
        """The least-norm x with J[rows, cols] x = rhs: x = C^T (C C^T)^-1 rhs, by a sparse
        factorization of C C^T on the sparse path (C has full row rank once redundant
        equations are out; where it has not, least squares), dense least squares otherwise.
        With `scale` (one positive number per column), the least change in the norm
        ||x / scale||: C's columns are scaled, and the answer scaled back. `extra`: dense
        rows below J's (joints' initial conditions, :mod:`.icjoint`; rhs ends with theirs),
        by dense least squares (C C^T can be singular but for rounding with them)."""
        if self.sparse and (extra is None or not len(extra)):
            import scipy.sparse as sp
            import scipy.sparse.linalg as spla
            C = self.J[:, cols].tocsr()[rows]
            if scale is not None:
                C = C @ sp.diags(scale)
            try:
                with np.errstate(all="raise"):
                    x = C.T @ spla.splu((C @ C.T).tocsc()).solve(np.asarray(rhs, float))
                if np.all(np.isfinite(x)):
                    return x if scale is None else scale * x
            except (RuntimeError, FloatingPointError):
                pass
            C = C.toarray()
        else:
            C = self.block(rows, cols)
            C = C.toarray() if hasattr(C, "toarray") else C
            if extra is not None and len(extra):
                C = np.vstack([C, extra])
            if scale is not None:
                C = C * scale
        x = np.linalg.lstsq(C, rhs, rcond=None)[0]
        return x if scale is None else scale * x

    def rows_times(self, rows, v):
        """J[rows] @ v."""
        return (self.J @ v)[rows]


def consistent(kernel, t, y, iters=8, initial=False, tol=None):
    """Make y consistent in place (positions, velocities, lam, mu, w) and return yp; at the
    `initial` state also with the motions' ic_disp and ic_vel, noting in
    ``kernel.start_notes`` the bodies the assembly moved (past the limits integr_tol `tol`
    sets, :mod:`.icposition`) and the given velocities it changed. Its residuals at nearby
    times are not step attempts, nor bound by max_num_steps (as in C,
    ps_restart_consistent)."""
    d = kernel.d
    kept = (d.ntimes, d.nfail, d.last_t, d.step_limit)
    d.step_limit = 0
    try:
        return _consistent(kernel, t, y, iters, initial, tol)
    finally:
        d.ntimes, d.nfail, d.last_t, d.step_limit = kept


def start(kernel, t, y, tol=None):
    """:func:`consistent` at a run's initial state (in place; returns yp) for a run at
    integr_tol `tol`, remembered per kernel: a run that starts from the same numbers as the
    last (every number of the kernel's arrays, gravity, the stored sensor values, t, `tol`
    and y) gets the same state and rates,
    bit for bit, without recomputing them (the revolute pendulum's warm run: 0.15 ms of
    Python of 0.5 ms), and the kernel's residual and Jacobian counts it took, so that a run's
    statistics do not depend on the runs before it. A kernel that calls user routines always
    recomputes (a routine may keep state between calls), as does a start that failed. The
    bodies the assembly moved and the given velocities it changed are noted in
    ``kernel.start_notes`` (the run's log), remembered with the start."""
    kernel.start_notes = []
    if kernel.model_calls_routines:
        return consistent(kernel, t, y, initial=True, tol=tol)
    a = kernel.arrays
    key = b"".join([np.ascontiguousarray(v).tobytes() for v in a.values()
                    if isinstance(v, np.ndarray) and v.dtype == np.float64]
                   + [np.array([t, np.nan if tol is None else tol,
                                *kernel.m.gravity]).tobytes(),
                      kernel.senval.tobytes(), np.ascontiguousarray(y, float).tobytes()])
    d = kernel.d
    got = kernel.__dict__.get("_start")
    if got is not None and got[0] == key:
        y[:] = got[1]
        d.nres, d.njac = d.nres + got[3][0], d.njac + got[3][1]
        kernel.start_notes = list(got[4])
        return got[2].copy()
    before = (d.nres, d.njac)
    yp = consistent(kernel, t, y, initial=True, tol=tol)
    if np.all(np.isfinite(yp)) and not d.bad_kind:
        kernel.__dict__["_start"] = (key, y.copy(), yp.copy(),
                                     (d.nres - before[0], d.njac - before[1]),
                                     list(kernel.start_notes))
    return yp


def _consistent(kernel, t, y, iters, initial, tol):
    """consistent() proper."""
    lay = kernel.layout
    lam, mu, rate = (np.array(v, dtype=int) for v in (lay.lam, lay.mu, lay.rate))
    y[lam] = 0.0
    y[mu[mu >= 0]] = 0.0
    u_idx = _velocities(lay)
    yp = np.zeros_like(y)
    deck_y = y.copy()
    # 1. positions: g (the rows of mu) to zero along the reactions' directions; the tracked
    # angles follow their measured angles (each row is its wrapped error, d/ds = -1)
    _track_turns(kernel, t, y, yp)
    held_rows, deck_g, ndisp = _assemble(kernel, t, y, initial)
    _track_turns(kernel, t, y, yp)
    moved = moved_note(kernel, deck_y, y, held_rows, deck_g, ndisp, tol) if initial else []
    # 2. velocities: A motions take w = g' (or their ic_vel, and u changes); the others change u
    given = [initial and rate[k] >= 0 and lay.motion_ic[k][1] is not None
             for k in range(len(rate))]
    for k, w in enumerate(rate):
        if given[k]:
            y[w] = lay.motion_ic[k][1]
    r = kernel.residual_array(t, y, yp)[lam]
    for k, w in enumerate(rate):
        if w >= 0 and not given[k]:
            y[w] += r[k]
            r[k] = 0.0
    held = np.nonzero((rate < 0) | np.array(given, dtype=bool))[0]
    vics = icjoint.with_velocity(kernel) if initial else []     # joints' initial velocities
    C_ic, e = icjoint.directions(kernel, t, y, vics, u_idx), icjoint.rate_gaps(kernel, t, y, vics)
    # at the initial state the velocities the deck leaves at zero change first, and all of
    # them (the given ones too) only for what those cannot do, each the least in kinetic
    # energy (icvelocity); elsewhere every velocity alike
    scale, free = velocity_scale(lay, y, u_idx) if initial else (None, None)
    deck_u = y[u_idx].copy() if initial else None
    stages = ([(u_idx, scale)] if free is None or free.all() or not free.any()
              else [(u_idx[free], scale[free]), (u_idx, scale)])
    # Newton on the held rates (one step when they are linear in u; a relation of velocities
    # may not be)
    met = False
    for _ in range(iters if len(held) or vics else 0):
        J = _Jac(kernel, t, y, yp, 0.0)
        for (cols, s), part in zip(stages, [free, None] if len(stages) > 1 else [None]):
            extra = C_ic if part is None else C_ic[:, part]
            y[cols] += J.least_change(lam[held], cols, -np.concatenate([r[held], e]), s,
                                      extra)
            r = kernel.residual_array(t, y, yp)[lam]
            e = icjoint.rate_gaps(kernel, t, y, vics)
            met = np.abs([*r[held], *e, 0.0]).max() <= 1e-14 * (1.0 + np.abs(y[u_idx]).max())
            if met:
                break
        if met:
            break
    if icjoint.unmet(vics, e, 1e-9 * (1.0 + np.abs(y[u_idx]).max())):
        raise AssemblyError(icjoint.unmet(vics, e, 1e-9 * (1.0 + np.abs(y[u_idx]).max())))
    if initial:
        kernel.start_notes = moved + changed_given(lay, u_idx, deck_u, y[u_idx], ~free)
    # 3. accelerations and reactions (linear in them unless forces read accelerations)
    rows = np.setdiff1d(np.arange(kernel.ny), lay.algebraic)
    for _ in range(4):
        res = kernel.residual_array(t, y, yp)
        if not np.isfinite(res).all():      # d.bad_kind says where (the caller words it)
            return np.full_like(yp, np.nan)
        J0 = _Jac(kernel, t, y, yp, 0.0)
        D = _Jac(kernel, t, y, yp, 1.0).J - J0.J
        # the rate rows' time derivative from after t, where the run goes on (a motion's rate
        # may kink at t: a spline's data start, a STEP's end), as csrc/control.c takes it
        h = 1e-6 * max(1.0, abs(t))
        r_t = (4 * kernel.residual_array(t + h, y, yp)[lam] - 3 * res[lam]
               - kernel.residual_array(t + 2 * h, y, yp)[lam]) / (2 * h)
        rhs = -np.concatenate([res[rows], J0.rows_times(lam, yp) + r_t])
        dz = _solve_saddle(D, J0.J, rows, lam, rhs, J0.sparse)
        yp[rows] += dz[:len(rows)]
        y[lam] += dz[len(rows):]
        if np.max(np.abs(dz)) <= 1e-14 * (1 + np.max(np.abs(np.concatenate([yp, y[lam]])))):
            break
    return yp


def _track_turns(kernel, t, y, yp):
    """Move each tracked angle s onto its measured angle (one exact Newton step: its row is
    atan2(sin(theta - s), cos(theta - s)))."""
    turns = list(kernel.layout.turns.values())
    if turns:
        y[turns] += kernel.residual_array(t, y, yp)[turns]


def redundant(kernel, t, y, tol=1e-8):
    """The joint equations that repeat others at the assembled initial positions, as (joint
    id, equation index): each equation in table order (motions first) is kept when its
    velocity-level row d(g')/du adds a direction to those kept before it (relative size of
    the new part above `tol`), else it is redundant. Raises AssemblyError when a motion's is
    (it drives what other motions or the joints already fix, and it comes first)."""
    lay = kernel.layout
    y = np.array(y, dtype=float)
    u_idx = _velocities(lay)
    _track_turns(kernel, t, y, np.zeros_like(y))
    _assemble(kernel, t, y, initial=True)
    C = _Jac(kernel, t, y, np.zeros_like(y), 0.0).block(np.array(lay.lam, dtype=int), u_idx)
    C = C.toarray() if hasattr(C, "toarray") else np.asarray(C)
    basis, out = [], []
    nmot = len(lay.motion_ids)
    for k, row in enumerate(C):
        size = np.linalg.norm(row)
        for q in basis:
            row = row - (q @ row) * q
        if size > 0 and np.linalg.norm(row) > tol * size:
            basis.append(row / np.linalg.norm(row))
        elif k < nmot:
            mid = lay.motion_ids[k]
            raise AssemblyError(f"{kernel.motion_tags[mid]} {mid} drives a coordinate that "
                                "other motions or the joints already fix")
        else:
            out.append(lay.constraint_rows[k - nmot])
    return out


#: Most Newton steps of the assembly (as csrc/control.c's PS_ASSEMBLY_ITERS), the last
#: PLAIN_ITERS of them plain least-change steps onto the constraints (quadratic), whatever the
#: steps toward the least change reached (:mod:`.icmetric`: 6 to 12 steps on a bar whose joint
#: is up to twice its length off).
ASSEMBLY_ITERS = 50
PLAIN_ITERS = 5
#: The bounds of the pull's step length (Barzilai-Borwein, :mod:`.icmetric`).
PULL_BOUNDS = (0.05, 20.0)


def _assemble(kernel, t, y, initial=False, iters=ASSEMBLY_ITERS):
    """Move the positions of y (in place) to satisfy the position-level constraints (and at
    the `initial` state the motions' ic_disp) by the least change in the mass metric
    (:mod:`.icmetric`, which says how): Newton steps along the reactions' directions, each
    the least change that zeroes the constraints' linearization plus a pull along them
    toward the least change from the positions it started from. They stop on the constraints
    once a step is below 1e-12 of the change (or at rounding's level), or the whole change
    below 1e-8 of the state's size (the constraints' curvature then moves its least change by
    less than 1e-8 of it). Return (rows, g, ndisp): the held equations' indices into
    layout.lam (the first `ndisp` of them held by a mu, the rest motions' ic_disp) and their
    values at the positions it started from (then the joints' initial displacements')."""
    lay = kernel.layout
    lam, mu = np.array(lay.lam, dtype=int), np.array(lay.mu, dtype=int)
    disp = np.nonzero(mu >= 0)[0]
    ic = [k for k, (d, _, _) in enumerate(lay.motion_ic) if initial and d is not None]
    rows = np.concatenate([disp, ic]).astype(int)
    jics = icjoint.with_displacement(kernel) if initial else []
    u_idx = _velocities(lay)
    yp = np.zeros_like(y)
    first = None
    w = weights(kernel)
    scale, y0 = np.sqrt(w[u_idx]), y.copy()
    alpha, before, settled = 1.0, None, True

    def gaps():
        """The held g and, per ic_disp, the driven measure's distance from it."""
        extra = []
        for k in ic:
            target, _, angle = lay.motion_ic[k]
            e = kernel.eval_tape(kernel.motion_slots[lay.motion_ids[k]], t, y, yp) - target
            extra.append(np.angle(np.exp(1j * e)) if angle else e)
        return np.concatenate([kernel.residual_array(t, y, yp)[mu[disp]], extra,
                               icjoint.gaps(kernel, t, y, jics)])

    def dot(a, b):
        """a . b in the metric, over the velocities."""
        return float(np.sum(a * b / w[u_idx]))
    for it in range(iters if len(rows) or jics else 0):
        g = gaps()
        first = g if first is None else first
        tol = 1.0 + np.max(np.abs(y))
        if np.max(np.abs(g)) <= 1e-13 * tol and settled:
            return rows, first, len(disp)
        J = _Jac(kernel, t, y, yp, 0.0)
        C_ic = icjoint.directions(kernel, t, y, jics, u_idx)
        du = np.zeros(kernel.ny)
        du[u_idx] = J.least_change(lam[rows], u_idx, -g, scale, C_ic)
        d = change(kernel, y0, y, w)[u_idx]
        if it < iters - PLAIN_ITERS and d.any():
            # the pull: the change's part along the constraints, taken back by alpha (1: its
            # Gauss-Newton length; then the secant length of the last two pulls)
            along = np.concatenate([J.rows_times(lam[rows], _at(d, u_idx, y)), C_ic @ d])
            pull = J.least_change(lam[rows], u_idx, along, scale, C_ic) - d
            if before is not None:
                bend = dot(before, before - pull)
                alpha = (min(max(alpha * dot(before, before) / bend, PULL_BOUNDS[0]),
                             PULL_BOUNDS[1]) if bend > 0 else 1.0)
            before = pull
            du[u_idx] += alpha * pull
        else:
            d = np.zeros(len(u_idx))
        settled = (np.max(np.abs(d + du[u_idx])) <= 1e-8 * tol
                   or np.sqrt(dot(du[u_idx], du[u_idx])) <= 1e-12 * np.sqrt(dot(d, d))
                   or np.max(np.abs(du)) <= 1e-13 * tol)
        _move(lay, y, du)
    if len(rows) or jics:
        g = gaps()
        _unassembled(kernel, lay, rows, g, y, len(disp), jics)
    return rows, np.zeros(0) if first is None else first, len(disp)


def _at(values, idx, like):
    """A vector like `like`, zero but at idx, which holds `values`."""
    out = np.zeros_like(like)
    out[idx] = values
    return out


def _positions(lay):
    """The state indices of every body's positions q."""
    return np.concatenate([np.arange(qa, qa + nq)
                           for (nq, _), qa in zip(lay.sizes, lay.qadr)]).astype(int)


def _velocities(lay):
    """The state indices of every body's velocities u."""
    return np.concatenate([np.arange(ua, ua + nu)
                           for (_, nu), ua in zip(lay.sizes, lay.uadr)]).astype(int)


class AssemblyError(ValueError):
    """No positions satisfy the constraints near the initial ones."""


def _unassembled(kernel, lay, rows, g, y, ndisp, jics=()):
    """Raise AssemblyError unless the position constraints hold after the Newton steps (rows:
    the held equations' indices into lay.lam, the first `ndisp` of them with a mu; then the
    joints' initial displacements `jics`)."""
    if np.max(np.abs(g)) <= 1e-9 * (1.0 + np.max(np.abs(y))):
        return
    big = np.flatnonzero(np.abs(g) > 1e-9)
    names = [icjoint.name(jics[n - len(rows)]) for n in big if n >= len(rows)]
    for n in big[big < len(rows)]:
        k = rows[n]
        if n >= ndisp:                    # a motion's ic_disp
            mid = lay.motion_ids[k]
            names.append(f"{kernel.motion_tags[mid]} {mid} (ic_disp)")
            continue
        prefix = kernel.layout.names[lay.mu[k]].split(".")[0]
        kind = prefix.rstrip("0123456789")
        eid = int(prefix[len(kind):])
        tag = {"joint": "Constraint_Joint", "gcon": "Constraint_General",
               "coupler": "Constraint_Coupler"}.get(kind)
        names.append(f"{kernel.motion_tags[eid] if kind == 'motion' else tag} {eid}")
    raise AssemblyError("the initial positions cannot be assembled: "
                        f"{', '.join(dict.fromkeys(names))} violated by up to "
                        f"{np.max(np.abs(g)):.3g} after the least-change correction")


def reactions(kernel, t, y, yp):
    """The motions' reactions that balance the residual's force rows at (t, y, yp), by least
    squares. IDA interpolates output rows over its steps, and for the algebraic reactions,
    which its error test leaves out, the interpolant can be far off (a jump in the reaction
    inside a step spreads over the whole step): the driver recomputes them at every row."""
    lay = kernel.layout
    lam, mu = np.array(lay.lam, dtype=int), np.array(lay.mu, dtype=int)
    y = np.array(y, dtype=float)
    y[lam] = 0.0                       # the reactions, not the tracked angles
    y[mu[mu >= 0]] = 0.0
    rows = np.setdiff1d(np.arange(kernel.ny), kernel.layout.algebraic)
    r = kernel.residual_array(t, y, yp)[rows]
    C = _Jac(kernel, t, y, yp, 0.0).block(rows, lam)
    return np.linalg.lstsq(C, -r, rcond=None)[0]


def _solve_saddle(D, J0, rows, lam, rhs, sparse):
    """Solve [[D_rr, J0_rl], [J0_lr, 0]] z = rhs (accelerations, then reactions)."""
    if not sparse:
        n = len(rows) + len(lam)
        A = np.zeros((n, n))
        A[:len(rows), :len(rows)] = D[np.ix_(rows, rows)]
        A[:len(rows), len(rows):] = J0[np.ix_(rows, lam)]
        A[len(rows):, :len(rows)] = J0[np.ix_(lam, rows)]
        return np.linalg.solve(A, rhs)
    import scipy.sparse as sp
    from scipy.sparse.linalg import spsolve
    D, J0 = D.tocsr(), J0.tocsr()
    A = sp.bmat([[D[rows][:, rows], J0[rows][:, lam]], [J0[lam][:, rows], None]], format="csc")
    return spsolve(A, rhs)


def _move(lay, y, du):
    """q += N(q) du: translate by du's velocities, rotate by its body angular velocities (Euler
    parameters renormalised)."""
    for b, qa, ua in zip(lay.bodies, lay.qadr, lay.uadr):
        y[qa:qa + 3] += du[ua:ua + 3]       # a planar body's (x, y, rz) by (vx, vy, wz)
        if b.kind != "rigid" or b.id in lay.planar:
            continue
        e, w = y[qa + 3:qa + 7].copy(), du[ua + 3:ua + 6]
        e += 0.5 * G(e) @ w
        y[qa + 3:qa + 7] = e / np.linalg.norm(e)
