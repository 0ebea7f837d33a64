"""The LoadControl task as an actor of the transient driver (seed 002).

Every ``update_time`` the task reads its body's displacement along the axis (from where it
started), the load and the target L(t); the law (:mod:`.loadlaw`, run in C as
``ps_law_update``) gives the velocity for the next interval. The load is the force the body
puts on its drive along the axis: minus the reaction of the velocity motion that drives it
(``-res.motion(-id)``). At constant velocity it equals the sum of the other forces on the body
along the axis, so a body pressed down (-z) into a material carries a positive load (the
material pushes it up), and a target is given in that sign. The new velocity is a jump: the
state is made consistent at once (the body's velocity takes the new value, accelerations and
the reaction are solved for again) and IDA is restarted there, so no impulse enters the logged
load.

An update is one C call (``ps_control_update``, csrc/control.c): the general driver calls it
through :meth:`LoadControlTask.on_time`, the batched path (:mod:`.fast`) from its C loop, so
the two give the same runs to the bit; a sparse scene restarts on the kernel's sparse pattern
(:mod:`pysolver.build.restart`). A sparse scene whose restart would pass
``restart.SPARSE_LIMIT`` measures and restarts in Python (``consistent.reactions`` and
``consistent_yp``) around the same C law, on the general driver.
"""
import math

import numpy as np

from ..build.bindings import ffi, lib
from ..build.consistent import reactions
from ..build.restart import Restart
from . import nonfinite
from .actors import Actor, Flow
from .loadlaw import FIELDS, LawParams, auto_gains


class NonFinite(Exception):
    """A LoadControl task's load, target or velocity is not finite, or the state cannot be made
    consistent with its new velocity."""


class Interrupted(Exception):
    """Ctrl-C came during a LoadControl update."""


