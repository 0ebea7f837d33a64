"""Motion_Marker (Adams MOTION with I=, J=) B1, B2, B3 are the first, second and third angles
of the body-fixed 1-2-3 sequence of I relative to J (Adams' MOTION statement: "the first angle
of the Body 1-2-3 Euler angle sequence"), so three driven angles give R = Rx(B1) Ry(B2)
Rz(B3): read back by ORIENT and by I's axes against SciPy's rotation, with a rotated J; the
velocity and acceleration forms drive the angles' derivatives; the three reactions are the
torque Euler's equations need; the Adams dataset reads the same."""
import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import pysolver

J_ANGLES = (0.4, 1.1, -0.7)              # J's 3-1-3 angles on ground
INERTIA = (1.0, 2.0, 3.0)
B1, B2, B3 = "0.6*SIN(2*TIME)", "0.2 + 0.5*TIME", "0.8*TIME"


def angles(t):
    """The driven (B1, B2, B3) at times t."""
    return np.column_stack([0.6 * np.sin(2 * t), 0.2 + 0.5 * t, 0.8 * t])


def rel(b):
    """R = Rx(b1) Ry(b2) Rz(b3): I's axes (columns) in J's."""
    return Rotation.from_euler("XYZ", b).as_matrix()


def _deck(motions):
    """Ground marker 1 (J, turned), a body with its cg 10 at J's origin (unturned) and marker 11
    (I) there turned as the motions start, markers 12..14 one unit along I's axes."""
    A_J = Rotation.from_euler("ZXZ", J_ANGLES).as_matrix()
    A_I = A_J @ rel(angles(np.zeros(1))[0])
    psi, theta, phi = map(float, Rotation.from_matrix(A_I).as_euler("ZXZ"))
    ends = "".join(f'<Reference_Marker id="{12 + c}" body_id="2" pos_x="{float(A_I[0, c])!r}" '
                   f'pos_y="{float(A_I[1, c])!r}" pos_z="{float(A_I[2, c])!r}"/>'
                   for c in range(3))
    return f"""<MotionSolve><Model>
  <Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="1" body_id="1" psi="{J_ANGLES[0]}" theta="{J_ANGLES[1]}"
                    phi="{J_ANGLES[2]}"/>
  <Body_Rigid id="2" cg_id="10" mass="2" inertia_xx="{INERTIA[0]}" inertia_yy="{INERTIA[1]}"
              inertia_zz="{INERTIA[2]}"/>
  <Reference_Marker id="10" body_id="2"/>
  <Reference_Marker id="11" body_id="2" psi="{psi!r}" theta="{theta!r}" phi="{phi!r}"/>
  {ends}
  <Motion_Marker id="1" i_marker_id="11" j_marker_id="1" direction="X" expr="0"/>
  <Motion_Marker id="2" i_marker_id="11" j_marker_id="1" direction="Y" expr="0"/>
  <Motion_Marker id="3" i_marker_id="11" j_marker_id="1" direction="Z" expr="0"/>
  {motions}
  <Post_Request id="1" expr1="ORIENT(1,1,11,1)" expr2="ORIENT(1,2,11,1)"
                expr3="ORIENT(1,3,11,1)"/>
  <Post_Request id="2" expr1="DX(12,11,1)" expr2="DY(12,11,1)" expr3="DZ(12,11,1)"
                expr4="DX(13,11,1)" expr5="DY(13,11,1)" expr6="DZ(13,11,1)"
                expr7="DX(14,11,1)" expr8="DY(14,11,1)"/>
  <Post_Request id="3" expr1="DZ(14,11,1)"
                expr2="MOTION(4,0,6,0) + MOTION(5,0,6,0) + MOTION(6,0,6,0)"
                expr3="MOTION(4,0,7,0) + MOTION(5,0,7,0) + MOTION(6,0,7,0)"
                expr4="MOTION(4,0,8,0) + MOTION(5,0,8,0) + MOTION(6,0,8,0)"/>
</Model><Simulate analysis_type="Transient" end_time="1" print_interval="0.02"/>
</MotionSolve>"""


def _driven(b1=("D", B1), b2=("D", B2), b3=("D", B3)):
    out = []
    for k, (kind, expr) in enumerate((b1, b2, b3)):
        out.append(f'<Motion_Marker id="{4 + k}" i_marker_id="11" j_marker_id="1" '
                   f'direction="B{k + 1}" val_type="{kind}" expr="{expr}"/>')
    return "".join(out)


def _axes(res):
    """I's axes in J's at the output rows, (n, 3, 3), columns x, y, z."""
    d = np.column_stack([res.request(2), res.request(3)[:, :1]])
    return d.reshape(-1, 3, 3).transpose(0, 2, 1)


@pytest.mark.parametrize("kernel", ["tapes", "generated"])
def test_three_driven_angles_are_the_body_fixed_1_2_3_sequence(kernel):
    """B1 = 0.6 sin 2t, B2 = 0.2 + 0.5 t, B3 = 0.8 t of I (turned on its body) relative to
    a turned J: ORIENT(1, k, I, J) reads them back, and I's axes seen from J (unit markers
    along them, DX..DZ resolved in J) are Rx(B1) Ry(B2) Rz(B3), SciPy's intrinsic "XYZ",
    within 1e-9 (measured 1.3e-11; before: B1..B3 drove AX, AY, AZ, and the attitude was
    0.099 off at 1 s)."""
    res = pysolver.loads(_deck(_driven())).run(kernel=kernel, integr_tol=1e-9)
    assert res.success, res.message
    b = angles(res.t)
    np.testing.assert_allclose(res.request(1)[:, :3], b, rtol=0, atol=1e-9)
    np.testing.assert_allclose(_axes(res), rel(b), rtol=0, atol=1e-9)


