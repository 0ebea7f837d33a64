"""User subroutines in Python (PFOSUB, SENSUB, SEVSUB, VARSUB, SFOSUB, REQSUB): traced into the
kernel's expressions, they give the expression version's answers, steps and exact Jacobian; and
every bad input is a DeckError that says where."""
import math
import re

import numpy as np
import pytest

import pysolver

from helpers import DECKS, fd_iteration_matrix

# -- seed example 1, the catenary bead: g = DY(9) - COSH(DX(9)) -----------------------------

BEAD_SCRIPT = '''import math


def PFOSUB(id, time, par, npar, dflag, iflag):
    marker = int(par[0])
    [x, errflg] = py_sysfnc("DX", [marker])
    py_errmes(errflg, "DX failed", id, "STOP")
    [y, errflg] = py_sysfnc("DY", [marker])
    return y - math.cosh(x)
'''


def bead_xml(attrs):
    text = (DECKS / "catenary_bead.xml").read_text()
    old = 'type="EXPRESSION"\n                   expr="dy(9) - cosh(dx(9))"'
    assert old in text
    return text.replace(old, attrs)


def bead_py(pfoce):
    text = (DECKS / "catenary_bead.py").read_text()
    old = 'PFORCE(1, LABEL="Particle sliding on a catenary", FUNCTION="DY(9)-COSH(DX(9))",'
    assert old in text
    return text.replace(old, pfoce)


@pytest.fixture
def bead_script(tmp_path):
    path = tmp_path / "bead_sub.py"
    path.write_text(BEAD_SCRIPT)
    return path


def _agree(res, ref, steps_ratio=1.0):
    assert res.success, res.message
    np.testing.assert_array_equal(res.t, ref.t)
    np.testing.assert_allclose(res.request(1)[:, :6], ref.request(1)[:, :6], rtol=0, atol=1e-9)
    assert res.stats["steps"] <= steps_ratio * ref.stats["steps"]


def test_bead_pfosub_in_every_python_form_agrees_with_the_expression(bead_script, tmp_path):
    ref = pysolver.load(DECKS / "catenary_bead.xml").run(integr_tol=1e-10)
    xml = bead_xml(f'type="USERSUB" script_name="{bead_script}" usrsub_param_string="USER(9)"')
    # the script relative to the deck's folder, and the deck as a Python file with a callable
    (tmp_path / "bead.xml").write_text(xml.replace(str(bead_script), "bead_sub.py"))
    routine = BEAD_SCRIPT.replace("def PFOSUB", "def bead")
    pydeck = bead_py(routine + '\nPFORCE(1, FUNCTION="USER(9)", ROUTINE=bead,')
    scripted = bead_py(f'PFORCE(1, FUNCTION="USER(9)", SCRIPT={str(bead_script)!r}, '
                       'INTERPRETER="PYTHON",')
    for model in (pysolver.loads(xml), pysolver.load(tmp_path / "bead.xml"),
                  pysolver.loads(pydeck, fmt="py"), pysolver.loads(scripted, fmt="py")):
        res = model.run(integr_tol=1e-10)
        _agree(res, ref)
        assert res.stats["steps"] == ref.stats["steps"]
        (path,) = res.meta["usersubs"].values()
        assert "traced into the kernel: (DY(9) - COSH(DX(9)))" in path


def test_loading_an_xml_deck_does_not_run_its_script(tmp_path):
    flag = tmp_path / "ran.txt"
    script = tmp_path / "sub.py"
    script.write_text(f"open({str(flag)!r}, 'w').write('ran')\n" + BEAD_SCRIPT)
    model = pysolver.loads(bead_xml(f'type="USERSUB" script_name="{script}" '
                                    'usrsub_param_string="USER(9)"'))
    assert not flag.exists()
    print(model.summary())
    assert not flag.exists()
    assert model.run().success
    assert flag.exists()


def test_traced_jacobian_is_exact(bead_script):
    """The traced routine is an expression: the kernel's iteration matrix matches central
    differences, including the penalty's second-order term."""
    model = pysolver.loads(bead_xml(f'type="USERSUB" script_name="{bead_script}" '
                                    'usrsub_param_string="USER(9)"'))
    k = model.compile().kernel
    rng = np.random.default_rng(3)
    for _ in range(5):
        y = rng.normal(size=k.ny)
        yp = rng.normal(size=k.ny)
        J = k.jacobian_array(0.3, y, yp, 7.0)
        fd = fd_iteration_matrix(k, 0.3, y, yp, 7.0)
        assert np.abs(J - fd).max() <= 1e-6 * max(1.0, np.abs(fd).max())


# -- seed example 3, two lines: one routine for both, the line's slope in USER(...) -----------

LINES_SCRIPT = '''def PFOSUB(id, time, par, npar, dflag, iflag):
    ipar = [int(par[0])]
    x = py_sysfnc("DX", ipar)[0]
    z = py_sysfnc("DZ", ipar)[0]
    return 1 + par[1] * x - z
'''


def test_two_lines_with_one_routine(tmp_path):
    script = tmp_path / "lines.py"
    script.write_text(LINES_SCRIPT)
    text = (DECKS / "particle_between_lines.xml").read_text()
    for k, sign in ((1, "1"), (2, "-1")):
        expr = "1+dx(10)-dz(10)" if k == 1 else "1-dx(10)-dz(10)"
        old = f'type="EXPRESSION" expr="{expr}"'
        assert old in text
        text = text.replace(old, f'type="USERSUB" script_name="{script}" '
                                 f'usrsub_param_string="USER(10, {sign})"')
    ref = pysolver.load(DECKS / "particle_between_lines.xml").run(integr_tol=1e-10)
    res = pysolver.loads(text).run(integr_tol=1e-10)
    assert res.success
    np.testing.assert_allclose(res.request(1)[:, :4], ref.request(1)[:, :4], atol=1e-9)
    assert res.stats["steps"] == ref.stats["steps"]


# -- sensors, evaluates, variables, scalar forces, requests -------------------------------------

BALL = """from pysolver.msolve import *
import math
PART(1, GROUND=True)
MARKER(1, PART=1, QP=[0, 0, -100])
MARKER(10, PART=2, QP=[0, 0, 10])
POINT_MASS(2, MASS=1, CM=10)
ACCGRAV(KGRAV=-9.81)
{body}
INTEGRATOR(ERROR=1e-10)
SIMULATE(TYPE="TRANSIENT", END=2.0, DTOUT=0.05)
"""


BODY_EXPR = """
VARIABLE(5, FUNCTION="2*9.81*SENVAL(7)")
SFORCE(1, I=10, J=1, TRANSLATION=True, FUNCTION="VARVAL(5)")
SENSOR(7, FUNCTION="DZ(10)", OPERATOR="LT", VALUE=5, EVALUATE="1 + 0*DZ(10)")
REQUEST(1, F1="DZ(10)", F2="VZ(10)", F3="VARVAL(5)", F4="SFORCE(1, 0, 1, 0)",
        F5="SQRT(DZ(10)**2 + 1)", F6="ATAN2(VZ(10), 2)", F7="EXP(-TIME)", F8="SENVAL(7)")
"""
BODY_SUB = """
def sensub(id, time, par, npar, iflag):
    return py_sysfnc("DZ", [10])[0]
def sevsub(id, time, par, npar, iflag):
    return 1 + 0 * py_sysfnc("DZ", [10])[0]
def varsub(id, time, par, npar, dflag, iflag):
    return par[0] * 9.81 * py_sysfnc("SENVAL", [7])[0]
def sfosub(id, time, par, npar, dflag, iflag):
    return py_sysfnc("VARVAL", [5])[0]
def reqsub(id, time, par, npar, iflag):
    z, vz = py_sysfnc("DZ", [10])[0], py_sysfnc("VZ", [10])[0]
    return [z, vz, py_sysfnc("VARVAL", [5])[0], py_sysfnc("SFORCE", [1, 0, 1, 0])[0],
            math.sqrt(z ** 2 + 1), math.atan2(vz, 2), math.exp(-time), py_sysfnc("SENVAL", [7])[0]]
VARIABLE(5, FUNCTION="USER(2)", ROUTINE=varsub)
SFORCE(1, I=10, J=1, TRANSLATION=True, FUNCTION="USER()", ROUTINE=sfosub)
SENSOR(7, FUNCTION="USER()", ROUTINE=sensub, OPERATOR="LT", VALUE=5,
       EVALUATE="USER()", EVALUATE_ROUTINE=sevsub)
REQUEST(1, FUNCTION="USER()", ROUTINE=reqsub)
"""


