"""Actors that act at their own times (the protocol LoadControl will use): the driver stops IDA
exactly at their instants, they see the exact state there, and a change they make to the state
takes effect through a restart. Checked on a falling ball against its closed form."""
import math

import numpy as np
import pytest

import pysolver
from pysolver.solve import run_model
from pysolver.solve.actors import Actor, Flow

from scenes import G, ball

Z, VZ = 2, 5          # the ball's height and vertical velocity in the state


class Periodic(Actor):
    """Acts every `period` from `first` on; records (t, z, vz) and may set vz."""

    def __init__(self, period, first=None, set_vz=None):
        self.period, self.k0 = period, 1 if first is None else 0
        self.k = self.k0
        self.first = first if first is not None else period
        self.set_vz = set_vz
        self.seen = []

    def next_time(self, t):
        n = self.k - self.k0
        return self.first + n * self.period if n else self.first

    def on_time(self, run):
        self.seen.append((run.t, run.y[Z], run.y[VZ]))
        self.k += 1
        if self.set_vz is None:
            return Flow()
        run.y = run.y.copy()
        run.y[VZ] = self.set_vz
        run.yp = run.kernel.consistent_yp(run.t, run.y)
        return Flow(restart=True)


BACKENDS = ["c", "sksundae"]


@pytest.mark.parametrize("backend", BACKENDS)
def test_timed_actor_acts_at_its_instants_with_the_exact_state(backend):
    model = pysolver.loads(ball("", z0=10.0, end=2.0, dt=0.1))
    actor = Periodic(0.13)
    res = run_model(model, progress=False, actors=[actor],
                    overrides={"backend": backend})
    assert res.success, res.message
    times = np.array([s[0] for s in actor.seen])
    # exactly the instants the actor named (0.13 .. 1.95)
    np.testing.assert_array_equal(times, [0.13 + 0.13 * k for k in range(15)])
    z = np.array([s[1] for s in actor.seen])
    np.testing.assert_allclose(z, 10 - 0.5 * G * times ** 2, atol=1e-8)
    # the print grid is untouched and still exact
    np.testing.assert_allclose(res.t, np.linspace(0, 2, 21), atol=1e-12)
    np.testing.assert_allclose(res.request(1)[:, 0], 10 - 0.5 * G * res.t ** 2, atol=1e-8)


@pytest.mark.parametrize("backend", BACKENDS)
def test_timed_actor_changes_the_state_through_a_restart(backend):
    """At t = 0.5 the actor stops the ball (vz = 0): afterwards z = z(0.5) - g (t - 0.5)^2 / 2."""
    model = pysolver.loads(ball("", z0=10.0, end=1.5, dt=0.1))
    actor = Periodic(math.inf, first=0.5, set_vz=0.0)
    res = run_model(model, progress=False, actors=[actor],
                    overrides={"backend": backend})
    assert res.success and res.stats["nrestarts"] == 1
    assert [s[0] for s in actor.seen] == [0.5]
    t = res.t
    z_stop = 10 - 0.5 * G * 0.25
    expected = np.where(t <= 0.5, 10 - 0.5 * G * t ** 2, z_stop - 0.5 * G * (t - 0.5) ** 2)
    np.testing.assert_allclose(res.request(1)[:, 0], expected, atol=1e-8)


def test_actions_at_the_start_and_at_the_end_are_taken():
    """An action due at t = 0 acts before IDA starts (a kick up: z = 10 + 2 t - g t^2 / 2);
    one due at the command's end time acts there."""
    model = pysolver.loads(ball("", z0=10.0, end=1.0, dt=0.25))
    kick = Periodic(math.inf, first=0.0, set_vz=2.0)
    ends = Periodic(1.0)
    res = run_model(model, progress=False, actors=[kick, ends])
    assert res.success
    assert [s[0] for s in kick.seen] == [0.0] and [s[0] for s in ends.seen] == [1.0]
    np.testing.assert_allclose(res.request(1)[:, 0], 10 + 2 * res.t - 0.5 * G * res.t ** 2,
                               atol=1e-8)
    assert ends.seen[0][1] == pytest.approx(10 + 2 - 0.5 * G, abs=1e-8)


def test_actors_are_not_run_options():
    model = pysolver.loads(ball(""))
    with pytest.raises(TypeError, match="unknown run option 'actors'"):
        model.run(actors=[Periodic(0.1)])


def test_sensor_firing_at_the_start_with_a_dt_action_runs():
    """A sensor whose condition holds at t = 0 fires there; its dt action before the first
    command keeps the command's print interval (the rows are every 0.25 s)."""
    deck = ball('<Sensor_Event id="1" expr="DZ(10)" compare="LT" value="50" dt="0.01"/>',
                z0=10.0, end=1.0, dt=0.25)
    res = pysolver.loads(deck).run()
    assert res.success and [e.time for e in res.events] == [0.0]
    np.testing.assert_allclose(res.t, [0, 0.25, 0.5, 0.75, 1.0], atol=1e-12)
