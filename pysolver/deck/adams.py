"""Adams datasets (.adm) and command files (.acf), read into pysolver's statements.

Longer than 420 lines because it is a language: the lexer (title line, ``!`` comments,
continuation lines, ``\\``-separated functions, ``D`` for degrees and D exponents), keyword
abbreviation and the placement of parts and markers; each statement then becomes the call of
its pysolver.deck.msolve statement function (the translations:
pysolver/deck/adams_statements.py), so an .adm deck builds the same elements as the XML and
Python forms (../shared/reference/elements.md sections 8.3, 9; docs/adams.md says what is
read and what is refused).
"""
import difflib
import os
import re

import numpy as np

from ..errors import DeckError, DeckWarning, warn
from ..records import Placement
from ..rotations import rot_313, rot_321, rot_from_e
from . import msolve
from .adams_statements import COMMANDS, DATASET, EXTENSIONS, PRIMARY, SHARED

#: The comment line after END that marks the commands of a command file (load("x.acf")).
COMMANDS_MARK = "!pysolver: commands of"
#: The comment line before it that keeps the command file's output name (its second line).
OUTPUT_MARK = "!pysolver: output name"

#: Statements that would change the dynamics and that pysolver does not model: a DeckError.
UNSUPPORTED = ("CONTACT", "FLEX_BODY", "DIFF", "LSE", "GSE", "TFSISO",
               "NFORCE", "CVCV", "PTCV", "CURVE", "SURFACE", "FRICTION", "GEAR", "MFORCE",
               "FEMDATA", "ARRAY", "STRING", "MATRIX", "PSTATE", "EXTERNAL_SYSTEM",
               "COUSUB", "CLEARANCE", "ENVIRONMENT", "USER", "SECTION", "FE_PART", "FE_NODE",
               "FE_LOAD")
#: Statements that only shape output or diagnostics: read and set aside with a DeckWarning.
SET_ASIDE = ("LIST", "NOLIST", "DEBUG", "MREQUEST", "PINPUT", "POUTPUT", "FEMDATA_OUTPUT",
             "PREFERENCES", "FILE", "SHOW", "INFO", "HELP", "MENU", "RETURN", "TIME",
             "MATERIAL", "LSOLVER")
#: Why a statement of SET_ASIDE is set aside, where it does not only shape output.
_ASIDE_WHY = {"LSOLVER": "only chooses Adams' linear solver (pysolver chooses its own, "
                         "dense or sparse LU)",
              "PINPUT": "only names the variables that are a plant's inputs for Adams' "
                        "linearization and control co-simulation",
              "POUTPUT": "only names the variables that are a plant's outputs for Adams' "
                         "linearization and control co-simulation"}
#: Statements (and commands) that only set the tolerances of an Adams analysis pysolver does
#: not run as Adams does: their keywords checked, then set aside with a DeckWarning saying why.
SETTINGS_ONLY = {
    "KINEMATICS": (("AERROR", "ALIMIT", "AMAXIT", "APATTERN", "ERROR", "HMAX", "MAXIT",
                    "PATTERN", "TLIMIT"),
                   "only sets the tolerances of Adams' kinematic analysis; pysolver runs "
                   "SIMULATE/KINEMATICS as a transient, with INTEGRATOR's settings "
                   "(docs/adams.md, \"Commands\")"),
    "IC": (("AERROR", "ALIMIT", "AMAXIT", "APATTERN", "ERROR", "MAXIT", "PATTERN", "TLIMIT",
            "VERROR"),
           "only sets the tolerances of Adams' initial-conditions analysis; pysolver "
           "assembles the initial conditions to its own tolerances (docs/deck-language.md, "
           "\"Initial positions\")"),
}
#: Commands that change the model or run what pysolver does not: a DeckError.
_OTHER_COMMANDS = ("DEACTIVATE", "ACTIVATE", "LINEAR", "SAVE", "RELOAD", "CONTROL", "DEBUG",
                   "BUSHING", "SHOW", "SWITCH")
#: Commands that change the dataset's settings statement of the same name (settings_command).
_SETTINGS = ("INTEGRATOR", "EQUILIBRIUM")
#: Statements read quietly and not used (output settings; graphics are kept).
QUIET = ("OUTPUT", "RESULTS")

#: A number of an argument list (docs/adams.md, "Numbers"): a mantissa, then an E exponent
#: (and a D for degrees), a Fortran D exponent (1.0D-3, 1.0D+3, 1.0D3), or a D for degrees.
_NUMBER = re.compile(r"^(?P<mant>[+-]?(?:\d+\.?\d*|\.\d+))(?:(?P<exp>[eE][+-]?\d+)(?P<edeg>[dD])?"
                     r"|(?P<dexp>[dD][+-]?\d+)|(?P<deg>[dD]))?$")
