"""Sensor_Event as an actor: fire at roots of the sensors' expressions, re-arm, act.

The rules (when a sensor's condition holds, when a fired sensor re-arms, and the root
functions whose crossings IDA reports) are the kernel's, in C (``ps_roots`` and
``ps_sensor_status``); this module decides what happens at an instant:

- **Arming.** Every sensor starts armed; one whose condition holds at the start fires there.
  A fired sensor watches for its re-arm condition (the value band ``error_tol`` away).
- **Event iteration.** Actions may change what sensors see (SENVAL, restarts), so at one
  instant sensors re-arm and fire until nothing changes; each fires and re-arms at most once
  per instant, which bounds the loop. Sensors act in id order.
- **Restore-and-shrink** (seed 003, Comment 3). A ``zero_crossing`` sensor seen firing for the
  first time sends the run back to the last converged step of the current Simulate command,
  with h_max and h_min scaled by ``zero_crossing``; when it fires again the bounds come back.
- **Chatter guard.** Over CHATTER_LIMIT events within CHATTER_WINDOW * max(1, |t|) end the run.

Sensors whose actions need no Python (:func:`decided_in_c`) are decided by the same rules in C
on the batched path (csrc/events.c, and csrc/ida.c's ps_ida_controlled for restore-and-shrink;
:class:`CSensors` hands its event records over); tests/test_fast.py holds the two to the same
rows, events, log and counters.
"""
import collections
import dataclasses

import numpy as np

from .actors import Actor, Flow

#: Events (firings and re-armings) allowed within CHATTER_WINDOW * max(1, |t|) of time before
#: the run stops as chattering (Zeno behaviour, or a sensor that re-fires at the same instant).
CHATTER_LIMIT = 100
CHATTER_WINDOW = 1e-9

#: Events the batched path's C loop records before it returns to Python to hand them over.
EVENT_CAP = 1024


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


class Chatter(Exception):
    """Sensor events keep recurring without time advancing."""


