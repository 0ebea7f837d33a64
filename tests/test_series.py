"""SHF, POLY, CHEBY, FORCOS, FORSIN (written as operations when parsed) against NumPy
evaluations of Adams' and MotionSolve's definitions, their exact derivatives through a
driven motion, the ranges of the STEP, IMPACT and BISTOP arguments, and the functions
pysolver does not have (docs/deck-language.md)."""
import math

import numpy as np
import pytest
from numpy.polynomial import chebyshev, polynomial

import pysolver
from pysolver import DeckError
from pysolver.deck import expr as ex

RNG = np.random.default_rng(44)
A7 = RNG.uniform(-2, 2, 7)                 # POLY's and the Fourier series' coefficients
A31 = RNG.uniform(-1, 1, 31)               # CHEBY with every coefficient it may take


def _list(a):
    return ",".join(repr(v) for v in a.tolist())


def deck(requests, extra="", end=5.0, step=0.01):
    """A point moving at 1 m/s along x from -0.5, so x = DX(20) runs over [-0.5, 4.5]."""
    return f"""<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
      <Reference_Marker id="1" body_id="1"/><Reference_Marker id="20" body_id="2" pos_x="-0.5"/>
      <Body_Point id="2" cg_id="20" mass="1" v_ic_x="1"/>{extra}{requests}</Model>
      <Simulate analysis_type="Transient" end_time="{end}" print_interval="{step}"/>
      </MotionSolve>"""


def _fourier(x, x0, w, a, trig):
    u = x - x0
    return a[0] + sum(a[j] * trig(j * w * u) for j in range(1, len(a)))


#: (expression, its value as NumPy computes the page's definition at x = DX(20) and t = TIME)
CASES = [
    ("SHF(DX(20), 0.3, 1.7, 2.5, 0.4, -0.2)",
     lambda x, t: 1.7 * np.sin(2.5 * (x - 0.3) - 0.4) - 0.2),
    (f"POLY(DX(20), 1.1, {_list(A7)})", lambda x, t: polynomial.polyval(x - 1.1, A7)),
    (f"CHEBY(0.4*DX(20), 0.8, {_list(A31)})",          # u in [-1, 1], degree 30
     lambda x, t: chebyshev.chebval(0.4 * x - 0.8, A31)),
    (f"CHEBY(DX(20), 2, {_list(A7[:5])})",             # u in [-2.5, 2.5]: past [-1, 1]
     lambda x, t: chebyshev.chebval(x - 2, A7[:5])),
    (f"FORCOS(DX(20), 0.2, 1.3, {_list(A7)})", lambda x, t: _fourier(x, 0.2, 1.3, A7, np.cos)),
    (f"FORSIN(DX(20), -0.7, 2.1, {_list(A7)})",
     lambda x, t: _fourier(x, -0.7, 2.1, A7, np.sin)),
    # the pages' own examples (degrees written with DTOR)
    ("CHEBY(TIME, 1, 1, 0, -1)", lambda x, t: -2 * t ** 2 + 4 * t),
    ("POLY(TIME, 5, 0, 10)", lambda x, t: 10 * (t - 5)),
    ("POLY(TIME, 10, 0, 25, 0, 0.75)", lambda x, t: 25 * (t - 10) + 0.75 * (t - 10) ** 3),
    ("SHF(TIME, 25*DTOR, PI, 360*DTOR, 0, 5)",
     lambda x, t: 5 + np.pi * np.sin(2 * np.pi * (t - np.radians(25)))),
    ("FORCOS(TIME, 0, 360*DTOR, 1, 2, 3, 4)",
     lambda x, t: 1 + sum(c * np.cos(j * 2 * np.pi * t) for j, c in enumerate((2, 3, 4), 1))),
    ("FORSIN(TIME, -0.25, PI, 0, 1, 2, 3)",
     lambda x, t: sum(c * np.sin(j * np.pi * (t + 0.25)) for j, c in enumerate((1, 2, 3), 1))),
    ("POLY(TIME, 0, 2)", lambda x, t: 2 + 0 * t),
    ("FORCOS(TIME, 0, 1, -3)", lambda x, t: -3 + 0 * t),
]


@pytest.mark.parametrize("kernel", ["tapes", "generated"])
def test_each_function_is_its_definition(kernel):
    """Every case's request equals NumPy's evaluation of the definition at the run's x and t
    to 1e-12 of the largest value (the Chebyshev series of degree 30 included, on both
    kernels)."""
    reqs = "".join(f'<Post_Request id="{k + 1}" expr1="{text}" expr2="DX(20)"/>'
                   for k, (text, _) in enumerate(CASES))
    res = pysolver.loads(deck(reqs)).run(kernel=kernel)
    assert res.success, res.message
    for k, (text, fn) in enumerate(CASES):
        got, x = res.request(k + 1)[:, 0], res.request(k + 1)[:, 1]
        want = fn(x, res.t)
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-12 * max(1.0, abs(want).max()),
                                   err_msg=text)


