"""Motion_Marker: a driven displacement, velocity or acceleration is met to the integration
tolerance and its reaction is the force balance's (k x against a spring, m a + k x, I alpha
about each axis of a rigid body); the Jacobian with the reaction state is exact; bad motions
are DeckErrors that say where."""
import numpy as np
import pytest

import pysolver

from helpers import DECKS, fd_iteration_matrix

HEAD = '''from pysolver.msolve import *
UNITS(MASS="KILOGRAM", LENGTH="METER", TIME="SECOND", FORCE="NEWTON")
PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(10, PART=2, QP=[0, 0, 0])
'''
POINT = 'POINT_MASS(2, MASS=2.0, CM=10)\n'
RIGID = 'PART(2, MASS=2.0, CM=10, IP=[0.3, 0.4, 0.5])\n'
SPRING = 'PFORCE(1, FUNCTION="DX(10)", PENALTY=1000.0)\n'   # a linear spring: F = -1000 x
TAIL = '''REQUEST(1, F1="DX(10,1,1)", F2="DY(10,1,1)", F3="DZ(10,1,1)", F4="AX(10,1)",
        F5="AY(10,1)", F6="AZ(10,1)", F7="VX(10,1,1)")
INTEGRATOR(ERROR={tol})
SIMULATE(TYPE="TRANSIENT", END={end}, DTOUT=0.05)
'''


def deck(body, motion, extra="", tol=1e-10, end=1.0):
    return HEAD + body + extra + motion + TAIL.format(tol=tol, end=end)


def motion(direction, val_type, expr, id=1):
    return (f'MOTION({id}, I=10, J=1, DIRECTION="{direction}", VAL_TYPE="{val_type}", '
            f'FUNCTION="{expr}")\n')


def run(text, **options):
    res = pysolver.loads(text, fmt="py").run(**options)
    assert res.success, res.message
    return res


@pytest.mark.parametrize("backend", ["c", "sksundae"])
def test_constant_velocity_against_a_spring_reaction_is_k_x(backend):
    """Driven at 0.5 m/s from rest (the initial velocity is made consistent), the body's
    velocity is exactly 0.5 and the motion's reaction balances the spring: k x (1e-8)."""
    res = run(deck(POINT, motion("X", "V", "0.5"), SPRING), backend=backend)
    x, vx = res.request(1)[:, 0], res.request(1)[:, 6]
    np.testing.assert_allclose(vx, 0.5, rtol=0, atol=1e-12)
    np.testing.assert_allclose(x, 0.5 * res.t, rtol=0, atol=1e-12)
    np.testing.assert_allclose(res.motion(1), 1000.0 * x, rtol=1e-8, atol=1e-12)


def test_acceleration_motion_reaction_is_m_a_plus_k_x():
    res = run(deck(POINT, motion("X", "A", "3.0"), SPRING))
    x = res.request(1)[:, 0]
    np.testing.assert_allclose(x, 1.5 * res.t ** 2, rtol=0, atol=1e-12)
    np.testing.assert_allclose(res.motion(1), 2.0 * 3.0 + 1000.0 * x, rtol=1e-8)


def test_displacement_motion_follows_its_expression():
    """x = 0.1 sin 2t is held through its rate: within 1e-8 (integr_tol 1e-10) over 2 s, and
    the reaction is m x'' + k x."""
    res = run(deck(POINT, motion("X", "D", "0.1*SIN(2*TIME)"), SPRING, end=2.0))
    t, x = res.t, res.request(1)[:, 0]
    assert np.abs(x - 0.1 * np.sin(2 * t)).max() <= 1e-8
    want = 2.0 * -0.4 * np.sin(2 * t) + 1000.0 * x
    assert np.abs(res.motion(1) - want).max() <= 1e-7 * np.abs(want).max()


