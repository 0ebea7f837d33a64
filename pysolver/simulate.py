"""Transient simulation of a compiled scene with SUNDIALS IDA (scikit-sundae).

IDA gets the kernel's residual, its exact Jacobian (dense, or sparse CSC for large scenes) and,
when the scene has sensors, one root function per sensor evaluated in C. The driver asks IDA
for each print time in turn (IDA interpolates; steps do not land on print times) with the
command's end time as a hard stop, so Python runs once per output, per event and per kernel
call, not per step. Steps and failed attempts are counted by the kernel from the times of the
residual calls.

Scenes with a ``zero_crossing`` sensor are stepped one internal step at a time instead, so
that the last converged step before an event is known and can be restored (restore-and-shrink,
seed 003 Comment 3). Scenes without one pay nothing for it.
"""
import collections
import dataclasses
import itertools
import math
import os
import sys
import time
import warnings

import numpy as np
from sksundae.ida import IDA

from . import cida, statics
from .results import Result

__version__ = "0.1.0"

_OPTION_NAMES = ("integr_tol", "h_max", "h_min", "h0_max", "max_num_steps", "linsolver",
                 "jacobian", "backend", "max_step_growth", "nonlin_conv_coef")

#: The C driver's step-growth limit once IDA's error test fails in most steps (a stiff
#: penalty mode; README "Stiff penalties"), and its Newton convergence coefficient
#: (IDA's default 0.33: ten times tighter costs nothing on the seed decks and halves the
#: steps of stiff penalties; near the limit of double precision, penalty/mass ~ 1e14,
#: rounding keeps Newton from reaching it and 0.33 must be asked for).
AUTO_STEP_GROWTH = 1.1
NONLIN_CONV_COEF = 0.033

#: With linsolver="auto", scenes with at least this many states use the sparse solver.
SPARSE_THRESHOLD = 300

#: Events (firings and re-armings) allowed within CHATTER_WINDOW * max(1, |t|) of time before
#: the run stops as chattering (Zeno behaviour, or a sensor that re-fires at the same instant).
CHATTER_LIMIT = 100
CHATTER_WINDOW = 1e-9

_ROOT_RETURN = 2
_TOO_MUCH_WORK = -1


@dataclasses.dataclass
class Event:
    """One sensor firing.

    Attributes
    ----------
    time : float
        Event time (IDA's root, just after the crossing).
    sensor : int
        Sensor_Event id.
    label : str
    value : float
        The sensor's expression at the event.
    actions : list of str
        Actions taken, in order (e.g. ``["evaluate_id", "halt"]``).
    """
    time: float
    sensor: int
    label: str
    value: float
    actions: list


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
        frac = min(max((t - self.t0) / max(self.t1 - self.t0, 1e-300), 0.0), 1.0)
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


class _Stop(Exception):
    """Ends the run: success flag, status and message."""

    def __init__(self, success, status, message):
        super().__init__(message)
        self.success, self.status, self.message = success, status, message


class _Rows:
    """Output rows kept as a list of row-arrays and whole (k x n) blocks from the C driver, so
    a batch of outputs is stored without splitting it into rows; supports the list operations
    the driver uses (append, extend, pop, [-1], len)."""

    def __init__(self):
        self.parts = []
        self.n = 0

    def append(self, row):
        self.parts.append(np.asarray(row)[None, :])
        self.n += 1

    def extend(self, block):
        if len(block):
            self.parts.append(block)
            self.n += len(block)

    def pop(self):
        last = self.parts[-1]
        if len(last) > 1:
            self.parts[-1] = last[:-1]
        else:
            self.parts.pop()
        self.n -= 1
        return last[-1]

    def __getitem__(self, i):
        if i != -1:
            raise IndexError("only the last row is kept addressable")
        return self.parts[-1][-1]

    def __len__(self):
        return self.n

    def array(self, width):
        """All rows as one (n x width) array."""
        if not self.parts:
            return np.zeros((0, width))
        return np.concatenate(self.parts, axis=0)


