"""Reference_Spline and AKISPL, CUBSPL, LINSPL, QUISPL: values and derivatives against SciPy
on the same knots, Adams' extrapolation, the statement, bad input."""
import numpy as np
import pytest
from scipy.interpolate import Akima1DInterpolator, CubicSpline, make_interp_spline

import pysolver
from pysolver import DeckError

from helpers import fd_iteration_matrix

X = np.array([0, 0.4, 1.0, 1.3, 2.0, 2.8, 3.5])
Y = np.sin(X) * 2 + 0.3 * X ** 2
POINTS = "\n".join(f"{a!r} {b!r}" for a, b in zip(X.tolist(), Y.tolist()))


def natural_quintic(xk, yk):
    """The natural quintic spline through (xk, yk) solved from its conditions with NumPy (not
    SciPy's spline code): one quintic per interval, in powers of x - its left knot, taking
    the data at both ends, its derivatives 1..4 continuous at the inner knots and its third
    and fourth derivatives 0 at the first and last knots (Herriot and Reinsch's natural
    spline). Returns f(x, order) on [xk[0], xk[-1]]."""
    from math import factorial
    n = len(xk) - 1
    A, b = np.zeros((6 * n, 6 * n)), np.zeros(6 * n)

    def row(i, t, r):                   # the r-th derivative of piece i at t, as a row
        out = np.zeros(6 * n)
        for k in range(r, 6):
            out[6 * i + k] = factorial(k) / factorial(k - r) * t ** (k - r)
        return out
    eqs = []
    for i in range(n):
        h = xk[i + 1] - xk[i]
        eqs += [(row(i, 0.0, 0), yk[i]), (row(i, h, 0), yk[i + 1])]
        if i + 1 < n:
            eqs += [(row(i, h, r) - row(i + 1, 0.0, r), 0.0) for r in range(1, 5)]
    eqs += [(row(0, 0.0, r), 0.0) for r in (3, 4)]
    eqs += [(row(n - 1, xk[-1] - xk[-2], r), 0.0) for r in (3, 4)]
    for k, (a, v) in enumerate(eqs):
        A[k], b[k] = a, v
    c = np.linalg.solve(A, b).reshape(n, 6)

    def f(x, order=0):
        i = np.clip(np.searchsorted(xk, x, side="right") - 1, 0, n - 1)
        t = np.asarray(x) - xk[i]
        return sum(c[i, k] * factorial(k) / factorial(k - order) * t ** (k - order)
                   for k in range(order, 6))
    return f


def deck(requests, spline_attrs='num_xy_pair="7"', points=POINTS):
    """A point moving at 1 m/s along x from -0.5 through the data and past its end, so x =
    DX(20) sweeps the spline, both extrapolations included."""
    return f"""<MotionSolve><Model><Body_Rigid id="1" isground="TRUE"/>
      <Reference_Marker id="1" body_id="1"/><Reference_Marker id="20" body_id="2" pos_x="-0.5"/>
      <Body_Point id="2" cg_id="20" mass="1" v_ic_x="1"/>
      <Reference_Spline id="7" {spline_attrs}>
      {points}
      </Reference_Spline>{requests}</Model>
      <Simulate analysis_type="Transient" end_time="4.5" print_interval="0.01"/></MotionSolve>"""


@pytest.mark.parametrize("kernel", ["tapes", "generated"])
def test_each_function_is_scipys_interpolant_with_its_derivatives(kernel):
    """Inside the data, every function and derivative order equals SciPy's (interp1d-like
    broken line, CubicSpline natural, Akima1DInterpolator) or, for QUISPL, the natural
    quintic spline solved from its conditions, to 1e-13."""
    calls = [(f, n) for f in ("LINSPL", "CUBSPL", "AKISPL", "QUISPL") for n in (0, 1, 2)]
    reqs = "".join(f'<Post_Request id="{10 + k}" ' + " ".join(
        f'expr{j + 1}="{f}(DX(20),0,7,{n})"' for j, (f, n) in enumerate(calls[4 * k:4 * k + 4]))
        + "/>" for k in range(3))
    res = pysolver.loads(deck(reqs)).run(kernel=kernel)
    assert res.success, res.message
    xs = -0.5 + res.t
    inside = (xs > 0) & (xs < 3.5)
    ref = {"LINSPL": make_interp_spline(X, Y, k=1), "CUBSPL": CubicSpline(X, Y, bc_type="natural"),
           "AKISPL": Akima1DInterpolator(X, Y), "QUISPL": natural_quintic(X, Y)}
    got = np.hstack([res.request(10 + k)[:, :4] for k in range(3)])
    for j, (f, n) in enumerate(calls):
        want = ref[f](xs[inside], n) if not (f == "LINSPL" and n == 2) else 0 * xs[inside]
        np.testing.assert_allclose(got[inside, j], want, rtol=0, atol=1e-13, err_msg=(f, n))


