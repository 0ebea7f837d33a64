"""A joint's initial conditions (Adams' JOINT IC, ICTRAN, ICROT; XML ic_tran_disp ..
ic_rot_vel; the msolve statement and class): the run starts from them (the coordinate
DZ(I, J, J) or AZ(I, J) at its displacement to assembly tolerance, its rate at its velocity)
and then moves freely, as the closed forms say; a motion on the same coordinate wins with a
warning; bad input is one DeckError naming file, line, element and attribute."""
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pysolver
from pysolver import DeckError, DeckWarning

G = 9.81

#: A 2 kg slider on a TRANSLATIONAL joint along ground's z axis tilted 30 degrees from
#: vertical (J = 10: REULER 0, 30D, 0 turns z about x), gravity -y; {ic} the joint's IC.
SLIDER = """slider
UNITS/FORCE=NEWTON, MASS=KILOGRAM, LENGTH=METER, TIME=SECOND
PART/1, GROUND
MARKER/10, PART=1, QP=0, 0, 0, REULER=0, 30D, 0
PART/2, MASS=2, CM=20, IP=1,1,1
MARKER/20, PART=2
MARKER/21, PART=2, REULER=0, 30D, 0
JOINT/5, TRANSLATIONAL, I=21, J=10
{ic}
ACCGRAV/JGRAV=-9.81
REQUEST/1, F2=DZ(21,10,10), F3=VZ(21,10,10,10)
{extra}
END
"""


def _write(tmp_path, text, name="deck.adm", end=1.0):
    adm = tmp_path / name
    adm.write_text(text)
    acf = tmp_path / (adm.stem + ".acf")
    acf.write_text(f"{adm.name}\n\nSIMULATE/DYNAMICS, END={end}, DTOUT=0.05\nSTOP\n")
    return adm, acf


def _slide(d, v, t):
    """DZ and its rate of the slider from (d, v) at times t: zJ = (0, -sin 30, cos 30) (a
    30 degree turn about x), its acceleration along zJ a = g . zJ = +g / 2."""
    z = np.array([0.0, -np.sin(np.radians(30)), np.cos(np.radians(30))])
    a = float(np.array([0.0, -G, 0.0]) @ z)
    return d + v * t + 0.5 * a * t * t, v + a * t


def test_a_translational_ic_starts_the_slider_there_and_lets_it_slide(tmp_path):
    """IC = 0.3, -1.5: DZ(21, 10, 10) = 0.3 at t = 0 (the deck puts the markers together:
    DZ 0 there) and its rate -1.5; then the free slide under gravity along the tilted axis,
    d + v t + a t^2 / 2 with a = g . zJ = +4.905 m/s^2, to 1e-7 (measured 1.03e-8, IDA's
    first step at integr_tol 1e-9), its rate to 1e-8: the IC holds nothing during the run
    (the slider leaves 0.3 at once)."""
    _, acf = _write(tmp_path, SLIDER.format(ic=", IC = 0.3, -1.5", extra=""))
    res = pysolver.load(acf).run(integr_tol=1e-9)
    assert res.success, res.message
    q = res.request(1)
    assert abs(q[0, 1] - 0.3) < 1e-12 and abs(q[0, 2] + 1.5) < 1e-12
    d, v = _slide(0.3, -1.5, res.t)
    assert np.abs(q[:, 1] - d).max() < 1e-7
    assert np.abs(q[:, 2] - v).max() < 1e-8
    assert abs(q[-1, 1] - 0.3) > 0.5
    # the assembly moved the slider 0.3 along the axis: the run's log says so
    assert res.log[-1] == (
        "initial conditions: the positions the deck gives violate Constraint_Joint 5 "
        "(initial translation, distance 0.3) and were assembled, the least change: body2 "
        "moved by 0.3 (docs/deck-language.md, \"Joints\")")


def test_a_displacement_alone_starts_at_rest(tmp_path):
    """IC = -0.2 (one number: the displacement; the velocity is the bodies' own, 0 here)."""
    _, acf = _write(tmp_path, SLIDER.format(ic=", IC = -0.2", extra=""))
    res = pysolver.load(acf).run(integr_tol=1e-9)
    d, v = _slide(-0.2, 0.0, res.t)
    assert np.abs(res.request(1)[:, 1] - d).max() < 1e-7
    assert np.abs(res.request(1)[:, 2] - v).max() < 1e-8


PENDULUM = """pendulum
UNITS/FORCE=NEWTON, MASS=KILOGRAM, LENGTH=METER, TIME=SECOND
PART/1, GROUND
MARKER/1, PART=1
PART/2, MASS=1, CM=20, IP=1e-6, 1e-6, 1e-6
MARKER/20, PART=2, QP=1, 0, 0
MARKER/21, PART=2
JOINT/1, REVOLUTE, I=21, J=1, IC = {ic}
ACCGRAV/JGRAV=-9.81
REQUEST/1, F2=AZ(21,1), F3=WZ(21,1,1)
END
"""