class _Driver:
    """One run of a model: the IDA object, the state, outputs, events and counters."""

    def __init__(self, model, kernel, opts, progress):
        self.model, self.kernel, self.opts = model, kernel, opts
        self.sensors = [model.sensors[i] for i in kernel.sensor_ids]
        self.eidx = {eid: i for i, eid in enumerate(kernel.evaluate_ids)}
        self.onestep = any(s.zero_crossing for s in self.sensors)
        self.sparse = opts["linsolver"] == "sparse" or (opts["linsolver"] == "auto"
                                                        and kernel.ny >= SPARSE_THRESHOLD)
        # IDA called from C where it can be (dense or band, exact Jacobian); scikit-sundae
        # otherwise. A large scene whose Jacobian is a narrow band gets IDA's band solver.
        self.band = None
        if self.sparse and opts["linsolver"] == "auto":
            mu, ml = kernel.bandwidths()
            if 4 * (mu + ml + 1) <= kernel.ny:
                self.band = (mu, ml)
        want_c = opts["backend"] in ("auto", "c") and opts["jacobian"] == "exact" and \
            (not self.sparse or self.band is not None)
        self.use_c = want_c and cida.available()
        if self.use_c and self.band is not None:
            self.sparse = False
        # scikit-sundae runs IDA's own step control: only its default values can be asked for
        for key, ida_default in (("max_step_growth", 2.0), ("nonlin_conv_coef", 0.33)):
            if opts[key] not in (None, ida_default) and not self.use_c:
                raise ValueError(f"{key} other than IDA's {ida_default:g} needs IDA driven from "
                                 "C (dense or band scenes, exact Jacobian, the scikit-sundae "
                                 "wheel's SUNDIALS libraries)")
        if opts["backend"] == "c" and not self.use_c:
            raise ValueError("backend='c' needs the dense exact-Jacobian path and SUNDIALS "
                             "libraries from the scikit-sundae wheel")
        self.hmax = opts["h_max"]          # None: unbounded
        self.hmin = opts["h_min"] or 0.0
        self.saved_bounds = None           # (hmax, hmin) while a zero-crossing search runs
        self.zc_pending = set()
        self.verbose_active = set()
        self.steps_seen = collections.deque(maxlen=3)   # last converged steps (onestep mode)
        self.dt = None
        self.ts = []
        self.ys, self.yps, self.outs = _Rows(), _Rows(), _Rows()
        self.events, self.log = [], []
        self.statics = []
        self.nrearms = 0
        self.recent = collections.deque(maxlen=CHATTER_LIMIT)
        self.bar = _Progress(0.0, model.commands[-1].end_time, progress)
        self.solver = None
        self.bounds = None
        self.nstarts = 0
        self.ida_done = [0, 0]             # nfev, njev of IDA objects already replaced
        self.ida_last = (0, 0)             # of the current one, from its last result
        self.ida_fail = [0, 0]             # error-test and convergence failures (C driver)
        self.ida_steps_done = 0            # IDA steps of replaced C-driver objects
        self.growth_limited_at = None      # step at which the automatic growth limit came on

    # integrator ------------------------------------------------------------------------
    def _linear(self):
        k = self.kernel
        if self.sparse:
            lin = dict(linsolver="sparse", sparsity=k.sparsity(), jacfn=k.jacobian_csc_fn())
        else:
            lin = dict(linsolver="dense", jacfn=k.jacobian_ida)
        if self.opts["jacobian"] == "dq":      # IDA's own difference quotients, for comparison
            lin.pop("jacfn")
        return lin

    def _new_solver(self, bounds):
        """An IDA object with these step bounds (max, min, first): driven from C when possible,
        otherwise scikit-sundae's, with the sensors' root functions."""
        tol = self.opts["integr_tol"]
        mxsteps = min(self.opts["max_num_steps"] + 1, 2 ** 31 - 1)
        if self.use_c:
            tune = (self.opts["max_step_growth"] or 0.0,
                    self.opts["nonlin_conv_coef"] or NONLIN_CONV_COEF, AUTO_STEP_GROWTH)
            return cida.CIDA(self.kernel, tol, tol, *bounds, mxsteps, band=self.band, tune=tune)
        options = dict(rtol=tol, atol=tol, max_step=bounds[0], min_step=bounds[1],
                       first_step=bounds[2], max_num_steps=mxsteps, **self._linear())
        if self.sensors:
            k = self.kernel
            ev = lambda t, y, yp, g: k.roots(t, y, yp, g)  # noqa: E731
            ev.direction = [1] * len(self.sensors)
            ev.terminal = [True] * len(self.sensors)
            options.update(eventsfn=ev, num_events=len(self.sensors))
            self.eventsfn = ev
        with warnings.catch_warnings():
            # scikit-sundae warns that the exact jacfn replaces its sparse DQ Jacobian
            warnings.simplefilter("ignore", UserWarning)
            return IDA(self.kernel.residual, **options)

    def start(self, first_step=None):
        """(Re)start IDA at the current state: a cold restart (order 1, history dropped).
        A new IDA object is built only when the step bounds change."""
        bounds = (self.hmax or 0.0, self.hmin, first_step or self.opts["h0_max"] or 0.0)
        self.kernel.d.last_t = self.t      # restarts are not step attempts (see ps_residual)
        if self.solver is None or bounds != self.bounds:
            self._retire_solver()
            self.solver = self._new_solver(bounds)
            self.bounds = bounds
        self.nstarts += 1
        self.fresh = True
        self.solver.init_step(self.t, self.y, self.yp)
        self.steps_seen.clear()
        self.remember_step()

    def remember_step(self):
        """Keep a converged step, with everything an event may change, for restore-and-shrink."""
        if not self.onestep:
            if not self.steps_seen:
                self.steps_seen.append((self.t, None, None, None))
            return
        k = self.kernel
        snap = (k.armed.copy(), k.senval.copy(), k.sensor_side.copy(), len(self.events),
                len(self.log), self.hmax, frozenset(self.verbose_active), self.dt,
                self.nrearms)
        self.steps_seen.append((self.t, self.y.copy(), self.yp.copy(), snap))

    def _retire_solver(self):
        """Keep the counters of an IDA object that is being replaced."""
        if self.solver is None:
            return
        if self.use_c:
            st = self.solver.stats()
            self.ida_done[0] += st[1]
            self.ida_done[1] += st[2]
            self.ida_fail[0] += st[3]
            self.ida_fail[1] += st[4]
            if st[6] and self.growth_limited_at is None:
                self.growth_limited_at = self.ida_steps_done + st[6]
            self.ida_steps_done += st[0]
        else:
            self.ida_done[0] += self.ida_last[0]
            self.ida_done[1] += self.ida_last[1]
        self.ida_last = (0, 0)

    def steps(self):
        c = self.kernel.counters
        return c["attempts"] - c["nfail"]

    # outputs ---------------------------------------------------------------------------
    def output(self, t, y, yp, out=None):
        if self.ts and t < self.ts[-1]:
            return
        if self.ts and t == self.ts[-1]:      # a later answer at the same time replaces it
            for lst in (self.ts, self.ys, self.yps, self.outs):
                lst.pop()
        self.ts.append(t)
        self.ys.append(np.array(y))
        self.yps.append(np.array(yp))
        self.outs.append(self.kernel.outputs(t, self.ys[-1], self.yps[-1]) if out is None
                         else out)
        if self.verbose_active:
            f = self.kernel.sensor_values(t, self.ys[-1], self.yps[-1])
            for k in sorted(self.verbose_active):
                se = self.sensors[k]
                self.log.append(f"t = {t:.9g}: Sensor_Event {se.id} active "
                                f"(value {f[k]:.6g} {se.compare} {se.value:g})")
        self.bar.update(t)

    # events ----------------------------------------------------------------------------
    def _holds(self, k, f):
        se = self.sensors[k]
        if se.compare == "GE":
            return f >= se.value
        if se.compare == "LT":
            return f < se.value
        return abs(f - se.value) <= se.error_tol

    def _rearms(self, k, f):
        se = self.sensors[k]
        if se.compare == "GE":
            return f < se.value - se.error_tol
        if se.compare == "LT":
            return f > se.value + se.error_tol
        return abs(f - se.value) > 2 * se.error_tol

    def initial_events(self):
        """Sensors whose condition already holds at the start fire at the start."""
        if not self.sensors:
            return {}
        f = self.kernel.sensor_values(self.t, self.y, self.yp)
        for k in range(len(self.sensors)):
            self.arm(k, f[k])
        return self.settle(set(), set())

    def on_root(self, sol):
        """Handle an IDA root return; returns the actions that affect the command loop."""
        if getattr(sol, "roots", None) is not None:
            info = sol.roots
        else:
            info = self.eventsfn._i[-1]
            for lst in (self.eventsfn._i, self.eventsfn._t, self.eventsfn._y, self.eventsfn._yp):
                lst.clear()               # scikit-sundae keeps every event; we do not need to
        self.t, self.y, self.yp = float(sol.t), np.array(sol.y), np.array(sol.yp)
        self._check_chatter()
        armed = self.kernel.armed
        crossed = [k for k in range(len(self.sensors)) if info[k] != 0]
        fired = [k for k in crossed if armed[k]]
        rearmed = [k for k in crossed if not armed[k]]
        # restore-and-shrink for zero_crossing sensors seen for the first time
        search = [k for k in fired if self.sensors[k].zero_crossing and k not in self.zc_pending]
        if search and self.steps_seen[-1][0] < self.t:
            self.restore_and_shrink(search)
            return {"restored": True}
        # IDA saw these crossings: take them as they are, then settle the rest
        f = self.kernel.sensor_values(self.t, self.y, self.yp)
        for k in rearmed:
            self.arm(k, f[k])
            self.nrearms += 1
            self.verbose_active.discard(k)
        flow = self.fire(fired, f) if fired else {}
        flow.update(self.settle(set(fired), set(rearmed)))
        return flow

    def arm(self, k, f):
        """Arm sensor k; an EQ sensor remembers from which side it approaches its value."""
        self.kernel.armed[k] = 1
        self.kernel.sensor_side[k] = 1.0 if f >= self.sensors[k].value else -1.0

    def settle(self, fired, rearmed):
        """Event iteration at one instant: actions may change what the sensors see (SENVAL,
        restarts), so re-arm and fire until nothing changes; each sensor fires and re-arms at
        most once per instant, which bounds the loop."""
        flow = {}
        armed = self.kernel.armed
        while True:
            f = self.kernel.sensor_values(self.t, self.y, self.yp)
            up = [k for k in range(len(self.sensors))
                  if not armed[k] and k not in rearmed and self._rearms(k, f[k])]
            for k in up:
                self.arm(k, f[k])
                self.nrearms += 1
                self.verbose_active.discard(k)
                rearmed.add(k)
                self._check_chatter()
            now = [k for k in range(len(self.sensors))
                   if armed[k] and k not in fired and self._holds(k, f[k])]
            if now:
                fired.update(now)
                self._check_chatter()
                flow.update(self.fire(now, f))
            if not up and not now:
                return flow

    def _check_chatter(self):
        self.recent.append(self.t)
        if (len(self.recent) == CHATTER_LIMIT
                and self.recent[-1] - self.recent[0] <= CHATTER_WINDOW * max(1.0, abs(self.t))):
            raise _Stop(False, -200, f"sensor events chatter: {CHATTER_LIMIT} events between "
                        f"t = {self.recent[0]:.12g} and {self.recent[-1]:.12g}; the sensors keep "
                        "re-firing without time advancing (give them an error_tol band)")

    def restore_and_shrink(self, search):
        """Go back to the last converged step before the event and approach it again with
        hmax and hmin scaled by zero_crossing. "Current hmax" when h_max is unbounded is the
        size of the last step completed before the event."""
        t_prev, y_prev, yp_prev, snap = self.steps_seen[-1]
        # everything the events inside this step changed goes back too: they will recur
        k = self.kernel
        (armed, senval, side, nev, nlog, hmax, verbose, dt, nrearms) = snap
        k.armed[:], k.senval[:], k.sensor_side[:] = armed, senval, side
        del self.events[nev:]
        del self.log[nlog:]
        self.hmax, self.verbose_active, self.dt, self.nrearms = hmax, set(verbose), dt, nrearms
        if self.hmax:
            current = self.hmax
        elif len(self.steps_seen) >= 2:
            current = t_prev - self.steps_seen[-2][0]
        else:
            current = self.t - t_prev
        zc = min(self.sensors[k].zero_crossing for k in search)
        self.zc_pending.update(search)
        if self.saved_bounds is None:
            self.saved_bounds = (self.hmax, self.hmin)
        self.hmax, self.hmin = zc * current, zc * self.hmin
        self.t, self.y, self.yp = t_prev, y_prev.copy(), yp_prev.copy()
        for k in search:
            se = self.sensors[k]
            self.log.append(f"t = {t_prev:.9g}: Sensor_Event {se.id} zero crossing: back to the "
                            f"last converged step, hmax {self.hmax:.3g}")
        self.start()

    def fire(self, fired, f):
        """Run the actions of the sensors that fired at the current time, in id order."""
        k_ = self.kernel
        flow = {}
        restart, first_step, emit = False, None, False
        for k in fired:
            se = self.sensors[k]
            k_.armed[k] = 0
            actions = se.actions()
            if k in self.zc_pending:
                self.zc_pending.discard(k)
                if not self.zc_pending and self.saved_bounds is not None:
                    self.hmax, self.hmin = self.saved_bounds
                    self.saved_bounds = None
                    restart = True
            if se.evaluate_id is not None:
                idx = self.eidx[se.evaluate_id]
                k_.senval[idx] = k_.evaluate(idx, self.t, self.y, self.yp)
                restart |= k_.forces_use_senval
            if se.dt is not None:
                flow["dt"] = se.dt
            if se.stepsize is not None:
                first_step = se.stepsize if first_step is None else min(first_step, se.stepsize)
            if se.hmax is not None:
                self.hmax = se.hmax
                if self.saved_bounds is not None:
                    self.saved_bounds = (se.hmax, self.saved_bounds[1])
                restart = True
            restart |= se.restart
            emit |= se.print or se.halt
            if se.verbose:
                self.verbose_active.add(k)
            if se.halt:
                flow["halt"] = se.id
            if se.ret:
                flow["return"] = se.id
            self.events.append(Event(self.t, se.id, se.label, float(f[k]), actions))
            self.log.append(f"t = {self.t:.9g}: Sensor_Event {se.id} fired (value {f[k]:.6g} "
                            f"{se.compare} {se.value:g}): {', '.join(actions) or 'log only'}")
        if restart or first_step is not None:
            if k_.forces_use_senval:
                self.yp = k_.consistent_yp(self.t, self.y)
            if self.solver is not None:       # at t0 the run starts the integrator later
                self.start(first_step)
            else:
                self.first_step0 = first_step
        if emit:
            self.output(self.t, self.y, self.yp)
        return flow

    # the command loop ------------------------------------------------------------------
    def run_command(self, cmd):
        self.dt = cmd.print_interval
        pending = collections.deque(_print_times(self.t, cmd.end_time, self.dt))
        start_steps = self.steps()
        while pending:
            # after a (re)start IDA sizes its first step from the distance to the requested
            # time; asking for the command's end keeps that choice independent of print times
            if self.onestep or self.fresh:
                sol = self.solver.step(cmd.end_time, method="onestep", tstop=cmd.end_time)
                self.fresh = False
            elif self.use_c and not self.verbose_active:
                # the C driver runs through all pending outputs until an event or the end
                sol, Y, YP, REQ, n = self.solver.outputs(list(pending), cmd.end_time)
                times = list(itertools.islice(pending, n))
                pending = collections.deque(itertools.islice(pending, n, None))
                if n:
                    self.ts.extend(times)
                    self.ys.extend(Y)
                    self.yps.extend(YP)
                    self.outs.extend(REQ)
                    self.bar.update(times[-1])
            else:
                sol = self.solver.step(pending[0], tstop=cmd.end_time)
            if sol.status == _TOO_MUCH_WORK or self.steps() - start_steps > self.opts["max_num_steps"]:
                raise _Stop(False, -100, f"more than max_num_steps = "
                            f"{self.opts['max_num_steps']} steps in one Simulate command "
                            f"(stopped at t = {float(sol.t):.6g})")
            self.ida_last = (int(sol.nfev), int(sol.njev))
            if not sol.success:
                raise _Stop(False, int(sol.status),
                            f"IDA failed at t = {float(sol.t):.6g}: {sol.message}")
            t = float(sol.t)
            # outputs up to t: the returned point itself, or IDA's interpolant
            while pending and pending[0] <= t:
                tp = pending.popleft()
                o = sol if tp == t else self.solver.step(tp)
                self.output(float(o.t), o.y, o.yp)
            if sol.status == _ROOT_RETURN:
                flow = self.on_root(sol)
                if "halt" in flow:
                    self.output(self.t, self.y, self.yp)
                    raise _Stop(True, 1, f"halted by Sensor_Event {flow['halt']} at "
                                f"t = {self.t:.9g}")
                if "return" in flow:
                    self.output(self.t, self.y, self.yp)
                    return
                if "dt" in flow:
                    self.dt = flow["dt"]
                    pending = collections.deque(_print_times(self.t, cmd.end_time, self.dt))
                if flow.get("restored"):
                    # outputs past the restored time are redone, on the schedule of that time
                    while self.ts and self.ts[-1] > self.t:
                        self.ts.pop()
                        self.ys.pop()
                        self.yps.pop()
                        self.outs.pop()
                    last = self.ts[-1] if self.ts else self.t
                    pending = collections.deque(
                        tp for tp in _print_times(last, cmd.end_time, self.dt))
                continue
            self.t, self.y, self.yp = t, np.array(sol.y), np.array(sol.yp)
            if self.onestep and t > self.steps_seen[-1][0]:
                self.remember_step()

    # statics ---------------------------------------------------------------------------
    def _after_static(self, t, y):
        """Continue from an equilibrium: velocities zero and, since the forces balance there,
        yp = 0 is consistent; IDA is restarted when a transient follows."""
        self.t, self.y = t, y
        self.yp = np.zeros_like(y)
        self.kernel.d.last_t = t
        self.need_start = True

    def run_static(self, cmd):
        y, res = statics.solve_static(self.model, cmd.end_time, self.y, self.model.static,
                                      self.opts["integr_tol"])
        self.statics.append(res)
        if not res.success:
            raise _Stop(False, -300, f"static analysis at t = {cmd.end_time:g}: {res.message}")
        self._after_static(cmd.end_time, y)
        self.output(self.t, self.y, self.yp)

    def run_quasi_static(self, cmd):
        params = self.model.static
        times = _print_times(self.t, cmd.end_time, cmd.print_interval)
        if params.method == "FIM_D":
            out, results = statics.quasi_static(self.model, self.t, self.y, times, params,
                                                   self.model.transient)
            self.statics.extend(results)
            for tp, y in out:
                self._after_static(tp, y)
                self.output(tp, self.y, self.yp)
            if not results[-1].success or len(out) < len(times) + 1:
                raise _Stop(False, -300, f"quasi-static analysis: {results[-1].message}")
            return
        prob = statics.StaticProblem(self.kernel)
        y = self.y
        for tp in [self.t] + list(times):
            y, res = statics.fim_s(prob, tp, y, params)
            self.statics.append(statics._finish(prob, tp, y, params, res))
            if not res.success:
                raise _Stop(False, -300, f"quasi-static analysis at t = {tp:g}: {res.message}")
            self._after_static(tp, y)
            self.output(tp, self.y, self.yp)

    def run(self):
        k = self.kernel
        k.reset_counters()
        k.armed[:] = 1
        k.senval[:] = 0.0
        t_start = time.perf_counter()
        self.t = 0.0
        self.y = k.layout.initial_state()
        k.d.last_t = self.t
        self.yp = k.consistent_yp(self.t, self.y)
        status, message, success = 0, "The simulation finished.", True
        try:
            flow = self.initial_events()
            self.output(self.t, self.y, self.yp)
            if "halt" in flow:
                raise _Stop(True, 1, f"halted by Sensor_Event {flow['halt']} at t = {self.t:.9g}")
            self.need_start = True
            self.setup_time = time.perf_counter() - t_start
            for cmd in self.model.commands:
                if cmd.analysis == "STATIC":
                    self.run_static(cmd)
                elif cmd.analysis == "QUASI-STATIC":
                    self.run_quasi_static(cmd)
                else:
                    if self.need_start:
                        self.start(getattr(self, "first_step0", None))
                        self.first_step0 = None
                        self.need_start = False
                    self.run_command(cmd)
        except _Stop as stop:
            success, status, message = stop.success, stop.status, stop.message
        finally:
            self.bar.close(self.t)
        if not hasattr(self, "setup_time"):
            self.setup_time = time.perf_counter() - t_start
        return success, status, message


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
    opts["backend"] = os.environ.get("PYSOLVER_BACKEND", "auto")
    opts.update(overrides)
    if opts["max_step_growth"] is not None and not opts["max_step_growth"] > 1:
        raise ValueError("max_step_growth must be > 1")
    if opts["nonlin_conv_coef"] is not None and not 0 < opts["nonlin_conv_coef"] < 1:
        raise ValueError("nonlin_conv_coef must be in (0, 1)")
    if opts["backend"] not in ("auto", "c", "sksundae"):
        raise ValueError(f"backend must be 'auto', 'c' or 'sksundae', not {opts['backend']!r}")
    if not opts["integr_tol"] > 0:
        raise ValueError("integr_tol must be > 0")
    if opts["linsolver"] not in ("auto", "dense", "sparse"):
        raise ValueError(f"linsolver must be 'auto', 'dense' or 'sparse', not {opts['linsolver']!r}")
    if opts["jacobian"] not in ("exact", "dq"):
        raise ValueError(f"jacobian must be 'exact' or 'dq', not {opts['jacobian']!r}")
    drv = _Driver(model, kernel, opts, progress)
    t_setup0 = time.perf_counter()
    success, status, message = drv.run()
    t_end = time.perf_counter()
    drv._retire_solver()
    counters = kernel.counters
    stats = {"steps": drv.steps(), "nres": counters["nres"], "njac": counters["njac"],
             "nfail": counters["nfail"], "outputs": len(drv.ts), "nroots": counters["nroots"],
             "nevents": len(drv.events), "nrearms": drv.nrearms,
             "nrestarts": max(drv.nstarts - 1, 0),
             "ida_nfev": drv.ida_done[0], "ida_njev": drv.ida_done[1],
             "netf": drv.ida_fail[0] if drv.use_c else None,
             "ncfn": drv.ida_fail[1] if drv.use_c else None,
             "growth_limited_at": drv.growth_limited_at}
    setup = (t_setup0 - t_start) + drv.setup_time
    timing = {"setup": setup, "integrate": (t_end - t_start) - setup, "total": t_end - t_start}
    opts["linsolver"] = ("band" if drv.use_c and drv.band else
                         "sparse" if drv.sparse else "dense")
    opts["backend"] = "c" if drv.use_c else "sksundae"
    meta = {"version": __version__, "deck": model.source.file, "sha256": model.source.sha256,
            "options": opts, "ny": kernel.ny, "stepping": "onestep" if drv.onestep else "normal",
            "static": dataclasses.asdict(model.static)}
    labels = {(r.id, k): n for r in model.requests.values() for k, n in enumerate(r.names) if n}
    res = Result(drv.ts, drv.ys.array(kernel.ny), drv.yps.array(kernel.ny),
                 drv.outs.array(len(kernel.channels)), kernel.channels, kernel.layout.names,
                 success, status, message, stats, timing, meta, labels)
    res.events = drv.events
    res.log = drv.log
    res.statics = drv.statics
    return res
