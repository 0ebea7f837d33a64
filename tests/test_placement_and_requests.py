"""Marker placement (rm_id chains, every orientation form, lprf_id), the orientation angle
functions and the marker request types, against independent computations."""
import warnings

import numpy as np
import pytest

import pysolver
from pysolver import DeckError, DeckWarning
from pysolver.convert import convert
from pysolver.rotations import rot_313, rot_321

RNG = np.random.default_rng(7)


def _matrix_attrs(A):
    return " ".join(f'a{r}{c}="{float(A[r, c])!r}"' for c in range(3) for r in range(3))


def _quat(A):
    """Euler parameters (e0 >= 0) of a rotation matrix."""
    e0 = 0.5 * np.sqrt(max(0.0, 1 + np.trace(A)))
    e = np.array([e0, (A[2, 1] - A[1, 2]) / (4 * e0), (A[0, 2] - A[2, 0]) / (4 * e0),
                  (A[1, 0] - A[0, 1]) / (4 * e0)])
    return e / np.linalg.norm(e)


def _scene(markers, requests, end="1"):
    return f"""<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="1" body_id="1"/>
  {markers}
  <Body_Rigid id="2" cg_id="20" mass="1.5" inertia_xx="0.2" inertia_yy="0.3" inertia_zz="0.4"
    w_ic_x="1" w_ic_y="0.3" w_ic_z="2" v_ic_x="0.5"/>
  <Force_Gravity grav_y="-9.81"/>
  {requests}
  <Param_Transient integr_tol="1e-10"/></Model>
  <Simulate analysis_type="Transient" end_time="{end}" print_interval="0.1"/></MotionSolve>"""


def test_markers_placed_through_rm_chains_equal_the_same_markers_given_globally():
    """Markers 20-23 on a spinning body and 5-6 on ground, each given relative to the one
    before (rm_id) in a different orientation form; the same deck with every marker written
    globally (positions and a00..a22 computed here) runs the same to 1e-12."""
    local = [(5, 1, None, [0.3, -0.2, 0.1], ("313", (0.3, 1.1, -0.4))),
             (6, 1, 5, [0.5, 0.0, -0.3], ("321", (0.2, -0.5, 0.9))),
             (20, 2, 6, [0.1, 0.7, 0.2], ("e", _quat(rot_313(0.4, 0.2, 1.3)))),
             (21, 2, 20, [0.4, 0.0, 0.0], ("matrix", rot_321(1.0, 0.3, -0.2))),
             (22, 2, 21, [0.0, 0.2, 0.1], ("313", (-0.7, 0.5, 0.25)))]
    frames, rel, glob = {}, [], []
    for mid, body, rm, pos, (form, vals) in local:
        A = {"313": lambda v: rot_313(*v), "321": lambda v: rot_321(*v),
             "e": lambda v: _rot_e(v), "matrix": lambda v: v}[form](vals)
        attrs = {"313": lambda v: f'psi="{v[0]}" theta="{v[1]}" phi="{v[2]}"',
                 "321": lambda v: f'yaw="{v[0]}" pitch="{v[1]}" roll="{v[2]}"',
                 "e": lambda v: " ".join(f'e{k}="{float(x)!r}"' for k, x in enumerate(v)),
                 "matrix": _matrix_attrs}[form](vals)
        p0, R0 = frames.get(rm, (np.zeros(3), np.eye(3)))
        p, R = p0 + R0 @ np.array(pos), R0 @ A
        frames[mid] = (p, R)
        where = " ".join(f'pos_{c}="{float(v)!r}"' for c, v in zip("xyz", pos))
        rel.append(f'<Reference_Marker id="{mid}" body_id="{body}" {where} {attrs}'
                   + (f' rm_id="{rm}"' if rm else "") + "/>")
        where = " ".join(f'pos_{c}="{float(v)!r}"' for c, v in zip("xyz", p))
        glob.append(f'<Reference_Marker id="{mid}" body_id="{body}" {where} '
                    f'{_matrix_attrs(R)}/>')
    requests = ('<Post_Request id="1" expr1="DX(22,6,5)" expr2="DY(22,6,5)" expr3="DZ(22,6,5)" '
                'expr4="PSI(22,5)" expr5="THETA(22,5)" expr6="PHI(22,5)" expr7="WX(21,6,22)" '
                'expr8="VZ(22,5,21)"/>')
    a = pysolver.loads(_scene("".join(rel), requests)).run()
    b = pysolver.loads(_scene("".join(glob), requests)).run()
    assert a.success and b.success
    np.testing.assert_allclose(a.request(1), b.request(1), rtol=0, atol=1e-12)