class Sensors(Actor):
    """Every Sensor_Event of a scene; owns the kernel's root functions 0 .. nsensor - 1."""

    def __init__(self, model, kernel, log):
        self.kernel, self.log = kernel, log
        self.sensors = [model.sensors[i] for i in kernel.sensor_ids]
        self.nroots = len(self.sensors)
        self.needs_restore = any(s.zero_crossing for s in self.sensors)
        self.eidx = {eid: i for i, eid in enumerate(kernel.evaluate_ids)}
        self.verbose_active = set()
        self.zc_pending = set()
        self.saved_bounds = None           # (hmax, hmin) while a zero-crossing search runs
        self.nrearms = 0
        self.recent = collections.deque(maxlen=CHATTER_LIMIT)
        kernel.armed[:] = 1
        kernel.senval[:] = 0.0

    @property
    def watching(self):
        """True while a verbose sensor must see every output row."""
        return bool(self.verbose_active)

    @property
    def instants(self):
        """Sensors act at roots of their expressions, which the batched path decides in C for
        sensors whose actions need no Python (:func:`decided_in_c`); any other sensor makes a
        run leave it."""
        return not all(decided_in_c(se, self.kernel) for se in self.sensors)

    # hooks ---------------------------------------------------------------------------
    def start(self, run):
        """Sensors whose condition already holds at the start fire at the start."""
        if not self.sensors:
            return Flow()
        f, _, _ = self.kernel.sensor_status(run.t, run.y, run.yp)
        for k in range(len(self.sensors)):
            self._arm(k, f[k])
        return self._settle(run, set(), set())

    def on_roots(self, run, found):
        crossed = [k for k in range(len(self.sensors)) if found[k] != 0]
        armed = self.kernel.armed
        fired = [k for k in crossed if armed[k]]
        rearmed = [k for k in crossed if not armed[k]]
        self._check_chatter(run.t)
        # restore-and-shrink for zero_crossing sensors seen firing for the first time
        search = [k for k in fired if self.sensors[k].zero_crossing and k not in self.zc_pending]
        if search and run.last_converged_time() < run.t:
            return self._restore_and_shrink(run, search)
        # IDA saw these crossings: take them as they are, then settle the rest
        f, _, _ = self.kernel.sensor_status(run.t, run.y, run.yp)
        for k in rearmed:
            self._rearm(k, f[k])
        flow = self._fire(run, fired, f) if fired else Flow()
        return flow.update(self._settle(run, set(fired), set(rearmed)))

    def on_output(self, t, y, yp):
        if not self.verbose_active:
            return
        f, _, _ = self.kernel.sensor_status(t, y, yp)
        for k in sorted(self.verbose_active):
            se = self.sensors[k]
            self.log.append(f"t = {t:.9g}: Sensor_Event {se.id} active "
                                f"(value {f[k]:.6g} {se.compare} {se.value:g})")

    def save(self):
        k = self.kernel
        return (k.armed.copy(), k.senval.copy(), k.sensor_side.copy(),
                frozenset(self.verbose_active), self.nrearms)

    def restore(self, snapshot, t):
        armed, senval, side, verbose, nrearms = snapshot
        k = self.kernel
        k.armed[:], k.senval[:], k.sensor_side[:] = armed, senval, side
        self.verbose_active, self.nrearms = set(verbose), nrearms

    # the rules of an instant -----------------------------------------------------------
    def _arm(self, k, f):
        """Arm sensor k; an EQ sensor remembers from which side it approaches its value."""
        self.kernel.armed[k] = 1
        self.kernel.sensor_side[k] = 1.0 if f >= self.sensors[k].value else -1.0

    def _rearm(self, k, f):
        self._arm(k, f)
        self.nrearms += 1
        self.verbose_active.discard(k)

    def _settle(self, run, fired, rearmed):
        """Event iteration at one instant (see the module docstring)."""
        flow = Flow()
        armed = self.kernel.armed
        while True:
            f, holds, rearms = self.kernel.sensor_status(run.t, run.y, run.yp)
            up = [k for k in range(len(self.sensors))
                  if not armed[k] and k not in rearmed and rearms[k]]
            for k in up:
                self._rearm(k, f[k])
                rearmed.add(k)
                self._check_chatter(run.t)
            now = [k for k in range(len(self.sensors)) if armed[k] and k not in fired and holds[k]]
            if now:
                fired.update(now)
                self._check_chatter(run.t)
                flow.update(self._fire(run, now, f))
            if not up and not now:
                return flow

    def _check_chatter(self, t):
        self.recent.append(t)
        if (len(self.recent) == CHATTER_LIMIT
                and self.recent[-1] - self.recent[0] <= CHATTER_WINDOW * max(1.0, abs(t))):
            raise Chatter(f"sensor events chatter: {CHATTER_LIMIT} events between "
                          f"t = {self.recent[0]:.12g} and {self.recent[-1]:.12g}; the sensors "
                          "keep re-firing without time advancing (give them an error_tol band)")

    def _restore_and_shrink(self, run, search):
        """Back to the last converged step before the event, then approach it again with h_max
        and h_min scaled by zero_crossing. The "current h_max" when h_max is unbounded is the
        size of the last step completed before the event."""
        current = run.restore_last_step()
        zc = min(self.sensors[k].zero_crossing for k in search)
        self.zc_pending.update(search)
        if self.saved_bounds is None:
            self.saved_bounds = (run.hmax, run.hmin)
        run.hmax, run.hmin = zc * current, zc * run.hmin
        for k in search:
            run.log.append(f"t = {run.t:.9g}: Sensor_Event {self.sensors[k].id} zero crossing: "
                           f"back to the last converged step, hmax {run.hmax:.3g}")
        return Flow(restart=True, restored=True)

    def _fire(self, run, fired, f):
        """Run the actions of the sensors that fired at the current time, in id order."""
        k_ = self.kernel
        flow = Flow()
        for k in fired:
            se = self.sensors[k]
            k_.armed[k] = 0
            actions = se.actions()
            if k in self.zc_pending:
                self.zc_pending.discard(k)
                if not self.zc_pending and self.saved_bounds is not None:
                    run.hmax, run.hmin = self.saved_bounds
                    self.saved_bounds = None
                    flow.restart = True
            if se.evaluate_id is not None:
                idx = self.eidx[se.evaluate_id]
                k_.senval[idx] = k_.eval_tape(k_.evaluate_tapes[idx], run.t, run.y, run.yp)
                flow.restart |= k_.forces_use_senval
            if se.dt is not None:
                run.set_print_interval(se.dt, f"Sensor_Event {se.id}'s dt = {se.dt:g}")
            if se.stepsize is not None:
                flow.update(Flow(first_step=se.stepsize))
            if se.hmax is not None:
                run.hmax = se.hmax
                if self.saved_bounds is not None:
                    self.saved_bounds = (se.hmax, self.saved_bounds[1])
                flow.restart = True
            flow.restart |= se.restart
            flow.emit |= se.print or se.halt
            if se.verbose:
                self.verbose_active.add(k)
            if se.halt:
                flow.halt = f"Sensor_Event {se.id}"
            if se.ret:
                flow.ret = f"Sensor_Event {se.id}"
            run.events.append(Event(run.t, se.id, se.label, float(f[k]), actions))
            run.log.append(f"t = {run.t:.9g}: Sensor_Event {se.id} fired (value {f[k]:.6g} "
                           f"{se.compare} {se.value:g}): {', '.join(actions) or 'log only'}")
        if (flow.restart or flow.first_step is not None) and k_.forces_use_senval:
            run.yp = _consistent(run.model, k_, run.t, run.y)
        return flow



