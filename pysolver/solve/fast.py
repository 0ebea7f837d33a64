"""The batched path of a run: IDA through print times, one C call per batch, with almost no
Python.

A run whose actors (:func:`.driver.deck_actors`: sensors, LoadControl tasks, the printer, knot
restarts; a new
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
import sys
import time

import numpy as np

from .. import settings
from ..build.bindings import ffi, lib
from ..build.kernel import UserFailure
from . import integrator, report
from .breaks import TimeBreaks
from .csensors import CSensors
from .driver import Stop, deck_actors, failure, start_state, user_failure
from .loadcontrol import NonFinite
from .outputs import Grid, Progress, command_rows, over_budget
from .sensors import restart_failure

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
        sensors, controls, printer, knots = deck_actors(model, kernel, [],
                                                        Progress(0.0, 1.0, False))
        ok = (plan.use_c and all(cmd.analysis == "TRANSIENT" for cmd in model.commands)
              and not any(a.instants for a in (sensors, *controls, *knots, printer)))
        c_sensors = CSensors(model, kernel) if sensors.sensors and ok else None
        stops = [a.times for a in knots if isinstance(a, TimeBreaks)]
        cache[key] = (options, FastRun(model, kernel, options, plan, controls, c_sensors,
                                       stops[0] if stops else ()) if ok else None)
    return cache[key][1]


class FastRun:
    """Everything a clean run of one model under one set of options needs, built once."""

    def __init__(self, model, kernel, options, plan, controls=(), sensors=None, breaks=()):
        self.model, self.k, self.options, self.plan = model, kernel, options, plan
        # LoadControl tasks and sensors whose actions need no Python act inside the C loop
        # (ps_ida_controlled), one call per Simulate command (a first step after a restart may
        # pass any number of print times, which the general loop writes before acting)
        self.controls, self.sensors = list(controls), sensors
        if sensors is not None:           # a zero-crossing restore takes the tasks back too
            sensors.tasks(self.controls)
        # the times of solve.breaks.TimeBreaks: the C loop stops and restarts there
        self.acting = bool(self.controls or sensors or len(breaks))
        if self.acting:
            self.ctl = ffi.new("psControl *[]", [task.c for task in self.controls] or 1)
            self.restart = self.controls[0].restart.r if self.controls else ffi.NULL
            self.S = sensors.S if sensors else ffi.NULL
        self.loop = _Loop(kernel.ny)
        self.solver = integrator.make(kernel, options, plan, (
            options.h_max or 0.0, options.h_min or 0.0, options.h0_max or 0.0))
        ny = kernel.ny if len(breaks) else 0
        self.bwork = np.zeros(2 * ny * ny + ny), np.zeros(ny, np.int32)
        if lib.ps_ida_breaks(self.solver.s, ffi.new("double[]", list(breaks)), len(breaks),
                             ffi.from_buffer("double[]", self.bwork[0]),
                             ffi.cast("int *", ffi.from_buffer(self.bwork[1]))):
            raise MemoryError("the times of a run's breaks")
        # each command, its start and its print times (those of outputs.Grid, bit for bit) in
        # batches of one C call; every row's time
        self.commands, t, rows = [], 0.0, [np.zeros(1)]
        for cmd in model.commands:
            times = Grid(t, cmd.end_time, cmd.print_interval).all()
            size = len(times) if self.acting else Grid.BATCH
            batches = [times[i:i + size] for i in range(0, len(times), size)]
            self.commands.append((cmd, t, batches))
            rows.append(times)
            t = cmd.end_time
        self.times = np.concatenate(rows)
        # the rows of the commands after each (room a command's call keeps for them)
        sizes = [len(r) for r in rows[1:]]
        self.later = [sum(sizes[i + 1:]) for i in range(len(sizes))]
        self.nout = max(int(kernel.arrays["nout"]), 1)
        self.fb = ffi.from_buffer
        self.reached, self.tret = ffi.new("int *"), ffi.new("double *")
        self.roots = ffi.new("int[1]")
        self.reporter = None
        self.budget_ok = None           # the output budget every command's rows were within

    def run(self, t_start, used, static, labels, log, progress=None, stream=None):
        """Run the model; returns its Result, or None when its outputs would pass the budget
        (the general path stops at the command past it). `progress` as Model.run; `stream`
        an outputs.Stream the rows are written to."""
        k, d, opts = self.k, self.k.d, self.options
        k.reset_counters()
        n, ny = len(self.times), k.ny
        # the rows are the same run after run: checked once per output budget
        budget = settings.output_budget()
        checked = budget == self.budget_ok and not self.acting
        if not checked and over_budget(n, ny, len(k.channels), "the run"):
            return None
        # rows at events, and print intervals sensors change, may need more room
        room = n + (_SLACK if self.acting else 0)
        out = _Out(self.times, room, ny, self.nout)
        # a bar off, or left to a standard error that is no terminal: the bar that does nothing
        quiet = progress is False or (progress is None and not sys.stderr.isatty())
        bar, t_run = _QUIET if quiet else Progress(0.0, self.times[-1], progress), None
        status, message, ida_counters = 0, "The simulation finished.", None
        ida = self.solver
        loop = self.loop
        loop.nrestarts[0] = 0
        try:
            # a new run's actors: stored values zero, every sensor armed (as Sensors does)
            k.senval[:] = 0.0
            if self.sensors:
                self.sensors.reset()
            for task in self.controls:
                task.reset()
            # the initial state (sweep cases change it) and a consistent yp, as the driver
            t0, y0, yp0 = start_state(self.model, k, opts.integr_tol,
                                      opts.reactions == "exact")
            halt = self._start(t0, y0, yp0)
            # the row's own copy: outputs makes its accelerations and reactions exact
            out.Y[0], out.YP[0] = y0, yp0
            k.outputs(t0, out.Y[0], out.YP[0], out=out.REQ[0])
            # row 0 is written again when a sensor at the start asks for a row (print, halt,
            # return), as Run.apply does
            again = self.sensors and (self.S.emit or self.S.halt >= 0 or self.S.ret >= 0)
            self._verbose(t0, y0, yp0, 2 if again else 1)
            out.row, t_run = 1, time.perf_counter()
            if stream is not None:
                stream.rows(out.T[:1], out.REQ[:1])
            out.streamed = 1
            if halt:
                ida_counters = {"steps": 0, "nfev": 0, "njev": 0, "netf": 0, "ncfn": 0,
                                "growth_limited_at": None}
                raise Stop(True, 1, f"halted by {halt} at t = {t0:.9g}")
            if stream is not None:
                lib.ps_ida_set_stream(ida.s, stream.st)
            d.last_t = t0
            fb = self.fb
            if lib.ps_ida_rerun(ida.s, t0, fb("double[]", y0), fb("double[]", yp0)) != 0:
                ida.started = False
                ida.init_step(t0, y0, yp0)
            if self.sensors and (self.S.hmax > 0 or self.S.first_step > 0):
                # sensors at the start set the first start's bounds, as Run.start does
                base = ida.opts[2:5]
                ida.set_bounds(self.S.hmax or base[0], base[1], self.S.first_step or base[2])
            if self.acting:
                loop.t[0], loop.y[:], loop.yp[:], loop.fresh[0] = t0, y0, yp0, 1
                self._commands_acting(out, bar)
            else:
                fresh = True
                for cmd, t_cmd, batches in self.commands:
                    if not checked:
                        self._budget(cmd, t_cmd, out.row)
                    d.step_limit = d.ntimes - d.nfail + opts.max_num_steps    # as the driver
                    for times in batches:
                        stop = self._command(cmd, times, fresh, out)
                        fresh = False
                        if stop is not None:
                            raise stop
                        bar.update(out.T[out.row - 1])
                self.budget_ok = budget
        except Stop as stop:
            status, message = stop.status, stop.message
        except NonFinite as err:                     # as the general loop words them
            status, message = -700, str(err)
        except UserFailure as err:
            status, message = -400, user_failure(k, err, getattr(err, "t", loop.t[0]))
        finally:
            if self.sensors:
                self.sensors.drain()
                log.extend(self.sensors.log)
            for task in self.controls:
                log.extend(task.notes())
            d.step_limit = 0
            if stream is not None:
                lib.ps_ida_set_stream(ida.s, ffi.NULL)
                if self.acting and out.streamed < out.row:     # the row C held back
                    stream.rows(out.T[out.streamed:out.row], out.REQ[out.streamed:out.row])
            bar.close(out.T[max(out.row - 1, 0)])
        t_end = time.perf_counter()
        row = out.row
        rows = (out.T[:row], out.Y[:row], out.YP[:row], out.REQ[:row, :len(k.channels)])
        events = self.sensors.events if self.sensors else []
        return self._reporter((used, static, labels)).result(
            rows, (status >= 0, status, message), (t_start, t_run or t_end, t_end),
            ida_counters or self.solver.counters(), log, steps=int(k.d.ntimes - k.d.nfail),
            nevents=len(events), events=events,
            nrearms=int(self.S.nrearms) if self.sensors else 0,
            nrestarts=int(loop.nrestarts[0]), onestep=bool(self.sensors and self.S.nzc),
            controllers={task.lc.id: task.records() for task in self.controls})

    def _reporter(self, settings):
        """The Reporter of runs with these settings (the same objects run after run: kept)."""
        if self.reporter is None or not all(a is b for a, b in zip(self.reporter[0], settings)):
            self.reporter = (settings, report.Reporter(self.model, self.k, self.plan, settings))
        return self.reporter[1]

    def _start(self, t0, y0, yp0):
        """The actors' start, in the general loop's order: the sensors (those whose condition
        holds fire), then the tasks; returns the element that halts the run there, or None."""
        self.loop.t[0] = t0
        halt = None
        if self.sensors:
            code = lib.ps_sensors_start(self.k.m, self.k.d, self.S, t0,
                                        self.fb("double[]", y0), self.fb("double[]", yp0))
            if code == lib.PS_SE_USER:
                if lib.ps_interrupted():              # as the general loop words Ctrl-C
                    raise Stop(False, -600, f"interrupted at t = {t0:.6g}")
                raise UserFailure(self.k.message)
            if code == lib.PS_SE_RESTART:
                raise Stop(False, -700, restart_failure(self.model, self.k, self.S.restart_rc,
                                                        t0))
            if code != lib.PS_OK:
                raise Stop(False, -200, self.sensors.chatter())
            halt = self.sensors.halted_by() if self.S.halt >= 0 else None
            self.sensors.drain()                  # the loop's records start empty
        state = _State(t0, y0, yp0) if self.controls else None
        for task in self.controls:
            task.start(state)
        return halt

    def _verbose(self, t, y, yp, times):
        """The active verbose sensors' log lines of row 0 (written `times` times)."""
        if self.sensors and self.S.nverbose:
            self.sensors.reserve(times)
            for _ in range(times):
                lib.ps_sensors_verbose(self.k.m, self.k.d, self.S, t, self.fb("double[]", y),
                                       self.fb("double[]", yp))

    def _command(self, cmd, times, fresh, out):
        """One batch of a command's print times, nothing acting: ps_ida_outputs. Returns the
        Stop that ends the run there, or None."""
        fb, row = self.fb, out.row
        flag = lib.ps_ida_outputs(self.solver.s, fb("double[]", times), len(times),
                                  cmd.end_time, fresh, fb("double[]", out.Y[row:]),
                                  fb("double[]", out.YP[row:]), fb("double[]", out.REQ[row:]),
                                  self.reached, self.tret, self.roots)
        out.row += self.reached[0]
        return self._check(flag, out.T, out.row)

    def _commands_acting(self, out, bar):
        """Every command with tasks and sensors acting in C: one ps_ida_controlled call per
        command, called again after the sensors' event records are drained or the rows grown,
        with a new print interval's times, and in the next command after a return."""
        k, d, fb, opts = self.k, self.k.d, self.fb, self.options
        loop = self.loop
        nused, nstreamed = ffi.new("int *"), ffi.new("int *")
        if self.sensors:                 # what a print interval may add (outputs.over_budget)
            self.S.row_bytes = 8 * (2 * k.ny + max(len(k.channels), 1))
            self.S.budget = settings.output_budget()
        moved = False                    # a return ended the last command early
        for ci, (cmd, t_cmd, batches) in enumerate(self.commands):
            times = batches[0]
            self._budget(cmd, loop.t[0], out.row)
            if moved:                    # the command starts where the return left it
                times = Grid(loop.t[0], cmd.end_time, cmd.print_interval).all()
            if self.sensors:             # its print grid; a restore goes back to its start
                self.S.interval = cmd.print_interval
                self.S.anchor = loop.t[0] if moved else t_cmd
                self.S.nsnap = 0
            d.step_limit = d.ntimes - d.nfail + opts.max_num_steps        # as the driver
            used = 0
            while True:
                out.reserve(len(times) - used + 1 + self.later[ci])
                row = out.row
                if self.sensors:
                    self.S.rows = row
                    self.sensors.reserve(len(times) - used + 1)
                flag = lib.ps_ida_controlled(
                    self.solver.s, self.restart, self.ctl, len(self.controls), self.S,
                    fb("double[]", times) + used, len(times) - used, cmd.end_time, loop.t,
                    fb("double[]", loop.y), fb("double[]", loop.yp), loop.fresh,
                    len(out.T) - row, row, row - out.streamed, fb("double[]", out.T) + row,
                    fb("double[]", out.Y) + row * k.ny, fb("double[]", out.YP) + row * k.ny,
                    fb("double[]", out.REQ) + row * self.nout, self.reached, nused, nstreamed,
                    self.tret, loop.nrestarts, loop.ctl)
                out.row += self.reached[0]
                out.streamed = row + nstreamed[0]
                used += nused[0]
                if self.sensors:
                    self.sensors.drain()
                if flag == lib.PS_IDA_REGRID:     # the new interval from the instant on
                    times, used = Grid(loop.t[0], cmd.end_time, self.S.dt).all(), 0
                elif flag == lib.PS_IDA_RESTORED:
                    # back at the last converged step: the print times after it of the grid
                    # then in force (Printer.restore)
                    times = Grid(self.S.anchor, cmd.end_time, self.S.interval).all()
                    times, used = times[times > loop.t[0]], 0
                elif flag != lib.PS_IDA_DRAIN:
                    break
            if out.row:
                bar.update(out.T[out.row - 1])
            stop = self._acting_stop(flag, out, cmd.end_time)
            if stop is not None:
                raise stop
            moved = flag == lib.PS_IDA_RETURN

    def _budget(self, cmd, t, rows):
        """Stop when a command starting at t after `rows` rows would pass the output budget,
        as the general loop checks it (Run.check_output_budget)."""
        k = self.k
        why = over_budget(rows + command_rows(t, cmd.end_time, cmd.print_interval), k.ny,
                          len(k.channels), f"the Simulate command ending at {cmd.end_time:g}")
        if why:
            raise Stop(False, -500, why)

    def _over_budget(self, end, out):
        """The message of a sensor's print interval past the output budget, as the general loop
        words it (Run.set_print_interval)."""
        k, t, se = self.k, self.loop.t[0], self.sensors.sensors[self.S.over]
        return over_budget(out.row + command_rows(t, end, se.dt), k.ny, len(k.channels),
                           f"Sensor_Event {se.id}'s dt = {se.dt:g} at t = {t:.6g}")

    def _acting_stop(self, flag, out, cmd_end):
        """The Stop of a call of ps_ida_controlled that ended the run, or None."""
        t, ctl = self.loop.t, self.loop.ctl
        if not lib.ps_interrupted():
            if flag == lib.PS_IDA_CONTROL_FAILED:
                try:
                    self.controls[ctl[0]].fail(ctl[1], t[0])
                except NonFinite as err:             # as the general loop words them
                    return Stop(False, -700, str(err))
                except UserFailure as err:
                    return Stop(False, -400, user_failure(self.k, err, t[0]))
            if flag == lib.PS_IDA_CHATTER:
                return Stop(False, -200, self.sensors.chatter())
            if flag == lib.PS_IDA_SENSOR_RESTART:
                return Stop(False, -700, restart_failure(self.model, self.k,
                                                         self.S.restart_rc, t[0]))
            if flag == lib.PS_IDA_BOUNDS:
                raise RuntimeError(ffi.string(lib.ps_ida_message(self.solver.s)).decode())
            if flag == lib.PS_IDA_USER:
                return Stop(False, -400, user_failure(self.k, self.k.message, self.tret[0]))
            if flag == lib.PS_IDA_BUDGET:
                return Stop(False, -500, self._over_budget(cmd_end, out))
            if flag == lib.PS_IDA_HALTED:
                return Stop(True, 1, f"halted by {self.sensors.halted_by()} at t = {t[0]:.9g}")
        return self._check(flag, out.T, out.row)

    def _check(self, flag, T, row):
        """The Stop of Ctrl-C or a failed step, worded as the general loop words them, or
        None."""
        d = self.k.d
        if lib.ps_interrupted():
            t = max(self.loop.t[0], T[row - 1]) if self.acting else T[row - 1]
            return Stop(False, -600, f"interrupted at t = {t:.6g}")
        if flag < 0 or d.user_error or d.steps_exceeded:
            return Stop(False, *failure(self.model, self.k, self.options, flag, self.tret[0]))
        return None


