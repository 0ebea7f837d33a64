"""The fast path of a run (pysolver.solve.fast) against the general driver it stands in for:
the same rows to the last bit, the same counters and messages, on every deck it takes; the
general path for every run it does not take, or does not finish cleanly."""
import numpy as np
import pytest

import pysolver
from pysolver.solve import fast

from helpers import DECKS, TEST_DECKS

FAST_DECKS = ["catenary_bead.xml", "particle_above_line.xml", "particle_between_lines.xml",
              "particle_between_lines_si.xml", "spinning_top.xml", "stiff_penalty_pendulum.xml",
              "torque_free_spin.xml", "catenary_bead.py", "torque_free_spin.py",
              # motions and exact joints: reactions and request rows from C at steps' ends
              "driven_indenter.xml", "joints/pendulum_revolute.xml", "joints/slider_crank.xml",
              "joints/spherical_pendulum.xml", "joints/iftomm_a04_bricard.xml"]

TWO_COMMANDS = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="2" body_id="2" pos_z="1"/>
  <Body_Point id="2" cg_id="2" mass="1"/><Force_Gravity grav_z="-9.81"/>
  <Force_Penalty id="1" expr="0.5 - DZ(2)" unilateral="TRUE" penalty="1e3" penalty1="5"/>
  <Post_Request id="1" expr1="DZ(2)" expr2="PFORCE(1)"/>
  <Param_Transient integr_tol="1e-6"/></Model>
  <Simulate analysis_type="Transient" end_time="{end}" print_interval="0.05"/>
  <Simulate analysis_type="Transient" end_time="0.9" print_interval="0.1"/></MotionSolve>"""

_SAME_STATS = ("steps", "nres", "njac", "nfail", "outputs", "nroots", "nevents", "nrestarts",
               "ida_nfev", "ida_njev", "netf", "ncfn", "growth_limited_at")


def _takes_fast_path(model, **options):
    from pysolver.solve.run import _settings
    opts = _settings(model.compile(), options)[0]
    return fast.fast_run(model.compile(), opts, ()) is not None


def _general(model, monkeypatch, **options):
    with monkeypatch.context() as m:
        m.setattr(fast, "ENABLED", False)
        return model.run(progress=False, **options)


def _same(a, b, events=False):
    """Rows, outcome, counters, metadata, log and events equal to the bit (no events at all
    unless `events`)."""
    for name in ("t", "y", "yp", "_outputs"):
        assert np.array_equal(getattr(a, name), getattr(b, name), equal_nan=True), name
    assert (a.success, a.status, a.message) == (b.success, b.status, b.message)
    assert {k: a.stats[k] for k in _SAME_STATS} == {k: b.stats[k] for k in _SAME_STATS}
    assert a.meta == b.meta and a.log == b.log and a.events == b.events
    assert events or a.events == []


def _load(name):
    path = DECKS / name if (DECKS / name).exists() else TEST_DECKS / name
    return pysolver.load(path)


@pytest.mark.parametrize("name", FAST_DECKS + ["all_functions.xml"])
def test_fast_path_gives_the_general_paths_rows_to_the_bit(name, monkeypatch):
    """Twice (the second run restarts the kept IDA object), and the same as the driver."""
    model = _load(name)
    assert _takes_fast_path(model)
    first, second = model.run(progress=False), model.run(progress=False)
    kept = [run for _, run in model.compile().batched.values()]
    ref = _general(model, monkeypatch)
    _same(first, ref)
    _same(second, ref)
    assert len(kept) == 1 and kept[0] is not None
    assert [run for _, run in model.compile().batched.values()] == kept   # nothing rebuilt


@pytest.mark.parametrize("end", ["0.5", "1e-9", "0.05"])
def test_commands_and_first_steps_of_every_length(end, monkeypatch):
    """Two Simulate commands, the first ending inside IDA's first step (1e-9: its first step is
    cut at the end, which is the row), at its first print time, or after many."""
    model = pysolver.loads(TWO_COMMANDS.format(end=end))
    assert _takes_fast_path(model)
    res = model.run(progress=False)
    _same(res, _general(model, monkeypatch))
    assert res.success and res.t[-1] == 0.9 and np.all(np.diff(res.t) > 0)


LOADCONTROL = (DECKS / "loadcontrol_indenter.xml").read_text()


def _controlled(update="0.01", end="3.0", dt="0.01", target=None, second=None, tasks=1):
    """The LoadControl indenter with its update interval, end, print interval, target, a
    second Simulate command and a second task (on a second indenter) changed."""
    text = LOADCONTROL.replace('<Parameter name="UpdateTime">0.01</Parameter>',
                               f'<Parameter name="UpdateTime">{update}</Parameter>')
    text = text.replace('end_time="3.0" print_interval="0.01"/>',
                        f'end_time="{end}" print_interval="{dt}"/>' + (second or ""))
    if target:
        text = text.replace("IF(t-1: 20*t, 20, IF(t-2: 20, 40, 40))", target)
    if tasks == 2:
        body = ('<Reference_Marker id="20" body_id="3" pos_x="5"/>\n'
                '<Body_Point id="3" cg_id="20" mass="0.02"/>\n'
                '<Force_Penalty id="2" type="EXPRESSION" expr="-DZ(20)" penalty="50" '
                'penalty1="0" unilateral="True" smoothing_factor="1e-4"/>\n<Post_Request')
        task = text[text.index("<Schedule"):text.index("</Schedule>") + len("</Schedule>")]
        task = task.replace('"material">2<', '"material">3<').replace("20*t", "10*t")
        text = text.replace("<Post_Request", body, 1).replace("</CustomTasks>",
                                                              task + "</CustomTasks>")
    return pysolver.loads(text)


def _same_control(a, b):
    _same(a, b)
    assert a.stats["nrestarts"] == b.stats["nrestarts"] > 0
    for lid in a._controllers:
        for name, values in a.controller(lid).items():
            assert np.array_equal(values, b.controller(lid)[name], equal_nan=True), name


@pytest.mark.parametrize("case", [
    {},                                                  # updates on the print times
    {"update": "0.015", "dt": "0.1", "end": "1.0"},      # between them, several per row
    {"update": "0.25", "dt": "0.01", "end": "1.0"},      # many rows per update
    {"end": "1.0", "second": '<Simulate analysis_type="Transient" end_time="1.5" '
                             'print_interval="0.02"/>'},
    {"end": "1.2", "tasks": 2}])
def test_load_control_runs_in_c_to_the_bit(case, monkeypatch):
    """LoadControl's updates in the batched path's C loop (ps_ida_controlled): the general
    loop's rows, counters, restarts and controller records to the last bit, on every run (the
    kept IDA object restarts), whatever the update and print intervals, over two Simulate
    commands and with two tasks."""
    model = _controlled(**case)
    assert _takes_fast_path(model)
    runs = [model.run(progress=False) for _ in range(2)]
    ref = _general(model, monkeypatch)
    assert ref.success and len(ref.controller(1)["time"]) > 3
    for res in runs:
        _same_control(res, ref)


def test_load_control_failures_are_worded_as_the_general_loop(monkeypatch):
    """A target that turns infinite at t = 0.5 (1 / (TIME - 0.5) is evaluated at the update
    there): both paths stop at that update with status -700 and the same message, rows and
    records."""
    model = _controlled(target="IF(TIME-0.5: 20*TIME, 1/(TIME-0.5), 20)", end="1.0")
    res = model.run(progress=False)
    ref = _general(model, monkeypatch)
    assert not res.success and res.status == -700
    assert res.message == "LoadControl 1: the target load is inf at t = 0.5"
    _same(res, ref)
    assert res.controller(1)["time"][-1] < 0.5


def _ball(sensors, **kw):
    from scenes import ball
    return pysolver.loads(ball(sensors, **kw))


BOUNCE = ('<Force_Penalty id="1" expr="-DZ(10)" penalty="1e5" unilateral="TRUE" '
          'smoothing_factor="1e-4"/>')
SENSOR_DECKS = {
    "halt deck": lambda: _load("sensor_halt_acceleration.xml"),
    "end condition": lambda: _load("sensor_end_condition.xml"),
    "re-arming": lambda: _ball(
        '<Sensor_Event id="1" expr="DZ(10)" compare="GE" value="5" error_tol="0.01"/>'
        '<Sensor_Event id="2" expr="VZ(10)" compare="EQ" value="0" error_tol="1e-3" '
        'restart="TRUE"/>', extra=BOUNCE, end=6.0, tol=1e-8),
    "id order": lambda: _ball("".join(
        f'<Sensor_Event id="{i}" expr="DZ(10)" compare="LT" value="5"/>' for i in (9, 2, 5))),
    "halt at the start": lambda: _ball(
        '<Sensor_Event id="1" expr="DZ(10)" compare="GE" value="10" halt="TRUE"/>'),
    "print, dt and evaluate": lambda: _load("sensor_output_interval.xml"),
    "return, two commands": lambda: _ball(
        '<Sensor_Event id="1" expr="DZ(10)" compare="LT" value="5" return="TRUE"/>', end=1.5,
        more='<Simulate analysis_type="Transient" end_time="2.0" print_interval="0.25"/>'),
    "dt at every bounce": lambda: _ball(
        '<Sensor_Event id="1" expr="DZ(10)" compare="LT" value="5" error_tol="0.01" '
        'dt="0.02" print="TRUE"/><Sensor_Event id="2" expr="DZ(10)" compare="GE" value="5" '
        'error_tol="0.01" dt="0.2"/>', extra=BOUNCE, end=6.0, tol=1e-8),
    "verbose": lambda: _ball(
        '<Sensor_Event id="1" expr="TIME" compare="GE" value="0.5" error_tol="1e-9" '
        'verbose="TRUE"/>'),
    "verbose, re-armed, halted": lambda: _ball(
        '<Sensor_Event id="1" expr="DZ(10)" compare="LT" value="5" error_tol="0.01" '
        'verbose="TRUE" print="TRUE"/><Sensor_Event id="2" expr="TIME" compare="GE" '
        'value="4.05" halt="TRUE"/>', extra=BOUNCE, end=6.0, dt=0.05, tol=1e-8),
    "verbose at the start, halt there": lambda: _ball(
        '<Sensor_Event id="1" expr="DZ(10)" compare="GE" value="10" verbose="TRUE" '
        'halt="TRUE"/>'),
    "hmax and stepsize": lambda: _ball(
        '<Sensor_Event id="1" expr="DZ(10)" compare="LT" value="5" hmax="0.002"/>'
        '<Sensor_Event id="2" expr="DZ(10)" compare="LT" value="3" stepsize="1e-5" '
        'restart="TRUE"/><Sensor_Event id="3" expr="DZ(10)" compare="LT" value="2" '
        'stepsize="1e-4"/>'),
    "hmax at the start": lambda: _ball(
        '<Sensor_Event id="1" expr="DZ(10)" compare="GE" value="10" hmax="0.01" '
        'stepsize="1e-6"/>'),
    "zero crossing": lambda: _load("contact_onset_zero_crossing.xml"),
    "zero crossing after a print and a new interval": lambda: _ball(
        '<Sensor_Event id="1" expr="DZ(10)" compare="LT" value="5" print="TRUE" dt="0.01"/>'
        '<Sensor_Event id="2" expr="DZ(10)" compare="LT" value="4.97" zero_crossing="0.1"/>'),
    "zero crossings with hmax, verbose and bounces": lambda: _ball(
        '<Sensor_Event id="1" expr="DZ(10)" compare="LT" value="5" error_tol="0.01" '
        'zero_crossing="0.3" verbose="TRUE"/><Sensor_Event id="2" expr="DZ(10)" compare="LT" '
        'value="2" error_tol="0.01" zero_crossing="0.05" hmax="0.02" print="TRUE"/>'
        '<Sensor_Event id="3" expr="VZ(10)" compare="EQ" value="0" error_tol="1e-3" '
        'zero_crossing="0.5"/>', extra=BOUNCE, end=3.0, tol=1e-7),
    "a SENVAL force on a revolute pendulum": lambda: _senval_pendulum(
        '<Sensor_Event id="1" expr="DY(20)" compare="LT" value="-1.9" error_tol="0.05" '
        'evaluate_id="1" zero_crossing="0.2"/><Sensor_Event id="2" expr="VX(20)" compare="EQ" '
        'value="0" error_tol="1e-3" evaluate_id="1" restart="TRUE" hmax="0.01"/>'),
    "a SENVAL force in a sparse scene": lambda: _senval_bed(),
    "chatter": lambda: _ball(
        '<Sensor_Event id="1" expr="TIME - 0.3 + SENVAL(1)" compare="GE" value="0" '
        'error_tol="0" evaluate_id="1"/>',
        extra='<Sensor_Evaluate id="1" expr="SENVAL(1) - 1e-13"/>'),
}


def _senval_pendulum(sensors):
    """The revolute pendulum with a force along the cm's position reading SENVAL(1) (half its
    x velocity, stored by the sensors): each restart makes the whole state consistent."""
    extra = ('<Sensor_Evaluate id="1" expr="-0.5 * VX(20)"/><Force_Scalar_TwoBody id="9" '
             'type="Force" i_marker_id="20" j_marker_id="1" expr="SENVAL(1)"/>')
    text = (DECKS / "joints" / "pendulum_revolute.xml").read_text()
    return pysolver.loads(text.replace("<Post_Request", extra + sensors + "<Post_Request", 1))


def _senval_bed():
    """The particle bed without its LoadControl (324 states, sparse, no reactions) and a force
    on the indenter reading its velocity, stored at t = 0.2 by a restarting sensor."""
    text = (DECKS / "loadcontrol_bed.py").read_text()
    start = text.index("LOADCONTROL(")
    text = text[:start] + text[text.index(")\n", start) + 2:]
    return pysolver.loads(text.replace("REQUEST(1,", (
        'SENSOR(7, FUNCTION="TIME", VALUE=0.2, OPERATOR="GE", EVALUATE="VZ(10)", RESTART=True)\n'
        'SFORCE(77, I=10, J=1, TRANSLATION=True, FUNCTION="1e-3*SENVAL(7)")\nREQUEST(1,')),
        fmt="py")


@pytest.mark.parametrize("name", sorted(SENSOR_DECKS))
@pytest.mark.parametrize("cap", [None, 1])
def test_sensors_decided_in_c_to_the_bit(name, cap, monkeypatch):
    """Sensors with every action, zero_crossing's restore-and-shrink included, are decided in
    the batched path's C loop (csrc/events.c, csrc/ida.c): the general loop's rows, events,
    log, re-armings, restarts and message to the last bit, on every run; with room for one
    event at a time in C (cap 1) the loop hands them over after each instant and goes on (and
    a restore takes back records already handed over)."""
    from pysolver.solve import sensors
    monkeypatch.setattr(sensors, "EVENT_CAP", cap or sensors.EVENT_CAP)
    model = SENSOR_DECKS[name]()
    assert _takes_fast_path(model)
    runs = [model.run(progress=False) for _ in range(2)]
    ref = _general(model, monkeypatch)
    assert ref.events
    for res in runs:
        _same(res, ref, events=True)


@pytest.mark.parametrize("cap", [None, 1])
def test_zero_crossing_beside_load_control_to_the_bit(cap, monkeypatch):
    """Zero-crossing sensors in a LoadControl deck (contact deeper than 0.01, a time, a printed
    restart): the batched path's C loop remembers the tasks with the steps and gives the
    general loop's rows, events, log and controller records to the bit."""
    from pysolver.solve import sensors
    monkeypatch.setattr(sensors, "EVENT_CAP", cap or sensors.EVENT_CAP)
    found = ('<Sensor_Event id="1" expr="DZ(10)" compare="LT" value="-0.01" zero_crossing="0.3" '
             'print="TRUE"/><Sensor_Event id="2" expr="TIME" compare="GE" value="0.333" '
             'zero_crossing="0.5" restart="TRUE"/><Post_Request')
    model = pysolver.loads(LOADCONTROL.replace('end_time="3.0"', 'end_time="1.0"').replace(
        "<Post_Request", found, 1))
    assert _takes_fast_path(model)
    runs = [model.run(progress=False) for _ in range(2)]
    ref = _general(model, monkeypatch)
    assert sum("zero crossing" in line for line in ref.log) == 2
    for res in runs:
        _same(res, ref, events=True)
        for name, values in res.controller(1).items():
            assert np.array_equal(values, ref.controller(1)[name], equal_nan=True), name