#: The same in a function, where the number ends at any character that cannot continue it:
#: a D exponent's digits are followed by no letter, digit or point (30D+10D is two angles),
#: a D for degrees by no letter, digit or parenthesis.
_FUNCTION_NUMBER = re.compile(r"(?<![\w.])(?P<mant>\d+\.?\d*|\.\d+)"
                              r"(?:(?P<exp>[eE][+-]?\d+)(?P<edeg>[dD](?![\w(]))?"
                              r"|(?P<dexp>[dD][+-]?\d+)(?![\w.])|(?P<deg>[dD])(?![\w(]))?")
_VIEW_NAME = re.compile(r"""adams_view_name\s*=\s*(['"])(.*?)\1""", re.I)
_SEP = "\x00"            # a continuation line's leading comma, before arguments are split


class _Statement:
    """One statement: its name, id, arguments [(keyword, value text, is_function, line)],
    first line and the label Adams View left in a comment above it."""

    def __init__(self, name, ident, args, line, label):
        self.name, self.id, self.args, self.line, self.label = name, ident, args, line, label


def _strip_comment(text):
    """The line without its ``!`` comment (outside quotes), and the comment."""
    quote = None
    for k, ch in enumerate(text):
        if quote:
            quote = None if ch == quote else quote
        elif ch in "\"'":
            quote = ch
        elif ch == "!":
            return text[:k], text[k + 1:]
    return text, ""


def statements(text, file, first=1, title=True):
    """The statements of dataset or command text: a title line (when `title`), then
    statements whose continuation lines start with a comma; `first` is the line number of
    the text's first line."""
    lines = text.splitlines()
    out, cur, label, joined = [], None, "", False
    for k, raw in enumerate(lines[1 if title else 0:], first + (1 if title else 0)):
        body, comment = _strip_comment(raw)
        found = _VIEW_NAME.search(comment)
        if found:
            label = found.group(2)
        if not body.strip():
            continue
        if title and not joined and body.strip().upper() == "END":
            out.append(([(k, body)], label))        # a dataset's end: nothing after it is read
            break
        ampersand = body.rstrip().endswith("&")     # the command language's continuation
        if ampersand:
            body = body.rstrip()[:-1]
        if body.lstrip().startswith(",") or joined:
            if cur is None:
                raise DeckError("a continuation line (starting with a comma) with no statement "
                                "before it", file=file, line=k)
            text = body.lstrip()
            cur[0].append((k, _SEP + (text[1:] if text.startswith(",") else text)))
        else:
            cur = ([(k, body)], label)
            label = ""
            out.append(cur)
        joined = ampersand
    return [_split(segments, lab, file) for segments, lab in out]


def _split(segments, label, file):
    """A statement's name, id and arguments from its text segments (line, text)."""
    line = segments[0][0]
    text = "".join(t for _, t in segments)
    starts = np.cumsum([0] + [len(t) for _, t in segments])

    def line_at(pos):
        return segments[int(np.searchsorted(starts, pos, side="right")) - 1][0]
    head, slash, rest = text.partition("/")
    name = head.strip().upper()
    if not re.fullmatch(r"[A-Z_][A-Z0-9_]*", name):
        raise DeckError(f"expected a statement NAME/..., got {text.strip()[:40]!r}",
                        file=file, line=line)
    offset = len(head) + len(slash)
    if not slash:                           # END, STOP: no arguments
        rest, offset = "", len(text)
    args, ident, pos = [], None, 0
    items = _items(rest)
    if items and re.fullmatch(r"\s*[+-]?\d+\s*", items[0][1].replace(_SEP, "")) \
            and "=" not in items[0][1]:
        ident = int(items[0][1].replace(_SEP, ""))
        items = items[1:]
    for pos, item, function in items:
        args.append((item, function, line_at(offset + pos)))
    return _Statement(name, ident, args, line, label)


def _items(rest):
    """Top-level items of an argument list: [(position, text, is_function_text)]; a
    function's text runs to the next backslash (commas and continuation marks inside are
    its own, the continuation marks dropped)."""
    out, k, n = [], 0, len(rest)
    while k < n:
        while k < n and rest[k] in f", \t{_SEP}\\":
            k += 1
        if k >= n:
            break
        start = k
        m = re.match(r"\s*([A-Za-z_][A-Za-z0-9_]*)\s*=", rest[k:])
        if m and _is_function_key(m.group(1)):
            end, text = _function_end(rest, k + m.end())
            out.append((start, rest[start:k + m.end()] + text, True))
            k = end + 1
            continue
        depth, quote = 0, None
        while k < n:
            ch = rest[k]
            if quote:
                quote = None if ch == quote else quote
            elif ch in "\"'":
                quote = ch
            elif ch == "(":
                depth += 1
            elif ch == ")":
                depth -= 1
            elif depth == 0 and ch in f",{_SEP}\\":
                break
            k += 1
        out.append((start, rest[start:k].strip(), False))
    return out