def test_sensor_evaluate_variable_sforce_and_request_routines_match_expressions():
    """One deck written twice, with expressions and with Python routines: same events, same
    stored value, same force and the same eight request channels."""
    ref = pysolver.loads(BALL.format(body=BODY_EXPR), fmt="py").run()
    res = pysolver.loads(BALL.format(body=BODY_SUB), fmt="py").run()
    assert ref.success and res.success
    assert [e.time for e in res.events] == [e.time for e in ref.events]
    assert res.events[0].time == pytest.approx(math.sqrt(10 / 9.81), abs=1e-9)
    np.testing.assert_allclose(res.request(1), ref.request(1), rtol=0, atol=1e-9)
    assert res.stats["steps"] == ref.stats["steps"]
    assert len(res.meta["usersubs"]) == 5


def test_math_functions_are_traced():
    """Every math function the tracer maps, against the same expression."""
    routine = """
def sub(id, time, par, npar, iflag):
    z = py_sysfnc("DZ", [10])[0]
    v = py_sysfnc("VZ", [10])[0]
    return [math.sin(z) + math.cos(z) + math.tan(z / 20), math.asin(z / 20) + math.acos(z / 20),
            math.atan(v) + math.atan2(v, z), math.sinh(z / 10) + math.cosh(z / 10) + math.tanh(v),
            math.exp(-z) + math.log(z) + math.log10(z) + math.log(z, 2),
            math.sqrt(z) + math.fabs(v) + abs(v) + math.pow(z, 1.5) + z ** 2,
            math.hypot(z, v) + math.fmod(z, 3.0) + math.copysign(2.0, v),
            -z / 2 + 3 - z * 0.5 + 1 / z + 2 ** z]
REQUEST(1, FUNCTION="USER()", ROUTINE=sub)
"""
    exprs = ["SIN(DZ(10)) + COS(DZ(10)) + TAN(DZ(10)/20)", "ASIN(DZ(10)/20) + ACOS(DZ(10)/20)",
             "ATAN(VZ(10)) + ATAN2(VZ(10), DZ(10))",
             "SINH(DZ(10)/10) + COSH(DZ(10)/10) + TANH(VZ(10))",
             "EXP(-DZ(10)) + LOG(DZ(10)) + LOG10(DZ(10)) + LOG(DZ(10))/LOG(2)",
             "SQRT(DZ(10)) + 2*ABS(VZ(10)) + DZ(10)**1.5 + DZ(10)**2",
             "SQRT(DZ(10)**2 + VZ(10)**2) + MOD(DZ(10), 3) + SIGN(2, VZ(10))",
             "-DZ(10)/2 + 3 - DZ(10)*0.5 + 1/DZ(10) + 2**DZ(10)"]
    expr_body = "REQUEST(1, " + ", ".join(f'F{k + 1}="{e}"' for k, e in enumerate(exprs)) + ")"
    deck = BALL.replace("END=2.0", "END=1.2")
    ref = pysolver.loads(deck.format(body=expr_body), fmt="py").run()
    res = pysolver.loads(deck.format(body=routine), fmt="py").run()
    assert ref.success and res.success
    np.testing.assert_allclose(res.request(1), ref.request(1), rtol=1e-13, atol=1e-12)


# -- bad input ----------------------------------------------------------------------------------

def _deck_with(tmp_path, script_text, attrs=""):
    script = tmp_path / "s.py"
    script.write_text(script_text)
    return bead_xml(f'type="USERSUB" script_name="{script}" usrsub_param_string="USER(9)" '
                    + attrs)


@pytest.mark.parametrize("script,attrs,attribute,match", [
    (BEAD_SCRIPT, 'usrsub_fnc_name="NOPE"', "usrsub_fnc_name", "defines no function NOPE"),
    ("def PFOSUB(id, time, par):\n    return 0\n", "", "usrsub_fnc_name",
     "takes 3 arguments; expected 6: id, time, par, npar, dflag, iflag"),
    ("def PFOSUB(id, time, par, npar, dflag, iflag)\n", "", "script_name", "cannot read script"),
    (BEAD_SCRIPT, 'interpreter="MATLAB"', "interpreter", "MATLAB user subroutines"),
])
def test_bad_scripts_are_deck_errors_at_load(tmp_path, script, attrs, attribute, match):
    with pytest.raises(pysolver.DeckError, match=match) as info:
        pysolver.loads(_deck_with(tmp_path, script, attrs), file=str(tmp_path / "d.xml"))
    err = info.value
    assert (err.element, err.id, err.attribute) == ("Force_Penalty", 1, attribute)
    assert err.line == 12 and err.file.endswith("d.xml")


@pytest.mark.parametrize("attrs,attribute,match", [
    ('type="USERSUB" script_name="missing.py"', "script_name", "script 'missing.py' not found"),
    ('type="USERSUB" usrsub_dll_name="sub.so"', "usrsub_dll_name", "library 'sub.so' not found"),
    ('type="USERSUB" usrsub_dll_name="sub.so" script_name="a.py"', "usrsub_dll_name",
     "not both"),
    ('type="USERSUB" usrsub_param_string="USER(9)"', "script_name", "needs the routine"),
    ('type="USERSUB" usrsub_param_string="USER(9, x)" script_name="a.py"', "usrsub_param_string",
     "parameter 'x' is not a number"),
    ('type="EXPRESSION" expr="USER(9)"', "expr", r"USER\(\.\.\.\) calls a user subroutine"),
    ('expr="DZ(9)" script_name="a.py"', "script_name", "only with type=\"USERSUB\""),
])
def test_bad_usersub_attributes(attrs, attribute, match):
    with pytest.raises(pysolver.DeckError, match=match) as info:
        pysolver.loads(bead_xml(attrs))
    assert (info.value.element, info.value.attribute) == ("Force_Penalty", attribute)


@pytest.mark.parametrize("body,match", [
    ("    return py_sysfnc('DQ', [9])[0]\n", "unknown function 'DQ'"),
    ("    return py_sysfnc('DX', [99])[0]\n", "refers to marker id 99, which does not exist"),
    ("    return py_sysfnc('VX', [9])[0]\n", "displacement measures only"),
    ("    raise ValueError('bad day')\n", r"PFOSUB raised ValueError: bad day \(line 5\)"),
    ("    return 'tall'\n", "PFOSUB returned 'tall'"),
    ("    return None\n", "PFOSUB returned None"),
    ("    return float('nan')\n", "returned nan"),
    ("    py_errmes(1, 'cannot go on', id, 'STOP')\n", r"cannot go on \(id 1\)"),
])
def test_bad_routines_are_deck_errors_when_traced(tmp_path, body, match):
    """A script runs when the model is first run: its problems are DeckErrors then, naming
    the element and the script attribute, and nothing runs."""
    head = "import math\n\n\ndef PFOSUB(id, time, par, npar, dflag, iflag):\n"
    model = pysolver.loads(_deck_with(tmp_path, head + body))
    with pytest.raises(pysolver.DeckError, match=match) as info:
        model.run()
    assert (info.value.element, info.value.id, info.value.attribute) == \
        ("Force_Penalty", 1, "script_name")


def test_py_sysfnc_outside_a_routine():
    from pysolver.msolve import py_sysfnc
    with pytest.raises(RuntimeError, match="only inside a user subroutine"):
        py_sysfnc("DX", [9])


# -- routines the kernel calls: untraceable Python (a cffi callback) and C libraries ----------

def _reference_error(text, tol=1e-10):
    """The expression version at `tol` and at 1e-12: its result and its own global error at
    `tol`, the largest over five tolerances within 1e-4 of it. One run's error is a matter of
    its step sequence, which rounding changes: on the bead at 1e-10 the expression's ran from
    1.0e-8 to 3.7e-8 and the C routine's from 0.9e-8 to 5.3e-8 over such tolerances, with
    either dense solver (stop 41)."""
    model = pysolver.loads(text) if text.lstrip().startswith("<") else pysolver.load(text)
    ref, fine = model.run(integr_tol=tol), model.run(integr_tol=1e-12)
    near = [model.run(integr_tol=tol * (1 + d)) for d in (-1e-4, -5e-5, 5e-5, 1e-4)]
    return ref, fine, max(np.abs(r.request(1)[:, :4] - fine.request(1)[:, :4]).max()
                          for r in [ref, *near])