def test_velocity_and_acceleration_forms_drive_the_angles_derivatives():
    """Adams' MOTION page: with VELOCITY or ACCELERATION the function is the angle's first or
    second time derivative ("the second time derivative of B2 (Euler angle)"), not an angular
    velocity component: B2'' = 1 from rest gives B2 = 0.2 + t^2 / 2 (ic_disp 0.2), B3' = 0.8
    gives B3 = 0.8 t, beside B1 driven in displacement; within 1e-8 at integr_tol 1e-10
    (measured 3e-10)."""
    motions = _driven(b2=("A", "1"), b3=("V", "0.8")).replace(
        'direction="B2" val_type="A"', 'direction="B2" val_type="A" ic_disp="0.2" ic_vel="0"')
    res = pysolver.loads(_deck(motions)).run(integr_tol=1e-10)
    assert res.success, res.message
    t = res.t
    b = np.column_stack([0.6 * np.sin(2 * t), 0.2 + 0.5 * t * t, 0.8 * t])
    np.testing.assert_allclose(res.request(1)[:, :3], b, rtol=0, atol=1e-8)
    np.testing.assert_allclose(_axes(res), rel(b), rtol=0, atol=1e-8)


def _euler_torque(t, h=1e-4):
    """The global torque about the cg that turns the body as the driven angles say:
    I alpha + w x I w, with the body's axes A_B = A_J R(t) C^T (C: I's axes on the body),
    its angular velocity from central differences of A_B."""
    A_J = Rotation.from_euler("ZXZ", J_ANGLES).as_matrix()
    C = A_J @ rel(angles(np.zeros(1))[0])

    def axes(s):
        return A_J @ rel(angles(np.atleast_1d(s)))[0] @ C.T

    def omega(s, e=1e-5):
        W = (axes(s + e) - axes(s - e)) / (2 * e) @ axes(s).T
        return np.array([W[2, 1], W[0, 2], W[1, 0]])
    out = []
    for s in t:
        A = axes(s)
        Ig = A @ np.diag(INERTIA) @ A.T
        w, alpha = omega(s), (omega(s + h) - omega(s - h)) / (2 * h)
        out.append(Ig @ alpha + np.cross(w, Ig @ w))
    return np.array(out)


def test_the_three_reactions_are_the_torque_the_driven_turn_needs():
    """MOTION(k, 0, 6..8, 0) of B1..B3 are lam_k times the dual basis of the sequence's axes
    (the torque whose power is lam_k times the angle's rate, what the kernel applies): their
    sum is the torque about the cg Euler's equations need for the driven attitude,
    I alpha + w x I w, within 1e-6 relative (measured 9.3e-8, the reference's central
    differences included)."""
    res = pysolver.loads(_deck(_driven())).run(integr_tol=1e-10)
    assert res.success, res.message
    torque = res.request(3)[:, 1:4]
    expected = _euler_torque(res.t)
    assert np.abs(expected).max() > 1.0
    np.testing.assert_allclose(torque, expected, rtol=0, atol=1e-6 * np.abs(expected).max())


# trial 44's dataset: the same three angles on a body at the origin, J = ground
ADAMS = """B123 motion test
UNITS/FORCE=NEWTON, MASS=KILOGRAM, LENGTH=METER, TIME=SECOND
PART/1, GROUND
MARKER/1, PART=1
PART/2, MASS=1, CM=10, IP=1,1,1
MARKER/10, PART=2
MOTION/1, I=10, J=1, X, FUNCTION=0
MOTION/2, I=10, J=1, Y, FUNCTION=0
MOTION/3, I=10, J=1, Z, FUNCTION=0
MOTION/4, I=10, J=1, B1, FUNCTION=0.6*SIN(2*TIME)
MOTION/5, I=10, J=1, B2, FUNCTION=0.5*TIME
MOTION/6, I=10, J=1, B3, FUNCTION=0.8*TIME
REQUEST/1, F1=ORIENT(27,1,10)\\F2=ORIENT(27,2,10)\\F3=ORIENT(27,3,10)\\F4=ORIENT(27,4,10)\\
, F5=ORIENT(1,1,10)\\F6=ORIENT(1,2,10)\\F7=ORIENT(1,3,10)
END
"""


def test_the_adams_dataset_drives_the_same_angles(tmp_path):
    """Trial 44's MOTION/4..6 B1, B2, B3 = 0.6 sin 2t, 0.5 t, 0.8 t: the part's Euler
    parameters (ORIENT 27) make Rx(B1) Ry(B2) Rz(B3) within 1e-9 (the trial found 0.099 at
    1 s) and ORIENT(1, k) reads the three functions back."""
    path = tmp_path / "b123.adm"
    path.write_text(ADAMS)
    res = pysolver.load(path).run(integr_tol=1e-10)
    assert res.success, res.message
    q, t = res.request(1), res.t
    b = np.column_stack([0.6 * np.sin(2 * t), 0.5 * t, 0.8 * t])
    R = Rotation.from_quat(np.column_stack([q[:, 1:4], q[:, 0]])).as_matrix()
    np.testing.assert_allclose(R, rel(b), rtol=0, atol=1e-9)
    np.testing.assert_allclose(q[:, 4:7], b, rtol=0, atol=1e-9)
