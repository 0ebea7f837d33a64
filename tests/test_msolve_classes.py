"""The msolve class API (pysolver.msolve: Model, Part, Marker, Joint, ..., model.simulate):
models built directly and scripts loaded by pysolver.load, against closed forms and the same
model written as an XML deck."""
import sys

import numpy as np
import pytest

import pysolver
from pysolver import DeckError
from pysolver.msolve import (
    Accgrav,
    Graphics,
    Integrator,
    Joint,
    LoadControl,
    Marker,
    Model,
    Part,
    Pforce,
    Point,
    PointMass,
    Request,
    Sensor,
    Sforce,
    Units,
)

from helpers import DECKS, TEST_DECKS

W = 2 * np.pi


def test_a_script_with_its_own_main_block_loads_with_its_commands():
    """Altair's sliding-block example as written (`from msolve import *`, the model built in a
    function, simulate() under `if __name__ == "__main__"`): pysolver.load records the
    command (4 s every 0.01 s) and runs nothing; the block follows x = 3 t / w - 3 sin(w t) /
    w^2 (1e-8 at integr_tol 1e-11); the msolve shim is gone afterwards."""
    model = pysolver.load(TEST_DECKS / "msolve" / "sliding_block.py")
    assert "msolve" not in sys.modules
    assert [(c.analysis, c.end_time, c.print_interval) for c in model.commands] == \
        [("TRANSIENT", 4.0, pytest.approx(0.01))]
    res = model.run(integr_tol=1e-11)
    assert res.success, res.message
    x = res.request(1)[:, 3]            # along z of the J marker (global x): the joint's axis
    np.testing.assert_allclose(x, 3 * res.t / W - 3 * np.sin(W * res.t) / W ** 2, atol=1e-8)
    np.testing.assert_allclose(res.request(1)[:, 1:3], 0, atol=1e-12)


def _pendulum():
    """decks/joints/pendulum_revolute.xml built with the classes (same ids)."""
    model = Model(output="pendulum")
    Units(mass="KILOGRAM", length="METER", time="SECOND", force="NEWTON")
    ground = Part(ground=True)
    Marker(body=ground, label="global")
    pivot = Marker(body=ground, id=2)
    bob = Part(id=2, mass=1, ip=[1e-3, 1e-3, 1e-3])
    bob.cm = Marker(body=bob, id=20, qp=Point(2, 0, 0))
    pin = Marker(body=bob, id=21)
    Accgrav(jgrav=-9.81)
    Joint(type="REVOLUTE", i=pin, j=pivot)
    Request(f1="DX(20)", f2="DY(20)", f3="VX(20)", f4="VY(20)", f5="WZ(20)")
    return model


def test_a_model_built_with_the_classes_runs_as_its_xml_deck():
    """simulate() runs every command so far and returns the Result: the revolute pendulum
    equals decks/joints/pendulum_revolute.xml run the same way to 1e-9 (integr_tol 1e-11),
    and a second simulate() continues to the later end."""
    model = _pendulum()
    res = model.simulate(type="DYNAMICS", end=2, dtout=0.05, integr_tol=1e-11)
    ref = pysolver.load(DECKS / "joints" / "pendulum_revolute.xml").run(integr_tol=1e-11)
    n = len(res.t)
    np.testing.assert_allclose(res.t, ref.t[:n], atol=1e-12)
    np.testing.assert_allclose(res.request(1)[:, :5], ref.request(1)[:n, :5], atol=1e-9)
    more = model.simulate(type="DYNAMICS", end=3, dtout=0.05, integr_tol=1e-11)
    assert more.t[-1] == pytest.approx(3.0) and len(more.t) == 61


def test_the_model_as_a_dataset():
    """model.adm() is the Adams dataset pysolver reads back (part-relative markers, labels as
    adams_view_name comments)."""
    text = _pendulum().adm()
    assert "PART/2, MASS = 1" in text and "MARKER/20, PART = 2" in text
    assert "JOINT/1, REVOLUTE" in text and text.rstrip().endswith("END")


def test_errors_name_the_python_line_that_made_the_element():
    model = Model()
    ground = Part(ground=True)
    with pytest.raises(DeckError, match="unknown attribute 'qpp'") as err:
        Marker(body=ground, qpp=Point(1, 0, 0))
    assert err.value.line is not None and err.value.file == __file__
    arm = Part(mass=1, ip=[1, 1, 1])
    arm.cm = Marker(body=arm)
    line = sys._getframe().f_lineno + 1
    Sforce(type="TRANSLATION", i=arm.cm, j=ground, function="1 +")
    with pytest.raises(DeckError, match="bad expression") as err:
        model.simulate(end=1, dtout=0.1)
    assert (err.value.file, err.value.line) == (__file__, line)