def _close_to_expression(res, ref, fine, err):
    """A differenced path takes its own steps, so it is checked against the expression
    version's own global error: within 3x of it from the converged solution, in at most 1.2x
    the steps."""
    assert res.success, res.message
    np.testing.assert_allclose(res.t, ref.t, rtol=0, atol=1e-9)
    assert np.abs(res.request(1)[:, :4] - fine.request(1)[:, :4]).max() <= 3 * err + 1e-12
    assert res.stats["steps"] <= 1.2 * ref.stats["steps"]


BRANCHY = '''import math


def PFOSUB(id, time, par, npar, dflag, iflag):
    x = py_sysfnc("DX", [9])[0]
    y = py_sysfnc("DY", [9])[0]
    if iflag:
        return 0.0
    ch = math.cosh(x)        # the same g, through a state-dependent branch
    return y - ch if x >= 0 else y - math.cosh(-x)
'''

#: The same g through NumPy: a conversion to float, which cannot be traced.
UNTRACEABLE = '''import numpy as np


def PFOSUB(id, time, par, npar, dflag, iflag):
    x, y = np.array([py_sysfnc("DX", [9])[0], py_sysfnc("DY", [9])[0]], dtype=float)
    if x < 0.0:
        return float(y - np.cosh(-x))
    return float(y - np.cosh(x))
'''


def test_branches_on_the_state_are_traced_into_if(tmp_path):
    """Both paths of the branch are traced and joined into IF(DX(9): ...): the expression
    version's answers and steps."""
    ref = pysolver.load(DECKS / "catenary_bead.xml").run(integr_tol=1e-10)
    res = pysolver.loads(_deck_with(tmp_path, BRANCHY)).run(integr_tol=1e-10)
    _agree(res, ref)
    assert res.stats["steps"] == ref.stats["steps"]
    (path,) = res.meta["usersubs"].values()
    assert "traced into the kernel: IF(DX(9): (DY(9) - COSH(-(DX(9)))), (DY(9) - COSH(DX(9)))," \
        in path


def test_branch_tracing_joins_nested_branches_min_max_and_conditions_as_numbers():
    """Nested branches, min/max, chained comparisons and a comparison used as 0/1 trace into
    nested IFs that give the routine's own values at random states and on the boundaries."""
    from pysolver.deck import tracer

    def routine(x, y):
        if x > 1.0:
            v = max(x, y) if y != 2.0 else 7.0
        elif 0 <= y < 1:
            v = min(x * y, 0.5) + (x <= y) * 3.0
        else:
            v = -abs(x) if x else 2.0 * y
        return v

    sx, sy = (tracer.Sym(("call", name, [("num", 9.0)], 0)) for name in ("DX", "DY"))
    leaves = tracer.explore(lambda: tracer.tree_of(routine(sx, sy)))
    assert len(leaves) == 9
    tree = tracer.join(leaves)
    rng = np.random.default_rng(4)
    points = [(x, y) for x, y in rng.uniform(-2, 3, size=(200, 2))]
    points += [(0.0, 2.0), (2.0, 2.0), (0.5, 0.5), (0.5, 0.0), (1.0, 1.0)]
    for x, y in points:
        got = _eval_tree(tree, {"DX": x, "DY": y})
        assert got == routine(x, y), (x, y)


def _eval_tree(node, values):
    """Evaluate a traced tree at given DX/DY (only the node kinds the test above produces)."""
    kind = node[0]
    if kind == "num":
        return node[1]
    if kind == "neg":
        return -_eval_tree(node[1], values)
    if kind == "bin":
        a, b = _eval_tree(node[2], values), _eval_tree(node[3], values)
        return {"+": a + b, "-": a - b, "*": a * b, "/": a / b if b else math.nan}[node[1]]
    name, args = node[1], node[2]
    if name in values:
        return values[name]
    if name == "ABS":
        return abs(_eval_tree(args[0], values))
    assert name == "IF", name
    d = _eval_tree(args[0], values)
    return _eval_tree(args[1 if d < 0 else 2 if d == 0 else 3], values)


def test_untraceable_python_routine_is_called_from_the_kernel(tmp_path):
    ref, fine, err = _reference_error(str(DECKS / "catenary_bead.xml"))
    model = pysolver.loads(_deck_with(tmp_path, UNTRACEABLE))
    res = model.run(integr_tol=1e-10)
    _close_to_expression(res, ref, fine, err)
    (path,) = res.meta["usersubs"].values()
    assert "Python callback (not traced: float() of a state-dependent value" in path
    assert path.endswith("partials in DX(9), DY(9) (not TIME: it never reads its time "
                         "argument) by central differences, except those it gives with "
                         "c_syspar / py_syspar")


#: UNTRACEABLE on a catenary that sinks with time: y = cosh(x) - 0.5 t (a routine that reads
#: its time argument, so the kernel differences it in time too).
SINKING = UNTRACEABLE.replace("return float(y - np.cosh(-x))",
                              "return float(y - np.cosh(-x) + 0.5 * time)").replace(
    "return float(y - np.cosh(x))", "return float(y - np.cosh(x) + 0.5 * time)")


def test_a_routine_reading_time_is_differenced_in_time(tmp_path):
    """The sinking catenary as a routine the kernel calls gives its expression's answers (the
    penalty's rate needs dg/dt = 0.5: without it the damping would act on the wrong rate)."""
    text = (DECKS / "catenary_bead.xml").read_text().replace(
        'expr="dy(9) - cosh(dx(9))"', 'expr="dy(9) - cosh(dx(9)) + 0.5 * time"')
    ref, fine, err = _reference_error(text)
    res = pysolver.loads(_deck_with(tmp_path, SINKING)).run(integr_tol=1e-10)
    _close_to_expression(res, ref, fine, err)
    (path,) = res.meta["usersubs"].values()
    assert "partials in DX(9), DY(9), TIME by central differences" in path
    assert "never reads" not in path


def _f_plain(id, time, par, npar, dflag, iflag):
    return par[0]


def _f_reads(id, time, par, npar, dflag, iflag):
    return par[0] + time


def _f_deleted(id, time, par, npar, dflag, iflag):
    del time
    return par[0]


def _f_captured(id, time, par, npar, dflag, iflag):
    return (lambda: time)()


def _f_comprehension(id, time, par, npar, dflag, iflag):
    return sum([time * p for p in par])


def _f_locals(id, time, par, npar, dflag, iflag):
    return locals()["t" + "ime"]


def _f_eval(id, time, par, npar, dflag, iflag):
    return eval("time")


def _f_args(*args):
    return args[1]


class _Callable:
    def __call__(self, id, time, par, npar, dflag, iflag):
        return 0.0


@pytest.mark.parametrize("fn,reads", [
    (_f_plain, False), (_f_deleted, False), (_f_reads, True), (_f_captured, True),
    (_f_comprehension, True), (_f_locals, True), (_f_eval, True), (_f_args, True),
    (_Callable(), True), (_Callable().__call__, True), (lambda id, t, *rest: 0.0, False),
    (lambda id, t, *rest: t, True), (math.hypot, True)])
def test_reads_time_is_false_only_for_code_that_never_loads_it(fn, reads):
    """Whether a Python routine may read its time argument, from its bytecode: any doubt
    (introspection, a closure, a callable that is not a plain function) counts as a read."""
    from pysolver.build.usercalls import reads_time
    assert reads_time(fn) is reads


def _jacobian_like_the_expression(model, seed):
    """A differenced path's iteration matrix against the exact one of the expression version
    (1e-6 relative; measured 4e-8) and against central differences of its own residual (1e-5:
    those difference the routine's differenced partials once more)."""
    k, exact = model.compile().kernel, pysolver.load(DECKS / "catenary_bead.xml").compile().kernel
    rng = np.random.default_rng(seed)
    for _ in range(3):
        y, yp = rng.normal(size=k.ny), rng.normal(size=k.ny)
        J = k.jacobian_array(0.3, y, yp, 7.0)
        Je, fd = exact.jacobian_array(0.3, y, yp, 7.0), fd_iteration_matrix(k, 0.3, y, yp, 7.0)
        assert np.abs(J - Je).max() <= 1e-6 * np.abs(Je).max()
        assert np.abs(J - fd).max() <= 1e-5 * np.abs(fd).max()


