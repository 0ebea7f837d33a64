"""The LoadControl law (seed 002): the velocity that makes a body's load follow a target.

Every ``UpdateTime`` the controller reads the body's displacement x along its direction and
the load L on it, and sets the body's velocity there for the next interval:

- optional median filter of the last ``median_window`` loads (beyond the seed: contact loads
  carry fat-tailed noise);
- the load/displacement ratio by exponential smoothing,
  ``A_t = (lam L x + gam A_{t-1}) / (lam x^2 + gam)``, ``lam = 2 (1 - a) / (L^2 + (A_{t-1} x)^2)``,
  ``gam = a / A_{t-1}^2`` (a = ``smooth``);
- the error in displacement units and its integral and derivative:
  ``e_t = (1 - a) (L(t) - L) / A_t + a e_{t-1}``, ``Ie_t = (L(t) - L) / A_t + Ie_{t-1}``,
  ``e2_t = (1 - a) e_t + a e2_{t-1}``, ``De_t = (1 - a) / a (e_t - e2_t)`` (Brown's double
  smoothing);
- ``V_t = Kp e_t + Ki Ie_t + 0.25 Ki De_t``, clamped to ``MaxVelocity`` in magnitude; a clamped
  update does not accrue Ie.

The seed leaves some points open; decided here:

- **Before any load** A is unknown: the velocity stays the starting ``velocity`` and e, Ie, De
  stay 0. x is counted from the body's position at the last update without load (the onset
  of contact; the start if the body is loaded at once): measured from the start, a gap before
  contact would enter A = L / x and make it far too small, and the loop far too fast. The
  first update with L != 0 and x != 0 sets A = L / x.
- **No information**: with x = 0 the formula leaves A unchanged (lam x^2 = 0); with L = 0
  (contact lost) A is kept, where the formula would shrink it toward 0 and the error e toward
  infinity; an update that would give A = 0, a non-finite A, or flip A's sign (a load pulling
  the way the body pushes) keeps A_{t-1}.
- **Signs** need no convention: A carries the sign of L / x, so e = (L(t) - L) / A is the
  displacement still to go, in the direction's own sign.
- **Median filter** of fewer samples than the window at the start: the median of those there are.
"""
import dataclasses
import math
import statistics


def auto_gains(smooth, update_time, median_window=1):
    """Gains for ``Kp = auto`` / ``Ki = auto``: ``(kp, ki)`` in 1/time.

    In the seed's law e is the load error divided by A_t, a displacement; with A_t equal to the
    true stiffness the loop per update is x_{k+1} = x_k + dt V_k, whatever the stiffness, so the
    gains depend only on the smoothing a, the update interval dt and the median filter. With
    k = (1 - sqrt(a)) / (1 + sqrt(a)), the proportional gain at which the loop through e's
    smoothing is critically damped (a double pole at sqrt(a)), Kp dt = 1.6 k: a step in the
    target then overshoots by less than 2 % and settles to 2 % within 3 / (1 - sqrt(a)) updates
    (a = 0.95: 119), for every a in (0, 1). A median filter of w samples delays a step by w // 2
    updates, which that gain does not survive; Kp is then the largest gain up to 1.6 k whose
    step response on the delayed loop (simulated here) overshoots by at most 2 %. Ki = 0: the
    body's position integrates its velocity, so proportional action alone removes the error of
    a constant target; an integral term would only shorten a ramp's lag, at the price of
    overshoot and a slow tail once the ramp ends (tests/test_loadlaw.py checks the step on the
    closed loop).
    """
    k = (1.0 - math.sqrt(smooth)) / (1.0 + math.sqrt(smooth))
    delay = int(median_window) // 2
    if delay == 0:
        return 1.6 * k / update_time, 0.0
    lo, hi = 0.0, 1.6
    for _ in range(30):                 # bisection on the multiplier of k
        mid = 0.5 * (lo + hi)
        if step_overshoot(mid * k, smooth, delay) <= 0.02:
            lo = mid
        else:
            hi = mid
    return lo * k / update_time, 0.0


