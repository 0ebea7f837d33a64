"""Rigid bodies: torque-free axisymmetric precession, conservation laws, orientation forms."""
import numpy as np

import pysolver
from pysolver.rotations import rot_from_e as _rot_from_e

I1, I3, W3, W1 = 0.1, 0.18, 20.0, 1.0


def rotation(y):
    e = y[3:7] / np.linalg.norm(y[3:7])
    return _rot_from_e(e)


def test_torque_free_precession_exact(decks):
    res = pysolver.load(decks / "torque_free_spin.xml").run()
    assert res.success
    R, t = res.request(1), res.t
    om = (I3 - I1) / I1 * W3
    np.testing.assert_allclose(R[:, 0], W1 * np.cos(om * t), atol=1e-5)
    np.testing.assert_allclose(R[:, 1], W1 * np.sin(om * t), atol=1e-5)
    np.testing.assert_allclose(R[:, 2], W3, rtol=1e-12)
    # the centre of mass moves uniformly: x = 0.5 t, z = 1
    np.testing.assert_allclose(R[:, 6], 0.5 * t, atol=1e-9)
    np.testing.assert_allclose(R[:, 7], 1.0, atol=1e-12)


def test_energy_and_angular_momentum_conserved(decks):
    res = pysolver.load(decks / "torque_free_spin.xml").run()
    J = np.diag([I1, I1, I3])
    E, H = [], []
    for y in res.y:
        wb = y[10:13]
        E.append(0.5 * wb @ J @ wb + 0.5 * 3.0 * y[7:10] @ y[7:10])
        H.append(rotation(y) @ (J @ wb))
    E, H = np.array(E), np.array(H)
    assert np.abs(E - E[0]).max() < 1e-6 * E[0]
    assert np.abs(H - H[0]).max() < 1e-6 * np.linalg.norm(H[0])
    # global angular velocity from WX(20) etc. is A w_body
    for y, row in zip(res.y[::40], res.request(1)[::40]):
        np.testing.assert_allclose(row[3:6], rotation(y) @ y[10:13], atol=1e-12)
    # Euler parameters keep unit norm to tolerance
    assert np.abs(np.linalg.norm(res.y[:, 3:7], axis=1) - 1).max() < 1e-6


def test_orientation_forms_agree():
    """The same frame given as 3-1-3 angles, Euler parameters and a direction-cosine matrix."""
    psi, theta, phi = 0.3, 0.7, -0.4
    c, s = np.cos, np.sin
    Rz = lambda a: np.array([[c(a), -s(a), 0], [s(a), c(a), 0], [0, 0, 1]])
    Rx = lambda a: np.array([[1, 0, 0], [0, c(a), -s(a)], [0, s(a), c(a)]])
    A = Rz(psi) @ Rx(theta) @ Rz(phi)
    e = [float(v) for v in pysolver.rotations.e_from_rot(A)]
    cols = " ".join(f'a{r}{k}="{float(A[r, k])!r}"' for k in range(3) for r in range(3))
    deck = f"""<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
      <Reference_Marker id="1" body_id="1" psi="{psi}" theta="{theta}" phi="{phi}"/>
      <Reference_Marker id="2" body_id="1" e0="{e[0]!r}" e1="{e[1]!r}" e2="{e[2]!r}" e3="{e[3]!r}"/>
      <Reference_Marker id="3" body_id="1" {cols}/>
      <Reference_Marker id="4" body_id="1" pos_x="1" pos_y="2" pos_z="3" rm_id="1"/>
      </Model></MotionSolve>"""
    model = pysolver.loads(deck)
    for mid in (1, 2, 3):
        np.testing.assert_allclose(model.markers[mid].rot, A, atol=1e-12)
    np.testing.assert_allclose(model.markers[4].pos, A @ [1, 2, 3], atol=1e-12)


def heavy_top_reference(t, m=1.0, g=9.81, arm=0.1, I1c=0.004, I3=0.00178, w3=200.0, th0=0.3):
    """Heavy symmetric top about a fixed tip, by Lagrange's equations in Euler angles,
    integrated with SciPy at rtol 1e-11: returns (theta, phi) at times t."""
    from scipy.integrate import solve_ivp
    I1 = I1c + m * arm * arm                  # about the pivot
    p_phi = I3 * w3 * np.cos(th0)         # released without precession

    def rhs(_, s):
        th, thd, _phi = s
        phid = (p_phi - I3 * w3 * np.cos(th)) / (I1 * np.sin(th) ** 2)
        thdd = (I1 * phid ** 2 * np.sin(th) * np.cos(th) - I3 * w3 * phid * np.sin(th)
                + m * g * arm * np.sin(th)) / I1
        return [thd, thdd, phid]

    sol = solve_ivp(rhs, (0, t[-1]), [th0, 0.0, 0.0], t_eval=t, rtol=1e-11, atol=1e-13,
                    method="DOP853")
    return sol.y[0], sol.y[2]


