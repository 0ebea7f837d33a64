"""Motions (and LoadControl's Load_Function) driven by a spline of time or by a variable of
time: they load, and a motion follows the spline (its value, first and second derivative as
SciPy's on the same knots) on both kernels and in the XML, Adams and msolve forms; what reads
the state through a spline's x or a variable is refused, naming it."""
import numpy as np
import pytest
from scipy.interpolate import Akima1DInterpolator, CubicSpline

import pysolver
from pysolver import DeckError

from helpers import DECKS

# knots around t = 0 and through the run (1.9 s): the start is inside the data
X = np.array([-0.5, 0.4, 1.0, 1.3, 1.7, 2.8])
Y = 0.2 * np.sin(X) + 0.03 * X ** 2
POINTS = "\n".join(f"{a!r} {b!r}" for a, b in zip(X.tolist(), Y.tolist()))
SCIPY = {"CUBSPL": CubicSpline(X, Y, bc_type="natural"), "AKISPL": Akima1DInterpolator(X, Y)}
INNER = X[1:-1]


def marker_deck(expr, extra=""):
    """A 2 kg point driven along x by `expr` against a 1000 N/m spring (no gravity)."""
    return f"""<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
      <Reference_Marker id="1" body_id="1"/><Reference_Marker id="20" body_id="2"/>
      <Body_Point id="2" cg_id="20" mass="2"/>
      <Reference_Spline id="7">{POINTS}</Reference_Spline>{extra}
      <Force_Penalty id="1" expr="DX(20)" penalty="1000"/>
      <Motion_Marker id="1" i_marker_id="20" j_marker_id="1" direction="X" expr="{expr}"/>
      <Post_Request id="1" expr1="DX(20)" expr2="VX(20)" expr3="ACCX(20)"/>
      </Model><Param_Transient integr_tol="1e-10"/>
      <Simulate analysis_type="Transient" end_time="1.9" print_interval="0.01"/></MotionSolve>"""


def check_follows(res, spline, x, v, a):
    """x, v = the spline's value and slope at every row (1e-9); a its second derivative at
    every row (1e-9), on a knot where an AKISPL's jumps the right limit: an output row takes
    its accelerations and reactions exact at its state (ps_row_exact), the time derivative
    of the motion's rate from after the row, where the run goes on. (They were the
    corrector's derivative of the integrated velocity, which the error test does not hold:
    98 % of the rows within 1e-8 and one CUBSPL row 3.5e-5 off of 0.14, the knots' rows the
    left limit.)"""
    assert res.success, res.message
    t = res.t
    np.testing.assert_allclose(x, spline(t), rtol=0, atol=1e-9)
    np.testing.assert_allclose(v, spline(t, 1), rtol=0, atol=1e-9)
    on = np.isclose(t[:, None], INNER[None, :], rtol=0, atol=1e-12).any(axis=1)
    want = np.where(on, spline(t + 1e-12, 2), spline(t, 2))
    np.testing.assert_allclose(a, want, rtol=0, atol=1e-9)
    return on


@pytest.mark.parametrize("kernel", ["tapes", "generated"])
@pytest.mark.parametrize("fn", ["CUBSPL", "AKISPL"])
def test_a_motion_marker_follows_its_spline_of_time(fn, kernel):
    """x, v, a of the driven point are the spline's value and derivatives, and the reaction
    is m a + k x (1e-9 of its size), on both kernels; AKISPL's second derivative jumps at the
    four knots inside the run (by 0.017 .. 0.41 here), and the rows there hold its right
    limit."""
    res = pysolver.loads(marker_deck(f"{fn}(TIME, 0, 7)")).run(kernel=kernel)
    r = res.request(1)
    on = check_follows(res, SCIPY[fn], r[:, 0], r[:, 1], r[:, 2])
    assert on.sum() == 4
    want = 2.0 * r[:, 2] + 1000.0 * r[:, 0]
    np.testing.assert_allclose(res.motion(1), want, rtol=0, atol=1e-9 * np.abs(want).max())
    jumps = SCIPY["AKISPL"](INNER, 2) - SCIPY["AKISPL"](INNER - 1e-12, 2)
    assert np.abs(jumps).min() > 1e-2      # the left limits differ from the right ones


