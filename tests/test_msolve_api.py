"""The msolve class API's contract around simulate() and msolve's idioms (trial 43): a model
changed between analyses is refused where the change was made, a simulate() that raises
leaves the commands as they were, cm markers made without an owner, active=, name=, zv/xv,
Point.x, owners given twice, Motion errors in msolve's names, sweep() of an msolve Model and
the log line of the default run. Messages are checked whole; runs against closed forms."""
import sys
import warnings

import numpy as np
import pytest

import pysolver
from pysolver import DeckError, DeckWarning
from pysolver.msolve import (
    Accgrav,
    Joint,
    Marker,
    Model,
    Motion,
    Part,
    Point,
    PointMass,
    Request,
    Sforce,
    SpringDamper,
    Vector,
)

#: The advice every refusal of a change between analyses ends with.
REWRITE = ("pysolver runs every command from t = 0 with the model as it is, so this would "
           "rewrite the analyses before it too: build a new Model for the new values, or vary "
           "a number with model.load().run(params=...) or pysolver.sweep (docs/msolve.md)")


def _here():
    return sys._getframe(1).f_lineno


def _oscillator(k=100.0, mass=1.0):
    """A body on a spring along global x: x = v0 / w sin(w t), w = sqrt(k / m), v0 = 1."""
    model = Model()
    ground = Part(ground=True)
    anchor = Marker(body=ground, qp=[-1, 0, 0])
    body = Part(mass=mass, ip=[0.1] * 3, vx=1.0)
    body.cm = Marker(body=body)
    spring = SpringDamper(type="TRANSLATION", i=body.cm, j=anchor, k=k, c=0.0, length=1.0)
    Request(type="DISPLACEMENT", i=body.cm)
    return model, body, spring


def _swing(res, k, mass):
    w = np.sqrt(k / mass)
    return np.sin(w * res.t) / w


# ---- item 1: no change between analyses --------------------------------------------------
def test_a_change_between_simulates_is_refused_at_its_line_and_the_first_run_stands():
    """Trial 43's script: k and mass set between two simulate() calls. The second call is a
    DeckError at the first change (k, at its line) and records no command; the first
    Result stays the k = 100, m = 1 oscillator it was (1e-6 of the closed form)."""
    model, body, spring = _oscillator()
    first = model.simulate(type="DYNAMICS", end=1, dtout=0.1, integr_tol=1e-10)
    run_line = _here() - 1
    np.testing.assert_allclose(first.request(1)[:, 1], _swing(first, 100.0, 1.0), atol=1e-6)
    x_before = first.request(1)[:, 1].copy()
    spring.k = 400.0; body.mass = 5.0          # noqa: E702  (the trial's line)
    change_line = _here() - 1
    with pytest.raises(DeckError) as err:
        model.simulate(type="DYNAMICS", end=2, dtout=0.1)
    assert str(err.value) == (f"{__file__}:{change_line}, SpringDamper id=1, attribute 'k': "
                              f"changed after the simulate() at line {run_line}; {REWRITE}")
    assert (err.value.line, err.value.element, err.value.id, err.value.attribute) == \
        (change_line, "SpringDamper", 1, "k")
    assert [c for c, _ in model.commands] == ["SIMULATE/DYNAMICS, END = 1, DTOUT = 0.1"]
    np.testing.assert_array_equal(first.request(1)[:, 1], x_before)


def test_load_and_adm_refuse_the_change_too_and_setting_it_back_runs_on():
    """model.load() and model.adm() after a change are the same DeckError (at the mass
    line); setting the value back (or the same value again) is no change, and the second
    simulate() runs both commands from t = 0: the k = 100, m = 1 oscillator to t = 2."""
    model, body, _ = _oscillator()
    model.simulate(type="DYNAMICS", end=1, dtout=0.1)
    run_line = _here() - 1
    body.mass = 5.0
    line = _here() - 1
    for call in (model.load, model.adm, model.elements):
        with pytest.raises(DeckError) as err:
            call()
        assert str(err.value) == (f"{__file__}:{line}, Part id=2, attribute 'mass': changed "
                                  f"after the simulate() at line {run_line}; {REWRITE}")
    body.mass = 1
    body.vx = 1.0
    res = model.simulate(type="DYNAMICS", end=2, dtout=0.1, integr_tol=1e-10)
    assert res.t[-1] == pytest.approx(2.0) and len(res.t) == 21
    np.testing.assert_allclose(res.request(1)[:, 1], _swing(res, 100.0, 1.0), atol=1e-6)