def _rot_e(e):
    from pysolver.rotations import rot_from_e
    return rot_from_e(np.asarray(e) / np.linalg.norm(e))


@pytest.mark.parametrize("trial", range(4))
def test_angle_functions_read_back_every_orientation_form(trial):
    """A ground marker given by psi/theta/phi, another by yaw/pitch/roll (random angles in
    their ranges), a third by the Euler parameters and a fourth by the matrix of a random
    rotation: PSI/THETA/PHI and YAW/PITCH/ROLL read the given angles back, and the angles of
    the third and fourth relative to each other equal those of A_J^T A_I computed here."""
    psi, phi, yaw, roll = RNG.uniform(-np.pi, np.pi, 4)
    theta, pitch = RNG.uniform(0.05, np.pi - 0.05), RNG.uniform(-1.5, 1.5)
    A3, A4 = rot_313(*RNG.uniform(-3, 3, 3)), rot_321(*RNG.uniform(-1.4, 1.4, 3))
    e3 = _quat(A3)
    markers = (f'<Reference_Marker id="5" body_id="1" psi="{float(psi)!r}" theta="{float(theta)!r}" '
               f'phi="{float(phi)!r}"/><Reference_Marker id="6" body_id="1" yaw="{float(yaw)!r}" '
               f'pitch="{float(pitch)!r}" roll="{float(roll)!r}"/>'
               f'<Reference_Marker id="7" body_id="1" '
               + " ".join(f'e{k}="{float(x)!r}"' for k, x in enumerate(e3)) + "/>"
               f'<Reference_Marker id="8" body_id="1" {_matrix_attrs(A4)}/>'
               '<Reference_Marker id="20" body_id="2"/>')
    requests = ('<Post_Request id="1" expr1="PSI(5)" expr2="THETA(5)" expr3="PHI(5)" '
                'expr4="YAW(6)" expr5="PITCH(6)" expr6="ROLL(6)"/>'
                '<Post_Request id="2" expr1="PSI(7,8)" expr2="THETA(7,8)" expr3="PHI(7,8)" '
                'expr4="YAW(7,8)" expr5="PITCH(7,8)" expr6="ROLL(7,8)"/>')
    res = pysolver.loads(_scene(markers, requests, end="0.1")).run()
    assert res.success, res.message
    np.testing.assert_allclose(res.request(1)[0, :6], [psi, theta, phi, yaw, pitch, roll],
                               rtol=0, atol=1e-12)
    R = A4.T @ A3
    want = [np.arctan2(R[0, 2], -R[1, 2]), np.arccos(R[2, 2]), np.arctan2(R[2, 0], R[2, 1]),
            np.arctan2(R[1, 0], R[0, 0]), np.arcsin(R[2, 0]), np.arctan2(R[2, 1], R[2, 2])]
    np.testing.assert_allclose(res.request(2)[0, :6], want, rtol=0, atol=1e-12)


def test_the_3_1_3_angles_of_an_unturned_marker_are_zero_and_a_turn_about_z_is_phi():
    """At theta = 0 only psi + phi is defined: PSI = 0 and PHI the whole turn."""
    markers = ('<Reference_Marker id="5" body_id="1"/>'
               '<Reference_Marker id="6" body_id="1" psi="0.7"/>'
               '<Reference_Marker id="7" body_id="1" psi="0.3" theta="3.141592653589793"/>'
               '<Reference_Marker id="20" body_id="2"/>')
    requests = ('<Post_Request id="1" expr1="PSI(5)" expr2="THETA(5)" expr3="PHI(5)" '
                'expr4="PSI(6)" expr5="PHI(6)" expr6="PHI(7)" expr7="THETA(7)"/>')
    res = pysolver.loads(_scene(markers, requests, end="0.1")).run()
    np.testing.assert_allclose(res.request(1)[0, :7], [0, 0, 0, 0, 0.7, -0.3, np.pi],
                               rtol=0, atol=1e-12)


