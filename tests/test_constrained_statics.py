"""Statics and quasi-statics of scenes with exact constraints (joints, motions, general
constraints, couplers): equilibria and reactions against hand calculations and virtual work."""
import math
import re

import numpy as np
import pytest

import pysolver
from pysolver import DeckError

from helpers import ROOT

JOINTS = ROOT / "decks" / "joints"
P = 100.0                       # N, pushing the slider toward the crank (-x)
R, L = 0.1, 0.4                 # crank and rod lengths of decks/joints/slider_crank.xml


def slider_crank(simulate, method="FIM_D"):
    """decks/joints/slider_crank.xml without gravity, a constant force -P x on the slider, and
    the given Simulate elements."""
    text = (JOINTS / "slider_crank.xml").read_text()
    text = text.replace('grav_y="-9.81"', 'grav_y="0"').replace(
        "</Model>", f'<Force_Vector_TwoBody id="9" i_marker_id="41" j_floating_marker_id="1" '
                    f'fx_expression="-{P}" fy_expression="0" fz_expression="0"/>'
                    f'<Param_Static method="{method}"/></Model>')
    return pysolver.loads(re.sub(r"<Simulate[^>]*/>", simulate, text))


def crank_closed_form(t):
    """Slider position and the crank torque that balances P (virtual work: T = P dx/dtheta)
    at crank angle 2 pi t."""
    th = 2 * np.pi * np.asarray(t)
    root = np.sqrt(L * L - R * R * np.sin(th) ** 2)
    dx = -R * np.sin(th) - R * R * np.sin(th) * np.cos(th) / root
    return R * np.cos(th) + root, P * dx


@pytest.mark.parametrize("kernel", ["tapes", "generated"])
@pytest.mark.parametrize("method", ["FIM_S", "MKEAM"])
def test_a_static_slider_crank_balances_its_load_by_virtual_work(method, kernel):
    """Statics at three crank angles set by the Motion_Joint (t = 0.1, 0.3, 0.7): the motion's
    reaction is the torque P dx/dtheta, the slider sits where the closed form puts it, the
    crank pivot carries the load along x (a slide passes no force along itself) and the
    slide takes the pivot's y force. MKEAM integrates with time standing still (its kernel's
    TIME a constant set to the command's time), so the crank motion holds its angle."""
    model = slider_crank("".join(f'<Simulate analysis_type="Static" end_time="{t}"/>'
                                 for t in (0.1, 0.3, 0.7)), method)
    res = model.run(kernel=kernel)
    assert res.success, res.message
    assert [s.success for s in res.statics] == [True] * 3
    t = res.t[1:]
    np.testing.assert_allclose(t, [0.1, 0.3, 0.7])
    x, torque = crank_closed_form(t)
    np.testing.assert_allclose(res.request(1)[1:, 0], x, rtol=0, atol=1e-10)
    np.testing.assert_allclose(res.motion(1)[1:], torque, rtol=1e-9)
    pivot, slide = res.joint(1)[1:], res.joint(4)[1:]
    np.testing.assert_allclose(pivot[:, 1], P, rtol=1e-9)
    np.testing.assert_allclose(slide[:, 2], -pivot[:, 2], rtol=0, atol=1e-9)


@pytest.mark.parametrize("method,atol_x,rtol_torque", [("FIM_D", 1e-8, 1e-6),
                                                       ("FIM_S", 1e-10, 1e-9)])
def test_a_quasi_static_slider_crank_follows_the_crank(method, atol_x, rtol_torque):
    """Quasi-statics over one crank turn (21 outputs; the crank angle passes pi): slider
    position and balancing torque at every row against the closed forms; FIM_D follows the
    path with IDA at integr_tol 1e-8 (measured 2.7e-9 m, torque 1.9e-8 relative), FIM_S
    solves each output (measured 1.4e-13 m)."""
    model = slider_crank('<Simulate analysis_type="Quasi-Static" end_time="1" '
                         'print_interval="0.05"/>', method)
    res = model.run()
    assert res.success, res.message
    np.testing.assert_allclose(res.t, np.linspace(0, 1, 21), atol=1e-12)
    x, torque = crank_closed_form(res.t)
    assert np.abs(res.request(1)[:, 0] - x).max() < atol_x
    assert np.abs(res.motion(1) - torque).max() < rtol_torque * P * R * 1.3
    # the mechanism's constraints hold at every row: the slide's coordinate is the slider's x
    np.testing.assert_allclose(res.request(1)[:, 6], res.request(1)[:, 0], rtol=0, atol=1e-10)


