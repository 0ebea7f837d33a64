"""Python user subroutines that use NumPy on the values they read (trial 43, item 2): a ufunc
the expression language has (np.sin(time), np.sqrt(z * z), np.linalg.norm of py_sysary's
list) traces into the expression written by hand; any other NumPy use is called from the
kernel; a routine that raises at every state is still a DeckError; no message names the
tracer's internal types."""
import numpy as np
import pytest

import pysolver

SCENE = """from pysolver.msolve import *
PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(10, PART=2, QP=[0, 0, 1])
POINT_MASS(2, MASS=1, CM=10)
{body}
REQUEST(1, F1="DZ(10)", F2="VZ(10)")
INTEGRATOR(ERROR=1e-10)
SIMULATE(TYPE="TRANSIENT", END=1.0, DTOUT=0.01)
"""

#: The trial's routines (subs3.py), the same with float() (called from the kernel), and more.
ROUTINES = '''import numpy as np


def S_NPSIN_TIME(id, time, par, npar, dflag, iflag):
    return par[0] * np.sin(par[1] * time)


def S_NPSIN_FLOAT(id, time, par, npar, dflag, iflag):
    return float(par[0] * np.sin(par[1] * time))


def S_NPSQRT(id, time, par, npar, dflag, iflag):
    [z, errflg] = py_sysfnc("DZ", [int(par[0])])
    return -par[1] * np.sqrt(z * z)


def S_NPSQRT_FLOAT(id, time, par, npar, dflag, iflag):
    z = float(py_sysfnc("DZ", [int(par[0])])[0])
    return -par[1] * np.sqrt(z * z)


def S_SYSARY(id, time, par, npar, dflag, iflag):
    p, errflg = py_sysary("TDISP", [int(par[0])])
    return -par[1] * np.linalg.norm(p)


def S_EXPM1(id, time, par, npar, dflag, iflag):
    z = py_sysfnc("DZ", [int(par[0])])[0]
    return -par[1] * np.expm1(z)


def S_EXPM1_FLOAT(id, time, par, npar, dflag, iflag):
    z = float(py_sysfnc("DZ", [int(par[0])])[0])
    return -par[1] * np.expm1(z)


def S_ARRAY_EXPM1(id, time, par, npar, dflag, iflag):
    p, errflg = py_sysary("TDISP", [int(par[0])])
    return -par[1] * np.expm1(np.array(p))[2]


def S_KEYED(id, time, par, npar, dflag, iflag):
    z = py_sysfnc("DZ", [int(par[0])])[0]
    scale = {z: par[1]}
    return -par[1] * np.expm1(z)


def S_RAISES(id, time, par, npar, dflag, iflag):
    z = py_sysfnc("DZ", [int(par[0])])[0] * np.sin(time)
    raise ValueError("no floor given")


def S_OWN_TYPEERROR(id, time, par, npar, dflag, iflag):
    z = py_sysfnc("DZ", [int(par[0])])[0]
    return len(np.sqrt(z))


def M_NP(id, time, par, npar, iord, iflag):
    return par[0] * np.sin(par[1] * time)


def V_CLIP(id, time, par, npar, dflag, iflag):
    z = py_sysfnc("DZ", [int(par[0])])[0]
    return np.clip(par[1] * (par[2] - z), -2.0, 2.0)
'''


@pytest.fixture
def script(tmp_path):
    path = tmp_path / "subs3.py"
    path.write_text(ROUTINES)
    return path


def _force(function, routine=None, script=None):
    user = f', ROUTINE="{routine}", SCRIPT="{script}"' if routine else ""
    return f'SFORCE(1, I=10, J=1, TRANSLATION=True, FUNCTION="{function}"{user})'


def _run(body):
    return pysolver.loads(SCENE.format(body=body), fmt="py").run()


def _path(res):
    (path,) = res.meta["usersubs"].values()
    assert "Sym" not in path and "Cond" not in path
    return path


def _same(res, ref):
    """The same run: steps, times and the request to 1e-9 (traced: to the bit)."""
    assert res.success and ref.success, res.message
    assert res.stats["steps"] == ref.stats["steps"]
    np.testing.assert_array_equal(res.t, ref.t)
    np.testing.assert_allclose(res.request(1)[:, :2], ref.request(1)[:, :2], rtol=0, atol=1e-9)