@pytest.mark.parametrize("case", ["a new interval before", "a return before",
                                  "a second command"])
def test_a_zero_crossing_restore_keeps_the_print_schedule(case, monkeypatch):
    """A restore goes back to the grid of print times in force at the step it returns to
    (one a dt action began at an instant without a row, not one rebuilt from the last row),
    and no further back than the command's start (not across a return or a command's end):
    the rows' times are those of the same deck without zero_crossing, on both paths (review of stop
    37: a print time before the restored step failed IDA's interpolation, or the schedule
    shifted, or a return was undone and the second command lost)."""
    from scenes import ball
    second = '<Simulate analysis_type="Transient" end_time="2.5" print_interval="0.07"/>'
    sensors, kw, options = {
        "a new interval before": (
            '<Sensor_Event id="1" expr="TIME" compare="GE" value="0.62" dt="{dt}"/>'
            '<Sensor_Event id="2" expr="DZ(10)" compare="LT" value="7.6" {zc}/>',
            dict(dt=0.5, tol=1e-6), {"h_max": 0.05}),
        "a return before": (
            '<Sensor_Event id="1" expr="DZ(10)" compare="LT" value="5" return="TRUE" '
            'print="TRUE"/><Sensor_Event id="2" expr="DZ(10)" compare="LT" value="4.5" {zc}/>',
            dict(more=second, dt=0.25), {}),
        "a second command": (
            '<Sensor_Event id="1" expr="DZ(10)" compare="LT" value="5" {zc}/>',
            dict(end=1.0, more=second.replace("2.5", "2.0"), dt=0.25), {}),
    }[case]
    runs = {}
    for dt in ("0.1", "0.2"):
        for zc in ('zero_crossing="0.3"', ""):
            model = pysolver.loads(ball(sensors.format(dt=dt, zc=zc), **kw))
            assert _takes_fast_path(model)
            res = model.run(progress=False, **options)
            _same(res, _general(model, monkeypatch, **options), events=True)
            assert res.success, res.message
            runs[zc] = res
        restored = runs['zero_crossing="0.3"']
        assert any("zero crossing" in line for line in restored.log)
        # the same times (an event's root, which a grid may begin at, moves by rounding: the
        # zero-crossing search takes other steps to it)
        assert len(restored.t) == len(runs[""].t) and restored.t[-1] == runs[""].t[-1]
        np.testing.assert_allclose(restored.t, runs[""].t, rtol=0, atol=1e-9)


