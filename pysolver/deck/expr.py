"""The MotionSolve/Adams expression language: tokenizer, parser and function table.

Grammar (case-insensitive, FORTRAN-77 precedence)::

    expr    := term (('+' | '-') term)*
    term    := unary (('*' | '/') unary)*
    unary   := ('-' | '+') unary | power
    power   := primary ('**' unary)?          # right-associative, binds tighter than unary minus
    primary := NUMBER | NAME | NAME '(' args ')' | '(' expr ')'
    args    := expr (',' expr)*  |  expr ':' expr ',' expr ',' expr     # the latter for IF

so ``-2**2 == -4`` and ``2**3**2 == 512``. The parser produces a small tree of tuples:
``('num', value)``, ``('name', NAME, col)``, ``('neg', x)``, ``('bin', op, a, b)``,
``('call', NAME, [args], col)``. Semantic checks (function names, argument counts, ids) are
done here too, so that a deck fails at load time and not during a run.
"""
import math

from .. import catalogue
from ..errors import ExpressionError
from . import series
from .tokens import tokenize

#: Named constants.
CONSTANTS = {name: f.py() for name, f in catalogue.NAMES.items() if f.py is not None}

#: Functions (pysolver/catalogue.py): name -> (minimum, maximum) number of arguments.
MATH1 = tuple(f.name for f in catalogue.of_kind("math1"))
MATH2 = tuple(f.name for f in catalogue.of_kind("math2"))
MEASURES = {f.name: f.arity for f in catalogue.of_kind("measure")}
FUNCTIONS = {name: f.arity for name, f in catalogue.FUNCTIONS.items()}
#: Functions whose arguments are element ids (integer literals): the kind of the first.
ID_ARGS = {name: f.ids[0] for name, f in catalogue.FUNCTIONS.items() if f.ids}
#: Functions and names of MotionSolve or Adams that pysolver does not support, and why.
REFUSED, REFUSED_NAMES = catalogue.REFUSED, catalogue.REFUSED_NAMES

#: The interpolation functions: x and z are expressions, the spline id and order literals.
SPLINES = ("AKISPL", "CUBSPL", "LINSPL", "QUISPL")

#: Deepest nesting an expression may have: parentheses, function calls, unary signs and the
#: terms of one sum or product each add a level (the trees are walked recursively).
MAX_DEPTH = 120


def _too_deep(col):
    return ExpressionError(f"the expression nests deeper than {MAX_DEPTH} levels (parentheses, "
                           "calls, signs and the terms of one sum or product each count); "
                           "split it with Reference_Variables", col)


class _Parser:
    def __init__(self, text):
        self.toks = tokenize(text)
        self.i = 0
        self.depth = 0

    def nest(self):
        """Enter one level of recursion; ExpressionError past MAX_DEPTH."""
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise _too_deep(self.peek()[2])

    def peek(self):
        return self.toks[self.i]

    def take(self):
        tok = self.toks[self.i]
        self.i += 1
        return tok

    def expect(self, op):
        kind, val, col = self.take()
        if kind != "op" or val != op:
            found = "end of expression" if kind == "end" else repr(val)
            raise ExpressionError(f"expected '{op}' but found {found}", col)

    def at(self, op):
        kind, val, _ = self.peek()
        return kind == "op" and val == op

    def expr(self):
        node = self.term()
        while self.at("+") or self.at("-"):
            op = self.take()[1]
            node = ("bin", op, node, self.term())
        return node

    def term(self):
        node = self.unary()
        while self.at("*") or self.at("/"):
            op = self.take()[1]
            node = ("bin", op, node, self.unary())
        return node

    def unary(self):
        self.nest()
        try:
            if self.at("-"):
                self.take()
                return ("neg", self.unary())
            if self.at("+"):
                self.take()
                return self.unary()
            return self.power()
        finally:
            self.depth -= 1

    def power(self):
        base = self.primary()
        if self.at("**"):
            self.take()
            return ("bin", "**", base, self.unary())
        return base

    def primary(self):
        kind, val, col = self.take()
        if kind == "num":
            return ("num", val)
        if kind == "name":
            if self.at("("):
                self.take()
                args = self.args(val)
                self.expect(")")
                return ("call", val, args, col)
            return ("name", val, col)
        if kind == "op" and val == "(":
            node = self.expr()
            self.expect(")")
            return node
        found = "end of expression" if kind == "end" else repr(val)
        raise ExpressionError(f"expected a number, name or '(' but found {found}", col)

    def args(self, fname):
        if self.at(")"):
            return []
        args = [self.expr()]
        if fname == "IF":
            self.expect(":")
            args.append(self.expr())
        while self.at(","):
            self.take()
            args.append(self.expr())
        return args