@pytest.mark.parametrize("routine, function, expr, traced", [
    ("S_NPSIN_TIME", "USER(2, 3)", "2*SIN(3*TIME)", "(2 * SIN((3 * TIME)))"),
    ("S_NPSQRT", "USER(10, 10)", "-10*SQRT(DZ(10)*DZ(10))", "(-10 * SQRT((DZ(10) * DZ(10))))"),
    ("S_SYSARY", "USER(10, 10)", "-10*SQRT(DX(10)**2 + DY(10)**2 + DZ(10)**2)",
     "(-10 * SQRT((((DX(10) * DX(10)) + (DY(10) * DY(10))) + (DZ(10) * DZ(10)))))"),
])
def test_the_trials_numpy_routines_trace_into_the_expression(script, routine, function, expr,
                                                             traced):
    """np.sin(time), np.sqrt(z * z) and np.linalg.norm of py_sysary's list were refused at
    load (NumPy raised TypeError on the tracer's stand-in): now traced, they are the
    expression version's run, steps and numbers; the float() form, called from the kernel,
    gives the same numbers to 1e-9."""
    ref = _run(_force(expr))
    res = _run(_force(function, routine, script))
    _same(res, ref)
    np.testing.assert_array_equal(res.request(1)[:, :2], ref.request(1)[:, :2])
    assert _path(res) == f"USER({function[5:-1]}) -> {routine} ({script}): traced into the " \
        f"kernel: {traced}"
    if routine != "S_SYSARY":
        called = _run(_force(function, routine.replace("_TIME", "") + "_FLOAT", script))
        assert "Python callback (not traced: float() of a state-dependent value" in \
            _path(called)
        _same(called, ref)


def test_a_numpy_motsub_and_varsub_trace(script):
    """MOTSUB `par[0] * np.sin(par[1] * time)` (trial 43: refused) and a VARSUB through
    np.clip (traced into the branches of its comparisons) give their expressions' runs."""
    joint = ("PART(3, MASS=1, IP=[1, 1, 1], CM=30)\nMARKER(30, PART=3)\nMARKER(31, PART=3)\n"
             "JOINT(1, TYPE=\"TRANSLATIONAL\", I=31, J=1)\n")
    motion = 'MOTION(1, JOINT=1, TYPE="TRANSLATION", FUNCTION="{}"{})'
    ref = _run(joint + motion.format("0.2*SIN(5*TIME)", ""))
    res = _run(joint + motion.format("USER(0.2, 5)", f', ROUTINE="M_NP", SCRIPT="{script}"'))
    _same(res, ref)
    assert _path(res).endswith("traced into the kernel: (0.2 * SIN((5 * TIME)))")
    variable = 'VARIABLE(5, FUNCTION="{}"{})\n' + _force("VARVAL(5)")
    ref = _run(variable.format("MIN(MAX(100*(0.5-DZ(10)), -2), 2)", ""))
    res = _run(variable.format("USER(10, 100, 0.5)", f', ROUTINE="V_CLIP", SCRIPT="{script}"'))
    _same(res, ref)
    assert "traced into the kernel: IF(" in _path(res)


