"""Mass properties of parts: products of inertia are positive integrals (Adams' PART IP,
MotionSolve's inertia_xy.., msolve's ip: the tensor holds -Ixy), the inertia is given about
the IM marker's origin along its axes and moved to the centre of mass, a massless or
inertia-less part is refused naming the keywords of its deck. docs/deck-language.md,
"Mass properties"."""
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pysolver
from pysolver import DeckError, DeckWarning
from pysolver.convert import convert

from helpers import TEST_DECKS

INERTIA = TEST_DECKS / "inertia"
#: The tumbler's inertia about its centre of mass (Ixy, Ixz, Iyz = 0.5, 0.3, 0.2).
TUMBLER = np.array([[2.0, -0.5, -0.3], [-0.5, 3.0, -0.2], [-0.3, -0.2, 4.0]])
FORMS = ("tumbler.adm", "tumbler.xml", "tumbler_statements.py", "tumbler_classes.py")


def _load(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeckWarning)
        return pysolver.load(path)


def _bodies(model):
    """Every number of a model's bodies and markers (its mass properties among them)."""
    out = []
    for b in model.bodies.values():
        out += [b.mass, b.inertia, b.pos, b.rot, b.vel, b.omega, b.im_rot, b.inertia_im, b.im]
    for m in model.markers.values():
        out += [m.body, m.pos, m.rot]
    return out


def _euler(inertia, omega0, t):
    """Body-axis angular velocity of a free body by Euler's equations, at times t."""
    inv = np.linalg.inv(inertia)
    sol = solve_ivp(lambda _, w: inv @ -np.cross(w, inertia @ w), (0, t[-1]), omega0,
                    t_eval=t, rtol=1e-12, atol=1e-12)
    return sol.y.T


@pytest.mark.parametrize("form", FORMS)
def test_a_free_body_with_products_and_an_offset_im_tumbles_as_eulers_equations(form):
    """The tumbler (tests/decks/inertia) in each of its four forms: IP about an IM marker
    0.5 from the CM and turned 90 degrees, products as positive integrals in each form's
    order (Adams' IP xy, xz, yz; msolve's PART IP xy, yz, xz): the model's inertia about the
    centre of mass is the tensor with -Ixy.., and the body's angular velocity follows
    Euler's equations with it to 1e-7 over 2 s (measured 7e-10 at integr_tol 1e-10; the
    tensor with +Ixy.. is 0.38 rad/s away)."""
    model = _load(INERTIA / form)
    np.testing.assert_allclose(model.bodies[2].inertia, TUMBLER, rtol=0, atol=1e-15)
    res = model.run(integr_tol=1e-10)
    assert res.success and res.t[-1] == pytest.approx(2.0)
    omega = res.request(1)[:, :3]
    assert np.abs(omega - _euler(TUMBLER, [1.0, 0.2, -0.4], res.t)).max() < 1e-7
    flipped = TUMBLER * np.where(np.eye(3) == 1, 1, -1)
    assert np.abs(omega - _euler(flipped, [1.0, 0.2, -0.4], res.t)).max() > 0.1


def test_conversions_keep_the_tumblers_body(tmp_path):
    """pysolver convert of the tumbler to XML, an Adams dataset and msolve classes, and each
    back: the same model number for number, the same answer to the last bit."""
    ref = _load(INERTIA / "tumbler.adm")
    res = ref.run(integr_tol=1e-10)
    for ext in (".xml", ".adm", ".py"):
        first = tmp_path / f"first{ext}"
        convert(INERTIA / "tumbler.adm", first)
        again = tmp_path / f"again{ext}"
        convert(first, again)
        for path in (first, again):
            model = _load(path)
            for got, want in zip(_bodies(model), _bodies(ref), strict=True):
                np.testing.assert_array_equal(got, want, err_msg=path.name)
            assert np.array_equal(model.run(integr_tol=1e-10).request(1), res.request(1),
                                  equal_nan=True)