def test_changes_before_the_first_simulate_apply():
    """k and mass set before the first simulate() are the model's: w = sqrt(400 / 5)."""
    model, body, spring = _oscillator()
    spring.k, body.mass = 400.0, 5.0
    res = model.simulate(type="DYNAMICS", end=1, dtout=0.05, integr_tol=1e-10)
    np.testing.assert_allclose(res.request(1)[:, 1], _swing(res, 400.0, 5.0), atol=1e-6)


def test_an_element_created_or_an_item_changed_in_place_after_a_simulate_is_refused():
    """A force created after a simulate() is refused at its line ("created"); an item of an
    attribute's list changed in place, which no assignment shows, is refused at the line
    that made the element ("changed in place")."""
    model, body, _ = _oscillator()
    ground_marker = model.entities[1]
    model.simulate(type="DYNAMICS", end=1, steps=2)
    run_line = _here() - 1
    Sforce(type="TRANSLATION", i=body.cm, j=ground_marker, function="1")
    line = _here() - 1
    with pytest.raises(DeckError) as err:
        model.simulate(type="DYNAMICS", end=2, steps=2)
    assert str(err.value) == (f"{__file__}:{line}, Sforce id=1: created after the simulate() "
                              f"at line {run_line}; {REWRITE}")

    model, body, _ = _oscillator()
    model.simulate(type="DYNAMICS", end=1, steps=2)
    run_line = _here() - 1
    body.ip[0] = 0.2
    with pytest.raises(DeckError) as err:
        model.simulate(type="DYNAMICS", end=2, steps=2)
    made = next(k for k, text in enumerate(open(__file__).read().splitlines(), 1)
                if "body = Part(mass=mass" in text)
    assert str(err.value) == (f"{__file__}:{made}, Part id=2, attribute 'ip': changed in "
                              f"place after the simulate() at line {run_line}; {REWRITE}")


def test_a_script_that_changes_the_model_between_commands_does_not_load(tmp_path):
    """pysolver.load of a script whose simulate() calls have a change between them: the
    DeckError names the script's line of the change."""
    path = tmp_path / "ms_change.py"
    path.write_text("from pysolver.msolve import *\n"
                    "model = Model()\n"
                    "ground = Part(ground=True)\n"
                    "body = Part(mass=1, ip=[1, 1, 1], cm=Marker())\n"
                    "model.simulate(type=\"DYNAMICS\", end=1, steps=2)\n"
                    "body.mass = 2\n"
                    "model.simulate(type=\"DYNAMICS\", end=2, steps=2)\n")
    with pytest.raises(DeckError) as err:
        pysolver.load(path)
    assert str(err.value) == (f"{path}:6, Part id=2, attribute 'mass': changed after the "
                              f"simulate() at line 5; {REWRITE}")


# ---- item 4: a simulate() that raises records nothing -------------------------------------
def test_a_failed_simulate_leaves_the_commands_and_a_corrected_call_runs():
    """An END before the previous end, and a run option out of range: each call raises,
    model.commands is what it was, and the corrected call runs (its rows equal a fresh
    model's)."""
    model, _, _ = _oscillator()
    model.simulate(type="DYNAMICS", end=1, steps=5)
    kept = list(model.commands)
    line = _here() + 2
    with pytest.raises(DeckError) as err:
        model.simulate(type="DYNAMICS", end=0.5, steps=5)
    # (the whole message is tests/test_msolve_classes.py's to check)
    assert (err.value.file, err.value.line, err.value.element, err.value.attribute) == \
        (__file__, line, "SIMULATE (Simulate)", "END")
    assert err.value.reason.endswith(" 0.5 must be after the start time 1")
    assert model.commands == kept
    res = model.simulate(type="DYNAMICS", end=2, steps=5)
    assert [round(t, 12) for t in res.t] == [0, 0.2, 0.4, 0.6, 0.8, 1, 1.2, 1.4, 1.6, 1.8, 2]

    model, _, _ = _oscillator()
    with pytest.raises(ValueError, match=r"integr_tol must be in \[1e-14, 1\]"):
        model.simulate(type="DYNAMICS", end=1, steps=5, integr_tol=1e-20)
    assert model.commands == []
    res = model.simulate(type="DYNAMICS", end=1, steps=5)
    fresh = _oscillator()[0].simulate(type="DYNAMICS", end=1, steps=5)
    np.testing.assert_array_equal(res.request(1), fresh.request(1))


