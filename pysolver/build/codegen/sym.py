"""Scalar expression graphs with exact symbolic derivatives, for generated C.

A :class:`Graph` holds hash-consed nodes (one node per distinct operation on distinct
operands, so common subexpressions exist once) in creation order, which is a topological order.
Node ids are ints. Constructors fold constants and drop the identities x + 0, x * 1 and x * 0,
so derivatives that are structurally zero vanish and the Jacobian's sparsity falls out of
:meth:`Graph.diff`. Semantics follow the tape interpreter (csrc/tape.c) operation by operation:
non-smooth functions differentiate by branch, STEP-family functions carry their derivative order.
"""
import math

from ... import catalogue

#: One-argument functions (the catalogue's math1, lower case): d f(x) / dx as a function of
#: (graph, x, f(x)); None for a zero derivative.
_UNARY = {
    "sin": lambda g, x, f: g.fn("cos", x),
    "cos": lambda g, x, f: g.neg(g.fn("sin", x)),
    "tan": lambda g, x, f: g.add(g.const(1.0), g.mul(f, f)),
    "exp": lambda g, x, f: f,
    "log": lambda g, x, f: g.div(g.const(1.0), x),
    "log10": lambda g, x, f: g.div(g.const(1.0), g.mul(x, g.const(math.log(10)))),
    "sqrt": lambda g, x, f: g.div(g.const(0.5), f),
    "asin": lambda g, x, f: g.div(g.const(1.0), g.fn("sqrt", g.sub(
        g.const(1.0), g.mul(x, x)))),
    "acos": lambda g, x, f: g.div(g.const(-1.0), g.fn("sqrt", g.sub(
        g.const(1.0), g.mul(x, x)))),
    "atan": lambda g, x, f: g.div(g.const(1.0), g.add(g.const(1.0), g.mul(x, x))),
    "sinh": lambda g, x, f: g.fn("cosh", x),
    "cosh": lambda g, x, f: g.fn("sinh", x),
    "tanh": lambda g, x, f: g.sub(g.const(1.0), g.mul(f, f)),
    "abs": lambda g, x, f: g.sgn(x),
    "aint": None,
    "anint": None,
}


class Unsupported(Exception):
    """The scene uses something the generator does not translate (the tapes run it)."""


