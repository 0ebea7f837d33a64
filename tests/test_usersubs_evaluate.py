"""Adams' SENSOR ``EVALUATE = USER(...)`` with ``EVALUATE_ROUTINE`` (trial 45): a C SEVSUB
(library::name) or a function of the sensor's SCRIPT, and the errors worded in Adams'
keywords (and a Python deck's), not XML's type="USERSUB" / script_name."""
import math

import pytest

import pysolver

from scenes import usersub_library

C_SUBS = r'''#include "pysolver_usersub.h"
void SENSUB(int *id, double *time, double *par, int *npar, int *iflag, double *value) {
  int m = (int)par[0], err;
  c_sysfnc("DX", &m, 1, value, &err);
}
void SEVSUB(int *id, double *time, double *par, int *npar, int *iflag, double *value) {
  int m = (int)par[0], err;
  c_sysfnc("VX", &m, 1, value, &err);
}
'''

PY_SUBS = '''def sen(id, time, par, npar, iflag):
    return py_sysfnc("DX", [int(par[0])])[0]


def sev(id, time, par, npar, iflag):
    return py_sysfnc("VX", [int(par[0])])[0]
'''

#: x = 1 + cos(sqrt(10) t); the sensor (x <= 0.5) fires at sqrt(10) t = 2 pi / 3 and stores
#: VX there, -sqrt(10) sin(2 pi / 3).
ADM = '''osc
PART/1, GROUND
MARKER/1, PART = 1
MARKER/10, PART = 2, QP = 2.0, 0.0, 0.0
PART/2, MASS = 1.0, CM = 10, IP = 0.1, 0.1, 0.1
SFORCE/1, I = 10, J = 1, TRANSLATION, FUNCTION = -10*(DX(10) - 1)
SENSOR/3, FUNCTION = {function}\\, VALUE = 0.5, ERROR = 1e-6, LE, HALT, {sub}
REQUEST/1, F1 = DX(10)\\, F2 = SENVAL(3)
END
'''
ACF = "osc\nosc\nSIMULATE/DYNAMICS, END = 2.0, DTOUT = 0.05\nSTOP\n"
T_FIRE = 2 * math.pi / 3 / math.sqrt(10)
VX_FIRE = -math.sqrt(10) * math.sin(2 * math.pi / 3)


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    out = tmp_path_factory.mktemp("evaluate")
    if usersub_library(out, C_SUBS, "sx") is None:
        pytest.skip("no C compiler")
    (out / "subs.py").write_text(PY_SUBS)
    return out


def _load(folder, sub, function="USER(10)"):
    (folder / "osc.adm").write_text(ADM.format(function=function, sub=sub))
    (folder / "osc.acf").write_text(ACF)
    return pysolver.load(str(folder / "osc.acf"))


@pytest.mark.parametrize("sub, how", [
    ("ROUTINE = sx.so::SENSUB, EVALUATE = USER(10)\\, EVALUATE_ROUTINE = sx.so::SEVSUB",
     "USER(10) -> SEVSUB ({folder}/sx.so): C library {folder}/sx.so, called from the kernel"),
    ("SCRIPT = subs.py, ROUTINE = sen, EVALUATE = USER(10)\\, EVALUATE_ROUTINE = sev",
     "USER(10) -> sev ({folder}/subs.py): traced into the kernel: VX(10)"),
])
def test_a_sevsub_named_by_evaluate_routine_stores_senval(folder, sub, how):
    res = _load(folder, sub).run(integr_tol=1e-9)
    assert (res.success, res.message) == (True, "halted by Sensor_Event 3 at t = 0.662305885")
    assert res.meta["usersubs"]["Sensor_Evaluate 3"].startswith(how.format(folder=folder))
    assert res.t[-1] == pytest.approx(T_FIRE, abs=1e-8)
    x, senval = res.request(1)[-1, :2]
    assert x == pytest.approx(0.5, abs=1e-6)
    assert senval == pytest.approx(VX_FIRE, abs=1e-6)
    assert list(res.request(1)[:-1, 1]) == [0.0] * (len(res.t) - 1)


def test_a_scripts_sevsub_on_a_sensor_of_an_expression(folder):
    """SCRIPT serves the evaluate alone when the sensor's own FUNCTION is an expression."""
    res = _load(folder, "SCRIPT = subs.py, EVALUATE = USER(10)\\, EVALUATE_ROUTINE = sev",
                function="DX(10)").run(integr_tol=1e-9)
    assert res.success, res.message
    assert res.request(1)[-1, 1] == pytest.approx(VX_FIRE, abs=1e-6)


@pytest.mark.parametrize("sub, where, message", [
    ("EVALUATE = USER(10)", "SENSOR/3, attribute 'EVALUATE'",
     "EVALUATE = USER(...) without EVALUATE_ROUTINE calls Adams' default SEVSUB, the one "
     "linked into Adams' user library, and pysolver links no library: give EVALUATE_ROUTINE = "
     "library::SEVSUB (a C library), or SCRIPT = file.py and EVALUATE_ROUTINE = the name of "
     "its Python function (docs/adams.md, \"User subroutines\")"),
    ("EVALUATE = VX(10)\\, EVALUATE_ROUTINE = sx.so::SEVSUB",
     "SENSOR/3, attribute 'EVALUATE_ROUTINE'",
     "EVALUATE_ROUTINE names the SEVSUB that EVALUATE = USER(...) calls: give EVALUATE = "
     "USER(...) with its parameters"),
    ("EVALUATE = USER(10)\\, EVALUATE_ROUTINE = sx.so::NOPE",
     "SENSOR/3 (Sensor_Evaluate), attribute 'EVALUATE_ROUTINE'",
     "library {folder}/sx.so exports no function NOPE (it exports: SENSUB, SEVSUB)"),
    ("SCRIPT = subs.py, EVALUATE = USER(10)\\, EVALUATE_ROUTINE = nope",
     "SENSOR/3 (Sensor_Evaluate), attribute 'EVALUATE_ROUTINE'",
     "script {folder}/subs.py defines no function nope"),
])
def test_adams_evaluate_errors_name_adams_keywords(folder, sub, where, message):
    with pytest.raises(pysolver.DeckError) as err:
        _load(folder, sub, function="DX(10)").check()
    assert str(err.value) == f"{folder}/osc.adm:7, {where}: {message.format(folder=folder)}"


PY = '''from pysolver.msolve import *
PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(10, PART=2, QP=[2, 0, 0])
POINT_MASS(2, MASS=1.0, CM=10)
SENSOR(3, FUNCTION="DX(10)", VALUE=0.5, OPERATOR="LT", HALT=True, {sub})
SIMULATE(TYPE="TRANSIENT", END=1.0, DTOUT=0.1)
'''


@pytest.mark.parametrize("sub, message", [
    ('EVALUATE="USER(10)"', "attribute 'EVALUATE': USER(...) calls a user subroutine: give "
                            "EVALUATE_ROUTINE= the routine"),
    ('EVALUATE="VX(10)", EVALUATE_ROUTINE="{folder}/sx.so::SEVSUB"',
     "attribute 'EVALUATE': a user subroutine takes its parameters as EVALUATE=\"USER(...)\", "
     "not an expression"),
])
def test_python_deck_evaluate_errors_name_its_keywords(folder, sub, message):
    with pytest.raises(pysolver.DeckError) as err:
        pysolver.loads(PY.format(sub=sub.format(folder=folder)), fmt="py").check()
    assert str(err.value) == f"<string>:6, Sensor_Evaluate id=3, {message}"