# ---- item 5: cm markers made without an owner ---------------------------------------------
def test_a_cm_marker_made_without_an_owner_belongs_to_its_part():
    """Altair's idioms: Part(cm=Marker()) (the Accgrav example) falls freely, z = -g t^2 / 2;
    part.cm = Marker(qp=...) puts the part's cm there; a PointMass's too."""
    model = Model(output="accgrav")
    Accgrav(igrav=0, jgrav=0, kgrav=-9.81)
    ground = Part(ground=True)
    Marker(part=ground)
    body = Part(mass=1, ip=[1e3] * 3, cm=Marker())
    part = Part(mass=2, ip=[1, 1, 1])
    part.cm = Marker(qp=[0, 0, 5], zp=[0, 0, 6], xp=[1, 0, 5])
    point = PointMass(mass=3, cm=Marker(qp=[1, 2, 3]))
    Request(type="DISPLACEMENT", i=body.cm)
    Request(type="DISPLACEMENT", i=part.cm)
    Request(type="DISPLACEMENT", i=point.cm)
    assert (body.cm.body, part.cm.body, point.cm.body) == (body, part, point)
    res = model.simulate(type="DYNAMICS", end=1, steps=10, integr_tol=1e-10)
    fall = -9.81 * res.t ** 2 / 2
    np.testing.assert_allclose(res.request(1)[:, 3], fall, atol=1e-8)
    np.testing.assert_allclose(res.request(2)[:, 3], 5 + fall, atol=1e-8)
    np.testing.assert_allclose(res.request(3)[:, 1:4], np.column_stack(
        [np.ones_like(fall), 2 + 0 * fall, 3 + fall]), atol=1e-8)


def test_a_marker_with_no_owner_that_is_no_cm_is_an_error_naming_body():
    model = Model()
    Part(ground=True)
    Marker(qp=[1, 0, 0])
    line = _here() - 1
    with pytest.raises(DeckError) as err:
        model.load()
    assert str(err.value) == (
        f"{__file__}:{line}, Marker id=1, attribute 'body': a Marker needs its owner: body= "
        "(or part=, point_mass=), or to be made a Part's cm (Part(cm=Marker(...)), part.cm "
        "= Marker(...))")


# ---- item 8: sweep of an msolve Model; the default run's log line -------------------------
def test_sweep_takes_an_msolve_model_and_load_says_what_to_pass():
    """sweep(model) runs model.load()'s cases: each equals model.load().run(params=...);
    pysolver.load and loads of an msolve Model, and sweep of anything else, are one
    TypeError naming what to pass."""
    model, _, _ = _oscillator()
    model.simulate(type="DYNAMICS", end=1, dtout=0.1, returnResults=False)
    case = {"Force_SpringDamper/1/stiffness": 400.0, "Body_Rigid/2/mass": 5.0}
    sw = pysolver.sweep(model, [case], processes=0, outputs={"x": "final:request/1/2"})
    ref = model.load().run(params=case)
    assert sw.rows[0]["status"] == "ok"
    assert sw.rows[0]["x"] == ref.request(1)[-1, 1]
    np.testing.assert_array_equal(sw.result(0).request(1), ref.request(1))
    with pytest.raises(TypeError) as err:
        pysolver.load(model)
    assert str(err.value) == ("pysolver.load reads a deck file; this is an msolve Model, whose "
                              "pysolver.Model is model.load()")
    with pytest.raises(TypeError) as err:
        pysolver.loads(model)
    assert str(err.value) == ("pysolver.loads reads a deck's text; this is an msolve Model, "
                              "whose pysolver.Model is model.load()")
    with pytest.raises(TypeError) as err:
        pysolver.sweep(3.0, [case], processes=0)
    assert str(err.value) == "sweep takes a deck path, a pysolver.Model or an msolve Model, " \
                             "not float"


