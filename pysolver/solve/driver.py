"""The transient driver: integrate, stop at instants, ask the actors.

One :class:`Run` is one run of a model: the state (t, y, yp), the step bounds, the integrator
(:mod:`.integrator`) and the actors (:mod:`.actors`: sensors at roots, the printer at print
times). The C driver runs a batch of print times without returning to Python: Python runs
once per event and per batch, not per step. Scenes with a ``zero_crossing`` sensor step one
internal step at a time, each converged step kept with the actors' snapshots, so the run can
go back to the last one before an event (restore-and-shrink).
"""
import collections
import time

import numpy as np

from ..build import compliance, restart, usercalls
from ..build.bindings import ffi, lib
from ..build.consistent import AssemblyError
from ..build.kernel import UserFailure
from . import breaks, integrator, kept, kinks, nonfinite, precision, quasistatic
from .actors import Actor, Flow
from .loadcontrol import Interrupted, LoadControlTask, NonFinite
from .outputs import Printer, Progress, command_rows, over_budget
from .sensors import Chatter, Sensors
from .step import CONV_FAIL, ERR_FAIL, ROOT_RETURN, TOO_MUCH_WORK, Step


def max_steps_message(limit, t, why=None):
    """A command stopped by max_num_steps at t (`why`: precision.unresolved's advice)."""
    return (f"max_num_steps = {limit} reached: the Simulate command took {limit} steps "
            f"(IDA's converged steps, counted from the command's start) and stopped at "
            f"t = {t:.6g}; raise max_num_steps (Param_Transient) or "
            + (why or "loosen the scene's stiffest element"))


def user_failure(kernel, message, t):
    """Status -400's message: a routine's error in a run stopped at t, and the time of the
    failing call (an IDA trial's, a difference's) when that is another."""
    tc = kernel.d.user_t
    if not kernel.d.user_error or tc != tc or f"{tc:.6g}" == f"{t:.6g}":
        return f"{message} (t = {t:.6g})"
    return f"{message} (called at t = {tc:.6g}; the run's last converged step: t = {t:.6g})"


class Stop(Exception):
    """Ends the run: success flag, status and message."""

    def __init__(self, success, status, message):
        super().__init__(message)
        self.success, self.status, self.message = success, status, message


def deck_actors(model, kernel, log, bar):
    """The actors a deck's own elements make: its sensors, its LoadControl tasks, the printer
    and the restarts at spline knots where a motion's velocity jumps (they act at one
    instant in the order sensors, tasks, restarts, printer). Whether any of them acts at instants of
    its own decides whether a run can take the batched path (:mod:`.fast`)."""
    sensors = Sensors(model, kernel, log)
    printer = Printer(kernel, bar)
    printer.watchers = [sensors]
    controls = [LoadControlTask(model, kernel, model.controls[lid], k)
                for k, lid in enumerate(sorted(model.controls))]
    stops = (kinks.KnotRestarts(model, kernel, log), breaks.TimeBreaks(model, kernel))
    return sensors, controls, printer, [a for a in stops if a.times]


def start_state(model, kernel, tol, exact_rows=True):
    """(t0, y0, yp0) of a run at integr_tol `tol`: the bodies' initial state and rates
    consistent with it (Stop when they cannot be had); `exact_rows`: output rows take exact
    accelerations and reactions (options.reactions)."""
    compliance.set_tolerance(kernel, tol, (UserFailure,))
    restart.exact_rows(model, kernel, exact_rows)
    kernel.d.user_coarse = int(tol >= usercalls.COARSE_TOL)
    t0, y0 = 0.0, kernel.layout.initial_state()
    kernel.d.last_t = t0
    kernel.d.bad_kind = 0
    try:
        yp0 = kernel.consistent_yp(t0, y0, initial=True, tol=tol)
    except AssemblyError as err:
        raise Stop(False, -720, f"initial conditions: {err}") from None
    except np.linalg.LinAlgError:
        raise Stop(False, -700, "initial conditions: the accelerations and reactions cannot "
                   "be solved for (a zero mass or inertia, or constraints that fight)") from None
    except UserFailure as err:           # a user subroutine failed (or Ctrl-C came)
        if lib.ps_interrupted():
            raise Stop(False, -600, f"interrupted at t = {t0:.6g}") from None
        raise Stop(False, -400, user_failure(kernel, err, t0)) from None
    why = kept.at_start(kernel, t0, y0, tol)
    if why:
        raise Stop(False, -720, f"initial conditions: {why}")
    if kernel.d.bad_kind or not np.isfinite(yp0).all():
        why = nonfinite.describe(model, kernel) or (
            "the accelerations cannot be solved for: dF/dyp is singular or not "
            "finite (a zero or huge mass, inertia or penalty1?)")
        raise Stop(False, -700, f"initial conditions: {why}")
    return t0, y0, yp0