def test_a_motion_follows_a_variable_of_a_spline_of_time():
    """VARVAL(2) -> VARVAL(1) -> CUBSPL(TIME): the same motion as the spline itself."""
    variables = ('<Reference_Variable id="1" expr="CUBSPL(TIME, 0, 7)"/>'
                 '<Reference_Variable id="2" expr="VARVAL(1)"/>')
    res = pysolver.loads(marker_deck("VARVAL(2)", variables)).run()
    r = res.request(1)
    check_follows(res, SCIPY["CUBSPL"], r[:, 0], r[:, 1], r[:, 2])


JOINT_XML = f"""<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="1" body_id="1"/><Reference_Marker id="20" body_id="2" pos_x="0.3"/>
  <Reference_Marker id="21" body_id="2"/>
  <Body_Rigid id="2" cg_id="20" mass="2" inertia_xx="0.1" inertia_yy="0.1" inertia_zz="0.1"/>
  <Reference_Spline id="7">{POINTS}</Reference_Spline>
  <Constraint_Joint id="1" type="REVOLUTE" i_marker_id="21" j_marker_id="1"/>
  <Motion_Joint id="1" joint_id="1" expr="AKISPL(TIME, 0, 7)"/>
  <Post_Request id="1" expr1="AZ(21, 1)" expr2="WZ(21, 1, 1)" expr3="WDTZ(21, 1, 1)"/>
  </Model><Param_Transient integr_tol="1e-10"/>
  <Simulate analysis_type="Transient" end_time="1.9" print_interval="0.01"/></MotionSolve>"""

JOINT_ADM = f"""pysolver spline motion
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 2, CM = 20, IP = 0.1, 0.1, 0.1
MARKER/20, PART = 2, QP = 0.3, 0, 0
MARKER/21, PART = 2
JOINT/1, REVOLUTE, I = 21, J = 1
MOTION/1, JOINT = 1, ROTATION, FUNCTION = AKISPL(TIME, 0, 7)
SPLINE/7
, X = {", ".join(map(repr, X.tolist()))}
, Y = {", ".join(map(repr, Y.tolist()))}
REQUEST/1, F1 = AZ(21, 1)\\F2 = WZ(21, 1, 1)\\F3 = WDTZ(21, 1, 1)\\
INTEGRATOR/ERROR = 1e-10
END
"""

JOINT_PY = f"""from pysolver.msolve import *
model = Model()
ground = Part(ground=True)
pivot = Marker(body=ground)
arm = Part(mass=2, ip=[0.1, 0.1, 0.1])
arm.cm = Marker(body=arm, qp=Point(0.3, 0, 0))
pin = Marker(body=arm)
hinge = Joint(type="REVOLUTE", i=pin, j=pivot)
table = Spline(id=7, x={X.tolist()}, y={Y.tolist()})
Motion(joint=hinge, jtype="ROTATION", function="AKISPL(TIME, 0, 7)")
Request(f1="AZ(2, 1)", f2="WZ(2, 1, 1)", f3="WDTZ(2, 1, 1)")
Integrator(error=1e-10)
model.simulate(type="DYNAMICS", end=1.9, dtout=0.01)
"""