def test_displacement_motion_moves_the_body_to_its_start():
    """The body starts at x = 0 but the motion asks x = 0.2 + 0.1 t: it is moved there (and
    given the velocity 0.1) before the run starts."""
    res = run(deck(POINT, motion("X", "D", "0.2+0.1*TIME")))
    np.testing.assert_allclose(res.request(1)[:, 0], 0.2 + 0.1 * res.t, rtol=0, atol=1e-10)
    np.testing.assert_allclose(res.motion(1), 0.0, atol=1e-9)


SIX = {"X": (0, 2.0), "Y": (1, 2.0), "Z": (2, 2.0), "B1": (3, 0.3), "B2": (4, 0.4),
       "B3": (5, 0.5)}
#: val_type -> (expression, the driven quantity's displacement, its second derivative)
KINDS = {"D": ("0.3*SIN(TIME)", lambda t: 0.3 * np.sin(t), lambda t: -0.3 * np.sin(t)),
         "V": ("0.2+0.1*TIME", lambda t: 0.2 * t + 0.05 * t ** 2, lambda t: 0.1 + 0 * t),
         "A": ("0.5", lambda t: 0.25 * t ** 2, lambda t: 0.5 + 0 * t)}


@pytest.mark.parametrize("val_type", "DVA")
@pytest.mark.parametrize("direction", list(SIX))
def test_every_direction_of_a_rigid_body(direction, val_type):
    """A free rigid body (principal inertias 0.3, 0.4, 0.5) driven along or about one axis:
    the driven measure follows (1e-8), the other five stay exactly 0, and the reaction is
    m a or I alpha (1e-8)."""
    col, inertia = SIX[direction]
    expr, disp, acc = KINDS[val_type]
    res = run(deck(RIGID, motion(direction, val_type, expr)))
    meas = res.request(1)[:, :6]
    assert np.abs(meas[:, col] - disp(res.t)).max() <= 1e-8
    assert np.abs(np.delete(meas, col, axis=1)).max() == 0.0
    assert np.abs(res.motion(1) - inertia * acc(res.t)).max() <= 1e-8


def test_jacobian_with_reactions_matches_central_differences():
    """A rigid body with a rotational and a translational motion (one an acceleration motion,
    with its driven-velocity state) and a spring: the iteration matrix, reaction rows and
    columns included, against central differences of the residual at random states."""
    text = deck(RIGID, motion("B3", "D", "0.3*SIN(TIME)") + motion("Y", "A", "0.5", id=2),
                SPRING.replace("DX(10)", "DX(10)+0.1*AZ(10,1)"))
    k = pysolver.loads(text, fmt="py").compile().kernel
    rng = np.random.default_rng(11)
    for _ in range(3):
        y, yp = rng.normal(size=k.ny), rng.normal(size=k.ny)
        y[3:7] /= np.linalg.norm(y[3:7])
        J = k.jacobian_array(0.4, y, yp, 3.0)
        fd = fd_iteration_matrix(k, 0.4, y, yp, 3.0)
        assert np.abs(J - fd).max() <= 1e-6 * np.abs(fd).max()


def test_indenter_deck_force_balance():
    """decks/driven_indenter.xml: a point indenter driven down at 1 mm/s onto a penalty floor.
    At constant velocity the body is in balance: reaction = m g + the penalty force PFORCE(1)
    (g = -DZ: the floor pushes up by PFORCE), 0.981 N before contact."""
    res = pysolver.load(DECKS / "driven_indenter.xml").run()
    assert res.success, res.message
    z, pf = res.request(1)[:, 0], res.request(1)[:, 1]
    np.testing.assert_allclose(z, 2.0 - res.t, rtol=0, atol=1e-9)
    lam = res.motion(1)
    np.testing.assert_allclose(lam, 0.981 + pf, rtol=1e-9, atol=1e-9)
    assert np.abs(lam[res.t < 1.9] - 0.981).max() <= 1e-9
    assert lam[-1] < -1.0                      # pressing into the floor at the end