# A dumbbell, two 1 kg masses at (1, 1, 0) and (-1, -1, 0) from the centre of a 1 kg frame
# (inertia 0.1), each mass with inertia 0.01: built of three parts held by FIXED joints,
# which need no convention, and as one part with its IP (Ixy = +2, the integral of x*y dm).
DUMBBELL = """dumbbell: one part with IP, and three parts joined by FIXED joints
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 3, CM = 20, IP = 2.12, 2.12, 4.12, 2, 0, 0, WX = 1
MARKER/20, PART = 2
PART/3, MASS = 1, CM = 30, IP = 0.1, 0.1, 0.1, QG = 10, 0, 0, WX = 1
MARKER/30, PART = 3
MARKER/31, PART = 3, QP = 1, 1, 0
MARKER/32, PART = 3, QP = -1, -1, 0
PART/4, MASS = 1, CM = 40, IP = 0.01, 0.01, 0.01, QG = 11, 1, 0, WX = 1, VZ = 1
MARKER/40, PART = 4
PART/5, MASS = 1, CM = 50, IP = 0.01, 0.01, 0.01, QG = 9, -1, 0, WX = 1, VZ = -1
MARKER/50, PART = 5
JOINT/1, FIXED, I = 40, J = 31
JOINT/2, FIXED, I = 50, J = 32
REQUEST/1, F1 = WX(20)\\F2 = WY(20)\\F3 = WZ(20)\\F4 = WX(30)\\F5 = WY(30)\\F6 = WZ(30)\\
END
"""
#: The one part in MotionSolve XML (inertia_xy = +2, as Adams' IP).
DUMBBELL_XML = """<MotionSolve><Model>
  <Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="20" body_id="2"/>
  <Body_Rigid id="2" cg_id="20" mass="3" inertia_xx="2.12" inertia_yy="2.12" inertia_zz="4.12"
              inertia_xy="2" w_ic_x="1"/>
  <Post_Request id="1" expr1="WX(20)" expr2="WY(20)" expr3="WZ(20)"/>
</Model><Simulate analysis_type="Transient" end_time="1" print_interval="0.01"/></MotionSolve>
"""


def test_a_part_with_products_turns_as_the_parts_it_is_made_of(tmp_path):
    """The dumbbell spun about x: the part with IP (Adams, and the same numbers in XML)
    turns as the three fixed parts do, angular velocity equal to 1e-6 over 1 s (measured
    8e-9 at integr_tol 1e-9; read with +Ixy in the tensor its y and z components had the
    opposite sign)."""
    path = tmp_path / "dumbbell.adm"
    path.write_text(DUMBBELL)
    res = _load(path).run(integr_tol=1e-9)
    q = res.request(1)
    assert res.success and res.t[-1] == pytest.approx(1.0)
    assert abs(q[-1, 1]) > 0.1 and abs(q[-1, 2]) > 0.4     # it wobbles
    assert np.abs(q[:, :3] - q[:, 3:6]).max() < 1e-6
    xml = pysolver.loads(DUMBBELL_XML).run(integr_tol=1e-9)
    np.testing.assert_allclose(xml.t, res.t)
    assert np.abs(xml.request(1)[:, :3] - q[:, 3:6]).max() < 1e-6


# inertia 1, 2, 3 about the CM; the IM marker 2 m from it along y, turned 90 degrees about
# z: about the IM origin along its axes the 4 kg part has 2, 1 + 4*4 = 17, 3 + 4*4 = 19
IM_ADAMS = """IM marker away from the CM
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 4.0, CM = 20, IM = 21, IP = 2.0, 17.0, 19.0
MARKER/20, PART = 2
MARKER/21, PART = 2, QP = 0, 2, 0, REULER = 90D, 0, 0
MARKER/22, PART = 1, FLOATING
VTORQUE/1, I = 20, JFLOAT = 22, RM = 1, TX = 1.0\\TY = 2.0\\TZ = 3.0
REQUEST/1, F1 = WDTX(20)\\F2 = WDTY(20)\\F3 = WDTZ(20)\\
END
"""
IM_XML = """<MotionSolve><Model>
  <Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="1" body_id="1"/>
  <Reference_Marker id="20" body_id="2"/>
  <Reference_Marker id="21" body_id="2" pos_y="2" psi="1.5707963267948966"/>
  <Body_Rigid id="2" cg_id="20" im_id="21" mass="4" inertia_xx="2" inertia_yy="17"
              inertia_zz="19"/>
  <Force_Vector_OneBody id="1" type="TORQUEONLY" marker_id="20" ref_marker_id="1"
                        tx_expression="1" ty_expression="2" tz_expression="3"/>
  <Post_Request id="1" expr1="WDTX(20)" expr2="WDTY(20)" expr3="WDTZ(20)"/>
</Model><Simulate analysis_type="Transient" end_time="0.01" print_interval="0.01"/>
</MotionSolve>
"""


