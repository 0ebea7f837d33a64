"""The expression language's tokens: numbers (Adams' rule, docs/adams.md "Numbers": a D
after a number is degrees, a D with an exponent's digits the Fortran exponent), names and
operators. deck.expr parses them; deck.adams_writer writes functions token by token."""
import math
import re

from ..errors import ExpressionError

#: A number by Adams' rule (docs/adams.md "Numbers"): an E exponent (then a D: degrees), a
#: Fortran D exponent before no letter, digit or point, or a D for degrees before none or "(".
_NUMBER = (r"(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+(?:[dD](?![\w(]))?|[dD][+-]?\d+(?![\w.])"
           r"|[dD](?![\w(]))?")
_TOKEN = re.compile(rf"\s*(?:({_NUMBER})"
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
            word = m.group(1).replace("d", "D")
            value = math.radians(float(word[:-1])) if word[-1] == "D" else \
                float(word.replace("D", "e"))
            if not math.isfinite(value):
                raise ExpressionError(f"the number {m.group(1)} is too large for a double", col)
            tokens.append(("num", value, col))
        elif m.group(2):
            tokens.append(("name", m.group(2).upper(), col))
        else:
            tokens.append(("op", m.group(3), col))
        pos = m.end()
    tokens.append(("end", None, len(text)))
    return tokens
