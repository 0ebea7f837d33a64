"""The default-name forms (trial 45): Adams' ROUTINE = lib:: and MotionSolve's
usrsub_fnc_name="NULL" mean the element's conventional routine (SFOSUB)."""
import numpy as np
import pytest

import pysolver

from scenes import SPRING_PY, SPRING_SFOSUB, SPRING_XML, usersub_library


@pytest.fixture(scope="module")
def lib(tmp_path_factory):
    out = usersub_library(tmp_path_factory.mktemp("names"), SPRING_SFOSUB % "10.0", "sfo")
    if out is None:
        pytest.skip("no C compiler")
    return out


@pytest.mark.parametrize("fmt", ["py", "xml"])
def test_the_default_name_forms_call_sfosub(lib, fmt):
    text = (SPRING_PY.format(routine=f"{lib}::") if fmt == "py" else
            SPRING_XML.format(usersub=f'usrsub_dll_name="{lib}" usrsub_fnc_name="NULL"'))
    res = pysolver.loads(text, fmt=fmt).run(integr_tol=1e-9)
    assert res.success, res.message
    (how,) = res.meta["usersubs"].values()
    assert how.startswith(f"USER(10) -> SFOSUB ({lib}): C library {lib}")
    t = np.asarray(res.t)
    np.testing.assert_allclose(res.request(1)[:, 0], 1 + np.cos(np.sqrt(10) * t), atol=1e-5)
