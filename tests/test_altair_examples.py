"""Syntax of Altair's own MotionSolve XML examples (trial 45): Force_Scalar_TwoBody's
body1_id/body2_id, Motion_Joint's joint_type, the degree suffix 180D, Simulate's num_steps,
start_time and print_increment, FITSPL refused with advice, FIM_D statics' log line."""
import warnings

import numpy as np
import pytest

import pysolver
from pysolver import DeckError
from pysolver.errors import DeckWarning

PENDULUM = """<MotionSolve><Model>
<Body_Rigid id="1" isground="TRUE"/>
<Reference_Marker id="1" body_id="1"/>
<Reference_Marker id="2" body_id="1"/>
<Reference_Marker id="20" body_id="2" pos_x="1"/>
<Reference_Marker id="21" body_id="2"/>
<Body_Rigid id="2" cg_id="20" mass="1" inertia_xx="0.01" inertia_yy="0.01" inertia_zz="0.01"/>
<Constraint_Joint id="1" type="REVOLUTE" i_marker_id="21" j_marker_id="2"/>
{element}
<Post_Request id="1" expr1="AZ(21,2)" expr2="WZ(21)"/>
<Param_Transient integr_tol="1e-10"/>
</Model>{commands}</MotionSolve>"""
TRANSIENT = '<Simulate analysis_type="Transient" end_time="0.5" print_interval="0.1"/>'


def pendulum(element, commands=TRANSIENT):
    return PENDULUM.format(element=element, commands=commands)


def test_sforce_body_ids_as_in_altairs_examples():
    """Altair's DM, CUBSPL and FITSPL pages write body1_id and body2_id on
    Force_Scalar_TwoBody: they are checked against the markers' bodies, and the run is the
    one without them: a torque 2 on I = 1.01 turns the pendulum by t^2/1.01."""
    torque = ('<Force_Scalar_TwoBody id="1" type="Torque" i_marker_id="21" {b1} '
              'j_marker_id="2" {b2} val_expression="2"/>')
    with_ids = pysolver.loads(pendulum(torque.format(b1='body1_id="2"', b2='body2_id="1"')))
    plain = pysolver.loads(pendulum(torque.format(b1="", b2="")))
    a, b = with_ids.run(), plain.run()
    assert a.success and np.array_equal(a.request(1)[:, :2], b.request(1)[:, :2])
    np.testing.assert_allclose(a.request(1)[:, 0], a.t ** 2 / 1.01, rtol=0, atol=1e-9)


@pytest.mark.parametrize("b1, b2, attribute, words", [
    ('body1_id="1"', "", "body1_id", "got 1, but i_marker_id 21 is on body 2"),
    ("", 'body2_id="2"', "body2_id", "got 2, but j_marker_id 2 is on body 1"),
])
def test_sforce_body_ids_that_disagree_are_a_deck_error(b1, b2, attribute, words):
    text = pendulum(f'<Force_Scalar_TwoBody id="1" type="Torque" i_marker_id="21" {b1} '
                    f'j_marker_id="2" {b2} val_expression="2"/>')
    with pytest.raises(DeckError, match=words) as err:
        pysolver.loads(text)
    assert err.value.attribute == attribute
    assert err.value.element == "Force_Scalar_TwoBody"
