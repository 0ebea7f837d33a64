"""Static and quasi-static equilibrium (Param_Static, seed 004).

The static equations are the dynamic rows of the kernel's residual with every velocity and
acceleration zero: F(q, t) = M (0 - g) - Q(q, 0, t) = 0, one row per velocity coordinate u.
Rigid bodies have seven position coordinates (Euler parameters) but six velocity coordinates, so
Newton works in increments of u's kind: a translation and a rotation vector in the body frame,
applied as q <- q (+) N(q) du with the exact exponential map for rotations. The stiffness in
those coordinates is K = dF/dq N(q), from the kernel's exact Jacobian.

- FIM_S: Newton-Raphson on F = 0 with K + sqrt(stability) M; converged when the largest
  imbalance is below max_imbalance (deck force units) and the largest increment below max_error.
- MKEAM: integrate the undamped system (penalty1 and velocity terms removed), stop at each
  kinetic-energy peak (an IDA root of -dKE/dt), zero the velocities, restart; converged when the
  peak energy is below max_ke_tol and the largest relative change of q between peaks below
  max_dq_tol. The stable point found is then polished by FIM_S (which stays at that equilibrium).
- FIM_D (quasi-statics, :mod:`.quasistatic`): the equilibrium path followed by IDA. A pure
  static solve with FIM_D means FIM_S.
"""
import dataclasses
import math

import numpy as np

from ..build.compiler import FROZEN_TIME
from ..deck.expr import nodes
from ..rotations import G
from .pyida import PyIDA

#: The largest turn (rad) of one Newton increment in a scene with tracked angles.
TURN_LIMIT = 0.5


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


def _limit(prob, dx, tlimit, alimit):
    """Scale an increment (and its multipliers' change with it: a damped Newton step; the
    caller then sets the static reactions) so that no translation exceeds tlimit and no
    rotation alimit (Adams' TLIMIT and ALIMIT), keeping its direction; returns (the
    increment, whether tlimit was the limit that cut it)."""
    du = dx[:prob.n]
    turn = move = 1.0
    c = 0
    for b in prob.k.layout.bodies:
        move = min(move, tlimit / max(np.abs(du[c:c + 3]).max(), 1e-300))
        if b.kind == "rigid":
            turn = min(turn, alimit / max(np.linalg.norm(du[c + 3:c + 6]), 1e-300))
            c += 6
        else:
            c += 3
    return dx * min(move, turn), move < min(turn, 1.0)


def fim_s(prob, t, y, params, max_iter=None):
    """Newton-Raphson on the force imbalance; returns (y, StaticResult).

    Each increment is limited to params.tlimit per translation and params.alimit per rotation
    (Adams' TLIMIT, ALIMIT). Plain limited Newton is tried first; if it stops making progress
    or runs out of iterations, Newton with a step-halving search (halve while the next
    correction would be larger), which crosses contact onsets that make plain Newton cycle.
    The search can stall where a neutral direction amplifies tiny moments, which plain Newton
    does not mind; so each covers the other's failure. A failure names both passes and
    returns the point of the smallest imbalance either reached."""
    max_iter = max_iter or params.max_num_iter
    plain = _newton(prob, t, y, params, max_iter, search=False)
    if plain.stop == "converged":
        return plain.y, StaticResult(t, "FIM_S", True,
                                     f"FIM_S converged in {plain.iterations} iterations",
                                     plain.iterations, plain.imbalance, plain.error)
    halving = _newton(prob, t, y, params, max_iter, search=True)
    its = plain.iterations + halving.iterations
    if halving.stop == "converged":
        return halving.y, StaticResult(
            t, "FIM_S", True, f"FIM_S converged in {its} iterations (with step halving, after "
            f"{plain.iterations} plain iterations)", its, halving.imbalance, halving.error)
    best = min((plain, halving), key=lambda a: a.imbalance)
    return best.y, StaticResult(
        t, "FIM_S", False, f"FIM_S did not converge: {plain.why()}, then "
        f"{halving.why()}{_hint(prob, params, plain, halving)}; the best "
        f"imbalance reached {best.imbalance:.3g} (max_imbalance {params.max_imbalance:g}) with "
        f"increment or constraint violation {best.error:.3g}", its, best.imbalance, best.error)


def _hint(prob, params, *passes):
    """A note on failed passes: set stability after a singular matrix; how often tlimit cut
    the increments of a pass that ran out of iterations, when it cut most of them (it is in
    deck length units: its default 20 is 20 mm in a millimetre deck)."""
    if any(p.stop.startswith("singular") for p in passes):
        return (" (a neutral equilibrium, or the constraints at a singular position?): set "
                "Param_Static stability > 0" if prob.m else " (a neutral equilibrium?): set "
                "Param_Static stability > 0")
    cut = [p for p in passes if p.stop == "limit" and 2 * p.cut > p.iterations]
    if cut:
        p = max(cut, key=lambda p: p.cut)
        return (f" (tlimit cut {p.cut} of the {p.iterations} increments of {p.name} to "
                f"{params.tlimit:g} deck length units)")
    return ""