PENDULUM = (JOINTS / "pendulum_revolute.xml").read_text().replace(
    'pos_x="2" pos_y="0"', 'pos_x="1.2" pos_y="1.6"')


@pytest.mark.parametrize("method,y", [("FIM_S", 2.0), ("MKEAM", -2.0)])
def test_a_revolute_pendulum_rests_upright_or_hanging(method, y):
    """The 2 m revolute pendulum from 53 degrees above horizontal: FIM_S (Newton) finds the
    upright balance, MKEAM the hanging one; the pin carries m g; the transient that follows
    stays there (yp = 0 consistent at an equilibrium, the multipliers kept); upright is
    unstable (a negative stiffness along the free turn), hanging stable with compliance
    L / (m g) for a horizontal force at the bob (and Param_Static stability's share)."""
    text = re.sub(r"<Simulate[^>]*/>",
                  f'<Param_Static method="{method}"/><Simulate analysis_type="Static" '
                  'end_time="0"/><Simulate analysis_type="Transient" end_time="1" '
                  'print_interval="0.5"/>', PENDULUM)
    res = pysolver.loads(text).run()
    assert res.success, res.message
    np.testing.assert_allclose(res.request(1)[:, :2], [[0, y]] * 3, atol=1e-9)
    np.testing.assert_allclose(res.joint(1)[:, 2], 9.81, rtol=1e-9)
    c = res.compliance                         # coordinates body2.dx .. body2.rz
    assert res.statics[0].coordinates[0] == "body2.dx"
    assert (c[0, 0] < 0) == (y > 0)
    # a force F at the bob turns it by F L / k, k = -m g y + sqrt(stability) (m L^2 + I)
    k = -9.81 * y + 1e-5 * (4 + 1e-3)
    assert c[0, 0] == pytest.approx(4 / k, rel=1e-9)