@pytest.mark.parametrize("form", ["adm", "xml"])
def test_the_inertia_is_about_the_im_markers_origin(tmp_path, form):
    """Torques 1, 2, 3 on the part at rest give it angular accelerations 1, 1, 1: about its
    CM the inertia is 1, 2, 3 (reading IP as if about the CM gave 1/17, 2/2, 3/19)."""
    if form == "adm":
        path = tmp_path / "im.adm"
        path.write_text(IM_ADAMS)
        model = _load(path)
    else:
        model = pysolver.loads(IM_XML)
    np.testing.assert_allclose(model.bodies[2].inertia, np.diag([1.0, 2.0, 3.0]), atol=1e-13)
    res = model.run(integr_tol=1e-10)
    np.testing.assert_allclose(res.request(1)[0, :3], [1.0, 1.0, 1.0], rtol=1e-9)


def test_an_im_that_leaves_no_inertia_at_the_centre_of_mass_is_refused(tmp_path):
    """IP 2, 17, 19 about an IM 3 m from the CM: 17 - 4*9 < 0 about the CM."""
    path = tmp_path / "far.adm"
    path.write_text(IM_ADAMS.replace("QP = 0, 2, 0", "QP = 0, 3, 0"))
    with pytest.raises(DeckError) as info:
        _load(path)
    err = info.value
    assert (err.line, err.element, err.attribute) == (5, "PART/2 (Body_Rigid)", "IM")
    assert err.reason == (
        "the inertia about IM marker 21's origin, (0, 3, 0) from the centre of mass along the "
        "CM marker's axes, less the parallel-axis term m(|d|^2 E - d d^T) is not positive "
        "definite: give the inertia about the IM marker's origin, not about the centre of "
        "mass")


MASSLESS = ("pysolver has no massless parts: give it a small mass, a centre-of-mass marker "
            "and a small inertia (docs/deck-language.md, \"Massless parts\")")
DUMMY = """a dummy part fixed to a massive one
UNITS/SYSTEM = MKS
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 1, 1, 1, QG = 1, 0, 0
MARKER/20, PART = 2
PART/3, {part3}
MARKER/30, PART = 3
JOINT/1, FIXED, I = 30, J = 20
END
"""


@pytest.mark.parametrize("part3, attribute, reason", [
    ("QG = 1, 0, 0", "CM", f"missing: the centre-of-mass marker, and {MASSLESS}"),
    ("CM = 30, QG = 1, 0, 0", "MASS", f"missing: the mass, and {MASSLESS}"),
    ("MASS = 0, CM = 30", "MASS", "got 0; expected a value > 0"),
    ("MASS = 0.1, CM = 30", "IP", "missing: the part has no inertia (all its moments are "
     "0), and pysolver has no inertia-less parts: give it a small mass, a centre-of-mass "
     "marker and a small inertia (docs/deck-language.md, \"Massless parts\")"),
    ("MASS = 0.1, CM = 30, IP = 1, 1, -3", "IP", "the inertia tensor must be positive "
     "definite; its principal moments are -3, 1, 1"),
])
def test_a_massless_part_is_refused_naming_the_datasets_keywords(tmp_path, part3, attribute,
                                                                  reason):
    """Adams' dummy parts (no MASS, CM or IP: Adams' defaults are 0) are refused at the
    PART's line, naming its keyword, not the XML attribute it becomes."""
    path = tmp_path / "dummy.adm"
    path.write_text(DUMMY.format(part3=part3))
    with pytest.raises(DeckError) as info:
        _load(path)
    err = info.value
    assert (err.line, err.element, err.attribute, err.reason) == \
        (7, "PART/3 (Body_Rigid)", attribute, reason)


def test_a_massless_body_rigid_names_its_xml_attributes():
    deck = ('<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>\n'
            '<Reference_Marker id="30" body_id="3"/>\n'
            '<Body_Rigid id="3" cg_id="30" mass="0.1"/>\n</Model></MotionSolve>')
    with pytest.raises(DeckError) as info:
        pysolver.loads(deck)
    assert (info.value.line, info.value.attribute) == (3, "inertia_xx")


