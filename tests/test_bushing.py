"""Force_Bushing and the torque forms of the vector forces: the bushing against the same six
components written as a Force_Vector_TwoBody, its static deflections by hand, a OneBody and a
FORCEANDTORQUE torque against the closed form, the statements, bad input."""
import numpy as np
import pytest

import pysolver
from pysolver import DeckError

from helpers import TEST_DECKS

DECK = (TEST_DECKS / "bushing.xml").read_text()
BUSHING = DECK[DECK.index("<Force_Bushing"):DECK.index("/>", DECK.index("<Force_Bushing")) + 2]
# the same law, written out (components in J = marker 5's axes, at I = marker 21)
BY_HAND = ('<Force_Vector_TwoBody id="9" i_marker_id="21" j_floating_marker_id="5" '
           'ref_marker_id="5" type="FORCEANDTORQUE" '
           'fx_expression="-2000*DX(21,5,5) - 5*VX(21,5,5,5) + 1" '
           'fy_expression="-3000*DY(21,5,5) - 6*VY(21,5,5,5) - 2" '
           'fz_expression="-2500*DZ(21,5,5) - 7*VZ(21,5,5,5) + 0.5" '
           'tx_expression="-40*AX(21,5) - 0.1*WX(21,5,5) + 0.1" '
           'ty_expression="-50*AY(21,5) - 0.2*WY(21,5,5) - 0.05" '
           'tz_expression="-60*AZ(21,5) - 0.3*WZ(21,5,5) + 0.02"/>')


@pytest.mark.parametrize("kernel", ["tapes", "generated"])
def test_a_bushing_is_its_six_components_written_as_a_vector_force(kernel):
    """tests/decks/bushing.xml: the tumbling body on the bushing, and on the vector force with
    the bushing's law written out by hand: the same motion to 1e-12 at every row."""
    a = pysolver.loads(DECK).run(kernel=kernel)
    b = pysolver.loads(DECK.replace(BUSHING, BY_HAND)).run(kernel=kernel)
    assert a.success and b.success, (a.message, b.message)
    assert np.abs(a.request(1)[:, :6]).max() > 1e-3          # every deflection loaded
    np.testing.assert_allclose(a.request(1), b.request(1), rtol=0, atol=1e-12)


def test_one_body_and_force_and_torque_forms_spin_a_body_as_the_closed_form():
    """Izz = 0.25 under 0.5 N m along its own z (OneBody, TORQUEONLY, ref marker on the body)
    and 0.25 N m about global z with its weight held (TwoBody, FORCEANDTORQUE): WZ = 3 t, the
    body stays where it is."""
    res = pysolver.loads(DECK).run()
    np.testing.assert_allclose(res.request(1)[:, 6], 3 * res.t, rtol=0, atol=1e-9)
    np.testing.assert_allclose(res.request(1)[:, 7], 0, atol=1e-12)


def test_a_static_bushing_deflects_by_the_load_over_the_stiffness():
    """Statics without preloads or offsets (I at the centre of mass, J unturned; the second
    body's torques off, its weight held): the weight m g on ky deflects DY by -m g / ky and
    nothing else."""
    text = (DECK.replace('preload_x="1" preload_y="-2" preload_z="0.5" preload_tx="0.1"\n'
                         '                   preload_ty="-0.05" preload_tz="0.02"', "")
            .replace('pos_x="0.1" pos_y="-0.05" pos_z="0.02" psi="0.3"\n'
                     '                      theta="0.2" phi="-0.1"', "")
            .replace('<Simulate analysis_type="Transient" end_time="1" print_interval="0.01"/>',
                     '<Param_Static method="FIM_S" max_imbalance="1e-10" max_error="1e-12"/>'
                     '<Simulate analysis_type="Static" end_time="0"/>')
            .replace('tz_expression="0.5"', 'tz_expression="0"')
            .replace('tz_expression="0.25"', 'tz_expression="0"'))
    assert text.count('pos_x="0.1"') == 0 and "preload_x" not in text
    res = pysolver.loads(text).run()
    assert res.success, res.message
    q = res.request(1)[-1]
    np.testing.assert_allclose(q[:6], [0, -2 * 9.81 / 3000, 0, 0, 0, 0], rtol=0, atol=1e-12)