def _function_end(rest, k):
    """(end, text) of the expression starting at rest[k]: it runs to a backslash, or to a
    comma outside parentheses (Adams wants a backslash or the statement's end; a top-level
    comma cannot be part of an expression). A continuation line continues it inside
    parentheses or after an operator, and ends it otherwise."""
    depth, out, n = 0, [], len(rest)
    while k < n:
        ch = rest[k]
        if ch == "\\":
            break
        if ch in "([":
            depth += 1
        elif ch in ")]":
            depth -= 1
        elif ch == "," and depth == 0:
            break
        elif ch == _SEP:
            so_far, after = "".join(out).rstrip(), rest[k + 1:].lstrip()
            if depth == 0 and so_far and so_far[-1] not in "+-*/(:,^=<>" and \
                    after[:1] not in ("+", "-", "*", "/", "^"):
                break
            k += 1
            continue
        out.append(ch)
        k += 1
    return k, "".join(out)


#: Keywords whose value is an expression (up to a backslash or the statement's end).
_FUNCTION_KEYS = ("FUNCTION", "FX", "FY", "FZ", "TX", "TY", "TZ", "EVALUATE", "LOAD_FUNCTION",
                  *(f"F{k}" for k in range(1, 9)))
#: Keywords whose value is a list of strings (names continue it as numbers continue a list).
_STRING_LISTS = ("CNAMES",)


def _is_function_key(word):
    """A keyword (possibly abbreviated: FUN=) that takes an expression."""
    w = word.upper()
    return w in _FUNCTION_KEYS or (len(w) >= 3 and "FUNCTION".startswith(w)) or \
        (len(w) >= 3 and "EVALUATE".startswith(w))


def _args(stmt, file):
    """[(keyword as written, [values as text] or None for a flag, is_function, line)]:
    numbers after an assignment continue its list (names continue CNAMES=; so does a
    malformed number, which its keyword's checks then name)."""
    out = []
    for item, function, line in stmt.args:
        key, eq, val = item.partition("=")
        key = key.strip()
        if key[:1] and key[:1] in "\"'":                 # a quoted value holds no assignment
            key, eq, val = item.strip(), "", ""
        names = out and out[-1][1] is not None and len(out[-1][0]) >= 2 and \
            any(k.startswith(out[-1][0].upper()) for k in _STRING_LISTS)
        if eq:
            out.append([key, [val.strip()] if not function else val.strip(), function, line])
        elif out and out[-1][1] is not None and not out[-1][2] and \
                (re.match(r"[+-]?\.?\d", key) or names):
            out[-1][1].append(key)          # the next value of a list (REULER=90D, 0, 0)
        else:
            out.append([key, None, False, line])
    return out


#: Spellings Adams accepts besides the keyword and its prefixes (REQUEST/1, V, ...).
_ALIASES = {"TRANSLATIONAL": "TRANSLATION", "ROTATIONAL": "ROTATION"}
_REQUEST_ALIASES = {"D": "DISPLACEMENT", "V": "VELOCITY", "A": "ACCELERATION", "F": "FORCE",
                    "C": "COMMENT"}


def _resolve(word, known, stmt, file, line, extensions=()):
    """The keyword `word` abbreviates among `known` (an exact name or a unique prefix) or
    names among pysolver's `extensions` (in full); None for `known` takes any keyword
    (GRAPHICS, kept as written)."""
    w = word.upper()
    if known is None or w in known or w in extensions:
        return w
    alias = (_REQUEST_ALIASES if stmt.name == "REQUEST" else {}).get(w, _ALIASES.get(w))
    if alias in known:
        return alias
    hits = [k for k in known if k.startswith(w)]
    if len(hits) == 1:
        return hits[0]
    where = f"{stmt.name}/{stmt.id}" if stmt.id is not None else stmt.name
    if hits:
        raise DeckError(f"{word} is ambiguous: it abbreviates {', '.join(sorted(hits))}",
                        file=file, line=line, element=where, attribute=word)
    close = difflib.get_close_matches(w, tuple(known) + tuple(extensions), n=1)
    hint = f"; did you mean {close[0]}?" if close else ""
    raise DeckError(f"unknown keyword {word}{hint} ({stmt.name} takes "
                    f"{', '.join(sorted(known + tuple(extensions)))})", file=file, line=line,
                    element=where, attribute=word)