MARKERS = ('<Reference_Marker id="3" body_id="1" yaw="0.3" pitch="0.5" roll="-0.7" pos_x="1"/>'
           '<Reference_Marker id="20" body_id="2" pos_y="1" psi="0.2"/>'
           '<Reference_Marker id="21" body_id="2" pos_y="1.5" theta="0.4" pos_z="0.2"/>')


@pytest.mark.parametrize("kind, exprs", [
    ("MARKER_DISPLACEMENT", ["DM(21,3)", "DX(21,3,3)", "DY(21,3,3)", "DZ(21,3,3)", None,
                             "PSI(21,3)", "THETA(21,3)", "PHI(21,3)"]),
    ("MARKER_VELOCITY", ["VM(21,3)", "VX(21,3,3)", "VY(21,3,3)", "VZ(21,3,3)",
                         "SQRT(WX(21,3)**2 + WY(21,3)**2 + WZ(21,3)**2)", "WX(21,3,3)",
                         "WY(21,3,3)", "WZ(21,3,3)"]),
    ("MARKER_ACCELERATION", ["SQRT(ACCX(21,3)**2 + ACCY(21,3)**2 + ACCZ(21,3)**2)",
                             "ACCX(21,3,3)", "ACCY(21,3,3)", "ACCZ(21,3,3)",
                             "SQRT(WDTX(21,3)**2 + WDTY(21,3)**2 + WDTZ(21,3)**2)",
                             "WDTX(21,3,3)", "WDTY(21,3,3)", "WDTZ(21,3,3)"]),
])
def test_a_marker_request_is_its_eight_expressions(kind, exprs):
    """Of marker 21 on a tumbling body relative to a turned ground marker, in its axes: equal
    to the EXPRESSION request written out, at every row (1e-12), with the channel names of
    Adams' and msolve's requests."""
    req = (f'<Post_Request id="1" type="{kind}" i_marker_id="21" j_marker_id="3" '
           'ref_marker_id="3"/><Post_Request id="2" '
           + " ".join(f'expr{k + 1}="{e}"' for k, e in enumerate(exprs) if e) + "/>")
    model = pysolver.loads(_scene(MARKERS, req))
    res = model.run()
    assert res.success, res.message
    a, b = res.request(1), res.request(2)
    np.testing.assert_allclose(a, b, rtol=0, atol=1e-12)
    assert np.isnan(a[:, 4]).all() == (kind == "MARKER_DISPLACEMENT")
    assert model.requests[1].names[:2] == {"MARKER_DISPLACEMENT": ["mag", "x"],
                                           "MARKER_VELOCITY": ["vm", "vx"],
                                           "MARKER_ACCELERATION": ["accm", "accx"]}[kind]


@pytest.mark.parametrize("attrs, attribute, words", [
    ('type="MARKER_DISPLACEMENT" i_marker_id="99"', "i_marker_id", "marker 99 does not exist"),
    ('type="MARKER_DISPLACEMENT" i_marker_id="21" ref_marker_id="98"', "ref_marker_id",
     "marker 98 does not exist"),
    ('type="MARKER_VELOCITY"', "i_marker_id", "needs i_marker_id"),
    ('type="MARKER_DISPLACEMENT" i_marker_id="21" expr1="DX(21)"', "expr1",
     "computes its channels"),
])
def test_a_bad_marker_request_is_a_deck_error(attrs, attribute, words):
    with pytest.raises(DeckError, match=words) as err:
        pysolver.loads(_scene(MARKERS, f'<Post_Request id="4" {attrs}/>'))
    assert (err.value.element, err.value.id, err.value.attribute) == ("Post_Request", 4,
                                                                      attribute)


