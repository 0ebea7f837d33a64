"""Breaks of functions of time (pysolver.solve.breaks): the times found at load, and force
pulses shorter than IDA's step resolved by stopping and restarting there (trial 45, item 4),
the same to the bit on the batched path and the general driver."""
import numpy as np
import pytest

import pysolver
from pysolver.solve import breaks, fast

POINT = """<MotionSolve><Model>
<Body_Rigid id="1" isground="TRUE"/>
<Reference_Marker id="1" body_id="1"/>
<Reference_Marker id="10" body_id="2"/>
<Body_Point id="2" cg_id="10" mass="1"/>
<Force_Scalar_TwoBody id="1" type="Force" i_marker_id="10" j_marker_id="1"
  is_action_only="TRUE" expr="{expr}"/>
{extra}
<Post_Request id="1" expr1="DZ(10)" expr2="VZ(10)"/>
<Param_Transient integr_tol="{tol}"/>
</Model><Simulate analysis_type="Transient" end_time="3" print_interval="0.5"/></MotionSolve>"""

#: The trial's pulses: (expression, impulse in N s). Two equal STEPs a width d apart enclose
#: H d: 1000 N x 0.5 ms (the STEP pulses' impulse is 0.5 N s, not 1); the IF pulse is 1000 N
#: for 1 ms exactly.
PULSES = {
    "step 1 ms": ("STEP(TIME,1,0,1.0005,1000)-STEP(TIME,1.0005,0,1.001,1000)", 0.5),
    "step 10 us": ("STEP(TIME,1.7,0,1.700005,1e5)-STEP(TIME,1.700005,0,1.70001,1e5)", 0.5),
    "IF 1 ms": ("IF(TIME-1.2: 0, 1000, IF(TIME-1.201: 1000, 0, 0))", 1.0),
    "HAVSIN scaled": ("HAVSIN(2*(TIME-1),0,0,0.001,1000)-HAVSIN(2*TIME-2,0.001,0,0.002,1000)",
                      0.5),
}


def _times(expr, extra=""):
    model = pysolver.loads(POINT.format(expr=expr, extra=extra, tol=1e-6))
    return breaks.break_times(model.compile().model)


@pytest.mark.parametrize("expr, times", [
    ("STEP(TIME, 1, 0, 2, 5)", [1.0, 2.0]),
    ("STEP5(2*(TIME - 1), 0, 0, 1, 1)", [1.0, 1.5]),
    ("HAVSIN(TIME/2 + 1, 2, 0, 3, 1)", [2.0, 4.0]),
    ("SIN(3*TIME) + IF(TIME - PI/2: 0, 1, 2)", [np.pi / 2]),
    ("ABS(TIME - 0.25) + MAX(0, 1.5 - TIME) + SIGN(1, TIME - 2) + DIM(TIME, 2.5)",
     [0.25, 1.5, 2.0, 2.5]),
    ("IMPACT(TIME, 1, 0.5, 10, 1.5, 0, 0.1) + BISTOP(TIME, 1, 0.7, 0.9, 10, 1.5, 0, 0.1)",
     [0.5, 0.7, 0.9]),
    ("VARVAL(1)", [1.25, 1.5]),
    ("STEP(TIME, -1, 0, 0, 1)", []),               # at and before the start: none
    ("STEP(DZ(10), 1, 0, 2, 1)", []),              # a function of the state
    ("STEP(TIME*TIME, 1, 0, 2, 1)", []),           # not affine in TIME
    ("MOD(TIME, 0.5) + AINT(TIME)", []),           # periodic jumps: not found
    ("STEP(TIME, VARVAL(2), 0, 2, 1)", [2.0]),     # a plain-number variable a sweep may change
])
def test_the_breaks_found_at_load(expr, times):
    extra = ('<Reference_Variable id="1" expr="STEP(2*TIME, 2.5, 0, 3, 1)"/>'
             '<Reference_Variable id="2" expr="1"/>')
    assert _times(expr, extra) == pytest.approx(times, rel=1e-15, abs=0)


@pytest.mark.parametrize("name", PULSES)
@pytest.mark.parametrize("tol", [1e-3, 1e-6, 1e-9])
def test_a_pulse_shorter_than_the_step_gives_its_impulse(name, tol):
    """The body at rest is struck once: its final velocity is the impulse (it was 0: the
    steps passed over the pulse), to the tolerance, in a few hundred steps at most."""
    expr, impulse = PULSES[name]
    res = pysolver.loads(POINT.format(expr=expr, extra="", tol=tol)).run(progress=False)
    assert res.success
    assert abs(res.request(1)[-1, 1] - impulse) <= 20 * tol
    assert res.stats["steps"] < 300
    assert res.stats["nrestarts"] == len(_times(expr))


@pytest.mark.parametrize("tol", [1e-6, 1e-9, 1e-12])
def test_a_single_jump_at_a_break_from_rest(tol):
    """A force that jumps from 0 to 1000 N at t = 1 with the body at rest: the restart takes
    the rates past the jump (with those before it IDA's first step failed its error test)."""
    res = pysolver.loads(POINT.format(expr="IF(TIME-1: 0, 0, 1000)", extra="", tol=tol)).run(
        progress=False)
    assert res.success
    assert res.request(1)[-1, 1] == pytest.approx(2000.0, abs=1e-9)


