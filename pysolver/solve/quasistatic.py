"""Quasi-static analyses and the static commands of a run.

- FIM_D: quasi-statics as an index-1 DAE in q, the constraints' multipliers and the tracked
  angles (F(q, lam, t) = 0, |e| = 1 for each rigid body, g(q, t) = 0 for each constraint, each
  tracked angle's row) integrated by IDA with the run's tolerance, the algebraic states out of
  the error test; FIM_S at the first and the last point and
  whenever the integration fails.
- FIM_S: each output's equilibrium solved on its own, from the previous one.
"""
import math

import numpy as np

from ..build.consistent import AssemblyError
from ..options import transient_only
from .outputs import print_times
from .pyida import PyIDA
from .statics import StaticFailure, StaticProblem, fim_s, finished, solve_static  # noqa: F401


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
    nq, n, m, nt = len(prob.qcols), prob.n, prob.m, len(prob.turns)
    qpos = {q: i for i, q in enumerate(prob.qcols)}
    reg = math.sqrt(params.stability) * prob.M
    # the unknowns are q, the constraints' multipliers and the tracked angles; the equations
    # F = 0, |e| = 1, the constraints g = 0 and the tracked angles' rows
    cols = np.concatenate([prob.lam, prob.turns]).astype(int)
    size = nq + m + nt

    def embed(x):
        yy = np.zeros(kernel.ny)
        yy[prob.qcols] = x[:nq]
        yy[cols] = x[nq:]
        return yy

    def residual(t, x, xp, r):
        yy = embed(x)
        R = kernel.residual_array(t, yy, prob.zero)
        r[:n] = R[prob.rows] / prob.cf
        for i, e in enumerate(rigid):
            j = qpos[e]
            r[n + i] = x[j:j + 4] @ x[j:j + 4] - 1.0
        r[nq:nq + m] = R[prob.pos]
        r[nq + m:] = R[prob.turns]

    def jacobian(t, x, xp, r, cj, JJ):
        yy = embed(x)
        J = kernel.jacobian_array(t, yy, prob.zero, 0.0)
        JJ[:] = 0.0
        # regularised like FIM_S: sqrt(stability) M mapped back to q increments (N^+)
        JJ[:n, :nq] = (J[np.ix_(prob.rows, prob.qcols)] + reg @ prob.N_pinv(yy)) / prob.cf
        JJ[:n, nq:] = J[np.ix_(prob.rows, cols)] / prob.cf
        for i, e in enumerate(rigid):
            j = qpos[e]
            JJ[n + i, j:j + 4] = 2.0 * x[j:j + 4]
        rows = np.concatenate([prob.pos, prob.turns]).astype(int)
        JJ[nq:, :nq] = J[np.ix_(rows, prob.qcols)]
        JJ[nq:, nq:] = J[np.ix_(rows, cols)]

    def rate(t, x):
        """dx/dt on the equilibrium path: -(dR/dx)^-1 dR/dt (dR/dt by central differences)."""
        h = 1e-6 * max(1.0, abs(t))
        rp, rm, A = np.zeros(size), np.zeros(size), np.zeros((size, size))
        residual(t + h, x, None, rp)
        residual(t - h, x, None, rm)
        jacobian(t, x, None, None, 0.0, A)
        return -np.linalg.solve(A, (rp - rm) / (2 * h))

    # the multipliers are out of IDA's error test, as in the transient driver
    atol = np.concatenate([np.full(nq, tol), np.full(m + nt, 1e300)])
    solver = PyIDA(residual, rtol=tol, atol=atol, max_num_steps=100000, linsolver="dense",
                   hit_outputs=bool(m + nt),
                   jacfn=jacobian, algebraic_idx=list(range(size)))
    x = np.concatenate([y[prob.qcols], y[cols]])
    solver.init_step(t0, x, rate(t0, x))
    out = [(t0, y)]
    for i, tp in enumerate(times):
        sol = solver.step(tp)
        if not sol.success:
            # FIM_S from the last good point to this output, then integrate on from there
            yy, r = fim_s(prob, tp, embed(x), params)
            results.append(finished(prob, tp, yy, params, r))
            if not r.success:
                return out, results
            x = np.concatenate([yy[prob.qcols], yy[cols]])
            solver.init_step(tp, x, rate(tp, x))
        else:
            x = np.array(sol.y)
        if i == len(times) - 1:
            yy, r = fim_s(prob, tp, embed(x), params)
            results.append(finished(prob, tp, yy, params, r))
            x = np.concatenate([yy[prob.qcols], yy[cols]])
        out.append((tp, embed(x)))
    return out, results


