"""The compliance of the constraint rows (psModel.compliance): each position row g = 0 holds
g + c mu = 0 and each rate row g' = 0 holds g' + c lam = 0, with c made from the rows'
effective masses at the start (:func:`init_compliance`, once per kernel and its numbers) and,
for the rate rows, the run's tolerance (:func:`set_tolerance`, per run). docs/numerics.md,
"Constraints".
"""
import numpy as np

from .consistent import _Jac, _positions, _velocities

#: Each row holding a position, g = 0, holds g + c mu = 0 with c = COMPLIANCE_TIME x (the row's
#: reciprocal effective mass sum_j G_ij^2 / M_jj over the positions, at the start): exact, for
#: mu is zero on the solution, and where the constraints lose rank (a singular configuration,
#: IFToMM A02) the position rows, whose root turns double there, stay solvable by Newton's
#: method. Measured on A02's first second: 1e-12 s took 87,721 steps at integr_tol 1e-9
#: (43,573 corrector failures), 1e-9 s 674 steps; 1e-6 s and 1e-4 s no fewer, and the error at
#: 1e-8 grew from 9.3e-8 to 1.3e-7 and 3.4e-7 m (mu is not zero on BDF's discrete solution).
COMPLIANCE_TIME = 1e-9

#: Each row holding a rate, g' = 0, holds g' + c lam = 0 with c = RATE_COMPLIANCE x integr_tol /
#: (the bodies' weight): a reaction of that size moves the rate by the tolerance, and near a
#: singular configuration the velocity the constraints stop determining is left to the
#: dynamics instead of to rounding errors divided by a vanishing singular value. (0.01 held
#: the rate 100 x tighter but IFToMM A02 at integr_tol 1e-8 then took 9,735 steps, 4,394
#: corrector failures, over its first 2.5 s; 1.0: 1,037 steps, the same 2.3e-6 m error.)
RATE_COMPLIANCE = 1.0


def compliance(kernel, t, y, tau=COMPLIANCE_TIME):
    """The compliance of every reaction's row at (t, y) (zero for other states): tau times
    sum_j G_ij^2 / M_jj over the velocities j for a rate row and over the positions for a
    position row, where G is the row's gradient and M_jj the coefficient of yp_j in row j."""
    lay = kernel.layout
    c = np.zeros(kernel.ny)
    lam = np.array(lay.lam, dtype=int)
    mu = np.array([m for m in lay.mu if m >= 0], dtype=int)
    if not len(lam):
        return c
    yp = np.zeros_like(y)
    J0 = _Jac(kernel, t, y, yp, 0.0)
    J1 = _Jac(kernel, t, y, yp, 1.0)
    for rows, cols in ((lam, _velocities(lay)), (mu, _positions(lay))):
        if len(rows):
            diag = (J1.diagonal() - J0.diagonal())[cols]
            G = J0.block(rows, cols)
            c[rows] = tau * (G ** 2 / np.where(diag != 0.0, np.abs(diag), np.inf)).sum(axis=1)
    return c


def init_compliance(kernel, failures=()):
    """Set the position rows' compliance (:func:`compliance`) from the iteration matrix at the
    deck's initial state; a scale only, so a start where the matrix cannot be evaluated (the
    run will then report why; `failures`: the kernel's exception types) takes
    COMPLIANCE_TIME with unit gradients. Keep the bodies' weight (mass x 1 without gravity) as
    the rate rows' force scale (:func:`set_tolerance`). Its evaluations are not the run's: the
    call counters are left as they were (a run's statistics do not depend on whether an
    earlier run of other numbers made this one recompute it)."""
    c = kernel.arrays["compliance"]
    mu = np.array([m for m in kernel.layout.mu if m >= 0], dtype=int)
    d = kernel.d
    kept = (d.nres, d.njac, d.ntimes, d.nfail, d.last_t)
    try:
        got = compliance(kernel, 0.0, kernel.layout.initial_state())[mu]
    except (*failures, ValueError, ArithmeticError):
        got = np.full(len(mu), np.nan)
    finally:
        d.nres, d.njac, d.ntimes, d.nfail, d.last_t = kept
    c[mu] = np.where(np.isfinite(got), got, COMPLIANCE_TIME)
    mass = float(np.sum(kernel.arrays["body_mass"]))
    gravity = float(np.linalg.norm(kernel.arrays["gravity"]))
    kernel.force_scale = max(mass * max(gravity, 1.0), 1e-300)
    kernel.compliance_key = _numbers(kernel)


def _numbers(kernel):
    """The numbers the compliance depends on and a run may change (params=, sweeps): masses,
    inertias, gravity, marker positions, the bodies' initial state."""
    a = kernel.arrays
    return b"".join(np.ascontiguousarray(v, float).tobytes() for v in (
        a["body_mass"], a["body_inertia"], a["gravity"], a["marker_pos"],
        kernel.layout.initial_state()))


def set_tolerance(kernel, tol, failures=()):
    """Set the joints' rate rows' compliance for a run at integr_tol `tol`: RATE_COMPLIANCE x
    tol / (the bodies' weight), so that a reaction of that size moves its rate by the
    tolerance. A motion's rate rows keep none: a prescribed rate is exact; nor does a
    constraint held at the velocity level alone (non-holonomic): its rate row is the
    constraint. The position rows' compliance and the weight are recomputed first when the run
    changed their numbers."""
    lay = kernel.layout
    if lay.lam and kernel.compliance_key != _numbers(kernel):
        init_compliance(kernel, failures)
    if lay.constraint_rows:
        base = len(lay.motion_ids)
        rows = [lam for lam, mu in zip(lay.lam[base:], lay.mu[base:]) if mu >= 0]
        kernel.arrays["compliance"][rows] = RATE_COMPLIANCE * tol / kernel.force_scale
