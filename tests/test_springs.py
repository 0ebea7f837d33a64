"""Force_SpringDamper against closed forms: a damped oscillator hung from ground and a torsion
spring wound through more than a turn; its numbers as sweep parameters; the statement; bad
input."""
import numpy as np
import pytest

import pysolver
from pysolver import DeckError

from helpers import TEST_DECKS


def damped(t, x0, v0, m, k, c):
    """x(t) of m x'' + c x' + k x = 0 (underdamped)."""
    wn, z = np.sqrt(k / m), c / (2 * np.sqrt(k * m))
    wd = wn * np.sqrt(1 - z * z)
    return np.exp(-z * wn * t) * (x0 * np.cos(wd * t) + (v0 + z * wn * x0) / wd * np.sin(wd * t))


@pytest.mark.parametrize("kernel", ["tapes", "generated"])
def test_a_hung_spring_and_a_wound_torsion_spring_move_as_the_closed_forms(kernel):
    """tests/decks/springs.xml at integr_tol 1e-9: the 2 kg point oscillates about
    -(L + m g / k) with the damped period and decay (measured 8.4e-10 m); the rotor spun at
    20 rad/s winds the torsion spring to 9.6 rad and back (the angle tracked through the turn;
    measured 7.4e-8 rad)."""
    res = pysolver.load(TEST_DECKS / "springs.xml").run(kernel=kernel)
    assert res.success, res.message
    t, q = res.t, res.request(1)
    y_eq = -(1 + 2 * 9.81 / 100)
    np.testing.assert_allclose(q[:, 0], y_eq + damped(t, -1.2 - y_eq, 0, 2, 100, 0.4),
                               rtol=0, atol=1e-8)
    theta = damped(t, 0, 20, 0.5, 2, 0.05)
    assert theta.max() > 3 * np.pi
    assert np.abs(np.angle(np.exp(1j * (q[:, 1] - theta)))).max() < 1e-6


ROTOR = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="1" body_id="1"/><Reference_Marker id="30" body_id="3"/>
  <Body_Rigid id="3" cg_id="30" mass="1" inertia_xx="1" inertia_yy="1" inertia_zz="0.5"/>
  <Reference_Marker id="20" body_id="2" pos_y="-1.2"/><Body_Point id="2" cg_id="20" mass="2"/>
  <Force_Gravity grav_y="-9.81"/>
  <Constraint_Joint id="1" type="REVOLUTE" i_marker_id="30" j_marker_id="1"/>
  <Force_SpringDamper id="1" type="TRANSLATIONAL" i_marker_id="20" j_marker_id="1"
    stiffness="100" damping="0.4" length="1"/>
  <Force_SpringDamper id="2" type="ROTATIONAL" i_marker_id="30" j_marker_id="1" stiffness="3"
    damping="0.1" length="{angle}" preload="0.4"/>
  <Post_Request id="1" expr1="DY(20)" expr2="AZ(30,1)"/>
  <Param_Static method="{method}" max_imbalance="1e-10" max_error="1e-10"/></Model>
  <Simulate analysis_type="Static" end_time="0"/></MotionSolve>"""


@pytest.mark.parametrize("method", ["FIM_S", "MKEAM"])
@pytest.mark.parametrize("angle", [0.2, 3.1])
def test_preloaded_springs_rest_where_their_laws_balance(method, angle):
    """Statics: the hung point at -(L + m g / k), the rotor on its preloaded torsion spring
    (reference angle 0.2 or 3.1 rad, preload 0.4 N m, k 3) at angle + 0.4 / 3, past pi in
    the second case: FIM_S's increments and MKEAM's swing keep the angle's turn."""
    res = pysolver.loads(ROTOR.format(method=method, angle=angle)).run(integr_tol=1e-9)
    assert res.success, res.message
    y, az = res.request(1)[-1, :2]
    assert y == pytest.approx(-(1 + 2 * 9.81 / 100), abs=1e-9)
    rest = angle + 0.4 / 3
    assert np.angle(np.exp(1j * (az - rest))) == pytest.approx(0, abs=1e-8)


