"""Constraint_General: an expression of displacements and time held at zero exactly (the
joints' formulation), against closed forms; redundancy with a joint; clear errors."""
import numpy as np
import pytest
from scipy.special import ellipk

import pysolver
from pysolver import DeckError

from helpers import TEST_DECKS

CIRCLE = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="1" body_id="1"/>
  <Reference_Marker id="9" body_id="2" pos_x="1"/>
  <Body_Point id="2" cg_id="9" mass="0.5"/>
  <Force_Gravity grav_y="-9.81"/>
  {extra}
  <Post_Request id="1" expr1="DX(9)" expr2="DY(9)" expr3="VX(9)" expr4="VY(9)" expr5="DM(9)"/>
  </Model>
  <Simulate analysis_type="Transient" end_time="{T!r}" print_interval="{dt!r}"/></MotionSolve>"""
SPHERE = '<Constraint_General id="3" expr="DX(9)**2 + DY(9)**2 + DZ(9)**2 - 1"/>'
PERIOD = float(4 * ellipk(0.5) / np.sqrt(9.81))      # 1 m, released horizontally


def test_a_point_on_a_sphere_swings_as_the_pendulum():
    """A point mass held at 1 m from the origin by DX^2 + DY^2 + DZ^2 - 1 = 0, released
    horizontally: at the bottom at T/4 and 3T/4 with speed sqrt(2 g L), back at T (complete
    elliptic integral), the distance 1 at every row; within 1e-8 at integr_tol 1e-11."""
    res = pysolver.loads(CIRCLE.format(extra=SPHERE, T=PERIOD, dt=PERIOD / 4)).run(
        integr_tol=1e-11)
    assert res.success, res.message
    q = res.request(1)
    np.testing.assert_allclose(q[:, 4], 1.0, rtol=0, atol=1e-11)
    assert np.abs(q[[1, 3], 0]).max() < 1e-8 and np.abs(q[[1, 3], 1] + 1).max() < 1e-8
    np.testing.assert_allclose(np.abs(q[[1, 3], 2]), np.sqrt(2 * 9.81), rtol=1e-8)
    assert np.abs(q[4, :2] - [1, 0]).max() < 1e-8


def test_general_constraints_hold_at_every_row_on_both_kernels():
    """tests/decks/gcon.xml (also in the Jacobian and generated-C checks): a sphere, a driven
    x (a function of time) and a product of a rotation and a height, each zero at every row
    within the tolerance."""
    model = pysolver.load(TEST_DECKS / "gcon.xml")
    for kind in ("tapes", "generated"):
        res = model.run(kernel=kind)
        assert res.success, res.message
        q = res.request(1)
        assert np.abs(q[:, 0] - 1).max() < 1e-8
        assert np.abs(q[:, 1] - 0.5 - 0.1 * np.sin(2 * res.t)).max() < 1e-8
        assert np.abs(q[:, 2]).max() < 1e-8


def test_a_general_constraint_that_repeats_a_joint_is_removed_and_named():
    """A spherical joint at the origin holds the body's centre at 1 m already; the expression
    (checked first, as the joints are) adds nothing and the log names it."""
    rigid = CIRCLE.replace('<Body_Point id="2" cg_id="9" mass="0.5"/>',
                           '<Reference_Marker id="8" body_id="2"/><Body_Rigid id="2" cg_id="9" '
                           'mass="0.5" inertia_xx="0.01" inertia_yy="0.01" inertia_zz="0.01"/>')
    extra = SPHERE + '<Constraint_Joint id="1" type="SPHERICAL" i_marker_id="8" j_marker_id="1"/>'
    res = pysolver.loads(rigid.format(extra=extra, T=PERIOD, dt=PERIOD / 4)).run(
        integr_tol=1e-9)
    assert res.success, res.message
    assert any("redundant constraints removed (1): Constraint_General 3" in line
               for line in res.log), res.log
    assert np.abs(res.request(1)[:, 4] - 1).max() < 1e-9


def test_the_python_statement(tmp_path):
    deck = tmp_path / "sphere.py"
    deck.write_text("from pysolver.msolve import *\n"
                    "PART(1, GROUND=True)\nMARKER(1, PART=1)\n"
                    "MARKER(9, PART=2, QP=[1, 0, 0])\nPOINT_MASS(2, MASS=0.5, CM=9)\n"
                    "ACCGRAV(JGRAV=-9.81)\n"
                    "GCON(3, FUNCTION='DX(9)**2 + DY(9)**2 + DZ(9)**2 - 1')\n"
                    "REQUEST(1, F1='DM(9)')\nSIMULATE(TYPE='TRANSIENT', END=0.5, DTOUT=0.1)\n")
    model = pysolver.load(deck)
    assert model.gcons[3].text.replace(" ", "") == "DX(9)**2+DY(9)**2+DZ(9)**2-1"
    res = model.run(integr_tol=1e-9)
    assert res.success, res.message
    assert np.abs(res.request(1)[:, 0] - 1).max() < 1e-9


@pytest.mark.parametrize("gcon, attribute, words", [
    ('expr="ACCX(9)"', "expr", "found ACCX"),
    ('expr="DX(99)"', "expr", "marker id 99"),
    ('expr="DX(9)" i_marker_id="77"', "i_marker_id", "marker 77 does not exist"),
    ('', "expr", "give expr, or a user subroutine"),
    ('expr="USER(9)"', "script_name", "needs the routine"),
])
def test_a_bad_general_constraint_is_a_deck_error(gcon, attribute, words):
    text = CIRCLE.format(extra=f'<Constraint_General id="4" {gcon}/>', T=1.0, dt=0.5)
    with pytest.raises(DeckError) as err:
        pysolver.loads(text)
    e = err.value
    assert (e.element, e.attribute) == ("Constraint_General", attribute)
    assert words in str(e)


def test_a_general_constraint_that_is_not_finite_fails_the_run():
    """1/TIME at t = 0: a failed Result naming the problem, not an exception."""
    text = CIRCLE.format(extra='<Constraint_General id="7" expr="DZ(9) - 1/TIME"/>', T=1.0,
                         dt=0.5)
    res = pysolver.loads(text).run()
    assert not res.success
    assert "initial conditions" in res.message
