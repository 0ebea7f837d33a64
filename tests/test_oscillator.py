"""Bilateral penalty on a point mass under gravity: an exact damped linear oscillator."""
import numpy as np
import pytest

import pysolver

M, K, C, G, Z0, V0 = 2.0, 100.0, 4.0, 9.81, 1.2, 0.5

DECK = f"""<MotionSolve><Model>
  <Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="10" body_id="2" pos_z="{Z0}"/>
  <Body_Point id="2" cg_id="10" mass="{M}" v_ic_z="{V0}"/>
  <Force_Gravity grav_z="-{G}"/>
  <Force_Penalty id="1" expr="DZ(10) - 1" penalty="{K}" penalty1="{C}"/>
  <Post_Request id="1" expr1="DZ(10)" expr2="VZ(10)" expr3="PFORCE(1)"/>
</Model>
<Simulate analysis_type="Transient" end_time="3.0" print_interval="0.01"/>
</MotionSolve>"""


def exact(t):
    w0 = np.sqrt(K / M)
    zeta = C / (2 * np.sqrt(K * M))
    wd = w0 * np.sqrt(1 - zeta ** 2)
    zeq = 1 - M * G / K
    x0 = Z0 - zeq
    a, b = x0, (V0 + zeta * w0 * x0) / wd
    decay = np.exp(-zeta * w0 * t)
    z = zeq + decay * (a * np.cos(wd * t) + b * np.sin(wd * t))
    v = decay * ((-zeta * w0 * a + wd * b) * np.cos(wd * t) + (-zeta * w0 * b - wd * a) * np.sin(wd * t))
    return z, v


def run(tol):
    res = pysolver.loads(DECK).run(integr_tol=tol)
    assert res.success, res.message
    z, v = exact(res.t)
    R = res.request(1)
    # position error, and velocity error relative to the velocity amplitude
    return res, max(np.abs(R[:, 0] - z).max(), np.abs(R[:, 1] - v).max() / np.abs(v).max())


def test_error_below_1e6_at_tol_1e8():
    res, err = run(1e-8)
    assert err < 1e-6
    # the penalty force measure is the law F = -k g - c g'
    z, v = exact(res.t)
    np.testing.assert_allclose(res.request(1)[:, 2], -K * (z - 1) - C * v, atol=1e-4)


def test_error_scales_with_tolerance():
    errs = [run(tol)[1] for tol in (1e-4, 1e-6, 1e-8)]
    assert errs[0] > errs[1] > errs[2]
    # two decades of tolerance buy at least one decade of error
    assert errs[0] / errs[1] > 10 and errs[1] / errs[2] > 10


@pytest.mark.parametrize("tol,max_steps", [(1e-4, 250), (1e-6, 600), (1e-8, 1500)])
def test_cost_bounds(tol, max_steps):
    res, _ = run(tol)
    s = res.stats
    assert s["steps"] <= max_steps
    assert s["nres"] <= 2 * s["steps"] + 20
    assert s["njac"] <= s["steps"] // 2 + 20