def test_quispl_is_the_natural_quintic_spline_near_the_ends_too():
    """Trial 44's data (8 uneven knots): QUISPL and its derivatives are the natural quintic
    (MotionSolve's QUISPL page cites Herriot and Reinsch's natural spline) in the first and
    last intervals, where a not-a-knot quintic differs by 1.1 (at x = 4.675: 1.2552, not
    2.3504)."""
    xk = np.array([0, 0.7, 1.1, 2.0, 2.4, 3.5, 4.0, 5.0])
    yk = np.array([0, 1.2, 0.8, 2.5, 2.2, -0.5, 0.3, 1.0])
    points = "\n".join(f"{a!r} {b!r}" for a, b in zip(xk.tolist(), yk.tolist()))
    text = deck('<Post_Request id="1" expr1="QUISPL(DX(20),0,7)" expr2="QUISPL(DX(20),0,7,1)" '
                'expr3="QUISPL(DX(20),0,7,2)"/>', "", points).replace(
        'pos_x="-0.5"', 'pos_x="0"').replace('end_time="4.5" print_interval="0.01"',
                                               'end_time="5" print_interval="0.005"')
    res = pysolver.loads(text).run()
    inside = res.t < 4.999             # the last knot on takes Adams' extrapolation
    xs, q = res.t[inside], res.request(1)[inside, :3]
    ref = natural_quintic(xk, yk)
    for order in range(3):
        np.testing.assert_allclose(q[:, order], ref(xs, order), rtol=0, atol=1e-12)
    k = int(np.argmin(abs(xs - 4.675)))
    assert q[k, 0] == pytest.approx(1.2551556600555565, abs=1e-12)
    assert make_interp_spline(xk, yk, k=5)(xs[k]) == pytest.approx(2.3503764141700305)


TRIAL45 = """<MotionSolve><Model>
<Body_Rigid id="1" isground="TRUE"/>
<Reference_Marker id="1" body_id="1"/>
<Reference_Marker id="20" body_id="2" pos_x="0.0"/>
<Body_Point id="2" cg_id="20" mass="1.5" v_ic_x="1.0"/>
<Reference_Spline id="7" num_xy_pair="6">
-0.2 30
0.0 5
0.05 -2
0.1 -10
0.2 -40
0.35 -70
</Reference_Spline>
<Force_Vector_OneBody id="1" type="FORCEONLY" marker_id="20" ref_marker_id="1"
   fx_expression="CUBSPL(DX(20),0,7)" fy_expression="0" fz_expression="0"/>
<Post_Request id="1" expr1="DX(20)" expr2="VX(20)" expr3="CUBSPL(DX(20),0,7)"
   expr4="CUBSPL(DX(20),0,7,1)" expr5="CUBSPL(DX(20),0,7,2)"/>
<Param_Transient integr_tol="1e-10"/>
</Model><Simulate analysis_type="Transient" end_time="1.5" print_interval="0.01"/></MotionSolve>"""


@pytest.mark.parametrize("kernel", ["tapes", "generated"])
def test_cubspl_is_the_natural_cubic_spline(kernel):
    """MotionSolve's Reference_Spline page: "The Cubic fitting algorithm ensures a much
    smoother fit by utilizing natural splines". Trial 45's point mass pushed by a CUBSPL of
    its own position: the force and its slope are SciPy's natural spline (1e-12), its second
    derivative 0 at the first and last knots, and the motion is that spline's ODE solved by
    SciPy (1e-8 m). The not-a-knot spline pysolver used before differs by 0.51 N on the
    path and moves the mass 4.7e-3 m elsewhere."""
    from scipy.integrate import solve_ivp
    xk = np.array([-0.2, 0.0, 0.05, 0.1, 0.2, 0.35])
    yk = np.array([30.0, 5.0, -2.0, -10.0, -40.0, -70.0])
    natural = CubicSpline(xk, yk, bc_type="natural")
    res = pysolver.loads(TRIAL45).run(kernel=kernel)
    assert res.success, res.message
    r = res.request(1)
    x = r[:, 0]
    assert xk[0] < x.min() and x.max() < xk[-1]
    np.testing.assert_allclose(r[:, 2], natural(x), rtol=0, atol=1e-12)
    np.testing.assert_allclose(r[:, 3], natural(x, 1), rtol=0, atol=1e-12)
    np.testing.assert_allclose(r[:, 4], natural(x, 2), rtol=0, atol=1e-9)
    assert natural(xk[[0, -1]], 2) == pytest.approx([0.0, 0.0], abs=1e-12)
    ref = solve_ivp(lambda t, s: [s[1], natural(s[0]) / 1.5], (0, 1.5), [0.0, 1.0],
                    t_eval=res.t, method="DOP853", rtol=1e-12, atol=1e-13)
    np.testing.assert_allclose(x, ref.y[0], rtol=0, atol=1e-8)
    np.testing.assert_allclose(r[:, 1], ref.y[1], rtol=0, atol=1e-7)
    old = CubicSpline(xk, yk)
    assert np.max(abs(old(x) - natural(x))) == pytest.approx(0.51, abs=0.01)


