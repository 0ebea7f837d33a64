"""The default-name forms (trial 45): Adams' ROUTINE = lib:: and MotionSolve's
usrsub_fnc_name="NULL" mean the element's conventional routine (SFOSUB)."""
import numpy as np
import pytest

import pysolver

from scenes import usersub_library

SFOSUB = r'''#include "pysolver_usersub.h"
void SFOSUB(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
            double *value) {
  int m = (int)par[0], err;
  double x;
  c_sysfnc("DX", &m, 1, &x, &err);
  *value = -10.0 * (x - 1.0);
}
'''

PY = '''from pysolver.msolve import *
PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(10, PART=2, QP=[2, 0, 0])
POINT_MASS(2, MASS=1.0, CM=10)
SFORCE(1, I=10, J=1, TRANSLATION=True, FUNCTION="USER(10)", ROUTINE="{lib}::")
REQUEST(1, F1="DX(10)")
SIMULATE(TYPE="TRANSIENT", END=1.0, DTOUT=0.1)
'''

XML = '''<MotionSolve><Model>
<Body_Rigid id="1" isground="TRUE"/>
<Reference_Marker id="1" body_id="1"/>
<Reference_Marker id="10" body_id="2" pos_x="2"/>
<Body_Point id="2" cg_id="10" mass="1.0"/>
<Force_Scalar_TwoBody id="1" type="Force" i_marker_id="10" j_marker_id="1"
  usrsub_dll_name="{lib}" usrsub_fnc_name="NULL" usrsub_param_string="USER(10)"/>
<Post_Request id="1" expr1="DX(10)"/>
</Model><Simulate analysis_type="Transient" end_time="1" print_interval="0.1"/></MotionSolve>
'''


@pytest.fixture(scope="module")
def lib(tmp_path_factory):
    out = usersub_library(tmp_path_factory.mktemp("names"), SFOSUB, "sfo")
    if out is None:
        pytest.skip("no C compiler")
    return out


@pytest.mark.parametrize("fmt", ["py", "xml"])
def test_the_default_name_forms_call_sfosub(lib, fmt):
    text = (PY if fmt == "py" else XML).format(lib=lib)
    res = pysolver.loads(text, fmt=fmt).run(integr_tol=1e-9)
    assert res.success, res.message
    (how,) = res.meta["usersubs"].values()
    assert how.startswith(f"USER(10) -> SFOSUB ({lib}): C library {lib}")
    t = np.asarray(res.t)
    np.testing.assert_allclose(res.request(1)[:, 0], 1 + np.cos(np.sqrt(10) * t), atol=1e-5)