#: (expression of TIME, its value, first and second time derivatives)
_C = np.array([0.3, -0.2, 0.5, 0.1, -0.4, 0.25])
MOTIONS = [
    ("SHF(TIME, 0.1, 0.2, 3, 0.5, 0.05)",
     (lambda t: 0.2 * np.sin(3 * (t - 0.1) - 0.5) + 0.05,
      lambda t: 0.6 * np.cos(3 * (t - 0.1) - 0.5),
      lambda t: -1.8 * np.sin(3 * (t - 0.1) - 0.5))),
    (f"POLY(TIME, 0.4, {_list(_C)})",
     tuple((lambda t, n=n: polynomial.polyval(t - 0.4, polynomial.polyder(_C, n)))
           for n in range(3))),
    (f"CHEBY(TIME, 0.9, {_list(_C)})",
     tuple((lambda t, n=n: chebyshev.chebval(t - 0.9, chebyshev.chebder(_C, n)))
           for n in range(3))),
    (f"FORCOS(TIME, 0.3, 2, {_list(0.1 * _C)})",
     tuple((lambda t, n=n: 0.1 * _C[0] * (n == 0) + sum(
         0.1 * c * (2 * j) ** n * np.cos(2 * j * (t - 0.3) + n * np.pi / 2)
         for j, c in enumerate(_C[1:], 1))) for n in range(3))),
    (f"FORSIN(TIME, 0.3, 2, {_list(0.1 * _C)})",
     tuple((lambda t, n=n: 0.1 * _C[0] * (n == 0) + sum(
         0.1 * c * (2 * j) ** n * np.sin(2 * j * (t - 0.3) + n * np.pi / 2)
         for j, c in enumerate(_C[1:], 1))) for n in range(3))),
]


@pytest.mark.parametrize("kernel", ["tapes", "generated"])
@pytest.mark.parametrize("text, want", MOTIONS, ids=[m[0].split("(")[0] for m in MOTIONS])
def test_a_motion_driven_by_each_follows_its_derivatives(text, want, kernel):
    """A point driven along x by the function of time: its position, velocity and
    acceleration are the function and its first and second derivatives (NumPy's polyder,
    chebder and the series differentiated term by term) to 1e-9 of their size: the kernel's
    derivatives of the expanded operations are exact."""
    extra = f"""<Force_Penalty id="1" expr="DX(20)" penalty="1000"/>
      <Motion_Marker id="1" i_marker_id="20" j_marker_id="1" direction="X" expr="{text}"/>
      <Param_Transient integr_tol="1e-10"/>"""
    res = pysolver.loads(deck('<Post_Request id="1" expr1="DX(20)" expr2="VX(20)" '
                              'expr3="ACCX(20)"/>', extra, end=1.5)).run(kernel=kernel)
    assert res.success, res.message
    for k in range(3):
        w = want[k](res.t)
        np.testing.assert_allclose(res.request(1)[:, k], w, rtol=0,
                                   atol=1e-9 * max(1.0, abs(w).max()), err_msg=(text, k))


def test_the_expansion_is_arithmetic_sin_and_cos():
    """What the kernel is given: zero coefficients left out, u = x when x0 is 0, u^j a
    power, Tj by doubling, Adams' JPRIM the JOINT function."""
    assert ex.unparse(ex.parse("POLY(TIME, 0, 0, 0, 1)")) == "(TIME ** 2)"
    assert ex.unparse(ex.parse("POLY(TIME, 2, 1, 3)")) == "(1 + (3 * (TIME - 2)))"
    assert ex.unparse(ex.parse("CHEBY(TIME, 0, 0, 0, 0, 2)")) == \
        "(2 * ((2 * (TIME * ((2 * (TIME * TIME)) - 1))) - TIME))"
    assert ex.unparse(ex.parse("FORSIN(TIME, 0, 3, 0, 0, 1)")) == "SIN((2 * (3 * TIME)))"
    assert ex.unparse(ex.parse("SHF(TIME, 1, 2, 3, 4, 5)")) == \
        "((2 * SIN(((3 * (TIME - 1)) - 4))) + 5)"
    assert ex.parse("JPRIM(99, 1, 6, 0)") == ex.parse("JOINT(99, 1, 6, 0)")
    assert ex.references(ex.parse("JPRIM(99, 1, 6, 7)")) == {"joint": {99}, "marker": {7}}


