"""Hard cases for penalty models: stiffness and smoothing over decades (issue 5, part).

Each run must complete, come to rest at the force balance, and stay within a step budget
(measured values with about 30 % margin)."""
import numpy as np
import pytest

import pysolver


def rest_penetration(k, mg, s):
    """Root of 2 k g STEP(g, 0, 0, s, 1) = m g, also beyond the smoothing band."""
    lo, hi = 0.0, max(s, mg / k)
    for _ in range(200):
        g = 0.5 * (lo + hi)
        d = min(g / s, 1.0)
        if 2 * k * g * d * d * (3 - 2 * d) > mg:
            hi = g
        else:
            lo = g
    return 0.5 * (lo + hi)

# (penalty N/mm, smoothing mm): step budget
CASES = {(1e2, 1.0): 650, (1e2, 1e-2): 620, (1e4, 1.0): 700, (1e4, 1e-2): 760,
         (1e4, 1e-4): 720, (1e6, 1e-2): 2100, (1e6, 1e-4): 750, (1e8, 1e-4): 13500}


@pytest.mark.parametrize("k,s", list(CASES), ids=[f"k{k:g}-s{s:g}" for k, s in CASES])
def test_seed3_over_stiffness_and_smoothing(decks, k, s):
    text = (decks / "particle_between_lines.xml").read_text().replace(
        'penalty="1E4"', f'penalty="{k:g}"').replace('smoothing_factor="1.0"',
                                                     f'smoothing_factor="{s:g}"')
    end = 10.0 if k < 1e3 else 3.0
    text = text.replace('end_time="3.0"', f'end_time="{end}"')
    res = pysolver.loads(text).run()
    assert res.success, res.message
    x, z = res.request(1)[-1, :2]
    g = rest_penetration(k, 9.81, s)
    assert abs(x) < 1e-4 and abs(z - (1 - g)) < 1e-4, (x, z, 1 - g)
    assert res.stats["steps"] <= CASES[(k, s)]


def test_undamped_contact_keeps_energy(decks):
    """penalty1 = 0: a conservative bouncing particle; its energy stays constant to tolerance."""
    text = (decks / "particle_between_lines.xml").read_text().replace(
        'penalty1="1E2"', 'penalty1="0"').replace('integr_tol="1e-6"', 'integr_tol="1e-9"')
    text = text.replace('end_time="3.0"', 'end_time="1.0"')
    res = pysolver.loads(text).run()
    assert res.success
    x, z = res.request(1)[:, 0], res.request(1)[:, 1]
    vx, vz = res.y[:, 3], res.y[:, 5]

    def potential(g):
        gp = np.clip(g, 0, None)
        d = np.clip(gp, 0, 1)
        # integral of k g S(g) for S = d^2 (3 - 2 d) on [0, 1], linear k g beyond
        inside = 1e4 * (0.75 * d ** 4 - 0.4 * d ** 5)
        return np.where(gp <= 1, inside, 1e4 * (0.35 + 0.5 * (gp ** 2 - 1)))

    E = 0.5 * (vx ** 2 + vz ** 2) + 9810 * z + 1000 * (potential(1 + x - z) + potential(1 - x - z))
    assert np.abs(E - E[0]).max() < 1e-5 * E[0]


def test_resting_on_a_sharp_contact_does_not_chatter():
    """A particle at rest on a floor with a tiny smoothing band: no step collapse."""
    deck = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
      <Reference_Marker id="10" body_id="2" pos_z="-1e-6"/><Body_Point id="2" cg_id="10" mass="1"/>
      <Force_Gravity grav_z="-9.81"/>
      <Force_Penalty id="1" expr="-DZ(10)" penalty="1e7" penalty1="1e3" unilateral="TRUE" smoothing_factor="1e-6"/>
      <Post_Request id="1" expr1="DZ(10)" expr2="PFORCE(1)"/></Model>
      <Simulate analysis_type="Transient" end_time="10" print_interval="0.1"/></MotionSolve>"""
    res = pysolver.loads(deck).run(integr_tol=1e-6)
    assert res.success and res.stats["steps"] < 400
    np.testing.assert_allclose(res.request(1)[-10:, 1], -9.81, rtol=1e-6)
