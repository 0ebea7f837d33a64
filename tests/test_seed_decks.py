"""The seed's three Force_Penalty examples, in XML and in the Python format."""
import numpy as np
import pytest

import pysolver

from scenes import rest_penetration

SEEDS = ["catenary_bead", "particle_above_line", "particle_between_lines"]


@pytest.mark.parametrize("deck,k,s,z_line,length_unit", [
    ("particle_between_lines.xml", 1e4, 1.0, 1.0, 1.0),        # kg, mm, s, N
    ("particle_between_lines_si.xml", 1e7, 1e-3, 1e-3, 1e-3),  # consistent SI, no Units
])
def test_seed3_comes_to_rest_at_force_balance(decks, deck, k, s, z_line, length_unit):
    res = pysolver.load(decks / deck).run()
    assert res.success, res.message
    x, z = res.request(1)[-1, :2]
    g = rest_penetration(k, 1.0 * 9.81, s)     # m grav = 9.81 N in both unit systems
    assert abs(x) < 1e-6 * length_unit
    assert abs(z - (z_line - g)) < 1e-6 * length_unit
    # both penalties carry half the weight each, in newtons
    np.testing.assert_allclose(res.request(1)[-1, 2:4], [-9.81 / 2] * 2, rtol=1e-6)


def test_seed3_same_motion_in_mm_and_m(decks):
    mm = pysolver.load(decks / "particle_between_lines.xml").run(integr_tol=1e-8)
    m = pysolver.load(decks / "particle_between_lines_si.xml").run(integr_tol=1e-11)
    np.testing.assert_allclose(m.request(1)[:, :2] * 1e3, mm.request(1)[:, :2], atol=2e-3)


def catenary_energy(R, k=1e4, grav=9.81):
    x, y, vx, vy, g = R[:, :5].T
    return 0.5 * (vx ** 2 + vy ** 2) + grav * y + 0.5 * k * g ** 2


def test_catenary_violation_and_energy(decks):
    res = pysolver.load(decks / "catenary_bead.xml").run()
    R = res.request(1)
    g = R[:, 4]
    # violation is O(m grav / penalty): weight plus centripetal load over the stiffness
    assert np.abs(g).max() < 2 * 9.81 / 1e4
    assert np.abs(g).max() > 0.5 * 9.81 / 1e4
    # g really is y - cosh(x)
    np.testing.assert_allclose(g, R[:, 1] - np.cosh(R[:, 0]), atol=1e-12)
    # energy only leaves through penalty1 (damping of g'): never gained, and little lost
    E = catenary_energy(R)
    assert np.all(E <= E[0] + 1e-6)
    assert E[0] - E[-1] < 1e-3 * E[0]


def test_catenary_violation_scales_with_one_over_penalty(decks):
    text = (decks / "catenary_bead.xml").read_text()
    stiff = pysolver.loads(text.replace('penalty="1E4"', 'penalty="1E6"')).run()
    soft = pysolver.load(decks / "catenary_bead.xml").run()
    ratio = np.abs(soft.request(1)[:, 4]).max() / np.abs(stiff.request(1)[:, 4]).max()
    assert 50 < ratio < 200


@pytest.mark.parametrize("name", SEEDS + ["torque_free_spin", "spinning_top"])
def test_xml_and_python_decks_agree(decks, name):
    a = pysolver.load(decks / f"{name}.xml").run()
    b = pysolver.load(decks / f"{name}.py").run()
    assert a.success and b.success
    np.testing.assert_array_equal(a.t, b.t)
    A, B = a.request(1), b.request(1)
    np.testing.assert_array_equal(np.isnan(A), np.isnan(B))
    assert np.nanmax(np.abs(A - B)) <= 1e-12


# steps, residual and Jacobian evaluations measured at the deck tolerances, plus ~25 % margin
COST = {"catenary_bead": (410, 620, 45), "particle_above_line": (290, 460, 110),
        "particle_between_lines": (660, 990, 185)}


@pytest.mark.parametrize("name", SEEDS)
def test_cost_counters(decks, name):
    res = pysolver.load(decks / f"{name}.xml").run()
    steps, nres, njac = COST[name]
    assert res.stats["steps"] <= steps
    assert res.stats["nres"] <= nres
    assert res.stats["njac"] <= njac
    assert res.stats["steps"] >= steps // 3, "suspiciously few steps: is the run complete?"