def parse(text):
    """Parse and check an expression; return its tree.

    Raises
    ------
    ExpressionError
        On a syntax error, an unknown name or function, a wrong argument count, or an id
        argument that is not an integer literal.
    """
    if text is None or not str(text).strip():
        raise ExpressionError("the expression is empty")
    p = _Parser(str(text))
    node = p.expr()
    kind, val, col = p.peek()
    if kind != "end":
        raise ExpressionError(f"unexpected {val!r} after the end of the expression", col)
    if depth(node) > MAX_DEPTH:
        raise _too_deep(0)
    _check(node)
    _constant_parts(node)
    expanded = series.expand(node)
    if expanded is not node:            # a series of constants may overflow
        _constant_parts(expanded)
    return expanded


def _fn(name):
    """The value of a math function of the language on constant arguments (NumPy's rules)."""
    f = catalogue.FUNCTIONS.get(name)
    return f.py if f is not None and f.kind in ("math1", "math2") else None


def _constant_parts(tree):
    """ExpressionError when a part of the tree that depends on nothing (numbers, constants
    and math functions of them) evaluates to infinity or NaN: 1/0, 10**400, LOG(-1), ..."""
    import numpy as np
    ops = {op: f.py for op, f in catalogue.ARITHMETIC.items()}
    values = {}
    order, stack = [], [tree]
    while stack:                        # post-order without recursion
        node = stack.pop()
        order.append(node)
        if node[0] == "neg":
            stack.append(node[1])
        elif node[0] == "bin":
            stack += [node[2], node[3]]
        elif node[0] == "call" and node[1] not in ID_ARGS:
            stack += list(node[2])
    with np.errstate(all="ignore"):
        for node in reversed(order):
            tag, v = node[0], None
            if tag == "num":
                v = node[1]
            elif tag == "name" and node[1] in CONSTANTS:
                v = CONSTANTS[node[1]]
            elif tag == "neg" and id(node[1]) in values:
                v = -values[id(node[1])]
            elif tag == "bin" and id(node[2]) in values and id(node[3]) in values:
                v = float(ops[node[1]](np.float64(values[id(node[2])]),
                                       np.float64(values[id(node[3])])))
            elif tag == "call" and _fn(node[1]) is not None and \
                    all(id(a) in values for a in node[2]):
                v = float(_fn(node[1])(*[np.float64(values[id(a)]) for a in node[2]]))
            if v is None:
                continue
            if not math.isfinite(v):
                raise ExpressionError(f"{unparse(node)} is {v} (a constant part of the "
                                      "expression)", node[3] if tag == "call" else 0)
            values[id(node)] = v
    for node in order:
        if node[0] == "call" and node[1] in _RANGES:
            _check_ranges(node, [values.get(id(a)) for a in node[2]])


#: The arguments of the smoothing and contact functions that must lie in a range, checked
#: when they are constants (Adams' and MotionSolve's function pages): (index, name, test,
#: the range, what the argument is).
_NONNEG, _POS = (lambda v: v >= 0, ">= 0"), (lambda v: v > 0, "> 0")
_IMPACT = (("k", _NONNEG, "the stiffness"), ("e", _POS, "the exponent"),
           ("cmax", _NONNEG, "the largest damping coefficient"),
           ("d", _POS, "the penetration of full damping"))
