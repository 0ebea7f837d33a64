"""Non-holonomic Constraint_General: a relation of velocities held at the velocity level.
A Chaplygin sleigh against its reduced equations (integrated here by SciPy), a skate on its
circle, energy kept by a constraint that does no work, the relation held at every row, bad
input."""
import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pysolver
from pysolver import DeckError

from helpers import TEST_DECKS

DECK = (TEST_DECKS / "nonholonomic.xml").read_text()
M, IZ, A = 2.0, 0.2, 0.3          # the sleigh: mass, inertia about z, knife 0.3 m ahead


def sleigh(deck=DECK):
    """The deck without gravity and without the push: the sleigh alone on its plane."""
    return pysolver.loads(deck.replace('grav_y="-9.81"', 'grav_y="0"').replace(
        'fx_expression="0.5"', 'fx_expression="0"'))


@pytest.mark.parametrize("kernel", ["tapes", "generated"])
def test_a_chaplygin_sleigh_follows_its_reduced_equations(kernel):
    """Forward speed u and turn rate w of the sleigh whose knife edge, a ahead of the centre
    of mass, cannot slide: u' = -a w^2, w' = m a u w / (I + m a^2) (body-frame Newton-Euler
    with the knife's lateral force), from the deck's start (u = 1, w = 0.8 and the lateral
    velocity -a w that the knife allows, kept as given); within 1e-7 over 3 s at
    integr_tol 1e-9; the knife's lateral speed within 1e-9 at every row; the energy kept
    within 1e-7 J (the constraint does no work)."""
    res = sleigh().run(kernel=kernel)
    assert res.success, res.message
    q, t = res.request(1), res.t
    u0, w0 = q[0, 2], q[0, 3]
    assert (u0, w0) == pytest.approx((1.0, 0.8), rel=1e-12)     # as the deck gives them
    ref = solve_ivp(lambda _, s: [-A * s[1] ** 2, M * A * s[0] * s[1] / (IZ + M * A * A)],
                    (0, t[-1]), [u0, w0], t_eval=t, rtol=1e-12, atol=1e-12)
    assert np.abs(q[:, 2] - ref.y[0]).max() < 1e-7
    assert np.abs(q[:, 3] - ref.y[1]).max() < 1e-7
    assert np.abs(q[:, 4]).max() < 1e-9
    energy = q[:, 6]
    assert np.abs(energy - energy[0]).max() < 1e-7
    assert abs(q[:, 3]).max() > 2 * w0 - 0.5          # it does turn: not a trivial path


def test_a_skate_glides_on_its_circle():
    """With the knife at the centre of mass (a = 0) the skate keeps u and w and draws a
    circle of radius u / w."""
    text = DECK.replace('<Reference_Marker id="21" body_id="2" pos_x="0.3"/>',
                        '<Reference_Marker id="21" body_id="2"/>').replace(
        'v_ic_y="-0.24"', 'v_ic_y="0"')
    res = sleigh(text).run()
    assert res.success, res.message
    q, t = res.request(1), res.t
    r = 1.0 / 0.8
    np.testing.assert_allclose(q[:, 0], r * np.sin(0.8 * t), rtol=0, atol=1e-7)
    np.testing.assert_allclose(q[:, 1], r * (1 - np.cos(0.8 * t)), rtol=0, atol=1e-7)


def test_a_nonlinear_relation_is_held_at_every_row_with_gravity_and_a_push():
    """tests/decks/nonholonomic.xml as written: the second body's relation (nonlinear in
    velocities and positions, its start made consistent by Newton on the velocities) holds
    within 1e-9 at every row, the sleigh's too."""
    res = pysolver.loads(DECK).run()
    assert res.success, res.message
    assert np.abs(res.request(1)[:, 4]).max() < 1e-9
    assert np.abs(res.request(1)[:, 5]).max() < 1e-9


@pytest.mark.parametrize("expr, words", [
    ("ACCX(21) - 1", r"may read displacements, velocities and time \(found ACCX\)"),
])
def test_a_constraint_of_accelerations_is_a_deck_error(expr, words):
    with pytest.raises(DeckError, match=words):
        pysolver.loads(DECK.replace('expr="VY(21, 0, 21)"', f'expr="{expr}"'))


def test_velocities_through_a_variable_are_a_deck_error():
    text = DECK.replace('expr="VY(21, 0, 21)"', 'expr="VARVAL(9)"').replace(
        "</Model>", '<Reference_Variable id="9" expr="VY(21, 0, 21)"/></Model>')
    with pytest.raises(DeckError, match=r"reads velocities \(VY\) through another element"):
        pysolver.loads(text)


def test_statics_of_a_non_holonomic_scene_is_a_deck_error():
    text = DECK.replace('<Simulate analysis_type="Transient" end_time="3" '
                        'print_interval="0.05"/>', '<Simulate analysis_type="Static"/>')
    with pytest.raises(DeckError, match="Constraint_General 5 is a relation of velocities"):
        pysolver.loads(text)