def test_a_series_of_an_adams_dataset_with_degrees(tmp_path):
    """Adams' SHF example as written in a dataset (degrees with D): 5 + pi sin(360D (TIME -
    25D))."""
    path = tmp_path / "shf.adm"
    path.write_text("SHF\nPART/1, GROUND\nMARKER/1, PART = 1\nPART/2, MASS = 1, CM = 3, "
                    "IP = 1, 1, 1\nMARKER/3, PART = 2\n"
                    "REQUEST/1, F1 = SHF(TIME, 25D, PI, 360D, 0, 5)\nEND\n")
    res = pysolver.load(path).run()
    np.testing.assert_allclose(res.request(1)[:, 0],
                               5 + np.pi * np.sin(2 * np.pi * (res.t - math.radians(25))),
                               rtol=0, atol=1e-13)


def _error(expr):
    with pytest.raises(DeckError) as err:
        pysolver.loads(deck(f'<Post_Request id="1" expr1="{expr}"/>'))
    assert (err.value.element, err.value.id, err.value.attribute) == \
        ("Post_Request", 1, "expr1")
    return err.value.reason


@pytest.mark.parametrize("expr, message", [
    ("POLY(TIME, 0)", "POLY takes 3 to 33 arguments, got 2"),
    (f"CHEBY(TIME, 0, {_list(np.ones(32))})", "CHEBY takes 3 to 33 arguments, got 34"),
    ("FORCOS(TIME, 0, 1)", "FORCOS takes 4 to 34 arguments, got 3"),
    ("SHF(TIME, 0, 1, 1, 0)", "SHF takes 6 arguments, got 5"),
    ("POLY(1e200, 0, 0, 0, 1)", "(1e+200 ** 2) is inf (a constant part of the expression)"),
])
def test_wrong_calls_are_deck_errors(expr, message):
    assert _error(expr) == f"bad expression {expr!r}: {message} (at column 1)"


@pytest.mark.parametrize("expr, message", [
    ("STEP(TIME, 0.5, 0, 0.5, 1)", "STEP(x, x0, h0, x1, h1): x0 and x1 are both 0.5; x1 must "
     "differ from x0 (equal values are a jump, which STEP cannot fit)"),
    ("STEP5(TIME, 1/2, 0, 0.5, 1)", "STEP5(x, x0, h0, x1, h1): x0 and x1 are both 0.5; x1 "
     "must differ from x0 (equal values are a jump, which STEP5 cannot fit)"),
    ("HAVSIN(TIME, DX(20), 0, DX(20), 1)", "HAVSIN(x, x0, h0, x1, h1): x0 and x1 are the same "
     "expression; x1 must differ from x0 (equal values are a jump, which HAVSIN cannot fit)"),
    ("IMPACT(TIME-0.5, 1, 0, -100, 1.5, 10, 0.1)",
     "IMPACT: k = -100; expected k >= 0 (the stiffness)"),
    ("IMPACT(DX(20), VX(20), 0, 100, 0, 10, 0.1)",
     "IMPACT: e = 0; expected e > 0 (the exponent)"),
    ("IMPACT(DX(20), VX(20), 0, 100, 1.5, -1, 0.1)",
     "IMPACT: cmax = -1; expected cmax >= 0 (the largest damping coefficient)"),
    ("IMPACT(DX(20), VX(20), 0, 100, 1.5, 10, 0)",
     "IMPACT: d = 0; expected d > 0 (the penetration of full damping)"),
    ("BISTOP(TIME, 1, 0.6, 0.4, 10, 1.5, 1, 0.1)",
     "BISTOP: x1 = 0.6 and x2 = 0.4; expected x1 < x2 (the lower and upper bounds of the gap)"),
    ("BISTOP(TIME, 1, 0.4, 0.4, 10, 1.5, 1, 0.1)",
     "BISTOP: x1 = 0.4 and x2 = 0.4; expected x1 < x2 (the lower and upper bounds of the gap)"),
    ("BISTOP(TIME, 1, 0.4, 0.6, 10, -1.5, 1, 0.1)",
     "BISTOP: e = -1.5; expected e > 0 (the exponent)"),
    ("BISTOP(TIME, 1, 0.4, 0.6, 10, 1.5, 1, -0.1)",
     "BISTOP: d = -0.1; expected d > 0 (the penetration of full damping)"),
])
def test_arguments_out_of_range_are_deck_errors(expr, message):
    """Adams' STEP page: x1 must not equal x0; IMPACT and BISTOP: k >= 0, e > 0, cmax >= 0,
    d > 0, x1 < x2 (Adams' IMPACT page, MotionSolve's BISTOP page)."""
    assert _error(expr) == f"bad expression {expr!r}: {message} (at column 1)"