_RANGES = {"IMPACT": tuple((3 + k,) + r for k, r in enumerate(_IMPACT)),
           "BISTOP": tuple((4 + k,) + r for k, r in enumerate(_IMPACT)),
           **dict.fromkeys(catalogue.STEP_SHAPES, ())}


def _check_ranges(node, vals):
    """ExpressionError when a constant argument of a STEP-family, IMPACT or BISTOP call is
    out of its range: x1 = x0 (a jump the step cannot fit), k < 0, e <= 0, cmax < 0, d <= 0,
    BISTOP's x1 >= x2."""
    name, col = node[1], node[3]
    if name in catalogue.STEP_SHAPES and (vals[1] is not None and vals[1] == vals[3]
                                          or unparse(node[2][1]) == unparse(node[2][3])):
        same = f"both {vals[1]:g}" if vals[1] is not None else "the same expression"
        raise ExpressionError(f"{name}(x, x0, h0, x1, h1): x0 and x1 are {same}; x1 must "
                              f"differ from x0 (equal values are a jump, which {name} cannot "
                              "fit)", col)
    if name == "BISTOP" and None not in vals[2:4] and not vals[2] < vals[3]:
        raise ExpressionError(f"BISTOP: x1 = {vals[2]:g} and x2 = {vals[3]:g}; expected x1 "
                              "< x2 (the lower and upper bounds of the gap)", col)
    for k, arg, (ok, rule), what in _RANGES[name]:
        if vals[k] is not None and not ok(vals[k]):
            raise ExpressionError(f"{name}: {arg} = {vals[k]:g}; expected {arg} {rule} "
                                  f"({what})", col)


def depth(node):
    """Depth of a tree, computed without recursion."""
    deepest, stack = 0, [(node, 1)]
    while stack:
        n, d = stack.pop()
        deepest = max(deepest, d)
        tag = n[0]
        if tag == "neg":
            stack.append((n[1], d + 1))
        elif tag == "bin":
            stack += [(n[2], d + 1), (n[3], d + 1)]
        elif tag == "call":
            stack += [(a, d + 1) for a in n[2]]
        elif tag == "user":
            stack += [(a, d + 1) for a in n[3]]
    return deepest