def test_the_default_run_says_so_in_the_log():
    """A model without a simulate() runs the documented default (1 s, 100 outputs) and its
    log says so; one with a command has no such line."""
    model, _, _ = _oscillator()
    res = model.load().run()
    assert (res.t[-1], len(res.t)) == (pytest.approx(1.0), 101)
    assert res.log == ["no Simulate command: the default run, a transient of 1 s with 100 "
                       "outputs (docs/deck-language.md)"]
    res = model.simulate(type="DYNAMICS", end=1, steps=10)
    assert res.log == []


# ---- item 10: active, name, zv/xv, Point.x, owners, Motion errors -------------------------
def test_an_inactive_element_is_left_out_and_what_refers_to_it_must_be_inactive():
    """active=False drops the spring: the body flies on, x = t; active=True is the default.
    A spring on an inactive marker is a DeckError naming its attribute; active=1 is refused
    where it is given."""
    model, body, spring = _oscillator()
    spring.active = False
    res = model.simulate(type="DYNAMICS", end=1, steps=4)
    np.testing.assert_allclose(res.request(1)[:, 1], res.t, atol=1e-12)
    assert "SPRINGDAMPER" not in model.adm()

    model, body, _ = _oscillator()
    off = Marker(body=body, active=False)
    SpringDamper(type="TRANSLATION", i=off, j=model.entities[1], k=1.0)
    line = _here() - 1
    with pytest.raises(DeckError) as err:
        model.load()
    assert str(err.value) == (f"{__file__}:{line}, SpringDamper id=2, attribute 'i': Marker 3 "
                              "is inactive (active=False); an inactive element is left out of "
                              "the model, so what refers to it must be inactive too")
    line = _here() + 2
    with pytest.raises(DeckError) as err:
        Part(mass=1, active=1)
    assert str(err.value) == (f"{__file__}:{line}, Part, attribute 'active': active=1; "
                              "expected True or False")


def test_name_is_kept_and_labels_an_element_without_a_label():
    model, body, _ = _oscillator()
    named = Request(type="DISPLACEMENT", i=body.cm, name="req_disp")
    both = Request(type="DISPLACEMENT", i=body.cm, name="n", label="the label")
    loaded = model.load()
    assert (named.name, loaded.requests[2].label) == ("req_disp", "req_disp")
    assert (both.name, loaded.requests[3].label) == ("n", "the label")