@pytest.mark.parametrize("fn", ["AKISPL", "CUBSPL"])
@pytest.mark.parametrize("kernel", ["tapes", "generated"])
@pytest.mark.parametrize("form", ["xml", "adm", "py"])
def test_a_motion_joint_turns_as_its_spline_of_time(tmp_path, form, kernel, fn):
    """A revolute driven by AKISPL(TIME, 0, 7) or CUBSPL (the natural spline in every form)
    as MotionSolve XML, an Adams MOTION/JOINT= with a SPLINE statement, and msolve classes
    (Spline, Motion(joint=)): AZ, WZ, WDTZ are the spline's value and derivatives on both
    kernels."""
    path = tmp_path / f"turn.{form}"
    text = {"xml": JOINT_XML, "adm": JOINT_ADM, "py": JOINT_PY}[form]
    path.write_text(text.replace("AKISPL(TIME, 0, 7)", f"{fn}(TIME, 0, 7)"))
    simulate = {"analysis_type": "TRANSIENT", "end_time": 1.9, "print_interval": 0.01}
    model = pysolver.load(path, simulate=simulate if form == "adm" else None)
    res = model.run(kernel=kernel)
    r = res.request(1)
    check_follows(res, SCIPY[fn], r[:, 0], r[:, 1], r[:, 2])


@pytest.mark.parametrize("expr, words", [
    ("CUBSPL(DX(20), 0, 7)", "it reads DX"),
    ("CUBSPL(TIME, 0, 7) + VARVAL(1)", "it reads VARVAL(1), which reads VX"),
    ("VARVAL(2)", "it reads VARVAL(2), which reads VARVAL(1), which reads VX"),
    ("VARVAL(9)", "the expression refers to variable id 9, which does not exist"),
    ("CUBSPL(TIME, 0, 8)", "the expression refers to spline id 8, which does not exist"),
])
def test_what_reads_the_state_through_a_spline_or_variable_is_named(expr, words):
    """The motion comes before the variables in the deck: they are read at the end, with the
    references."""
    variables = ('<Reference_Variable id="1" expr="2*VX(20)"/>'
                 '<Reference_Variable id="2" expr="VARVAL(1)"/>')
    text = marker_deck(expr).replace("</Model>", variables + "</Model>")
    with pytest.raises(DeckError) as err:
        pysolver.loads(text)
    assert err.value.attribute == "expr" and err.value.element == "Motion_Marker"
    assert str(err.value).endswith(words if "refers" in words else
                                   "a motion's expression must depend on time only; " + words)


def test_a_load_function_may_be_a_spline_of_time():
    """LoadControl's target from LINSPL(t, 0, 5) (a ramp to 20 N by 1 s, then held): the
    controller's target at every update is the broken line's value (1e-12); one of DZ is
    refused."""
    text = (DECKS / "loadcontrol_indenter.xml").read_text().replace(
        "Load_Function IF(t-1: 20*t, 20, IF(t-2: 20, 40, 40))", "Load_Function LINSPL(t, 0, 5)"
    ).replace("<Post_Request", '<Reference_Spline id="5">0 0 1 20 3 20</Reference_Spline>\n'
              "    <Post_Request").replace('end_time="3.0"', 'end_time="1.5"')
    res = pysolver.loads(text).run()
    assert res.success, res.message
    c = res.controller(1)
    np.testing.assert_allclose(c["target"], np.interp(c["time"], [0, 1, 3], [0, 20, 20]),
                               rtol=0, atol=1e-12)
    with pytest.raises(DeckError, match="Load_Function must depend on time only; it reads "
                       "DZ$") as err:
        pysolver.loads(text.replace("LINSPL(t, 0, 5)", "LINSPL(DZ(10), 0, 5)"))
    assert err.value.attribute == "Load_Function"


