"""Held states (pysolver/build/held.py, ps_ida_hold): a point body's coordinate that nothing
moves stays at its start value, and IDA integrates the other states only. Checked: which axes a
scene holds, the same answers and steps as integrating every state, the held entries exactly
constant, a start that is not at rest (a sweep case, an actor) integrating every state, and
the run ending when a held state's equation does not hold."""
import math

import numpy as np
import pytest

import pysolver
from pysolver.build.bindings import ffi, lib
from pysolver.build.held import held_axes
from pysolver.solve import cida, run_model
from pysolver.solve.actors import Actor, Flow

from scenes import DECKS, G, ball

pytestmark = pytest.mark.skipif(not cida.available(),
                                reason="the scikit-sundae wheel ships no SUNDIALS libraries")

SEED3 = (DECKS / "particle_between_lines.xml").read_text()
LINE1 = 'expr="1+dx(10)-dz(10)"'


def _seed3(old=None, new=None):
    text = SEED3 if old is None else SEED3.replace(old, new)
    assert old is None or text != SEED3
    return pysolver.loads(text)


@pytest.mark.parametrize("old, new, held", [
    (None, None, {2: (1,)}),                                         # the x-z plane
    (LINE1, 'expr="1+dx(10)-dz(10)+0*dy(10)"', {}),                  # a penalty reads y
    (LINE1, 'expr="1+dx(10)-dz(10)+0*VARVAL(5)"', {}),               # through a variable
    (LINE1, 'expr="1+dx(10)-dz(10)+0*DM(10)"', {}),                  # a magnitude: all axes
    (LINE1, 'expr="1+dx(10)-dz(10)+0*DX(10,1,1)"', {}),             # in marker 1's axes
    (LINE1, 'expr="1+dx(10)-dz(10)+0*DY(1)"', {2: (1,)}),            # y of the ground
    ('grav_y="0"', 'grav_y="-1"', {}),                               # gravity along y
    ('mass="1.0"', 'mass="1.0" v_ic_y="2"', {}),                     # a start velocity along y
    ('mass="1.0"', 'mass="1.0" v_ic_x="0"', {2: (1,)}),
])
def test_which_axes_are_held(old, new, held):
    variable = '<Reference_Variable id="5" type="EXPRESSION" expr="DY(10)"/>'
    text = SEED3.replace("<Force_Gravity", variable + "\n    <Force_Gravity")
    if old is not None:
        assert old in text
        text = text.replace(old, new)
    assert held_axes(pysolver.loads(text)) == held


def test_other_elements_keep_every_state():
    """A scene with any element that may push a point body (here LoadControl on a penalty
    deck, a vector force) holds nothing; a ball falling along z holds x and y."""
    for deck in ("loadcontrol_indenter.xml", "driven_indenter.xml"):
        assert held_axes(pysolver.load(DECKS / deck)) == {}
    assert held_axes(pysolver.loads(ball(""))) == {2: (0, 1)}


def test_held_run_is_the_full_run(monkeypatch):
    """Seed example 3 holds y and vy (4 of 6 states in IDA): its steps and answers are those
    of integrating all six to rounding (IDA's norms weigh the live entries so), y and vy are
    exactly zero in every row, and the summary says what is held."""
    model = _seed3()
    model.compile()
    assert model.compile().kernel.layout.held == (1, 4)
    assert model.summary().splitlines()[-1] == "states: 6 (IDA holds 2 at rest: body 2's y)"
    monkeypatch.setenv("PYSOLVER_HELD", "off")
    full_model = _seed3()
    assert full_model.compile().kernel.layout.held == ()
    for tol in (1e-6, 1e-10):
        held, full = model.run(integr_tol=tol), full_model.run(integr_tol=tol)
        assert held.success and full.success
        # rounding alone moves seed 3's steps by up to 1.7 % (integr_tol changed by 1e-15..1e-14
        # relative); without the weights' scaling the held run took 4.6 % more at 1e-6
        assert abs(held.stats["steps"] - full.stats["steps"]) <= 0.03 * full.stats["steps"]
        assert np.abs(held.request(1)[:, :2] - full.request(1)[:, :2]).max() <= 10 * tol
        assert np.all(held.y[:, [1, 4]] == 0.0) and np.all(held.yp[:, [1, 4]] == 0.0)