def test_a_zero_crossing_run_streams_the_rows_it_keeps(tmp_path, monkeypatch):
    """Rows after the last converged step are held back from the stream until no restore can
    take them back: the streamed CSV holds the Result's rows on both paths."""
    model = SENSOR_DECKS["zero crossings with hmax, verbose and bounces"]()
    assert _takes_fast_path(model)
    texts = []
    for enabled in (True, False):
        monkeypatch.setattr(fast, "ENABLED", enabled)
        path = tmp_path / f"rows_{enabled}.csv"
        res = model.run(progress=False, stream=str(path))
        texts.append(path.read_text())
        assert len(texts[-1].splitlines()) == len(res.t) + 1
        assert sum("zero crossing" in line for line in res.log) >= 3
    assert texts[0] == texts[1]


def test_a_senval_restart_keeps_the_joint_and_fails_cleanly(monkeypatch):
    """Where a force reads SENVAL in a scene with joints, a sensor's restart makes the whole
    state consistent in C on both paths (ps_restart_consistent): through the restarts the
    pendulum stays within 10 integr_tol (1e-8) of 2 m from its pivot (the compliant joint's
    drift: 2.9e-8 here, 1.9e-9 without the force) and its velocity perpendicular to the arm
    (1e-7 relative; 8.5e-9 here); a stored value that makes the force infinite ends the run with
    status -700 and the same message on both paths."""
    model = SENSOR_DECKS["a SENVAL force on a revolute pendulum"]()
    res = model.run(progress=False)
    assert res.success and res.stats["nrestarts"] >= 5
    q = res.request(1)
    np.testing.assert_allclose(np.hypot(q[:, 0], q[:, 1]), 2.0, rtol=0, atol=1e-7)
    v, r = np.hypot(q[1:, 2], q[1:, 3]), np.hypot(q[1:, 0], q[1:, 1])
    assert np.abs(q[1:, 2] * q[1:, 0] + q[1:, 3] * q[1:, 1]).max() <= 1e-7 * (v * r).max()
    text = (DECKS / "joints" / "pendulum_revolute.xml").read_text().replace(
        "<Post_Request", '<Sensor_Evaluate id="1" expr="1/(DY(20)-DY(20))"/>'
        '<Force_Scalar_TwoBody id="9" type="Force" i_marker_id="20" j_marker_id="1" '
        'expr="SENVAL(1)"/><Sensor_Event id="1" expr="TIME" compare="GE" value="1" '
        'evaluate_id="1"/><Post_Request', 1)
    model = pysolver.loads(text)
    assert _takes_fast_path(model)
    res = model.run(progress=False)
    assert res.status == -700 and res.message.startswith(
        "a sensor's restart at t = 1 cannot make the state consistent: non-finite value (inf) "
        "in Force_Scalar_TwoBody 9: SENVAL(1)")
    _same(res, _general(model, monkeypatch), events=True)


