"""The static equations of a compiled kernel (Param_Static, seed 004), for the solvers of
:mod:`.statics` and :mod:`.quasistatic`.

The static equations are the dynamic rows of the kernel's residual with every velocity and
acceleration zero: F(q, t) = M (0 - g) - Q(q, 0, t) = 0, one row per velocity coordinate u, and
each constraint's position row g(q, t) = 0. Rigid bodies have seven position coordinates (Euler
parameters) but six velocity coordinates, so Newton works in increments of u's kind: a
translation and a rotation vector in the body frame, applied as q <- q (+) N(q) du with the
exact exponential map for rotations. The stiffness in those coordinates is K = dF/dq N(q), from
the kernel's exact Jacobian. Increments are measured in the mass metric, the same in every
unit system; the static reactions and the return onto the constraints after a step cut short
are here too.
"""
import dataclasses
import math

import numpy as np

from ..rotations import G


class StaticFailure(Exception):
    """A static or quasi-static command did not find its equilibrium."""


@dataclasses.dataclass
class StaticResult:
    """Outcome of one static solve.

    Attributes
    ----------
    time : float
    method : str
        The method that produced the answer (``"MKEAM+FIM_S"`` for a polished MKEAM).
    success : bool
    message : str
    iterations : int
        Newton iterations (FIM_S: of both passes when the first failed), kinetic-energy peaks
        (MKEAM), or IDA steps (FIM_D).
    imbalance : float
        Largest force imbalance at the answer, deck force units (moments in deck force times
        length); after a failed FIM_S, the least either pass reached.
    error : float
        Largest increment of the Newton iteration that reached the answer, or the constraints'
        violation there if larger (or relative change between the last two peaks for
        MKEAM).
    compliance : ndarray
        Inverse of the regularised stiffness (K + sqrt(stability) M)^-1 at the answer, in the
        velocity-like coordinates of ``coordinates`` (deck length per deck force).
    coordinates : list of str
    """
    time: float
    method: str
    success: bool
    message: str
    iterations: int
    imbalance: float
    error: float
    compliance: np.ndarray = None
    coordinates: list = None


