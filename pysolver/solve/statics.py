"""Static and quasi-static equilibrium (Param_Static, seed 004): the solvers.

The static equations, in increments of translation and body-frame rotation vector, are
:class:`.staticproblem.StaticProblem`'s.

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
from .pyida import PyIDA
from .staticproblem import StaticFailure, StaticProblem, StaticResult  # noqa: F401

#: The largest turn (rad) of one Newton increment in a scene with tracked angles.
TURN_LIMIT = 0.5


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
