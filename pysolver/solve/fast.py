"""The batched path of a run: IDA through print times, one C call per batch, with almost no
Python.

A run whose actors (:func:`.driver.deck_actors`: sensors, LoadControl tasks, the printer; a new
kind of actor says it through :attr:`.actors.Actor.instants`) have no instants of their own,
integrated by IDA from C, needs none of the general loop's machinery: it is the initial
conditions (:func:`.driver.start_state`, shared with the general loop), then per Simulate
command ``ps_ida_outputs`` calls through its print times (per :data:`~.outputs.Grid.BATCH`, so
a progress bar moves) into arrays allocated once for the whole run. What does not change
between runs of the same model, options and backend is built once and kept: the print times,
the row count and the IDA object with its linear solver (started again with
``ps_ida_rerun``). A failure is worded by :func:`.driver.failure`, as the general loop words
it, and the two give the same rows, counters and messages to the last bit
(tests/test_fast.py).
"""
import time

import numpy as np

from .. import settings
from ..build.bindings import ffi, lib
from ..build.kernel import UserFailure
from . import integrator, report
from .driver import Stop, deck_actors, failure, start_state
from .loadcontrol import NonFinite
from .outputs import Grid, Progress, over_budget

#: Whether runs may take the fast path (tests switch it off to compare with the general path).
ENABLED = True


def fast_run(compiled, options, actors):
    """The kept :class:`FastRun` of a compiled model under `options`, or None when the run
    needs the general driver."""
    if not ENABLED or actors:
        return None
    cache = compiled.batched
    key = (id(options), settings.backend())
    if key not in cache:
        cache.clear()                       # one entry: the options object is kept alive
        model, kernel = compiled.model, compiled.kernel
        plan = integrator.cached_plan(compiled, options)
        # the batched path: IDA from C, transient commands only, and no actor of the deck's
        # acting at instants of its own (a new actor says so through Actor.instants)
        sensors, controls, printer = deck_actors(model, kernel, [], Progress(0.0, 1.0, False))
        ok = (plan.use_c and all(cmd.analysis == "TRANSIENT" for cmd in model.commands)
              and not any(a.instants for a in (sensors, *controls, printer)))
        cache[key] = (options, FastRun(model, kernel, options, plan, controls) if ok else None)
    return cache[key][1]


class FastRun:
    """Everything a clean run of one model under one set of options needs, built once."""

    def __init__(self, model, kernel, options, plan, controls=()):
        self.model, self.k, self.options, self.plan = model, kernel, options, plan
        # LoadControl tasks act at their update times inside the C loop (ps_ida_controlled)
        self.controls = list(controls)
        if self.controls:
            self.ctl = ffi.new("psControl *[]", [task.c for task in self.controls])
            self.restart = self.controls[0].restart.r
            self.state = (ffi.new("double *"), np.empty(kernel.ny), np.empty(kernel.ny),
                          ffi.new("int *"), ffi.new("long *"), ffi.new("int[2]"))
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
        """Run the model; returns its Result, or None when its outputs would pass the budget
        (the general path stops at the command past it). `progress` as Model.run; `stream`
        an outputs.Stream the rows are written to."""
        k, d, fb, opts = self.k, self.k.d, self.fb, self.options
        k.reset_counters()
        n, ny = len(self.times), k.ny
        if over_budget(n, ny, len(k.channels), "the run"):
            return None
        T, Y, YP = self.times.copy(), np.empty((n, ny)), np.empty((n, ny))
        REQ = np.empty((n, self.nout))
        bar, row, t_run = Progress(0.0, self.times[-1], progress), 0, None
        status, message = 0, "The simulation finished."
        ida = self.solver
        try:
            # the initial state (sweep cases change it) and a consistent yp, as the driver
            k.senval[:] = 0.0                      # as a new run's actors (Sensors) set it
            t0, y0, yp0 = start_state(self.model, k, opts.integr_tol)
            if self.controls:
                self.state[0][0] = t0
            for task in self.controls:             # as the general loop: the tasks start
                task.start(_State(t0, y0, yp0))
            Y[0], YP[0], REQ[0, :len(k.channels)] = y0, yp0, k.outputs(t0, y0, yp0)
            row, t_run, fresh = 1, time.perf_counter(), True
            d.last_t = t0
            if stream is not None:
                stream.rows(T[:1], REQ[:1])
                lib.ps_ida_set_stream(ida.s, stream.st)
            if lib.ps_ida_rerun(ida.s, t0, fb("double[]", y0), fb("double[]", yp0)) != 0:
                ida.started = False
                ida.init_step(t0, y0, yp0)
            if self.controls:
                t, y, yp, cfresh, nrestarts, ctl = self.state
                t[0], y[:], yp[:], cfresh[0], nrestarts[0] = t0, y0, yp0, 1, 0
            for cmd, _, batches in self.commands:
                d.step_limit = d.ntimes - d.nfail + opts.max_num_steps    # as the driver
                for i, times in enumerate(batches):
                    out = (fb("double[]", Y[row:]), fb("double[]", YP[row:]),
                           fb("double[]", REQ[row:]), self.reached, self.tret)
                    if self.controls:
                        flag = lib.ps_ida_controlled(
                            ida.s, self.restart, self.ctl, len(self.controls),
                            fb("double[]", times), len(times), cmd.end_time,
                            i == len(batches) - 1, t, fb("double[]", y), fb("double[]", yp),
                            cfresh, *out, nrestarts, ctl)
                    else:
                        flag = lib.ps_ida_outputs(ida.s, fb("double[]", times), len(times),
                                                  cmd.end_time, fresh, *out, self.roots)
                    row += self.reached[0]
                    fresh = False
                    if lib.ps_interrupted():
                        raise Stop(False, -600, f"interrupted at t = {T[row - 1]:.6g}")
                    if flag == lib.PS_IDA_CONTROL_FAILED:
                        self.controls[ctl[0]].fail(ctl[1], t[0])
                    if flag < 0 or d.user_error or d.steps_exceeded:
                        raise Stop(False, *failure(self.model, k, opts, flag, self.tret[0]))
                    bar.update(T[row - 1])
        except Stop as stop:
            status, message = stop.status, stop.message
        except NonFinite as err:                     # as the general loop words them
            status, message = -700, str(err)
        except UserFailure as err:
            status, message = -400, f"{err} (t = {self.state[0][0]:.6g})"
        finally:
            for task in self.controls:
                log.extend(task.notes())
            d.step_limit = 0
            if stream is not None:
                lib.ps_ida_set_stream(ida.s, ffi.NULL)
            bar.close(T[max(row - 1, 0)])
        t_end = time.perf_counter()
        rows = (T[:row], Y[:row], YP[:row], REQ[:row, :len(k.channels)])
        return report.result(self.model, k, self.plan, (used, static, labels), rows,
                             (status == 0, status, message), (t_start, t_run or t_end, t_end),
                             self.solver.counters(), log, steps=int(k.d.ntimes - k.d.nfail),
                             nrestarts=int(self.state[4][0]) if self.controls else 0,
                             controllers={task.lc.id: task.records() for task in self.controls})


class _State:
    """The run state a task's start reads and makes consistent (in place), as the driver's."""

    def __init__(self, t, y, yp):
        self.t, self.y, self.yp = t, y, yp
