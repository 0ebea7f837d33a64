"""A very stiff penalty pendulum (issue 5): IDA as shipped fails its error test almost every
step; the C driver notices the "grow 2x, fail, halve" cycle and limits the step growth, which
makes the run short and more accurate without touching the model."""
import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pysolver
from pysolver.solve import cida

pytestmark = pytest.mark.skipif(not cida.available(),
                                reason="the scikit-sundae wheel ships no SUNDIALS libraries")

DECK = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/><Reference_Marker id="1" body_id="1"/>
<Reference_Marker id="10" body_id="2" pos_x="1"/><Body_Point id="2" cg_id="10" mass="1"/>
<Force_Gravity grav_y="-9.81"/>
<Force_Penalty id="1" expr="DM(10,1) - 1" penalty="1e8" penalty1="2e4"/>
<Post_Request id="1" expr1="DX(10)" expr2="DY(10)"/>
<Param_Transient integr_tol="{tol}" {extra}/></Model>
<Simulate analysis_type="Transient" end_time="{end}" print_interval="0.01"/></MotionSolve>"""


def error(res):
    """Largest distance from the ideal rigid pendulum (released horizontally)."""
    sol = solve_ivp(lambda t, s: [s[1], -9.81 * np.cos(s[0])], (0, res.t[-1]), [0, 0],
                    t_eval=res.t, rtol=1e-12, atol=1e-12, method="DOP853")
    return np.hypot(res.request(1)[:, 0] - np.cos(sol.y[0]),
                    res.request(1)[:, 1] - np.sin(sol.y[0])).max()


def run(extra="", tol=1e-7, end=2):
    return pysolver.loads(DECK.format(extra=extra, tol=tol, end=end)).run(backend="c")


def test_stiff_penalty_is_detected_and_tamed():
    # IDA as shipped: step growth 2, Newton coefficient 0.33
    plain = run('max_step_growth="2" nonlin_conv_coef="0.33"')
    auto = run()
    assert plain.success and auto.success
    assert plain.stats["netf"] > 0.9 * plain.stats["steps"]
    assert plain.stats["growth_limited_at"] is None
    # the limit comes on within the first windows of 50 steps, and the cycle stops
    assert 0 < auto.stats["growth_limited_at"] <= 500
    assert auto.stats["netf"] < 0.1 * auto.stats["steps"]
    assert auto.stats["steps"] < 0.2 * plain.stats["steps"]
    assert auto.stats["njac"] < 0.05 * plain.stats["njac"]
    assert error(auto) < error(plain)


def test_stiff_penalty_reaches_the_rigid_pendulum(decks):
    """decks/stiff_penalty_pendulum.xml, 10 s at its integr_tol 1e-10: within 1e-5 of the rigid
    pendulum (the penalty model itself differs by ~6e-6) in a bounded number of steps (IDA as
    shipped: ~5e5 steps, 2e-4)."""
    res = pysolver.load(decks / "stiff_penalty_pendulum.xml").run(backend="c")
    assert res.success and res.stats["growth_limited_at"] is not None
    assert error(res) < 1e-5
    assert res.stats["steps"] < 20000 and res.stats["njac"] < 4000


def test_ordinary_decks_keep_ida_step_control(decks):
    for name in ("catenary_bead", "particle_between_lines", "torque_free_spin", "spinning_top"):
        res = pysolver.load(decks / f"{name}.xml").run(backend="c")
        assert res.success and res.stats["growth_limited_at"] is None, name


def test_bad_step_control_options():
    with pytest.raises(pysolver.DeckError, match="expected a value > 1"):
        pysolver.loads(DECK.format(extra='max_step_growth="0.9"', tol=1e-7, end=1))
    with pytest.raises(pysolver.DeckError, match=r"expected a value in \(0, 1\)"):
        pysolver.loads(DECK.format(extra='nonlin_conv_coef="1.5"', tol=1e-7, end=1))
    model = pysolver.loads(DECK.format(extra="", tol=1e-7, end=1))
    with pytest.raises(ValueError, match="nonlin_conv_coef must be in"):
        model.run(nonlin_conv_coef=0)
    with pytest.raises(ValueError, match="nonlin_conv_coef other than IDA's 0.33 needs"):
        model.run(backend="sksundae", nonlin_conv_coef=0.1)


def test_python_deck_sets_the_step_control():
    text = """from pysolver.msolve import *
PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(10, PART=2, QP=[1, 0, 0])
POINT_MASS(2, MASS=1.0, CM=10)
PFORCE(1, FUNCTION="DM(10,1) - 1", PENALTY=1e8, PENALTY1=2e4)
INTEGRATOR(ERROR=1e-7, MAX_STEP_GROWTH=1.2, NONLIN_CONV_COEF=0.1)
"""
    model = pysolver.loads(text, fmt="py")
    assert model.transient.max_step_growth == 1.2
    assert model.transient.nonlin_conv_coef == 0.1
    assert model.transient.integr_tol == 1e-7


def test_summary_reports_the_stiff_penalty_mode():
    res = run()
    assert f"step growth limited from step {res.stats['growth_limited_at']}" in res.summary()
    assert "stiff penalty" not in run('max_step_growth="2"').summary()
