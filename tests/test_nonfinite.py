"""Non-finite values at run time (issue 13): a NaN or infinity in a force, motion, sensor or the
state ends the run with success=False and status -700, naming the element, its expression, the
time and the state of that evaluation; non-finite request channels are kept and listed in the
log. Both integrators (C driver, scikit-sundae) report alike."""
import math
import re

import numpy as np
import pytest

import pysolver

from helpers import DECKS

ABOVE = (DECKS / "particle_above_line.xml").read_text()      # falls from y = 3 under -9.81 g
PUSHED = (DECKS / "sensor_halt_acceleration.xml").read_text()
G_EXPR = 'expr="1 + dx(10) - dy(10)"'
T_AT_2 = math.sqrt(2 * 1.0 / 9.81)        # free fall from y = 3 to y = 2


def _penalty(extra):
    return ABOVE.replace(G_EXPR, f'expr="1 + dx(10) - dy(10) + {extra}"')


def _bad_time_and_y(message):
    t = float(re.search(r"at t = ([0-9.e+-]+); state", message).group(1))
    y = float(re.search(r"body2\.y = ([0-9.e+-]+)", message).group(1))
    return t, y


@pytest.mark.parametrize("jacobian", ["exact", "dq"])    # C driver / scikit-sundae callbacks
@pytest.mark.parametrize("extra", ["LOG(DY(10) - 2)", "SQRT(DY(10) - 2)"])
def test_a_force_running_into_nan_names_itself(extra, jacobian):
    """g is finite only while y > 2 (the term keeps the penalty inactive): the solution reaches
    y = 2 at t = sqrt(2/g) and cannot go on. IDA must stop there, at once (no creeping towards
    it with ever smaller steps), and say which expression went NaN, when and where."""
    res = pysolver.loads(_penalty(extra)).run(jacobian=jacobian)
    assert not res.success and res.status == -700
    assert f"non-finite value (nan) in Force_Penalty 10: 1 + dx(10) - dy(10) + {extra}" \
        in res.message
    t, y = _bad_time_and_y(res.message)
    assert abs(t - T_AT_2) < 1e-5 and abs(y - 2.0) < 1e-4
    assert res.stats["steps"] < 200                  # it does not creep towards t = 0.4515
    # the rows before are kept and agree with free fall
    assert len(res.t) > 80 and res.t[-1] <= T_AT_2
    assert np.allclose(res.y[:, 1], 3 - 9.81 * res.t ** 2 / 2, atol=1e-4)


def test_a_nan_at_the_initial_conditions_names_the_force():
    res = pysolver.loads(_penalty("LOG(DY(10) - 4)")).run()
    assert res.status == -700 and res.message.startswith("initial conditions: non-finite "
                                                         "value (nan) in Force_Penalty 10")
    assert "at t = 0; state: body2.x = 0, body2.y = 3," in res.message
    assert len(res.t) == 0 or np.isfinite(res.y).all()


def test_an_infinite_derivative_is_named_as_a_derivative():
    """SQRT(ABS(DY)) at DY = 0: the force is finite, its Jacobian entry is not."""
    text = PUSHED.replace('expr="2*TIME"', 'expr="2*TIME + SQRT(ABS(DY(21)))"')
    res = pysolver.loads(text).run()
    assert res.status == -700
    assert "non-finite derivative" in res.message
    assert "Force_Scalar_TwoBody 1: 2*TIME + SQRT(ABS(DY(21)))" in res.message
    assert "... (1 more)" in res.message           # 13 states: the first 12 quoted


def test_a_sensor_expression_going_nan_names_the_sensor():
    sensor = ('<Sensor_Event id="3" expr="SQRT(DY(10) - 2)" value="0.1" compare="LT" '
              'error_tol="1e-6" halt="FALSE"/>\n    <Param_Transient')
    res = pysolver.loads(ABOVE.replace("<Param_Transient", sensor)).run()
    assert res.status == -700 and "in Sensor_Event 3: SQRT(DY(10) - 2)" in res.message
    t, y = _bad_time_and_y(res.message)
    assert y < 2.0 and t > T_AT_2 - 1e-6
    # it fired first, where SQRT(y - 2) = 0.1, y = 2.01
    assert len(res.events) == 1 and abs(res.events[0].time - math.sqrt(2 * 0.99 / 9.81)) < 1e-5


def test_non_finite_request_channels_are_kept_and_logged_once():
    """DX/(DY - 3) is 0/0 at the first row only."""
    text = ABOVE.replace('expr1="DX(10)"', 'expr1="DX(10)/(DY(10)-3)"')
    res = pysolver.loads(text).run()
    assert res.success
    col = res.request(1)[:, 0]
    assert np.isnan(col[0]) and np.isfinite(col[1:]).all()
    assert res.log == ["request 1 channel 1 (DX(10)/(DY(10)-3)) is not finite at 1 of 401 "
                       "output times, first at t = 0 (nan)"]