def test_a_revolute_ic_starts_the_pendulum_at_that_angle_and_rate(tmp_path):
    """IC = 30D, 2 on a pendulum (a 1 kg point 1 m along I's x, the deck hanging it
    horizontal, AZ = 0): AZ(21, 1) = pi/6 and WZ = 2 at t = 0, then SciPy's pendulum
    th'' = -g/l cos th from there (th from horizontal, l = 1, inertia 1e-6 about the CM):
    within 1e-6 rad over 1 s (measured 2e-8)."""
    _, acf = _write(tmp_path, PENDULUM.format(ic="30D, 2"))
    res = pysolver.load(acf).run(integr_tol=1e-9)
    assert res.success, res.message
    q = res.request(1)
    assert abs(q[0, 1] - np.pi / 6) < 1e-12 and abs(q[0, 2] - 2.0) < 1e-12
    inertia = 1.0 + 1e-6
    ref = solve_ivp(lambda t, s: [s[1], -G * np.cos(s[0]) / inertia], (0, 1),
                    [np.pi / 6, 2.0], t_eval=res.t, rtol=1e-12, atol=1e-12)
    assert np.abs(np.angle(np.exp(1j * (q[:, 1] - ref.y[0])))).max() < 1e-6
    assert np.abs(q[:, 2] - ref.y[1]).max() < 1e-5


CYLINDER = """cylinder
UNITS/FORCE=NEWTON, MASS=KILOGRAM, LENGTH=METER, TIME=SECOND
PART/1, GROUND
MARKER/1, PART=1
PART/2, MASS=2, CM=20, IP=0.1, 0.1, 0.15
MARKER/20, PART=2
JOINT/1, CYLINDRICAL, I=20, J=1, ICTRAN = 0.25, 0.5, ICROT = 90D, 3
ACCGRAV/KGRAV=-9.81
REQUEST/1, F2=DZ(20,1,1), F3=VZ(20,1,1,1), F4=AZ(20,1), F6=WZ(20,1,1)
END
"""


def test_a_cylindrical_joint_starts_from_both(tmp_path):
    """ICTRAN = 0.25, 0.5 and ICROT = 90D, 3 on a vertical cylindrical joint: the body
    falls from 0.25 m at 0.5 m/s (d = 0.25 + 0.5 t - g t^2 / 2) and spins from pi/2 at a
    steady 3 rad/s (AZ = pi/2 + 3 t, wrapped): the height and rates to 1e-8, the angle to
    1e-7 (measured 4.1e-8)."""
    _, acf = _write(tmp_path, CYLINDER)
    res = pysolver.load(acf).run(integr_tol=1e-9)
    assert res.success, res.message
    q, t = res.request(1), res.t
    assert np.abs(q[:, 1] - (0.25 + 0.5 * t - 0.5 * G * t * t)).max() < 1e-8
    assert np.abs(q[:, 2] - (0.5 - G * t)).max() < 1e-8
    assert np.abs(np.angle(np.exp(1j * (q[:, 3] - np.pi / 2 - 3 * t)))).max() < 1e-7
    assert np.abs(q[:, 5] - 3.0).max() < 1e-8


def test_a_motion_on_the_same_coordinate_wins_with_a_warning(tmp_path):
    """Decision (MotionSolve's precedence: motions before joints' initial conditions): a
    joint MOTION of the coordinate the IC sets drives it; the IC is dropped with a
    DeckWarning at the IC's line."""
    text = SLIDER.format(ic=", IC = 0.3, -1.5",
                         extra="MOTION/7, JOINT=5, TRANSLATION, FUNCTION=0.1*TIME")
    adm, acf = _write(tmp_path, text)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        model = pysolver.load(acf)
    said = [str(w.message) for w in caught if issubclass(w.category, DeckWarning)]
    assert said == [f"{adm}:9, JOINT/5 (Constraint_Joint), attribute 'IC': the initial "
                    "translation is not used: MOTION/7 drives the joint's translation, and "
                    "a motion's own value at the start wins"]
    assert model.joints[5].ic == ()
    res = model.run(integr_tol=1e-9)
    assert np.abs(res.request(1)[:, 1] - 0.1 * res.t).max() < 1e-9


def test_an_ic_the_other_joints_fix_cannot_be_assembled(tmp_path):
    """A FIXED joint holding the slider at DZ = 0 and an IC of 0.3: the run stops at its
    start naming the IC (the initial conditions cannot be met)."""
    text = SLIDER.format(ic=", IC = 0.3", extra="JOINT/6, FIXED, I=20, J=10")
    _, acf = _write(tmp_path, text.replace("MARKER/10, PART=1, QP=0, 0, 0, REULER=0, 30D, 0",
                                           "MARKER/10, PART=1, REULER=0, 30D, 0"))
    res = pysolver.load(acf).run()
    assert not res.success
    assert "Constraint_Joint 5 (initial translation)" in res.message


