"""The fast path of :meth:`pysolver.Model.run`: a run that is nothing but IDA through print
times, with almost no Python.

A scene without sensors, load controls, motions or user subroutines called from the kernel,
integrated by IDA from C, needs none of the driver's machinery (:mod:`.driver`): its run is the
initial conditions, then one C call per Simulate command (``ps_ida_outputs``) that integrates
through the command's print times into arrays allocated once for the whole run (per
:data:`~.outputs.Grid.BATCH` print times, as the driver, so that a progress bar moves). What
does not change between runs of the same model and options is built once and kept on the
kernel: the print times, the row count and the IDA object with its linear solver (started
again with ``ps_ida_rerun``, not rebuilt).

A run that does not finish cleanly (an IDA failure, too many steps, a non-finite value) is run
again on the general path, which reports it in its own words: the fast path has no side effects
to undo, and a scene that runs cleanly, the common case in a batch study, pays nothing for the
general path's generality. The two give the same rows to the last bit (tests/test_fast.py).
"""
import threading
import time

import numpy as np

from ..build.bindings import ffi, lib
from ..build.kernel import UserFailure
from . import integrator, report
from .outputs import Grid, Progress, over_budget

#: Whether runs may take the fast path (tests switch it off to compare with the general path).
ENABLED = True


def fast_run(model, kernel, options, actors):
    """The kept :class:`FastRun` of `model` under `options`, or None when the run needs the
    general driver."""
    if not ENABLED or actors:
        return None
    cache = kernel.__dict__.setdefault("_fast", {})
    key = id(options)
    if key not in cache:
        cache.clear()                       # one entry: the options object is kept alive
        plan = integrator.cached_plan(kernel, options)
        ok = (plan.use_c and not model.sensors and not model.controls and
              not kernel.arrays["nuser"] and not kernel.layout.lam and
              all(cmd.analysis == "TRANSIENT" for cmd in model.commands))
        cache[key] = (options, FastRun(model, kernel, options, plan) if ok else None)
    return cache[key][1]


class FastRun:
    """Everything a clean run of one model under one set of options needs, built once."""

    def __init__(self, model, kernel, options, plan):
        self.model, self.k, self.options, self.plan = model, kernel, options, plan
        self.solver = integrator.make(kernel, options, plan, (
            options.h_max or 0.0, options.h_min or 0.0, options.h0_max or 0.0))
        # each command, its start and its print times (those of outputs.Grid, bit for bit) in
        # batches of one C call; every row's time
        self.commands, t, rows = [], 0.0, [np.zeros(1)]
        for cmd in model.commands:
            times = Grid(t, cmd.end_time, cmd.print_interval).all()
            batches = [times[i:i + Grid.BATCH] for i in range(0, len(times), Grid.BATCH)]
            self.commands.append((cmd, t, batches))
            rows.append(times)
            t = cmd.end_time
        self.times = np.concatenate(rows)
        self.nout = max(int(kernel.arrays["nout"]), 1)
        self.fb = ffi.from_buffer
        self.reached, self.tret = ffi.new("int *"), ffi.new("double *")
        self.roots = ffi.new("int[1]")

    def run(self, t_start, used, static, labels, log, progress=None, stream=None):
        """Run the model; returns its Result, or None when the general path must run it.
        `progress` as Model.run; `stream` an outputs.Stream the rows are written to."""
        k, d, fb, opts = self.k, self.k.d, self.fb, self.options
        k.reset_counters()
        n, ny = len(self.times), k.ny
        if over_budget(n, ny, len(k.channels), "the run"):
            return None                     # the driver stops at the command past the budget
        main = threading.current_thread() is threading.main_thread()
        if main:
            lib.ps_interrupt_arm()
        bar, row, ran = Progress(0.0, self.times[-1], progress), 1, False
        try:
            # the initial state (sweep cases change it) and a consistent yp
            t0, y0 = 0.0, k.layout.initial_state()
            d.last_t = t0
            d.bad_kind = 0
            try:
                yp0 = k.consistent_yp(t0, y0)
            except UserFailure:
                return None
            if d.bad_kind or not np.isfinite(yp0).all():
                return None
            T, Y, YP = self.times.copy(), np.empty((n, ny)), np.empty((n, ny))
            REQ = np.empty((n, self.nout))
            Y[0], YP[0], REQ[0, :len(k.channels)] = y0, yp0, k.outputs(t0, y0, yp0)
            t_run = time.perf_counter()
            fresh, status = True, 0
            ida = self.solver
            if stream is not None:
                stream.rows(T[:1], REQ[:1])
                lib.ps_ida_set_stream(ida.s, stream.st)
            if lib.ps_ida_rerun(ida.s, t0, fb("double[]", y0), fb("double[]", yp0)) != 0:
                ida.started = False
                ida.init_step(t0, y0, yp0)
            for cmd, _, batches in self.commands:
                d.step_limit = d.ntimes - d.nfail + opts.max_num_steps    # as the driver
                for times in batches:
                    flag = lib.ps_ida_outputs(
                        ida.s, fb("double[]", times), len(times), cmd.end_time, fresh,
                        fb("double[]", Y[row:]), fb("double[]", YP[row:]),
                        fb("double[]", REQ[row:]), self.reached, self.tret, self.roots)
                    row += self.reached[0]
                    fresh = False
                    if lib.ps_interrupted():
                        status = -600
                        break
                    if flag < 0 or self.reached[0] < len(times) or d.user_error:
                        return None
                    bar.update(T[row - 1])
                if status:
                    break
            ran = True
        finally:
            d.step_limit = 0
            lib.ps_ida_set_stream(self.solver.s, ffi.NULL)
            if main:
                lib.ps_interrupt_disarm()
            if ran or bar.shown:        # a run handed to the driver shows the driver's bar
                bar.close(self.times[row - 1])
        t_end = time.perf_counter()
        return self.result((T[:row], Y[:row], YP[:row], REQ[:row, :len(k.channels)]), status,
                           (t_start, t_run, t_end), (used, static, labels), log)

    def result(self, rows, status, clock, settings, log):
        """The Result of a run that reached len(rows[0]) rows (status 0, or -600 Ctrl-C)."""
        k = self.k
        message = f"interrupted at t = {rows[0][-1]:.6g}" if status else \
            "The simulation finished."
        return report.result(self.model, k, self.plan, settings, rows,
                             (not status, status, message), clock, self.solver.counters(), log,
                             steps=int(k.d.ntimes - k.d.nfail))
