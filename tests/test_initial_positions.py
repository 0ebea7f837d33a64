"""Initial positions the joints do not hold: the initial-conditions analysis assembles them
with the least change in the mass metric, the same pose in any units, and res.log names the
joints the deck violates and how far each body moved (docs/deck-language.md, "Joints"; the
metric: pysolver.build.icmetric; the limits: pysolver.build.icposition)."""
import math

import numpy as np
import pytest

import pysolver
from pysolver.rotations import e_from_rot, rot_313, rot_from_e
from pysolver.solve.driver import start_state

from helpers import DECKS

#: A 1 kg bar on a REVOLUTE: its centre of mass at (1, 0), the joint's I marker at its body's
#: (1 m from it) and J on ground at `j` (trial 43, item 3: bad.py); `i` turns I.
PENDULUM = """<MotionSolve><Model>
<Body_Rigid id="1" isground="TRUE"/><Reference_Marker id="1" body_id="1"/>
<Reference_Marker id="2" body_id="1" {j}/>
<Reference_Marker id="20" body_id="2" pos_x="1"/><Reference_Marker id="21" body_id="2" {i}/>
<Body_Rigid id="2" cg_id="20" mass="1" inertia_xx="0.1" inertia_yy="0.1" inertia_zz="0.1"/>
<Force_Gravity grav_x="0" grav_y="-9.81" grav_z="0"/>
<Constraint_Joint id="1" type="REVOLUTE" i_marker_id="21" j_marker_id="2"/>
<Post_Request id="1" expr1="DX(20)" expr2="DY(20)" expr3="DZ(20)" expr4="AZ(20)"/>
</Model><Simulate analysis_type="Transient" end_time="0.1" print_interval="0.1"/></MotionSolve>"""
TAIL = ' and were assembled, the least change: {} (docs/deck-language.md, "Joints")'


def pendulum(j="", i=""):
    return pysolver.loads(PENDULUM.format(j=j, i=i))


def position_lines(res):
    return [line for line in res.log if line.startswith("initial conditions: the positions")]


def test_a_joint_half_a_metre_apart_is_named_with_how_far_the_body_moved():
    """J 0.5 m above I ran silently with the bar already turned. Now one line names the
    joint's distance and the bar's move: its centre of mass from (1, 0) to c, 1 m from the
    pivot (0, 0.5), turned by the angle of c - pivot; the least change in the mass metric
    (1 kg, 0.1 kg m^2 about z: the bar mostly turns, 0.4256 rad, where the same weight on
    metres and radians turned it by 0.2474 and millimetres by 0.4594)."""
    model = pendulum(j='pos_y="0.5"')
    res = model.run()
    assert res.success, res.message
    c = res.request(1)[0, :2]
    assert np.hypot(c[0], c[1] - 0.5) == pytest.approx(1.0, abs=1e-12)
    shift, turn = np.hypot(c[0] - 1.0, c[1]), abs(math.atan2(c[1] - 0.5, c[0]))
    assert (shift, turn) == pytest.approx((0.1247, 0.4256), abs=1e-4)
    assert position_lines(res) == [
        "initial conditions: the positions the deck gives violate Constraint_Joint 1 (distance "
        "0.5)" + TAIL.format(f"body2 moved by {shift:.4g} and turned by {turn:.4g} rad")]
    again = model.run()                         # the start remembered, and its note with it
    assert again.log == res.log
    np.testing.assert_array_equal(again.y[0], res.y[0])


def test_a_revolute_tilted_by_a_tenth_of_a_radian_is_named():
    """zI 0.1 rad from zJ about x (through I and the centre of mass): the bar turns back by
    0.1 rad about x and its centre of mass stays, so only the turn is named."""
    res = pendulum(i='theta="0.1"').run()
    assert res.success, res.message
    assert position_lines(res) == [
        "initial conditions: the positions the deck gives violate Constraint_Joint 1 (angle "
        "0.1 rad)" + TAIL.format("body2 turned by 0.1 rad")]
    np.testing.assert_allclose(res.request(1)[0, :3], [1.0, 0.0, 0.0], atol=1e-12)