class StaticProblem:
    """The static equations of one compiled kernel, in increment coordinates."""

    def __init__(self, kernel):
        self.k = kernel
        lay = kernel.layout
        self.cf = kernel.arrays["force_scale"]
        rows, names, qcols, M, force = [], [], [], [], []
        for b, qa, ua in zip(lay.bodies, lay.qadr, lay.uadr):
            nu = 6 if b.kind == "rigid" else 3
            rows += list(range(ua, ua + nu))
            force += [True] * 3 + [False] * (nu - 3)
            qcols += list(range(qa, qa + (7 if nu == 6 else 3)))
            names += [f"body{b.id}.{c}" for c in ("dx", "dy", "dz", "rx", "ry", "rz")[:nu]]
            blk = np.eye(nu) * b.mass
            if nu == 6:
                blk[3:, 3:] = b.inertia
            M.append(blk)
        self.rows = np.array(rows, dtype=int)
        self.qcols = np.array(qcols, dtype=int)
        self.names = names
        self.n = len(rows)
        self.M = _block_diag(M, self.n)
        # which rows balance forces (the others balance moments), and the Cholesky factor of
        # the mass metric that measures increments alike in any unit system (masses are
        # positive and inertias positive definite: the deck checks both)
        self.force_rows = np.array(force, dtype=bool)
        self.chol = np.linalg.cholesky(self.M)
        self.chol_inv = np.linalg.inv(self.chol)
        self.zero = np.zeros(kernel.ny)
        # constraint equations: each one's multiplier state and its position row (displacement
        # motions and every constraint have one; the deck refuses other motions in statics);
        # the tracked angles of screws, racks and couplers, kept on their measured angles
        self.lam = np.array(lay.lam, dtype=int)
        self.pos = np.array(lay.mu, dtype=int)
        if np.any(self.pos < 0):               # a GCOSUB of velocities, known once traced
            raise StaticFailure("a relation of velocities (non-holonomic) has no static "
                                "form; run the scene as a transient")
        self.m = len(self.lam)
        self.size = self.n + self.m
        self.turns = np.array(list(lay.turns.values()), dtype=int)

    def state(self, y):
        """Positions and multipliers of y with every velocity (and position multiplier mu)
        set to zero."""
        y = np.array(y, dtype=float)
        y[self.rows] = 0.0
        y[self.pos] = 0.0
        return y

    def residual(self, t, y):
        """The static equations [F; g]: force imbalance (model units) and the constraints'
        violations."""
        r = self.k.residual_array(t, y, self.zero)
        return np.concatenate([r[self.rows], r[self.pos]])

    def track(self, t, y):
        """Move the tracked angles of y (in place) onto their measured angles (each row is
        the wrapped error, d/ds = -1): increments turn a body by less than pi."""
        if len(self.turns):
            y[self.turns] += self.k.residual_array(t, y, self.zero)[self.turns]
        return y

    def norm(self, du):
        """The size of an increment of the n coordinates in the mass metric, sqrt(du' M du):
        translations weighed by the masses, rotations by the inertias, so that it scales alike
        in every unit system."""
        w = self.chol.T @ du[:self.n]
        return math.sqrt(w @ w)

    def reactions(self, t, y):
        """y with the static multipliers at its positions: the reactions that balance the
        bodies' forces as nearly as they can (least squares), and of those the ones that
        balance the moments best. (The reactions of the bodies released at rest, weighed by
        the inverse mass matrix, would turn a link towards the top: a hanging pendulum's pin
        carries less than its weight while it falls.)"""
        if not self.m:
            return y
        J = self.k.jacobian_array(t, y, self.zero, 0.0)
        B = J[np.ix_(self.rows, self.lam)]
        F = self.residual(t, y)[:self.n]
        scale = np.linalg.norm(B, axis=0)
        scale[scale == 0] = 1.0
        B = B / scale
        f, m = self.force_rows, ~self.force_rows
        U, sv, Vt = np.linalg.svd(B[f], full_matrices=f.sum() < self.m)
        rank = int(np.sum(sv > 1e-10 * sv[0])) if len(sv) else 0
        dlam = Vt[:rank].T @ ((U[:, :rank].T @ -F[f]) / sv[:rank])
        free = Vt[rank:].T                       # multipliers the forces leave open
        if free.shape[1] and m.any():
            dlam += free @ np.linalg.lstsq(B[m] @ free, -(F[m] + B[m] @ dlam), rcond=None)[0]
        y = y.copy()
        y[self.lam] += dlam / scale
        return y

    def restore(self, t, y, step):
        """y moved back onto the constraints g = 0 by the smallest corrections in the mass
        metric (Newton on g alone), after an increment of size `step` that Newton's method did
        not take in full (its constraints hold to first order only, and a stiff force reading
        their violation, a bushing on a joint, would answer with a force that is not there at
        any assembled position). y unchanged if the corrections do not converge."""
        if not self.m:
            return y
        n, last, y0 = self.n, math.inf, y
        for _ in range(10):
            g = self.residual(t, y)[n:]
            C = self.matrix(t, y)[n:, :n]
            # du = L^-T z with the least |z| = |du|_M: C L^-T z = -g, rows made unit size
            Z = C @ self.chol_inv.T
            rn = np.linalg.norm(Z, axis=1)
            rn[rn == 0] = 1.0
            z = np.linalg.lstsq(Z / rn[:, None], -g / rn, rcond=None)[0]
            du = self.chol_inv.T @ z
            size = self.norm(du)
            if size > 0.5 * last or (last == math.inf and size > step):
                break                    # at rounding's level, or not converging
            y = self.track(t, self.apply(y, np.concatenate([du, np.zeros(self.m)])))
            last = size
            if size <= 1e-14 * step:
                break
        return y if last < math.inf else y0

    def violation(self, R):
        """Largest constraint violation in a residual of :meth:`residual` (model lengths or
        radians)."""
        return np.abs(R[self.n:]).max() if self.m else 0.0

    def matrix(self, t, y, reg=None):
        """d[F; g]/d[u-increment, lam] at y, with `reg` (n x n) added to the stiffness block:
        [[K + reg, dF/dlam], [C, 0]]."""
        J = self.k.jacobian_array(t, y, self.zero, 0.0)
        N = self.N(y)
        A = np.zeros((self.size, self.size))
        A[:self.n, :self.n] = J[np.ix_(self.rows, self.qcols)] @ N
        if reg is not None:
            A[:self.n, :self.n] += reg
        if self.m:
            A[:self.n, self.n:] = J[np.ix_(self.rows, self.lam)]
            A[self.n:, :self.n] = J[np.ix_(self.pos, self.qcols)] @ N
        return A

    def imbalance(self, t, y):
        """F(q, t) in model units (mass * length / time^2)."""
        return self.k.residual_array(t, y, self.zero)[self.rows]

    def N(self, y):
        """dq/du at y: identity for translations, 1/2 G(e) for Euler parameters (7 x 6 blocks)."""
        N = np.zeros((len(self.qcols), self.n))
        r = c = 0
        for b in self.k.layout.bodies:
            N[r:r + 3, c:c + 3] = np.eye(3)
            if b.kind == "rigid":
                qa = self.k.layout.qadr[self.k.layout.index[b.id]]
                N[r + 3:r + 7, c + 3:c + 6] = 0.5 * G(y[qa + 3:qa + 7])
                r, c = r + 7, c + 6
            else:
                r, c = r + 3, c + 3
        return N

    def N_pinv(self, y):
        """Pseudo-inverse of N(q): identity for translations, 4 N^T / |e|^2 for rotations."""
        N = self.N(y)
        P = N.T.copy()
        r = c = 0
        for b in self.k.layout.bodies:
            if b.kind == "rigid":
                blk = N[r + 3:r + 7, c + 3:c + 6]
                P[c + 3:c + 6, r + 3:r + 7] = blk.T / (blk.T @ blk)[0, 0]
                r, c = r + 7, c + 6
            else:
                r, c = r + 3, c + 3
        return P

    def apply(self, y, dx):
        """q <- q (+) du: translations added, rotations by the exponential map (body frame);
        the multipliers (dx past the n increments) added."""
        y = y.copy()
        du = dx[:self.n]
        y[self.lam] += dx[self.n:]
        c = 0
        for b, qa in zip(self.k.layout.bodies, self.k.layout.qadr):
            y[qa:qa + 3] += du[c:c + 3]
            if b.kind == "rigid":
                th = du[c + 3:c + 6]
                a = np.linalg.norm(th)
                dq = np.concatenate([[math.cos(a / 2)],
                                     (math.sin(a / 2) / a) * th if a > 0 else 0.5 * th])
                e = _quat_mul(y[qa + 3:qa + 7], dq)
                y[qa + 3:qa + 7] = e / np.linalg.norm(e)
                c += 6
            else:
                c += 3
        return y


def _block_diag(blocks, n):
    M = np.zeros((n, n))
    i = 0
    for blk in blocks:
        k = blk.shape[0]
        M[i:i + k, i:i + k] = blk
        i += k
    return M


def _quat_mul(p, q):
    p0, pv = p[0], p[1:]
    q0, qv = q[0], q[1:]
    return np.concatenate([[p0 * q0 - pv @ qv], p0 * qv + q0 * pv + np.cross(pv, qv)])