def _number(text, stmt, key, file, line, integer=False):
    """A number of the dataset (a trailing D: degrees, read as radians; a D exponent: the
    Fortran double precision exponent)."""
    m = _NUMBER.match(text.strip())
    if not m:
        raise DeckError(f"expected a number, got {text!r}", file=file, line=line,
                        element=f"{stmt.name}/{stmt.id}", attribute=key)
    degrees = bool(m["deg"] or m["edeg"])
    if integer and not degrees and re.fullmatch(r"[+-]?\d+", text.strip()):
        return int(text.strip())
    val = _value(m)
    return float(np.radians(val)) if degrees else val


def _value(m):
    """The number a match of _NUMBER or _FUNCTION_NUMBER writes, without its degrees."""
    exp = m["exp"] or ("E" + m["dexp"][1:] if m["dexp"] else "")
    return float(m["mant"] + exp)


def expression(text, signed=None):
    """An Adams function in pysolver's language: numbers with a D for degrees become radians,
    a D exponent becomes an E one. `signed`, a list, collects the D exponents written with a
    sign (1.0D-3), which would also read as degrees minus a number (1.0D - 3)."""
    def number(m):
        if m["deg"] or m["edeg"]:
            return repr(float(np.radians(_value(m))))
        if m["dexp"]:
            if signed is not None and m["dexp"][1] in "+-":
                signed.append(m.group(0))
            return m["mant"] + ("e" if m["dexp"][0] == "d" else "E") + m["dexp"][1:]
        return m.group(0)
    return _FUNCTION_NUMBER.sub(number, text)


def _signed_exponent(text):
    """The warning on a D exponent with a sign in a function (docs/adams.md, "Numbers")."""
    m = _NUMBER.match(text)
    mant, sign, digits = m["mant"], m["dexp"][1], m["dexp"][2:]
    angle = f"{mant}D {sign} {digits}"
    return (f"{text} is read as a Fortran exponent, {_value(m)!r}, not as {mant} degrees "
            f"{'plus' if sign == '+' else 'minus'} {digits}; write {mant}E{sign}{digits} for "
            f"the number, or {angle} for the angle (docs/adams.md, \"Numbers\")")


