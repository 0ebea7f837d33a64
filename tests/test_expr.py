"""The expression language: parsing rules and the value of every function."""
import math

import numpy as np
import pytest

import pysolver
from pysolver.deck import expr as ex
from pysolver.errors import ExpressionError


def values(exprs, extra=""):
    """Evaluate expressions at t = 0 for a point at (0.3, -0.4, 1.2) moving at (1, 2, -0.5)."""
    chans = " ".join(f'expr{k + 1}="{e}"' for k, e in enumerate(exprs))
    deck = f"""<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
      <Reference_Marker id="1" body_id="1" pos_x="0.1" psi="0.5"/>
      <Reference_Marker id="2" body_id="2" pos_x="0.3" pos_y="-0.4" pos_z="1.2"/>
      <Body_Point id="2" cg_id="2" mass="2" v_ic_x="1" v_ic_y="2" v_ic_z="-0.5"/>
      <Force_Gravity grav_z="-10"/>{extra}
      <Post_Request id="1" {chans}/></Model>
      <Simulate analysis_type="Transient" end_time="0.001" num_step="1"/></MotionSolve>"""
    res = pysolver.loads(deck).run()
    return res.request(1)[0, :len(exprs)]


def step(x, x0, h0, x1, h1):
    d = min(max((x - x0) / (x1 - x0), 0), 1)
    return h0 + (h1 - h0) * d * d * (3 - 2 * d)


@pytest.mark.parametrize("text,expected", [
    ("-2**2", -4.0), ("2**3**2", 512.0), ("2*3+4", 10.0), ("2+3*4", 14.0), ("(2+3)*4", 20.0),
    ("8/4/2", 1.0), ("2**-1", 0.5), ("-3+5", 2.0), ("1.5D2", 150.0), (".5e1", 5.0),
    ("pi", math.pi), ("dtor*rtod", 1.0), ("time", 0.0),
])
def test_precedence_and_constants(text, expected):
    assert values([text])[0] == pytest.approx(expected, rel=1e-15)


MATH = [("ABS(-1.5)", 1.5), ("ACOS(0.3)", math.acos(0.3)), ("ASIN(0.3)", math.asin(0.3)),
        ("ATAN(2)", math.atan(2)), ("COS(0.7)", math.cos(0.7)), ("COSH(0.7)", math.cosh(0.7)),
        ("SIN(0.7)", math.sin(0.7)), ("SINH(0.7)", math.sinh(0.7)), ("TAN(0.7)", math.tan(0.7)),
        ("TANH(0.7)", math.tanh(0.7)), ("EXP(0.7)", math.exp(0.7)), ("LOG(0.7)", math.log(0.7)),
        ("LOG10(0.7)", math.log10(0.7)), ("SQRT(0.7)", math.sqrt(0.7)), ("AINT(-2.7)", -2.0),
        ("ANINT(-2.5)", -3.0), ("ATAN2(-1,-2)", math.atan2(-1, -2)), ("MOD(-7,3)", -1.0),
        ("MAX(2,3)", 3.0), ("MIN(2,3)", 2.0), ("SIGN(-2,3)", 2.0), ("SIGN(2,-3)", -2.0),
        ("DIM(5,3)", 2.0), ("DIM(3,5)", 0.0)]


@pytest.mark.parametrize("text,expected", MATH)
def test_math_functions(text, expected):
    assert values([text])[0] == pytest.approx(expected, rel=1e-14, abs=1e-15)


def impact(x, xd, x1, k, e, cmax, d):
    return max(0.0, k * (x1 - x) ** e - step(x, x1 - d, cmax, x1, 0) * xd) if x < x1 else 0.0


def bistop(x, xd, x1, x2, k, e, cmax, d):
    if x < x1:
        return max(k * (x1 - x) ** e - step(x, x1 - d, cmax, x1, 0) * xd, 0.0)
    if x > x2:
        return min(-k * (x - x2) ** e - step(x, x2, 0, x2 + d, cmax) * xd, 0.0)
    return 0.0