@pytest.mark.parametrize("linear", [False, True])
def test_outside_the_data_a_parabola_or_a_line(linear):
    """Adams' extrapolation: the parabola through the first (last) three points, or with
    linear_extrap the line through the first (last) two."""
    attrs = 'linear_extrap="TRUE"' if linear else ""
    res = pysolver.loads(deck('<Post_Request id="1" expr1="CUBSPL(DX(20),0,7)"/>',
                              attrs)).run()
    xs, q = -0.5 + res.t, res.request(1)[:, 0]
    k = 2 if linear else 3
    left, right = xs < 0, xs > 3.5
    np.testing.assert_allclose(q[left], np.polyval(np.polyfit(X[:k], Y[:k], k - 1), xs[left]),
                               rtol=0, atol=1e-12)
    np.testing.assert_allclose(q[right], np.polyval(np.polyfit(X[-k:], Y[-k:], k - 1),
                                                    xs[right]), rtol=0, atol=1e-12)


def test_the_statement(tmp_path):
    path = tmp_path / "s.py"
    path.write_text("from pysolver.msolve import *\nPART(1, GROUND=True)\nMARKER(1, PART=1)\n"
                    "MARKER(20, PART=2, QP=[0.5, 0, 0])\nPOINT_MASS(2, MASS=1, CM=20)\n"
                    f"SPLINE(7, X={X.tolist()}, Y={Y.tolist()})\n"
                    "REQUEST(1, F1='AKISPL(DX(20), 0, 7)')\n"
                    "SIMULATE(TYPE='TRANSIENT', END=0.1, DTOUT=0.1)\n")
    res = pysolver.load(path).run()
    assert res.request(1)[0, 0] == pytest.approx(float(Akima1DInterpolator(X, Y)(0.5)),
                                                 abs=1e-14)


@pytest.mark.parametrize("spline, request_, attribute, words", [
    ('num_xy_pair="3"', 'expr1="LINSPL(DX(20),0,7)"', "num_xy_pair", "the text has 7"),
    ("", 'expr1="CUBSPL(DX(20),0,9)"', "expr1", "spline id 9, which does not exist"),
    ("", 'expr1="CUBSPL(DX(20),0,7,3)"', "expr1", "order is 0, 1 or 2"),
])
def test_bad_spline_use_is_a_deck_error(spline, request_, attribute, words):
    with pytest.raises(DeckError, match=words) as err:
        pysolver.loads(deck(f'<Post_Request id="1" {request_}/>', spline))
    assert err.value.attribute == attribute


@pytest.mark.parametrize("points, words", [
    ("0 1 2 3 1 4", "x must be strictly increasing; x\\[2\\] = 1 follows x\\[1\\] = 2"),
    ("0 1 2", "x y pairs; got 3 numbers"),
    ("0 1", "at least 2 points"),
])
def test_bad_spline_data_is_a_deck_error(points, words):
    with pytest.raises(DeckError, match=words) as err:
        pysolver.loads(deck("", "", points))
    assert err.value.element == "Reference_Spline"


def test_too_few_points_for_a_function_is_a_deck_error():
    with pytest.raises(DeckError, match="QUISPL needs at least 6 points; Reference_Spline 7 "
                                        "has 4") as err:
        pysolver.loads(deck('<Post_Request id="1" expr1="QUISPL(DX(20),0,7)"/>', "",
                            "0 0 1 1 2 4 3 9"))
    assert err.value.attribute == "expr1"


# a surface: three curves at z = -1, 0.5, 2 (MotionView's table layout: z values, then rows)
ZS = np.array([-1.0, 0.5, 2.0])
YS = np.array([Y, 0.5 * Y + X, np.cos(X)])             # one curve per z value


def surface_deck(requests, extra=""):
    """The point of deck(), now also moving along y at 1.5 m/s from -2, so z = DY(20) passes
    below the first curve, between all of them and above the last."""
    table = " ".join(map(repr, ZS.tolist())) + "\n" + "\n".join(
        " ".join(map(repr, [x, *YS[:, i].tolist()])) for i, x in enumerate(X.tolist()))
    return deck(requests, f'num_z="3" {extra}', table).replace(
        'pos_x="-0.5"', 'pos_x="-0.5" pos_y="-2"').replace('v_ic_x="1"', 'v_ic_x="1" v_ic_y="1.5"')