class _Reader:
    """Reads the statements in order, calling pysolver.deck.msolve's statement functions."""

    def __init__(self, file, acf=None):
        self.file, self.acf = file, acf or file
        self.dataset = file         # the file the deck is loaded as (its elements' default)
        self.parts = {}             # part id -> (origin, axes) of its BCS
        self.markers = {}           # marker id -> (statement, values)
        self.spaces = {}            # pysolver id space -> [(statement name, statement)]
        self.ids = {}               # (statement name, Adams id) -> pysolver id, on a clash
        self.units_seen = False

    def warn(self, stmt, msg, line=None, key=None):
        where = f"{stmt.name}/{stmt.id}" if stmt.id is not None else stmt.name
        warn(DeckWarning(msg, file=self.file, line=line or stmt.line, element=where,
                         attribute=key))

    def error(self, stmt, msg, key=None, line=None):
        where = f"{stmt.name}/{stmt.id}" if stmt.id is not None else stmt.name
        return DeckError(msg, file=self.file, line=line or stmt.line, element=where,
                         attribute=key)

    def values(self, stmt, known, extensions=()):
        """{KEYWORD: value} of a statement: flags True, numbers as numbers (lists of
        several), functions as expression text; with the line of each keyword."""
        vals, lines = {}, {}
        for key, val, function, line in _args(stmt, self.file):
            name = _resolve(key, known, stmt, self.file, line, extensions)
            if name in vals and name != "Y":
                raise self.error(stmt, f"{name} given twice", key, line)
            lines[name] = line
            if val is None:
                vals[name] = True
            elif function:
                signed = []
                vals[name] = expression(val, signed)
                if re.match(r"\s*USER\s*\(", val, re.I):
                    signed = []             # USER(...) takes numbers: one reading
                for text in signed:
                    self.warn(stmt, _signed_exponent(text), line, key)
            elif name == "Y":
                vals.setdefault("Y", []).append(
                    [_number(v, stmt, key, self.file, line) for v in val])
            elif not val[0].strip() and len(val) == 1:
                raise self.error(stmt, f"{key} = has no value (the statement is cut short?)",
                                 key, line)
            else:
                # a list may start on the next line (KMATRIX = at a line's end, then numbers)
                val = val[1:] if not val[0].strip() else val
                conv = [_number(v, stmt, key, self.file, line, integer=True)
                        if _NUMBER.match(v) else v.strip().strip("\"'") for v in val]
                vals[name] = conv[0] if len(conv) == 1 else conv
        return vals, lines

    def raw_values(self, stmt):
        """{keyword in lower case: its text as written (a list joined by ", "; quotes
        removed), or True for a flag} of a statement kept as written (GRAPHICS)."""
        out = {}
        for key, val, function, _line in _args(stmt, self.file):
            if val is None:
                out[key.lower()] = True
            else:
                texts = [val] if function else [v.strip().strip("\"'") for v in val]
                out[key.lower()] = ", ".join(texts)
        return out

    # ---- placement -------------------------------------------------------------------
    def frame(self, stmt, vals, lines, keys, ref=None):
        """(origin, axes) in the reference frame `ref` (global when None) from the origin
        and one orientation form of `keys` (PART_KEYS or MARKER_KEYS)."""
        o0, A0 = ref if ref is not None else (np.zeros(3), np.eye(3))
        o = self.triple(stmt, vals, lines, keys[0], np.zeros(3))
        A = self.axes(stmt, vals, lines, o, keys)
        return o0 + A0 @ o, A0 @ (np.eye(3) if A is None else A)

    def orientation_form(self, stmt, vals, lines, keys):
        """The orientation keyword given (REULER, YPR, EP, AXES, or ZP/ZG for points on the
        axes), or None."""
        _, euler, zp, xp, *other = keys
        given = [k for k in (euler, zp, *other) if k in vals]
        if xp in vals and zp not in vals:
            raise self.error(stmt, f"{xp} needs {zp} (a point on the z axis)", xp, lines[xp])
        if len(given) > 1:
            raise self.error(stmt, f"give one of {', '.join(given)} for the axes, not both",
                             given[1], lines[given[1]])
        return given[0] if given else None

    def axes(self, stmt, vals, lines, origin, keys):
        """The axes an orientation form gives (columns x, y, z), or None without one."""
        form = self.orientation_form(stmt, vals, lines, keys)
        zp, xp = keys[2], keys[3]
        if form is None:
            return None
        if form == zp:
            z = self.triple(stmt, vals, lines, zp, None) - origin
            x = self.triple(stmt, vals, lines, xp, None) - origin if xp in vals else None
            try:
                return axes_from_points(z, x, vals.get("USEXP", False))
            except ValueError as err:
                raise self.error(stmt, str(err), zp, lines[zp]) from None
        numbers = self.numbers(stmt, vals, lines, form, {"EP": 4, "AXES": 9}.get(form, 3))
        if form == "YPR":
            return rot_321(*numbers)
        if form == "EP":
            if not np.any(numbers):
                raise self.error(stmt, "Euler parameters are all zero", "EP", lines["EP"])
            return rot_from_e(numbers / np.linalg.norm(numbers))
        if form == "AXES":
            return numbers.reshape(3, 3).T
        return rot_313(*numbers)

    def triple(self, stmt, vals, lines, key, default):
        if key not in vals:
            return default
        return self.numbers(stmt, vals, lines, key, 3)

    def numbers(self, stmt, vals, lines, key, count):
        v = vals[key]
        v = v if isinstance(v, list) else [v]
        if len(v) != count or not all(isinstance(c, (int, float)) for c in v):
            names = {3: "three", 4: "four", 9: "nine"}[count]
            raise self.error(stmt, f"{key} takes {names} numbers, got {v!r}", key, lines[key])
        return np.array(v, float)

    # ---- the statements --------------------------------------------------------------
    def run(self, stmts, commands):
        """Emit every statement through pysolver.deck.msolve; returns the elements."""
        rec = msolve._Recorder(self.file)
        prev = getattr(msolve._STATE, "rec", None)
        msolve._STATE.rec = rec
        try:
            self.first_pass(stmts)
            for stmt in stmts:
                if self.statement_name(stmt, DATASET) == "END":
                    break
                self.emit(rec, stmt, DATASET)
            self.file = rec.file = self.acf     # errors in commands name the command file
            ran = set()                         # the analyses of the SIMULATEs so far
            for stmt in commands:
                if stmt.name.upper() == "STOP":
                    break
                start = len(rec.elements)
                self.emit(rec, stmt, COMMANDS)
                if stmt.name in _SETTINGS:
                    self.settings_command(rec, stmt, start, ran)
                ran.update(str(el[1].get("analysis_type", "")).upper()
                           for el in rec.elements[start:] if el[0] == "Simulate")
        finally:
            msolve._STATE.rec = prev
        return rec.elements

    def emit(self, rec, stmt, table):
        name = self.statement_name(stmt, table)
        stmt.name = name
        if name in UNSUPPORTED:
            raise self.error(stmt, f"{name} is not supported by pysolver (docs/adams.md)")
        if name in SET_ASIDE:
            why = _ASIDE_WHY.get(name, "only shapes Adams' output or diagnostics")
            self.warn(stmt, f"{name} {why}; set aside")
            return
        if name in SETTINGS_ONLY:
            keywords, why = SETTINGS_ONLY[name]
            self.values(stmt, keywords)             # an unknown keyword is a DeckError
            self.warn(stmt, f"{name} {why}; set aside")
            return
        if name in QUIET or name == "END":
            return
        known, extensions, handler = table[name]
        # a statement that takes any keyword reads its text as written (raw_values)
        vals, lines = self.values(stmt, known, extensions) if known is not None else ({}, {})
        start = len(rec.elements)
        rec.line = stmt.line
        try:
            handler(self, stmt, vals, lines)
        finally:
            rec.line = None
        where = f"{name}/{stmt.id}" if stmt.id is not None else name
        for _, _, _, names in rec.elements[start:]:
            names["#element"] = where
            if self.file != self.dataset:     # a command: its checks name the command file
                names["#file"] = self.file

    def settings_command(self, rec, stmt, start, ran):
        """An INTEGRATOR or EQUILIBRIUM command changes the dataset's statement of that name:
        the keywords it gives replace the dataset's, the others are kept (each located where
        it was written). pysolver runs every analysis with one set of settings, so such a
        command must come before the first SIMULATE it would apply to (INTEGRATOR: a
        transient; EQUILIBRIUM: statics)."""
        uses = {"INTEGRATOR": {"TRANSIENT"}, "EQUILIBRIUM": {"STATIC", "QUASI-STATIC"}}
        if ran & uses[stmt.name]:
            raise self.error(stmt, f"{stmt.name} after a SIMULATE it applies to would change "
                             "the settings between analyses, and pysolver runs every "
                             "analysis with one set of settings: give it before that SIMULATE")
        tag = rec.elements[start][0]
        first = next((k for k, el in enumerate(rec.elements[:start])
                      if el[0] == tag and "#file" not in el[3]), None)
        if first is None:
            return
        _, attrs, _, names = rec.elements[start]
        _, kept, line, kept_names = rec.elements.pop(first)
        lines, files = names.setdefault("#lines", {}), names.setdefault("#files", {})
        for key, value in kept.items():
            if key not in attrs:
                attrs[key], names[key] = value, kept_names.get(key, key)
                lines[key], files[key] = line, self.dataset

    def statement_name(self, stmt, table):
        """The statement `stmt` names (a unique prefix of Adams' statements will do;
        pysolver's own are named in full)."""
        known = tuple(table) + UNSUPPORTED + SET_ASIDE + tuple(SETTINGS_ONLY) + QUIET + \
            ("END", "STOP")
        w = stmt.name.upper()
        where = f"{stmt.name}/{stmt.id}" if stmt.id is not None else stmt.name
        hits = [k for k in known if k == w] or \
            [k for k in known if k.startswith(w) and k not in EXTENSIONS]
        if len(hits) == 1:
            return hits[0]
        what = "command" if table is COMMANDS else "statement"
        if table is COMMANDS:
            other = [k for k in tuple(DATASET) + _OTHER_COMMANDS if k.startswith(w)]
            if other:
                raise DeckError(f"the command {other[0]} is not supported: pysolver runs the "
                                "dataset as written, with SIMULATE, INTEGRATOR and "
                                "EQUILIBRIUM commands only (docs/adams.md)", file=self.file,
                                line=stmt.line, element=where)
        if hits:
            raise DeckError(f"{stmt.name} is ambiguous: it abbreviates {', '.join(sorted(hits))}",
                            file=self.file, line=stmt.line, element=where)
        close = difflib.get_close_matches(w, tuple(table), n=1)
        hint = f"; did you mean {close[0]}?" if close else ""
        raise DeckError(f"unknown {what} {stmt.name}{hint} (docs/adams.md lists what pysolver "
                        "reads)", file=self.file, line=stmt.line, element=where)

    def first_pass(self, stmts):
        """The frames of parts and point masses, and the raw values of markers (a marker's
        RM may come later in the file)."""
        for stmt in stmts:
            try:
                name = self.statement_name(stmt, DATASET)
            except DeckError:
                continue                        # reported in order by emit
            if name == "END":
                break
            if name in SHARED and stmt.id is not None:
                self.spaces.setdefault(SHARED[name], []).append((name, stmt))
        for space in self.spaces.values():
            self.renumber(space)
        for stmt in stmts:
            try:
                name = self.statement_name(stmt, DATASET)
            except DeckError:
                continue
            if name == "END":
                break
            if name in ("PART", "POINT_MASS"):
                vals, lines = self.values(stmt, *DATASET[name][:2])
                self.need_id(stmt)
                self.parts[self.id(stmt)] = self.frame(stmt, vals, lines, PART_KEYS)
            elif name == "MARKER":
                vals, lines = self.values(stmt, *DATASET[name][:2])
                self.need_id(stmt)
                self.markers[stmt.id] = (stmt, vals, lines)

    def renumber(self, space):
        """Adams keeps point masses apart from parts, joint primitives apart from joints,
        VTORQUE and GFORCE apart from VFORCE; pysolver has one id space for each group: a
        clash gets the next free id (a DeckWarning says which)."""
        primary = {st.id for name, st in space if name in PRIMARY}
        nxt = max([st.id for _, st in space] + [0]) + 1
        taken = set(primary)
        for name, stmt in space:
            if name in PRIMARY:
                continue
            if stmt.id in taken:
                self.ids[(name, stmt.id)] = nxt
                self.warn(stmt, f"{name}/{stmt.id} has the id of another statement that "
                          f"pysolver counts with it; pysolver numbers it {nxt}")
                nxt += 1
            taken.add(self.ids.get((name, stmt.id), stmt.id))

    def id(self, stmt, name=None):
        """The pysolver id of a statement (or of statement `name`'s id `stmt`)."""
        if name is not None:
            return self.ids.get((name, stmt), stmt)
        return self.ids.get((stmt.name, stmt.id), stmt.id)

    def need_id(self, stmt):
        if stmt.id is None:
            raise self.error(stmt, f"{stmt.name} needs an id: {stmt.name}/id, ...")

    def marker_body(self, mid):
        """(keyword, id as written, pysolver id) of the part or point mass of marker mid."""
        stmt, vals, _ = self.markers[mid]
        if "PART" not in vals and "POINT_MASS" not in vals:
            raise self.error(stmt, "a marker needs PART= (or POINT_MASS=)")
        key = "PART" if "PART" in vals else "POINT_MASS"
        return key, vals[key], self.id(vals[key], key)

    def marker_pose(self, mid, seen=()):
        """Global (origin, axes) of marker mid."""
        stmt, vals, lines = self.markers[mid]
        if mid in seen:
            raise self.error(stmt, "RM markers refer to each other in a loop", "RM")
        key, written, body = self.marker_body(mid)
        if body not in self.parts:
            raise self.error(stmt, f"{key.lower().replace('_', ' ')} {written} does not "
                             "exist", key, lines.get(key))
        ref = self.parts[body]
        if "RM" in vals and not vals.get("FLOATING"):
            rm = vals["RM"]
            if rm not in self.markers:
                raise self.error(stmt, f"marker {rm} does not exist", "RM", lines["RM"])
            rm_key, rm_written, rm_body = self.marker_body(rm)
            if rm_body != body:
                raise self.error(stmt, f"RM = {rm} is a marker of {rm_key}/{rm_written}, not "
                                 f"of {key}/{written}: Adams requires the RM marker on the "
                                 f"marker's own part (give QP and the axes in {key}/{written}'s "
                                 f"frame, or an RM of {key}/{written})", "RM", lines["RM"])
            ref = self.marker_pose(rm, seen + (mid,))
        if vals.get("FLOATING"):
            return ref
        return self.frame(stmt, vals, lines, MARKER_KEYS, ref)

    def marker_placement(self, mid):
        """MARKER's keywords of pysolver.deck.msolve.MARKER for marker `mid`: its placement
        as written (QP, the orientation form, RM) when its part's frame is the global frame,
        so that the dataset builds the marker exactly as the XML deck it was written from
        (docs/adams.md, "Placement"); else its global place and axes."""
        o, A = self.marker_pose(mid)            # checks the part, the RM chain, the numbers
        stmt, vals, lines = self.markers[mid]
        po, pa = self.parts[self.marker_body(mid)[2]]
        if vals.get("FLOATING") or po.any() or not np.array_equal(pa, np.eye(3)):
            return {"QP": o.tolist(), "AXES": A.T.ravel().tolist()}
        kw = {"QP": self.triple(stmt, vals, lines, "QP", np.zeros(3)).tolist()}
        form = self.orientation_form(stmt, vals, lines, MARKER_KEYS)
        if form == "ZP":                       # the axes the points give, in RM's frame
            axes = self.axes(stmt, vals, lines, np.array(kw["QP"]), MARKER_KEYS)
            kw["AXES"] = axes.T.ravel().tolist()
        elif form is not None:
            kw[form] = self.numbers(stmt, vals, lines, form,
                                    {"EP": 4, "AXES": 9}.get(form, 3)).tolist()
        if "RM" in vals:
            kw["RM"] = vals["RM"]
        return kw

    def marker_reference(self, mid):
        """How QP places marker `mid` when marker_placement gives its global place (its part's
        frame is not the global one): its QP in RM's frame (with RM's axes as marker_pose
        makes them) or in the part's; None when the statement's own QP and RM say it (or a
        FLOATING marker has none). A sweep's pos_* then mean QP (pysolver.build.params)."""
        stmt, vals, lines = self.markers[mid]
        po, pa = self.parts[self.marker_body(mid)[2]]
        if vals.get("FLOATING") or not (po.any() or not np.array_equal(pa, np.eye(3))):
            return None
        qp = self.triple(stmt, vals, lines, "QP", np.zeros(3))
        if "RM" in vals:
            return Placement(qp, rm=vals["RM"], axes=self.marker_pose(vals["RM"])[1])
        return Placement(qp, origin=po, axes=pa)