#: A body on a spherical joint (5) to a turned ground marker, held by a bushing (6), a
#: spring-damper (7) and a scalar force (8), with a second body on a revolute (9) driven by a
#: motion (10): every element type an ELEMENTAL_FORCE request names.
ELEMENTS = MARKERS + """
  <Reference_Marker id="22" body_id="2" pos_x="0.3" pos_y="1.1"/>
  <Reference_Marker id="30" body_id="3" pos_x="2"/><Reference_Marker id="31" body_id="3"
    pos_x="2" pos_y="0.5"/><Reference_Marker id="4" body_id="1" pos_x="2" pos_y="0.5"/>
  <Body_Rigid id="3" cg_id="30" mass="2" inertia_xx="0.1" inertia_yy="0.1" inertia_zz="0.1"/>
  <Constraint_Joint id="5" type="SPHERICAL" i_marker_id="20" j_marker_id="3"/>
  <Force_Bushing id="6" i_marker_id="21" j_marker_id="1" kx="40" ky="50" kz="60" ktx="3"
    kty="4" ktz="5" cx="1" cy="1" cz="1" ctx="0.1" cty="0.1" ctz="0.1"/>
  <Force_SpringDamper id="7" type="TRANSLATIONAL" i_marker_id="22" j_marker_id="1"
    stiffness="30" damping="0.5" length="0.8"/>
  <Force_Scalar_TwoBody id="8" type="Force" i_marker_id="22" j_marker_id="3"
    val_expression="2*SIN(TIME)"/>
  <Constraint_Joint id="9" type="REVOLUTE" i_marker_id="31" j_marker_id="4"/>
  <Motion_Joint id="10" joint_id="9" motion_type="R" val_type="D" expr="0.4*SIN(3*TIME)"/>"""

ELEMENT_KINDS = [("JOINT", "JOINT", 5), ("Constraint_Jprim", "JOINT", 5),
                 ("Bushing", "BUSH", 6), ("SPRINGDAMPER", "SPDP", 7),
                 ("Force_Scalar_TwoBody", "SFORCE", 8), ("MOTION", "MOTION", 10)]


@pytest.mark.parametrize("jflag", ["0", "1"])
def test_an_elemental_force_request_is_its_element_s_force_function(jflag):
    """ELEMENTAL_FORCE (what MotionView writes for joint and bushing outputs; its element id
    attribute, elem_id, is a decision): the element's force and torque on I (jflag 0) or J (1),
    in ref_marker_id's axes: at every row exactly the EXPRESSION request FN(elem_id, jflag,
    1..8, rm), with MARKER_FORCE's channel names; and the spherical joint's reaction on the
    body (jflag 0, global axes) closes Newton's second law of its centre of mass with gravity
    and the other three forces (1e-7 of the weight)."""
    reqs = []
    for k, (kind, fn, eid) in enumerate(ELEMENT_KINDS):
        reqs.append(f'<Post_Request id="{k + 1}" type="ELEMENTAL_FORCE" elem_type="{kind}" '
                    f'elem_id="{eid}" jflag="{jflag}" ref_marker_id="3"/>')
        reqs.append(f'<Post_Request id="{k + 11}" ' + " ".join(
            f'expr{c}="{fn}({eid},{jflag},{c},3)"' for c in range(1, 9)) + "/>")
    reqs.append('<Post_Request id="30" type="ELEMENTAL_FORCE" elem_type="JOINT" elem_id="5"/>'
                '<Post_Request id="31" type="MARKER_ACCELERATION" i_marker_id="20"/>'
                + "".join(f'<Post_Request id="{32 + n}" type="ELEMENTAL_FORCE" '
                          f'elem_type="{kind}" elem_id="{eid}"/>'
                          for n, (kind, eid) in enumerate((("BUSHING", 6), ("SPRINGDAMPER", 7),
                                                           ("SFORCE", 8)))))
    model = pysolver.loads(_scene(ELEMENTS, "".join(reqs), end="0.5"))
    res = model.run(integr_tol=1e-10)
    assert res.success, res.message
    for k in range(len(ELEMENT_KINDS)):
        assert model.requests[k + 1].names == ["fm", "fx", "fy", "fz", "tm", "tx", "ty", "tz"]
        np.testing.assert_array_equal(res.request(k + 1), res.request(k + 11))
    if jflag == "0":
        # m a = m g + joint + bushing + spring + sforce, each force's action on body 2
        total = sum(res.request(i)[:, 1:4] for i in (30, 32, 33, 34))
        ma = 1.5 * (res.request(31)[:, 1:4] - [0.0, -9.81, 0.0])
        np.testing.assert_allclose(total, ma, rtol=0, atol=1e-7 * 1.5 * 9.81)
        assert np.abs(res.request(30)[:, 2]).max() > 1.0       # the joint carries load


