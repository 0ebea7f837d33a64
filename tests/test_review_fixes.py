"""Cases a review of the tracked angles, statics and the element library found wrong, each
now right or refused with a clear error."""
import numpy as np
import pytest

import pysolver
from pysolver import DeckError

from helpers import ROOT, TEST_DECKS

FREE_SPRING = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="1" body_id="1"/><Reference_Marker id="30" body_id="3"/>
  <Body_Rigid id="3" cg_id="30" mass="1" inertia_xx="0.3" inertia_yy="0.3" inertia_zz="0.5"
    w_ic_z="20"/>
  <Force_SpringDamper id="2" type="ROTATIONAL" i_marker_id="30" j_marker_id="1" stiffness="2"
    damping="0.05"/>
  <Post_Request id="1" expr1="AZ(30,1)"/><Param_Transient integr_tol="1e-9"/></Model>
  <Simulate analysis_type="Transient" end_time="3" print_interval="0.05"/></MotionSolve>"""


def damped(t, x0, v0, m, k, c):
    wn, z = np.sqrt(k / m), c / (2 * np.sqrt(k * m))
    wd = wn * np.sqrt(1 - z * z)
    return np.exp(-z * wn * t) * (x0 * np.cos(wd * t) + (v0 + z * wn * x0) / wd * np.sin(wd * t))


def test_a_torsion_spring_on_a_free_body_without_constraints_winds_past_pi():
    """No joint at all (its tracked angle made consistent without reactions): a body spun
    about its symmetry axis winds the spring to 9.6 rad and back as the closed form."""
    res = pysolver.loads(FREE_SPRING).run()
    assert res.success, res.message
    theta = damped(res.t, 0, 20, 0.5, 2, 0.05)
    assert theta.max() > 3 * np.pi
    assert np.abs(np.angle(np.exp(1j * (res.request(1)[:, 0] - theta)))).max() < 1e-6


PENDULUM = (ROOT / "decks" / "joints" / "pendulum_revolute.xml").read_text()


def test_mkeam_accepts_a_start_already_at_rest():
    """A revolute pendulum driven to rest at 0 (a Motion_Joint of 0): no kinetic-energy peak,
    and that is an equilibrium, not a failure."""
    text = PENDULUM.replace("</Model>", '<Motion_Joint id="1" joint_id="1" expr="0"/>'
                                        '<Param_Static method="MKEAM"/></Model>').replace(
        '<Simulate analysis_type="Transient" end_time="5" print_interval="0.05"/>',
        '<Simulate analysis_type="Static" end_time="0"/>')
    res = pysolver.loads(text).run()
    assert res.success, res.message
    assert res.motion(1)[-1] == pytest.approx(-9.81 * 2, rel=1e-9) or \
        res.motion(1)[-1] == pytest.approx(9.81 * 2, rel=1e-9)


def test_mkeam_refuses_a_motsub_called_from_the_kernel(tmp_path):
    """MKEAM freezes time in its own kernel, which a routine called from the kernel does not
    see: a failed run saying so (FIM_S works)."""
    (tmp_path / "m.py").write_text("def MOTSUB(id, time, par, npar, iord, iflag):\n"
                                   "    return 0.3 * float(time)\n")
    text = PENDULUM.replace("</Model>", '<Motion_Joint id="1" joint_id="1" type="USERSUB" '
                                        'script_name="m.py"/><Param_Static method="{m}"/>'
                                        '</Model>').replace(
        '<Simulate analysis_type="Transient" end_time="5" print_interval="0.05"/>',
        '<Simulate analysis_type="Static" end_time="1"/>')
    res = pysolver.loads(text.replace("{m}", "MKEAM"), file=str(tmp_path / "d.xml")).run()
    assert not res.success and "a MOTSUB called from the kernel" in res.message
    assert pysolver.loads(text.replace("{m}", "FIM_S"), file=str(tmp_path / "d.xml")).run().success


def test_mkeam_with_params_equals_the_edited_deck():
    """MKEAM's undamped kernel takes a run's numbers (params=) like the run's own kernel: a
    pendulum on a torsion spring rests where the edited deck does."""
    deck = PENDULUM.replace("</Model>", '<Force_SpringDamper id="4" type="ROTATIONAL" '
                                        'i_marker_id="21" j_marker_id="2" stiffness="10" '
                                        'damping="1" length="4.7"/><Param_Static '
                                        'method="MKEAM"/></Model>').replace(
        '<Simulate analysis_type="Transient" end_time="5" print_interval="0.05"/>',
        '<Simulate analysis_type="Static" end_time="0"/>')
    swept = pysolver.loads(deck).run(params={"Force_SpringDamper/4/stiffness": 0.1,
                                             "Force_SpringDamper/4/length": 3.0})
    edited = pysolver.loads(deck.replace('stiffness="10"', 'stiffness="0.1"').replace(
        'length="4.7"', 'length="3.0"')).run()
    assert swept.success and edited.success
    np.testing.assert_allclose(swept.request(1)[-1, :2], edited.request(1)[-1, :2], atol=1e-9)


@pytest.mark.parametrize("element, attribute, words", [
    ('<Constraint_Joint id="9" type="SCREW" i_marker_id="9" j_marker_id="1" pitch="0.1"/>',
     "i_marker_id", "holds orientations and needs rigid bodies"),
    ('<Force_SpringDamper id="9" type="ROTATIONAL" i_marker_id="9" j_marker_id="1"/>',
     "i_marker_id", "ROTATIONAL spring turns rigid bodies"),
    ('<Force_Vector_OneBody id="9" marker_id="9" type="TORQUEONLY" tz_expression="1"/>',
     "marker_id", "a torque needs rigid bodies"),
    ('<Force_Bushing id="9" i_marker_id="9" j_marker_id="1" kx="1" ktz="1"/>',
     "i_marker_id", "a bushing's torques needs rigid bodies"),
])
def test_rotations_on_a_point_body_are_a_deck_error(element, attribute, words):
    text = PENDULUM.replace("</Model>", '<Reference_Marker id="9" body_id="9" pos_x="5"/>'
                                        '<Body_Point id="9" cg_id="9" mass="1"/>'
                                        f"{element}</Model>")
    with pytest.raises(DeckError, match=words) as err:
        pysolver.loads(text)
    assert err.value.attribute == attribute


def test_a_swept_free_length_obeys_the_decks_rule():
    model = pysolver.load(TEST_DECKS / "springs.xml")
    with pytest.raises(DeckError, match="a free length is >= 0"):
        model.run(params={"Force_SpringDamper/1/length": -0.5})
    assert model.run(params={"Force_SpringDamper/2/length": -0.5}).success   # an angle


def test_a_bushing_that_goes_non_finite_is_named_with_its_law():
    """The diagnosis names the Force_Bushing by its own id and quotes its law."""
    from pysolver.build.bindings import lib
    from pysolver.solve import nonfinite
    model = pysolver.load(TEST_DECKS / "bushing.xml")
    kernel = model.compile().kernel
    k = next(i for i, e in enumerate(kernel.elements) if e[0] == "vforce" and e[1] < 0)
    name, rec = nonfinite._element(model.compile().model, kernel, lib.PS_BAD_ELEMENT, k)
    assert (name, rec.id) == ("Force_Bushing", 1)
    assert "-kx DX(21, 5, 5)" in "; ".join(rec.texts)


def test_a_loadcontrol_deck_with_a_static_command_names_the_task():
    text = (ROOT / "decks" / "loadcontrol_indenter.xml").read_text()
    import re
    text = re.sub(r"<Simulate[^>]*/>", '<Simulate analysis_type="Static" end_time="0"/>', text,
                  count=1)
    with pytest.raises(DeckError, match="LoadControl 1 drives its body through a velocity"):
        pysolver.loads(text)
