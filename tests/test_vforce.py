"""Force_Vector_TwoBody (VFORCE): components resolved in a (moving) reference marker, applied
at I and, opposite, on J's body at the same point: Newton's second law on a point mass, and
conservation of linear and angular momentum between two spinning rigid bodies; the Jacobian
matches central differences; bad references are DeckErrors."""
import numpy as np
import pytest

import pysolver

from helpers import fd_iteration_matrix

HEAD = '''from pysolver.msolve import *
UNITS(MASS="KILOGRAM", LENGTH="METER", TIME="SECOND", FORCE="NEWTON")
PART(1, GROUND=True)
MARKER(1, PART=1)
'''


def test_point_mass_accelerates_along_the_reference_axes():
    """FX = 1 N in a ground marker turned 30 degrees about z: x, y = t^2/2 (cos, sin 30)/m."""
    text = HEAD + '''MARKER(5, PART=1, QP=[0, 0, 0], REULER=[0.5235987755982988, 0, 0])
MARKER(10, PART=2, QP=[0, 0, 0])
POINT_MASS(2, MASS=2.0, CM=10)
VFORCE(1, I=10, JFLOAT=1, RM=5, FX="1.0")
REQUEST(1, F1="DX(10)", F2="DY(10)", F3="DZ(10)")
INTEGRATOR(ERROR=1e-10)
SIMULATE(TYPE="TRANSIENT", END=1.0, DTOUT=0.1)
'''
    res = pysolver.loads(text, fmt="py").run()
    assert res.success, res.message
    a = np.array([np.cos(np.pi / 6), np.sin(np.pi / 6), 0.0]) / 2.0
    np.testing.assert_allclose(res.request(1)[:, :3], 0.5 * res.t[:, None] ** 2 * a,
                               rtol=0, atol=1e-12)


TWO = HEAD + '''MARKER(20, PART=2, QP=[0.1, 0, 0])
MARKER(21, PART=2, QP=[0.4, 0.2, -0.1])
MARKER(30, PART=3, QP=[1.0, 0.5, 0.3], REULER=[0.3, 0.4, 0.5])
PART(2, MASS=2.0, CM=20, IP=[0.3, 0.4, 0.5], WX=1.0, WY=-0.5, WZ=2.0)
PART(3, MASS=3.0, CM=30, IP=[0.6, 0.2, 0.7], VX=0.1, WZ=-1.0, WX=0.3)
VFORCE(1, I=21, JFLOAT=30, RM=30, FX="SIN(3*TIME)", FY="0.5", FZ="0.2*TIME")
INTEGRATOR(ERROR=1e-11)
SIMULATE(TYPE="TRANSIENT", END=2.0, DTOUT=0.05)
'''


def _momenta(res):
    """Total linear momentum and angular momentum about the origin at every output row."""
    from pysolver.rotations import rot_from_e
    names = res.state_names
    P = np.zeros((len(res.t), 3))
    L = np.zeros((len(res.t), 3))
    for body, mass, inertia in ((2, 2.0, [0.3, 0.4, 0.5]), (3, 3.0, [0.6, 0.2, 0.7])):
        col = {n: names.index(f"body{body}.{n}") for n in
               ("x", "vx", "e0", "wx")}
        r = res.y[:, col["x"]:col["x"] + 3]
        v = res.y[:, col["vx"]:col["vx"] + 3]
        e = res.y[:, col["e0"]:col["e0"] + 4]
        w = res.y[:, col["wx"]:col["wx"] + 3]
        P += mass * v
        for k in range(len(res.t)):
            A = rot_from_e(e[k])
            L[k] += mass * np.cross(r[k], v[k]) + A @ (np.diag(inertia) @ w[k])
    return P, L


def test_two_rigid_bodies_conserve_momentum_and_angular_momentum():
    """The force acts on body 2 at marker 21 and, opposite, on body 3 at the same point, in the
    axes of body 3's marker: no net force or moment on the pair, so P and L stay at their
    initial values (1e-8 relative) while each body's own momentum changes."""
    res = pysolver.loads(TWO, fmt="py").run()
    assert res.success, res.message
    P, L = _momenta(res)
    assert np.abs(P - P[0]).max() <= 1e-8 * np.abs(P[0]).max()
    assert np.abs(L - L[0]).max() <= 1e-8 * np.abs(L[0]).max()
    v2 = res.y[:, res.state_names.index("body2.vx")]
    assert np.abs(v2 - v2[0]).max() > 0.05                 # the force does act


def test_jacobian_matches_central_differences():
    k = pysolver.loads(TWO, fmt="py").compile().kernel
    rng = np.random.default_rng(5)
    for _ in range(3):
        y, yp = rng.normal(size=k.ny), rng.normal(size=k.ny)
        for qa in k.layout.qadr:
            y[qa + 3:qa + 7] /= np.linalg.norm(y[qa + 3:qa + 7])
        J = k.jacobian_array(0.7, y, yp, 4.0)
        fd = fd_iteration_matrix(k, 0.7, y, yp, 4.0)
        assert np.abs(J - fd).max() <= 1e-6 * np.abs(fd).max()


@pytest.mark.parametrize("old,new,attribute,match", [
    ("I=21", "I=99", "I", "marker 99 does not exist"),
    ("RM=30", "RM=98", "RM", "marker 98 does not exist"),
    ('FY="0.5"', 'FY="DX(77)"', "FY", "refers to marker id 77"),
])
def test_bad_vector_forces(old, new, attribute, match):
    with pytest.raises(pysolver.DeckError, match=match) as info:
        pysolver.loads(TWO.replace(old, new), fmt="py")
    assert info.value.attribute == attribute