def test_a_spline_whose_data_starts_at_the_run_start():
    """Road profiles start their data at t = 0: the first row's acceleration (and reaction)
    is the spline's from the right (a natural CUBSPL's: 0; Adams' parabola on the left has
    0.0035). A central difference in time straddled the data's start, where Adams'
    extrapolation meets the curve, and gave -5262 for about 0.05."""
    knots = X - X[0]                                   # 0 .. 3.3
    text = marker_deck("CUBSPL(TIME, 0, 7)").replace(
        POINTS, "\n".join(f"{a!r} {b!r}" for a, b in zip(knots.tolist(), Y.tolist())))
    model = pysolver.loads(text)
    res = model.run()
    assert res.success, res.message
    spline = CubicSpline(knots, Y, bc_type="natural")
    r = res.request(1)
    assert spline(0.0, 2) == pytest.approx(0.0, abs=1e-14)
    assert r[0, 2] == pytest.approx(0.0, abs=1e-8)
    want = 2.0 * r[0, 2] + 1000.0 * r[0, 0]
    assert res.motion(1)[0] == pytest.approx(want, rel=1e-6)
    # a restart there (after a static, an assembly, a sensor's) takes the same start (its
    # Python form gave -18799 before it looked forward; csrc/control.c's takes the same)
    kernel = model.compile().kernel
    y = kernel.layout.initial_state()
    kernel.consistent_yp(0.0, y, initial=True)
    vx = kernel.layout.names.index("body2.vx")
    assert kernel.consistent_yp(0.0, y.copy())[vx] == pytest.approx(0.0, abs=1e-8)
    text = text.replace("</Model>", "</Model><Simulate analysis_type=\"Static\"/>")
    after = pysolver.loads(text).run()
    assert after.success and np.array_equal(after.t, res.t), after.message
    np.testing.assert_allclose(after.request(1)[1:, :2], r[1:, :2], rtol=0, atol=1e-9)


# a slider driven along x by a spline of time, carrying a pendulum hinged about y: a velocity
# jump of the slider is an impulse on the pendulum
SLIDER_PENDULUM = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="1" body_id="1" psi="1.5707963267948966" theta="1.5707963267948966"/>
  <Reference_Marker id="10" body_id="2"/>
  <Body_Rigid id="2" cg_id="10" mass="1" inertia_xx="1" inertia_yy="1" inertia_zz="1"/>
  <Reference_Marker id="11" body_id="2" psi="1.5707963267948966" theta="1.5707963267948966"/>
  <Reference_Marker id="12" body_id="2" theta="-1.5707963267948966"/>
  <Constraint_Joint id="1" type="TRANSLATIONAL" i_marker_id="11" j_marker_id="1"/>
  <Reference_Marker id="20" body_id="3" pos_z="-1"/>
  <Body_Rigid id="3" cg_id="20" mass="1" inertia_xx="0.1" inertia_yy="0.1" inertia_zz="0.1"/>
  <Reference_Marker id="21" body_id="3" theta="-1.5707963267948966"/>
  <Constraint_Joint id="2" type="REVOLUTE" i_marker_id="21" j_marker_id="12"/>
  <Reference_Spline id="5"{extrap}>0 0