#: Rows beyond the print times that a run whose actors act in C starts with (rows at events).
_SLACK = 64


#: The progress bar of runs that show none.
_QUIET = Progress(0.0, 1.0, False)


class _Out:
    """A run's rows: times, states, rates and request channels, and how many are written; room
    for more is made by :meth:`reserve` (the batched path's C loop never allocates)."""

    def __init__(self, times, room, ny, nout):
        self.T = np.empty(room)
        self.T[:len(times)] = times
        self.Y, self.YP, self.REQ = np.empty((room, ny)), np.empty((room, ny)), \
            np.empty((room, nout))
        self.row = 0
        self.streamed = 0          # rows written to the run's stream

    def reserve(self, more):
        """Make room for `more` rows after those written."""
        if len(self.T) - self.row >= more:
            return
        room = self.row + more + _SLACK
        for name in ("T", "Y", "YP", "REQ"):
            old = getattr(self, name)
            new = np.empty((room,) + old.shape[1:])
            new[:self.row] = old[:self.row]
            setattr(self, name, new)


class _Loop:
    """The state the C loop carries from call to call (ps_ida_controlled's arguments): the
    current time, state and rates, whether IDA was just (re)started, the restarts, and a failed
    LoadControl update's task and code."""

    def __init__(self, ny):
        self.t, self.y, self.yp = ffi.new("double *"), np.empty(ny), np.empty(ny)
        self.fresh, self.nrestarts, self.ctl = ffi.new("int *"), ffi.new("long *"), \
            ffi.new("int[2]")


class _State:
    """The run state a task's start reads and makes consistent (in place), as the driver's."""

    def __init__(self, t, y, yp):
        self.t, self.y, self.yp = t, y, yp