def failure(model, kernel, options, status, t):
    """(status, message) of an integration that stopped with IDA's flag `status` at t: too
    many steps, a user subroutine's error, a non-finite value, or IDA's own failure."""
    d = kernel.d
    if d.steps_exceeded or status == TOO_MUCH_WORK:
        return -100, max_steps_message(options.max_num_steps, d.last_t if d.steps_exceeded
                                       else t, precision.unresolved(kernel, options.integr_tol))
    if d.user_error:
        return -400, user_failure(kernel, kernel.message, t)
    why = nonfinite.describe(model, kernel)
    if why:
        return -700, f"IDA failed at t = {t:.6g} after a {why}"
    message = f"IDA failed at t = {t:.6g}: {Step(t, None, None, status).message}"
    if options.h_min and status in (ERR_FAIL, CONV_FAIL):
        message += (f" (h_min = {options.h_min:g} is set: IDA may take no smaller step; a "
                    "smaller h_min, or 0, lets it)")
    return status, message


class Run:
    """One run of a model: state, step bounds, integrator, actors, and what they recorded."""

    def __init__(self, model, kernel, options, plan, progress, stream=None):
        self.model, self.kernel, self.options, self.plan = model, kernel, options, plan
        self.hmax = options.h_max          # None: unbounded
        self.hmin = options.h_min or 0.0
        self.events, self.log, self.statics = [], [], []
        self.bar = Progress(0.0, model.commands[-1].end_time, progress)
        self.sensors, self.controls, self.printer, knots = deck_actors(model, kernel,
                                                                       self.log, self.bar)
        self.printer.stream = stream
        self.actors = [self.sensors, *self.controls, *knots, self.printer]
        # each actor's slice of IDA's root flags, in the kernel's root order
        self.root_slices, off = [], 0
        for a in self.actors:
            if a.nroots:
                self.root_slices.append((a, slice(off, off + a.nroots)))
                off += a.nroots
        self.onestep = any(a.needs_restore for a in self.actors)
        self.steps_seen = collections.deque(maxlen=3)   # (t, y, yp, snapshot) of converged steps
        self.solver = None
        self.bounds = None
        self.nstarts = 0
        self.retired = {"nfev": 0, "njev": 0, "netf": 0, "ncfn": 0, "steps": 0}
        self.growth_limited_at = None
        self.need_start = True
        self.first_step = None
        self.fresh = False
        self.t_setup = None             # when the initial events were done (perf_counter)

    # the integrator --------------------------------------------------------------------
    def start(self, first_step=None):
        """(Re)start IDA at the current state: a cold restart (order 1, history dropped). New
        step bounds are set on IDA from C (ps_ida_bounds, as the batched path's C loop sets
        them); through scikit-sundae a new IDA object is built for them."""
        bounds = (self.hmax or 0.0, self.hmin, first_step or self.options.h0_max or 0.0)
        self.kernel.d.last_t = self.t      # restarts are not step attempts (see ps_residual)
        if self.solver is not None and bounds != self.bounds and self.plan.use_c:
            self.solver.set_bounds(*bounds)
            self.bounds = bounds
        if self.solver is None or bounds != self.bounds:
            self.retire_solver()
            self.solver = integrator.make(self.kernel, self.options, self.plan, bounds)
            self.bounds = bounds
            if self.printer.stream is not None and self.plan.use_c:
                lib.ps_ida_set_stream(self.solver.s, self.printer.stream.st)
                self.printer.c_streams = True
        self.nstarts += 1
        self.fresh = True
        self.need_start = False
        self.solver.init_step(self.t, self.y, self.yp)
        self.steps_seen.clear()
        self.remember_step()

    def retire_solver(self):
        """Keep the counters of an IDA object that is being replaced (or at the end)."""
        if self.solver is None:
            return
        if self.printer.c_streams:
            lib.ps_ida_set_stream(self.solver.s, ffi.NULL)
        c = self.solver.counters()
        if c["growth_limited_at"] and self.growth_limited_at is None:
            self.growth_limited_at = self.retired["steps"] + c["growth_limited_at"]
        for key in self.retired:
            self.retired[key] += c[key] or 0
        self.solver = None

    def steps(self):
        """Converged steps so far, counted by the kernel from the times of residual calls."""
        d = self.kernel.d
        return int(d.ntimes - d.nfail)

    # restore-and-shrink ------------------------------------------------------------------
    def remember_step(self):
        """Keep a converged step, with everything an action may change (onestep mode only)."""
        if not self.onestep:
            if not self.steps_seen:
                self.steps_seen.append((self.t, None, None, None))
            return
        snap = (len(self.events), len(self.log), self.hmax, [a.save() for a in self.actors])
        self.steps_seen.append((self.t, self.y.copy(), self.yp.copy(), snap))

    def last_converged_time(self):
        return self.steps_seen[-1][0]

    def restore_last_step(self):
        """Go back to the last converged step, undoing every action taken since; returns the
        size of the last step completed before it (or h_max when bounded)."""
        t_prev, y_prev, yp_prev, (nev, nlog, hmax, snaps) = self.steps_seen[-1]
        del self.events[nev:]
        del self.log[nlog:]
        self.hmax = hmax
        for actor, snap in zip(self.actors, snaps):
            actor.restore(snap, t_prev)
        if self.hmax:
            current = self.hmax
        elif len(self.steps_seen) >= 2:
            current = t_prev - self.steps_seen[-2][0]
        else:
            current = self.t - t_prev
        self.t, self.y, self.yp = t_prev, y_prev.copy(), yp_prev.copy()
        return current

    # instants --------------------------------------------------------------------------
    def apply(self, flow):
        """Carry out what the actors asked for at the current instant; returns True when the
        current command ends here."""
        if flow.restored:
            self.start()
            return False
        if flow.restart or flow.first_step is not None:
            if self.solver is not None:
                self.start(flow.first_step)
            else:                           # at t0 the integrator starts later
                self.first_step = flow.first_step
        if flow.emit or flow.halt or flow.ret:
            self.printer.emit(self.t, self.y, self.yp)
        if flow.halt:
            raise Stop(True, 1, f"halted by {flow.halt} at t = {self.t:.9g}")
        return flow.ret is not None

    def act_due(self, timed):
        """Let every actor whose time has come act; returns True when the command ends here."""
        due = [a for a in timed if a.next_time(self.t) <= self.t]
        if not due:
            return False
        flow = Flow()
        for actor in due:
            flow.update(actor.on_time(self))
        return self.apply(flow)

    def add_actor(self, actor):
        """Add an actor that acts at its own times or when rows are written (before run())."""
        if actor.nroots:
            raise ValueError("an actor with root functions must be compiled into the kernel; "
                             "add_actor takes actors that act at times or on output rows")
        self.actors.append(actor)
        self.onestep |= actor.needs_restore
        if type(actor).on_output is not Actor.on_output:
            self.printer.watchers.append(actor)

    def on_roots(self, step):
        flow = Flow()
        for actor, sl in self.root_slices:
            flow.update(actor.on_roots(self, step.roots[sl]))
        return self.apply(flow)

    def interrupted(self):
        """The Stop of a Ctrl-C: the time is that of the last row kept (a batch may have run
        past the driver's own time)."""
        t = max(self.t, self.printer.ts.last) if self.printer.ts else self.t
        return Stop(False, -600, f"interrupted at t = {t:.6g}")

    def check_output_budget(self, end, dt, what):
        """Stop before allocating when the rows kept so far and those of printing every dt to
        end would pass the memory budget (see outputs.over_budget)."""
        rows = len(self.printer.ts) + command_rows(self.t, end, dt)
        why = over_budget(rows, self.kernel.ny, len(self.kernel.channels), what)
        if why:
            raise Stop(False, -500, why)

    def set_print_interval(self, dt, what):
        """A new print interval from now on (a sensor's dt action), within the budget."""
        if self.printer.end is not None:
            self.check_output_budget(self.printer.end, dt, f"{what} at t = {self.t:.6g}")
        self.printer.set_interval(self.t, dt)

    # a transient command -------------------------------------------------------------
    def run_transient(self, cmd):
        printer = self.printer
        self.check_output_budget(cmd.end_time, cmd.print_interval,
                                 f"the Simulate command ending at {cmd.end_time:g}")
        # the schedule first: the first converged step's snapshot holds the command's interval
        printer.begin_command(self.t, cmd.end_time, cmd.print_interval)
        if self.need_start:
            quasistatic.leave_equilibrium(self)
            self.start(self.first_step)
            self.first_step = None
        elif self.onestep:
            # a zero-crossing restore goes back no further than the command's start
            self.steps_seen.clear()
            self.remember_step()
        # max_num_steps counts the command's converged steps; the kernel ends the run at the
        # attempt of one more (d.step_limit), on either integrator
        self.kernel.d.step_limit = self.steps() + self.options.max_num_steps
        try:
            self.integrate_command(cmd)
        finally:
            self.kernel.d.step_limit = 0

    def integrate_command(self, cmd):
        printer = self.printer
        timed = [a for a in self.actors if a is not printer]
        while printer.pending:
            if lib.ps_interrupted():
                raise self.interrupted()
            if self.act_due(timed):
                return
            self.kernel.d.bad_kind = 0        # a non-finite value names itself in C (below)
            # IDA stops exactly at the next instant an actor named (tstop), or the command's end
            tstop = min([cmd.end_time] + [a.next_time(self.t) for a in timed])
            # rows no action can take back any more go to the stream before integrating on
            if self.onestep:
                printer.flush_stream(self.steps_seen[0][0], inclusive=False)
            else:
                printer.flush_stream(self.t, inclusive=True)
            # after a (re)start IDA sizes its first step from the distance to the requested
            # time; asking for the stop keeps that choice independent of print times
            if self.onestep or self.fresh:
                step = self.solver.step(tstop, tstop, onestep=True)
                self.fresh = False
            elif not any(a.watching for a in self.actors):
                # all pending outputs up to the stop, an event or a failure in one call (from C:
                # without returning to Python)
                times = printer.times_before(tstop)
                if len(times):
                    step, Y, YP, REQ, n = self.solver.outputs(times, tstop)
                    printer.take(times[:n], Y, YP, REQ)
                else:
                    step = self.solver.step(tstop, tstop)
            else:
                step = self.solver.step(min(printer.pending[0], tstop), tstop)
            if lib.ps_interrupted():          # Ctrl-C: the rows so far are kept
                raise self.interrupted()
            d = self.kernel.d
            if not step.success or d.user_error or d.steps_exceeded:
                raise Stop(False, *failure(self.model, self.kernel, self.options, step.status,
                                           step.t))
            # outputs up to the point reached: the point itself, or IDA's interpolant
            t = step.t
            bad = printer.emit_due(step, self.solver, tstop)
            if bad is not None:
                raise Stop(False, *failure(self.model, self.kernel, self.options, bad.status,
                                           bad.t))
            self.t, self.y, self.yp = t, step.y, step.yp
            if step.status == ROOT_RETURN:
                if self.on_roots(step):
                    return
                continue
            if self.onestep and t > self.steps_seen[-1][0]:
                self.remember_step()
        self.act_due(timed)

    def run_assembly(self, cmd):
        """Simulate analysis_type="Assembly": the state made consistent with the constraints
        (pysolver.build.consistent; at the start of a run that is already done) and one row;
        IDA restarts from it when a transient follows."""
        if self.t > 0.0 or not self.printer.ts:
            y = self.y.copy()
            try:
                self.yp = self.kernel.consistent_yp(self.t, y)
            except AssemblyError as err:
                raise Stop(False, -720, f"assembly at t = {self.t:.6g}: {err}") from None
            self.y = y
            self.need_start = True
        self.printer.emit(self.t, self.y, self.yp)

    # the whole run -------------------------------------------------------------------
    def run(self):
        """Run every command; returns (success, status, message)."""
        k = self.kernel
        self.t = 0.0
        self.y = self.yp = np.zeros(k.ny)
        commands = {"TRANSIENT": self.run_transient, "ASSEMBLY": self.run_assembly,
                    "STATIC": lambda c: quasistatic.run_static(self, c),
                    "QUASI-STATIC": lambda c: quasistatic.run_quasi_static(self, c)}
        try:
            try:
                self.t, self.y, self.yp = start_state(self.model, k, self.options.integr_tol,
                                                      self.options.reactions == "exact")
                flow = Flow()
                for actor in self.actors:
                    flow.update(actor.start(self))
                self.printer.emit(self.t, self.y, self.yp)
                self.apply(flow)
                self.t_setup = time.perf_counter()
                for cmd in self.model.commands:
                    commands[cmd.analysis](cmd)
            except Chatter as err:
                raise Stop(False, -200, str(err)) from None
            except NonFinite as err:
                raise Stop(False, -700, str(err)) from None
            except Interrupted:
                raise self.interrupted() from None
            except UserFailure as err:      # a user subroutine failed outside IDA's calls
                raise Stop(False, -400, user_failure(k, err, getattr(err, "t", self.t))) from None
            except quasistatic.StaticFailure as err:
                why = nonfinite.describe(self.model, k)
                raise Stop(False, -300, f"{err}" + (f"; last {why}" if why else "")) from None
        except Stop as stop:
            return stop.success, stop.status, stop.message
        finally:
            for task in self.controls:
                self.log.extend(task.notes())
            self.printer.flush_stream(np.inf, inclusive=True)
            self.bar.close(self.t)
        return True, 0, "The simulation finished."

    def counters(self):
        """IDA's counters of the whole run (C driver: all; scikit-sundae: nfev, njev)."""
        self.retire_solver()
        return dict(self.retired), self.growth_limited_at

