"""Reference_Spline and the interpolation functions AKISPL, CUBSPL, LINSPL, QUISPL.

A spline is an x-y curve (``Reference_Spline``: x-y pairs as the element's text, or the
``SPLINE`` statement's X and Y lists; x strictly increasing). Each function's curve is a
piecewise polynomial whose pieces this module computes with SciPy, at the same knots:

- LINSPL: the broken line (scipy.interpolate.make_interp_spline, k = 1): value continuous,
  first derivative jumps at the knots, second derivative 0 (at least 2 points);
- CUBSPL: the natural cubic spline, its second derivative 0 at the first and last knots
  (scipy.interpolate.CubicSpline, bc_type="natural"; C2; at least 4), as MotionSolve's
  Reference_Spline page says ("The Cubic fitting algorithm ensures a much smoother fit by
  utilizing natural splines");
- AKISPL: scipy.interpolate.Akima1DInterpolator (Akima's local cubic: C1, the second
  derivative jumps at the knots; at least 4);
- QUISPL: the natural quintic spline of Herriot and Reinsch (ACM Algorithm 507, which
  MotionSolve's QUISPL page cites): C4, its third and fourth derivatives 0 at the first and
  last knots (make_interp_spline, k = 5, with those end conditions; at least 6 points, as
  MotionSolve asks).

Outside the data (Adams' rule): the parabola through the first (last) three points, or with
``linear_extrap`` the line through the first (last) two. The compiler lowers a call to a
balanced tree of IF instructions that picks the piece and a Horner polynomial in x - knot,
so values and derivatives (of any order the tape takes) are exact, on the tapes and in
generated C alike. ``order`` 0, 1, 2 is the value, the first or the second derivative.

A surface (z values, one curve per z) is the function's curve in x at each z value,
interpolated linearly in z between the two curves around z (Adams' AKISPL and CUBSPL on
surfaces: cubic in x, linear in z); below the first z value and above the last, the line
through the two nearest curves continues (one curve: constant in z). No derivative order
on surfaces (as in Adams); the kernel's own derivatives in x and z are exact.
"""
import numpy as np

from ..deck.splinedata import FEWEST

NAMES = tuple(FEWEST)
#: QUISPL's end conditions: the third and fourth derivatives vanish (a natural quintic).
NATURAL = [(3, 0.0), (4, 0.0)]


def pieces(spline, method):
    """(knots, [coefficients per piece, ascending powers of x - its anchor]): the piece left
    of knots[0] anchored at knots[0], the interior pieces at their left knots, the piece from
    the last knot on at it."""
    from scipy.interpolate import Akima1DInterpolator, CubicSpline, PPoly, make_interp_spline
    x, y = np.asarray(spline.x, float), np.asarray(spline.y, float)
    if method == "CUBSPL":
        pp = CubicSpline(x, y, bc_type="natural")
    elif method == "AKISPL":
        pp = Akima1DInterpolator(x, y)
    elif method == "LINSPL":
        pp = PPoly.from_spline(make_interp_spline(x, y, k=1))
    else:
        pp = PPoly.from_spline(make_interp_spline(x, y, k=5, bc_type=(NATURAL, NATURAL)))
    inner = []
    for k in range(len(x) - 1):
        # PPoly's breakpoints may repeat knots (from a B-spline): take the piece at x[k]
        j = int(np.searchsorted(pp.x, x[k], side="right") - 1)
        c = pp.c[::-1, j]                       # ascending powers of (t - pp.x[j])
        inner.append(_shift(c, x[k] - pp.x[j]))
    return x, [_end(x[:3], y[:3], x[0], spline.linear_extrap, 0)] + inner + \
        [_end(x[-3:], y[-3:], x[-1], spline.linear_extrap, -1)]


def _shift(c, s):
    """Coefficients of p(t + s) from those of p(t) (ascending)."""
    out = np.zeros(len(c))
    for j, cj in enumerate(c):
        for i in range(j + 1):
            out[i] += cj * _binom(j, i) * s ** (j - i)
    return out


def _binom(n, k):
    from math import comb
    return comb(n, k)


def _end(xs, ys, anchor, linear, side):
    """The extrapolating polynomial anchored at `anchor`: the line through the two points
    nearest the end, or the parabola through three (two when there are only two)."""
    if linear or len(xs) < 3:
        xs, ys = (xs[:2], ys[:2]) if side == 0 else (xs[-2:], ys[-2:])
    c = np.polyfit(np.asarray(xs) - anchor, ys, len(xs) - 1)[::-1]
    return c


def derivative(c, order):
    """Coefficients of the `order`-th derivative (ascending)."""
    c = np.asarray(c, float)
    for _ in range(order):
        c = c[1:] * np.arange(1, len(c)) if len(c) > 1 else np.zeros(1)
    return c


def lower_spline(comp, tape, name, x, spline, order):
    """Slot of `name` (AKISPL, ...) of `spline` at the slot x, derivative `order`."""
    from .bindings import lib
    knots, polys = pieces(spline, name)
    polys = [derivative(c, order) for c in polys]

    def leaf(p):
        anchor = knots[0] if p == 0 else knots[p - 1]
        t = tape.op(lib.PS_OP_SUB, x, tape.const(float(anchor)))
        c = polys[p]
        v = tape.const(float(c[-1]))
        for cj in c[-2::-1]:
            v = tape.op(lib.PS_OP_ADD, tape.op(lib.PS_OP_MUL, v, t), tape.const(float(cj)))
        return v

    def select(lo, hi):                     # pieces lo..hi; piece p is [knots[p-1], knots[p])
        if lo == hi:
            return leaf(lo)
        mid = (lo + hi + 1) // 2
        right = select(mid, hi)
        return tape.op(lib.PS_OP_IF, tape.op(lib.PS_OP_SUB, x, tape.const(float(knots[mid - 1]))),
                       select(lo, mid - 1), right, right)
    return select(0, len(polys) - 1)


def lower_surface(comp, tape, name, x, z, spline):
    """Slot of `name` on the surface `spline` at the slots x and z."""
    from .bindings import lib
    zs = spline.z
    curves = [lower_spline(comp, tape, name, x, spline.curve(k), 0) for k in range(len(zs))]
    if len(zs) == 1:
        return curves[0]

    def blend(k):                           # the line through curves k and k + 1
        s = tape.op(lib.PS_OP_MUL, tape.op(lib.PS_OP_SUB, z, tape.const(float(zs[k]))),
                    tape.const(1.0 / (zs[k + 1] - zs[k])))
        return tape.op(lib.PS_OP_ADD, curves[k], tape.op(
            lib.PS_OP_MUL, s, tape.op(lib.PS_OP_SUB, curves[k + 1], curves[k])))

    def select(lo, hi):                     # segment k serves z up to zs[k + 1]
        if lo == hi:
            return blend(lo)
        mid = (lo + hi + 1) // 2
        right = select(mid, hi)
        return tape.op(lib.PS_OP_IF, tape.op(lib.PS_OP_SUB, z, tape.const(float(zs[mid]))),
                       select(lo, mid - 1), right, right)
    return select(0, len(zs) - 2)