def unused_note(model, options):
    """A log line when a run sets settings its static and quasi-static commands do not use
    (None when it has no such command or sets none)."""
    if not any(c.analysis in ("STATIC", "QUASI-STATIC") for c in model.commands):
        return None
    unused = transient_only(options)
    if not unused:
        return None
    names, one = ", ".join(unused), len(unused) == 1
    why = "static and quasi-static commands (FIM_S, MKEAM, FIM_D) take integr_tol alone"
    if any(c.analysis == "TRANSIENT" for c in model.commands):
        return (f"Param_Transient {names} act{'s' if one else ''} on the transient commands "
                f"only: {why} (docs/statics.md)")
    return (f"Param_Transient {names} {'is' if one else 'are'} not used: {why}, and the run "
            "has no transient command (docs/statics.md)")


def fim_d_note(model):
    """A log line when FIM_D is asked of Static commands, which FIM_S solves (FIM_D follows a
    quasi-static path; one equilibrium has none); None otherwise."""
    times = [c.end_time for c in model.commands if c.analysis == "STATIC"]
    if model.static.method != "FIM_D" or not times:
        return None
    at = ", ".join(f"{t:g}" for t in times)
    return (f"Param_Static method FIM_D: the Static command{'s' if len(times) > 1 else ''} "
            f"at t = {at} {'are' if len(times) > 1 else 'is'} solved by FIM_S (FIM_D follows "
            "quasi-static paths; docs/statics.md)")


def run_static(run, cmd):
    """A Static command of a run: one equilibrium at cmd.end_time, then an output row."""
    y, res = solve_static(run.model, cmd.end_time, run.y, run.model.static,
                          run.options.integr_tol, run.options.resolved_kernel())
    run.statics.append(res)
    if not res.success:
        raise StaticFailure(f"static analysis at t = {cmd.end_time:g}: {res.message}")
    after_static(run, cmd.end_time, y)


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
            after_static(run, tp, y)
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
        after_static(run, tp, y)


def after_static(run, t, y):
    """Continue `run` from an equilibrium at (t, y), its output row with the velocities zero;
    IDA is restarted when a transient follows (:func:`leave_equilibrium`)."""
    run.t, run.y = t, y
    run.yp = np.zeros_like(y)
    run.kernel.d.last_t = t
    run.need_start = True
    run.equilibrium = True
    run.printer.emit(run.t, run.y, run.yp, exact=False)       # the equilibrium's reactions


def leave_equilibrium(run):
    """Before a transient that follows a static analysis: velocities zero and yp = 0 are
    consistent at an equilibrium only where nothing moves by itself; a motion whose rate or
    acceleration is not zero there (30 deg sin(2 pi t) at t = 0) needs the velocities, the
    accelerations and the reactions made consistent (the transient failed at its first step),
    as after an assembly. A failure is a StaticFailure (the run's -300)."""
    if not getattr(run, "equilibrium", False):
        return
    run.equilibrium = False
    if not len(run.kernel.layout.lam):
        return                          # no constraints: at rest is the consistent state
    y, why = run.y.copy(), None
    try:
        yp = run.kernel.consistent_yp(run.t, y)
        if run.kernel.d.bad_kind or not np.all(np.isfinite(yp)):
            why = "its accelerations are not finite"
    except (AssemblyError, np.linalg.LinAlgError) as err:
        why = f"its velocities and accelerations cannot be made consistent ({err})"
    if why:
        raise StaticFailure(f"the transient after the static analysis at t = {run.t:g} cannot "
                            f"start: {why}")
    run.y, run.yp = y, yp