def test_zv_and_xv_are_the_axes_zp_and_xp_give_as_points():
    """zv/xv (vectors) give the axes zp/xp give as the points qp + zv, qp + xv, usexv those of
    usexp; a pendulum hinged about global x through zv swings as through zp (bit for bit).
    zv with another orientation, and xv without zv, are DeckErrors naming them."""
    def pendulum(**axes):
        model = Model()
        Accgrav(kgrav=-9.81)
        ground = Part(ground=True)
        bob = Part(mass=1, ip=[0.01] * 3)
        bob.cm = Marker(part=bob, qp=[0, 1, 1])
        Joint(type="REVOLUTE", i=Marker(part=bob, qp=[0, 0, 1], **axes),
              j=Marker(part=ground, qp=[0, 0, 1], **axes))
        Request(type="DISPLACEMENT", i=bob.cm)
        return model
    by_points = pendulum(zp=[5, 0, 1], xp=[0, 1, 1]).simulate(end=0.5, steps=10)
    by_vectors = pendulum(zv=Vector(4, 0, 0), xv=[0, 1, 0]).simulate(end=0.5, steps=10)
    np.testing.assert_array_equal(by_vectors.request(1), by_points.request(1))
    assert by_points.request(1)[-1, 3] < 0.5          # it swung down about x

    model = Model()
    ground = Part(ground=True)
    plain = Marker(body=ground, qp=[1, 2, 3], zv=[0, 0, 2], xv=[1, 1, 0], usexv=True)
    points = Marker(body=ground, qp=[1, 2, 3], zp=[1, 2, 5], xp=[2, 3, 3], usexp=True)
    markers = model.load().markers
    np.testing.assert_array_equal(markers[plain.id].rot, markers[points.id].rot)
    s = np.sqrt(0.5)
    np.testing.assert_allclose(markers[plain.id].rot, [[s, -s, 0], [s, s, 0], [0, 0, 1]],
                               atol=1e-15)
    for attrs, attribute, reason in [
            (dict(zv=[0, 0, 1], reuler=[0, 0, 0]), "zv",
             "give one orientation: zv (with xv), not reuler too"),
            (dict(xv=[1, 0, 0]), "xv", "xv (a vector in the x-z plane) needs zv (the z axis)")]:
        model = Model()
        ground = Part(ground=True)
        Marker(body=ground, **attrs)
        line = _here() - 1
        with pytest.raises(DeckError) as err:
            model.load()
        assert str(err.value) == f"{__file__}:{line}, Marker id=1, attribute " \
                                 f"'{attribute}': {reason}"


def test_points_have_x_y_z_and_flex_body_is_refused():
    p = Point(1, 2, 3)
    assert (p.x, p.y, p.z) == (1.0, 2.0, 3.0)
    p.y = 7
    assert p.tolist() == [1.0, 7.0, 3.0] and Vector(4, 5, 6).z == 6.0
    Model()
    line = _here() + 2
    with pytest.raises(DeckError) as err:
        Marker(flex_body=1)
    assert str(err.value) == (f"{__file__}:{line}, Marker, attribute 'flex_body': flex_body "
                              "is not supported: pysolver has rigid bodies only")


def test_a_marker_given_body_and_part_is_refused_where_it_is_made():
    Model()
    ground = Part(ground=True)
    line = _here() + 2
    with pytest.raises(DeckError) as err:
        Marker(body=ground, part=ground)
    assert str(err.value) == (
        f"{__file__}:{line}, Marker, attribute 'part': body= and part= both give the marker's "
        "owner (body and part are msolve's two names for its Part); give one")
    marker = Marker(part=ground)
    line = _here() + 2
    with pytest.raises(DeckError) as err:
        marker.point_mass = ground
    assert (err.value.line, err.value.attribute) == (line, "point_mass")


def _motion_model(joint_type="REVOLUTE"):
    model = Model()
    ground = Part(ground=True)
    pivot = Marker(body=ground)
    arm = Part(mass=1, ip=[1, 1, 1])
    arm.cm = Marker(body=arm, qp=[0.5, 0, 0])
    pin = Marker(body=arm)
    return model, Joint(type=joint_type, i=pin, j=pivot), pin, pivot


@pytest.mark.parametrize("kind, motion, attribute, reason", [
    ("REVOLUTE", dict(jtype="TRANSLATION", function="0.1*TIME"), "jtype",
     "jtype=TRANSLATION is not a coordinate of REVOLUTE Joint 1 (it has ROTATION)"),
    ("REVOLUTE", dict(jtype="ROTATION"), "function",
     'give function= (an expression of time), or routine= (a MOTSUB, with '
     'function="USER(...)")'),
    ("REVOLUTE", dict(function="TIME", direction="B3"), "direction",
     "direction= is a marker motion's; this one drives joint= (its coordinate: jtype=)"),
    ("CYLINDRICAL", dict(function="TIME"), "jtype",
     'Joint 1 is CYLINDRICAL: give jtype="ROTATION" or "TRANSLATION"'),
    ("SPHERICAL", dict(function="TIME"), "joint",
     "Joint 1 is SPHERICAL; a Motion drives a REVOLUTE (jtype ROTATION), TRANSLATIONAL "
     "(TRANSLATION) or CYLINDRICAL (either) joint"),
    ("REVOLUTE", dict(function="TIME", dtype="POS"), "dtype",
     "dtype='POS'; expected one of DISPLACEMENT, VELOCITY, ACCELERATION, D, V, A"),
])
def test_motion_errors_name_msolves_attributes(kind, motion, attribute, reason):
    """The errors trial 43 met in XML names (expr, IC_DISP, TYPE) are the class's own, at
    the Motion's line, in its attributes' names."""
    model, joint, _, _ = _motion_model(kind)
    Motion(joint=joint, **motion)
    line = _here() - 1
    with pytest.raises(DeckError) as err:
        model.load()
    assert str(err.value) == f"{__file__}:{line}, Motion id=1, attribute '{attribute}': {reason}"


