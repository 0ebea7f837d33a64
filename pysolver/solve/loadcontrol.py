"""The LoadControl task as an actor of the transient driver (seed 002).

Every ``update_time`` the task reads its body's displacement along the axis (from where it
started), the load and the target L(t); the law (:mod:`.loadlaw`) gives the velocity for the
next interval. The load is the force the body puts on its drive along the axis: minus the
reaction of the velocity motion that drives it (``-res.motion(-id)``). At constant velocity it
equals the sum of the other forces on the body along the axis, so a body pressed down (-z)
into a material carries a positive load (the material pushes it up), and a target is given in
that sign. The new velocity is a jump: the state is made consistent at once (the
body's velocity takes the new value, accelerations and the reaction are solved for again) and
IDA is restarted there, so no impulse enters the logged load.
"""
import copy
import math

from ..build.consistent import reactions
from .actors import Actor, Flow
from .loadlaw import FIELDS, LawParams, LoadLaw, auto_gains


class NonFinite(Exception):
    """A LoadControl task's load, target or velocity is not finite."""


class LoadControlTask(Actor):
    """One LoadControl task (k-th in id order) of a model, on a compiled kernel."""

    def __init__(self, kernel, lc, k):
        self.kernel, self.lc, self.k = kernel, lc, k
        lay = kernel.layout
        self.value = len(kernel.evaluate_tapes) + k          # its slot in kernel.senval
        self.q = lay.qadr[lay.index[lc.body]] + lc.direction
        self.u = lay.uadr[lay.index[lc.body]] + lc.direction
        self.lam = lay.motion_ids.index(lc.motion)
        auto = auto_gains(lc.smooth, lc.update_time, lc.median_window)
        kp = auto[0] if lc.kp == "auto" else lc.kp
        ki = auto[1] if lc.ki == "auto" else lc.ki
        self.law = LoadLaw(LawParams(lc.velocity, lc.max_velocity, kp, ki, lc.smooth,
                                     lc.median_window))
        self.t0 = self.x0 = None
        self.n = 0

    def start(self, run):
        """The starting velocity, made consistent with the state."""
        self.t0, self.x0 = run.t, float(run.y[self.q])
        self.n = 1
        self.kernel.senval[self.value] = self.law.velocity
        run.yp = self.kernel.consistent_yp(run.t, run.y)
        return Flow(restart=True)

    def next_time(self, t):
        return self.t0 + self.n * self.lc.update_time if self.t0 is not None else float("inf")

    def on_time(self, run):
        k = self.kernel
        t = run.t
        if self.lc.load == "CONTACT":
            load = float(k.penalty_loads(t, run.y, run.yp)[self.u])
        else:
            load = -float(reactions(k, t, run.y, run.yp)[self.lam])
        target = k.eval_tape(k.control_tapes[self.k], t, run.y, run.yp)
        for what, value in (("measured load", load), ("target load", target)):
            if not math.isfinite(value):
                raise NonFinite(f"LoadControl {self.lc.id}: the {what} is {value} at t = "
                                f"{t:.9g}")
        v = self.law.update(t, float(run.y[self.q]) - self.x0, load, target)
        if not math.isfinite(v):
            raise NonFinite(f"LoadControl {self.lc.id}: the control law's velocity is {v} at "
                            f"t = {t:.9g} (load {load:g}, target {target:g})")
        k.senval[self.value] = v
        run.yp = k.consistent_yp(t, run.y)
        self.n += 1
        return Flow(restart=True)

    def notes(self):
        """Log lines on the run as a whole: a task whose velocity was clamped at MaxVelocity in
        every update never controlled the load."""
        log = self.law.log
        if log and all(row[FIELDS.index("clamped")] for row in log):
            return [f"LoadControl {self.lc.id}: the velocity was clamped at MaxVelocity = "
                    f"{self.lc.max_velocity:g} in all {len(log)} updates, so the load never "
                    "followed its target (raise MaxVelocity, or check direction, material and "
                    "the sign of Load_Function)"]
        return []

    def records(self):
        """The per-update log as {field: list}, fields as loadlaw.FIELDS."""
        cols = list(zip(*self.law.log)) if self.law.log else [()] * len(FIELDS)
        return {name: list(col) for name, col in zip(FIELDS, cols)}

    def save(self):
        return copy.deepcopy(self.law), self.n, float(self.kernel.senval[self.value])

    def restore(self, snapshot, t):
        law, self.n, v = snapshot
        self.law = copy.deepcopy(law)
        self.kernel.senval[self.value] = v
