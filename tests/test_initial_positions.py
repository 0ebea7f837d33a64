"""Initial positions the joints do not hold: the initial-conditions analysis assembles them
with the least change and res.log names the joints the deck violates and how far each body
moved (docs/deck-language.md, "Joints"; the limits: pysolver.build.icposition)."""
import math

import numpy as np
import pytest

import pysolver
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
    """J 0.5 m above I ran silently with the bar already turned (its centre of mass at
    (0.9695, 0.2551)). Now one line names the joint's distance and the bar's move: its centre
    of mass from (1, 0) to c, 1 m from the pivot (0, 0.5), turned by the angle of c - pivot."""
    model = pendulum(j='pos_y="0.5"')
    res = model.run()
    assert res.success, res.message
    c = res.request(1)[0, :2]
    assert np.hypot(c[0], c[1] - 0.5) == pytest.approx(1.0, abs=1e-12)
    shift, turn = np.hypot(c[0] - 1.0, c[1]), abs(math.atan2(c[1] - 0.5, c[0]))
    assert (shift, turn) == pytest.approx((0.2569, 0.2474), abs=1e-4)
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