@pytest.mark.parametrize("joint, words, key, line", [
    ("JOINT/5, SPHERICAL, I=21, J=10, IC = 0.3", "a SPHERICAL joint has no free coordinate to "
     "start from an initial condition; IC belongs to TRANSLATIONAL and REVOLUTE joints, ICTRAN "
     "and ICROT to CYLINDRICAL ones", "IC", 8),
    ("JOINT/5, CYLINDRICAL, I=21, J=10\n, IC = 0.3", "a CYLINDRICAL joint takes ICTRAN and "
     "ICROT (its two coordinates)", "IC", 9),
    ("JOINT/5, TRANSLATIONAL, I=21, J=10, ICTRAN = 0.3", "ICTRAN belongs to a CYLINDRICAL "
     "joint; a TRANSLATIONAL joint takes IC", "ICTRAN", 8),
    ("JOINT/5, TRANSLATIONAL, I=21, J=10\n, IC = 0.3, 1, 2", "IC takes one or two numbers (the "
     "initial displacement, then the velocity), got 3", "IC", 9),
    ("JOINT/5, CYLINDRICAL, I=21, J=10, ICTRAN = 0.1\n, IC = 0.3", "give IC (a TRANSLATIONAL "
     "or REVOLUTE joint) or ICTRAN and ICROT (a CYLINDRICAL joint), not both", "ICTRAN", 8),
])
def test_bad_joint_ic_is_one_deck_error(tmp_path, joint, words, key, line):
    text = SLIDER.format(ic="", extra="").replace("JOINT/5, TRANSLATIONAL, I=21, J=10", joint)
    adm, acf = _write(tmp_path, text)
    with pytest.raises(DeckError) as err:
        pysolver.load(acf)
    assert str(err.value) == f"{adm}:{line}, JOINT/5, attribute '{key}': {words}"


def test_xml_attributes_and_their_checks(tmp_path):
    """pysolver's XML attributes ic_tran_disp .. ic_rot_vel: a velocity needs its
    displacement; a rotation's on a TRANSLATIONAL joint is refused."""
    base = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="1" body_id="1"/><Reference_Marker id="20" body_id="2"/>
  <Body_Rigid id="2" cg_id="20" mass="1" inertia_xx="1" inertia_yy="1" inertia_zz="1"/>
  <Constraint_Joint id="3" type="TRANSLATIONAL" i_marker_id="20" j_marker_id="1" {a}/>
  </Model></MotionSolve>"""
    ok = pysolver.loads(base.format(a='ic_tran_disp="0.5" ic_tran_vel="2"'))
    assert ok.joints[3].ic == (("T", 0.5, 2.0),)
    with pytest.raises(DeckError) as err:
        pysolver.loads(base.format(a='ic_tran_vel="2"'))
    assert str(err.value) == ("<string>:4, Constraint_Joint id=3, attribute 'ic_tran_vel': an "
                              "initial velocity needs the initial displacement too "
                              "(ic_tran_disp)")
    with pytest.raises(DeckError) as err:
        pysolver.loads(base.format(a='ic_rot_disp="2"'))
    assert str(err.value) == ("<string>:4, Constraint_Joint id=3, attribute 'ic_rot_disp': a "
                              "TRANSLATIONAL joint has no free rotation to start from an initial "
                              "condition (its free coordinate is its translation)")


def test_convert_writes_it_back_and_the_msolve_forms_read_it(tmp_path):
    """pysolver convert's .adm writes IC (and ICTRAN, ICROT) back; XML and the msolve
    class script keep the numbers; the msolve statement JOINT(IC=) and class Joint(ic=)
    build the same joint."""
    from pysolver.convert import convert
    _, acf = _write(tmp_path, CYLINDER, name="cyl.adm")
    model = pysolver.load(acf)
    want = (("T", 0.25, 0.5), ("R", np.pi / 2, 3.0))
    assert model.joints[1].ic == want
    convert(acf, tmp_path / "out.adm")
    assert "ICTRAN = 0.25, 0.5" in (tmp_path / "out.adm").read_text()
    for out in ("out.acf", "out.xml", "out.py"):
        if out != "out.acf":
            convert(acf, tmp_path / out)
        assert pysolver.load(tmp_path / out).joints[1].ic == want, out
    # the class script writes the msolve class Joint with ictran= and icrot=
    assert "ictran=[0.25, 0.5]" in (tmp_path / "out.py").read_text()


def test_the_msolve_statement_takes_ic(tmp_path):
    """JOINT(..., IC=(d, v)) in a Python deck; IC on a CYLINDRICAL joint is a DeckError
    at the statement's line."""
    deck = tmp_path / "deck.py"
    deck.write_text("""from pysolver.msolve import *
PART(1, GROUND=True)
MARKER(1, PART=1)
PART(2, MASS=1, CM=20, IP=[1, 1, 1])
MARKER(20, PART=2)
JOINT(3, TYPE="REVOLUTE", I=20, J=1, IC=(0.5, 2))
""")
    assert pysolver.load(deck).joints[3].ic == (("R", 0.5, 2.0),)
    deck.write_text(deck.read_text().replace('"REVOLUTE"', '"CYLINDRICAL"'))
    with pytest.raises(DeckError) as err:
        pysolver.load(deck)
    assert str(err.value) == (f"{deck}:6, JOINT id=3, attribute 'IC': a CYLINDRICAL joint takes "
                              "ICTRAN and ICROT (its two coordinates)")