def test_initial_conditions_a_motion_does_not_integrate_are_not_used():
    """Inspire writes icdisp=0.0, icvel=0.0 on every displacement motion; Adams' and
    MotionSolve's ICDISP/ICVEL are the integration constants of a V or A motion only, so on
    another they are taken and not used: quietly when 0, with a DeckWarning at the Motion's
    line otherwise. The displacement motion follows its function from its value at 0."""
    model, joint, pin, pivot = _motion_model()
    Motion(joint=joint, function="0.3*TIME", icdisp=0.0, icvel=0.0)
    Request(f1=f"AZ({pin.id},{pivot.id})", f2=f"WZ({pin.id},{pivot.id},{pivot.id})")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        res = model.simulate(type="TRANSIENT", end=1, dtout=0.5, integr_tol=1e-9)
    np.testing.assert_allclose(res.request(1)[:, :2], [[0, 0.3], [0.15, 0.3], [0.3, 0.3]],
                               atol=1e-9)
    for motion, shown, text in (
            (dict(function="TIME", icdisp=0.5), "ICDISP",
             "ICDISP = 0.5 is not used: it is the integration constant of a V or A motion, and "
             "this one is val_type D, whose function gives the displacement itself"),
            (dict(function="TIME", dtype="V", icdisp=0.0, icvel=1.0), "ICVEL",
             "ICVEL = 1 is not used: it is the integration constant of an A motion, and this "
             "one is val_type V, whose function gives the velocity itself")):
        model, joint, _, _ = _motion_model()
        Motion(joint=joint, **motion)
        line = _here() - 1
        with pytest.warns(DeckWarning) as caught:
            model.load()
        assert [str(w.message) for w in caught] == [
            f"{__file__}:{line}, MOTION/1 (Motion_Joint), attribute '{shown}': {text}"]


def test_marker_motion_errors_and_the_datasets_checks_in_msolves_names():
    """A marker motion without direction=, and jtype= on one, are the class's errors; the
    dataset's check of two motions on one coordinate names JTYPE, not motion_type."""
    model, _, pin, pivot = _motion_model()
    Motion(i=pin, j=pivot, function="TIME")
    line = _here() - 1
    with pytest.raises(DeckError) as err:
        model.load()
    assert str(err.value) == (
        f"{__file__}:{line}, Motion id=1, attribute 'direction': a Motion drives joint= "
        "(jtype= its coordinate), or marker i= relative to j= along or about direction= (X, "
        "Y, Z, B1, B2, B3)")
    model, joint, _, _ = _motion_model()
    Motion(joint=joint, function="TIME")
    Motion(joint=joint, jtype="R", function="2*TIME")
    line = _here() - 1
    with pytest.raises(DeckError) as err:
        model.load()
    assert (err.value.line, err.value.element, err.value.attribute) == \
        (line, "MOTION/2 (Motion_Joint)", "JTYPE")


def test_a_joint_motion_drives_its_joint_as_before():
    """The checks leave a good motion alone: the driven angle is 0.1 t (to 1e-9)."""
    model, joint, pin, pivot = _motion_model()
    Motion(joint=joint, jtype="ROTATION", function="0.1*TIME")
    Request(f1=f"AZ({pin.id},{pivot.id})")
    res = model.simulate(type="DYNAMICS", end=1, steps=4, integr_tol=1e-10)
    np.testing.assert_allclose(res.request(1)[:, 0], 0.1 * res.t, atol=1e-9)