def test_callback_jacobian_matches_the_exact_one(tmp_path):
    _jacobian_like_the_expression(pysolver.loads(_deck_with(tmp_path, UNTRACEABLE)), 5)


@pytest.mark.parametrize("reads_time", [False, True])
def test_jacobian_reuses_the_residuals_partials_only_at_the_same_state(tmp_path, reads_time):
    """After a residual at the same state the Jacobian reuses the routine's value and first
    partials (bit for bit the matrix it computes alone) and calls it only for second
    differences: 2 per input it reads (DX, DY) and 2 for the pair, 6 in all; alone it also
    makes the 9 first-order calls (value, +/- h and +/- 2h in DX and in DY: fourth-order
    differences), and one step in time (flat: 0 * time) when the routine reads its time
    argument. At another state nothing is reused."""
    counted = UNTRACEABLE.replace("def PFOSUB(id, time, par, npar, dflag, iflag):\n",
                                  "CALLS = []\n\n\ndef PFOSUB(id, time, par, npar, dflag, "
                                  "iflag):\n    CALLS.append(iflag)\n")
    if reads_time:
        counted = counted.replace("    CALLS.append(iflag)\n",
                                  "    CALLS.append(iflag + 0.0 * time)\n")
    model = pysolver.loads(_deck_with(tmp_path, counted))
    k = model.compile().kernel
    calls = next(iter(model.compile().model._scripts.values()))["CALLS"]
    rng = np.random.default_rng(8)
    ya, ypa, yb, ypb = (rng.normal(size=k.ny) for _ in range(4))
    first = 10 if reads_time else 9
    k.reset_counters()
    del calls[:]
    alone = k.jacobian_array(0.3, ya, ypa, 7.0)
    assert len(calls) == first + 6
    k.reset_counters()
    k.residual_array(0.3, ya, ypa)
    assert len(calls) == 2 * first + 6
    np.testing.assert_array_equal(k.jacobian_array(0.3, ya, ypa, 7.0), alone)
    assert len(calls) == 2 * first + 12
    k.residual_array(0.3, yb, ypb)
    np.testing.assert_array_equal(k.jacobian_array(0.3, ya, ypa, 7.0), alone)
    assert len(calls) == 4 * first + 18


def test_a_routine_failing_during_the_run_ends_it_with_its_message(tmp_path):
    """The routine raises once the bead has slid left of x = 0.3: success=False, the message
    names the routine and the error, and the rows up to then are kept."""
    script = BRANCHY.replace("    ch = math.cosh(x)", "    if x < 0.3:\n        raise ValueError('off the end')\n    ch = math.cosh(x)")
    res = pysolver.loads(_deck_with(tmp_path, script)).run()
    assert not res.success and res.status == -400
    assert "PFOSUB raised ValueError: off the end" in res.message
    assert len(res.t) > 1 and np.all(res.request(1)[:, 0] >= 0.3 - 1e-3)


C_BEAD = r"""
#include <math.h>
#include "pysolver_usersub.h"

void PFOSUB(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
            double *value) {
  int marker = (int)par[0], err;
  double x, y;
  c_sysfnc("DX", &marker, 1, &x, &err);
  c_errmes(err, "DX failed", *id, "STOP");
  c_sysfnc("DY", &marker, 1, &y, &err);
  *value = y - cosh(x);
}

void LINES(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
           double *value) {
  int m = (int)par[0], err;
  double p[3];
  int n;
  c_sysary("TDISP", &m, 1, p, &n, &err);
  *value = 1.0 + par[1] * p[0] - p[2];
}

void SENSUB(int *id, double *time, double *par, int *npar, int *iflag, double *value) {
  int m = 10, err;
  c_sysfnc("DZ", &m, 1, value, &err);
}

void GREEDY(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
            double *value) {
  int m = 9, err;
  double x, y = 0;
  c_sysfnc("DX", &m, 1, &x, &err);
  if (!*iflag) c_sysfnc("DY", &m, 1, &y, &err);   /* not declared on the iflag call */
  *value = y - cosh(x);
}
"""


@pytest.fixture(scope="module")
def c_library(tmp_path_factory):
    import shutil
    import subprocess
    cc = shutil.which("cc") or shutil.which("gcc")
    if cc is None:
        pytest.skip("no C compiler on this machine to build the test's subroutine library")
    d = tmp_path_factory.mktemp("csub")
    (d / "subs.c").write_text(C_BEAD)
    subprocess.run([cc, "-shared", "-fPIC", f"-I{pysolver.get_include()}", str(d / "subs.c"),
                    "-o", str(d / "subs.so"), "-lm"], check=True)
    return d / "subs.so"


def test_c_pfosub_on_the_bead(c_library):
    ref, fine, err = _reference_error(str(DECKS / "catenary_bead.xml"))
    model = pysolver.loads(bead_xml(f'type="USERSUB" usrsub_dll_name="{c_library}" '
                                    'usrsub_param_string="USER(9)"'))
    res = model.run(integr_tol=1e-10)
    _close_to_expression(res, ref, fine, err)
    _jacobian_like_the_expression(model, 2)


def test_c_routines_on_the_two_lines_and_a_sensor(c_library, tmp_path):
    """Seed example 3 with one C routine for both lines (c_sysary TDISP), and a C SENSUB
    halting the run when the particle drops below z = 50 mm."""
    text = (DECKS / "particle_between_lines.xml").read_text()
    sensor = '<Sensor_Event id="1" expr="DZ(10)" compare="LT" value="50" halt="TRUE"/>'
    with_sensor = text.replace("</Model>", sensor + "\n  </Model>")
    ref, fine, err = _reference_error(with_sensor)
    for k, sign in ((1, "1"), (2, "-1")):
        expr = "1+dx(10)-dz(10)" if k == 1 else "1-dx(10)-dz(10)"
        with_sensor = with_sensor.replace(
            f'type="EXPRESSION" expr="{expr}"',
            f'type="USERSUB" usrsub_dll_name="{c_library}" usrsub_fnc_name="LINES" '
            f'usrsub_param_string="USER(10, {sign})"')
    with_sensor = with_sensor.replace(
        sensor, f'<Sensor_Event id="1" type="USERSUB" usrsub_dll_name="{c_library}" '
                'compare="LT" value="50" halt="TRUE"/>')
    res = pysolver.loads(with_sensor).run(integr_tol=1e-10)
    assert res.success and "halted by Sensor_Event 1" in res.message
    assert res.events[0].time == pytest.approx(ref.events[0].time, abs=1e-8)
    _close_to_expression(res, ref, fine, err)


def test_c_library_errors(c_library, tmp_path):
    """A missing function and a file that is no library are DeckErrors at load (the symbol
    table is read, the library not loaded); a routine reading undeclared values fails the run."""
    with pytest.raises(pysolver.DeckError, match="exports no function NOPE \\(it exports: "
                       "GREEDY, LINES, PFOSUB, SENSUB\\)") as info:
        pysolver.loads(bead_xml(f'type="USERSUB" usrsub_dll_name="{c_library}" '
                                'usrsub_fnc_name="NOPE" usrsub_param_string="USER(9)"'))
    assert info.value.attribute == "usrsub_fnc_name" and info.value.id == 1
    (tmp_path / "fake.so").write_text("not a library")
    with pytest.raises(pysolver.DeckError, match="fake.so is not a shared library") as info:
        pysolver.loads(bead_xml(f'type="USERSUB" usrsub_dll_name="{tmp_path / "fake.so"}" '
                                'usrsub_param_string="USER(9)"'))
    assert info.value.attribute == "usrsub_dll_name"
    greedy = pysolver.loads(bead_xml(f'type="USERSUB" usrsub_dll_name="{c_library}" '
                                     'usrsub_fnc_name="GREEDY" usrsub_param_string="USER(9)"'))
    res = greedy.run()
    assert not res.success
    assert "read a value its iflag call did not ask for: DY(9)" in res.message
    assert "0 rows" in res.summary()


# -- seed example 3 in every form ---------------------------------------------------------------

@pytest.mark.parametrize("form", ["script", "callable", "branchy", "untraceable",
                                  "untraceable_syspar", "c", "c_syspar"])