def test_integrator_holds_only_a_start_at_rest():
    """The C integrator leaves the held states out for a start at rest in them, and integrates
    every state for one that is not (here a start moving along y)."""
    kernel = pysolver.loads(SEED3).compile().kernel
    y0 = kernel.layout.initial_state()
    for vy, held in ((0.0, 2), (5.0, 0)):
        y = y0.copy()
        y[4] = vy
        yp = kernel.consistent_yp(0.0, y)
        ida = cida.CIDA(kernel, 1e-6, 1e-6)
        ida.init_step(0.0, y, yp)
        assert ida.held() == held
        step = ida.step(0.1, 3.0)
        assert step.status >= 0
        assert step.y[1] == pytest.approx(vy * step.t, rel=1e-6, abs=1e-12)


def test_a_sweep_case_along_the_held_axis_runs_every_state(monkeypatch):
    """A case with gravity along y cannot hold y: its run is the run of a deck that never held
    anything, bit for bit; the next case holds again."""
    model = _seed3()
    case = {"Force_Gravity/grav_y": -100.0}
    moved = model.run(params=case)
    again = model.run()
    np.testing.assert_array_equal(again.y, _seed3().run().y)
    monkeypatch.setenv("PYSOLVER_HELD", "off")
    ref = pysolver.loads(SEED3.replace('grav_y="0"', 'grav_y="-100"')).run()
    np.testing.assert_array_equal(moved.y, ref.y)
    assert moved.y[-1, 1] < -100.0                      # y fell


class AtHalf(Actor):
    """Acts once, at t = 0.5 s (:meth:`act`), and restarts IDA."""

    def __init__(self):
        self.done = False

    def next_time(self, t):
        return math.inf if self.done else 0.5

    def on_time(self, run):
        self.done = True
        self.act(run)
        return Flow(restart=True)


class Push(AtHalf):
    """Sets the falling ball's x velocity to 1 (a held state moves)."""

    def act(self, run):
        run.y = run.y.copy()
        run.y[3] = 1.0
        run.yp = run.kernel.consistent_yp(run.t, run.y)


def test_an_actor_moving_a_held_state_is_followed():
    """The ball holds x: an actor that gives it an x velocity restarts IDA on every state, and
    x then grows as t - 0.5 exactly."""
    model = pysolver.loads(ball("", z0=10.0, end=1.0, dt=0.1))
    assert model.compile().kernel.layout.held == (0, 1, 3, 4)
    res = run_model(model, progress=False, actors=[Push()], overrides={"backend": "c"})
    assert res.success, res.message
    np.testing.assert_allclose(res.y[:, 0], np.maximum(res.t - 0.5, 0.0), atol=1e-9)
    np.testing.assert_allclose(res.y[:, 2], 10 - 0.5 * G * res.t ** 2, atol=1e-8)


SLOW_DOWN = ('<Sensor_Event id="1" expr="DZ(10)" compare="LT" value="9.5" error_tol="1e-6" '
             'hmax="1e-3"/>')


@pytest.mark.parametrize("sensor", ["", SLOW_DOWN])
def test_starting_again_on_every_state_keeps_the_run(monkeypatch, sensor):
    """When the push makes IDA start again on every state, the run keeps its counters and the
    step bound a sensor set before (h_max 1e-3 from z < 9.5): the same statistics and steps as
    the run that never held anything."""
    def run():
        model = pysolver.loads(ball(sensor, z0=10.0, end=1.0, dt=0.1, tol=1e-6))
        return run_model(model, progress=False, actors=[Push()], overrides={"backend": "c"})
    held = run()
    monkeypatch.setenv("PYSOLVER_HELD", "off")
    full = run()
    assert held.success and full.success
    assert held.stats == full.stats
    assert held.stats["steps"] > (500 if sensor else 0)       # h_max 1e-3 over the last 0.68 s
    np.testing.assert_allclose(held.y, full.y, rtol=0, atol=1e-9)


class GravityAlongY(AtHalf):
    """Turns gravity along y on, without new rates (IDA's corrector finds them): the start's
    equations are not at rest in the held y any more."""

    def act(self, run):
        run.kernel.m.gravity = run.kernel.arrays["gravity"] = [0.0, -1.0, -G]