#: The orientation keywords of a part (origin, 3-1-3 angles, a point on z, a point in the x-z
#: plane) and of a marker (the same, and pysolver's YPR, EP and AXES).
PART_KEYS = ("QG", "REULER", "ZG", "XG")
MARKER_KEYS = ("QP", "REULER", "ZP", "XP", "YPR", "EP", "AXES")


def axes_from_points(z, x, usexp=False):
    """Axes (columns x, y, z) from a z direction and an x-z plane direction (Adams' ZP/XP,
    ZG/XG; with `usexp` x is the x direction and z the plane's); ValueError when they
    give none."""
    if np.linalg.norm(z) == 0 or (x is not None and np.linalg.norm(x) == 0):
        raise ValueError("a direction point coincides with the origin")
    if x is None:               # Decision: x from the reference axis least along z
        x = np.eye(3)[int(np.argmin(np.abs(z)))]
        usexp = False
    if usexp:
        x = x / np.linalg.norm(x)
        y = np.cross(z, x)
        z = np.cross(x, y)
    else:
        z = z / np.linalg.norm(z)
        y = np.cross(z, x)
        x = np.cross(y, z)
    if np.linalg.norm(y) < 1e-12 * np.linalg.norm(z) * np.linalg.norm(x):
        raise ValueError("the x-z plane point lies on the z axis")
    return np.column_stack([v / np.linalg.norm(v) for v in (x, y, z)])


