"""A MOTSUB called from the kernel gives its velocity and acceleration when asked (iord = 1, 2,
as Adams asks): the motion's reaction and the accelerations are then the expression version's
(trial 45: differenced in time they were off by up to 5e-4 of the peak)."""
import numpy as np
import pytest

import pysolver
from pysolver.errors import DeckError

from scenes import usersub_library

A, W, M = 100.0, 0.2, 2.0

HONOURS = r'''#include <math.h>
#include "pysolver_usersub.h"
void MOTSUB(int *id, double *time, double *par, int *npar, int *iord, int *iflag,
            double *value) {
  double a = par[0], w = par[1], t = *time;
  if (*iord == 0) *value = a * sin(w * t);
  else if (*iord == 1) *value = a * w * cos(w * t);
  else *value = -a * w * w * sin(w * t);
}
'''
IGNORES = HONOURS.replace("if (*iord == 0) *value", "*value").split("  else if")[0] + "}\n"
WRONG = HONOURS.replace("a * w * cos(w * t)", "a * cos(w * t)")

PYTHON = '''import math
def mot(id, time, par, npar, iord, iflag):
    t = float(time)              # not traced: called from the kernel
    a, w = par
    return [a * math.sin(w * t), a * w * math.cos(w * t), -a * w * w * math.sin(w * t)][iord]
'''

DECK = '''from pysolver.msolve import *
{pre}
PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(10, PART=2)
POINT_MASS(2, MASS={m}, CM=10)
MOTION(1, I=10, J=1, DIRECTION="X", {f})
REQUEST(1, F1="DX(10,1)", F2="ACCX(10)", F3="MOTION(1)")
INTEGRATOR(ERROR=1e-6)
SIMULATE(TYPE="TRANSIENT", END=10, DTOUT=0.05)
'''


def _run(f, pre=""):
    return pysolver.loads(DECK.format(f=f, pre=pre, m=M), fmt="py").run()


@pytest.fixture(scope="module")
def libs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("motsub")
    built = {k: usersub_library(folder, src, k) for k, src in
             (("honours", HONOURS), ("ignores", IGNORES), ("wrong", WRONG))}
    if built["honours"] is None:
        pytest.skip("no C compiler")
    return built


def _routine(lib):
    return f'FUNCTION="USER({A},{W})", ROUTINE="{lib}::MOTSUB"'


@pytest.mark.parametrize("form", ["c", "python"])
def test_a_motsub_that_honours_iord_gives_the_expressions_reaction(libs, form):
    ref = _run(f'FUNCTION="{A}*SIN({W}*TIME)"')
    res = _run(_routine(libs["honours"])) if form == "c" else \
        _run('FUNCTION="USER(100, 0.2)", ROUTINE=mot', PYTHON)
    assert res.success and ref.success, res.message
    t = np.asarray(res.t)
    peak = M * A * W * W
    exact = -M * A * W * W * np.sin(W * t)
    # the expression's own error against the closed form is 2e-9 of the peak
    for run in (res, ref):
        assert abs(run.request(1)[:, 2] - exact).max() < 1e-8 * peak
        assert abs(run.request(1)[:, 1] - exact / M).max() < 1e-8 * peak / M
    np.testing.assert_allclose(res.request(1)[:, 2], ref.request(1)[:, 2], rtol=0,
                               atol=1e-8 * peak)
    (how,) = res.meta["usersubs"].values()
    assert how.endswith("called from the kernel; its velocity and acceleration from the "
                        "routine itself (iord = 1, 2)")


def test_a_motsub_that_ignores_iord_is_differenced_and_says_so(libs):
    res = _run(_routine(libs["ignores"]))
    assert res.success, res.message
    (how,) = res.meta["usersubs"].values()
    assert how.endswith("its velocity and acceleration by differences of its value in time "
                        "(it ignores iord)")
    t = np.asarray(res.t)
    assert abs(res.request(1)[:, 0] - A * np.sin(W * t)).max() < 1e-6


def test_a_motsub_with_a_wrong_velocity_is_refused(libs):
    with pytest.raises(DeckError) as err:
        _run(_routine(libs["wrong"]))
    assert "MOTSUB gives 100 for iord = 1 at t = 0, but differences of its value give 20: " \
        "give the velocity (iord = 1) and acceleration (iord = 2), or the value whatever " \
        "iord is" in str(err.value)