def _check(node):
    tag = node[0]
    if tag == "user":                   # a user subroutine the kernel calls, on its inputs
        for a in node[3]:
            _check(a)
        return
    if tag == "name":
        if node[1] in REFUSED_NAMES:
            raise ExpressionError(f"{node[1]} is not supported: {REFUSED_NAMES[node[1]]}",
                                  node[2])
        if node[1] != "TIME" and node[1] not in CONSTANTS:
            raise ExpressionError(f"unknown name {node[1]!r} (known: TIME, PI, DTOR, RTOD)",
                                  node[2])
    elif tag == "neg":
        _check(node[1])
    elif tag == "bin":
        _check(node[2])
        _check(node[3])
    elif tag == "call":
        name, args, col = node[1], node[2], node[3]
        if name not in FUNCTIONS:
            if name in REFUSED:
                raise ExpressionError(f"{name} is not supported: {REFUSED[name]}", col)
            raise ExpressionError(f"unknown function {name}", col)
        lo, hi = FUNCTIONS[name]
        if not lo <= len(args) <= hi:
            want = str(lo) if lo == hi else f"{lo} to {hi}"
            raise ExpressionError(f"{name} takes {want} arguments, got {len(args)}", col)
        if name in SPLINES:
            _check(args[0])
            _check(args[1])
            for a, what in zip(args[2:], ("spline id", "derivative order (0, 1 or 2)")):
                if a[0] != "num" or a[1] != int(a[1]) or a[1] < 0:
                    raise ExpressionError(f"{name}(x, z, id[, order]) expects the {what} as "
                                          "an integer literal", col)
            if len(args) == 4 and args[3][1] > 2:
                raise ExpressionError(f"{name}: the derivative order is 0, 1 or 2", col)
            return
        if name in ID_ARGS:
            elements = ("SFORCE", "MOTION", "JOINT", "JPRIM", "SPDP", "BUSH", "FIELD", "BEAM")
            nid = len(args) if name not in elements else 1
            for a in args[:nid]:
                if a[0] != "num" or a[1] != int(a[1]) or a[1] < 0:
                    raise ExpressionError(f"{name} expects {ID_ARGS[name]} ids as integer "
                                          "literals", col)
            if name == "ORIENT" and not (1 <= args[0][1] <= 12 and 1 <= args[1][1] <= 3 or
                                         args[0][1] == 27 and 1 <= args[1][1] <= 4):
                raise ExpressionError("ORIENT(system, comp, i[, j]): pysolver computes systems "
                                      "1..12 (body-fixed angles, comp 1..3) and 27 (Euler "
                                      "parameters, comp 1..4)", col)
            if name == "MOTION" and len(args) not in (1, 4):
                raise ExpressionError("MOTION(id) is the reaction along the motion's axis; "
                                      "MOTION(id, jflag, comp, rm) a component", col)
            if name in elements and len(args) == 4:
                for a, what in zip(args[1:], ("jflag (0 or 1)", "comp (1..8)", "rm marker id")):
                    if a[0] != "num" or a[1] != int(a[1]):
                        raise ExpressionError(f"SFORCE expects {what} as an integer literal", col)
                if args[1][1] not in (0, 1) or not 1 <= args[2][1] <= 8:
                    raise ExpressionError(f"{name}(id, jflag, comp, rm): jflag is 0 or 1 and "
                                          "comp is 1..8", col)
        else:
            for a in args:
                _check(a)


def unparse(node):
    """The text of an expression tree (fully parenthesised binary operations)."""
    tag = node[0]
    if tag == "num":
        v = node[1]
        return repr(int(v)) if v == int(v) and abs(v) < 1e15 else repr(v)
    if tag == "name":
        return node[1]
    if tag == "user":
        return f"USER#{node[1]}[{node[2]}]({', '.join(unparse(a) for a in node[3])})"
    if tag == "neg":
        return f"-({unparse(node[1])})"
    if tag == "bin":
        return f"({unparse(node[2])} {node[1]} {unparse(node[3])})"
    name, args = node[1], node[2]
    if name == "IF":
        return f"IF({unparse(args[0])}: {', '.join(unparse(a) for a in args[1:])})"
    return f"{name}({', '.join(unparse(a) for a in args)})"


def nodes(tree):
    """Yield every node of an expression tree (depth first, without recursion)."""
    stack = [tree]
    while stack:
        node = stack.pop()
        yield node
        tag = node[0]
        if tag == "user":
            stack.extend(node[3])
        elif tag == "neg":
            stack.append(node[1])
        elif tag == "bin":
            stack.extend(node[2:4])
        elif tag == "call":
            stack.extend(node[2])


def references(tree, out=None):
    """Return {kind: set(ids)} of the elements an expression tree refers to by id."""
    out = out if out is not None else {}
    for node in nodes(tree):
        if node[0] != "call" or node[1] not in ID_ARGS:
            continue
        for a, kind in zip(node[2], catalogue.FUNCTIONS[node[1]].ids):
            # marker 0 is the global frame, body 0 every body; any other id names an element
            if kind is not None and (int(a[1]) != 0 or kind not in ("marker", "body")):
                out.setdefault(kind, set()).add(int(a[1]))
    return out


#: MotionSolve's AXU..AZU: single-axis angles through every turn (tracked; AX..AZ are wrapped).
TRACKED_ANGLES = ("AXU", "AYU", "AZU")


def call(name, *ids):
    """The tree of function `name` of element ids (a measure of markers: ``call("AZ", i, j)``),
    as the parser makes it."""
    return ("call", name, [("num", float(i)) for i in ids], 0)
