"""FX..TM and MARKER_FORCE requests: the net force and torque acting at a marker, against the
element force functions they sum and against the force balance of bodies at equilibrium."""
import re

import numpy as np

import pysolver

from helpers import ROOT

CRANK = (ROOT / "decks" / "joints" / "slider_crank.xml").read_text()


def test_net_forces_sum_the_element_forces_acting_at_the_marker():
    """On the driven slider-crank: a MARKER_FORCE request of the crank pivot (I of joint 1 and
    of the crank motion) from ground is the joint's force and the joint's plus the motion's
    torque; FX at the pivot's ground marker is the reaction; FY at the crank pin's J marker is
    joint 2's force on J; FX(2, 21) counts only elements between 2 and 21. 1e-12."""
    text = CRANK.replace("</Model>", (
        '<Post_Request id="5" type="MARKER_FORCE" i_marker_id="21" j_marker_id="2"/>'
        '<Post_Request id="6" expr1="JOINT(1,0,1,0)" expr2="JOINT(1,0,2,0)" '
        'expr3="JOINT(1,0,3,0)" expr4="JOINT(1,0,4,0)" expr5="JOINT(1,0,8,0)" '
        'expr6="MOTION(1,0,8,0)"/>'
        '<Post_Request id="7" expr1="FX(2)" expr2="FX(2,21)" expr3="FY(22)" '
        'expr4="JOINT(2,1,3,0)" expr5="TZ(2)" expr6="JOINT(1,1,8,0) + MOTION(1,1,8,0)"/>'
        "</Model>"))
    res = pysolver.loads(text).run()
    assert res.success, res.message
    a, b, c = res.request(5), res.request(6), res.request(7)
    assert np.abs(b[:, 1:3]).max() > 1
    np.testing.assert_allclose(a[:, :4], b[:, :4], rtol=0, atol=1e-12)
    np.testing.assert_allclose(a[:, 7], b[:, 4] + b[:, 5], rtol=0, atol=1e-12)
    np.testing.assert_allclose(c[:, 0], -a[:, 1], rtol=0, atol=1e-12)
    np.testing.assert_allclose(c[:, 1], c[:, 0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(c[:, 2], c[:, 3], rtol=0, atol=1e-12)
    np.testing.assert_allclose(c[:, 4], c[:, 5], rtol=0, atol=1e-12)


def test_at_equilibrium_the_net_forces_on_each_body_balance():
    """Statics of the slider-crank without gravity under a 100 N push on the slider: the
    forces acting at a body's markers sum to zero (the crank: its pivot and pin markers; the
    slider: its wrist-pin marker, where the push acts too, and its slide marker), 1e-9 N."""
    text = CRANK.replace('grav_y="-9.81"', 'grav_y="0"').replace("</Model>", (
        '<Force_Vector_TwoBody id="9" i_marker_id="41" j_floating_marker_id="1" '
        'fx_expression="-100" fy_expression="0" fz_expression="0"/>'
        '<Post_Request id="5" expr1="FX(21) + FX(22)" expr2="FY(21) + FY(22)" '
        'expr3="FX(41) + FX(42)" expr4="FY(41) + FY(42)" expr5="JOINT(3,0,2,0)"/></Model>'))
    text = re.sub(r"<Simulate[^>]*/>", '<Simulate analysis_type="Static" end_time="0.1"/>',
                  text)
    res = pysolver.loads(text).run()
    assert res.success, res.message
    q = res.request(5)[-1]
    assert q[4] > 50                                   # the pin carries the push
    np.testing.assert_allclose(q[:4], 0, atol=1e-9)
