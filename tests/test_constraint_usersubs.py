"""MOTSUB and GCOSUB: a motion and a general constraint given by a user subroutine, in every
form (traced Python, a Python routine called from the kernel, a C library, the Python
statements), against the same element given by its expression."""
import os
import shutil
import subprocess

import numpy as np
import pytest

import pysolver
from pysolver import DeckError

from helpers import ROOT

CRANK = (ROOT / "decks" / "joints" / "slider_crank.xml").read_text()
EXPR_MOTION = 'type="EXPRESSION" val_type="D"\n                  expr="2*PI*TIME"'
assert EXPR_MOTION in CRANK

MOTSUB_PY = """import math


def MOTSUB(id, time, par, npar, iord, iflag):
    return par[0] * math.pi * time
"""
# float() cannot be traced: the routine is called from the kernel, its time partial differenced
MOTSUB_UNTRACED = MOTSUB_PY.replace("par[0] * math.pi * time", "par[0] * math.pi * float(time)")
MOTSUB_C = r"""
#include <math.h>
#include "pysolver_usersub.h"

void MOTSUB(int *id, double *time, double *par, int *npar, int *iord, int *iflag,
            double *value) {
  /* the kernel asks for the value only (iord = 0) and differences it */
  *value = *iord == 0 ? par[0] * M_PI * *time : NAN;
}
"""


def _crank(tmp_path, usersub):
    return pysolver.loads(CRANK.replace(EXPR_MOTION, f'type="USERSUB" val_type="D" {usersub}'),
                          file=str(tmp_path / "crank.xml"))


def _library(tmp_path, source, name):
    (tmp_path / f"{name}.c").write_text(source)
    cc = shutil.which(os.environ.get("CC", "cc")) or shutil.which("gcc")
    subprocess.run([cc, "-shared", "-fPIC", f"-I{pysolver.get_include()}",
                    str(tmp_path / f"{name}.c"), "-o", str(tmp_path / f"{name}.so"), "-lm"],
                   check=True)
    return tmp_path / f"{name}.so"


@pytest.fixture(scope="module")
def crank_reference():
    return pysolver.loads(CRANK).run()


@pytest.mark.parametrize("form", ["traced", "untraced", "c"])
def test_a_motsub_drives_the_crank_as_its_expression(tmp_path, crank_reference, form):
    """The slider-crank's Motion_Joint 2 pi t as MOTSUB = par[0] pi t with USER(2): traced,
    the run is the expression's (same tree: equal to 1e-12); called from the kernel (a Python
    callback or a C library, iord always 0), its time derivatives by central differences:
    within 1e-7 of the expression's channels (measured about 1e-9), the driving torque within
    1e-4 of its peak."""
    if form == "c":
        usersub = (f'usrsub_dll_name="{_library(tmp_path, MOTSUB_C, "motsub")}" '
                   'usrsub_param_string="USER(2)"')
    else:
        (tmp_path / "motsub.py").write_text(MOTSUB_PY if form == "traced" else MOTSUB_UNTRACED)
        usersub = 'script_name="motsub.py" usrsub_param_string="USER(2)"'
    model = _crank(tmp_path, usersub)
    res = model.run()
    assert res.success, res.message
    ref = crank_reference
    np.testing.assert_array_equal(res.t, ref.t)
    tol = 1e-12 if form == "traced" else 1e-7
    q, q_ref = res.request(1)[:, :7].copy(), ref.request(1)[:, :7].copy()
    q[:, 5] = np.angle(np.exp(1j * (q[:, 5] - q_ref[:, 5])))   # the crank angle: AZ, at +-pi
    q_ref[:, 5] = 0.0                                          # either sign
    np.testing.assert_allclose(q, q_ref, rtol=0, atol=tol)
    # the driving torque rests on accelerations: 1e-4 of its peak (measured 1.0e-5)
    np.testing.assert_allclose(res.motion(1), ref.motion(1), rtol=0,
                               atol=(tol if form == "traced" else 1e-4)
                               * np.abs(ref.motion(1)).max())
    how = model.compile().model.usersub_paths["Motion_Joint 1"]
    assert ("traced into the kernel" in how) == (form == "traced")


def test_a_motsub_that_reads_the_state_is_a_deck_error(tmp_path):
    (tmp_path / "motsub.py").write_text(
        "def MOTSUB(id, time, par, npar, iord, iflag):\n"
        "    return time + py_sysfnc('DX', [40])[0]\n")
    model = _crank(tmp_path, 'script_name="motsub.py" usrsub_param_string="USER(2)"')
    with pytest.raises(DeckError, match="MOTSUB must give a function of time only; it reads DX"):
        model.run()


SPHERE = """<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
  <Reference_Marker id="1" body_id="1"/>
  <Reference_Marker id="9" body_id="2" pos_x="1"/>
  <Body_Point id="2" cg_id="9" mass="0.5" v_ic_z="0.3"/>
  <Force_Gravity grav_y="-9.81"/>
  {gcon}
  <Post_Request id="1" expr1="DX(9)" expr2="DY(9)" expr3="DZ(9)" expr4="DM(9)"/>
  <Param_Transient integr_tol="1e-9"/></Model>
  <Simulate analysis_type="Transient" end_time="1" print_interval="0.05"/></MotionSolve>"""
