"""SCREW and RACK_PINION joints: one equation d . zJ = lead theta + c0 with theta tracked through
every turn; closed forms, reactions by power balance, the Python statement, a driven screw."""
import numpy as np
import pytest

import pysolver

from helpers import TEST_DECKS

G = 9.81
K = 0.1 / (2 * np.pi)            # the screw's lead: pitch 0.1 m per turn
R = 0.05                         # the pinion's pitch radius


def wrapped(a):
    return np.angle(np.exp(1j * np.asarray(a)))


@pytest.mark.parametrize("kernel", ["tapes", "generated"])
def test_a_falling_nut_and_a_falling_rack_turn_as_the_closed_forms(kernel):
    """tests/decks/lead_joints.xml at integr_tol 1e-9. The nut falls z = a t^2 / 2 with
    a = -m g / (m + I / k^2) and turns by z / k (right-handed: down the axis, negative about
    it; about two turns, its angle passing pi); the screw carries m (a + g) along z and
    -k m (a + g) about z, so its reactions do no work. The rack falls
    x = a t^2 / 2, a = -m g / (m + I / r^2), and the pinion turns by -x / r (24 turns); the
    mesh pushes the pinion by -m (a + g) along x with the torque r m (a + g). Measured: nut
    2.3e-9 m, rack 2.7e-8 m after 7.5 m (relative 3.6e-9), reactions to 1e-10."""
    res = pysolver.load(TEST_DECKS / "lead_joints.xml").run(kernel=kernel)
    assert res.success, res.message
    q, t = res.request(1), res.t
    a = -2 * G / (2 + 0.05 / K ** 2)
    z = a * t ** 2 / 2
    assert z[-1] / K < -2 * np.pi * 1.9
    assert np.abs(q[:, 0] - z).max() < 1e-8
    assert np.abs(wrapped(q[:, 1] - z / K)).max() < 1e-8 / K
    np.testing.assert_allclose(q[:, 4], 2 * (a + G), rtol=1e-9)
    np.testing.assert_allclose(q[:, 5], -K * 2 * (a + G), rtol=1e-9)
    a = -0.5 * G / (0.5 + 0.002 / R ** 2)
    x = a * t ** 2 / 2
    assert -x[-1] / R > 2 * np.pi * 24
    assert np.abs(q[:, 2] - x).max() < 1e-7
    assert np.abs(wrapped(q[:, 3] + x / R)).max() < 1e-7 / R
    np.testing.assert_allclose(q[:, 6], -0.5 * (a + G), rtol=1e-9)
    np.testing.assert_allclose(q[:, 7], R * 0.5 * (a + G), rtol=1e-9)
    # the tracked angles are the unwrapped rotations
    s = pysolver.load(TEST_DECKS / "lead_joints.xml").compile(kernel).kernel.layout.turns
    assert set(s) == {("joint", 2, 0), ("joint", 5, 0)}
    np.testing.assert_allclose(res.y[:, s[("joint", 2, 0)]], z / K, rtol=0, atol=1e-8 / K)
    np.testing.assert_allclose(res.y[:, s[("joint", 5, 0)]], -x / R, rtol=0, atol=1e-7 / R)


SCREW_PY = """from pysolver.msolve import *
PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(20, PART=2, QP=[0, 0, 0.3])
PART(2, MASS=1, CM=20, IP=[0.1, 0.1, 0.1])
JOINT(1, TYPE='CYLINDRICAL', I=20, J=1)
JOINT(2, TYPE='SCREW', I=20, J=1, PITCH=-0.02)
MOTION(1, JOINT=1, TYPE='R', FUNCTION='2*PI*TIME')
REQUEST(1, F1='DZ(20,1,1)', F2='AZ(20,1)')
SIMULATE(TYPE='TRANSIENT', END=3, DTOUT=0.125)
"""


def test_a_driven_left_handed_screw_advances_its_pitch_per_turn(tmp_path):
    """The Python statements; a Motion_Joint turns the cylindrical joint once a second and a
    left-handed screw (pitch -0.02 m) sinks 0.02 m per turn from where it was (z = 0.3),
    through three turns, to the tolerance (integr_tol 1e-9), its angle too."""
    deck = tmp_path / "screw.py"
    deck.write_text(SCREW_PY)
    res = pysolver.load(deck).run(integr_tol=1e-9)
    assert res.success, res.message
    q, t = res.request(1), res.t
    np.testing.assert_allclose(q[:, 0], 0.3 - 0.02 * t, rtol=0, atol=1e-9)
    assert np.abs(wrapped(q[:, 1] - 2 * np.pi * t)).max() < 1e-9


def test_a_screw_keeps_the_relation_its_markers_are_given():
    """c0 is the relation at the deck's positions: a nut that starts 0.3 m up and turned by
    1 rad keeps z - k theta = 0.3 - k at every row (here at rest under no gravity)."""
    text = (TEST_DECKS / "lead_joints.xml").read_text().replace(
        '<Reference_Marker id="20" body_id="2"/>',
        '<Reference_Marker id="20" body_id="2" pos_z="0.3" a00="0.5403023058681398" '
        'a10="0.8414709848078965" a20="0" a01="-0.8414709848078965" a11="0.5403023058681398" '
        'a21="0" a02="0" a12="0" a22="1"/>').replace('grav_z="-9.81"', 'grav_z="0"')
    res = pysolver.loads(text).run()
    assert res.success, res.message
    np.testing.assert_allclose(res.request(1)[:, :2], [[0.3, 1.0]] * len(res.t), atol=1e-12)