def decided_in_c(sensor, kernel):
    """Whether a sensor's instants can be decided in C (csrc/events.c, on the batched path):
    every action, zero_crossing's restore-and-shrink included. Where forces read SENVAL, an
    action that restarts makes the state consistent again (:func:`_consistent`, the same C on
    both paths); only a scene whose whole restart would pass the sparse restart's size limit
    (pysolver.build.restart.SPARSE_LIMIT) restarts in Python, on the general loop."""
    restarts = (sensor.evaluate_id is not None or sensor.restart or sensor.hmax is not None
                or sensor.stepsize is not None or sensor.zero_crossing is not None)
    return not (kernel.forces_use_senval and restarts and not dense_yp(kernel)
                and whole_restart(kernel) is None)


def whole_restart(kernel):
    """The kernel's C restart of the whole state (positions, rates, accelerations and
    reactions: pysolver.build.restart), or None past its size limit."""
    from ..build.restart import Restart
    return Restart.of(kernel)


def _consistent(model, kernel, t, y):
    """yp (and y, in place) consistent again after sensors restarted where forces read SENVAL:
    yp alone in a dense scene without motions, joints or tracked angles
    (ps_consistent_yp: NaN when it fails, as kernel.consistent_yp); else the whole restart in
    C (ps_restart_consistent), as the batched path's C loop does, or in Python past its size
    limit. Raises NonFinite (status -700) when the state cannot be made consistent."""
    from ..build.bindings import ffi, lib
    from ..build.kernel import UserFailure
    from .loadcontrol import Interrupted, NonFinite
    rs = None if dense_yp(kernel) else whole_restart(kernel)
    try:
        if rs is None:
            return kernel.consistent_yp(t, y)
        yp = np.zeros(kernel.ny)
        rc = lib.ps_restart_consistent(kernel.m, kernel.d, rs.r, t,
                                       ffi.from_buffer("double[]", y),
                                       ffi.from_buffer("double[]", yp))
        if rc != lib.PS_OK and kernel.d.user_error:
            raise UserFailure(kernel.message)
    except UserFailure:
        if lib.ps_interrupted():          # Ctrl-C: the driver words it (status -600)
            raise Interrupted() from None
        raise
    if rc != lib.PS_OK:
        raise NonFinite(restart_failure(model, kernel, rc, t))
    return yp


def restart_failure(model, kernel, code, t):
    """The message of a sensors' restart at t that could not make the state consistent
    (ps_restart_consistent's `code`)."""
    from .nonfinite import restart_reason
    return (f"a sensor's restart at t = {t:.9g} cannot make the state consistent: "
            f"{restart_reason(model, kernel, code)}")


def dense_yp(kernel):
    """Whether kernel.consistent_yp is C's ps_consistent_yp (no motions, joints or tracked
    angles; a dense scene)."""
    from ..options import SPARSE_THRESHOLD
    lay = kernel.layout
    return not (lay.lam or lay.turns) and kernel.ny < SPARSE_THRESHOLD