def test_altairs_attribute_names_and_pysolvers_classes_build_the_xml_deck_exactly():
    """decks/sensor_halt_acceleration.xml written with the classes as Altair names their
    attributes (Sensor operator, evaluate; Sforce type) builds the XML deck's model and run,
    number for number; pysolver's Pforce and LoadControl classes the LoadControl deck's."""
    from test_formats import model_differences

    model = Model()
    ground = Part(id=1, ground=True)
    m11 = Marker(id=11, body=ground)
    block = Part(id=2, mass=1, ip=[0.1, 0.1, 0.1])
    block.cm = m21 = Marker(id=21, body=block, qp=[1, 0, 0])
    Sforce(id=1, type="TRANSLATION", i=m21, j=m11, function="2*TIME")
    Sensor(id=100, function="ABS( ACCX(21,11,21,11) )", operator="GE", value=5, error=1e-4,
           halt=True, evaluate="VX(21,11,11)")
    Request(id=1, f1="DX(21,11)", f2="VX(21,11)", f3="ACCX(21,11,21,11)", f4="SENVAL(100)",
            cnames=["x", "vx", "ax", "stored_vx"])
    Integrator(error=1e-8)
    model.simulate(type="TRANSIENT", end=10, dtout=0.1, returnResults=False)
    xml = pysolver.load(DECKS / "sensor_halt_acceleration.xml")
    assert model_differences(xml, model.load()) == []

    model = Model()
    Units(mass="KILOGRAM", length="MILLIMETER", time="SECOND", force="NEWTON")
    ground = Part(id=1, ground=True)
    Marker(id=1, body=ground)
    tip = PointMass(id=2, mass=0.01)
    tip.cm = Marker(id=10, body=tip)
    Pforce(id=1, function="-DZ(10)", penalty=100, penalty1=0, unilateral=True,
           smoothing_factor=1e-4, label="floor z >= 0")
    Request(id=1, f1="DZ(10)", f2="PFORCE(1)", cnames=["z", "floor_force"])
    Integrator(error=1e-8)
    LoadControl(velocity=-0.1, material=tip, direction=3, maxvelocity=10,
                load_function="IF(t-1: 20*t, 20, IF(t-2: 20, 40, 40))", kp="auto",
                ki="auto", smooth=0.8, updatetime=0.01)
    model.simulate(type="TRANSIENT", end=3, dtout=0.01, returnResults=False)
    xml = pysolver.load(DECKS / "loadcontrol_indenter.xml")
    assert model_differences(xml, model.load()) == []


def test_a_value_the_class_does_not_know_is_an_error_at_the_python_line():
    model = Model()
    ground = Part(ground=True)
    pin = Marker(body=ground)
    line = sys._getframe().f_lineno + 1
    Joint(type="REVOLUT", i=pin, j=pin)
    with pytest.raises(DeckError, match="type='REVOLUT'; expected one of REVOLUTE, ") as err:
        model.load()
    assert (err.value.file, err.value.line, err.value.element) == (__file__, line, "Joint")


def test_graphics_keep_any_attribute_for_the_3d_view():
    model = Model()
    ground = Part(ground=True)
    pin = Marker(body=ground)
    Graphics(type="Cylinder", center_marker_id=pin, radius=1.5, length="2.0")
    Graphics(type="SPHERE", cm=pin, radius=0.25)
    graphics = model.load().graphics
    assert (graphics[1].type, graphics[1].attrs) == \
        ("Cylinder", {"center_marker_id": "1", "radius": "1.5", "length": "2.0"})
    assert (graphics[2].type, graphics[2].attrs) == ("SPHERE", {"cm": "1", "radius": "0.25"})


