"""Quasi-static analyses and the static commands of a run.

- FIM_D: quasi-statics as an index-1 DAE in q alone (F(q, t) = 0 plus |e| = 1 for each rigid
  body) integrated by IDA with the run's tolerance; FIM_S at the first and the last point and
  whenever the integration fails.
- FIM_S: each output's equilibrium solved on its own, from the previous one.
"""
import math

import numpy as np

from .outputs import print_times
from .pyida import PyIDA
from .statics import StaticProblem, fim_s, finished, solve_static


def quasi_static(model, t0, y0, times, params, tol, kind=None):
    """FIM_D: follow F(q, t) = 0 from (t0, y0) through `times` with IDA; FIM_S polishes the
    first and last points and restarts the integration wherever it fails.

    Returns (list of (t, y) at t0 and `times`, list of StaticResult)."""
    kernel = model.compile(kind).kernel
    prob = StaticProblem(kernel)
    y, first = fim_s(prob, t0, y0, params)
    results = [finished(prob, t0, y, params, first)]
    if not first.success:
        return [], results
    lay = kernel.layout
    rigid = [qa + 3 for b, qa in zip(lay.bodies, lay.qadr) if b.kind == "rigid"]
    nq = len(prob.qcols)
    qpos = {q: i for i, q in enumerate(prob.qcols)}
    reg = math.sqrt(params.stability) * prob.M

    def embed(q):
        yy = np.zeros(kernel.ny)
        yy[prob.qcols] = q
        return yy

    def residual(t, q, qp, r):
        r[:prob.n] = prob.imbalance(t, embed(q)) / prob.cf
        for i, e in enumerate(rigid):
            j = qpos[e]
            r[prob.n + i] = q[j:j + 4] @ q[j:j + 4] - 1.0

    def jacobian(t, q, qp, r, cj, JJ):
        yy = embed(q)
        J = kernel.jacobian_array(t, yy, prob.zero, 0.0)[np.ix_(prob.rows, prob.qcols)]
        # regularised like FIM_S: sqrt(stability) M mapped back to q increments (N^+)
        JJ[:prob.n, :] = (J + reg @ prob.N_pinv(yy)) / prob.cf
        for i, e in enumerate(rigid):
            j = qpos[e]
            JJ[prob.n + i, :] = 0.0
            JJ[prob.n + i, j:j + 4] = 2.0 * q[j:j + 4]

    def rate(t, q):
        """dq/dt on the equilibrium path: -(dR/dq)^-1 dR/dt (dR/dt by central differences)."""
        h = 1e-6 * max(1.0, abs(t))
        rp, rm, JJ = np.zeros(nq), np.zeros(nq), np.zeros((nq, nq))
        residual(t + h, q, None, rp)
        residual(t - h, q, None, rm)
        jacobian(t, q, None, None, 0.0, JJ)
        return -np.linalg.solve(JJ, (rp - rm) / (2 * h))

    solver = PyIDA(residual, rtol=tol, atol=tol, max_num_steps=100000, linsolver="dense",
                   jacfn=jacobian, algebraic_idx=list(range(nq)))
    q = y[prob.qcols].copy()
    solver.init_step(t0, q, rate(t0, q))
    out = [(t0, y)]
    for i, tp in enumerate(times):
        sol = solver.step(tp)
        if not sol.success:
            # FIM_S from the last good point to this output, then integrate on from there
            yy, r = fim_s(prob, tp, embed(q), params)
            results.append(finished(prob, tp, yy, params, r))
            if not r.success:
                return out, results
            q = yy[prob.qcols].copy()
            solver.init_step(tp, q, rate(tp, q))
        else:
            q = np.array(sol.y)
        if i == len(times) - 1:
            yy, r = fim_s(prob, tp, embed(q), params)
            results.append(finished(prob, tp, yy, params, r))
            q = yy[prob.qcols].copy()
        out.append((tp, embed(q)))
    return out, results


class StaticFailure(Exception):
    """A static or quasi-static command did not find its equilibrium."""


def run_static(run, cmd):
    """A Static command of a run: one equilibrium at cmd.end_time, then an output row."""
    y, res = solve_static(run.model, cmd.end_time, run.y, run.model.static,
                          run.options.integr_tol, run.options.resolved_kernel())
    run.statics.append(res)
    if not res.success:
        raise StaticFailure(f"static analysis at t = {cmd.end_time:g}: {res.message}")
    run.after_static(cmd.end_time, y)


def run_quasi_static(run, cmd):
    """A Quasi-Static command of a run: equilibria at the print times (FIM_D follows them with
    IDA; FIM_S solves each one)."""
    params = run.model.static
    times = print_times(run.t, cmd.end_time, cmd.print_interval)
    if params.method == "FIM_D":
        out, results = quasi_static(run.model, run.t, run.y, times, params,
                                    run.options.integr_tol, run.options.resolved_kernel())
        run.statics.extend(results)
        for tp, y in out:
            run.after_static(tp, y)
        if not results[-1].success or len(out) < len(times) + 1:
            raise StaticFailure(f"quasi-static analysis: {results[-1].message}")
        return
    prob = StaticProblem(run.kernel)
    y = run.y
    for tp in [run.t] + list(times):
        y, res = fim_s(prob, tp, y, params)
        run.statics.append(finished(prob, tp, y, params, res))
        if not res.success:
            raise StaticFailure(f"quasi-static analysis at t = {tp:g}: {res.message}")
        run.after_static(tp, y)
