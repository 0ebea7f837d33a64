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
import re

from ..errors import ExpressionError

#: Named constants.
CONSTANTS = {"PI": 3.141592653589793, "DTOR": 3.141592653589793 / 180.0,
             "RTOD": 180.0 / 3.141592653589793}

#: Functions: name -> (minimum, maximum) number of arguments.
MATH1 = ("ABS", "ACOS", "ASIN", "ATAN", "COS", "COSH", "SIN", "SINH", "TAN", "TANH", "EXP",
         "LOG", "LOG10", "SQRT", "AINT", "ANINT")
MATH2 = ("ATAN2", "MOD", "MAX", "MIN", "SIGN", "DIM")
MEASURES = {
    "DX": (1, 3), "DY": (1, 3), "DZ": (1, 3), "DM": (1, 2),
    "VX": (1, 4), "VY": (1, 4), "VZ": (1, 4), "VM": (1, 3), "VR": (1, 3),
    "ACCX": (1, 4), "ACCY": (1, 4), "ACCZ": (1, 4),
    "WX": (1, 3), "WY": (1, 3), "WZ": (1, 3),
    "AX": (1, 2), "AY": (1, 2), "AZ": (1, 2),
}
FUNCTIONS = {
    **{f: (1, 1) for f in MATH1},
    **{f: (2, 2) for f in MATH2},
    **MEASURES,
    "STEP": (5, 5), "STEP5": (5, 5), "HAVSIN": (5, 5), "IMPACT": (7, 7), "BISTOP": (8, 8),
    "IF": (4, 4), "VARVAL": (1, 1), "PFORCE": (1, 1), "SFORCE": (4, 4), "SENVAL": (1, 1),
    "MOTION": (1, 4),
}
#: Functions whose arguments are element ids (integer literals).
ID_ARGS = {**{m: "marker" for m in MEASURES}, "VARVAL": "variable", "PFORCE": "penalty",
           "SFORCE": "sforce", "SENVAL": "evaluate", "MOTION": "motion"}

_TOKEN = re.compile(r"\s*(?:(\d+\.?\d*(?:[eEdD][+-]?\d+)?|\.\d+(?:[eEdD][+-]?\d+)?)"
                    r"|([A-Za-z_][A-Za-z_0-9]*)|(\*\*|[-+*/(),:]))")


def tokenize(text):
    """Split an expression into (kind, value, column) tokens; kind is num, name or op."""
    tokens, pos = [], 0
    text = text.rstrip()
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if not m or m.end() == pos:
            col = pos + len(text[pos:]) - len(text[pos:].lstrip())
            raise ExpressionError(f"unexpected character {text[col]!r}", col)
        col = m.start(m.lastindex)
        if m.group(1):
            tokens.append(("num", float(m.group(1).replace("d", "e").replace("D", "e")), col))
        elif m.group(2):
            tokens.append(("name", m.group(2).upper(), col))
        else:
            tokens.append(("op", m.group(3), col))
        pos = m.end()
    tokens.append(("end", None, len(text)))
    return tokens


class _Parser:
    def __init__(self, text):
        self.toks = tokenize(text)
        self.i = 0

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
        if self.at("-"):
            self.take()
            return ("neg", self.unary())
        if self.at("+"):
            self.take()
            return self.unary()
        return self.power()

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
    _check(node)
    return node


def _check(node):
    tag = node[0]
    if tag == "user":                   # a user subroutine the kernel calls, on its inputs
        for a in node[3]:
            _check(a)
        return
    if tag == "name":
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
            raise ExpressionError(f"unknown function {name}", col)
        lo, hi = FUNCTIONS[name]
        if not lo <= len(args) <= hi:
            want = str(lo) if lo == hi else f"{lo} to {hi}"
            raise ExpressionError(f"{name} takes {want} arguments, got {len(args)}", col)
        if name in ID_ARGS:
            nid = len(args) if name not in ("SFORCE", "MOTION") else 1
            for a in args[:nid]:
                if a[0] != "num" or a[1] != int(a[1]) or a[1] < 0:
                    raise ExpressionError(f"{name} expects {ID_ARGS[name]} ids as integer "
                                          "literals", col)
            if name == "MOTION" and len(args) not in (1, 4):
                raise ExpressionError("MOTION(id) is the reaction along the motion's axis; "
                                      "MOTION(id, jflag, comp, rm) a component", col)
            if name in ("SFORCE", "MOTION") and len(args) == 4:
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


def references(node, out=None):
    """Return {kind: set(ids)} of the elements an expression tree refers to by id."""
    out = out if out is not None else {}
    tag = node[0]
    if tag == "user":
        for a in node[3]:
            references(a, out)
    elif tag == "neg":
        references(node[1], out)
    elif tag == "bin":
        references(node[2], out)
        references(node[3], out)
    elif tag == "call":
        name, args = node[1], node[2]
        if name in ID_ARGS:
            kind = ID_ARGS[name]
            if name in ("SFORCE", "MOTION"):
                out.setdefault(kind, set()).add(int(args[0][1]))
                if len(args) == 4 and int(args[3][1]):
                    out.setdefault("marker", set()).add(int(args[3][1]))
            else:
                for a in args:
                    if int(a[1]) != 0 or kind != "marker":
                        out.setdefault(kind, set()).add(int(a[1]))
        else:
            for a in args:
                references(a, out)
    return out