def test_its_numbers_are_sweep_parameters():
    """Force_SpringDamper/1/stiffness changed by params= runs exactly as the edited deck (the
    same rows), and the point oscillates with the new frequency (measured 6.3e-8 m from the
    closed form over 3 s at integr_tol 1e-9)."""
    model = pysolver.load(TEST_DECKS / "springs.xml")
    paths = model.compile().parameters.paths()
    assert {f"Force_SpringDamper/1/{k}" for k in ("stiffness", "damping", "length",
                                                   "preload")} <= set(paths)
    res = model.run(params={"Force_SpringDamper/1/stiffness": 400.0})
    edited = pysolver.loads((TEST_DECKS / "springs.xml").read_text().replace(
        'stiffness="100"', 'stiffness="400"')).run()
    np.testing.assert_array_equal(res.request(1), edited.request(1))
    y_eq = -(1 + 2 * 9.81 / 400)
    np.testing.assert_allclose(res.request(1)[:, 0],
                               y_eq + damped(res.t, -1.2 - y_eq, 0, 2, 400, 0.4), atol=1e-7)
    # and the next run has the deck's stiffness again
    np.testing.assert_array_equal(model.run().request(1),
                                  pysolver.load(TEST_DECKS / "springs.xml").run().request(1))


def test_the_statement(tmp_path):
    deck = tmp_path / "spring.py"
    deck.write_text(
        "from pysolver.msolve import *\n"
        "PART(1, GROUND=True)\nMARKER(1, PART=1)\nMARKER(20, PART=2, QP=[0, -1.2, 0])\n"
        "POINT_MASS(2, MASS=2, CM=20)\nACCGRAV(JGRAV=-9.81)\n"
        "SPRINGDAMPER(1, I=20, J=1, TRANSLATION=True, K=100, C=0.4, LENGTH=1)\n"
        "REQUEST(1, F1='DY(20)')\nSIMULATE(TYPE='TRANSIENT', END=1, DTOUT=0.1)\n")
    model = pysolver.load(deck)
    assert model.springdampers[1].stiffness == 100.0
    res = model.run(integr_tol=1e-9)
    y_eq = -(1 + 2 * 9.81 / 100)
    np.testing.assert_allclose(res.request(1)[:, 0],
                               y_eq + damped(res.t, -1.2 - y_eq, 0, 2, 100, 0.4), atol=1e-8)


@pytest.mark.parametrize("attrs, attribute, words", [
    ('type="TRANSLATIONAL" i_marker_id="20" j_marker_id="1" stiffness="-1"', "stiffness",
     "expected"),
    ('type="TRANSLATIONAL" i_marker_id="20" j_marker_id="1" length="-1"', "length", ">= 0"),
    ('type="TRANSLATIONAL" i_marker_id="20" j_marker_id="99"', "j_marker_id",
     "marker 99 does not exist"),
    ('type="ROTATIONAL" i_marker_id="40" j_marker_id="42"', "j_marker_id", "on one body"),
    ('i_marker_id="20" j_marker_id="1"', "type", "required"),
])
def test_a_bad_spring_is_a_deck_error(attrs, attribute, words):
    text = (TEST_DECKS / "springs.xml").read_text().replace(
        "</Model>", f'<Force_SpringDamper id="9" {attrs}/></Model>')
    with pytest.raises(DeckError, match=words) as err:
        pysolver.loads(text)
    assert (err.value.element, err.value.attribute) == ("Force_SpringDamper", attribute)


def test_spdp_reports_the_springs_force_and_torque():
    """SPDP(1, jflag, comp, 0): the hung spring's force on the point (and its opposite on
    ground) along the line, equal to the law written out; SPDP(2, 0, 8, 0): the torsion
    spring's torque about z, -k AZU - c WZ, through its turns."""
    text = (TEST_DECKS / "springs.xml").read_text().replace("</Model>", (
        '<Post_Request id="7" expr1="SPDP(1,0,2,0)" expr2="SPDP(1,0,3,0)" expr3="SPDP(1,1,3,0)" '
        'expr4="(-100*(DM(20,1) - 1) - 0.4*VR(20,1))*DY(20,1)/DM(20,1)" '
        'expr5="SPDP(2,0,8,0)" expr6="-2*AZU(30,1) - 0.05*WZ(30,1,1)" expr7="SPDP(1,0,1,0)"/>'
        "</Model>"))
    res = pysolver.loads(text).run()
    assert res.success, res.message
    q = res.request(7)
    np.testing.assert_allclose(q[:, 0], 0, atol=1e-9)
    np.testing.assert_allclose(q[:, 1], q[:, 3], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(q[:, 2], -q[:, 3], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(q[:, 4], q[:, 5], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(q[:, 6], np.abs(q[:, 3]), rtol=1e-9, atol=1e-9)