def step_overshoot(kp_dt, smooth, delay, n=None):
    """Overshoot of the unit step response of the P loop x += kp_dt e per update, e the seed's
    smoothing of the error measured `delay` updates late."""
    n = n or int(60 / (1.0 - math.sqrt(smooth))) + 20 * delay
    xs = [0.0] * (delay + 1)
    e = peak = 0.0
    for _ in range(n):
        e = (1.0 - smooth) * (1.0 - xs[-1 - delay]) + smooth * e
        xs.append(xs[-1] + kp_dt * e)
        peak = max(peak, xs[-1])
    return peak - 1.0


#: What :meth:`LoadLaw.update` logs per update, in this order.
FIELDS = ("time", "target", "measured", "filtered", "displacement", "A", "e", "Ie", "De",
          "velocity", "clamped")


@dataclasses.dataclass
class LawParams:
    """The task's parameters, with the seed's defaults."""
    velocity: float                  # starting velocity (its sign chooses the first direction)
    max_velocity: float = 1000.0
    kp: float = 0.1
    ki: float = 0.001
    smooth: float = 0.95
    median_window: int = 1           # samples; 1 = off

    def check(self):
        """Raise ValueError naming the first parameter out of its range."""
        if not 0.0 < self.smooth < 1.0:
            raise ValueError("smooth must be in (0, 1)")
        if not self.max_velocity > 0.0:
            raise ValueError("MaxVelocity must be > 0")
        if int(self.median_window) != self.median_window or self.median_window < 1:
            raise ValueError("median_window must be a whole number >= 1")
        for name in ("velocity", "kp", "ki"):
            if not math.isfinite(getattr(self, name)):
                raise ValueError(f"{name} must be a finite number")


class LoadLaw:
    """The controller's state between updates; :meth:`update` runs one update.

    Parameters
    ----------
    params : LawParams
        The task's parameters.
    """

    def __init__(self, params):
        params.check()
        self.p = params
        self.A = None
        self.e = self.ie = self.e2 = 0.0
        self.velocity = float(params.velocity)
        self.x_onset = 0.0
        self._loads = []
        self.log = []

    def update(self, t, x, load, target):
        """Run one update at time t with displacement x (from the start), measured load and
        target load L(t); return the velocity for the next interval and append a row of
        :data:`FIELDS` to ``self.log`` (its displacement counted from the onset of load)."""
        p, a = self.p, self.p.smooth
        self._loads = (self._loads + [float(load)])[-int(p.median_window):]
        L = statistics.median(self._loads) if p.median_window > 1 else float(load)
        if self.A is None and L == 0.0:
            self.x_onset = x              # displacement counts from the onset of load
        x = x - self.x_onset
        self.A = self._ratio(x, L)
        de = 0.0
        clamped = False
        if self.A is not None:
            err = (target - L) / self.A
            self.e = (1.0 - a) * err + a * self.e
            ie = err + self.ie
            self.e2 = (1.0 - a) * self.e + a * self.e2
            de = (1.0 - a) / a * (self.e - self.e2)
            v = p.kp * self.e + p.ki * ie + 0.25 * p.ki * de
            clamped = abs(v) > p.max_velocity
            if clamped:
                v = math.copysign(p.max_velocity, v)
            else:
                self.ie = ie
            self.velocity = v
        self.log.append((t, target, float(load), L, x, math.nan if self.A is None else self.A,
                         self.e, self.ie, de, self.velocity, clamped))
        return self.velocity

    def _ratio(self, x, L):
        """A_t from A_{t-1}, x and the filtered load (the decisions in the module's text)."""
        prev, a = self.A, self.p.smooth
        if prev is None:
            return L / x if L != 0.0 and x != 0.0 else None
        if L == 0.0 or x == 0.0:
            return prev
        # products, not powers: an overflow is inf (rejected below), not an OverflowError
        denom, pp = L * L + (prev * x) * (prev * x), prev * prev
        if denom == 0.0 or pp == 0.0:            # underflow: no information, A stays
            return prev
        lam, gam = 2.0 * (1.0 - a) / denom, a / pp
        den = lam * x * x + gam
        if den == 0.0 or not math.isfinite(den):
            return prev
        new = (lam * L * x + gam * prev) / den
        if not math.isfinite(new) or new == 0.0 or (new > 0) != (prev > 0):
            return prev
        return new
