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


#: The trial-43 double pendulum (SI numbers): link 2 (1.2 kg) hangs from the ground at the
#: origin, link 3 (0.9 kg) from link 2 at P2; centres of mass C2 and C3 (the start frame).
C2, P2, C3 = np.array([0.294515, -0.189106]), np.array([0.673177, -0.432242]), np.array(
    [0.556351, -0.708560])
M2, M3, G = 1.2, 0.9, 9.81


def double_pendulum(unit, method, extra=""):
    """The double pendulum on two revolutes about z in metres or millimetres, with a
    Force_Bushing of translational stiffness only (1e6 N/m) on revolute 2, which holds its
    markers together: it adds no force at any assembled position. Request 1: AZ of each
    link; request 2: the centres of mass."""
    s = 1000.0 if unit == "mm" else 1.0

    def num(v):
        return f'"{v * s:.12g}"'

    def inertia(*v):
        return " ".join(f'inertia_{k}="{x * s * s:.12g}"' for k, x in zip(("xx", "yy", "zz"), v))

    k = f'"{1e6 / s:.12g}"'
    return pysolver.loads(f"""<MotionSolve><Model>
  <Units mass="KILOGRAM" length="{'MILLIMETER' if s > 1 else 'METER'}" time="SECOND"
    force="NEWTON"/>
  <Body_Rigid id="1" isground="TRUE"/><Reference_Marker id="1" body_id="1"/>
  <Reference_Marker id="20" body_id="2" pos_x={num(C2[0])} pos_y={num(C2[1])} psi="1.0"/>
  <Reference_Marker id="21" body_id="2"/>
  <Reference_Marker id="22" body_id="2" pos_x={num(P2[0])} pos_y={num(P2[1])}/>
  <Body_Rigid id="2" cg_id="20" mass="{M2}" {inertia(0.04, 0.06, 0.07)}/>
  <Reference_Marker id="30" body_id="3" pos_x={num(C3[0])} pos_y={num(C3[1])} psi="-0.4"/>
  <Reference_Marker id="31" body_id="3" pos_x={num(P2[0])} pos_y={num(P2[1])}/>
  <Body_Rigid id="3" cg_id="30" mass="{M3}" {inertia(0.02, 0.025, 0.03)}/>
  <Force_Gravity grav_x="0" grav_y={num(-G)} grav_z="0"/>
  <Constraint_Joint id="1" type="REVOLUTE" i_marker_id="21" j_marker_id="1"/>
  <Constraint_Joint id="2" type="REVOLUTE" i_marker_id="31" j_marker_id="22"/>
  <Force_Bushing id="2" i_marker_id="31" j_marker_id="22" kx={k} ky={k} kz={k}
    ktx="0" kty="0" ktz="0" cx="0" cy="0" cz="0" ctx="0" cty="0" ctz="0"/>
  <Post_Request id="1" expr1="AZ(21,1)" expr2="AZ(31,22)"/>
  <Post_Request id="2" expr1="DX(20)" expr2="DY(20)" expr3="DX(30)" expr4="DY(30)"/>
  <Param_Static method="{method}" {extra}/></Model>
  <Simulate analysis_type="Static"/></MotionSolve>""")


def hanging():
    """Both links hanging, by a hand balance: link 3's centre of mass straight below P2 (its
    moment about P2), and the weights at C2 and at P2 (link 3's, carried by the pin) straight
    below the origin (link 2's moment about the origin). The turns from the start frame, of
    link 2 and of link 3 against link 2, and the centres of mass there (SI)."""
    down = -math.pi / 2
    turn2 = down - math.atan2(*(M2 * C2 + M3 * P2)[::-1])
    turn3 = down - math.atan2(*(C3 - P2)[::-1])
    return ((turn2, (turn3 - turn2 + math.pi) % (2 * math.pi) - math.pi),
            [*rotate(C2, turn2), *(rotate(P2, turn2) + [0, -np.linalg.norm(C3 - P2)])])