SENSOR = ('<Sensor_Event id="1" expr="DZ(10)" value="0.25" compare="GE" error_tol="1e-9" '
          'zero_crossing="0.1" print="TRUE"/>')


@pytest.mark.parametrize("extra", ["", SENSOR], ids=["plain", "zero_crossing"])
def test_the_batched_path_stops_at_the_breaks_to_the_bit(extra, monkeypatch):
    model = pysolver.loads(POINT.format(expr=PULSES["IF 1 ms"][0] + " + 0.01", extra=extra,
                                        tol=1e-7))
    first, second = model.run(progress=False), model.run(progress=False)
    assert [run for _, run in model.compile().batched.values()] != [None]
    with monkeypatch.context() as m:
        m.setattr(fast, "ENABLED", False)
        ref = model.run(progress=False)
    for res in (first, second):
        for name in ("t", "y", "yp", "_outputs"):
            assert np.array_equal(getattr(res, name), getattr(ref, name), equal_nan=True)
        assert res.stats == ref.stats | {k: res.stats[k] for k in res.stats if "time" in k}
        assert res.events == ref.events
    assert ref.success and ref.stats["nrestarts"] >= 2
    assert ref.request(1)[-1, 1] == pytest.approx(1.0 + 0.03, abs=1e-5)
    assert len(ref.events) == (1 if extra else 0)


def test_a_scene_with_joints_stops_on_the_general_driver():
    """A torque pulse of 0.5 N m s on a revolute pendulum without gravity (I = 2 kg m^2 about
    the pin): its rate after the pulse is 0.25 rad/s."""
    deck = """<MotionSolve><Model>
<Body_Rigid id="1" isground="TRUE"/>
<Reference_Marker id="1" body_id="1"/>
<Reference_Marker id="20" body_id="2" pos_x="1"/>
<Reference_Marker id="21" body_id="2"/>
<Body_Rigid id="2" cg_id="20" mass="1" inertia_xx="1" inertia_yy="1" inertia_zz="1"/>
<Constraint_Joint id="1" type="REVOLUTE" i_marker_id="21" j_marker_id="1"/>
<Force_Scalar_TwoBody id="2" type="Torque" i_marker_id="21" j_marker_id="1"
  is_action_only="TRUE" expr="STEP(TIME,1,0,1.0005,1000)-STEP(TIME,1.0005,0,1.001,1000)"/>
<Post_Request id="1" expr1="WZ(20)"/>
<Param_Transient integr_tol="1e-8"/>
</Model><Simulate analysis_type="Transient" end_time="2" print_interval="0.5"/></MotionSolve>"""
    model = pysolver.loads(deck)
    res = model.run(progress=False)
    assert model.compile().batched and list(model.compile().batched.values())[0][1] is None
    assert res.success and res.stats["nrestarts"] == 3
    assert res.request(1)[-1, 0] == pytest.approx(0.25, abs=1e-7)


MOTION_KINK = """<MotionSolve><Model>
<Body_Rigid id="1" isground="TRUE"/>
<Reference_Marker id="1" body_id="1"/>
<Reference_Marker id="20" body_id="2"/>
<Body_Rigid id="2" cg_id="20" mass="2" inertia_xx="1" inertia_yy="1" inertia_zz="1"/>
<Constraint_Joint id="1" type="TRANSLATIONAL" i_marker_id="20" j_marker_id="1"/>
<Motion_Joint id="1" joint_id="1" type="EXPRESSION" val_type="D" expr="{expr}"/>
<Post_Request id="1" expr1="DZ(20)" expr2="VZ(20)"/>
<Param_Transient integr_tol="{tol}"/>
</Model><Simulate analysis_type="Transient" end_time="1" print_interval="0.05"/></MotionSolve>"""


@pytest.mark.parametrize("expr, rate", [("MAX(0, TIME-0.5)", 1.0),
                                        ("IF(TIME-0.5: 0, 0, 0.3*(TIME-0.5))", 0.3)])
@pytest.mark.parametrize("tol", [1e-3, 1e-6])
def test_a_motion_whose_velocity_jumps_at_a_break(expr, rate, tol):
    """A displacement motion with a kink at t = 0.5 (its velocity jumps from 0 to `rate`):
    the restart there takes the impulse's velocities, as at a spline knot; the slider
    follows the motion exactly (the restart had taken only new rates: IDA failed at 0.5)."""
    res = pysolver.loads(MOTION_KINK.format(expr=expr, tol=tol)).run()
    assert res.success, res.message
    t = np.asarray(res.t)
    z, v = res.request(1)[:, 0], res.request(1)[:, 1]
    np.testing.assert_allclose(z, rate * np.maximum(0.0, t - 0.5), atol=1e-9)
    np.testing.assert_allclose(v[t > 0.5], rate, atol=1e-9)
    np.testing.assert_allclose(v[t < 0.5], 0.0, atol=1e-9)