def test_two_lines_in_every_form(tmp_path, form):
    """Seed example 3 with both penalties as user subroutines (tests/scenes.py): traced
    forms give the expression version's answers and steps; the forms the kernel calls stay
    within 3x the expression version's own global error, in at most 1.2x its steps."""
    from scenes import lines_deck
    text, fmt = lines_deck(form, tmp_path)
    if text is None:
        pytest.skip("no C compiler on this machine to build the subroutine library")
    expr_text, _ = lines_deck("expression", tmp_path)
    expr_model = pysolver.loads(expr_text, fmt="py")
    ref, fine = expr_model.run(integr_tol=1e-10), expr_model.run(integr_tol=1e-12)
    err = np.abs(ref.request(1)[:, :4] - fine.request(1)[:, :4]).max()
    res = pysolver.loads(text, fmt=fmt).run(integr_tol=1e-10)
    paths = list(res.meta["usersubs"].values())
    assert len(paths) == 2
    if form in ("script", "callable", "branchy"):
        assert all("traced into the kernel" in p for p in paths)
        np.testing.assert_allclose(res.request(1)[:, :4], ref.request(1)[:, :4], atol=1e-9)
        assert res.stats["steps"] == ref.stats["steps"]
    else:
        assert all("called from the kernel" in p for p in paths)
        _close_to_expression(res, ref, fine, err)


def test_every_routine_kind_through_the_kernel_call_path():
    """The sensor deck above with every routine made untraceable (a float() conversion of the
    state in a test that is always false): SENSUB, SEVSUB, VARSUB, SFOSUB and REQSUB are then called from the
    kernel, and give the expression version's events and channels to its own accuracy."""
    guard = '    if float(py_sysfnc("DZ", [10])[0]) < -1e30:\n        return 0.0\n'
    body = BODY_SUB
    lines = []
    for line in body.splitlines():
        lines.append(line)
        if line.startswith("def "):
            lines.append(guard.rstrip("\n").replace("return 0.0", "return [0.0] * 8"
                                                    if "reqsub" in line else "return 0.0"))
    text = BALL.format(body="\n".join(lines))
    ref = pysolver.loads(BALL.format(body=BODY_EXPR), fmt="py").run()
    model = pysolver.loads(text, fmt="py")
    res = model.run()
    assert res.success, res.message
    paths = res.meta["usersubs"]
    assert len(paths) == 5 and all("Python callback" in p for p in paths.values())
    assert res.events[0].time == pytest.approx(ref.events[0].time, abs=1e-8)
    np.testing.assert_allclose(res.request(1), ref.request(1), rtol=0, atol=1e-6)


@pytest.mark.parametrize("looped", [False, True], ids=["straight", "looped"])
def test_kernel_called_routines_run_in_generated_c(tmp_path, looped, monkeypatch):
    """A scene whose routines the kernel calls is generated like any other (issue 27): the
    generated residual calls each routine through the kernel (ps_user_point) and chains its
    differenced partials with the exact derivatives of what it read. Every routine kind as
    an untraceable Python callback (SENSUB, SEVSUB, VARSUB, SFOSUB, REQSUB) and C PFOSUBs
    agree with the tapes to rounding at random states, in straight-line and looped C, and
    their runs take the tapes' steps."""
    from test_codegen import _agree

    from pysolver.build import codegen
    monkeypatch.setattr(codegen, "STRAIGHT", 0 if looped else 10 ** 9)
    guard = '    if float(py_sysfnc("DZ", [10])[0]) < -1e30:\n        return 0.0\n'
    lines = []
    for line in BODY_SUB.splitlines():
        lines.append(line)
        if line.startswith("def "):
            lines.append(guard.rstrip("\n").replace("return 0.0", "return [0.0] * 8"
                                                    if "reqsub" in line else "return 0.0"))
    from scenes import lines_deck
    c_text, _ = lines_deck("c", tmp_path)
    if c_text is None:
        pytest.skip("no C compiler on this machine to build the subroutine library")
    for text, fmt in ((BALL.format(body="\n".join(lines)), "py"), (c_text, "py")):
        model = pysolver.loads(text, fmt=fmt)
        gen, tape = model.compile("generated").kernel, model.compile("tapes").kernel
        assert gen.codegen["kernel"] == "generated", gen.codegen
        assert codegen.is_looped(gen) == looped
        assert tape.arrays["nuser"] > 0
        _agree(gen, tape)
        a, b = model.run(), model.run(kernel="tapes")
        assert a.meta["kernel"] == "generated" and b.meta["kernel"] == "tapes"
        assert a.success and b.success and a.stats["steps"] == b.stats["steps"]


# -- partials a routine gives (c_syspar / py_syspar, Adams' SYSPAR) ----------------------------

C_SYSPAR = r"""
#include <math.h>
#include "pysolver_usersub.h"

static long counts[3];   /* calls; calls that were asked for partials; calls that were not */
long count(int i) { return counts[i]; }

static void lines(double *par, double *value, int give, double kink) {
  int m = (int)par[0], n, err, asked;
  double p[3];
  c_adams_needs_partials(&asked);
  counts[0]++;
  counts[asked ? 1 : 2]++;
  c_sysary("TDISP", &m, 1, p, &n, &err);
  *value = 1.0 + par[1] * p[0] - p[2] + kink * fabs(p[0] - 100.0);
  double dg[3] = {par[1] + kink * (p[0] >= 100.0 ? 1.0 : -1.0), 0.0, -1.0};
  if (give > 1 || (give == 1 && asked)) c_syspar("TDISP", &m, 1, dg, 3, &err);
}

void ALWAYS(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
            double *value) { lines(par, value, 2, 0.0); }
void ASKED(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
           double *value) { lines(par, value, 1, 0.0); }
void NEVER(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
           double *value) { lines(par, value, 0, 0.0); }
void KINK(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
          double *value) { lines(par, value, 2, 0.1); }

void WRONG(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
           double *value) {
  int m = (int)par[0], err;
  double x, z, dx = 1.0;   /* right for line 1 only */
  c_sysfnc("DX", &m, 1, &x, &err);
  c_sysfnc("DZ", &m, 1, &z, &err);
  *value = 1.0 + par[1] * x - z;
  c_syspar("DX", &m, 1, &dx, 1, &err);
}

void UNASKED(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
             double *value) {
  int m = (int)par[0], err;
  double x, z, d = 0.0;
  c_sysfnc("DX", &m, 1, &x, &err);
  c_sysfnc("DZ", &m, 1, &z, &err);
  *value = 1.0 + par[1] * x - z;
  c_syspar("DY", &m, 1, &d, 1, &err);
}

void SHORT(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
           double *value) {
  int m = (int)par[0], n, err;
  double p[3], d[2] = {par[1], 0.0};
  c_sysary("TDISP", &m, 1, p, &n, &err);
  *value = 1.0 + par[1] * p[0] - p[2];
  c_syspar("TDISP", &m, 1, d, 2, &err);
}

/* lines(par, value, 2, 0) with the partial in DX a little off (2 %); the value and partials
 * scaled to 1e-12, or to 1e-2 on top of 1e6, with the partial in DX twice what it is */
/* offset + scale g, giving the partial in DX times dx_factor */
static void scaled(double *par, double *value, double scale, double offset, double dx_factor) {
  int m = (int)par[0], n, err;
  double p[3];
  c_sysary("TDISP", &m, 1, p, &n, &err);
  *value = offset + scale * (1.0 + par[1] * p[0] - p[2]);
  double dg[3] = {dx_factor * scale * par[1], 0.0, -scale};
  c_syspar("TDISP", &m, 1, dg, 3, &err);
}
void NEAR(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
          double *value) { scaled(par, value, 1.0, 0.0, 1.02); }
void TINY(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
          double *value) { scaled(par, value, 1e-12, 0.0, 2.0); }
void OFFSET(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
            double *value) { scaled(par, value, 1e-2, 1e6, 2.0); }

/* the partial in DX always; the one in DZ, 10 % off, only once x < 50 */
void LATE(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
          double *value) {
  int m = (int)par[0], err;
  double x, z, dx = par[1], dz = -1.1;
  c_sysfnc("DX", &m, 1, &x, &err);
  c_sysfnc("DZ", &m, 1, &z, &err);
  *value = 1.0 + par[1] * x - z;
  c_syspar("DX", &m, 1, &dx, 1, &err);
  if (x < 50.0) c_syspar("DZ", &m, 1, &dz, 1, &err);
}

/* g = z - c(x), its partials given: USER(marker, 0, a, L) c = a cos(x / L); USER(marker, 1,
 * a, x0) c = a / (x - x0); USER(marker, 2, a, x0) c = a max(0, x0 - x)^2 (a contact);
 * USER(marker, 3, r) c = sqrt(r^2 - x^2) (a circle, not defined past x = r) */
void CURVE(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
           double *value) {
  int m = (int)par[0], err, kind = (int)par[1];
  double x, z, c, dc, one = 1.0;
  c_sysfnc("DX", &m, 1, &x, &err);
  c_sysfnc("DZ", &m, 1, &z, &err);
  if (kind == 0) {
    c = par[2] * cos(x / par[3]);
    dc = -par[2] / par[3] * sin(x / par[3]);
  } else if (kind == 1) {
    c = par[2] / (x - par[3]);
    dc = -c / (x - par[3]);
  } else if (kind == 2) {
    c = par[2] * fmax(0.0, par[3] - x) * fmax(0.0, par[3] - x);
    dc = -2.0 * par[2] * fmax(0.0, par[3] - x);
  } else {
    c = sqrt(par[2] * par[2] - x * x);
    dc = -x / c;
  }
  *value = z - c;
  dc = -dc;
  c_syspar("DX", &m, 1, &dc, 1, &err);
  c_syspar("DZ", &m, 1, &one, 1, &err);
}

/* the lines moving up at par[2] mm/s (g = 1 + par[1] x - z + par[2] t), the partial in time
 * given as par[2] times par[3] (1: right, 0: wrong); TIMEIDS names an id with TIME */
static long moving_counts[1];
long moving_count(void) { return moving_counts[0]; }
void MOVING(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
            double *value) {
  int m = (int)par[0], n, err;
  double p[3], dt = par[2] * par[3];
  moving_counts[0]++;
  c_sysary("TDISP", &m, 1, p, &n, &err);
  *value = 1.0 + par[1] * p[0] - p[2] + par[2] * *time;
  double dg[3] = {par[1], 0.0, -1.0};
  c_syspar("TDISP", &m, 1, dg, 3, &err);
  c_syspar("TIME", NULL, 0, &dt, 1, &err);
}
void TIMEIDS(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
             double *value) {
  int m = (int)par[0], n, err;
  double p[3], dt = 0.0;
  c_sysary("TDISP", &m, 1, p, &n, &err);
  *value = 1.0 + par[1] * p[0] - p[2];
  c_syspar("TIME", &m, 1, &dt, 1, &err);
}

/* a wave: g = z - a cos(x / L - w t), USER(marker, a, L, w), every partial given (time's too) */
void WAVE(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
          double *value) {
  int m = (int)par[0], err;
  double x, z, one = -1.0, u, dx, dt;
  c_sysfnc("DX", &m, 1, &x, &err);
  c_sysfnc("DZ", &m, 1, &z, &err);
  u = x / par[2] - par[3] * *time;
  *value = par[1] * cos(u) - z;
  dx = -par[1] / par[2] * sin(u);
  dt = par[1] * par[3] * sin(u);
  c_syspar("DX", &m, 1, &dx, 1, &err);
  c_syspar("DZ", &m, 1, &one, 1, &err);
  c_syspar("TIME", NULL, 0, &dt, 1, &err);
}

void BEAD(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
          double *value) {
  int marker = (int)par[0], err;
  double x, y, dx, dy = 1.0;
  c_sysfnc("DX", &marker, 1, &x, &err);
  c_sysfnc("DY", &marker, 1, &y, &err);
  *value = y - cosh(x);
  dx = -sinh(x);
  c_syspar("DY", &marker, 1, &dy, 1, &err);
  c_syspar("DX", &marker, 1, &dx, 1, &err);
}
"""