def test_a_sweep_keeps_the_inertia_about_the_centre_of_mass():
    """Sweep paths read and set the deck's numbers (products as positive integrals, about
    the IM origin): a product set to its own number changes nothing, the mass moves the
    parallel-axis term (a 5 kg part with the same IP: 1 - 4 = -3 about the CM is refused,
    the deck's values put back, as they are after any case refused) and so does the IM
    marker's place."""
    model = pysolver.loads(IM_XML.replace('inertia_zz="19"', 'inertia_zz="19" '
                                          'inertia_xy="0.25"'))
    compiled = model.compile()
    params = compiled.parameters
    deck = model.bodies[2].inertia.copy()
    assert deck[0, 1] == pytest.approx(0.25, abs=1e-14)    # -Ixy of the IM axes, turned
    params.apply({"Body_Rigid/2/inertia_xy": 0.25})
    np.testing.assert_array_equal(compiled.model.bodies[2].inertia, deck)
    params.apply({"Body_Rigid/2/mass": 4.2})
    np.testing.assert_allclose(np.diag(compiled.model.bodies[2].inertia),
                               [1.0 - 0.8, 2.0, 3.0 - 0.8], atol=1e-13)
    with pytest.raises(DeckError, match="body 2's inertia about its centre of mass"):
        params.apply({"Body_Rigid/2/mass": 5.0})
    np.testing.assert_array_equal(compiled.model.bodies[2].inertia, deck)
    with pytest.raises(DeckError, match="inertia tensor must be positive definite"):
        params.apply({"Body_Rigid/2/mass": 4.2, "Body_Rigid/2/inertia_xx": -1.0})
    assert compiled.model.bodies[2].mass == 4.0
    np.testing.assert_array_equal(compiled.model.bodies[2].inertia, deck)
    params.apply({"Reference_Marker/21/pos_y": 1.0})
    np.testing.assert_allclose(np.diag(compiled.model.bodies[2].inertia),
                               [13.0, 2.0, 15.0], atol=1e-13)
    res = pysolver.loads(IM_XML).run(params={"Reference_Marker/21/pos_y": 1.0},
                                     integr_tol=1e-10)
    np.testing.assert_allclose(res.request(1)[0, :3], [1 / 13, 1.0, 3 / 15], rtol=1e-8)


#: A free part whose principal moments (1E-3, 1E-3, 4.8E-1: FAST's nacelle-like numbers,
#: scaled) break the triangle inequality: no rigid body has them, but the tensor is positive
#: definite, so Euler's equations hold.
NOT_A_TRIANGLE = """a part with FAST's kind of inertia
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 1.0E-3, 1.0E-3, 4.8E-1
, WX = 0.3, WY = 0.1, WZ = 0.01
MARKER/20, PART = 2
REQUEST/1, F1 = WX(20, 1, 20)\\F2 = WY(20, 1, 20)\\F3 = WZ(20, 1, 20)\\
END
"""


def test_an_inertia_breaking_the_triangle_inequality_loads_with_a_warning(tmp_path):
    """Adams takes such a part (FAST writes 2-4 of them in each dataset): pysolver too, with
    a DeckWarning naming the part, its line and IP, and the part tumbles as Euler's equations
    say with that tensor."""
    path = tmp_path / "fast_like.adm"
    path.write_text(NOT_A_TRIANGLE)
    with pytest.warns(DeckWarning) as caught:
        model = pysolver.load(str(path))
    assert [str(w.message) for w in caught] == [
        f"{path}:5, PART/2 (Body_Rigid), attribute 'IP': the principal moments of inertia "
        "0.001, 0.001, 0.48 break the triangle inequality (the largest is more than the sum "
        "of the other two; a rigid body's never is); Adams takes such a part and so does "
        "pysolver: the tensor is positive definite, so the motion is defined "
        "(docs/deck-language.md, \"Mass properties\")"]
    res = model.run(integr_tol=1e-10)
    assert res.success
    inertia = np.diag([1e-3, 1e-3, 0.48])
    omega = res.request(1)[:, :3]
    assert np.abs(omega - _euler(inertia, [0.3, 0.1, 0.01], res.t)).max() < 1e-7