def test_a_print_interval_past_the_output_budget(monkeypatch):
    """A dt action whose rows would pass PYSOLVER_OUTPUT_BUDGET: both paths stop there with
    status -500 and the same message, rows and events (that sensor's event is not written; an
    earlier sensor's at the same instant is)."""
    model = _ball('<Sensor_Event id="1" expr="DZ(10)" compare="LT" value="5" print="TRUE"/>'
                  '<Sensor_Event id="2" expr="DZ(10)" compare="LT" value="5" dt="1e-6"/>')
    monkeypatch.setenv("PYSOLVER_OUTPUT_BUDGET", str(8 * 7 * 200))
    assert _takes_fast_path(model)
    res, ref = model.run(progress=False), _general(model, monkeypatch)
    assert res.status == -500 and "Sensor_Event 2's dt = 1e-06" in res.message
    assert [e.sensor for e in res.events] == [1]
    _same(res, ref, events=True)


def test_a_root_in_a_restarts_first_step_past_print_times(monkeypatch):
    """The first step after a (re)start finds a root and passes print times before it (loose
    tolerance, h0_max 0.05, rows every 5 ms): the rows before the root are IDA's interpolant over
    that step (not the root's state, which a normal-mode call wrote there before), the root is
    acted on, and both paths agree to the bit."""
    model = _ball('<Sensor_Event id="1" expr="DZ(10)" compare="LT" value="9.999" '
                  'restart="TRUE"/>', end=0.2, dt="0.005", tol=1e-4)
    res = model.run(progress=False, h0_max=0.05)
    ref = _general(model, monkeypatch, h0_max=0.05)
    _same(res, ref, events=True)
    (event,) = res.events
    assert 0.005 < event.time < 0.01 and res.stats["nrestarts"] == 1
    z = res.request(1)[:, 0]
    assert 9.999 < z[1] < 10.0 and res.t[1] == 0.005          # interpolated, not the root
    assert res.success and res.t[-1] == 0.2