RACK = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="5" body_id="1"/>
  <Reference_Marker id="6" body_id="1" pos_y="1" a00="0" a10="1" a20="0" a01="0" a11="0"
    a21="1" a02="1" a12="0" a22="0"/>
  <Reference_Marker id="60" body_id="6"/><Reference_Marker id="61" body_id="6" pos_x="0.1"/>
  <Body_Rigid id="6" cg_id="61" mass="1" inertia_xx="0.1" inertia_yy="0.1" inertia_zz="0.2"/>
  <Reference_Marker id="70" body_id="7" pos_y="1" a00="0" a10="1" a20="0" a01="0" a11="0"
    a21="1" a02="1" a12="0" a22="0"/>
  <Body_Rigid id="7" cg_id="70" mass="0.5" inertia_xx="1" inertia_yy="1" inertia_zz="1"/>
  <Force_Gravity grav_x="-9.81"/>
  <Force_Vector_TwoBody id="1" i_marker_id="70" j_floating_marker_id="5"
    fx_expression="2*TIME" fy_expression="0" fz_expression="0"/>
  <Constraint_Joint id="5" type="REVOLUTE" i_marker_id="60" j_marker_id="5"/>
  <Constraint_Joint id="6" type="TRANSLATIONAL" i_marker_id="70" j_marker_id="6"/>
  <Constraint_Coupler id="1" joint1_id="6" joint2_id="5" coefficients="1, -0.05"/>
  <Post_Request id="1" expr1="DZ(70,6,6)" expr2="AZ(60,5)"/>
  <Param_Static method="{method}"/></Model>{simulate}</MotionSolve>"""


def rack_angle(t):
    """Equilibria of the rack and the off-centre pinion: the pinion's weight (1 kg at 0.1 m)
    turns it by 0.981 sin(theta) N m against the rack's weight and a push 2 t N along x
    through the 0.05 m pitch radius."""
    return np.arcsin((0.5 * 9.81 * 0.05 - 0.05 * 2 * np.asarray(t)) / 0.981)


@pytest.mark.parametrize("method,theta", [("FIM_S", rack_angle(0)),
                                          ("MKEAM", -np.pi - rack_angle(0))])
def test_a_rack_and_a_pinion_rest_where_the_weights_balance(method, theta):
    """The coupler x = 0.05 theta holds with theta tracked through its turns. FIM_S (Newton,
    from theta = 0) finds the balance above (unstable, asin(0.25)); MKEAM lets the rack fall
    and the pinion swing back through half a turn to the stable one, -pi - asin(0.25)
    (measured 1e-16 m and 3e-15 rad at integr_tol 1e-8; 2.5e-6 rad when the relation was held
    at the rate level)."""
    text = RACK.format(method=method, simulate='<Simulate analysis_type="Static" '
                                               'end_time="0"/>')
    res = pysolver.loads(text).run(integr_tol=1e-8)
    assert res.success, res.message
    x, az = res.request(1)[-1, :2]
    assert x == pytest.approx(0.05 * theta, abs=1e-10)
    assert np.angle(np.exp(1j * (az - theta))) == pytest.approx(0, abs=1e-9)
    assert res.statics[0].imbalance < 1e-4


@pytest.mark.parametrize("method", ["FIM_D", "FIM_S"])
def test_a_quasi_static_rack_follows_its_growing_push(method):
    """Quasi-statics from 0 to 1 s while the push grows: theta(t) from the balance of
    moments at every row (FIM_D with IDA at integr_tol 1e-8, FIM_S per row)."""
    text = RACK.format(method=method, simulate='<Simulate analysis_type="Quasi-Static" '
                                               'end_time="1" print_interval="0.1"/>')
    res = pysolver.loads(text).run(integr_tol=1e-8)
    assert res.success, res.message
    th = rack_angle(res.t)
    np.testing.assert_allclose(res.request(1)[:, 1], th, rtol=0, atol=1e-7)
    np.testing.assert_allclose(res.request(1)[:, 0], 0.05 * th, rtol=0, atol=1e-8)


CIRCLE = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="1" body_id="1"/>
  <Reference_Marker id="9" body_id="2" pos_y="-1"/>
  <Body_Point id="2" cg_id="9" mass="0.5"/>
  <Force_Gravity grav_y="-9.81"/>
  <Force_Vector_TwoBody id="1" i_marker_id="9" j_floating_marker_id="1"
    fx_expression="3" fy_expression="0" fz_expression="0"/>
  <Constraint_General id="1" expr="DX(9)**2 + DY(9)**2 + DZ(9)**2 - 1"/>
  <Constraint_General id="2" expr="DZ(9)"/>
  <Post_Request id="1" expr1="DX(9)" expr2="DY(9)"/>
  <Param_Static method="FIM_S" max_imbalance="1e-10" max_error="1e-10"/></Model>
  <Simulate analysis_type="Static" end_time="0"/></MotionSolve>"""


def test_a_bead_on_a_general_constraint_leans_with_the_side_force():
    """A 0.5 kg point held on the unit circle by two Constraint_General expressions, pushed
    sideways by 3 N: it leans to tan(phi) = F / (m g), to within the imbalance asked
    (1e-10 N against a stiffness of about 5.7 N/m)."""
    res = pysolver.loads(CIRCLE).run()
    assert res.success, res.message
    phi = math.atan2(3.0, 0.5 * 9.81)
    np.testing.assert_allclose(res.request(1)[-1, :2], [math.sin(phi), -math.cos(phi)],
                               rtol=0, atol=1e-10)


@pytest.mark.parametrize("val_type,kind", [("V", "velocity"), ("A", "acceleration")])
def test_a_rate_motion_in_a_static_analysis_is_a_deck_error(val_type, kind):
    """Statics hold a motion's displacement; a velocity or acceleration motion has none."""
    text = (JOINTS / "slider_crank.xml").read_text().replace(
        'val_type="D"', f'val_type="{val_type}"')
    text = re.sub(r"<Simulate[^>]*/>", '<Simulate analysis_type="Static" end_time="0"/>', text)
    with pytest.raises(DeckError, match=f"Motion_Joint 1 gives a {kind}") as err:
        pysolver.loads(text)
    assert err.value.element == "Simulate"
