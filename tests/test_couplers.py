"""Constraint_Coupler: linear relations between joint coordinates (gears, a rack and pinion,
coupled slides) against closed forms; clear errors."""
import numpy as np
import pytest

import pysolver
from pysolver import DeckError

from helpers import TEST_DECKS


def wrapped(a):
    return np.angle(np.exp(1j * np.asarray(a)))


def test_geared_rotors_slides_and_a_rack_move_as_the_closed_forms():
    """tests/decks/couplers.xml, no forces: rotors geared w1 + 2 w2 = 0 start from the given
    w1 = 3, w2 taking what the gear needs (-1.5; the least change of both, which took the
    given spin down to 2.4, was the rule before the velocities a deck gives were kept), and
    keep it; slides x1 + 2 x2 = 0 from the given v1 = 0.4: (0.4, -0.2); a rack x = 0.05 theta
    of a pinion spun at 1 rad/s: (0.05, 1). Rates exact at every row, the positions too: the slides' directly,
    the rotations' through angles tracked over every turn (the gears' angles pass pi many
    times): the gears' relation within 1e-8 rad after 4 s (measured 9.9e-10 at integr_tol
    1e-9; 2.9e-7 when rotations were held at the rate level only), the rack's within 1e-9 m
    (measured 1.5e-10)."""
    res = pysolver.load(TEST_DECKS / "couplers.xml").run()
    assert res.success, res.message
    q, a, t = res.request(1), res.request(2), res.t
    np.testing.assert_allclose(q[:, 0], 3.0, rtol=1e-12)
    np.testing.assert_allclose(q[:, 1], -1.5, rtol=1e-12)
    np.testing.assert_allclose(q[:, 2], 0.4 * t, rtol=0, atol=1e-12)
    np.testing.assert_allclose(q[:, 3], -0.2 * t, rtol=0, atol=1e-12)
    w = 1.0
    np.testing.assert_allclose(q[:, 5], w, rtol=1e-12)
    np.testing.assert_allclose(q[:, 6], 0.05 * w, rtol=1e-12)
    assert np.abs(wrapped(a[:, 0] + 2 * a[:, 1])).max() < 1e-8
    assert np.abs(q[:, 4] - 0.05 * w * t).max() < 1e-9
    assert np.abs(wrapped(a[:, 2] - w * t)).max() < 1e-6


RACK = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="5" body_id="1"/>
  <Reference_Marker id="6" body_id="1" pos_y="1" a00="0" a10="1" a20="0" a01="0" a11="0"
    a21="1" a02="1" a12="0" a22="0"/>
  <Reference_Marker id="60" body_id="6"/>
  <Body_Rigid id="6" cg_id="60" mass="1" inertia_xx="0.1" inertia_yy="0.1" inertia_zz="0.2"/>
  <Reference_Marker id="70" body_id="7" pos_y="1" a00="0" a10="1" a20="0" a01="0" a11="0"
    a21="1" a02="1" a12="0" a22="0"/>
  <Body_Rigid id="7" cg_id="70" mass="0.5" inertia_xx="1" inertia_yy="1" inertia_zz="1"/>
  <Force_Gravity grav_x="-9.81"/>
  <Constraint_Joint id="5" type="REVOLUTE" i_marker_id="60" j_marker_id="5"/>
  <Constraint_Joint id="6" type="TRANSLATIONAL" i_marker_id="70" j_marker_id="6"/>
  {coupler}
  <Post_Request id="1" expr1="DZ(70,6,6)" expr2="WZ(60,5,5)"/>
  <Param_Transient integr_tol="1e-9"/></Model>
  <Simulate analysis_type="Transient" end_time="2" print_interval="0.1"/></MotionSolve>"""
COUPLER = '<Constraint_Coupler id="1" joint1_id="6" joint2_id="5" coefficients="1, -0.05"/>'


def test_a_falling_rack_spins_its_pinion():
    """A 0.5 kg rack falls along x under gravity and turns a pinion (I = 0.2, radius 0.05 m):
    x = a t^2 / 2 with a = -m g / (m + I / r^2) within 1e-8 of the 0.12 m it falls (measured
    2e-9 at integr_tol 1e-9 when the relation was held at the velocity level), and the
    pinion's rate a t / r within 1e-9 (4e-11)."""
    res = pysolver.loads(RACK.format(coupler=COUPLER)).run()
    assert res.success, res.message
    q, t = res.request(1), res.t
    acc = -0.5 * 9.81 / (0.5 + 0.2 / 0.05 ** 2)
    np.testing.assert_allclose(q[:, 0], acc * t ** 2 / 2, rtol=0, atol=1e-8)
    np.testing.assert_allclose(q[:, 1], acc * t / 0.05, rtol=0, atol=1e-9)


def test_the_python_statement(tmp_path):
    deck = tmp_path / "gears.py"
    deck.write_text("from pysolver.msolve import *\n"
                    "PART(1, GROUND=True)\nMARKER(1, PART=1)\nMARKER(2, PART=1, QP=[1, 0, 0])\n"
                    "MARKER(20, PART=2)\nPART(2, MASS=1, CM=20, IP=[0.6, 0.6, 1], WZ=3)\n"
                    "MARKER(30, PART=3, QP=[1, 0, 0])\nPART(3, MASS=1, CM=30, IP=[0.3, 0.3, 0.5])\n"
                    "JOINT(1, TYPE='REVOLUTE', I=20, J=1)\nJOINT(2, TYPE='REVOLUTE', I=30, J=2)\n"
                    "COUPLER(1, JOINTS=[1, 2], TYPE='R:R', SCALES=[2])\n"
                    "REQUEST(1, F1='WZ(20,1,1)', F2='WZ(30,2,2)')\n"
                    "SIMULATE(TYPE='TRANSIENT', END=1, DTOUT=0.5)\n")
    model = pysolver.load(deck)
    assert model.couplers[1].scales == (1.0, 2.0)
    res = model.run()
    assert res.success, res.message
    np.testing.assert_allclose(res.request(1)[:, :2], [[3.0, -1.5]] * 3, rtol=1e-12)


@pytest.mark.parametrize("coupler, attribute, words", [
    ('joint1_id="6" joint2_id="9" coefficients="1, 2"', "joint2_id", "joint 9 does not exist"),
    ('joint1_id="6" joint2_id="5" freedom_2="T" coefficients="1, 2"', "freedom_2",
     "not a coordinate of REVOLUTE"),
    ('joint1_id="6" joint2_id="5" coefficients="1, 2, 3"', "coefficients", "expected 2"),
    ('joint1_id="6" joint2_id="5" coefficients="0 0"', "coefficients", "not all zero"),
    ('joint2_id="5" coefficients="1"', "joint1_id", "required"),
])
def test_a_bad_coupler_is_a_deck_error(coupler, attribute, words):
    with pytest.raises(DeckError) as err:
        pysolver.loads(RACK.format(coupler=f'<Constraint_Coupler id="1" {coupler}/>'))
    e = err.value
    assert (e.element, e.attribute) == ("Constraint_Coupler", attribute)
    assert words in str(e)