#: Plain Newton gives way to the step-halving search after this many iterations without a
#: smaller Newton correction than its best.
STALL = 10


@dataclasses.dataclass
class _Attempt:
    """How one Newton pass of FIM_S ended: `stop` is "converged", "stalled", "limit" or the
    singular matrix met; `y`, `imbalance` and `error` are its answer, or the point of its
    smallest imbalance; `cut` counts the increments tlimit cut."""
    name: str
    stop: str
    iterations: int
    y: np.ndarray
    imbalance: float
    error: float
    cut: int = 0

    def why(self):
        """How the pass ended, as a clause of the failure message."""
        if self.stop == "stalled":
            return (f"{self.name} stopped after {self.iterations} iterations (no smaller "
                    f"correction in the last {STALL})")
        if self.stop == "limit":
            return f"{self.name} used all {self.iterations} iterations (max_num_iter)"
        return f"{self.name} met a {self.stop} at iteration {self.iterations + 1}"


def _newton(prob, t, y, params, max_iter, search):
    """One Newton pass from y (plain, or with the step-halving search); an _Attempt.

    Progress is measured by the size of the Newton correction in the mass metric (Deuflhard's
    natural level function, :meth:`StaticProblem.norm`), which weighs imbalances and
    constraint violations alike in every unit system. A step cut short by tlimit, alimit or
    the search is followed back onto the constraints and the multipliers are set to the
    static reactions there, so that the next matrix is the right one."""
    name = "Newton with step halving" if search else "plain Newton"
    y = prob.reactions(t, prob.track(t, prob.state(y)))
    reg = math.sqrt(params.stability) * prob.M
    n = prob.n
    # a tracked angle follows its body only while each increment turns it well under pi
    alimit = min(params.alimit, TURN_LIMIT) if len(prob.turns) else params.alimit
    R = prob.residual(t, y)
    imb, err = np.abs(R[:n]).max() / prob.cf, prob.violation(R)
    best = (imb, y, err)
    least, least_it, cut = math.inf, 0, 0

    def ended(stop, its):
        return _Attempt(name, stop, its, best[1], best[0], best[2], cut)

    for it in range(1, max_iter + 1):
        if not search and it - least_it > STALL:
            return ended("stalled", it - 1)
        A = prob.matrix(t, y, reg)
        try:
            dx = np.linalg.solve(A, -R)
        except np.linalg.LinAlgError:
            dx = None
        if dx is None or not np.all(np.isfinite(dx)):
            return ended("singular stiffness matrix" + (" with the constraints" if prob.m
                                                        else ""), it - 1)
        size = prob.norm(dx)
        if size < least:
            least, least_it = size, it
        dx, moved = _limit(prob, dx, params.tlimit, alimit)
        cut += moved
        for _ in range(30 if search else 1):
            y1 = prob.track(t, prob.apply(y, dx))
            step = prob.norm(dx)
            if step < size:
                y1 = prob.reactions(t, prob.restore(t, y1, step))
            R1 = prob.residual(t, y1)
            if not search:
                break
            # accept a step whose next correction (with this matrix) is no larger than this
            # one (Deuflhard's natural monotonicity); otherwise halve it
            try:
                nxt = prob.norm(np.linalg.solve(A, -R1))
            except np.linalg.LinAlgError:
                nxt = math.inf
            if nxt <= size:
                break
            dx = 0.5 * dx
        y, R = y1, R1
        err = max(np.abs(dx[:n]).max(), prob.violation(R))
        imb = np.abs(R[:n]).max() / prob.cf
        if imb < best[0]:
            best = (imb, y, err)
        if imb < params.max_imbalance and err < params.max_error:
            return _Attempt(name, "converged", it, y, imb, err, cut)
    return ended("limit", max_iter)