def test_a_restart_whose_equations_move_a_held_state_integrates_every_state():
    model = pysolver.loads(ball("", z0=10.0, end=1.0, dt=0.1, tol=1e-8))
    res = run_model(model, progress=False, actors=[GravityAlongY()], overrides={"backend": "c"})
    assert res.success, res.message
    np.testing.assert_allclose(res.y[:, 1], -0.5 * np.maximum(res.t - 0.5, 0.0) ** 2, atol=1e-8)


def test_a_sweep_sequence_holds_and_lets_go(monkeypatch):
    """Cases that move the held coordinate's start, give it a velocity or a gravity, and the
    deck's own numbers, one after another on one model: each run is that of a model that
    never held anything (to rounding), and y is exactly constant in the runs that hold it."""
    cases = [{}, {"Reference_Marker/10/pos_y": 7.0}, {"Body_Point/2/v_ic_y": 3.0}, {},
             {"Force_Gravity/grav_y": -5.0}, {"Reference_Marker/10/pos_y": -2.0}, {}]
    model = _seed3()
    held = [model.run(params=c) for c in cases]
    monkeypatch.setenv("PYSOLVER_HELD", "off")
    full_model = _seed3()
    for case, a in zip(cases, held):
        b = full_model.run(params=case)
        assert a.success and b.success
        if "v_ic_y" in str(case) or "grav_y" in str(case):
            np.testing.assert_array_equal(a.y, b.y)      # nothing held: the same arithmetic
            continue
        # held: the full run's steps in exact arithmetic, its rounding aside, which moves
        # the answer by a tenth of the run's error against integr_tol 1e-12 (4.9e-5 against
        # 4.9e-4, 459 steps against 463, with either dense solver; stop 41)
        assert abs(a.stats["steps"] - b.stats["steps"]) <= 0.03 * b.stats["steps"]
        err = np.abs(b.y - full_model.run(params=case, integr_tol=1e-12).y).max()
        assert np.abs(a.y - b.y).max() <= 0.25 * err
        assert np.all(a.y[:, 1] == a.y[0, 1]) and np.all(a.y[:, 4] == 0.0)


def test_holding_a_state_that_moves_ends_the_run():
    """The residual checks the held equations: holding x, which the penalties move, fails the
    run with a message instead of answering for another scene."""
    kernel = pysolver.loads(SEED3).compile().kernel
    y0 = kernel.layout.initial_state()
    yp0 = kernel.consistent_yp(0.0, y0)
    ida = cida.CIDA(kernel, 1e-6, 1e-6)
    hold = np.array([0, 3], dtype=np.int32)          # x and vx, at rest at the start
    lib.ps_ida_hold(ida.s, ffi.cast("int *", ffi.from_buffer(hold)), 2)
    ida.init_step(0.0, y0, yp0)
    assert ida.held() == 2
    step = ida.step(3.0, 3.0)
    assert step.status < 0
    # the first force along x comes with the first contact (z = 1 + x after a fall of 19 mm,
    # t > 0.062 s): the velocity's equation, m vx' = F_x, no longer holds at rest, and the
    # step that reaches it fails
    assert kernel.message.startswith("body2.vx was held at rest, but its equation gives ")
    assert kernel.message.endswith("(run with PYSOLVER_HELD=off and report this)")
    # the last converged step is before the contact, the particle still above the line
    assert step.t < 0.0622 and step.y[2] > 101.0


def test_a_routine_holds_what_it_did_not_declare(tmp_path):
    """A routine the kernel calls reads what its iflag call declared: the NumPy PFOSUB that
    asks for DX and DZ lets y be held (the expression version's steps and answers to
    rounding), the C one that asks for TDISP does not."""
    from scenes import lines_deck
    expr_text, _ = lines_deck("expression", tmp_path)
    ref = pysolver.loads(expr_text, fmt="py").run(integr_tol=1e-8)
    text, _ = lines_deck("untraceable_syspar", tmp_path)
    model = pysolver.loads(text, fmt="py")
    assert model.compile().kernel.layout.held == (1, 4)
    res = model.run(integr_tol=1e-8)
    assert res.success and res.stats["steps"] == ref.stats["steps"]
    assert np.abs(res.request(1)[:, :4] - ref.request(1)[:, :4]).max() <= 1e-12
    text, _ = lines_deck("c", tmp_path)
    if text is not None:
        assert pysolver.loads(text, fmt="py").compile().kernel.layout.held == ()