0.5 1
1 1.5
1.5 1.7</Reference_Spline>
  <Motion_Joint id="1" joint_id="1" motion_type="T" val_type="{val}" expr="{fn}(TIME,0,5)"/>
  <Force_Gravity grav_z="-9.81"/>
  <Post_Request id="1" expr1="DX(20)"/></Model>
  <Simulate analysis_type="Transient" end_time="{end}" print_interval="0.01"/></MotionSolve>"""


def _pendulum(knots, end):
    """The pendulum's angle phi and rate by SciPy: between knots a compound pendulum under
    gravity (its pivot moves at a constant velocity), at each knot the impulse of the
    pivot's velocity jump dv, d(phi') = m l cos(phi) dv / (I + m l^2) (its angular momentum
    about the pivot's point is kept): `knots` [(time, dv)], the first at t = 0 from rest."""
    from scipy.integrate import solve_ivp
    m, length, inertia, g = 1.0, 1.0, 0.1, 9.81
    J = inertia + m * length ** 2
    state, pieces = np.array([0.0, 0.0]), []
    for (t0, dv), t1 in zip(knots, [k[0] for k in knots[1:]] + [end]):
        state[1] += m * length * np.cos(state[0]) * dv / J
        sol = solve_ivp(lambda t, s: [s[1], -m * g * length * np.sin(s[0]) / J], (t0, t1),
                        state, rtol=1e-12, atol=1e-13, dense_output=True)
        pieces.append((t0, t1, sol.sol))
        state = sol.y[:, -1].copy()
    def at(t):
        return np.array([next(f for a, b, f in pieces if a <= s <= b)(s) for s in t])
    return at


@pytest.mark.parametrize("tol, bound", [(1e-6, 1e-4), (1e-10, 1e-8)])
def test_a_velocity_jump_at_a_knot_is_an_impulse(tol, bound):
    """A LINSPL displacement motion jumps the slider's velocity at each knot (2 -> 1 -> 0.4
    m/s at 0.5 and 1 s); the run stops there and restarts with the impulse's velocities
    (it failed at t = 0.5 from integr_tol 1e-8, "error test failures"): the pendulum's angle
    and rate follow SciPy's compound pendulum with the impulse at each knot (measured 9e-6
    and 5e-9 in the angle's sine, 3e-5 and 2e-8 rad/s), and the log names the first knot."""
    deck = SLIDER_PENDULUM.format(fn="LINSPL", end=1.4, val="D", extrap="").replace(
        '<Post_Request id="1" expr1="DX(20)"/>',
        '<Post_Request id="1" expr1="DX(20,10)" expr2="WY(20)"/>')
    res = pysolver.loads(deck).run(integr_tol=tol)
    assert res.success, res.message
    ref = _pendulum([(0.0, 2.0), (0.5, -1.0), (1.0, -0.6)], 1.4)(res.t)
    np.testing.assert_allclose(res.request(1)[:, 0], -np.sin(ref[:, 0]), rtol=0, atol=bound)
    np.testing.assert_allclose(res.request(1)[:, 1], ref[:, 1], rtol=0, atol=10 * bound)
    assert res.log[0].startswith("t = 0.5: Motion_Joint 1's velocity jumps at a knot of "
                                 "Reference_Spline 5 (LINSPL); the run stops there")
    assert "(2 such knots before the run's end;" in res.log[0]


def test_a_motion_past_its_spline_s_data_restarts_at_the_last_knot():
    """Past its data's end a CUBSPL displacement motion follows Adams' extrapolation, which
    meets the curve at the last knot with a slope of its own: at integr_tol 1e-10 the run
    stopped there, and now restarts with the impulse."""
    res = pysolver.loads(SLIDER_PENDULUM.format(fn="CUBSPL", end=2.0, val="D", extrap="")
                         ).run(integr_tol=1e-10)
    assert res.success, res.message
    assert res.log[0].startswith("t = 1.5: Motion_Joint 1's velocity jumps at a knot of "
                                 "Reference_Spline 5 (CUBSPL)")


def _jumps(fn, val, extrap=False, order=""):
    from pysolver.solve import kinks
    deck = SLIDER_PENDULUM.format(fn=fn, end=2.0, val=val,
                                  extrap=' linear_extrap="TRUE"' if extrap else "")
    model = pysolver.loads(deck.replace(",5)", f",5{order})")).compile().model
    return [(x, rate) for x, _, _, rate in kinks._jumps(model, model.motions[1])]


def test_the_knots_where_a_motion_s_rates_jump():
    """Which knots make which rate of a motion jump: a displacement through LINSPL's inner
    knots its velocity, through AKISPL's its acceleration, CUBSPL's none; every spline's last
    knot (its extrapolation's kink) its velocity, except LINSPL's line with linear_extrap;
    a velocity motion one rate higher; a derivative order one lower; the first knot, at the
    run's start, never."""
    inner, last = [0.5, 1.0], [1.5]
    assert _jumps("LINSPL", "D") == [(x, "velocity") for x in inner + last]
    assert _jumps("LINSPL", "D", extrap=True) == [(x, "velocity") for x in inner]
    assert _jumps("AKISPL", "D") == [(x, "acceleration") for x in inner] + [(1.5, "velocity")]
    assert _jumps("CUBSPL", "D") == [(1.5, "velocity")]
    assert _jumps("LINSPL", "V") == [(x, "acceleration") for x in inner + last]
    assert _jumps("CUBSPL", "A") == []
    assert _jumps("AKISPL", "D", order=",1") == [(x, "velocity") for x in inner] + \
        [(1.5, "displacement")]