def test_both_at_once_name_the_distance_and_the_angle():
    res = pendulum(j='pos_y="0.5"', i='theta="0.1"').run()
    assert res.success, res.message
    line, = position_lines(res)
    assert line.startswith("initial conditions: the positions the deck gives violate "
                           "Constraint_Joint 1 (distance 0.5, angle 0.1 rad) and were "
                           "assembled, the least change: body2 moved by ")


def test_motions_that_move_the_bodies_are_named_too():
    """A rotation motion whose ic_disp turns the bar 0.2 rad about the pivot (its centre of
    mass moves by the chord 2 sin 0.1); a point mass a displacement motion takes 0.2 m along
    x (a point body has no turn)."""
    motion = ('<Motion_Joint id="3" joint_id="1" motion_type="R" val_type="V" expr="1" '
              'ic_disp="0.2"/><Post_Request')
    res = pysolver.loads(PENDULUM.format(j="", i="").replace("<Post_Request", motion, 1)).run()
    assert position_lines(res) == [
        "initial conditions: the positions the deck gives violate Motion_Joint 3 (ic_disp, "
        "angle 0.2 rad)" + TAIL.format(f"body2 moved by {2 * math.sin(0.1):.4g} and turned by "
                                       "0.2 rad")]
    point = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
<Reference_Marker id="1" body_id="1"/><Reference_Marker id="10" body_id="2"/>
<Body_Point id="2" cg_id="10" mass="2"/>
<Motion_Marker id="1" i_marker_id="10" j_marker_id="1" direction="X" expr="0.2+0.1*TIME"/>
</Model><Simulate analysis_type="Transient" end_time="0.1" print_interval="0.1"/>
</MotionSolve>"""
    assert position_lines(pysolver.loads(point).run()) == [
        "initial conditions: the positions the deck gives violate Motion_Marker 1 (distance "
        "0.2)" + TAIL.format("body2 moved by 0.2")]


def test_markers_that_coincide_to_rounding_are_silent():
    """J at 0.1 + 0.2 - 0.3 (5.6e-17) and turned by 1e-15 rad: nothing moves past the limit,
    and the log says nothing; a consistent deck neither."""
    assert pendulum().run().log == pendulum(
        j=f'pos_y="{0.1 + 0.2 - 0.3!r}" theta="1e-15"').run().log == [
        'planar scene: 1 body integrated in (x, y, rz), the revolutes\' out-of-plane equations '
        'left out (docs/numerics.md, "Planar scenes")']


def test_the_limit_follows_the_run_tolerance_down_to_a_millionth():
    """The scene is 1 m (the pivot to the centre of mass): a 1e-4 m offset moves the bar by
    less than integr_tol 1e-3 of it (silent) and by more than 1e-6 (named); a 1e-7 m offset is
    below the floor of 1e-6 at any tolerance."""
    model = pendulum(j='pos_y="1e-4"')
    assert position_lines(model.run()) == []
    line, = position_lines(model.run(integr_tol=1e-6))
    assert "Constraint_Joint 1 (distance 0.0001)" in line
    assert position_lines(pendulum(j='pos_y="1e-7"').run(integr_tol=1e-10)) == []


@pytest.mark.parametrize("path", sorted(
    p for p in DECKS.rglob("*") if p.suffix in (".xml", ".acf", ".py")
    and not p.name.startswith("make")), ids=lambda p: str(p.relative_to(DECKS)))
def test_the_example_decks_are_assembled_as_given(path):
    """Every example deck, in every form, starts where it says, even at the tightest
    tolerance (the limit then 1e-6 of the scene, 1e-6 rad)."""
    compiled = pysolver.load(path).compile()
    start_state(compiled.model, compiled.kernel, 1e-14)
    assert not [n for n in getattr(compiled.kernel, "start_notes", [])
                if n.startswith("initial conditions: the positions")]


#: A bar of mass m in `unit` (s of them to the metre): its centre of mass at (1, 0, 0) m with
#: inertia `inertia` about it (kg m^2), a REVOLUTE's I at the origin turned by psi, theta
#: (3-1-3) and its J on ground at (0, oy, oz) m, no gravity.
BAR = """<MotionSolve><Model>
<Units mass="KILOGRAM" length="{unit}" time="SECOND" force="NEWTON"/>
<Body_Rigid id="1" isground="TRUE"/><Reference_Marker id="1" body_id="1"/>
<Reference_Marker id="2" body_id="1" pos_y="{oy!r}" pos_z="{oz!r}"/>
<Reference_Marker id="20" body_id="2" pos_x="{s!r}"/>
<Reference_Marker id="21" body_id="2" psi="{psi!r}" theta="{theta!r}"/>
<Body_Rigid id="2" cg_id="20" mass="{m!r}" inertia_xx="{ix!r}" inertia_yy="{iy!r}"
            inertia_zz="{iz!r}"/>