@pytest.fixture(scope="module")
def syspar_library(tmp_path_factory):
    from scenes import usersub_library
    lib = usersub_library(tmp_path_factory.mktemp("syspar"), C_SYSPAR, "syspar")
    if lib is None:
        pytest.skip("no C compiler on this machine to build the test's subroutine library")
    return lib


def _lines(lib, routine, expr="1+DX(10)-DZ(10)", expr2="1-DX(10)-DZ(10)"):
    """Seed example 3 with both lines' penalties the C routine `routine` (or, with
    routine None, the expressions given)."""
    text = (DECKS / "particle_between_lines.py").read_text()
    for old, new, sign in (("1+DX(10)-DZ(10)", expr, "1"), ("1-DX(10)-DZ(10)", expr2, "-1")):
        assert f'FUNCTION="{old}"' in text
        text = text.replace(f'FUNCTION="{old}"', f'FUNCTION="{new}"' if routine is None else
                            f'FUNCTION="USER(10, {sign})", ROUTINE="{lib}::{routine}"')
    return pysolver.loads(text, fmt="py")


def _counter(lib):
    import ctypes
    handle = ctypes.CDLL(str(lib))      # already loaded by the model, with c_sysary resolved
    handle.count.restype = ctypes.c_long
    return lambda i: handle.count(i)


@pytest.mark.parametrize("tol", [1e-6, 1e-10])
def test_given_partials_replace_differences(syspar_library, tol, monkeypatch):
    """A routine that gives its partials with c_syspar runs the expression version's steps to
    rounding (its partials are exact) and is called at most twice per evaluation (the value,
    and one step in time, which is flat), six times per Jacobian (differences of the given
    partials in DX, DY, DZ) and 24 times once per run (the partials checked against fourth-order
    differences): under 0.4x the calls of the same routine differenced."""
    # the expression version integrated as the routine's is (all six states: a routine that
    # reads TDISP reads y, which the expression version's particle holds)
    monkeypatch.setenv("PYSOLVER_HELD", "off")
    ref = _lines(syspar_library, None).run(integr_tol=tol)
    given, differenced = _lines(syspar_library, "ALWAYS"), _lines(syspar_library, "NEVER")
    given.compile(), differenced.compile()
    count = _counter(syspar_library)
    c0 = count(0)
    res = given.run(integr_tol=tol)
    calls = count(0) - c0
    assert differenced.run(integr_tol=tol).success
    plain_calls = count(0) - c0 - calls
    assert res.success and res.stats["steps"] == ref.stats["steps"]
    assert np.abs(res.request(1)[:, :4] - ref.request(1)[:, :4]).max() <= 1e-12
    st = res.stats
    assert calls <= 2 * 2 * (st["nres"] + st["outputs"]) + 2 * 8 * st["njac"] + 2 * 12
    assert calls <= 0.4 * plain_calls


def test_given_partials_only_when_asked(syspar_library):
    """c_adams_needs_partials says when partials are wanted: a routine that gives them only
    then runs exactly as one that always does; the differencing calls (in time) do not ask."""
    always, asked = _lines(syspar_library, "ALWAYS"), _lines(syspar_library, "ASKED")
    always.compile(), asked.compile()
    count = _counter(syspar_library)
    a = always.run()
    before = [count(i) for i in range(3)]
    b = asked.run()
    n = [count(i) - before[i] for i in range(3)]
    np.testing.assert_array_equal(a.request(1), b.request(1))
    assert a.stats == b.stats
    assert n[1] > 0 and n[2] > 0 and n[1] + n[2] == n[0]


def test_given_partials_jacobian_is_the_exact_one(syspar_library):
    """Second partials from differences of the given first ones: the bead's routine
    (y - cosh x, partials -sinh x and 1) has the expression version's iteration matrix, and
    so do the straight lines (their given partials are constant: the second partials are 0)."""
    bead = pysolver.loads(bead_xml(f'type="USERSUB" usrsub_dll_name="{syspar_library}" '
                                   'usrsub_fnc_name="BEAD" usrsub_param_string="USER(9)"'))
    _jacobian_like_the_expression(bead, 3)
    lines, exact = _lines(syspar_library, "ALWAYS").compile().kernel, \
        _lines(syspar_library, None).compile().kernel
    rng = np.random.default_rng(4)
    for _ in range(3):
        y, yp = rng.normal(size=lines.ny) * 50, rng.normal(size=lines.ny)
        np.testing.assert_allclose(lines.jacobian_array(0.3, y, yp, 7.0),
                                   exact.jacobian_array(0.3, y, yp, 7.0), rtol=1e-12, atol=1e-9)