@pytest.mark.parametrize("attrs, attribute, message", [
    ('type="ELEMENTAL_FORCE" elem_type="CONTACT" elem_id="7"', "elem_type",
     "got 'CONTACT'; expected an element with a force function: JOINT (JPRIM), BUSHING, "
     "FIELD, BEAM, SPRINGDAMPER, SFORCE or MOTION"),
    ('type="ELEMENTAL_FORCE" elem_id="5"', "elem_type",
     "an ELEMENTAL_FORCE request needs elem_type"),
    ('type="ELEMENTAL_FORCE" elem_type="JOINT"', "elem_id",
     "an ELEMENTAL_FORCE request needs elem_id"),
    ('type="ELEMENTAL_FORCE" elem_type="JOINT" elem_id="99"', "elem_id",
     "joint 99 does not exist"),
    ('type="ELEMENTAL_FORCE" elem_type="BUSHING" elem_id="5"', "elem_id",
     "bushing 5 does not exist"),
    ('type="ELEMENTAL_FORCE" elem_type="JOINT" elem_id="5" ref_marker_id="98"',
     "ref_marker_id", "marker 98 does not exist"),
    ('type="ELEMENTAL_FORCE" elem_type="JOINT" elem_id="5" jflag="2"', "jflag",
     "got '2'; expected one of 0, 1"),
    ('type="ELEMENTAL_FORCE" elem_type="JOINT" elem_id="5" i_marker_id="20"', "i_marker_id",
     "an ELEMENTAL_FORCE request computes its channels from elem_type, elem_id, jflag and "
     "ref_marker_id"),
    ('type="ELEMENTAL_FORCE" elem_type="JOINT" elem_id="5" expr2="TIME"', "expr2",
     "an ELEMENTAL_FORCE request computes its channels from elem_type, elem_id, jflag and "
     "ref_marker_id"),
    ('expr1="TIME" elem_id="7"', "elem_id",
     "elem_id belongs to an ELEMENTAL_FORCE request, not EXPRESSION"),
    ('type="MARKER_FORCE" i_marker_id="20" jflag="1"', "jflag",
     "jflag belongs to an ELEMENTAL_FORCE request, not MARKER_FORCE"),
    ('type="ELEMENTAL_FORCE" elem_type="JOINT" elem_id="5" script_name="x.py"', "script_name",
     "script_name belongs to a USERSUB request, not ELEMENTAL_FORCE"),
    ('type="ELEMENTAL_FORCE" elem_type="JOINT" elem_id="5" usrsub_param_string="USER(1)"',
     "usrsub_param_string", "usrsub_param_string belongs to a USERSUB request, not "
     "ELEMENTAL_FORCE"),
])
def test_a_bad_elemental_force_request_is_a_deck_error(attrs, attribute, message):
    """One DeckError on the element, line and attribute, saying what was expected."""
    text = _scene(ELEMENTS, f'<Post_Request id="4" {attrs}/>')
    with pytest.raises(DeckError) as err:
        pysolver.loads(text)
    assert (err.value.element, err.value.id, err.value.attribute) == ("Post_Request", 4,
                                                                      attribute)
    assert str(err.value).endswith(f"attribute '{attribute}': {message}")
    assert err.value.line == text.splitlines().index(
        next(ln for ln in text.splitlines() if "Post_Request" in ln)) + 1