def rotate(v, a):
    return np.array([math.cos(a) * v[0] - math.sin(a) * v[1],
                     math.sin(a) * v[0] + math.cos(a) * v[1]])


@pytest.mark.parametrize("method", ["FIM_S", "FIM_D", "MKEAM"])
@pytest.mark.parametrize("unit", ["m", "mm"])
def test_a_bushing_on_a_hinge_leaves_a_double_pendulum_hanging_in_any_unit(unit, method):
    """Trial 43: a translational bushing on revolute 2 (1000 N/mm) made FIM_S fail in
    millimetres (an imbalance of 9e4 after 11 iterations) while metres converged. Each
    step tlimit or alimit cut short left the joint apart by its second-order error, which the
    bushing turned into a large force. Now such a step is followed back onto the
    constraints and the multipliers are set to the static reactions there. Every method
    then finds both links hanging, in either unit, and each pin carries the weight below
    it."""
    s = 1000.0 if unit == "mm" else 1.0
    res = double_pendulum(unit, method).run()
    assert res.success, res.message
    angles, centres = hanging()
    np.testing.assert_allclose(res.request(1)[-1, :2], angles, rtol=0, atol=1e-9)
    np.testing.assert_allclose(res.request(2)[-1, :4] / s, centres, rtol=0, atol=1e-9)
    # the reaction on each link at its pin: the weight below it (N in both units), no moment
    np.testing.assert_allclose(res.joint(1)[-1, 1:8], [0, (M2 + M3) * G, 0, 0, 0, 0, 0],
                               rtol=0, atol=1e-9)
    np.testing.assert_allclose(res.joint(2)[-1, 1:8], [0, M3 * G, 0, 0, 0, 0, 0],
                               rtol=0, atol=1e-9)


def test_the_double_pendulum_converges_alike_in_metres_and_millimetres():
    """With the same physical step limit (tlimit 20 m) FIM_S takes the same iterations in
    both units to the same angles; the default tlimit, 20 deck length units, cuts each step
    to 20 mm in millimetres, which takes more iterations to the same answer."""
    runs = {(unit, tlimit): double_pendulum(unit, "FIM_S", f'tlimit="{tlimit}"').run()
            for unit, tlimit in (("m", 20), ("mm", 20000), ("mm", 20))}
    assert all(res.success for res in runs.values())
    its = {key: res.statics[-1].iterations for key, res in runs.items()}
    assert its[("m", 20)] == its[("mm", 20000)] < its[("mm", 20)] <= 40
    for res in runs.values():
        np.testing.assert_allclose(res.request(1)[-1, :2], runs[("m", 20)].request(1)[-1, :2],
                                   rtol=0, atol=1e-10)


def test_a_static_that_runs_out_of_iterations_names_both_passes():
    """max_num_iter 2 on the millimetre double pendulum: both passes use their two
    iterations; the message says so, how often tlimit cut a pass's steps, and the best
    imbalance either pass reached (the point returned)."""
    res = double_pendulum("mm", "FIM_S", 'max_num_iter="2"').run()
    assert not res.success and res.status == -300
    st = res.statics[-1]
    assert not st.success and st.iterations == 4
    assert res.message == (
        "static analysis at t = 0: FIM_S did not converge: plain Newton used all 2 iterations "
        "(max_num_iter), then Newton with step halving used all 2 iterations (max_num_iter) "
        "(tlimit cut 2 of the 2 increments of plain Newton to 20 deck length units); the best "
        f"imbalance reached {st.imbalance:.3g} (max_imbalance 0.0001) with increment or "
        f"constraint violation {st.error:.3g}")
    # the best point reached is better than the start (imbalance: link 2's moment, N mm)
    start = double_pendulum("mm", "FIM_S", 'max_num_iter="1"').run()
    assert st.imbalance < start.statics[-1].imbalance