def _moving(lib, right=1):
    """Seed example 3 with both lines moving up at 20 mm/s, as the routine MOVING (its partial in
    time given: right, or as 0) or, with lib None, as expressions."""
    text = (DECKS / "particle_between_lines.py").read_text()
    for old, sign in (("1+DX(10)-DZ(10)", "1"), ("1-DX(10)-DZ(10)", "-1")):
        new = (f'FUNCTION="{old}+20*TIME"' if lib is None else
               f'FUNCTION="USER(10, {sign}, 20, {right})", ROUTINE="{lib}::MOVING"')
        text = text.replace(f'FUNCTION="{old}"', new)
    return pysolver.loads(text.replace("END=3.0", "END=1.0"), fmt="py")


@pytest.mark.parametrize("tol", [1e-6, 1e-10])
def test_given_partial_in_time_replaces_the_step_in_time(syspar_library, tol, monkeypatch):
    """A routine that also gives its partial in time (c_syspar "TIME") runs the expression
    version's steps and answers to rounding on lines that move with time, and is called once
    per evaluation: value and first partials in one call, no step in time (8 calls per
    Jacobian: central differences of the given partials in DX, DY, DZ and time)."""
    import ctypes
    monkeypatch.setenv("PYSOLVER_HELD", "off")
    ref = _moving(None).run(integr_tol=tol)
    model = _moving(syspar_library)
    model.compile()
    count = ctypes.CDLL(str(syspar_library)).moving_count
    count.restype = ctypes.c_long
    c0 = count()
    res = model.run(integr_tol=tol)
    calls, st = count() - c0, res.stats
    assert res.success and st["steps"] == ref.stats["steps"]
    assert np.abs(res.request(1)[:, :4] - ref.request(1)[:, :4]).max() <= 1e-9
    # both lines rise 20 mm in the second: the particle, resting on them, rises with them
    assert ref.request(1)[-1, 1] - ref.request(1)[50, 1] == pytest.approx(20 * 0.75, abs=0.5)
    # per evaluation one call per routine; per Jacobian eight more; the check of the partials
    # (each against differences of the value, once per run)
    assert calls <= 2 * (st["nres"] + st["outputs"]) + 2 * 8 * st["njac"] + 2 * 4 * 20


MOVING_NUMPY = '''def moving(id, time, par, npar, dflag, iflag):
    import numpy as np
    ipar = [int(par[0])]
    x, z = np.array([py_sysfnc("DX", ipar)[0], py_sysfnc("DZ", ipar)[0]], dtype=float)
    py_syspar("DX", ipar, [par[1]])
    py_syspar("DZ", ipar, [-1.0])
    py_syspar("TIME", [], [par[2]])
    return float(1 + par[1] * x - z + par[2] * time)
'''


def test_python_routine_gives_its_partial_in_time(monkeypatch):
    """py_syspar("TIME", [], [v]) from a routine the kernel calls: the expression version's
    steps and answers on the moving lines."""
    monkeypatch.setenv("PYSOLVER_HELD", "off")
    ref = _moving(None).run(integr_tol=1e-8)
    text = (DECKS / "particle_between_lines.py").read_text().replace("END=3.0", "END=1.0")
    text = text.replace("PART(1,", MOVING_NUMPY + "\nPART(1,")
    for old, sign in (("1+DX(10)-DZ(10)", "1"), ("1-DX(10)-DZ(10)", "-1")):
        text = text.replace(f'FUNCTION="{old}"',
                            f'FUNCTION="USER(10, {sign}, 20)", ROUTINE=moving')
    res = pysolver.loads(text, fmt="py").run(integr_tol=1e-8)
    assert res.success and res.stats["steps"] == ref.stats["steps"]
    assert np.abs(res.request(1)[:, :4] - ref.request(1)[:, :4]).max() <= 1e-9


def test_given_partial_in_time_is_checked(syspar_library):
    """A partial in time that differences of the value contradict ends the run naming TIME
    and both numbers; TIME named with ids is c_syspar's error."""
    wrong = _moving(syspar_library, right=0).run()
    assert not wrong.success and wrong.status == -400
    got = re.fullmatch(r"user subroutine \(id [12]\): MOVING: c_syspar gave the partial in "
                       r"TIME as 0, but differences of its value give (\S+) \((?:called at "
                       r"t = (\S+); the run's last converged step: )?t = 0\)", wrong.message)
    assert got is not None, wrong.message
    assert float(got[1]) == pytest.approx(20, rel=1e-6)
    assert got[2] is None or 0 < float(got[2]) < 1e-3
    res = _lines(syspar_library, "TIMEIDS").run()
    assert not res.success
    assert res.message in (f"user subroutine (id {i}): TIMEIDS: c_syspar: TIME takes no ids "
                           "and one partial, c_syspar was given 1 id and 1 partial (t = 0)"
                           for i in (1, 2))


def test_given_partials_in_time_jacobian_is_the_exact_one(syspar_library):
    """A travelling wave z = a cos(x / L - w t) as a routine giving every partial: its
    iteration matrix (second partials from central differences of the given first ones,
    time's row included) is the expression version's to 1e-8 of its largest entry."""
    text = CURVE_DECK.format(x=3, z=30, function="{}", routine="{}")
    params = "10, 40, 25, 6"
    exact = pysolver.loads(text.format("40*COS(DX(10)/25-6*TIME)-DZ(10)", ""), fmt="py")
    routine = pysolver.loads(text.format(f"USER({params})",
                                         f'ROUTINE="{syspar_library}::WAVE", '), fmt="py")
    k, ke = routine.compile().kernel, exact.compile().kernel
    rng = np.random.default_rng(8)
    for t in (0.0, 0.13, 0.4):
        y = ke.layout.initial_state() + rng.normal(size=ke.ny) * [5, 5, 5, 50, 50, 50][:ke.ny]
        yp = rng.normal(size=ke.ny) * 30
        J, Je = k.jacobian_array(t, y, yp, 7.0), ke.jacobian_array(t, y, yp, 7.0)
        assert np.abs(J - Je).max() <= 1e-8 * np.abs(Je).max()
        np.testing.assert_allclose(k.residual_array(t, y, yp), ke.residual_array(t, y, yp),
                                   rtol=1e-12, atol=1e-9)


def test_given_partials_are_checked(syspar_library):
    """Wrong partials end the run naming the value and both numbers; at a kink (the particle
    starts at x = 100, where |x - 100| bends) a one-sided partial is accepted; a partial in a
    value the iflag call did not ask for, or the wrong count, ends the run with c_syspar's
    message, each naming the routine."""
    wrong = _lines(syspar_library, "WRONG").run()
    assert not wrong.success and wrong.status == -400
    assert wrong.message == ("user subroutine (id 2): WRONG: c_syspar gave the partial in DX(10) "
                             "as 1, but differences of its value give -1 (t = 0)")
    kinked = _lines(syspar_library, None, "1+DX(10)-DZ(10)+0.1*ABS(DX(10)-100)",
                    "1-DX(10)-DZ(10)+0.1*ABS(DX(10)-100)")
    ref, fine = kinked.run(integr_tol=1e-10), kinked.run(integr_tol=1e-12)
    err = np.abs(ref.request(1)[:, :4] - fine.request(1)[:, :4]).max()
    _close_to_expression(_lines(syspar_library, "KINK").run(integr_tol=1e-10), ref, fine, err)
    for routine, message in (
            ("UNASKED", "c_syspar: partials in a value its iflag call did not ask for: DY(10)"),
            ("SHORT", "c_syspar: TDISP has 3 values, c_syspar was given 2 partials")):
        res = _lines(syspar_library, routine).run()
        assert not res.success
        assert res.message in (f"user subroutine (id {i}): {routine}: {message} (t = 0)"
                               for i in (1, 2))