<Constraint_Joint id="1" type="REVOLUTE" i_marker_id="21" j_marker_id="2"/>
</Model><Simulate analysis_type="Transient" end_time="0.01" print_interval="0.01"/>
</MotionSolve>"""
#: (J's (oy, oz), I's (psi, theta), m, inertia): the trial's pendulum (a planar scene), the
#: same with zI tilted 0.1 rad (3-D), a turn about no principal axis of an unequal inertia,
#: and J 1.5 m off the 1 m bar (where Gauss-Newton steps converge slowly: icmetric)
BARS = {"offset 0.5": ((0.5, 0.0), (0.0, 0.0), 1.0, (0.1, 0.1, 0.1)),
        "offset 0.5, tilt 0.1": ((0.5, 0.0), (0.0, 0.1), 1.0, (0.1, 0.1, 0.1)),
        "skew": ((0.3, 0.2), (0.7, 0.3), 2.0, (0.2, 0.25, 0.4)),
        "far": ((1.5, 0.3), (0.2, 0.4), 1.0, (0.1, 0.12, 0.15))}
UNITS = [("METER", 1.0), ("MILLIMETER", 1000.0)]


def bar(case, unit, s):
    (oy, oz), (psi, theta), m, inertia = BARS[case]
    ix, iy, iz = (v * s * s for v in inertia)
    return pysolver.loads(BAR.format(unit=unit, s=s, oy=oy * s, oz=oz * s, psi=psi,
                                     theta=theta, m=m, ix=ix, iy=iy, iz=iz))


def pose(names, y, s):
    """(centre of mass in m, rotation matrix) of body 2 in the state y (a planar scene's
    rz about z)."""
    at = {n: v for n, v in zip(names, y)}
    c = np.array([at["body2.x"], at["body2.y"], at.get("body2.z", 0.0)]) / s
    if "body2.rz" in at:
        a = at["body2.rz"]
        return c, np.array([[math.cos(a), -math.sin(a), 0.0], [math.sin(a), math.cos(a), 0.0],
                            [0.0, 0.0, 1.0]])
    return c, rot_from_e([at[f"body2.e{k}"] for k in range(4)])


@pytest.mark.parametrize("case", sorted(BARS))
def test_millimetres_assemble_to_the_pose_metres_do(case):
    """The trial's pendulum turned by 0.459 rad in millimetres and 0.247 in metres (each
    Newton step the least change with millimetres and radians weighed alike). Now the same
    pose: positions 1000 times the metres', Euler parameters (or rz) equal, to 1e-9."""
    runs = []
    for unit, s in UNITS:
        res = bar(case, unit, s).run()
        assert res.success, res.message
        runs.append((res.state_names, res.y[0], s))
    (names, y_m, _), (names_mm, y_mm, _) = runs
    assert names == names_mm
    length = np.array([n.split(".")[1] in ("x", "y", "z") for n in names])
    body = np.array([n.startswith("body2.") and n.split(".")[1] in
                     ("x", "y", "z", "rz", "e0", "e1", "e2", "e3") for n in names])
    np.testing.assert_allclose(y_mm[body & length], 1000.0 * y_m[body & length], rtol=0,
                               atol=1e-9 * 1000.0)
    np.testing.assert_allclose(y_mm[body & ~length], y_m[body & ~length], rtol=0, atol=1e-9)