@pytest.mark.parametrize("text,attribute,match", [
    (deck(POINT, motion("X", "V", "1").replace("I=10", "I=99")), "I",
     "marker 99 does not exist"),
    (deck(POINT, motion("X", "V", "1").replace("I=10", "I=1")), "J",
     "both markers are on ground"),
    (deck(POINT, motion("B3", "D", "0.1")), "I", "needs rigid bodies; marker 10 is on point"),
    (deck(POINT, motion("X", "V", "DX(10)")), "FUNCTION", "depend on time only; it reads DX"),
    (deck(POINT, motion("X", "V", "1") + motion("X", "D", "TIME", id=2)), "DIRECTION",
     "Motion_Marker 1 already drives X between these bodies"),
    (deck(POINT, motion("Q", "V", "1")), "DIRECTION", "X, Y, Z, B1, B2, B3"),
    (deck(POINT, motion("X", "J", "1")), "VAL_TYPE", "D, V, A"),
    (deck(POINT, motion("X", "V", "1")).replace('TYPE="TRANSIENT", END=1.0, DTOUT=0.05',
                                                  'TYPE="STATIC"'),
     "analysis_type", "hold each motion's displacement, and Motion_Marker 1 gives a velocity"),
])
def test_bad_motions(text, attribute, match):
    with pytest.raises(pysolver.DeckError, match=match) as info:
        pysolver.loads(text, fmt="py")
    assert info.value.attribute == attribute and info.value.line is not None


def test_motion_measure_in_requests_and_forces():
    """MOTION(1) is the reaction, MOTION(1, 0, 2, 0) its x component on I, MOTION(1, 1, 2, 0)
    the opposite on J; a force reading it (a lateral push 0.1 MOTION(1), like friction from a
    normal force) gives y = 0.1 k v t^3 / (6 m) exactly; the Jacobian's reaction column is
    right (central differences)."""
    extra = SPRING + 'VFORCE(2, I=10, JFLOAT=1, FY="0.1*MOTION(1)")\n'
    text = deck(POINT, motion("X", "V", "0.5"), extra).replace(
        'F7="VX(10,1,1)")', 'F7="VX(10,1,1)", F8="MOTION(1)")')
    text += 'REQUEST(2, F1="MOTION(1, 0, 2, 0)", F2="MOTION(1, 1, 2, 0)", F3="MOTION(1, 0, 1, 0)",'
    text += ' F4="MOTION(1, 1, 8, 0)", F5="MOTION(1, 0, 6, 0)")\n'
    res = run(text)
    t = res.t
    np.testing.assert_allclose(res.request(1)[:, 7], res.motion(1), rtol=1e-12, atol=1e-12)
    r2 = res.request(2)
    np.testing.assert_allclose(r2[:, 0], 1000.0 * 0.5 * t, rtol=1e-8, atol=1e-12)
    np.testing.assert_allclose(r2[:, 1], -r2[:, 0], rtol=0, atol=0)
    np.testing.assert_allclose(r2[:, 2], np.abs(r2[:, 0]), rtol=0, atol=0)
    # torque on J (ground, at the origin) of the opposite force at I = (x, y, 0): about z
    y = res.request(1)[:, 1]
    np.testing.assert_allclose(r2[:, 3], y * r2[:, 0], rtol=1e-9, atol=1e-12)
    assert np.all(r2[:, 4] == 0.0)
    np.testing.assert_allclose(y, 0.1 * 1000.0 * 0.5 * t ** 3 / (6 * 2.0), rtol=0, atol=1e-9)
    k = pysolver.loads(text, fmt="py").compile().kernel
    rng = np.random.default_rng(2)
    y0, yp0 = rng.normal(size=k.ny), rng.normal(size=k.ny)
    J = k.jacobian_array(0.3, y0, yp0, 5.0)
    fd = fd_iteration_matrix(k, 0.3, y0, yp0, 5.0)
    assert np.abs(J - fd).max() <= 1e-6 * np.abs(fd).max()
    assert J[k.layout.uadr[0] + 1, k.layout.lam[0]] == -0.1     # the push's reaction column