def test_given_partials_a_little_off_or_given_late_are_caught(syspar_library):
    """The check compares at the tolerance of the differences it takes (the value is linear
    here: they are exact), not 5 % one-sided (which took a DX partial 2 % or 8 % off: the run
    succeeded with forces 3 N off); with the value's own rounding, not 1e-9 of a unit (which
    took any partial of a value near 1e-12), at steps where that rounding is small (a value
    near 1e6 that changes by 1e-2 per mm); and each partial the first time the routine gives
    it, not only those of the first evaluation (LATE gives DZ's, 10 % off, once x < 50: the
    run succeeded with forces 16 N off). LATE's is caught in a call at an IDA trial time,
    past the run's last converged step: the message names both."""
    said = (r"user subroutine \(id 2\): {}: c_syspar gave the partial in (\w+)\(10\) as (\S+), "
            r"but differences of its value give (\S+) \((?:called at t = (\S+); the run's "
            r"last converged step: )?t = (\S+)\)")
    for routine, value, given, differences, t in (("NEAR", "DX", -1.02, -1.0, 0.0),
                                                  ("TINY", "DX", -2e-12, -1e-12, 0.0),
                                                  ("OFFSET", "DX", -2e-2, -1e-2, 0.0),
                                                  ("LATE", "DZ", -1.1, -1.0, 0.145)):
        res = _lines(syspar_library, routine).run()
        assert not res.success and res.status == -400
        got = re.fullmatch(said.format(routine), res.message)
        assert got is not None, res.message
        assert got[1] == value and float(got[2]) == given
        assert float(got[3]) == pytest.approx(differences, rel=1e-6)
        assert float(got[5]) == pytest.approx(t, abs=0.005)
        assert (got[4] is None) == (t == 0.0) and (t == 0.0 or float(got[4]) > float(got[5]))


CURVE_DECK = """from pysolver.msolve import *
UNITS(MASS="KILOGRAM", LENGTH="MILLIMETER", TIME="SECOND", FORCE="NEWTON")
PART(1, GROUND=True)
MARKER(1, PART=1)
MARKER(10, PART=2, QP=[{x}, 0, {z}])
POINT_MASS(2, MASS=1.0, CM=10)
ACCGRAV(KGRAV=-9810)
PFORCE(1, FUNCTION="{function}", {routine}PENALTY=1e4, PENALTY1=1e2)
REQUEST(1, F1="DX(10)", F2="DZ(10)", F3="PFORCE(1)")
SIMULATE(TYPE="TRANSIENT", END=0.05, DTOUT=0.005)
"""


@pytest.mark.parametrize("x, par, expr", [
    (1e4, "0, 50, 10", "DZ(10)-50*COS(DX(10)/10)"),
    (1e5, "0, 50, 10", "DZ(10)-50*COS(DX(10)/10)"),
    (1e3, "1, 1e3, 995", "DZ(10)-1e3/(DX(10)-995)"),
    (1e4, "1, 1e4, 9990", "DZ(10)-1e4/(DX(10)-9990)"),
    (1e3, "2, 1, 1000.1", "DZ(10)-MAX(0, 1000.1-DX(10))**2"),
    (999, "3, 1000", "DZ(10)-SQRT(1e6-DX(10)**2)")], ids=str)
def test_given_partials_of_curves_far_out_are_taken(syspar_library, x, par, expr):
    """Right partials of values that curve within the first difference step (1e-3 of the
    position: 8 mm at 1e4 mm) are taken, the check going to smaller steps: a cosine of
    wavelength 63 mm at 1e4 and 1e5 mm, 1 / gap 5 and 10 mm wide, a contact 0.1 mm deep at
    1000 mm, a circle 1 mm from its edge (a larger step leaves it); each ended the run at its
    first evaluation before. The residual there is the expression version's to rounding, and
    the run (from 1 mm off the curve) its answers to the integration's tolerance."""
    kind, a, b = (float(v) for v in (par + ", 0").split(",")[:3])
    curve = {0: lambda: a * math.cos(x / b), 1: lambda: a / (x - b),
             2: lambda: a * max(0.0, b - x) ** 2, 3: lambda: math.sqrt(a * a - x * x)}
    z = curve[kind]() + 1.0
    user, exact = (pysolver.loads(CURVE_DECK.format(x=x, z=z, function=f, routine=r), fmt="py")
                   for f, r in ((f"USER(10, {par})", f'ROUTINE="{syspar_library}::CURVE", '),
                                (expr, "")))
    k, e = user.compile().kernel, exact.compile().kernel
    y = k.layout.initial_state()
    np.testing.assert_allclose(k.residual_array(0.0, y, 0 * y), e.residual_array(0.0, y, 0 * y),
                               rtol=1e-9, atol=1e-9)
    res, ref = user.run(integr_tol=1e-9), exact.run(integr_tol=1e-9)
    assert res.success and ref.success, res.message
    a, b = res.request(1)[:, :3], ref.request(1)[:, :3]
    assert (np.abs(a - b).max(axis=0) <= 1e-6 * np.abs(b).max(axis=0)).all()


def test_py_syspar(tmp_path):
    """py_syspar from an untraceable Python routine: the expression version's answers and steps
    to rounding; wrong partials are reported; a traced routine that calls it is still traced
    (tracing differentiates exactly); outside a routine it is an error."""
    from scenes import LINES_NUMPY_SYSPAR, LINES_PFOSUB, lines_deck
    expr_text, _ = lines_deck("expression", tmp_path)
    ref = pysolver.loads(expr_text, fmt="py").run(integr_tol=1e-10)
    text, _ = lines_deck("untraceable_syspar", tmp_path)
    res = pysolver.loads(text, fmt="py").run(integr_tol=1e-10)
    assert res.success and res.stats["steps"] == ref.stats["steps"]
    assert np.abs(res.request(1)[:, :4] - ref.request(1)[:, :4]).max() <= 1e-12
    bad = text.replace("py_syspar('DZ', ipar, [-1.0])", "py_syspar('DZ', ipar, [1.0])")
    res = pysolver.loads(bad, fmt="py").run()
    assert not res.success
    assert res.message == ("user subroutine (id 2): lines: py_syspar gave the partial in DZ(10) "
                           "as 1, but differences of its value give -1 (t = 0)")
    traced = text.replace(LINES_NUMPY_SYSPAR.replace("def PFOSUB", "def lines"),
                          LINES_PFOSUB.replace("def PFOSUB", "def lines").replace(
                              "    return 1", "    py_syspar('DX', ipar, [par[1]])\n"
                              "    return 1"))
    assert traced != text
    res = pysolver.loads(traced, fmt="py").run(integr_tol=1e-10)
    assert all("traced into the kernel" in p for p in res.meta["usersubs"].values())
    np.testing.assert_allclose(res.request(1)[:, :4], ref.request(1)[:, :4], atol=1e-9)
    with pytest.raises(RuntimeError, match="py_syspar works only inside a user subroutine"):
        pysolver.msolve.py_syspar("DX", [10], [1.0])


def test_py_syspar_of_an_array_and_a_wrong_count(tmp_path, monkeypatch):
    """py_syspar of a TDISP array read with py_sysary goes through c_syspar: the expression
    version's steps and answers to rounding; one partial too many for DX is the run's error,
    in c_syspar's words with py_syspar's name."""
    from scenes import LINES_NUMPY_SYSPAR, lines_deck
    # the expression version integrated as the routine's is (all six states: a routine that
    # reads TDISP reads y, which the expression version's particle holds)
    monkeypatch.setenv("PYSOLVER_HELD", "off")
    expr_text, _ = lines_deck("expression", tmp_path)
    ref = pysolver.loads(expr_text, fmt="py").run(integr_tol=1e-10)
    text, _ = lines_deck("untraceable_syspar", tmp_path)
    body = LINES_NUMPY_SYSPAR.replace("def PFOSUB", "def lines")
    assert body in text
    array = body.replace(
        'x, z = np.array([py_sysfnc("DX", ipar)[0], py_sysfnc("DZ", ipar)[0]], dtype=float)',
        'x, _, z = np.array(py_sysary("TDISP", ipar)[0], dtype=float)').replace(
        "    py_syspar('DX', ipar, [par[1]])\n    py_syspar('DZ', ipar, [-1.0])\n",
        "    py_syspar('TDISP', ipar, [par[1], 0.0, -1.0])\n")
    assert array.count("TDISP") == 2
    res = pysolver.loads(text.replace(body, array), fmt="py").run(integr_tol=1e-10)
    assert res.success and res.stats["steps"] == ref.stats["steps"]
    assert np.abs(res.request(1)[:, :4] - ref.request(1)[:, :4]).max() <= 1e-12
    two = body.replace("py_syspar('DX', ipar, [par[1]])", "py_syspar('DX', ipar, [par[1], 1.0])")
    res = pysolver.loads(text.replace(body, two), fmt="py").run(integr_tol=1e-10)
    assert not res.success
    assert res.message == ("user subroutine (id 2): lines: py_syspar: DX has 1 value, py_syspar "
                           "was given 2 partials (t = 0)")