@pytest.mark.parametrize("suffix", [".adm", ".py"])
def test_an_elemental_force_request_converts_to_its_functions(tmp_path, suffix):
    """Adams and msolve have no ELEMENTAL_FORCE: a conversion writes the element's force
    function in F1..F8 with the channel names, and runs the same (1e-9)."""
    req = ('<Post_Request id="1" type="ELEMENTAL_FORCE" elem_type="Bushing" elem_id="6" '
           'jflag="1" ref_marker_id="3" name2="bx"/>')
    src = tmp_path / "deck.xml"
    src.write_text(_scene(ELEMENTS, req, end="0.3"))
    out = tmp_path / f"deck{suffix}"
    convert(src, out)
    text = out.read_text()
    assert "BUSH(6,1,2,3)" in text.replace(" ", "")
    a, b = pysolver.load(src).run(), pysolver.load(out).run()
    assert a.success and b.success
    np.testing.assert_allclose(b.request(1), a.request(1), rtol=0, atol=1e-9)
    assert pysolver.load(out).requests[1].names == ["fm", "bx", "fy", "fz", "tm", "tx", "ty",
                                                    "tz"]


def test_two_orientation_forms_on_one_marker_are_a_deck_error():
    with pytest.raises(DeckError, match="give one orientation form only") as err:
        pysolver.loads(_scene('<Reference_Marker id="20" body_id="2" psi="1" yaw="2"/>', ""))
    assert err.value.attribute == "yaw"


def test_an_lprf_off_the_global_frame_warns_and_moves_no_marker():
    """Decision (docs/deck-language.md, "Placement"): positions are global as MotionSolve's
    Reference_Marker says; an LPRF elsewhere is named in a DeckWarning, and the body is where
    its markers say."""
    text = _scene('<Reference_Marker id="20" body_id="2" pos_x="2"/>'
                  '<Reference_Marker id="24" body_id="2" pos_x="5" psi="1"/>',
                  '<Post_Request id="1" expr1="DX(20)"/>', end="0.1").replace(
        'cg_id="20"', 'cg_id="20" lprf_id="24"')
    with pytest.warns(DeckWarning, match="lprf_id 24 is not the global frame") as got:
        model = pysolver.loads(text)
    assert got[0].message.element == "Body_Rigid" and got[0].message.attribute == "lprf_id"
    assert model.run().request(1)[0, 0] == 2.0
    with warnings.catch_warnings():
        warnings.simplefilter("error")          # an LPRF at the global frame says nothing
        pysolver.loads(text.replace('pos_x="5" psi="1"', ""))


WDT = ('<Reference_Marker id="40" body_id="4" pos_x="2"/>'
       '<Body_Rigid id="4" cg_id="40" mass="1" inertia_xx="0.2" inertia_yy="0.25" '
       'inertia_zz="0.3" w_ic_x="-0.5" w_ic_z="1"/>'
       '<Force_Vector_OneBody id="1" marker_id="21" type="FORCEANDTORQUE" fx_expression="0.3" '
       'tz_expression="0.5" ty_expression="0.1*TIME"/>')


def test_angular_accelerations_are_the_rates_of_the_angular_velocities():
    """WDTX/Y/Z of a torqued tumbling body relative to another tumbling body: in the global
    frame (resolved in a turned ground marker) and in the other body's frame (resolved in
    its axes), against central differences of WX/Y/Z over 1 ms rows (within 2e-5 of up to
    2 rad/s^2; measured 7e-6, the differences' own error)."""
    req = ('<Post_Request id="1" expr1="WX(21,40,3)" expr2="WY(21,40,3)" expr3="WZ(21,40,3)" '
           'expr4="WDTX(21,40,3)" expr5="WDTY(21,40,3)" expr6="WDTZ(21,40,3)"/>'
           '<Post_Request id="2" expr1="WX(21,40,40)" expr2="WY(21,40,40)" expr3="WZ(21,40,40)" '
           'expr4="WDTX(21,40,40,40)" expr5="WDTY(21,40,40,40)" expr6="WDTZ(21,40,40,40)"/>')
    text = _scene(MARKERS + WDT, req).replace('print_interval="0.1"', 'print_interval="0.001"')
    res = pysolver.loads(text).run(integr_tol=1e-11)
    assert res.success, res.message
    t = res.t
    for rid in (1, 2):
        q = res.request(rid)
        rate = np.gradient(q[:, :3], t, axis=0)
        assert np.abs(q[:, 3:6]).max() > 0.5
        assert np.abs(q[5:-5, 3:6] - rate[5:-5]).max() < 2e-5


