"""Motion_Joint: a slider-crank driven through its crank's revolute against the closed-form
kinematics and the drive torque of the energy balance; a cylindrical joint driven in
translation and rotation; the Python statement MOTION(JOINT=); clear errors."""
import json

import numpy as np
import pytest

import pysolver
from pysolver import DeckError

from helpers import ROOT

JOINTS = ROOT / "decks" / "joints"
REFERENCE = json.loads((ROOT / "benchmarks" / "data" / "joint_references.json").read_text())


def test_slider_crank_follows_the_closed_form_through_whole_turns():
    """decks/joints/slider_crank.xml: the crank's revolute driven at AZ = 2 pi TIME for two
    turns (the angle passes pi four times). At integr_tol 1e-9 the slider's x (0.3-0.5 m)
    within 1e-9 m of r cos th + sqrt(l^2 - r^2 sin^2 th) (measured 1.6e-11), its velocity
    within 1e-8 m/s (1.7e-10), the rod angle within 1e-9 rad, the crank angle on 2 pi t within
    1e-9 rad (1.4e-10), and the motion's reaction (the drive torque, up to 1.24 N m) within
    5e-5 N m of dE/dt / omega (1.4e-5 at one row, t = 0.5 s, median 4e-8: it rests on the
    accelerations, BDF's y'; the force balance at that row, by least squares, is off by
    6e-6 too)."""
    ref = REFERENCE["problems"]["slider_crank"]
    res = pysolver.load(JOINTS / "slider_crank.xml").run(integr_tol=1e-9)
    assert res.success, res.message
    t = np.array(ref["times"])
    rows = np.searchsorted(res.t, t)
    assert np.allclose(res.t[rows], t, rtol=0, atol=1e-12)
    q = res.request(1)[rows]

    def wrapped(a):
        return np.abs(np.angle(np.exp(1j * a)))
    assert np.abs(q[:, 0] - ref["slider_x"]).max() < 1e-9
    assert np.abs(q[:, 1] - ref["slider_vx"]).max() < 1e-8
    assert wrapped(q[:, 4] - ref["rod_angle"]).max() < 1e-9
    assert wrapped(q[:, 5] - 2 * np.pi * t).max() < 1e-9
    assert np.abs(res.motion(1)[rows] - ref["drive_torque_z"]).max() < 5e-5
    # the slide's coordinate DZ(42, 3, 3) is the slider's x
    assert np.abs(q[:, 6] - q[:, 0]).max() < 1e-12