def rodrigues(phi):
    """The rotation matrix of the rotation vector phi (complex entries too)."""
    theta = np.sqrt(np.sum(phi * phi))
    K = np.array([[0, -phi[2], phi[1]], [phi[2], 0, -phi[0]], [-phi[1], phi[0], 0]])
    return np.eye(3) + np.sin(theta) / theta * K + (1 - np.cos(theta)) / theta ** 2 * K @ K


@pytest.mark.parametrize("unit, s", UNITS)
@pytest.mark.parametrize("case", sorted(BARS))
def test_the_assembly_is_the_least_change_in_the_mass_metric(case, unit, s):
    """The assembled pose against SciPy's SLSQP on the same REVOLUTE (d = 0, xI.zJ = yI.zJ
    = 0) over the centre of mass's move dc and the turn phi (a rotation vector), minimising
    m |dc|^2 + phi' diag(I) phi: the same pose to SLSQP's precision (1e-6), a size no larger
    (1e-12 relative), and at the assembled pose the optimality condition, grad f in the
    span of the constraints' gradients, to 1e-9 (complex-step gradients)."""
    import scipy.optimize
    (oy, oz), (psi, theta), m, inertia = BARS[case]
    D = np.array(inertia)
    res = bar(case, unit, s).run()
    assert res.success, res.message
    c, R = pose(res.state_names, res.y[0], s)
    c0, RI, pJ = np.array([1.0, 0.0, 0.0]), rot_313(psi, theta, 0.0), np.array([0.0, oy, oz])

    def g(z):
        R = rodrigues(z[3:])
        axes = R @ RI
        return np.concatenate([c0 + z[:3] + R @ np.array([-1.0, 0.0, 0.0]) - pJ, axes[2, :2]])

    def f(z):
        return m * z[:3] @ z[:3] + z[3:] @ (D * z[3:])
    e = e_from_rot(R)
    n = np.linalg.norm(e[1:])
    ours = np.concatenate([c - c0, e[1:] * 2.0 * math.atan2(n, e[0]) / n])
    best = scipy.optimize.minimize(f, np.full(6, 1e-3), method="SLSQP",
                                   constraints=[{"type": "eq", "fun": g}],
                                   options={"ftol": 1e-16, "maxiter": 500})
    assert best.success, best.message
    np.testing.assert_allclose(ours, best.x, rtol=0, atol=1e-6)
    assert f(ours) <= best.fun * (1 + 1e-12)
    assert np.abs(g(ours)).max() <= 1e-12
    grad = np.concatenate([2 * m * ours[:3], 2 * D * ours[3:]])
    dg = np.array([g(ours + 1e-30j * np.eye(6)[k]).imag / 1e-30 for k in range(6)])
    nu = np.linalg.lstsq(dg, grad, rcond=None)[0]
    assert np.linalg.norm(grad - dg @ nu) <= 1e-9 * np.linalg.norm(grad)


@pytest.mark.parametrize("unit, s", UNITS)
@pytest.mark.parametrize("case", sorted(BARS))
def test_the_c_restart_assembles_the_same_pose(case, unit, s):
    """The restart LoadControl and sensors take in C (ps_restart_consistent: its own
    assembly, csrc/control.c) from the deck's positions lands where the run's start does
    (pysolver.build.consistent, in Python), to 1e-10 of the scene."""
    from pysolver.build.bindings import ffi, lib
    from pysolver.build.restart import Restart
    model = bar(case, unit, s)
    res = model.run()
    compiled = model.compile()
    k = compiled.kernel
    start_state(compiled.model, k, 1e-3)
    y, yp = k.layout.initial_state(), np.zeros(k.ny)
    fb = ffi.from_buffer
    assert lib.ps_restart_consistent(k.m, k.d, Restart.of(k).r, 0.0, fb("double[]", y),
                                     fb("double[]", yp)) == lib.PS_OK
    (c, R), (c_run, R_run) = pose(res.state_names, y, s), pose(res.state_names, res.y[0], s)
    np.testing.assert_allclose(c, c_run, rtol=0, atol=1e-10)
    np.testing.assert_allclose(R, R_run, rtol=0, atol=1e-10)