def test_msolve_shape_classes_are_graphics_the_3d_view_draws():
    """Sphere, Box, Cylinder, Frustum, Ellipsoid (Altair's MV-9000/9001 tutorials use
    Sphere(cm=, radius=)) are GRAPHICS of their shape: kept like Graphics, each drawn as its
    shape on its marker; type= is a DeckError at its line."""
    from pysolver.msolve import Box, Cylinder, Ellipsoid, Frustum, Sphere
    from pysolver.viewer import shapes
    model = Model()
    ground = Part(ground=True)
    pin = Marker(body=ground)
    Sphere(cm=pin, radius=50)
    Box(corner=pin, x=2, y=4, z=6)
    Cylinder(cm=pin, radius=1.5, length=3)
    Frustum(cm=pin, bottom=2, top=1, length=4)
    Ellipsoid(cm=pin, xscale=4, yscale=2, zscale=1)
    loaded = model.load()
    graphics = loaded.graphics
    assert [(g.type, g.attrs) for g in graphics.values()] == [
        ("SPHERE", {"cm": "1", "radius": "50"}),
        ("BOX", {"corner": "1", "x": "2", "y": "4", "z": "6"}),
        ("CYLINDER", {"cm": "1", "radius": "1.5", "length": "3"}),
        ("FRUSTUM", {"cm": "1", "bottom": "2", "top": "1", "length": "4"}),
        ("ELLIPSOID", {"cm": "1", "xscale": "4", "yscale": "2", "zscale": "1"})]
    drawn = [shapes.graphic(g, loaded.markers, None, 1.0)[0] for g in graphics.values()]
    assert [(d["kind"], d["marker"]) for d in drawn] == [
        ("sphere", 1), ("box", 1), ("cylinder", 1), ("cylinder", 1), ("sphere", 1)]
    assert (drawn[0]["r"], drawn[1]["s"], drawn[2]["z1"], drawn[3]["r0"], drawn[4]["scale"]) \
        == (50.0, [2.0, 4.0, 6.0], 3.0, 2.0, [1.0, 0.5, 0.25])
    line = sys._getframe().f_lineno + 2
    with pytest.raises(DeckError) as err:
        Sphere(cm=pin, radius=1, type="BOX")
    assert (err.value.line, err.value.element, err.value.attribute) == (line, "Sphere", "type")
    assert str(err.value).endswith("Sphere is a SPHERE (type is not taken; Graphics(type=...) "
                                   "draws another shape)")


def test_the_tutorial_pendulum_with_a_sphere_runs(tmp_path):
    """MV-9001's style: `from msolve import *`, Sphere(cm=bob.cm, radius=50) on the bob; the
    script loads (it was a NameError), the sphere is drawn on the bob's cm marker, and the
    pendulum swings (it starts level and passes below the pivot)."""
    path = tmp_path / "pendulum.py"
    path.write_text("""from msolve import *
model = Model(output="pendulum")
units = Units(length="MILLIMETER")
gravity = Accgrav(kgrav=-9810)
ground = Part(ground=True)
pivot = Marker(part=ground, qp=[0, 0, 0], zp=[0, 1, 0])
bob = Part(mass=2, ip=[1e3, 1e3, 1e3], label="Bob")
bob.cm = Marker(part=bob, qp=[500, 0, 0], label="Bob CM")
sph = Sphere(cm=bob.cm, radius=50)
jm = Marker(part=bob, qp=[0, 0, 0], zp=[0, 1, 0])
jnt = Joint(type="REVOLUTE", i=jm, j=pivot)
req = Request(type="DISPLACEMENT", i=bob.cm, comment="bob displacement")
run = model.simulate(type="DYNAMICS", end=0.5, steps=50, returnResults=True)
""")
    res = pysolver.load(path).run(progress=False)
    assert res.success, res.message
    (sphere,) = [it for it in res.animate().scene.items if it["label"].startswith("Post_")]
    assert (sphere["kind"], sphere["r"], sphere["label"]) == ("sphere", 50.0, "Post_Graphic 1")
    assert res.request(1)[:, 3].min() < -400.0        # z of the bob: it swung down


#: docs/msolve.md's pendulum without its simulate() (11 lines); each case adds its lines.
_PENDULUM = """from pysolver.msolve import *

model = Model(output="pendulum")
Units(length="MILLIMETER")
Accgrav(jgrav=-9810)
ground = Part(ground=True)
pivot = Marker(body=ground)
arm = Part(mass=1, ip=[1e3, 1e3, 1e3])
arm.cm = Marker(body=arm, qp=Point(100, 0, 0))
Joint(type="REVOLUTE", i=Marker(body=arm), j=pivot)
Request(type="DISPLACEMENT", i=arm.cm)
"""
_RUN = 'model.simulate(type="DYNAMICS", end=1, dtout=0.1)'