class Graph:
    """Hash-consed scalar expression nodes.

    Leaves: ``const`` (a number), ``y`` / ``yp`` (a state entry or its rate), ``t`` (time),
    ``cj`` (the iteration matrix's coefficient), ``par`` (a number read at run time from the
    model's arrays, as (array, object, component): a sweep parameter) and ``sv`` (a stored
    Sensor_Evaluate value).
    """

    def __init__(self, limit=None):
        self.limit = limit    # most nodes (None: no limit); Unsupported beyond it
        self.op = []          # node -> operation name
        self.args = []        # node -> operand tuple (node ids, or literals for leaves)
        self.deps = []        # node -> frozenset of the variable nodes it depends on
        self._ids = {}
        self._d = {}          # (node, variable) -> derivative node
        self.zero = self.const(0.0)
        self.one = self.const(1.0)
        self.cj = self._node("cj", (0,), frozenset())

    # nodes ------------------------------------------------------------------------------
    def _node(self, op, args, deps):
        key = (op, args)
        got = self._ids.get(key)
        if got is None:
            got = len(self.op)
            if self.limit is not None and got >= self.limit:
                raise Unsupported(f"the deck is too large to generate (more than {self.limit} "
                                  "expression nodes)")
            self.op.append(op)
            self.args.append(args)
            self.deps.append(deps)
            self._ids[key] = got
        return got

    def _new(self, op, *args):
        deps = frozenset().union(*(self.deps[a] for a in args)) if args else frozenset()
        return self._node(op, args, deps)

    def const(self, v):
        v = float(v)
        return self._node("const", (v if v == v else "nan",), frozenset())

    def var(self, kind, i=0):
        """A differentiation variable: y[i], yp[i] or time (kind "t")."""
        n = len(self.op)
        node = self._node(kind, (i,), frozenset())
        if node == n:
            self.deps[node] = frozenset((node,))
        return node

    def leaf(self, kind, value):
        """A run-time number with no derivative: ``par`` ((array, object, component)) or ``sv``
        (index)."""
        return self._node(kind, (value,), frozenset())

    def value(self, a):
        """The number of a constant node, else None."""
        if self.op[a] != "const":
            return None
        v = self.args[a][0]
        return math.nan if v == "nan" else v

    # arithmetic -------------------------------------------------------------------------
    def add(self, a, b):
        va, vb = self.value(a), self.value(b)
        if va == 0.0:
            return b
        if vb == 0.0:
            return a
        if va is not None and vb is not None:
            return self.const(va + vb)
        return self._new("add", a, b)

    def sub(self, a, b):
        va, vb = self.value(a), self.value(b)
        if vb == 0.0:
            return a
        if va == 0.0:
            return self.neg(b)
        if va is not None and vb is not None:
            return self.const(va - vb)
        return self._new("sub", a, b)

    def mul(self, a, b):
        va, vb = self.value(a), self.value(b)
        if va == 0.0 or vb == 0.0:
            return self.zero
        if va == 1.0:
            return b
        if vb == 1.0:
            return a
        if va == -1.0:
            return self.neg(b)
        if vb == -1.0:
            return self.neg(a)
        if va is not None and vb is not None:
            return self.const(va * vb)
        return self._new("mul", a, b)

    def div(self, a, b):
        va, vb = self.value(a), self.value(b)
        if vb == 1.0:
            return a
        if va == 0.0 and vb != 0.0:
            return self.zero
        if va is not None and vb not in (None, 0.0):
            return self.const(va / vb)
        return self._new("div", a, b)

    def neg(self, a):
        va = self.value(a)
        if va is not None:
            return self.const(-va)
        if self.op[a] == "neg":
            return self.args[a][0]
        return self._new("neg", a)

    def lin(self, ca, a, cb=0.0, b=None):
        """ca a + cb b with number coefficients."""
        out = self.mul(self.const(ca), a)
        return out if b is None else self.add(out, self.mul(self.const(cb), b))

    def fn(self, name, a):
        if name not in _UNARY:
            raise Unsupported(f"function {name}")
        return self._node(("fn", name), (a,), self.deps[a])

    def ge(self, x, y, a, b):
        """a if x >= y else b."""
        if a == b:
            return a
        return self._new("ge", x, y, a, b)

    def if3(self, s, a, b, c):
        """a if s < 0, b if s == 0, c if s > 0 (the deck language's IF)."""
        if a == b == c:
            return a
        return self._new("if3", s, a, b, c)

    def sgn(self, x):
        """+1 for x >= 0, else -1 (the tape's sign; no derivative)."""
        return self._node("sgn", (x,), frozenset())

    def step(self, shape, k, x, bounds):
        """The k-th derivative in x of the STEP-family function `shape` (0 STEP, 1 STEP5,
        2 HAVSIN) between constant points bounds = (x0, h0, x1, h1) (node ids)."""
        if k > 3:
            raise Unsupported("a fourth derivative of a STEP function")
        return self._node(("step", shape, k), (x,) + tuple(bounds), self.deps[x])

    def atan2(self, y, x):
        return self._new("atan2", y, x)

    def user(self, call, inputs):
        """A user subroutine's value at its inputs (nodes: the system values it declared,
        then time); `call` = (cache entry, routine, result channel). Its partials in the
        inputs are the routine's own (central differences at run time, ps_user_point): the
        derivative is their sum against the inputs' exact derivatives."""
        return self._new(("user",) + tuple(call), *inputs)

    def upart(self, u, i, j=None):
        """The first partial of user node u in its input i (or the second, in i and j)."""
        if j is None:
            return self._node(("upart", i), (u,), self.deps[u])
        i, j = min(i, j), max(i, j)
        return self._node(("uhess", i, j), (u,), self.deps[u])

    def pow(self, a, b):
        return self._new("pow", a, b)

    def dot(self, u, v):
        out = self.mul(u[0], v[0])
        for i in (1, 2):
            out = self.add(out, self.mul(u[i], v[i]))
        return out

    def cross(self, u, v):
        return [self.sub(self.mul(u[1], v[2]), self.mul(u[2], v[1])),
                self.sub(self.mul(u[2], v[0]), self.mul(u[0], v[2])),
                self.sub(self.mul(u[0], v[1]), self.mul(u[1], v[0]))]

    def vsub(self, u, v):
        return [self.sub(a, b) for a, b in zip(u, v)]

    def vadd(self, u, v):
        return [self.add(a, b) for a, b in zip(u, v)]

    # derivatives ------------------------------------------------------------------------
    def diff(self, a, v):
        """d a / d v for a variable node v (exact, memoized)."""
        if v not in self.deps[a]:
            return self.zero
        if a == v:
            return self.one
        key = (a, v)
        got = self._d.get(key)
        if got is None:
            got = self._diff(a, v)
            self._d[key] = got
        return got

    def _diff(self, a, v):
        op, args, d = self.op[a], self.args[a], self.diff
        if op == "add":
            return self.add(d(args[0], v), d(args[1], v))
        if op == "sub":
            return self.sub(d(args[0], v), d(args[1], v))
        if op == "neg":
            return self.neg(d(args[0], v))
        if op == "mul":
            x, y = args
            return self.add(self.mul(d(x, v), y), self.mul(x, d(y, v)))
        if op == "div":
            x, y = args
            dx, dy = d(x, v), d(y, v)
            if dy == self.zero:
                return self.div(dx, y)
            return self.div(self.sub(dx, self.mul(a, dy)), y)
        if op == "ge":
            x, y, p, q = args
            return self.ge(x, y, d(p, v), d(q, v))
        if op == "if3":
            s, p, q, r = args
            return self.if3(s, d(p, v), d(q, v), d(r, v))
        if op == "atan2":
            y, x = args
            r2 = self.add(self.mul(x, x), self.mul(y, y))
            num = self.sub(self.mul(x, d(y, v)), self.mul(y, d(x, v)))
            return self.ge(self.zero, r2, self.zero, self.div(num, r2))
        if op == "pow":
            x, y = args
            dx, dy = d(x, v), d(y, v)
            vy = self.value(y)
            if dy == self.zero:
                if vy == 0.0:
                    return self.zero
                return self.mul(self.mul(y, self.pow(x, self.sub(y, self.one))), dx)
            f1 = self.mul(y, self.pow(x, self.sub(y, self.one)))
            return self.add(self.mul(f1, dx), self.mul(self.mul(a, self.fn("log", x)), dy))
        if isinstance(op, tuple) and op[0] == "fn":
            rule = _UNARY[op[1]]
            x = args[0]
            if rule is None:
                return self.zero
            return self.mul(rule(self, x, a), d(x, v))
        if isinstance(op, tuple) and op[0] == "user":
            out = self.zero
            for i, z in enumerate(args):
                out = self.add(out, self.mul(self.upart(a, i), d(z, v)))
            return out
        if isinstance(op, tuple) and op[0] == "upart":
            u = args[0]
            out = self.zero
            for j, z in enumerate(self.args[u]):
                out = self.add(out, self.mul(self.upart(u, op[1], j), d(z, v)))
            return out
        if isinstance(op, tuple) and op[0] == "uhess":
            raise Unsupported("a third derivative of a user subroutine")
        if isinstance(op, tuple) and op[0] == "step":
            x = args[0]
            return self.mul(self._node(("step", op[1], op[2] + 1), args, self.deps[x])
                            if op[2] < 3 else self._too_deep(), d(x, v))
        raise AssertionError(op)

    def _too_deep(self):
        raise Unsupported("a fourth derivative of a STEP function")

    def gradient(self, a, variables):
        """[d a / d v for v in variables]."""
        return [self.diff(a, v) for v in variables]

    def needed(self, roots, known=()):
        """The nodes the roots depend on, ascending (a topological order), not descending into
        the `known` nodes (those already computed, whose own inputs are then computed too)."""
        seen = set()
        stack = list(roots)
        while stack:
            n = stack.pop()
            if n in seen or n in known:
                continue
            seen.add(n)
            op = self.op[n]
            if op in ("const", "y", "yp", "t", "cj", "par", "sv"):
                continue
            stack.extend(self.args[n])
        return sorted(seen)


#: One-argument functions: the C function generated code calls.
UNARY_C = {f.name.lower(): f.libm for f in catalogue.of_kind("math1")}