def test_magnitude_functions_are_the_norms_of_their_components():
    """WM(i, j), ACCM(i, j, l), WDTM(i, j, l) equal the norms of WX..WZ, ACCX..ACCZ and
    WDTX..WDTZ (1e-12), relative to another tumbling body and seen from its frame."""
    def norm(f, ids):
        return "SQRT(" + " + ".join(f"{f}{c}({ids})**2" for c in "XYZ") + ")"
    req = ('<Post_Request id="1" expr1="WM(21,40)" expr2="ACCM(21,40,40)" '
           'expr3="WDTM(21,40,40)" expr4="ACCM(21)" '
           f'expr5="{norm("W", "21,40")}" expr6="{norm("ACC", "21,40,0,40")}" '
           f'expr7="{norm("WDT", "21,40,0,40")}" expr8="{norm("ACC", "21")}"/>')
    res = pysolver.loads(_scene(MARKERS + WDT, req)).run()
    assert res.success, res.message
    q = res.request(1)
    assert q[:, :4].min() > 0.1
    np.testing.assert_allclose(q[:, :4], q[:, 4:], rtol=1e-12, atol=1e-12)


def test_initial_velocities_along_the_axes_of_vm_and_wm_markers():
    """vm_id and wm_id give the axes of v_ic and w_ic (a ground marker turned 90 degrees about
    z): x of that marker is global y, so the body starts along global y and spins about it."""
    markers = ('<Reference_Marker id="7" body_id="1" psi="1.5707963267948966"/>'
               '<Reference_Marker id="20" body_id="2"/>')
    req = '<Post_Request id="1" expr1="VX(20)" expr2="VY(20)" expr3="WX(20)" expr4="WY(20)"/>'
    text = _scene(markers, req, end="0.1").replace(
        'w_ic_x="1" w_ic_y="0.3" w_ic_z="2" v_ic_x="0.5"',
        'w_ic_x="0.2" v_ic_x="0.5" vm_id="7" wm_id="7"').replace(
        'inertia_xx="0.2" inertia_yy="0.3" inertia_zz="0.4"',
        'inertia_xx="0.3" inertia_yy="0.3" inertia_zz="0.3"').replace(
        'grav_y="-9.81"', 'grav_y="0"')
    res = pysolver.loads(text).run()
    np.testing.assert_allclose(res.request(1)[:, :4], [[0, 0.5, 0, 0.2]] * 2, atol=1e-12)


def test_orient_27_is_adams_euler_parameters():
    """ORIENT(27, k, i[, j]): Adams' published example (REULER 180D, 90D, 180D prints
    0.70711, -0.70711, 0, 0) and the parameters of A_J^T A_I for a turned pair, e0 >= 0;
    other systems are refused."""
    from pysolver.rotations import e_from_rot
    markers = ('<Reference_Marker id="5" body_id="1" psi="3.141592653589793" '
               'theta="1.5707963267948966" phi="3.141592653589793"/>'
               '<Reference_Marker id="6" body_id="1" psi="0.4" theta="2.2" phi="-1.3"/>'
               '<Reference_Marker id="20" body_id="2"/>')
    req = ('<Post_Request id="1" ' + " ".join(f'expr{k}="ORIENT(27,{k},5)"' for k in range(1, 5))
           + " " + " ".join(f'expr{k + 4}="ORIENT(27,{k},6,5)"' for k in range(1, 5)) + "/>")
    res = pysolver.loads(_scene(markers, req, end="0.1")).run()
    e = e_from_rot(rot_313(np.pi, np.pi / 2, np.pi).T @ rot_313(0.4, 2.2, -1.3))
    e = e if e[0] >= 0 else -e
    np.testing.assert_allclose(res.request(1)[0, :4], [0.5 ** 0.5, -0.5 ** 0.5, 0, 0],
                               atol=1e-12)
    np.testing.assert_allclose(res.request(1)[0, 4:], e, atol=1e-12)
    for bad in ("ORIENT(13,1,5)", "ORIENT(3,4,5)", "ORIENT(27,5,5)"):
        with pytest.raises(DeckError, match="pysolver computes systems 1..12"):
            pysolver.loads(_scene(markers, f'<Post_Request id="1" expr1="{bad}"/>'))