class LoadControlTask(Actor):
    """One LoadControl task (k-th in id order) of a model, on its compiled kernel."""

    def __init__(self, model, kernel, lc, k):
        self.model, self.kernel, self.lc, self.k = model, kernel, lc, k
        end = max([cmd.end_time or 0.0 for cmd in model.commands] + [0.0])
        lay = kernel.layout
        auto = auto_gains(lc.smooth, lc.update_time, lc.median_window)
        params = LawParams(lc.velocity, lc.max_velocity, auto[0] if lc.kp == "auto" else lc.kp,
                           auto[1] if lc.ki == "auto" else lc.ki, lc.smooth, lc.median_window)
        params.check()
        self.restart = Restart.of(kernel)
        c = self.c = ffi.new("psControl *")
        w = c.law
        w.velocity0, w.max_velocity, w.kp, w.ki = (float(params.velocity), params.max_velocity,
                                                    params.kp, params.ki)
        w.smooth, w.window = params.smooth, int(params.median_window)
        self.loads, sorted_ = np.zeros(w.window), np.zeros(w.window)
        self.log = np.zeros((int(end / lc.update_time) + 3, len(FIELDS)))
        w.loads = ffi.cast("double *", ffi.from_buffer(self.loads))
        w.sorted = ffi.cast("double *", ffi.from_buffer(sorted_))
        self._keep = sorted_
        c.log, c.cap = ffi.cast("double *", ffi.from_buffer(self.log)), len(self.log)
        c.contact = int(lc.load == "CONTACT")
        c.q = lay.qadr[lay.index[lc.body]] + lc.direction
        c.u = lay.uadr[lay.index[lc.body]] + lc.direction
        c.lam = lay.motion_ids.index(lc.motion)
        c.value = len(kernel.evaluate_tapes) + k          # its slot in kernel.senval
        c.tape, c.slot = kernel.control_tapes[k]
        c.dt = lc.update_time
        c.t0 = math.inf                                   # not started: no next update
        self.row = np.zeros(len(FIELDS))

    @property
    def instants(self):
        """Its update times are its own; the batched path runs them in C (unless the scene
        restarts in Python)."""
        return self.restart is None

    # hooks -----------------------------------------------------------------------------
    def start(self, run):
        """The starting velocity, made consistent with the state."""
        c, k = self.c, self.kernel
        if self.restart is not None:
            self._check(lib.ps_control_start(k.m, k.d, self.restart.r, c, run.t,
                                             ffi.from_buffer("double[]", run.y),
                                             ffi.from_buffer("double[]", run.yp)), run.t)
            return Flow(restart=True)
        c.t0, c.x0, c.n, c.nlog = run.t, float(run.y[c.q]), 1, 0
        lib.ps_law_reset(ffi.addressof(c.law))
        k.senval[c.value] = c.law.velocity
        run.yp = k.consistent_yp(run.t, run.y)
        return Flow(restart=True)

    def next_time(self, t):
        return lib.ps_control_next(self.c)

    def on_time(self, run):
        c, k, t = self.c, self.kernel, run.t
        if self.restart is not None:
            self._check(lib.ps_control_update(k.m, k.d, self.restart.r, c, t,
                                              ffi.from_buffer("double[]", run.y),
                                              ffi.from_buffer("double[]", run.yp)), t)
            return Flow(restart=True)
        # a scene past the sparse restart's limit: the load and the restart in Python, the
        # law in C
        if c.contact:
            load = float(k.penalty_loads(t, run.y, run.yp)[c.u])
        else:
            load = -float(reactions(k, t, run.y, run.yp)[c.lam])
        target = k.eval_tape((c.tape, c.slot), t, run.y, run.yp)
        c.bad[0], c.bad[1] = load, target
        self._check(lib.PS_CTRL_LOAD if not math.isfinite(load) else
                    lib.PS_CTRL_TARGET if not math.isfinite(target) else
                    lib.PS_CTRL_LOG if c.nlog >= c.cap else lib.PS_OK, t)
        v = lib.ps_law_update(ffi.addressof(c.law), t, float(run.y[c.q]) - c.x0, load, target,
                              ffi.cast("double *", ffi.from_buffer(self.log[c.nlog])))
        c.nlog += 1
        c.bad[2] = v
        self._check(lib.PS_OK if math.isfinite(v) else lib.PS_CTRL_VELOCITY, t)
        k.senval[c.value] = v
        run.yp = k.consistent_yp(t, run.y)
        c.n += 1
        return Flow(restart=True)

    def failure(self, code, t):
        """The message of an update at t that returned `code` (a PS_CTRL_* or kernel code)."""
        c, lid = self.c, self.lc.id
        load, target, v = c.bad[0], c.bad[1], c.bad[2]
        if code == lib.PS_CTRL_LOAD:
            return f"LoadControl {lid}: the measured load is {load} at t = {t:.9g}"
        if code == lib.PS_CTRL_TARGET:
            return f"LoadControl {lid}: the target load is {target} at t = {t:.9g}"
        if code == lib.PS_CTRL_VELOCITY:
            return (f"LoadControl {lid}: the control law's velocity is {v} at t = {t:.9g} "
                    f"(load {load:g}, target {target:g})")
        if code == lib.PS_CTRL_LOG:
            return f"LoadControl {lid}: more updates than the run has room for at t = {t:.9g}"
        why = nonfinite.restart_reason(self.model, self.kernel, code)
        return (f"LoadControl {lid}: the state cannot be made consistent with the new "
                f"velocity at t = {t:.9g}: {why}")

    def _check(self, code, t):
        if code != lib.PS_OK:
            self.fail(code, t)

    def reset(self):
        """Before a run: no updates logged, none scheduled (start() schedules them)."""
        self.c.nlog, self.c.t0 = 0, math.inf

    def fail(self, code, t):
        """Raise the error of an update at t that returned `code` (not PS_OK)."""
        if lib.ps_interrupted():                # Ctrl-C: the driver words it
            raise Interrupted()
        if code == lib.PS_ERR_NONFINITE and self.kernel.d.user_error:
            from ..build.kernel import UserFailure
            raise UserFailure(self.kernel.message)
        raise NonFinite(self.failure(code, t))

    # results ---------------------------------------------------------------------------
    def notes(self):
        """Log lines on the run as a whole: a task whose velocity was clamped at MaxVelocity in
        every update never controlled the load."""
        n = self.c.nlog
        if n and np.all(self.log[:n, FIELDS.index("clamped")] != 0.0):
            return [f"LoadControl {self.lc.id}: the velocity was clamped at MaxVelocity = "
                    f"{self.lc.max_velocity:g} in all {n} updates, so the load never "
                    "followed its target (raise MaxVelocity, or check direction, material and "
                    "the sign of Load_Function)"]
        return []

    def records(self):
        """The per-update log as {field: list}, fields as loadlaw.FIELDS."""
        rows = self.log[:self.c.nlog]
        out = {name: rows[:, i].tolist() for i, name in enumerate(FIELDS)}
        out["clamped"] = [bool(v) for v in out["clamped"]]
        return out

    def save(self):
        return (bytes(ffi.buffer(self.c)), self.loads.copy(),
                float(self.kernel.senval[self.c.value]))

    def restore(self, snapshot, t):
        state, loads, v = snapshot
        ffi.buffer(self.c)[:] = state
        self.loads[:] = loads
        self.kernel.senval[self.c.value] = v