@pytest.mark.parametrize("tail, line, element, attribute, reason", [
    ('model.simulate(type="DYNAMICS", end=-1, dtout=0.01)', 12, "SIMULATE (Simulate)", "END",
     "END -1 must be after the start time 0"),
    ('model.simulate(type="DYNAMICS", end=1, dtout=0)', 12, "SIMULATE (Simulate)", "DTOUT",
     "got 0; expected a value > 0"),
    ('model.simulate(type="DYNAMICS", end=1, steps=0)', 12, "SIMULATE (Simulate)", "STEPS",
     "got 0; expected a positive integer"),
    ('model.simulate(type="DYNAMICS", end=3, start=2)', 12, "SIMULATE (Simulate)", "START",
     "got 2; a run starts at TIME = 0 (pysolver has no other start time): leave START out "
     "or give 0"),
    (f'{_RUN}\nmodel.simulate(type="DYNAMICS", end=0.5)', 13, "SIMULATE (Simulate)", "END",
     "END 0.5 must be after the start time 1"),
    ('model.simulate(type="DYNAMIC", end=1)', 12, "simulate", "type",
     "unknown simulate type 'DYNAMIC'; expected DYNAMICS, TRANSIENT, KINEMATICS, STATICS, "
     "STATIC, QUASI-STATIC, QUASISTATIC, ASSEMBLY"),
    (f'Joint(type="REVOLUTE", i=pivot, j=99)\n{_RUN}', 12, "JOINT/2 (Constraint_Joint)", "J",
     "marker 99 does not exist"),
    (f"\nPart(mass=-1)\n{_RUN}", 13, "PART/3 (Body_Rigid)", "MASS",
     "got -1; expected a value > 0"),
    (f"Integrator(error=-1)\n{_RUN}", 12, "INTEGRATOR (Param_Transient)", "ERROR",
     "got -1; expected a value > 0"),
    (f'Sensor(function="DX(9)", value=1, error=-1)\n{_RUN}', 12, "SENSOR/1 (Sensor_Event)",
     "ERROR", "got -1; expected a value >= 0"),
    (f'Sforce(type="TRANSLATION", i=pivot, j=arm.cm, function="DX(77)")\n{_RUN}', 12,
     "SFORCE/1 (Force_Scalar_TwoBody)", "FUNCTION",
     "the expression refers to marker id 77, which does not exist"),
])
@pytest.mark.parametrize("pad", [0, 3])
@pytest.mark.parametrize("how", ["run", "load"])
def test_each_error_names_the_script_line_of_its_statement(tmp_path, how, pad, tail, line,
                                                           element, attribute, reason):
    """A command's errors name its simulate() call, an element's checks (ids, values,
    expressions) the line that made it, whether the script runs (simulate() runs the model)
    or pysolver.load reads it; lines added above move them."""
    path = tmp_path / "ms_bad.py"
    text = _PENDULUM.replace("\n\n", "\n" * (2 + pad), 1) + tail + "\n"
    path.write_text(text)
    with pytest.raises(DeckError) as err:
        if how == "load":
            pysolver.load(path)
        else:
            exec(compile(text, str(path), "exec"), {"__name__": "__main__"})
    assert (err.value.file, err.value.line, err.value.reason) == (str(path), line + pad, reason)
    assert str(err.value) == f"{path}:{line + pad}, {element}, attribute '{attribute}': {reason}"


def test_an_element_made_in_another_module_is_named_at_its_line(tmp_path, monkeypatch):
    """A Part a helper module makes: its check names the helper's file and line, whether the
    script runs or pysolver.load reads it."""
    helper = tmp_path / "ms_helper_parts.py"
    helper.write_text("from pysolver.msolve import Part\n\n\ndef bad_part():\n"
                      "    return Part(mass=-1)\n")
    script = tmp_path / "ms_uses_helper.py"
    text = _PENDULUM + f"import ms_helper_parts\nms_helper_parts.bad_part()\n{_RUN}\n"
    script.write_text(text)
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.delitem(sys.modules, "ms_helper_parts", raising=False)
    for how in ("run", "load"):
        with pytest.raises(DeckError) as err:
            if how == "load":
                pysolver.load(script)
            else:
                exec(compile(text, str(script), "exec"), {"__name__": "__main__"})
        assert str(err.value) == (f"{helper}:5, PART/3 (Body_Rigid), attribute 'MASS': got -1; "
                                  "expected a value > 0")
        assert (err.value.file, err.value.line) == (str(helper), 5)
    sys.modules.pop("ms_helper_parts", None)