def mkeam(prob_c, t, y, params, tol):
    """Maximum kinetic energy attrition on the undamped kernel; returns (y, StaticResult)."""
    k = prob_c.k
    y = prob_c.state(y)
    if FROZEN_TIME in k.params:           # motions held where they are at time t
        k.arrays["consts"][k.params[FROZEN_TIME]] = t
    root = lambda tau, yy, yyp, g: g.__setitem__(0, -k.power(yy, yyp))  # noqa: E731
    res = lambda tau, yy, yyp, r: k.residual(t, yy, yyp, r)  # noqa: E731  (time frozen)
    jac = lambda tau, yy, yyp, r, cj, J: k.jacobian(t, yy, yyp, cj, J)  # noqa: E731
    # the constraints' multipliers are out of the error test, as in the transient driver
    atol = np.full(k.ny, tol)
    atol[k.layout.algebraic] = 1e300
    solver = PyIDA(res, rootfn=root, nroots=1, rtol=tol, atol=atol, max_num_steps=100000,
                   linsolver="dense", jacfn=jac, hit_outputs=bool(k.layout.algebraic))
    q_prev = y.copy()
    ke = dq = math.inf
    horizon = 1e6
    for it in range(1, params.max_num_iter + 1):
        yp = k.consistent_yp(t, y)
        solver.init_step(0.0, y, yp)
        sol = solver.step(horizon, horizon)
        if sol.status != 2:
            # no kinetic-energy peak: at rest already (its energy at the horizon is still
            # under max_ke_tol: FIM_S polishes it), or the motion never turns
            u = np.array(sol.y)[prob_c.rows] if sol.success else None
            rest = u is not None and 0.5 * u @ prob_c.M @ u / prob_c.cf < params.max_ke_tol
            return y, StaticResult(t, "MKEAM", (it > 1 or rest) and sol.success,
                                   f"MKEAM: no kinetic-energy peak in iteration {it} "
                                   f"({sol.message})", it, np.abs(prob_c.imbalance(t, y)).max()
                                   / prob_c.cf, dq)
        yr = np.array(sol.y)
        u = yr[prob_c.rows]
        ke = 0.5 * u @ prob_c.M @ u / prob_c.cf
        y = prob_c.state(yr)
        q = y[prob_c.qcols]
        dq = np.max(np.abs(q - q_prev[prob_c.qcols]) / np.maximum(1.0, np.abs(q)))
        q_prev = y.copy()
        if ke < params.max_ke_tol and dq < params.max_dq_tol:
            return y, StaticResult(t, "MKEAM", True, f"MKEAM converged after {it} "
                                   "kinetic-energy peaks", it,
                                   np.abs(prob_c.imbalance(t, y)).max() / prob_c.cf, dq)
    return y, StaticResult(t, "MKEAM", False, f"MKEAM did not converge in "
                           f"{params.max_num_iter} peaks: last peak energy {ke:.3g}, relative "
                           f"change {dq:.3g}", params.max_num_iter,
                           np.abs(prob_c.imbalance(t, y)).max() / prob_c.cf, dq)


def compliance(prob, t, y, params):
    """(K + sqrt(stability) M)^-1 in deck length per deck force, or None when singular; with
    constraints, the compliance of the motions they admit (the stiffness block of the
    inverse of [[K + sqrt(stability) M, dF/dlam], [C, 0]])."""
    A = prob.matrix(t, y, math.sqrt(params.stability) * prob.M)
    A[:prob.n] /= prob.cf
    try:
        return np.linalg.inv(A)[:prob.n, :prob.n]
    except np.linalg.LinAlgError:
        return None


def solve_static(model, t, y, params, tol, kind=None):
    """One static solve at time t from y with the deck's method, on the kernel of that `kind`
    (Options.kernel); returns (y, StaticResult)."""
    compiled = model.compile(kind)
    prob = StaticProblem(compiled.kernel)
    if params.method == "MKEAM" and any(_calls_routine(mo.expr)
                                        for mo in compiled.model.motions.values()):
        raise StaticFailure("MKEAM holds every motion at the command's time, which a MOTSUB "
                            "called from the kernel (a C library or untraceable Python) "
                            "cannot be: use FIM_S, or a MOTSUB that can be traced")
    if params.method == "MKEAM":
        y1, r1 = mkeam(StaticProblem(compiled.conservative_kernel), t, y, params, tol)
        if not r1.success:
            return y1, finished(prob, t, y1, params, r1)
        y2, r2 = fim_s(prob, t, y1, params)
        r2.method = "MKEAM+FIM_S"
        r2.iterations = r1.iterations
        r2.message = r1.message + "; " + r2.message
        return y2, finished(prob, t, y2, params, r2)
    y1, r1 = fim_s(prob, t, y, params)
    return y1, finished(prob, t, y1, params, r1)


def _calls_routine(tree):
    """Whether an expression tree calls a user subroutine from the kernel."""
    return tree is not None and any(n[0] == "user" for n in nodes(tree))


def finished(prob, t, y, params, res):
    """The equilibrium record `res` at (t, y) completed with its compliance and coordinates
    (every static and quasi-static result goes through here)."""
    res.compliance = compliance(prob, t, y, params)
    res.coordinates = prob.names
    return res