def test_a_failed_start_reports_no_records_of_the_run_before(monkeypatch):
    """The kept batched run of a LoadControl deck, after a run that logged 30 updates, runs a
    case whose initial conditions fail (a force 1e-9 / VARVAL = inf): no controller records
    and no notes of the earlier run, as on the general loop. (The force acts from a ground
    marker above the indenter: on its own marker, where it starts, a force has no
    direction.)"""
    text = LOADCONTROL.replace('end_time="3.0"', 'end_time="0.3"').replace(
        ">10</Parameter>", ">1e-6</Parameter>").replace(
        "<Post_Request", '<Reference_Variable id="5" expr="1"/><Reference_Marker id="98" '
        'body_id="1" pos_z="1"/><Force_Scalar_TwoBody id="9" type="Force" i_marker_id="10" '
        'j_marker_id="98" expr="1e-9/VARVAL(5)"/><Post_Request')
    model = pysolver.loads(text)
    case = {"Reference_Variable/5/value": 0.0}
    for enabled in (True, False):
        monkeypatch.setattr(fast, "ENABLED", enabled)
        assert len(model.run(progress=False).controller(1)["time"]) == 30
        bad = model.run(progress=False, params=case)
        assert bad.status == -700 and len(bad.controller(1)["time"]) == 0
        assert not [line for line in bad.log if "LoadControl" in line]