def _top_errors(res):
    R = res.request(1)
    theta, phi = heavy_top_reference(res.t)
    return (np.abs(R[:, 2] - 0.1 * np.cos(theta)).max(),
            np.abs(np.unwrap(R[:, 4]) - (phi - np.pi / 2)).max(), R[:, 3].max())


def test_heavy_top_against_lagrange_reference(decks):
    """The penalty-jointed top converges to the ideal joint's motion as O(1/penalty)."""
    text = (decks / "spinning_top.xml").read_text()
    soft = pysolver.loads(text).run()
    stiff = pysolver.loads(text.replace('penalty="1e6" penalty1="500"',
                                        'penalty="1e7" penalty1="2000"')).run(integr_tol=1e-9)
    assert soft.success and stiff.success
    np.testing.assert_allclose(soft.request(1)[:, 5], 200.0, rtol=1e-6)  # spin is conserved
    dz_soft, daz_soft, gap_soft = _top_errors(soft)
    dz_stiff, daz_stiff, gap_stiff = _top_errors(stiff)
    # the tip moves by m g / penalty and the motion error follows it
    assert gap_soft < 1.5e-5 and gap_stiff < 1.5e-6
    assert dz_soft < 5e-5 and daz_soft < 4e-3
    assert 8 < dz_soft / dz_stiff < 12 and 8 < daz_soft / daz_stiff < 12


def test_scalar_force_and_torque_on_a_rigid_body():
    """Initial accelerations from SFORCE: a force at an offset marker gives F/m and
    J^-1 (r x F); a torque about z of J gives T / Izz about that axis."""
    deck = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
      <Reference_Marker id="1" body_id="1" pos_x="3" pos_y="0.5" pos_z="0.2"/>
      <Reference_Marker id="2" body_id="1" psi="0.4" theta="0.6" phi="0.1"/>
      <Reference_Marker id="20" body_id="2"/>
      <Reference_Marker id="21" body_id="2" pos_x="0.2" pos_y="0.1" pos_z="-0.3"/>
      <Body_Rigid id="2" cg_id="20" mass="2" inertia_xx="0.3" inertia_yy="0.4" inertia_zz="0.5"/>
      <Force_Scalar_TwoBody id="1" type="Force" i_marker_id="21" j_marker_id="1" val="-7"/>
      <Force_Scalar_TwoBody id="2" type="Torque" i_marker_id="20" j_marker_id="2" val="1.5"/>
      </Model><Simulate analysis_type="Transient" end_time="0.001" num_step="1"/></MotionSolve>"""
    res = pysolver.loads(deck).run()
    model = pysolver.loads(deck)
    r = np.array([0.2, 0.1, -0.3])
    d = r - np.array([3, 0.5, 0.2])
    F = -7 * d / np.linalg.norm(d)
    zJ = model.markers[2].rot[:, 2]
    J = np.diag([0.3, 0.4, 0.5])
    np.testing.assert_allclose(res.yp[0, 7:10], F / 2, rtol=1e-12)
    np.testing.assert_allclose(res.yp[0, 10:13], np.linalg.solve(J, np.cross(r, F) + 1.5 * zJ),
                               rtol=1e-12)


def test_measures_in_a_rotating_frame():
    """A ground point seen from a frame spinning at w about z: velocity -w x r, acceleration
    -w^2 r (centripetal), both resolved in the ground frame here."""
    deck = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
      <Reference_Marker id="1" body_id="1" pos_x="1"/>
      <Reference_Marker id="20" body_id="2"/>
      <Body_Rigid id="2" cg_id="20" mass="1" inertia_xx="1" inertia_yy="1" inertia_zz="1" w_ic_z="2"/>
      <Post_Request id="1" expr1="VX(1,20,0,20)" expr2="VY(1,20,0,20)" expr3="ACCX(1,20,0,20)"
        expr4="ACCY(1,20,0,20)" expr5="VR(1,20,20)" expr6="VM(1,20,20)" expr7="WZ(20,1,20)"
        expr8="AZ(20)"/>
      </Model><Simulate analysis_type="Transient" end_time="0.5" num_step="5"/></MotionSolve>"""
    res = pysolver.loads(deck).run(integr_tol=1e-10)
    R = res.request(1)
    np.testing.assert_allclose(R[:, :7], [[0, -2, -4, 0, 0, 2, 2]] * len(res.t), atol=1e-9)
    np.testing.assert_allclose(R[:, 7], 2 * res.t, atol=1e-8)   # AZ: the body turns at 2 rad/s
