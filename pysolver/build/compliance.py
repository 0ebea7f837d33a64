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
#: (the bodies' weight; for a row holding an angle between axes, the weight of their effective
#: inertia about the joint, :func:`rate_scales`): a reaction of that size moves the rate by the
#: tolerance, and near a
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
    kernel.rate_scale = np.full(len(kernel.layout.constraint_rows), max(mass, 1e-300))
    if kernel.layout.angular_rows:
        try:
            kernel.rate_scale = rate_scales(kernel, kernel.layout.initial_state(), mass)
        except (*failures, ValueError, ArithmeticError):
            pass
        finally:
            d.nres, d.njac, d.ntimes, d.nfail, d.last_t = kept
    kernel.compliance_key = _numbers(kernel)


def rate_scales(kernel, y, mass):
    """The mass each constraint rate row's compliance is weighed by (times max(|gravity|, 1)):
    the bodies' total mass for a row holding a displacement's rate; for a joint row holding an
    angle between axes (an angular rate, its reaction a moment), the effective inertia of the
    bodies it turns about the joint, sum_b 1 / (I_b + m_b L_b^2) inverted, I_b the body's
    inertia about the row's axis, L_b the lever of the joint's own displacement rows on it
    (the norm of their gradient in its angular velocity), where that is the larger: the rate
    a reaction moment leaves then moves the bodies' points by at most about the tolerance,
    whatever the length unit (the total mass alone left a hinge in millimetres 1000 x as
    compliant as in metres: a body at rest turned at 5e-4 rad/s, 250 x integr_tol 1e-3 in
    mm/s at its centre of mass), and no row is more compliant than a displacement's, whose
    compliance IFToMM A02 tuned (in metres the total mass is the larger for most bodies)."""
    import scipy.sparse as sp
    lay = kernel.layout
    u = _velocities(lay)
    pos = {s: p for p, s in enumerate(u)}
    zero = np.zeros_like(y)
    J0 = _Jac(kernel, 0.0, y, zero, 0.0)
    M = np.abs(_Jac(kernel, 0.0, y, zero, 1.0).diagonal() - J0.diagonal())[u]
    rows = lay.constraint_rows
    lam = np.array(lay.lam[len(lay.motion_ids):], dtype=int)
    # the rows' gradients in the velocities, sparse (a chain of bodies gives few per row)
    G = J0.J[:, u].tocsr()[lam] if J0.sparse else sp.csr_matrix(J0.J[np.ix_(lam, u)])
    owner, mass_of = np.full(len(u), -1), []  # each angular velocity's body, and its mass
    for (nq, nu), ua in zip(lay.sizes, lay.uadr):
        ang = [pos[ua + k] for k in range(3, 6)] if nu == 6 else \
            [pos[ua + 2]] if nq == 3 and nu == 3 and lay.names[ua + 2].endswith(".wz") else []
        owner[ang] = len(mass_of)
        mass_of.append(M[pos[ua]])

    def angular(i):
        """Row i's gradient in each body's angular velocity: {body: (columns, values)}."""
        cols, vals = G.indices[G.indptr[i]:G.indptr[i + 1]], G.data[G.indptr[i]:G.indptr[i + 1]]
        keep = owner[cols] >= 0
        return {b: (cols[keep & (owner[cols] == b)], vals[keep & (owner[cols] == b)])
                for b in set(owner[cols[keep]].tolist())}

    shifts = {}                              # each joint's displacement rows
    for i, row in enumerate(rows):
        if row not in lay.angular_rows:
            shifts.setdefault(row[:2], []).append(i)
    scale = np.full(len(rows), mass)
    for k, row in enumerate(rows):
        if row not in lay.angular_rows:
            continue
        lever = {}
        for i in shifts.get(row[:2], ()):
            for b, (_, v) in angular(i).items():
                lever[b] = max(lever.get(b, 0.0), float(np.linalg.norm(v)))
        inverse = sum(float(np.sum(v ** 2 / (M[c] + mass_of[b] * lever.get(b, 0.0) ** 2)))
                      for b, (c, v) in angular(k).items())
        if inverse > 0.0 and np.isfinite(inverse):
            scale[k] = max(mass, 1.0 / inverse)
    return scale


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
        held = np.array(lay.mu[base:]) >= 0
        rows = np.array(lay.lam[base:], dtype=int)[held]
        gravity = kernel.force_scale / float(np.sum(kernel.arrays["body_mass"]))
        kernel.arrays["compliance"][rows] = \
            RATE_COMPLIANCE * tol / (gravity * kernel.rate_scale[held])
