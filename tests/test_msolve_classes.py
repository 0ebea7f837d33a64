"""The msolve class API (pysolver.msolve: Model, Part, Marker, Joint, ..., model.simulate):
models built directly and scripts loaded by pysolver.load, against closed forms and the same
model written as an XML deck."""
import sys

import numpy as np
import pytest

import pysolver
from pysolver import DeckError
from pysolver.msolve import Accgrav, Joint, Marker, Model, Part, Point, Request, Sforce, Units

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