def surface_reference(f, x, z):
    """Each curve by SciPy, then the line in z through the two curves around z (the nearest
    two outside)."""
    make = {"CUBSPL": lambda a, b: CubicSpline(a, b, bc_type="natural"), "AKISPL": Akima1DInterpolator,
            "LINSPL": lambda a, b: make_interp_spline(a, b, k=1)}[f]
    curves = np.array([make(X, ys)(x) for ys in YS])
    k = np.clip(np.searchsorted(ZS, z, side="right") - 1, 0, len(ZS) - 2)
    s = (z - ZS[k]) / (ZS[k + 1] - ZS[k])
    cols = np.arange(len(x))
    return curves[k, cols] + s * (curves[k + 1, cols] - curves[k, cols])


@pytest.mark.parametrize("kernel", ["tapes", "generated"])
def test_a_surface_is_each_curve_in_x_and_linear_in_z(kernel):
    """AKISPL, CUBSPL, LINSPL on a three-curve surface equal each curve's SciPy interpolant
    blended linearly in z (1e-13), below, between and above the z values."""
    names = ("AKISPL", "CUBSPL", "LINSPL")
    req = '<Post_Request id="1" ' + " ".join(
        f'expr{j + 1}="{f}(DX(20),DY(20),7)"' for j, f in enumerate(names)) + "/>"
    res = pysolver.loads(surface_deck(req)).run(kernel=kernel)
    assert res.success, res.message
    xs, zs = -0.5 + res.t, -2 + 1.5 * res.t
    inside = (xs > 0) & (xs < 3.5)
    assert zs[inside].min() < ZS[0] and zs[inside].max() > ZS[-1]
    for j, f in enumerate(names):
        np.testing.assert_allclose(res.request(1)[inside, j],
                                   surface_reference(f, xs[inside], zs[inside]),
                                   rtol=0, atol=1e-13, err_msg=f)


def test_a_force_from_a_surface_has_an_exact_jacobian():
    """A force of both spline arguments, positions and velocities: the iteration matrix equals
    central differences."""
    force = ('<Force_Vector_OneBody id="5" marker_id="20" ref_marker_id="1" '
             'fx_expression="CUBSPL(DX(20), VY(20), 7)" '
             'fy_expression="-AKISPL(DX(20) + VX(20), DY(20), 7)" fz_expression="0"/>')
    k = pysolver.loads(surface_deck(force)).compile().kernel
    rng = np.random.default_rng(3)
    for _ in range(3):
        y, yp = rng.normal(size=k.ny), rng.normal(size=k.ny)
        J = k.jacobian_array(0.4, y, yp, 3.0)
        fd = fd_iteration_matrix(k, 0.4, y, yp, 3.0)
        assert np.abs(J - fd).max() <= 1e-6 * np.abs(fd).max()


def test_the_statement_builds_a_surface(tmp_path):
    """SPLINE(..., Z=) with Y curve after curve equals the XML table."""
    path = tmp_path / "s.py"
    path.write_text("from pysolver.msolve import *\nPART(1, GROUND=True)\nMARKER(1, PART=1)\n"
                    "MARKER(20, PART=2, QP=[0.7, 1.1, 0])\nPOINT_MASS(2, MASS=1, CM=20)\n"
                    f"SPLINE(7, X={X.tolist()}, Y={YS.tolist()}, Z={ZS.tolist()})\n"
                    "REQUEST(1, F1='AKISPL(DX(20), DY(20), 7)')\n"
                    "SIMULATE(TYPE='TRANSIENT', END=0.1, DTOUT=0.1)\n")
    res = pysolver.load(path).run()
    assert res.request(1)[0, 0] == pytest.approx(
        float(surface_reference("AKISPL", np.array([0.7]), np.array([1.1]))[0]), abs=1e-14)


TEXT = "(the element's text)"


@pytest.mark.parametrize("table, request_, attribute, words", [
    ("0 1 0 1 1 2 2 2 3 3", "", TEXT, "its 2 z values, then rows of an x value and 2 y"),
    ("1 0 0 1 1 1 2 2 2 3 3 3 4 4", "", TEXT, "z must be strictly increasing"),
    ("0 1 0 1 1 1 2 2 2 3 3 3 4 4", 'expr1="CUBSPL(DX(20),0,7,1)"', "expr1",
     "no derivative order on a surface"),
])
def test_bad_surfaces_are_deck_errors(table, request_, attribute, words):
    with pytest.raises(DeckError, match=words) as err:
        pysolver.loads(deck(f'<Post_Request id="1" {request_}/>' if request_ else "",
                            'num_z="2"', table))
    assert err.value.attribute == attribute
