"""A very stiff penalty pendulum (issue 5): IDA's step-growth limit turns a run that fails its
error test almost every step into a short, more accurate one."""
import numpy as np
from scipy.integrate import solve_ivp

import pysolver

DECK = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/><Reference_Marker id="1" body_id="1"/>
<Reference_Marker id="10" body_id="2" pos_x="1"/><Body_Point id="2" cg_id="10" mass="1"/>
<Force_Gravity grav_y="-9.81"/>
<Force_Penalty id="1" expr="DM(10,1) - 1" penalty="1e8" penalty1="2e4"/>
<Post_Request id="1" expr1="DX(10)" expr2="DY(10)"/>
<Param_Transient integr_tol="1e-7" {extra}/></Model>
<Simulate analysis_type="Transient" end_time="2" print_interval="0.01"/></MotionSolve>"""


def error(res):
    """Largest distance from the ideal rigid pendulum (released horizontally)."""
    sol = solve_ivp(lambda t, s: [s[1], -9.81 * np.cos(s[0])], (0, 2), [0, 0], t_eval=res.t,
                    rtol=1e-12, atol=1e-12, method="DOP853")
    return np.hypot(res.request(1)[:, 0] - np.cos(sol.y[0]),
                    res.request(1)[:, 1] - np.sin(sol.y[0])).max()


def test_step_growth_limit_tames_a_stiff_penalty():
    plain = pysolver.loads(DECK.format(extra="")).run(backend="c")
    tamed = pysolver.loads(DECK.format(extra='max_step_growth="1.1"')).run(backend="c")
    assert plain.success and tamed.success
    # without the limit almost every step fails IDA's error test once
    assert plain.stats["netf"] > 0.9 * plain.stats["steps"]
    assert tamed.stats["netf"] < 0.2 * tamed.stats["steps"]
    assert tamed.stats["njac"] < 0.1 * plain.stats["njac"]
    assert tamed.stats["steps"] < 0.5 * plain.stats["steps"]
    assert error(tamed) <= error(plain)


def test_bad_step_growth():
    import pytest
    with pytest.raises(pysolver.DeckError, match="expected a value > 1"):
        pysolver.loads(DECK.format(extra='max_step_growth="0.9"'))