def test_a_halt_that_replaces_a_print_row_is_streamed_as_kept(tmp_path, monkeypatch):
    """A halt at a print time replaces that row (its Sensor_Evaluate now stored): the streamed
    CSV holds the replacing row, as the Result does, on both paths."""
    text = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
      <Reference_Marker id="10" body_id="2" pos_z="10"/>
      <Body_Point id="2" cg_id="10" mass="1"/><Force_Gravity grav_z="-9.81"/>
      <Sensor_Evaluate id="1" expr="100 + TIME"/>
      <Sensor_Event id="1" expr="TIME" compare="GE" value="0.5" evaluate_id="1" halt="TRUE"/>
      <Post_Request id="1" expr1="DZ(10)" expr2="SENVAL(1)"/>
      <Param_Transient integr_tol="1e-8"/></Model>
      <Simulate analysis_type="Transient" end_time="1.0" print_interval="0.1"/></MotionSolve>"""
    model = pysolver.loads(text)
    assert _takes_fast_path(model)
    for enabled in (True, False):
        monkeypatch.setattr(fast, "ENABLED", enabled)
        path = tmp_path / f"rows_{enabled}.csv"
        res = model.run(progress=False, stream=str(path))
        lines = path.read_text().splitlines()[1:]
        assert res.status == 1 and len(lines) == len(res.t) == 6
        assert lines[-1].split(",")[-1] == "100.5" and res.request(1)[-1, 1] == 100.5


SENVAL_FORCE = ('<Reference_Marker id="1" body_id="1"/><Sensor_Evaluate id="1" '
                'expr="-2 * VZ(10)"/><Force_Scalar_TwoBody id="9" type="Force" '
                'i_marker_id="10" j_marker_id="1" expr="SENVAL(1)"/>')


@pytest.mark.parametrize("sensors", [
    '<Sensor_Event id="1" expr="DZ(10)" compare="LT" value="5" evaluate_id="1"/>',
    '<Sensor_Event id="1" expr="DZ(10)" compare="LT" value="5" restart="TRUE"/>'
    '<Sensor_Event id="2" expr="DZ(10)" compare="LT" value="3" evaluate_id="1" '
    'stepsize="1e-4" print="TRUE"/>',
    '<Sensor_Event id="1" expr="DZ(10)" compare="LT" value="8" evaluate_id="1" '
    'hmax="0.01"/>'])
def test_a_force_that_reads_senval_restarts_consistent_in_c(sensors, monkeypatch):
    """A force reads SENVAL (a Sensor_Evaluate of the speed): an action that restarts makes yp
    consistent with the new force, in C on the batched path (ps_consistent_yp, the same C the
    general loop's kernel.consistent_yp calls), to the bit; the force acts from the event on
    (the body's acceleration jumps)."""
    model = _ball(sensors, extra=SENVAL_FORCE)
    assert _takes_fast_path(model)
    res, ref = model.run(progress=False), _general(model, monkeypatch)
    _same(res, ref, events=True)
    assert res.success and res.events
    i = int(np.searchsorted(res.t, res.events[-1].time))
    assert not np.allclose(res.yp[i + 1:, 5], res.yp[1, 5])        # vz' changed


def test_a_restart_where_forces_read_senval_with_a_motion_to_the_bit(monkeypatch):
    """With a motion, a consistent restart after a Sensor_Evaluate a force reads is the whole
    C restart on both paths: the run takes the batched path and gives the general loop's rows
    to the bit; a sparse scene past the sparse restart's size limit (here -1: every one)
    restarts in Python on the general loop (the particle bed below)."""
    from pysolver.build import restart
    text = (DECKS / "driven_indenter.xml").read_text()
    model = pysolver.loads(text.replace("<Post_Request", '<Sensor_Evaluate id="1" expr="1"/>'
        '<Sensor_Event id="1" expr="TIME" compare="GE" value="0.1" evaluate_id="1"/>'
        '<Force_Scalar_TwoBody id="99" type="Force" i_marker_id="10" j_marker_id="1" '
        'expr="SENVAL(1)"/><Post_Request', 1))
    assert model.compile().kernel.forces_use_senval and _takes_fast_path(model)
    res = model.run(progress=False)
    _same(res, _general(model, monkeypatch), events=True)
    assert res.success and res.stats["nrestarts"] == 1
    monkeypatch.setattr(restart, "SPARSE_LIMIT", -1)
    bed = _senval_bed()
    assert not _takes_fast_path(bed)
    assert bed.run(progress=False).success


def _rows_budget(model, rows):
    """PYSOLVER_OUTPUT_BUDGET for `rows` output rows of `model`."""
    k = model.compile().kernel
    return str(8 * (2 * k.ny + max(len(k.channels), 1)) * rows)


@pytest.mark.parametrize("case", ["dt and halt", "dt and return", "dt then a command"])
def test_print_intervals_against_the_budget_as_the_general_loop(case, monkeypatch):
    """A print interval past the output budget stops the run inside that sensor's action, even
    when another sensor halts or returns at the same instant (C checks the budget as it fires),
    and a later command's rows are checked at its start, after a dt made more of them: status
    -500 and the general loop's message, rows and events."""
    se = '<Sensor_Event id="{}" expr="DZ(10)" compare="LT" value="5" {}/>'
    decks = {"dt and halt": (se.format(1, 'dt="1e-6"') + se.format(2, 'halt="TRUE"'), {}, 200),
             "dt and return": (se.format(1, 'dt="1e-6"') + se.format(2, 'return="TRUE"'), {},
                               200),
             "dt then a command": (
                 '<Sensor_Event id="1" expr="TIME" compare="GE" value="0.5" dt="0.001"/>',
                 dict(end=1.0, more='<Simulate analysis_type="Transient" end_time="2.0" '
                                    'print_interval="0.1"/>'), 512)}
    sensors, kw, rows = decks[case]
    model = _ball(sensors, **kw)
    monkeypatch.setenv("PYSOLVER_OUTPUT_BUDGET", _rows_budget(model, rows))
    assert _takes_fast_path(model)
    res, ref = model.run(progress=False), _general(model, monkeypatch)
    assert res.status == -500
    assert ("the Simulate command ending at 2" if case == "dt then a command"
            else "Sensor_Event 1's dt = 1e-06") in res.message
    _same(res, ref, events=True)


@pytest.mark.parametrize("cap", [None, 1])
def test_events_after_print_interval_instants_are_all_kept(cap, monkeypatch):
    """Instants that each set a print interval (two sensors alternating at every bounce,
    error_tol 0), then a halt: every event reaches the Result (the records are handed over after
    each such instant), on both paths alike."""
    from pysolver.solve import sensors
    monkeypatch.setattr(sensors, "EVENT_CAP", cap or sensors.EVENT_CAP)
    model = _ball('<Sensor_Event id="1" expr="DZ(10)" compare="LT" value="5" error_tol="0" '
                  'dt="0.02"/><Sensor_Event id="2" expr="DZ(10)" compare="GE" value="5" '
                  'error_tol="0" dt="0.2"/><Sensor_Event id="3" expr="TIME" compare="GE" '
                  'value="4.0" halt="TRUE"/>', extra=BOUNCE, end=6.0, tol=1e-8)
    res, ref = model.run(progress=False), _general(model, monkeypatch)
    assert res.status == 1 and res.events[-1].sensor == 3 and len(res.events) == 5
    _same(res, ref, events=True)


def test_sensors_and_load_control_in_one_c_loop(monkeypatch):
    """A sensor that restarts at t = 0.5 and halts at 1.25 beside the LoadControl task: both
    in the C loop, the general loop's rows, records and events to the bit."""
    text = LOADCONTROL.replace("<Post_Request", '<Sensor_Event id="1" expr="TIME" compare="GE" '
                               'value="0.5" restart="TRUE"/><Sensor_Event id="2" expr="TIME" '
                               'compare="GE" value="1.25" halt="TRUE"/><Post_Request')
    model = pysolver.loads(text)
    assert _takes_fast_path(model)
    res, ref = model.run(progress=False), _general(model, monkeypatch)
    assert res.status == 1 and res.message.startswith("halted by Sensor_Event 2 at t = 1.25")
    _same(res, ref, events=True)
    for name, values in res.controller(1).items():
        assert np.array_equal(values, ref.controller(1)[name], equal_nan=True), name


def test_a_run_that_fails_is_reported_by_the_general_path(monkeypatch):
    """Too many steps: the batched path reports it in the general loop's words, rows and
    all."""
    model = _load("stiff_penalty_pendulum.xml")
    res = model.run(progress=False, max_num_steps=50)
    assert not res.success and res.status == -100 and "max_num_steps" in res.message
    _same(res, _general(model, monkeypatch, max_num_steps=50))
    ok = model.run(progress=False)                     # and the next clean run is fast again
    assert ok.success and _takes_fast_path(model)


def test_a_sparse_load_control_scene_to_the_bit(monkeypatch):
    """The LoadControl particle bed (325 states, the sparse LU): its 120 updates and their
    restarts (on the kernel's sparse pattern) run in the batched path's C loop, with the
    general loop's rows, records and counters to the bit; past the sparse restart's size limit
    (here 0) the scene restarts in Python on the general loop."""
    from pysolver.build import restart
    model = _load("loadcontrol_bed.py")
    assert _takes_fast_path(model)
    res = model.run(progress=False)
    _same_control(res, _general(model, monkeypatch))
    assert res.stats["nrestarts"] == 120
    monkeypatch.setattr(restart, "SPARSE_LIMIT", 0)
    again = _load("loadcontrol_bed.py")
    assert not _takes_fast_path(again)
    ref = again.run(progress=False)
    assert ref.success and len(ref.controller(1)["time"]) == 120
    np.testing.assert_allclose(ref.y[-1], res.y[-1], rtol=0,
                               atol=1e-6 * np.abs(res.y[-1]).max())


@pytest.mark.parametrize("name, why", [
                                       ("static_pendulum.xml", "a static command")])
def test_runs_that_need_the_driver_take_it(name, why):
    model = _load(name)
    assert not _takes_fast_path(model), why
    assert model.run(progress=False).success


def test_actors_take_the_driver_and_a_progress_bar_does_not(capsys, monkeypatch):
    model = _load("particle_above_line.xml")
    opts = model.transient
    assert fast.fast_run(model.compile(), opts, (object(),)) is None
    assert fast.fast_run(model.compile(), opts, ()) is not None
    res = model.run(progress=True)
    assert "100.0%" in capsys.readouterr().err
    _same(res, _general(model, monkeypatch))


@pytest.mark.parametrize("linsolver", ["dense", "band", "auto", "superlu_mt"])
def test_every_linear_solver_restarts_to_the_bit(linsolver, monkeypatch):
    """A chain of 60 bodies (360 states): dense, band, the sparse LU ("auto" picks it; kept
    between runs, its pivots forgotten at each start) and SuperLU_MT (whose IDA object is set
    up again each run) give the driver's rows on every run."""
    from scenes import chain_deck
    model = pysolver.loads(chain_deck(60, end_time=0.2))
    runs = [model.run(progress=False, linsolver=linsolver) for _ in range(2)]
    ref = _general(model, monkeypatch, linsolver=linsolver)
    assert ref.meta["options"]["linsolver"] == {"auto": "sparse"}.get(linsolver, linsolver)
    for res in runs:
        _same(res, ref)


@pytest.mark.parametrize("mode", ["clean", "error"])
def test_kernel_called_routines_take_the_batched_path(mode, monkeypatch, tmp_path):
    """A Python routine that cannot be traced is called from the kernel: such runs take the
    batched path, cleanly or ending in the routine's error (status -400 at t > 0.5), with the
    general loop's rows, counters and message."""
    script = tmp_path / "bead.py"
    script.write_text(
        "import math\n\n\ndef PFOSUB(id, time, par, npar, dflag, iflag):\n"
        "    [x, e] = py_sysfnc('DX', [9])\n    [y, e] = py_sysfnc('DY', [9])\n"
        "    if float(time) > par[1]:\n        py_errmes(1, 'past the end', id, 'STOP')\n"
        "    return float(y) - math.cosh(float(x))\n")
    text = (DECKS / "catenary_bead.xml").read_text().replace(
        'type="EXPRESSION"\n                   expr="dy(9) - cosh(dx(9))"',
        f'type="USERSUB" script_name="{script}" '
        f'usrsub_param_string="USER(9, {0.5 if mode == "error" else 1e9})"')
    model = pysolver.loads(text)
    assert model.run(progress=False).meta["usersubs"] and _takes_fast_path(model)
    res = model.run(progress=False)
    _same(res, _general(model, monkeypatch))
    assert res.success == (mode == "clean")
    if mode == "error":
        assert res.status == -400 and "past the end" in res.message and 0.4 < res.t[-1] <= 0.5


def test_the_actors_decide_the_path(monkeypatch):
    """The batched path is chosen from the deck's actors (Actor.instants), not a list of model
    features: a printer that needs its rows one by one sends the run to the general loop."""
    from pysolver.solve.outputs import Printer
    model = _load("particle_above_line.xml")
    assert _takes_fast_path(model)
    monkeypatch.setattr(Printer, "instants", property(lambda self: True))
    assert not _takes_fast_path(model, integr_tol=1e-4)     # a new options object: decided anew


def test_the_kept_run_follows_pysolver_backend(monkeypatch):
    """PYSOLVER_BACKEND changed between runs of one model: the second run uses it (the kept
    fast path said backend: c before)."""
    model = _load("particle_above_line.xml")
    assert model.run(progress=False).meta["options"]["backend"] == "c"
    monkeypatch.setenv("PYSOLVER_BACKEND", "sksundae")
    res = model.run(progress=False)
    assert res.success and res.meta["options"]["backend"] == "sksundae"


def _random_deck(rng):
    """A random scene of sensors on the bouncing ball: expressions, thresholds, error_tol
    bands and actions drawn from those the C loop decides, with random print intervals, a
    second Simulate command, first-step bounds and sometimes a force reading SENVAL."""
    actions = ['restart="TRUE"', 'print="TRUE"', 'dt="{:.3g}"', 'return="TRUE"',
               'evaluate_id="1"', 'halt="TRUE"', 'verbose="TRUE"', 'hmax="{:.3g}"',
               'stepsize="{:.1g}"']
    watched = [("TIME", "GE", lambda: rng.uniform(0.0, 0.6)),
               ("DZ(10)", "LT", lambda: rng.uniform(2.0, 9.0)),
               ("DZ(10)", "GE", lambda: rng.uniform(2.0, 9.0)),
               ("VZ(10)", "EQ", lambda: 0.0)]
    sensors = ['<Sensor_Evaluate id="1" expr="VZ(10) + TIME"/>']
    for sid in range(1, rng.integers(1, 4) + 1):
        expr, compare, value = watched[rng.integers(len(watched))]
        chosen = rng.choice(len(actions), size=rng.integers(0, 3), replace=False)
        acts = " ".join(actions[i].format(rng.choice([0.01, 0.05, 0.2]) / (
                            1e3 if "stepsize" in actions[i] else 1)) for i in chosen
                        if actions[i] != 'halt="TRUE"' or rng.random() < 0.3)
        if rng.random() < 0.3:                  # restore-and-shrink
            acts += f' zero_crossing="{rng.choice([0.05, 0.3, 0.9])}"'

        sensors.append(f'<Sensor_Event id="{sid}" expr="{expr}" compare="{compare}" '
                       f'value="{value():.4g}" error_tol="{rng.choice([0.0, 1e-3, 0.1])}" '
                       f'{acts}/>')
    more = ('<Simulate analysis_type="Transient" end_time="2.5" print_interval="0.07"/>'
            if rng.random() < 0.5 else "")
    # sometimes a force reads the stored value (restarts then make yp consistent again)
    force = ('<Reference_Marker id="1" body_id="1"/><Force_Scalar_TwoBody id="9" type="Force" '
             'i_marker_id="10" j_marker_id="1" expr="0.5 * SENVAL(1)"/>'
             if rng.random() < 0.3 else "")
    model = _ball("".join(sensors), extra=BOUNCE + force, end=1.6,
                  dt=rng.choice([0.1, 0.03]), tol=1e-7, more=more)
    return model, ({"h0_max": 0.05} if rng.random() < 0.3 else {})


@pytest.mark.parametrize("seed", range(24))
def test_random_sensor_scenes_to_the_bit(seed, monkeypatch):
    """Random sensor scenes (seeded): the batched path's C loop and the general loop give the
    same rows, events, log, counters and message, twice in a row."""
    model, options = _random_deck(np.random.default_rng(seed))
    options = dict(options, kernel="tapes")     # the loop is the same on either kernel
    assert _takes_fast_path(model, **options)
    runs = [model.run(progress=False, **options) for _ in range(2)]
    ref = _general(model, monkeypatch, **options)
    for res in runs:
        _same(res, ref, events=True)


SIGINT_DECK = '''
import os, signal
from pysolver.msolve import *
done = []
def sevsub(id, time, par, npar, iflag):
    v = float(py_sysfnc("VX", [20])[0])
    if iflag == 0 and time >= {at} and not done:
        done.append(1)
        os.kill(os.getpid(), signal.SIGINT)
    return -0.5 * v
ACCGRAV(JGRAV=-9.81)
PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(2, PART=1)
MARKER(20, PART=2, QP=[2, 0, 0])
MARKER(21, PART=2, QP=[0, 0, 0])
PART(2, MASS=1, CM=20, IP=[1e-3, 1e-3, 1e-3])
JOINT(1, TYPE="REVOLUTE", I=21, J=2)
SFORCE(9, I=20, J=1, TRANSLATION=True, FUNCTION="SENVAL(7)")
SENSOR(7, FUNCTION="TIME", VALUE={at}, OPERATOR="GE", EVALUATE="USER()", EVALUATE_ROUTINE=sevsub)
REQUEST(1, F1="DX(20)", F2="DY(20)")
INTEGRATOR(ERROR=1e-8)
SIMULATE(TYPE="TRANSIENT", END=1.0, DTOUT=0.05)
'''


@pytest.mark.parametrize("at", ["0.5", "0"])
@pytest.mark.parametrize("enabled", [True, False])
def test_ctrl_c_during_a_sensors_restart(at, enabled, monkeypatch):
    """Ctrl-C arriving while a sensor acts (its Python SEVSUB sends SIGINT; a force reads the
    value, so a consistent restart follows and meets the interrupt): status -600
    "interrupted at t = ..." with the rows so far, on both paths, at the start and later (the
    general loop said -400 before stop 37); and the next compile and run of another model are
    not stopped by the flag the interrupted run leaves set (they raised before)."""
    model = pysolver.loads(SIGINT_DECK.format(at=at), fmt="py")
    assert _takes_fast_path(model)
    monkeypatch.setattr(fast, "ENABLED", enabled)
    res = model.run(progress=False)
    assert (res.status, res.message) == (-600, f"interrupted at t = {float(at):g}")
    assert np.all(res.t <= float(at) + 1e-12)           # the rows before it (none at 0)
    nxt = pysolver.load(DECKS / "joints" / "pendulum_revolute.xml").run(progress=False)
    assert nxt.success, nxt.message