def test_numpy_ufuncs_trace_as_their_expression_functions():
    """Every ufunc the tracer maps, NumPy scalars, an object array's ufunc, np.where and
    np.linalg.norm, against the same expressions, channel by channel (the REQSUB returns its
    channels as a NumPy array)."""
    routine = """import numpy as np
def sub(id, time, par, npar, iflag):
    z = py_sysfnc("DZ", [10])[0] + 2
    v = py_sysfnc("VZ", [10])[0]
    p = py_sysary("TDISP", [10])[0]
    return np.array([np.sin(z) + np.cos(z) + np.tan(z / 20) + np.arcsin(z / 20) + np.arccos(z / 20),
            np.arctan(v) + np.arctan2(v, z) + np.sinh(z / 10) + np.cosh(z / 10) + np.tanh(v),
            np.exp(-z) + np.log(z) + np.log10(z) + np.sqrt(z) + np.abs(v) + np.fabs(v),
            np.power(z, 1.5) + np.square(z) + np.reciprocal(z) + np.hypot(z, v) - np.negative(v),
            np.fmod(z, 0.7) + np.copysign(2.0, v) + np.sign(v) + np.trunc(3 * z),
            np.maximum(z, 2.5) + np.minimum(v, -1.0) + np.fmax(v, 0.0) + np.fmin(z, 3.0),
            np.deg2rad(z) + np.rad2deg(v) + np.float64(2.0) * z + np.int64(3) * v,
            np.linalg.norm(p) + np.sin(np.array([z, v]))[1] + np.where(v < 0, -v, v)])
REQUEST(1, FUNCTION="USER()", ROUTINE=sub)
"""
    z, v = "(DZ(10)+2)", "VZ(10)"
    exprs = [f"SIN({z}) + COS({z}) + TAN({z}/20) + ASIN({z}/20) + ACOS({z}/20)",
             f"ATAN({v}) + ATAN2({v}, {z}) + SINH({z}/10) + COSH({z}/10) + TANH({v})",
             f"EXP(-{z}) + LOG({z}) + LOG10({z}) + SQRT({z}) + 2*ABS({v})",
             f"{z}**1.5 + {z}*{z} + 1/{z} + SQRT({z}**2 + {v}**2) + {v}",
             f"MOD({z}, 0.7) + SIGN(2, {v}) + IF({v}: -1, 0, 1) + AINT(3*{z})",
             f"MAX({z}, 2.5) + MIN({v}, -1) + MAX({v}, 0) + MIN({z}, 3)",
             f"{z}*PI/180 + {v}*180/PI + 2*{z} + 3*{v}",
             f"DM(10) + SIN({v}) + ABS({v})"]
    ball = SCENE.replace("QP=[0, 0, 1]", "QP=[0.3, 0.4, 1]").replace(
        "REQUEST(1, F1=\"DZ(10)\", F2=\"VZ(10)\")\n", "").replace(
        "POINT_MASS(2, MASS=1, CM=10)", "POINT_MASS(2, MASS=1, CM=10)\nACCGRAV(KGRAV=-1.0)")
    ref = pysolver.loads(ball.format(body="REQUEST(1, " + ", ".join(
        f'F{k + 1}="{e}"' for k, e in enumerate(exprs)) + ")"), fmt="py").run()
    res = pysolver.loads(ball.format(body=routine), fmt="py").run()
    assert ref.success and res.success, res.message
    assert "traced into the kernel" in _path(res)
    np.testing.assert_allclose(res.request(1), ref.request(1), rtol=1e-13, atol=1e-12)


@pytest.mark.parametrize("routine, why, reads", [
    ("S_EXPM1", "NumPy's expm1 of a state-dependent value: the expression language has no "
                "such function (line 29)", "DZ(10)"),
    ("S_ARRAY_EXPM1", "TypeError: loop of ufunc does not support argument 0 of type traced "
                      "value which has no callable expm1 method (line 39), raised on traced "
                      "values and not on numbers (time and every value it reads 0): a function "
                      "the tracer cannot follow", "DX(10), DY(10), DZ(10)"),
    ("S_KEYED", "TypeError: unhashable type: 'traced value' (line 44), raised on traced values "
                "and not on numbers (time and every value it reads 0): a function the tracer "
                "cannot follow", "DZ(10)"),
])
def test_numpy_the_tracer_cannot_follow_is_called_from_the_kernel(script, routine, why, reads):
    """A ufunc the expression language lacks, one on an object array of traced values, and a
    traced value as a dict key: the routine is called from the kernel and gives the float()
    form's run (the same numbers: both are called)."""
    ref = _run(_force("USER(10, 10)", "S_EXPM1_FLOAT", script))
    res = _run(_force("USER(10, 10)", routine, script))
    _same(res, ref)
    path = _path(res)
    assert path == (f"USER(10, 10) -> {routine} ({script}): Python callback (not traced: "
                    f"{why}), called from the kernel; its partials in {reads} (not TIME: it never "
                    "reads its time argument) by central differences, except those it gives "
                    "with c_syspar / py_syspar")


@pytest.mark.parametrize("routine, message", [
    ("S_RAISES", "S_RAISES raised ValueError: no floor given (line 50)"),
    ("S_OWN_TYPEERROR", "S_OWN_TYPEERROR raised TypeError: object of type 'numpy.float64' has "
                        "no len() (line 55)"),
])
def test_a_numpy_routine_that_raises_at_every_state_is_a_deck_error(script, routine, message):
    """A routine that raises on no branch of the state is refused when the model is first run,
    as the routine raises it on numbers (its own TypeError too, not taken for the tracer's)."""
    model = pysolver.loads(SCENE.format(body=_force("USER(10, 10)", routine, script)), fmt="py")
    with pytest.raises(pysolver.DeckError) as info:
        model.run()
    assert info.value.reason == message
    assert (info.value.element, info.value.attribute) == ("Force_Scalar_TwoBody", "SCRIPT")