def read_elements(text, file):
    """The elements of a dataset (and of the commands after its END when a command file
    was merged in: see with_commands)."""
    dataset, mark, commands = text.partition("\n" + COMMANDS_MARK)
    stmts = statements(dataset, file)
    cmds, acf = [], file
    if mark:
        head, _, body = commands.partition("\n")
        acf = head.strip() or file
        cmds = statements(body, acf, first=3, title=False)   # the command file's lines
    return _Reader(file, acf).run(stmts, cmds)


def with_commands(dataset_text, acf_text, acf_file):
    """A dataset's text with a command file's commands after a marked comment (Adams reads
    nothing after END), so the model's source is one text; the command file's first line
    (the dataset) is left out, its second (the output name) kept in a comment of its own
    before them (output_name), unless the first is blank (then the second is FILE/MODEL=)."""
    lines = acf_text.splitlines()
    name = lines[1].strip() if len(lines) > 1 and lines[0].strip() else ""
    kept = f"\n{OUTPUT_MARK} {name}" if name else ""
    return (dataset_text.rstrip("\n") + kept + f"\n{COMMANDS_MARK} {acf_file}\n"
            + "\n".join(lines[2:]) + "\n")


def output_name(text):
    """The output name of the command file merged into a dataset's text (with_commands), or
    None."""
    dataset = text.partition("\n" + COMMANDS_MARK)[0]
    found = re.search(rf"^{re.escape(OUTPUT_MARK)} (.+)$", dataset, re.M)
    return found.group(1).strip() if found else None


def acf_dataset(acf_text, acf_file):
    """The dataset a command file names on its first line (.adm added when it has no
    extension), relative to the command file's folder."""
    lines = acf_text.splitlines()
    name = lines[0].strip() if lines else ""
    if not name:            # a blank first line, then FILE/MODEL=name (as adamspy writes)
        for line in lines[1:3]:
            found = re.match(r"\s*FILE\s*/\s*MODEL\s*=\s*([^\s,!]+)", line, re.I)
            if found:
                name = found.group(1)
                break
    if not name:
        raise DeckError("a command file's first line names its dataset (or is blank and "
                        "the second is FILE/MODEL=name)", file=acf_file, line=1)
    if not os.path.splitext(name)[1]:
        name += ".adm"
    return os.path.join(os.path.dirname(os.path.abspath(acf_file)), name)
