"""Functions of the expression language that a parsed expression writes as other operations.

SHF, POLY, CHEBY, FORCOS and FORSIN are closed forms of arithmetic, SIN and COS, so the
parser replaces each call by its operations (:func:`expand`): the kernel, its exact
derivatives (hyper-duals on the tapes, symbolic in generated C) and every check after the
parser see only operations they already know. Adams' JPRIM is JOINT under another name.
The definitions, as Adams Solver's and MotionSolve's function pages give them (docs/
deck-language.md, "Series and harmonic functions", cites them), with u = x - x0:

- ``SHF(x, x0, a, w, phi, b) = a SIN(w u - phi) + b``;
- ``POLY(x, x0, a0, ..., an) = a0 + a1 u + ... + an u^n``;
- ``CHEBY(x, x0, a0, ..., an) = a0 T0(u) + ... + an Tn(u)``, T0 = 1, T1 = u,
  Tj = 2 u Tj-1 - Tj-2 (Chebyshev polynomials of the first kind);
- ``FORCOS(x, x0, w, a0, ..., an) = a0 + a1 COS(w u) + ... + an COS(n w u)``;
- ``FORSIN(x, x0, w, a0, ..., an) = a0 + a1 SIN(w u) + ... + an SIN(n w u)``;

at most 31 coefficients a0..a30. A term whose coefficient is the number 0 is left out; the
terms are summed as a balanced tree (an expression nests a few levels deeper, not one per
term); u^j is ``u ** j``; Tj comes from T(2m) = 2 T(m)^2 - 1 and T(2m+1) = 2 T(m) T(m+1) - u,
which keep each Tj as accurate as the recurrence and its tree a few levels deep.
"""
from .. import catalogue

#: The names :func:`expand` replaces.
EXPANDED = frozenset(f.name for f in catalogue.of_kind("expanded"))

_ZERO = ("num", 0.0)


def _bin(op, a, b):
    return ("bin", op, a, b)


def _times(c, term):
    """c * term, or term alone when c is the number 1."""
    return term if c == ("num", 1.0) else _bin("*", c, term)


def _total(terms):
    """The sum of a list of trees as a balanced tree (the number 0 when it is empty)."""
    if not terms:
        return _ZERO
    while len(terms) > 1:
        terms = [_bin("+", terms[k], terms[k + 1]) if k + 1 < len(terms) else terms[k]
                 for k in range(0, len(terms), 2)]
    return terms[0]


def _series(a0, coefficients, basis):
    """a0 + the sum of a_j basis(j) over j = 1.., leaving out the terms whose a_j is 0."""
    terms = [] if a0 == _ZERO else [a0]
    terms += [_times(a, basis(j)) for j, a in enumerate(coefficients, 1) if a != _ZERO]
    return _total(terms)


def _chebyshev(u):
    """T(j), the Chebyshev polynomial of the first kind of degree j >= 1 in u."""
    memo = {1: u}

    def T(j):
        if j not in memo:
            m = j // 2
            if j % 2:
                memo[j] = _bin("-", _bin("*", ("num", 2.0), _bin("*", T(m), T(m + 1))), u)
            else:
                memo[j] = _bin("-", _bin("*", ("num", 2.0), _bin("*", T(m), T(m))),
                               ("num", 1.0))
        return memo[j]
    return T


def _call(name, args, col):
    """The operations of one call of an expanded function (its arguments expanded)."""
    if name == "JPRIM":
        return ("call", "JOINT", args, col)
    x, x0 = args[0], args[1]
    u = x if x0 == _ZERO else _bin("-", x, x0)
    if name == "SHF":
        a, w, phi, b = args[2:]
        return _bin("+", _bin("*", a, ("call", "SIN", [_bin("-", _bin("*", w, u), phi)],
                                       col)), b)
    if name == "POLY":
        return _series(args[2], args[3:], lambda j: u if j == 1 else _bin("**", u, ("num",
                                                                                     float(j))))
    if name == "CHEBY":
        return _series(args[2], args[3:], _chebyshev(u))
    wu = _bin("*", args[2], u)
    trig = "COS" if name == "FORCOS" else "SIN"
    return _series(args[3], args[4:], lambda j: ("call", trig, [
        wu if j == 1 else _bin("*", ("num", float(j)), wu)], col))


def expand(node):
    """`node` (a parsed, checked tree) with every call of an :data:`EXPANDED` function
    replaced by its operations; the same object when it has none."""
    tag = node[0]
    if tag == "neg":
        inner = expand(node[1])
        return node if inner is node[1] else ("neg", inner)
    if tag == "bin":
        a, b = expand(node[2]), expand(node[3])
        return node if a is node[2] and b is node[3] else ("bin", node[1], a, b)
    if tag != "call":
        return node
    name, args, col = node[1], node[2], node[3]
    new = [expand(a) for a in args]
    if name in EXPANDED:
        return _call(name, new, col)
    return node if all(n is a for n, a in zip(new, args)) else ("call", name, new, col)
