"""Action-only scalar forces (Force_Scalar_TwoBody is_action_only, Adams SFORCE ACTIONONLY): a
force along z of J or a torque about it on I's body alone; J's body only gives the
direction."""
import numpy as np
import pytest

import pysolver

DECK = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="1" body_id="1"/>
  <Reference_Marker id="20" body_id="2"/>
  <Body_Rigid id="2" cg_id="20" mass="2" inertia_xx="0.2" inertia_yy="0.2" inertia_zz="0.2"/>
  <Reference_Marker id="30" body_id="3" pos_x="1" psi="0.4" theta="0.3"/>
  <Body_Rigid id="3" cg_id="30" mass="3" inertia_xx="0.3" inertia_yy="0.3" inertia_zz="0.5"/>
  <Force_Scalar_TwoBody id="1" type="FORCE" is_action_only="TRUE" i_marker_id="20"
    j_marker_id="30" val="1.5"/>
  <Force_Scalar_TwoBody id="2" type="TORQUE" is_action_only="TRUE" i_marker_id="20"
    j_marker_id="30" val="0.8"/>
  <Post_Request id="1" expr1="DX(20)" expr2="DY(20)" expr3="DZ(20)" expr4="WX(20)"
    expr5="WY(20)" expr6="WZ(20)" expr7="VM(30)" expr8="WX(30)**2+WY(30)**2+WZ(30)**2"/>
  <Post_Request id="2" expr1="SFORCE(1,0,2,0)" expr2="SFORCE(1,0,3,0)" expr3="SFORCE(1,0,4,0)"
    expr4="SFORCE(1,1,2,0)" expr5="SFORCE(2,0,6,0)" expr6="SFORCE(2,0,8,0)" expr7="SFORCE(2,1,7,0)"/>
  <Param_Transient integr_tol="1e-10"/></Model>
  <Simulate analysis_type="Transient" end_time="1" print_interval="0.1"/></MotionSolve>"""


@pytest.mark.parametrize("kernel", ["tapes", "generated"])
def test_action_only_force_and_torque_push_one_body_along_z_of_j(kernel):
    """J (body 3, turned, free) only points: body 2 moves as 1.5 N / 2 kg along z of J and
    turns as 0.8 N m / 0.2 kg m^2 about it (a uniform inertia: w' = T / I exactly); body 3
    feels nothing. SFORCE reports the
    force on I in global axes and nothing on J."""
    res = pysolver.loads(DECK).run(kernel=kernel)
    assert res.success, res.message
    z = np.array([np.sin(0.4) * np.sin(0.3), -np.cos(0.4) * np.sin(0.3), np.cos(0.3)])
    t, q, f = res.t, res.request(1), res.request(2)
    np.testing.assert_allclose(q[:, :3], 0.5 * (1.5 / 2) * np.outer(t ** 2, z), atol=1e-10)
    w = 0.8 * z / 0.2
    np.testing.assert_allclose(q[:, 3:6], np.outer(t, w), atol=1e-9)
    np.testing.assert_allclose(q[:, 6:8], 0.0, atol=1e-12)
    np.testing.assert_allclose(f[:, :3], np.outer(np.ones_like(t), 1.5 * z), atol=1e-12)
    np.testing.assert_allclose(f[:, 4:6], [[0.8 * z[0], 0.8 * z[2]]] * len(t), atol=1e-12)
    np.testing.assert_allclose(f[:, [3, 6]], 0.0, atol=1e-15)


def test_the_statement(tmp_path):
    deck = tmp_path / "a.py"
    deck.write_text("from pysolver.msolve import *\nPART(1, GROUND=True)\nMARKER(1, PART=1)\n"
                    "MARKER(9, PART=2)\nPOINT_MASS(2, MASS=2, CM=9)\n"
                    "SFORCE(1, I=9, J=1, TRANSLATION=True, ACTIONONLY=True, FUNCTION='3')\n"
                    "REQUEST(1, F1='DZ(9)')\nSIMULATE(TYPE='TRANSIENT', END=1, DTOUT=0.5)\n")
    model = pysolver.load(deck)
    assert model.sforces[1].action_only
    np.testing.assert_allclose(model.run(integr_tol=1e-9).request(1)[:, 0],
                               0.75 * np.array([0, 0.25, 1]),
                               atol=1e-10)