def test_the_statements(tmp_path):
    """BUSHING(K=, C=, KT=, CT=, FORCE=, TORQUE=), VTORQUE and GFORCE load as the XML does."""
    deck = tmp_path / "bush.py"
    deck.write_text(
        "from pysolver.msolve import *\n"
        "PART(1, GROUND=True)\nMARKER(1, PART=1)\nMARKER(5, PART=1)\n"
        "MARKER(20, PART=2)\nPART(2, MASS=2, CM=20, IP=[0.02, 0.03, 0.04])\n"
        "MARKER(30, PART=3, QP=[2, 0, 0])\nPART(3, MASS=1, CM=30, IP=[0.15, 0.15, 0.25])\n"
        "ACCGRAV(JGRAV=-9.81)\n"
        "BUSHING(1, I=20, J=5, K=[2000, 3000, 2500], C=[5, 6, 7], KT=[40, 50, 60], "
        "CT=[0.1, 0.2, 0.3], FORCE=[0, 0, 0], TORQUE=[0, 0, 0])\n"
        "VTORQUE(2, I=30, JFLOAT=1, TZ='0.5')\n"
        "GFORCE(3, I=30, JFLOAT=1, FX='0', FY='9.81', FZ='0', TX='0', TY='0', TZ='0.25')\n"
        "REQUEST(1, F1='DY(20)', F2='WZ(30)')\n"
        "SIMULATE(TYPE='TRANSIENT', END=1, DTOUT=0.5)\n")
    model = pysolver.load(deck)
    assert model.bushings[1].stiffness == (2000, 3000, 2500, 40, 50, 60)
    assert model.bushings[1].damping == (5, 6, 7, 0.1, 0.2, 0.3)
    res = model.run(integr_tol=1e-9)
    assert res.success, res.message
    assert -0.02 < res.request(1)[-1, 0] < 0              # sagging on its bushing
    np.testing.assert_allclose(res.request(1)[:, 1], 3 * res.t, atol=1e-9)


@pytest.mark.parametrize("attrs, attribute, words", [
    ('i_marker_id="21" j_marker_id="5" ky="-1"', "ky", "expected"),
    ('i_marker_id="21" j_marker_id="99"', "j_marker_id", "marker 99 does not exist"),
    ('i_marker_id="21" j_marker_id="20"', "j_marker_id", "on one body"),
])
def test_a_bad_bushing_is_a_deck_error(attrs, attribute, words):
    with pytest.raises(DeckError, match=words) as err:
        pysolver.loads(DECK.replace("</Model>", f'<Force_Bushing id="7" {attrs}/></Model>'))
    assert (err.value.element, err.value.attribute) == ("Force_Bushing", attribute)


def test_a_component_the_type_does_not_have_is_a_deck_error():
    with pytest.raises(DeckError, match="a TORQUEONLY force has no fx_expression") as err:
        pysolver.loads(DECK.replace('type="TORQUEONLY"', 'type="TORQUEONLY" fx_expression="1"'))
    assert (err.value.element, err.value.attribute) == ("Force_Vector_OneBody",
                                                        "fx_expression")


def test_bush_reports_the_bushings_force_and_torque_on_either_body():
    """BUSH(1, 0, comp, 5): the law's six components in J's axes (1e-12 against the
    expressions); BUSH(1, 1, comp, 5) on J's body at J: -F and -T - d x F (d = oI - oJ);
    comp 1 and 5 the magnitudes."""
    exprs = [BY_HAND.split(f'{c}_expression="')[1].split('"')[0]
             for c in ("fx", "fy", "fz", "tx", "ty", "tz")]
    reqs = ('<Post_Request id="7" ' + " ".join(f'expr{k + 1}="BUSH(1,0,{c},5)"' for k, c in
                                               enumerate((2, 3, 4, 6, 7, 8, 1, 5))) + "/>"
            '<Post_Request id="8" ' + " ".join(f'expr{k + 1}="{e}"' for k, e in enumerate(exprs))
            + ' expr7="DX(21,5,5)" expr8="DY(21,5,5)"/>'
            '<Post_Request id="9" ' + " ".join(f'expr{k + 1}="BUSH(1,1,{c},5)"' for k, c in
                                               enumerate((2, 3, 4, 6, 7, 8))) +
            ' expr7="DZ(21,5,5)"/>')
    res = pysolver.loads(DECK.replace("</Model>", reqs + "</Model>")).run()
    assert res.success, res.message
    on_i, law_v, on_j = res.request(7), res.request(8), res.request(9)
    np.testing.assert_allclose(on_i[:, :6], law_v[:, :6], rtol=0, atol=1e-12)
    np.testing.assert_allclose(on_i[:, 6], np.linalg.norm(law_v[:, :3], axis=1), atol=1e-12)
    np.testing.assert_allclose(on_i[:, 7], np.linalg.norm(law_v[:, 3:6], axis=1), atol=1e-12)
    d = np.c_[law_v[:, 6:8], on_j[:, 6]]
    np.testing.assert_allclose(on_j[:, :3], -law_v[:, :3], atol=1e-12)
    np.testing.assert_allclose(on_j[:, 3:6], -law_v[:, 3:6] - np.cross(d, law_v[:, :3]),
                               atol=1e-12)