@pytest.mark.parametrize("x", [-1.0, 0.1, 0.35, 0.6, 2.0])
def test_smoothing_and_contact_functions(x):
    texts = [f"STEP({x},0,1,1,3)", f"STEP5({x},0,1,1,3)", f"HAVSIN({x},0,1,1,3)",
             f"IMPACT({x},0.4,0.5,100,1.5,10,0.2)", f"BISTOP({x},-0.4,0.2,0.5,100,2,10,0.3)",
             f"IF({x}-0.35: 1, 2, 3)"]
    d = min(max(x, 0), 1)
    want = [step(x, 0, 1, 1, 3), 1 + 2 * d ** 3 * (10 - 15 * d + 6 * d * d),
            2 - math.cos(math.pi * d), impact(x, 0.4, 0.5, 100, 1.5, 10, 0.2),
            bistop(x, -0.4, 0.2, 0.5, 100, 2, 10, 0.3), 1 if x < 0.35 else (2 if x == 0.35 else 3)]
    np.testing.assert_allclose(values(texts), want, rtol=1e-13, atol=1e-14)


def test_marker_measures():
    c, s = math.cos(0.5), math.sin(0.5)
    rel = np.array([0.3 - 0.1, -0.4, 1.2])
    v = np.array([1.0, 2.0, -0.5])
    got = np.append(values(["DX(2)", "DY(2,1)", "DX(2,1,1)", "DY(2,1,1)", "DM(2,1)", "VX(2,0,1)",
                            "VM(2)", "VR(2,1)"]), values(["VR(2,1,1)", "VM(2,1,1)"]))
    want = [0.3, -0.4, rel @ [c, s, 0], rel @ [-s, c, 0], np.linalg.norm(rel), v @ [c, s, 0],
            np.linalg.norm(v), v @ rel / np.linalg.norm(rel), v @ rel / np.linalg.norm(rel),
            np.linalg.norm(v)]
    np.testing.assert_allclose(got, want, rtol=1e-14, atol=1e-15)
    # accelerations from the consistent initial yp: gravity only
    np.testing.assert_allclose(values(["ACCZ(2)", "ACCX(2,1,1)", "WZ(2)", "AZ(1)"]),
                               [-10.0, 0.0, 0.0, 0.5], atol=1e-14)


def test_varval_and_force_measures():
    extra = """<Reference_Variable id="5" expr="2*DX(2) + 1"/>
      <Force_Penalty id="3" expr="DZ(2) - 1" penalty="100" penalty1="4"/>
      <Force_Scalar_TwoBody id="4" type="Force" i_marker_id="2" j_marker_id="1" expr="-7"/>"""
    rel = np.array([0.2, -0.4, 1.2])
    got = values(["VARVAL(5)", "PFORCE(3)", "SFORCE(4,0,1,0)", "SFORCE(4,0,2,0)",
                  "SFORCE(4,1,3,0)", "SFORCE(4,0,5,0)"], extra)
    want = [1.6, -100 * 0.2 - 4 * (-0.5), 7.0, -7 * rel[0] / np.linalg.norm(rel),
            7 * rel[1] / np.linalg.norm(rel), 0.0]
    np.testing.assert_allclose(got, want, rtol=1e-13, atol=1e-14)


@pytest.mark.parametrize("text,msg", [
    ("1 +", "expected a number"), ("(1+2", "expected ')'"), ("FOO(1)", "unknown function FOO"),
    ("STEP(1,2,3)", "STEP takes 5 arguments, got 3"), ("DX(1.5)", "integer literals"),
    ("DX(1,2,3,4)", "DX takes 1 to 3 arguments"), ("BAR + 1", "unknown name 'BAR'"),
    ("1 $ 2", "unexpected character '$'"), ("2 3", "unexpected 3.0"), ("", "empty"),
    ("IF(1, 2, 3, 4)", "expected ':'"),
    ("DELAY(TIME, 0.1, 0)", "DELAY is not supported: MotionSolve interpolates its history"),
])
def test_syntax_errors(text, msg):
    with pytest.raises(ExpressionError, match=msg.replace("(", r"\(").replace(")", r"\)")
                       .replace("$", r"\$").replace("+", r"\+")):
        ex.parse(text)