@pytest.mark.parametrize("system", range(1, 13))
def test_orient_body_fixed_sequences_are_scipys_intrinsic_euler_angles(system):
    """ORIENT(1..12, k, i, j): Adams' body-fixed sequences (1-2-3 ... 3-2-3) of A_J^T A_I
    equal SciPy's as_euler with intrinsic axes (1e-12), and rebuild the rotation."""
    from scipy.spatial.transform import Rotation

    from pysolver.build.angles import SEQUENCES
    markers = ('<Reference_Marker id="5" body_id="1" psi="1.1" theta="0.3" phi="2.5"/>'
               '<Reference_Marker id="6" body_id="1" psi="0.4" theta="2.2" phi="-1.3"/>'
               '<Reference_Marker id="20" body_id="2"/>')
    req = '<Post_Request id="1" ' + " ".join(
        f'expr{k}="ORIENT({system},{k},6,5)"' for k in (1, 2, 3)) + "/>"
    res = pysolver.loads(_scene(markers, req, end="0.1")).run()
    R = rot_313(1.1, 0.3, 2.5).T @ rot_313(0.4, 2.2, -1.3)
    axes = "".join("XYZ"[a - 1] for a in SEQUENCES[system - 1])
    got = res.request(1)[0, :3]
    np.testing.assert_allclose(got, Rotation.from_matrix(R).as_euler(axes), atol=1e-12)
    np.testing.assert_allclose(Rotation.from_euler(axes, got).as_matrix(), R, atol=1e-12)


def test_unwrapped_angles_count_every_turn():
    """AXU, AYU, AZU (MotionSolve's unwrapped AX, AY, AZ; each a tracked angle, one state per
    name and marker pair): bodies spun about x, y and z at 5 rad/s read 5 t through almost two
    turns, where AX..AZ wrap (docs/deck-language.md, "Angles and requests")."""
    markers = "".join(f'<Reference_Marker id="{30 + k}" body_id="{3 + k}" pos_x="{k}"/>'
                      f'<Body_Rigid id="{3 + k}" cg_id="{30 + k}" mass="1" inertia_xx="0.3" '
                      f'inertia_yy="0.3" inertia_zz="0.3" w_ic_{c}="5"/>'
                      for k, c in enumerate("xyz")) + '<Reference_Marker id="20" body_id="2"/>'
    req = ('<Post_Request id="1" expr1="AXU(30)" expr2="AYU(31,1)" expr3="AZU(32)" '
           'expr4="AX(30)" expr5="AY(31)" expr6="AZ(32)"/>')
    text = _scene(markers, req, end="2").replace('grav_y="-9.81"', 'grav_y="0"')
    for kernel in ("tapes", "generated"):
        res = pysolver.loads(text).run(kernel=kernel)
        assert res.success, res.message
        q, t = res.request(1), res.t
        np.testing.assert_allclose(q[:, :3], np.outer(5 * t, [1, 1, 1]), rtol=0, atol=1e-8)
        np.testing.assert_allclose(q[:, 3:6], np.angle(np.exp(1j * q[:, :3])), rtol=0,
                                   atol=1e-8)
        assert np.abs(q[:, 3:6]).max() <= np.pi + 1e-12
        assert [n for n in res.state_names if n.endswith(".angle")] == [
            "AX_30_0.angle", "AY_31_1.angle", "AZ_32_0.angle"]
