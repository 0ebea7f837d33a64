"""Transient simulation of a compiled scene with SUNDIALS IDA (scikit-sundae).

IDA gets the kernel's residual and exact dense Jacobian. The driver asks IDA for each print
time in turn (IDA interpolates; steps do not land on print times) with the command's end time
as a hard stop. Steps and failed attempts are counted by the kernel from the times of the
residual calls, so the driver costs one Python call per output, not per step.
"""
import math
import sys
import time
import warnings

import numpy as np
from sksundae.ida import IDA

from .results import Result

__version__ = "0.1.0"

_OPTION_NAMES = ("integr_tol", "h_max", "h_min", "h0_max", "max_num_steps", "linsolver",
                 "jacobian")

#: With linsolver="auto", scenes with at least this many states use the sparse solver.
SPARSE_THRESHOLD = 300


def _print_times(t0, end, dt):
    n = max(int(math.floor((end - t0) / dt + 1e-9)), 0)
    times = t0 + dt * np.arange(1, n + 1)
    times = times[times < end - 1e-12 * max(1.0, abs(end))]
    return np.append(times, end)


class _Progress:
    """A one-line progress bar on standard error, shown only on a terminal for long runs."""

    def __init__(self, t0, t1, enabled):
        self.t0, self.t1 = t0, t1
        self.enabled = sys.stderr.isatty() if enabled is None else enabled
        self.auto = enabled is None
        self.start = time.perf_counter()
        self.last = self.start
        self.shown = False

    def update(self, t, force=False):
        if not self.enabled:
            return
        now = time.perf_counter()
        if not force and (now - self.last < 0.25 or (self.auto and now - self.start < 1.0)):
            return
        self.last = now
        frac = min(max((t - self.t0) / (self.t1 - self.t0), 0.0), 1.0)
        bar = "#" * int(30 * frac)
        sys.stderr.write(f"\r  [{bar:<30}] {100 * frac:5.1f}%  t = {t:.6g}")
        sys.stderr.flush()
        self.shown = True

    def close(self, t):
        """Show the final state (always when asked for explicitly) and end the line."""
        if self.shown or (self.enabled and not self.auto):
            self.update(t, force=True)
            sys.stderr.write("\n")
            sys.stderr.flush()


def _steps(kernel):
    """Steps IDA has taken: step attempts (new residual times) less failures, less the
    evaluation at the initial time (see ps_residual)."""
    c = kernel.counters
    return max(c["attempts"] - c["nfail"] - 1, 0)


def run_model(model, progress=None, **overrides):
    """Run every Simulate command of `model`; see :meth:`Model.run`."""
    for key in overrides:
        if key not in _OPTION_NAMES:
            raise TypeError(f"unknown run option {key!r}; expected one of {_OPTION_NAMES}")
    t_start = time.perf_counter()
    kernel = model._kernel()
    opts = {k: getattr(model.transient, k, None) for k in _OPTION_NAMES}
    opts["linsolver"] = "auto"
    opts["jacobian"] = "exact"
    opts.update(overrides)
    if opts["jacobian"] not in ("exact", "dq"):
        raise ValueError(f"jacobian must be 'exact' or 'dq', not {opts['jacobian']!r}")
    if not opts["integr_tol"] > 0:
        raise ValueError("integr_tol must be > 0")
    if opts["linsolver"] not in ("auto", "dense", "sparse"):
        raise ValueError(f"linsolver must be 'auto', 'dense' or 'sparse', not {opts['linsolver']!r}")
    sparse = opts["linsolver"] == "sparse" or (opts["linsolver"] == "auto"
                                               and kernel.ny >= SPARSE_THRESHOLD)
    kernel.reset_counters()
    y = kernel.layout.initial_state()
    t = 0.0
    yp = kernel.consistent_yp(t, y)
    if sparse:
        linear = dict(linsolver="sparse", sparsity=kernel.sparsity(),
                      jacfn=kernel.jacobian_csc_fn())
    else:
        linear = dict(linsolver="dense",
                      jacfn=lambda t, y, yp, res, cj, JJ: kernel.jacobian(t, y, yp, cj, JJ))
    if opts["jacobian"] == "dq":           # IDA's own difference quotients, for comparison
        linear.pop("jacfn")
    with warnings.catch_warnings():
        # scikit-sundae warns that our exact jacfn replaces its sparse difference quotients
        warnings.simplefilter("ignore", UserWarning)
        solver = IDA(kernel.residual, rtol=opts["integr_tol"], atol=opts["integr_tol"],
                     max_step=opts["h_max"] or 0.0, min_step=opts["h_min"] or 0.0,
                     first_step=opts["h0_max"] or 0.0,
                     max_num_steps=min(opts["max_num_steps"] + 1, 2 ** 31 - 1), **linear)
    solver.init_step(t, y, yp)
    ts, ys, yps, outs = [t], [y.copy()], [yp.copy()], [kernel.outputs(t, y, yp)]
    t_setup = time.perf_counter()
    status, message, success = 0, "The simulation finished.", True
    sol = None
    bar = _Progress(t, model.commands[-1].end_time, progress)
    try:
        for cmd in model.commands:
            start_steps = _steps(kernel)
            for tp in _print_times(t, cmd.end_time, cmd.print_interval):
                sol = solver.step(tp, tstop=cmd.end_time)
                if sol.status == -1 or _steps(kernel) - start_steps > opts["max_num_steps"]:
                    # IDA's "too much work" is the same limit, counted within one output
                    success, status = False, -100
                    message = (f"more than max_num_steps = {opts['max_num_steps']} steps in one "
                               f"Simulate command (stopped at t = {float(sol.t):.6g})")
                    break
                if not sol.success:
                    success, status = False, int(sol.status)
                    message = f"IDA failed at t = {float(sol.t):.6g}: {sol.message}"
                    break
                t = float(sol.t)
                ts.append(t)
                ys.append(np.array(sol.y))
                yps.append(np.array(sol.yp))
                outs.append(kernel.outputs(t, ys[-1], yps[-1]))
                bar.update(t)
            if not success:
                break
    finally:
        bar.close(t)
    t_end = time.perf_counter()
    counters = kernel.counters
    stats = {"steps": _steps(kernel), "nres": counters["nres"], "njac": counters["njac"],
             "nfail": counters["nfail"], "outputs": len(ts),
             "ida_nfev": int(sol.nfev) if sol is not None else 0,
             "ida_njev": int(sol.njev) if sol is not None else 0}
    timing = {"setup": t_setup - t_start, "integrate": t_end - t_setup,
              "total": t_end - t_start}
    opts["linsolver"] = "sparse" if sparse else "dense"
    meta = {"version": __version__, "deck": model.source.file, "sha256": model.source.sha256,
            "options": opts, "ny": kernel.ny}
    labels = {(r.id, k): n for r in model.requests.values() for k, n in enumerate(r.names) if n}
    return Result(ts, ys, yps, outs, kernel.channels, kernel.layout.names, success, status,
                  message, stats, timing, meta, labels)
