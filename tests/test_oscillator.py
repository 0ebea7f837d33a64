"""Bilateral penalty on a point mass under gravity: an exact damped linear oscillator."""
import numpy as np
import pytest

import pysolver

from scenes import OSCILLATOR as DECK
from scenes import V0, Z0, C, G, K, M  # noqa: F401
from scenes import oscillator_exact as exact


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