GCON_EXPR = '<Constraint_General id="3" expr="DX(9)**2 + DY(9)**2 + DZ(9)**2 - 1"/>'
GCOSUB_PY = """def GCOSUB(id, time, par, npar, dflag, iflag):
    m = [int(par[0])]
    x, y, z = (py_sysfnc(f, m)[0] for f in ("DX", "DY", "DZ"))
    return x * x + y * y + z * z - par[1] ** 2
"""
GCOSUB_C = r"""
#include "pysolver_usersub.h"

void GCOSUB(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
            double *value) {
  int marker = (int)par[0], err;
  double x = 0.0, y = 0.0, z = 0.0;
  c_sysfnc("DX", &marker, 1, &x, &err);
  c_sysfnc("DY", &marker, 1, &y, &err);
  c_sysfnc("DZ", &marker, 1, &z, &err);
  *value = x * x + y * y + z * z - par[1] * par[1];
}
"""


@pytest.mark.parametrize("form", ["traced", "c"])
def test_a_gcosub_holds_a_point_on_its_sphere(tmp_path, form):
    """A point held on the unit sphere by GCOSUB (USER(9, 1): marker and radius), implied by
    the routine's attributes as MotionSolve's Constraint_General has no type: traced, the run
    equals the expression's; from a C library (c_sysfnc, partials differenced) within 1e-7; the
    distance 1 at every row either way."""
    if form == "c":
        usersub = f'usrsub_dll_name="{_library(tmp_path, GCOSUB_C, "gcosub")}"'
    else:
        (tmp_path / "gcosub.py").write_text(GCOSUB_PY)
        usersub = 'script_name="gcosub.py"'
    text = SPHERE.format(gcon=f'<Constraint_General id="3" {usersub} '
                              'usrsub_param_string="USER(9, 1)"/>')
    res = pysolver.loads(text, file=str(tmp_path / "sphere.xml")).run()
    ref = pysolver.loads(SPHERE.format(gcon=GCON_EXPR)).run()
    assert res.success and ref.success, res.message
    tol = 1e-12 if form == "traced" else 1e-7
    np.testing.assert_allclose(res.request(1)[:, :4], ref.request(1)[:, :4], rtol=0, atol=tol)
    np.testing.assert_allclose(res.request(1)[:, 3], 1.0, rtol=0, atol=1e-9)


GCOSUB_SYSPAR = GCOSUB_C.replace(
    "  *value = x * x + y * y + z * z - par[1] * par[1];\n",
    "  *value = x * x + y * y + z * z - par[1] * par[1];\n"
    "  double d[3] = {par[2] * x, 2.0 * y, 2.0 * z};   /* USER(9, 1, 2): right */\n"
    "  c_syspar(\"DX\", &marker, 1, d, 1, &err);\n"
    "  c_syspar(\"DY\", &marker, 1, d + 1, 1, &err);\n"
    "  c_syspar(\"DZ\", &marker, 1, d + 2, 1, &err);\n")


def test_a_gcosub_giving_its_partials(tmp_path):
    """GCOSUB with c_syspar: right partials give the expression's run within 1e-7; a wrong one
    ends the run with success=False and c_syspar's message, as for the other kinds (the
    redundancy probe at compile time raised it instead)."""
    lib = _library(tmp_path, GCOSUB_SYSPAR, "gcosub_syspar")
    ref = pysolver.loads(SPHERE.format(gcon=GCON_EXPR)).run()
    for factor in (2, 3):
        res = pysolver.loads(SPHERE.format(gcon=f'<Constraint_General id="3" usrsub_dll_name='
                                                f'"{lib}" usrsub_param_string="USER(9, 1, '
                                                f'{factor})"/>')).run()
        if factor == 2:
            assert res.success, res.message
            np.testing.assert_allclose(res.request(1)[:, :4], ref.request(1)[:, :4], rtol=0,
                                       atol=1e-7)
        else:
            assert not res.success
            assert res.message == ("user subroutine (id 3): GCOSUB: c_syspar gave the partial in "
                                   "DX(9) as 3, but differences of its value give 2 (t = 0)")


def test_the_statements_take_the_routines(tmp_path):
    """MOTION(..., ROUTINE=) and GCON(..., ROUTINE=, FUNCTION="USER(...)") in a Python deck."""
    deck = tmp_path / "driven.py"
    deck.write_text(
        "from pysolver.msolve import *\n"
        "def drive(id, time, par, npar, iord, iflag):\n    return par[0] * time\n"
        "def ring(id, time, par, npar, dflag, iflag):\n"
        "    return py_sysfnc('DX', [9])[0] ** 2 + py_sysfnc('DY', [9])[0] ** 2 - 1\n"
        "PART(1, GROUND=True)\nMARKER(1, PART=1)\nMARKER(9, PART=2, QP=[1, 0, 0])\n"
        "POINT_MASS(2, MASS=1, CM=9)\n"
        "GCON(1, FUNCTION='USER(0)', ROUTINE=ring)\n"
        "MOTION(1, I=9, J=1, DIRECTION='Z', FUNCTION='USER(0.5)', ROUTINE=drive)\n"
        "ACCGRAV(JGRAV=-9.81)\n"
        "REQUEST(1, F1='DX(9)**2 + DY(9)**2', F2='DZ(9)')\n"
        "SIMULATE(TYPE='TRANSIENT', END=1, DTOUT=0.25)\n")
    res = pysolver.load(deck).run(integr_tol=1e-9)
    assert res.success, res.message
    np.testing.assert_allclose(res.request(1)[:, 0], 1.0, rtol=0, atol=1e-9)
    np.testing.assert_allclose(res.request(1)[:, 1], 0.5 * res.t, rtol=0, atol=1e-12)