def test_arguments_in_range_load():
    """The edges that are allowed: x1 < x0 for STEP, k = 0 and cmax = 0, a negative IMPACT
    x1, expression arguments."""
    for expr in ("STEP(TIME, 1, 0, 0.5, 1)", "IMPACT(DX(20), VX(20), -1, 0, 0.5, 0, 1e-3)",
                 "BISTOP(DX(20), VX(20), -0.1, DX(20)+1, 10, 2, 0, 0.1)",
                 "STEP(TIME, 0, 0, DX(20), 1)"):
        pysolver.loads(deck(f'<Post_Request id="1" expr1="{expr}"/>'))


@pytest.mark.parametrize("kernel", ["tapes", "generated"])
def test_step_bounds_that_meet_at_run_time_stop_a_force_naming_it(kernel):
    """Bounds that are not constants (here x1 = VARVAL(1), a number a sweep may change) and
    are equal: the STEP is NaN for every x, not a jump; a request shows NaN, a force stops
    the run with the element named (status -700). With the bounds apart the same deck runs
    as the formula."""
    force = ('<Force_Vector_OneBody id="3" marker_id="20" ref_marker_id="1" '
             'fx_expression="STEP(TIME,0.5,0,VARVAL(1),1)" fy_expression="0" '
             'fz_expression="0"/>')
    request = '<Post_Request id="1" expr1="STEP(TIME,0.5,0,VARVAL(1),1)"/>'
    met = '<Reference_Variable id="1" expr="0.5"/>'
    res = pysolver.loads(deck(request, met, end=1, step=0.1)).run(kernel=kernel)
    assert res.success and res.meta["kernel"] == kernel
    assert np.isnan(res.request(1)[:, 0]).all()
    res = pysolver.loads(deck("", met + force, end=1, step=0.1)).run(kernel=kernel)
    assert not res.success and res.status == -700
    assert res.message.startswith("initial conditions: non-finite value (nan) in "
                                  "Force_Vector_TwoBody 3: STEP(TIME,0.5,0,VARVAL(1),1)")
    res = pysolver.loads(deck(request, met.replace("0.5", "0.7"), end=1,
                              step=0.1)).run(kernel=kernel)
    d = np.clip((res.t - 0.5) / 0.2, 0, 1)
    np.testing.assert_allclose(res.request(1)[:, 0], d * d * (3 - 2 * d), rtol=0, atol=1e-14)


@pytest.mark.parametrize("name, why", [
    ("INVPSD", "the signal it rebuilds from a power spectral density depends on random phases "
     "drawn by a generator that is not public"),
    ("INTERP", "it reads SPLINEs of DAC or RPC III time-history files (Adams Durability), "
     "which pysolver does not read; use AKISPL, CUBSPL or LINSPL"),
    ("SWEEP", "its public definitions disagree (MotionSolve's page and the Adams-derived ones "
     "differ in the chirp's phase and in where its STEP5 ramp starts); write the chirp with "
     "SIN, STEP5 and IF"),
    ("VTORQ", "force functions of Force_Vector_TwoBody are not supported yet; FX..TZ(i, j, k) "
     "give the net force and torque at a marker"),
    ("FRICTION", "pysolver does not model the Force_Friction (Adams FRICTION) it reads"),
    ("DIF", "pysolver does not model the Control_Diff (Adams DIFF) it reads"),
])
def test_functions_pysolver_does_not_have_are_not_supported(name, why):
    expr = f"1 + {name}(TIME, 1, 2)"
    assert _error(expr) == f"bad expression {expr!r}: {name} is not supported: {why} " \
        "(at column 5)"


def test_every_refused_name_is_in_the_docs_and_a_misspelling_is_unknown():
    from helpers import ROOT
    page = (ROOT / "docs" / "deck-language.md").read_text()
    table = page.split("## Functions pysolver does not have", 1)[1]
    for name in list(ex.REFUSED) + list(ex.REFUSED_NAMES):
        assert f"`{name}`" in table, name
    assert _error("POLYY(TIME)") == "bad expression 'POLYY(TIME)': unknown function POLYY " \
        "(at column 1)"
    assert _error("2*MODE") == "bad expression '2*MODE': MODE is not supported: pysolver runs " \
        "no linear (modal) analysis (at column 3)"