CYLINDER = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="1" body_id="1"/>
  <Reference_Marker id="20" body_id="2"/>
  <Body_Rigid id="2" cg_id="20" mass="2" inertia_xx="0.1" inertia_yy="0.1" inertia_zz="0.15"/>
  <Force_Gravity grav_z="-9.81"/>
  <Constraint_Joint id="1" type="CYLINDRICAL" i_marker_id="20" j_marker_id="1"/>
  {motions}
  <Post_Request id="1" expr1="DZ(20,1,1)" expr2="AZ(20,1)" expr3="VZ(20,1,1,1)"
    expr4="WZ(20,1,1)"/>
  <Param_Transient integr_tol="1e-9"/></Model>
  <Simulate analysis_type="Transient" end_time="1" print_interval="0.05"/></MotionSolve>"""


def test_a_cylindrical_joint_driven_in_both_coordinates():
    """A body on a vertical cylindrical joint: its height follows a velocity motion (T, V:
    0.3 m/s from rest height 0) and its turn a displacement motion (R, D: 5 sin t, through
    +-pi); the lifting force is m (g + 0) and the torque about z is I_zz theta''."""
    motions = ('<Motion_Joint id="1" joint_id="1" motion_type="T" val_type="V" expr="0.3"/>'
               '<Motion_Joint id="2" joint_id="1" motion_type="R" expr="5*SIN(TIME)"/>')
    res = pysolver.loads(CYLINDER.format(motions=motions)).run()
    assert res.success, res.message
    q = res.request(1)
    assert np.abs(q[:, 0] - 0.3 * res.t).max() < 1e-9
    assert np.abs(np.angle(np.exp(1j * (q[:, 1] - 5 * np.sin(res.t))))).max() < 1e-9
    assert np.abs(q[:, 3] - 5 * np.cos(res.t)).max() < 1e-8
    np.testing.assert_allclose(res.motion(1), 2 * 9.81, rtol=1e-6)
    np.testing.assert_allclose(res.motion(2), -0.15 * 5 * np.sin(res.t), atol=1e-5)


def test_the_python_statement_drives_a_joint(tmp_path):
    """MOTION(id, JOINT=, TYPE="ROTATION", FUNCTION=) is a Motion_Joint."""
    deck = tmp_path / "crank.py"
    deck.write_text(
        "from pysolver.msolve import *\n"
        "PART(1, GROUND=True)\nMARKER(1, PART=1)\n"
        "MARKER(20, PART=2, QP=[0.5, 0, 0])\nMARKER(21, PART=2)\n"
        "PART(2, MASS=1, IP=[1e-3, 1e-3, 1e-3], CM=20)\n"
        "JOINT(1, TYPE='REVOLUTE', I=21, J=1)\n"
        "MOTION(1, JOINT=1, TYPE='ROTATION', FUNCTION='2*PI*TIME')\n"
        "REQUEST(1, F2='AZ(21,1)')\n"
        "SIMULATE(TYPE='TRANSIENT', END=0.75, DTOUT=0.25)\n")
    model = pysolver.load(deck)
    assert model.motions[1].joint == 1
    res = model.run(integr_tol=1e-9)
    assert res.success, res.message
    angle = res.request(1)[:, 1]
    assert np.abs(np.angle(np.exp(1j * (angle - 2 * np.pi * res.t)))).max() < 1e-9


@pytest.mark.parametrize("motion, attribute, words", [
    ('joint_id="9" expr="TIME"', "joint_id", "joint 9 does not exist"),
    ('joint_id="2" expr="TIME"', "joint_id", "SPHERICAL"),
    ('joint_id="1" expr="TIME"', "motion_type", "CYLINDRICAL: say which"),
    ('joint_id="3" motion_type="T" expr="TIME"', "motion_type", "not a coordinate of "
                                                               "REVOLUTE"),
    ('joint_id="3" expr="DX(20)"', "expr", "time only"),
    ('expr="TIME"', "joint_id", "required"),
])
def test_a_bad_joint_motion_is_a_deck_error_naming_it(motion, attribute, words):
    extra = ('<Reference_Marker id="30" body_id="3"/><Reference_Marker id="31" body_id="3"/>'
             '<Body_Rigid id="3" cg_id="30" mass="1" inertia_xx="1" inertia_yy="1" '
             'inertia_zz="1"/>'
             '<Constraint_Joint id="2" type="SPHERICAL" i_marker_id="31" j_marker_id="1"/>'
             '<Reference_Marker id="40" body_id="4"/><Body_Rigid id="4" cg_id="40" mass="1" '
             'inertia_xx="1" inertia_yy="1" inertia_zz="1"/>'
             '<Constraint_Joint id="3" type="REVOLUTE" i_marker_id="40" j_marker_id="1"/>')
    text = CYLINDER.format(motions=extra + f'\n  <Motion_Joint id="5" {motion}/>')
    with pytest.raises(DeckError) as err:
        pysolver.loads(text)
    e = err.value
    assert (e.element, e.attribute, e.line) == ("Motion_Joint", attribute, 8)
    assert words in str(e)


@pytest.mark.parametrize("motion, attribute, words", [
    ('ic_disp="0.1" expr="TIME"', "ic_disp", "ic_disp = 0.1 is not used: it is the "
     "integration constant of a V or A motion, and this one is val_type D, whose function "
     "gives the displacement itself"),
    ('val_type="V" ic_disp="0" ic_vel="0.1" expr="1"', "ic_vel", "ic_vel = 0.1 is not used: "
     "it is the integration constant of an A motion, and this one is val_type V, whose "
     "function gives the velocity itself"),
])
def test_an_initial_condition_the_motion_does_not_integrate_is_not_used(motion, attribute,
                                                                       words):
    """MotionView and Inspire write ic_disp and ic_vel on every motion; only V and A motions
    integrate from them (docs/deck-language.md): another is a DeckWarning when not 0."""
    extra = ('<Reference_Marker id="40" body_id="4"/><Body_Rigid id="4" cg_id="40" mass="1" '
             'inertia_xx="1" inertia_yy="1" inertia_zz="1"/>'
             '<Constraint_Joint id="3" type="REVOLUTE" i_marker_id="40" j_marker_id="1"/>')
    text = CYLINDER.format(motions=extra + f'\n  <Motion_Joint id="5" joint_id="3" {motion}/>')
    with pytest.warns(pysolver.DeckWarning) as caught:
        model = pysolver.loads(text)
    assert [(w.message.line, w.message.attribute, w.message.reason) for w in caught] == [
        (8, attribute, words)]
    assert getattr(model.motions[5], attribute) is None      # not used


def test_a_motion_joint_shares_the_motion_ids():
    """Motion_Joint and Motion_Marker are both MOTION: one id space."""
    motions = ('<Motion_Joint id="1" joint_id="1" motion_type="T" expr="0"/>'
               '<Motion_Marker id="1" i_marker_id="20" j_marker_id="1" direction="X" '
               'expr="0"/>')
    with pytest.raises(DeckError, match="duplicate motion id 1"):
        pysolver.loads(CYLINDER.format(motions=motions))


def test_initial_conditions_of_velocity_and_acceleration_motions():
    """ic_disp and ic_vel are the integration constants: a crank turned at 1 rad/s (V) from
    ic_disp 0.5 rad sits at 0.5 + t, one driven at zero acceleration (A) from ic_disp 2.5 and
    ic_vel 2 at 2.5 + 2 t (wrapped: it passes pi), and a slider driven at 0.2 m/s from ic_disp
    0.1 at 0.1 + 0.2 t; the bodies start there, moved with the least change from the deck's
    own (zero) positions and velocities; at integr_tol 1e-9."""
    deck = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
      <Reference_Marker id="1" body_id="1"/>
      <Reference_Marker id="20" body_id="2"/><Reference_Marker id="30" body_id="3"/>
      <Reference_Marker id="40" body_id="4"/>
      <Body_Rigid id="2" cg_id="20" mass="1" inertia_xx="1" inertia_yy="1" inertia_zz="1"/>
      <Body_Rigid id="3" cg_id="30" mass="1" inertia_xx="1" inertia_yy="1" inertia_zz="1"/>
      <Body_Rigid id="4" cg_id="40" mass="1" inertia_xx="1" inertia_yy="1" inertia_zz="1"/>
      <Constraint_Joint id="1" type="REVOLUTE" i_marker_id="20" j_marker_id="1"/>
      <Constraint_Joint id="2" type="REVOLUTE" i_marker_id="30" j_marker_id="1"/>
      <Constraint_Joint id="3" type="TRANSLATIONAL" i_marker_id="40" j_marker_id="1"/>
      <Motion_Joint id="1" joint_id="1" val_type="V" expr="1" ic_disp="0.5"/>
      <Motion_Joint id="2" joint_id="2" val_type="A" expr="0" ic_disp="2.5" ic_vel="2"/>
      <Motion_Joint id="3" joint_id="3" val_type="V" expr="0.2" ic_disp="0.1"/>
      <Post_Request id="1" expr1="AZ(20,1)" expr2="AZ(30,1)" expr3="DZ(40,1,1)"/>
      <Param_Transient integr_tol="1e-9"/></Model>
      <Simulate analysis_type="Transient" end_time="1" print_interval="0.25"/></MotionSolve>"""
    res = pysolver.loads(deck).run()
    assert res.success, res.message
    q, t = res.request(1), res.t

    def wrapped(a):
        return np.abs(np.angle(np.exp(1j * a)))
    assert wrapped(q[:, 0] - (0.5 + t)).max() < 1e-8
    assert wrapped(q[:, 1] - (2.5 + 2 * t)).max() < 1e-7        # measured 4.6e-8
    assert np.abs(q[:, 2] - (0.1 + 0.2 * t)).max() < 1e-9


def test_two_motions_on_one_joint_coordinate_name_the_first():
    motions = ('<Motion_Joint id="5" joint_id="1" motion_type="T" expr="0"/>'
               '<Motion_Joint id="6" joint_id="1" motion_type="T" expr="TIME"/>')
    with pytest.raises(DeckError) as err:
        pysolver.loads(CYLINDER.format(motions=motions))
    e = err.value
    assert (e.element, e.id, e.attribute) == ("Motion_Joint", 6, "motion_type")
    assert "Motion_Joint 5 already drives T of joint 1" in str(e)