def test_a_singular_iteration_matrix_at_the_start_is_a_message():
    """Found by the fuzzer: penalty1 = 1e308 on the spinning top made dF/dyp singular and
    np.linalg.solve raised LinAlgError out of run()."""
    text = (DECKS / "spinning_top.xml").read_text().replace(
        'expr="DY(21,1)" penalty="1e6" penalty1="500"', 'expr="DY(21,1)" penalty="1e6" '
        'penalty1="1e308"')
    assert 'penalty1="1e308"' in text
    res = pysolver.loads(text).run()
    assert res.status == -700 and "the accelerations cannot be solved for" in res.message


def test_a_contact_at_the_first_step_with_restore_and_shrink():
    """Found by the fuzzer: a zero-crossing sensor firing at the first step restored a snapshot
    taken before the command's print interval was set (TypeError). g = TIME: the contact
    penalty pushes from t = 0 on; the run must finish."""
    text = (DECKS / "contact_onset_zero_crossing.xml").read_text()
    text = text.replace('expr="-DZ(10)" penalty="1e6"', 'expr="TIME" penalty="1e6"')
    assert 'expr="TIME"' in text
    res = pysolver.loads(text).run()
    assert res.success, res.message
    assert res.t[-1] == pysolver.loads(text).commands[-1].end_time


#: A point body whose cg marker sits on ground's origin marker, and a force between them
#: ({force}): a translational force there acts along no line (trial 44's forces defect 6).
COINCIDENT = """<MotionSolve><Model>
<Body_Rigid id="1" isground="TRUE"/>
<Reference_Marker id="1" body_id="1"/>
<Body_Point id="2" cg_id="10" mass="1"/>
<Reference_Marker id="10" body_id="2"/>
{force}
</Model></MotionSolve>
"""
NO_DIRECTION = ("a translational force acts along the line from J to I, which has no direction "
                "there: place the markers apart, or give a force that is 0 where they meet "
                "(docs/deck-language.md, \"Coincident markers\")")


@pytest.mark.parametrize("kernel", ["tapes", "generated"])
@pytest.mark.parametrize("force, named, value", [
    ('<Force_Scalar_TwoBody id="1" type="Force" i_marker_id="10" j_marker_id="1" expr="5"/>',
     "Force_Scalar_TwoBody 1 (5)", "5"),
    # with a motion the start is made consistent in Python (pysolver.build.consistent)
    ('<Force_Scalar_TwoBody id="1" type="Force" i_marker_id="10" j_marker_id="1" expr="5"/>'
     '<Motion_Marker id="1" i_marker_id="10" j_marker_id="1" direction="Z" expr="0.1*TIME"/>',
     "Force_Scalar_TwoBody 1 (5)", "5"),
    ('<Force_SpringDamper id="3" type="TRANSLATIONAL" i_marker_id="10" j_marker_id="1" '
     'stiffness="10" damping="1" length="1" preload="0"/>',
     "Force_SpringDamper 3 (-k (DM(10,1) - length) - c VR(10,1) + preload)", "10"),
])
def test_a_force_along_no_line_fails_naming_itself(kernel, force, named, value):
    """A run that starts with the markers on each other and a force that is not 0 there
    fails (it was silently 0: an unstable start looked like an equilibrium), in both
    kernels alike."""
    res = pysolver.loads(COINCIDENT.format(force=force)).run(kernel=kernel)
    assert (res.success, res.status) == (False, -700)
    assert res.message == (f"initial conditions: force with no direction in {named}: its "
                           f"markers I = 10 and J = 1 coincide (DM = 0) while its force is "
                           f"{value}, at t = 0; {NO_DIRECTION}")


def test_a_force_that_is_zero_where_the_markers_meet_runs():
    """A spring of free length 0 and no preload is 0 at DM = 0: nothing to point, no load;
    pulled by gravity the body swings on it as a mass on a spring: y = -g/w^2 (1 - cos wt)."""
    force = ('<Force_SpringDamper id="3" type="TRANSLATIONAL" i_marker_id="10" j_marker_id="1" '
             'stiffness="100" damping="0" length="0" preload="0"/>'
             '<Force_Gravity grav_x="0" grav_y="-9.81" grav_z="0"/>')
    res = pysolver.loads(COINCIDENT.format(force=force)).run(integr_tol=1e-9)
    assert res.success
    y = res.y[:, res.state_names.index("body2.y")]
    np.testing.assert_allclose(y, -9.81 / 100 * (1 - np.cos(10 * res.t)), atol=1e-7)


@pytest.mark.parametrize("i, j, what", [("10", "10", "are one marker"),
                                        ("10", "11", "coincide on body 2")])
def test_markers_that_coincide_for_ever_are_refused_at_load(i, j, what):
    force = (f'<Reference_Marker id="11" body_id="2"/><Force_Scalar_TwoBody id="1" '
             f'type="Force" i_marker_id="{i}" j_marker_id="{j}" expr="5"/>')
    with pytest.raises(pysolver.DeckError) as err:
        pysolver.loads(COINCIDENT.format(force=force))
    assert (err.value.line, err.value.attribute, err.value.reason) == (
        6, "j_marker_id", f"markers I = 10 and J = {j} {what}, so DM is 0 for ever and a "
        "translational force, which acts along the line from J to I, has no direction "
        "(docs/deck-language.md, \"Coincident markers\")")
