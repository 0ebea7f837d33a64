"""A routine that fails at an output row (trial 45): a REQSUB, or a VARSUB only a request
reads. The run ends at that row's time with the routine's message (status -400); the failing
row is not kept (it was kept as NaN, and the failure reported at the next row)."""
import numpy as np
import pytest

import pysolver
from pysolver.solve import fast

from scenes import usersub_library

SCENE = '''from pysolver.msolve import *
{routine}
PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(10, PART=2, QP=[2, 0, 0])
POINT_MASS(2, MASS=1.0, CM=10)
SFORCE(1, I=10, J=1, TRANSLATION=True, FUNCTION="-10*(DM(10,1)-1)")
{elements}
INTEGRATOR(ERROR=1e-8)
SIMULATE(TYPE="TRANSIENT", END=1.0, DTOUT=0.1)
'''

REQSUB = ('def req(id, time, par, npar, iflag):\n'
          '    x = float(py_sysfnc("DX", [10])[0])\n'
          '    if time > 0.5:\n'
          '        raise RuntimeError("request failed")\n'
          '    return [x]\n')
REQUEST = 'REQUEST(1, FUNCTION="USER(10)", ROUTINE=req)'
VARSUB = ('def var(id, time, par, npar, dflag, iflag):\n'
          '    x = float(py_sysfnc("DX", [10])[0])\n'
          '    if iflag == 0 and time > 0.5:\n'
          '        py_errmes(1, "variable failed", id, "STOP")\n'
          '    return x\n')
VARIABLE = ('VARIABLE(3, FUNCTION="USER(10)", ROUTINE=var)\n'
            'REQUEST(1, F1="VARVAL(3)")')
#: a sensor that never fires: the run goes through the C loop of acting actors
SENSOR = '\nSENSOR(5, FUNCTION="TIME", VALUE=5, OPERATOR="GE", HALT=True)'
ROWS = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5]


def _check(res, message):
    assert (res.success, res.status, res.message) == (False, -400, message)
    np.testing.assert_allclose(res.t, ROWS, rtol=0, atol=1e-12)
    x = res.request(1)[:, 0]
    assert np.isfinite(x).all()
    # x = 1 + cos(sqrt(10) t)
    np.testing.assert_allclose(x, 1 + np.cos(np.sqrt(10) * np.asarray(ROWS)), atol=1e-6)


REQ_MESSAGE = "user subroutine (id 1): req raised RuntimeError: request failed (t = 0.6)"
VAR_MESSAGE = "user subroutine (id 3): var: variable failed (id 3) (t = 0.6)"


@pytest.mark.parametrize("path", ["batched", "acting", "general", "sksundae"])
@pytest.mark.parametrize("routine, elements, message", [
    (REQSUB, REQUEST, REQ_MESSAGE), (VARSUB, VARIABLE, VAR_MESSAGE)])
def test_a_routine_failing_at_a_row_ends_the_run_there(monkeypatch, path, routine, elements,
                                                       message):
    if path == "general":
        monkeypatch.setattr(fast, "ENABLED", False)
    if path == "acting":
        elements += SENSOR
    deck = pysolver.loads(SCENE.format(routine=routine, elements=elements), fmt="py")
    kw = {"backend": "sksundae"} if path == "sksundae" else {}
    _check(deck.run(**kw), message)


C_REQSUB = r'''#include "pysolver_usersub.h"
void REQSUB(int *id, double *time, double *par, int *npar, int *iflag, double *result) {
  int m = (int)par[0], err;
  c_sysfnc("DX", &m, 1, result, &err);
  if (!*iflag && *time > 0.5) c_errmes(1, "C request failed", *id, "STOP");
}
'''


def test_a_c_reqsub_failing_at_a_row_ends_the_run_there(tmp_path):
    lib = usersub_library(tmp_path, C_REQSUB, "req")
    if lib is None:
        pytest.skip("no C compiler")
    deck = pysolver.loads(SCENE.format(routine="", elements=f'REQUEST(1, FUNCTION="USER(10)", '
                                       f'ROUTINE="{lib}::REQSUB")'), fmt="py")
    _check(deck.run(), "user subroutine (id 1): REQSUB: C request failed (t = 0.6)")
