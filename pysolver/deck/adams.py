"""Adams datasets (.adm) and command files (.acf), read into pysolver's statements.

Longer than 420 lines because it is a language: the lexer (title line, ``!`` comments,
continuation lines, ``\\``-separated functions, ``D`` degrees), keyword abbreviation, the
placement of parts and markers, and one small translation per statement; each statement
becomes the call of its pysolver.deck.msolve statement function, so an .adm deck builds the
same elements as the XML and Python forms (../shared/reference/elements.md sections 8.3, 9;
docs/adams.md says what is read and what is refused).
"""
import difflib
import os
import re
import warnings

import numpy as np

from ..errors import DeckError, DeckWarning
from ..rotations import rot_313
from . import msolve

#: The comment line after END that marks the commands of a command file (load("x.acf")).
COMMANDS_MARK = "!pysolver: commands of"

#: Statements that would change the dynamics and that pysolver does not model: a DeckError.
UNSUPPORTED = ("CONTACT", "FLEX_BODY", "BEAM", "FIELD", "DIFF", "LSE", "GSE", "TFSISO",
               "NFORCE", "CVCV", "PTCV", "CURVE", "SURFACE", "FRICTION", "GEAR", "MFORCE",
               "FEMDATA", "IC", "ARRAY", "STRING", "MATRIX", "PSTATE", "EXTERNAL_SYSTEM",
               "COUSUB", "CLEARANCE", "ENVIRONMENT", "USER", "SECTION", "FE_PART", "FE_NODE",
               "FE_LOAD")
#: Statements that only shape output or diagnostics: read and set aside with a DeckWarning.
SET_ASIDE = ("LIST", "NOLIST", "DEBUG", "MREQUEST", "PINPUT", "POUTPUT", "FEMDATA_OUTPUT",
             "PREFERENCES", "FILE", "SHOW", "INFO", "HELP", "MENU", "RETURN", "TIME",
             "MATERIAL")
#: Commands that change the model or run what pysolver does not: a DeckError.
_OTHER_COMMANDS = ("DEACTIVATE", "ACTIVATE", "LINEAR", "SAVE", "RELOAD", "CONTROL", "DEBUG",
                   "BUSHING", "SHOW", "SWITCH")
#: Statements read quietly and not used (output settings; graphics are kept).
QUIET = ("OUTPUT", "RESULTS")

_NUMBER = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?([dD])?$")
_DEGREES = re.compile(r"(?<![\w.])((?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)[dD](?![\w(])")
_VIEW_NAME = re.compile(r"adams_view_name\s*=\s*'([^']*)'", re.I)
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
            label = found.group(1)
        if not body.strip():
            continue
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
_FUNCTION_KEYS = ("FUNCTION", "FX", "FY", "FZ", "TX", "TY", "TZ", "EVALUATE",
                  *(f"F{k}" for k in range(1, 9)))


def _is_function_key(word):
    """A keyword (possibly abbreviated: FUN=) that takes an expression."""
    w = word.upper()
    return w in _FUNCTION_KEYS or (len(w) >= 3 and "FUNCTION".startswith(w)) or \
        (len(w) >= 3 and "EVALUATE".startswith(w))


def _args(stmt, file):
    """[(keyword as written, [values as text] or None for a flag, is_function, line)]:
    numbers after an assignment continue its list."""
    out = []
    for item, function, line in stmt.args:
        key, eq, val = item.partition("=")
        key = key.strip()
        if eq:
            out.append([key, [val.strip()] if not function else val.strip(), function, line])
        elif out and out[-1][1] is not None and not out[-1][2] and _NUMBER.match(key):
            out[-1][1].append(key)          # the next value of a list (REULER=90D, 0, 0)
        else:
            out.append([key, None, False, line])
    return out


#: Spellings Adams accepts besides the keyword and its prefixes (REQUEST/1, V, ...).
_ALIASES = {"TRANSLATIONAL": "TRANSLATION", "ROTATIONAL": "ROTATION"}
_REQUEST_ALIASES = {"D": "DISPLACEMENT", "V": "VELOCITY", "A": "ACCELERATION", "F": "FORCE"}


def _resolve(word, known, stmt, file, line):
    """The keyword `word` abbreviates among `known` (an exact name or a unique prefix); None
    for `known` takes any keyword (GRAPHICS, kept as written)."""
    w = word.upper()
    if known is None or w in known:
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
    close = difflib.get_close_matches(w, known, n=1)
    hint = f"; did you mean {close[0]}?" if close else ""
    raise DeckError(f"unknown keyword {word}{hint} ({stmt.name} takes "
                    f"{', '.join(sorted(known))})", file=file, line=line, element=where,
                    attribute=word)


def _number(text, stmt, key, file, line, integer=False):
    """A number of the dataset (a trailing D: degrees, read as radians)."""
    m = _NUMBER.match(text.strip())
    if not m:
        raise DeckError(f"expected a number, got {text!r}", file=file, line=line,
                        element=f"{stmt.name}/{stmt.id}", attribute=key)
    body = text.strip()[:-1] if m.group(3) else text.strip()
    if integer and not m.group(3) and re.fullmatch(r"[+-]?\d+", body):
        return int(body)
    val = float(body)
    return np.radians(val) if m.group(3) else val


def expression(text):
    """An Adams expression in pysolver's language: numbers with a D suffix become radians."""
    return _DEGREES.sub(lambda m: repr(float(np.radians(float(m.group(1))))), text)


class _Reader:
    """Reads the statements in order, calling pysolver.deck.msolve's statement functions."""

    def __init__(self, file, acf=None):
        self.file, self.acf = file, acf or file
        self.parts = {}             # part id -> (origin, axes) of its BCS
        self.markers = {}           # marker id -> (statement, values)
        self.spaces = {}            # pysolver id space -> [(statement name, statement)]
        self.ids = {}               # (statement name, Adams id) -> pysolver id, on a clash
        self.units_seen = False

    def warn(self, stmt, msg, line=None):
        where = f"{stmt.name}/{stmt.id}" if stmt.id is not None else stmt.name
        warnings.warn(DeckWarning(msg, file=self.file, line=line or stmt.line, element=where),
                      stacklevel=3)

    def error(self, stmt, msg, key=None, line=None):
        where = f"{stmt.name}/{stmt.id}" if stmt.id is not None else stmt.name
        return DeckError(msg, file=self.file, line=line or stmt.line, element=where,
                         attribute=key)

    def values(self, stmt, known, functions=()):
        """{KEYWORD: value} of a statement: flags True, numbers as numbers (lists of
        several), functions as expression text; with the line of each keyword."""
        vals, lines = {}, {}
        for key, val, function, line in _args(stmt, self.file):
            name = _resolve(key, known, stmt, self.file, line)
            if name in vals and name != "Y":
                raise self.error(stmt, f"{name} given twice", key, line)
            lines[name] = line
            if val is None:
                vals[name] = True
            elif function or name in functions:
                text = val if isinstance(val, str) else ", ".join(val)
                vals[name] = expression(text)
            elif name == "Y":
                vals.setdefault("Y", []).append(
                    [_number(v, stmt, key, self.file, line) for v in val])
            else:
                conv = [_number(v, stmt, key, self.file, line, integer=True)
                        if _NUMBER.match(v) else v.strip().strip("\"'") for v in val]
                vals[name] = conv[0] if len(conv) == 1 else conv
        return vals, lines

    # ---- placement -------------------------------------------------------------------
    def frame(self, stmt, vals, lines, origin_key, euler_key, z_key, x_key, ref=None):
        """(origin, axes) in the reference frame `ref` (global when None) from an origin
        and REULER (3-1-3), or points on +z and in the x-z plane (USEXP: on +x)."""
        o0, A0 = ref if ref is not None else (np.zeros(3), np.eye(3))
        o = self.triple(stmt, vals, lines, origin_key, np.zeros(3))
        if euler_key in vals and (z_key in vals or x_key in vals):
            raise self.error(stmt, f"give {euler_key} or {z_key}/{x_key}, not both", euler_key)
        if euler_key in vals:
            A = rot_313(*self.triple(stmt, vals, lines, euler_key, None))
        elif z_key in vals:
            z = self.triple(stmt, vals, lines, z_key, None) - o
            x = self.triple(stmt, vals, lines, x_key, None) - o if x_key in vals else None
            A = self.axes_from_points(stmt, z, x, vals.get("USEXP", False), z_key)
        elif x_key in vals:
            raise self.error(stmt, f"{x_key} needs {z_key} (a point on the z axis)", x_key)
        else:
            A = np.eye(3)
        return o0 + A0 @ o, A0 @ A

    def axes_from_points(self, stmt, z, x, usexp, key):
        """Axes from a z direction and an x-z plane direction (Adams' ZP/XP, ZG/XG)."""
        if np.linalg.norm(z) == 0 or (x is not None and np.linalg.norm(x) == 0):
            raise self.error(stmt, "a direction point coincides with the origin", key)
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
            raise self.error(stmt, "the x-z plane point lies on the z axis", key)
        return np.column_stack([v / np.linalg.norm(v) for v in (x, y, z)])

    def triple(self, stmt, vals, lines, key, default):
        if key not in vals:
            return default
        v = vals[key]
        v = v if isinstance(v, list) else [v]
        if len(v) != 3 or not all(isinstance(c, (int, float)) for c in v):
            raise self.error(stmt, f"{key} takes three numbers, got {v!r}", key, lines[key])
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
            self.file = self.acf                # errors in commands name the command file
            for stmt in commands:
                if stmt.name.upper() == "STOP":
                    break
                self.emit(rec, stmt, COMMANDS)
        finally:
            msolve._STATE.rec = prev
        return rec.elements

    def emit(self, rec, stmt, table):
        name = self.statement_name(stmt, table)
        stmt.name = name
        if name in UNSUPPORTED:
            raise self.error(stmt, f"{name} is not supported by pysolver (docs/adams.md)")
        if name in SET_ASIDE:
            self.warn(stmt, f"{name} only shapes Adams' output or diagnostics; set aside")
            return
        if name in QUIET or name == "END":
            return
        known, handler = table[name]
        vals, lines = self.values(stmt, known, ())
        start = len(rec.elements)
        rec.line = stmt.line
        try:
            handler(self, stmt, vals, lines)
        finally:
            rec.line = None
        where = f"{name}/{stmt.id}" if stmt.id is not None else name
        for _, _, _, names in rec.elements[start:]:
            names["#element"] = where

    def statement_name(self, stmt, table):
        """The statement `stmt` names (a unique prefix will do)."""
        known = tuple(table) + UNSUPPORTED + SET_ASIDE + QUIET + ("END", "STOP")
        w = stmt.name.upper()
        hits = [k for k in known if k == w] or [k for k in known if k.startswith(w)]
        if len(hits) == 1:
            return hits[0]
        what = "command" if table is COMMANDS else "statement"
        if table is COMMANDS:
            other = [k for k in tuple(DATASET) + _OTHER_COMMANDS if k.startswith(w)]
            if other:
                raise DeckError(f"the command {other[0]} is not supported: pysolver runs the "
                                "dataset as written, with SIMULATE, INTEGRATOR and "
                                "EQUILIBRIUM commands only (docs/adams.md)", file=self.file,
                                line=stmt.line, element=stmt.name)
        if hits:
            raise DeckError(f"{stmt.name} is ambiguous: it abbreviates {', '.join(sorted(hits))}",
                            file=self.file, line=stmt.line, element=stmt.name)
        close = difflib.get_close_matches(w, tuple(table), n=1)
        hint = f"; did you mean {close[0]}?" if close else ""
        raise DeckError(f"unknown {what} {stmt.name}{hint} (docs/adams.md lists what pysolver "
                        "reads)", file=self.file, line=stmt.line, element=stmt.name)

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
            if name in _SHARED and stmt.id is not None:
                self.spaces.setdefault(_SHARED[name], []).append((name, stmt))
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
                vals, lines = self.values(stmt, DATASET[name][0])
                self.need_id(stmt)
                self.parts[self.id(stmt)] = self.frame(stmt, vals, lines, "QG", "REULER",
                                                       "ZG", "XG")
            elif name == "MARKER":
                vals, lines = self.values(stmt, DATASET[name][0])
                self.need_id(stmt)
                self.markers[stmt.id] = (stmt, vals, lines)

    def renumber(self, space):
        """Adams keeps point masses apart from parts, joint primitives apart from joints,
        VTORQUE and GFORCE apart from VFORCE; pysolver has one id space for each group: a
        clash gets the next free id (a DeckWarning says which)."""
        primary = {st.id for name, st in space if name in _PRIMARY}
        nxt = max([st.id for _, st in space] + [0]) + 1
        taken = set(primary)
        for name, stmt in space:
            if name in _PRIMARY:
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

    def marker_pose(self, mid, seen=()):
        """Global (origin, axes) of marker mid."""
        stmt, vals, lines = self.markers[mid]
        if mid in seen:
            raise self.error(stmt, "RM markers refer to each other in a loop", "RM")
        key = "PART" if "PART" in vals else "POINT_MASS"
        body = self.id(vals[key], key)
        if body not in self.parts:
            raise self.error(stmt, f"{key.lower().replace('_', ' ')} {vals[key]} does not "
                             "exist", key, lines.get(key))
        ref = self.parts[body]
        if "RM" in vals and not vals.get("FLOATING"):
            if vals["RM"] not in self.markers:
                raise self.error(stmt, f"marker {vals['RM']} does not exist", "RM", lines["RM"])
            ref = self.marker_pose(vals["RM"], seen + (mid,))
        if vals.get("FLOATING"):
            return ref
        return self.frame(stmt, vals, lines, "QP", "REULER", "ZP", "XP", ref)


def _label(stmt):
    return {"LABEL": stmt.label} if stmt.label else {}


def _pick(vals, mapping):
    """Keyword arguments of a statement function from an .adm statement's values."""
    return {new: vals[old] for old, new in mapping.items() if old in vals}


def _refuse(r, stmt, vals, lines, keys, why):
    for k in keys:
        if k in vals:
            raise r.error(stmt, f"{k} is not supported: {why}", k, lines[k])


def _one_flag(r, stmt, vals, flags, what):
    given = [f for f in flags if vals.get(f)]
    if len(given) != 1:
        raise r.error(stmt, f"give one of {', '.join(flags)} ({what})")
    return given[0]


def _units(r, stmt, vals, lines):
    _refuse(r, stmt, vals, lines, ("UCF",), "give FORCE, MASS, LENGTH and TIME")
    kw = dict(_SYSTEMS.get(str(vals.pop("SYSTEM", "")).upper(), {})) if "SYSTEM" in vals else {}
    if "SYSTEM" in lines and not kw:
        raise r.error(stmt, f"unknown SYSTEM; expected {', '.join(_SYSTEMS)}", "SYSTEM")
    for key in ("FORCE", "MASS", "LENGTH", "TIME"):
        if key in vals:
            kw[key] = _UNIT_NAMES.get(str(vals[key]).upper(), str(vals[key]).upper())
    msolve.UNITS(**kw)


_SYSTEMS = {"MKS": dict(FORCE="NEWTON", MASS="KILOGRAM", LENGTH="METER", TIME="SECOND"),
            "MMKS": dict(FORCE="NEWTON", MASS="KILOGRAM", LENGTH="MILLIMETER", TIME="SECOND"),
            "CGS": dict(FORCE="DYNE", MASS="GRAM", LENGTH="CENTIMETER", TIME="SECOND"),
            "FPS": dict(FORCE="POUND_FORCE", MASS="POUND_MASS", LENGTH="FOOT", TIME="SECOND"),
            "IPS": dict(FORCE="POUND_FORCE", MASS="POUND_MASS", LENGTH="INCH", TIME="SECOND")}
_UNIT_NAMES = {"KNEWTON": "KILONEWTON", "MNEWTON": "MILLINEWTON", "TONNE": "MEGAGRAM",
               "KG": "KILOGRAM", "MM": "MILLIMETER", "M": "METER", "SEC": "SECOND",
               "S": "SECOND", "N": "NEWTON", "LBF": "POUND_FORCE", "LBM": "POUND_MASS",
               "POUND": "POUND_FORCE", "MSEC": "MILLISECOND", "MS": "MILLISECOND"}


def _part(r, stmt, vals, lines):
    r.need_id(stmt)
    if vals.get("GROUND"):
        msolve.PART(stmt.id, GROUND=True, **_label(stmt))
        return
    if "EXACT" in vals:
        r.warn(stmt, "EXACT (coordinates the assembly keeps) is set aside: pysolver's "
               "assembly changes the initial positions least (docs/joints.md)", lines["EXACT"])
    kw = _pick(vals, {"MASS": "MASS", "CM": "CM", "IM": "IM", "VX": "VX", "VY": "VY",
                      "VZ": "VZ", "WX": "WX", "WY": "WY", "WZ": "WZ", "VM": "VM", "WM": "WM"})
    if "IP" in vals:
        ip = vals["IP"] if isinstance(vals["IP"], list) else [vals["IP"]]
        if len(ip) not in (3, 6):
            raise r.error(stmt, "IP takes xx, yy, zz[, xy, xz, yz]", "IP", lines["IP"])
        kw["IP"] = ip[:3] + ([ip[3], ip[5], ip[4]] if len(ip) == 6 else [])
    msolve.PART(stmt.id, **kw, **_label(stmt))


def _point_mass(r, stmt, vals, lines):
    r.need_id(stmt)
    msolve.POINT_MASS(r.id(stmt), **_pick(vals, {"MASS": "MASS", "CM": "CM", "VX": "VX",
                                              "VY": "VY", "VZ": "VZ"}), **_label(stmt))


def _marker(r, stmt, vals, lines):
    _refuse(r, stmt, vals, lines, ("FLEX_BODY", "FE_PART", "NODE_ID", "NODE_LABEL"),
            "pysolver has rigid bodies only")
    if "PART" not in vals and "POINT_MASS" not in vals:
        raise r.error(stmt, "a marker needs PART= (or POINT_MASS=)")
    o, A = r.marker_pose(stmt.id)
    key = "PART" if "PART" in vals else "POINT_MASS"
    body = r.id(vals[key], key)
    msolve.MARKER(stmt.id, PART=body, QP=o.tolist(),
                  AXES=A.T.ravel().tolist(), **_label(stmt))


_JOINT_TYPES = ("CONVEL", "CYLINDRICAL", "FIXED", "HOOKE", "PLANAR", "RACKPIN", "REVOLUTE",
                "SCREW", "SPHERICAL", "TRANSLATIONAL", "UNIVERSAL")
_JPRIM_TYPES = ("ATPOINT", "INLINE", "INPLANE", "ORIENTATION", "PARALLEL_AXES",
                "PERPENDICULAR")


def _joint(r, stmt, vals, lines):
    r.need_id(stmt)
    _refuse(r, stmt, vals, lines, ("IC", "ICTRAN", "ICROT"), "initial joint coordinates; give "
            "the markers' positions, or a MOTION with ICDISP/ICVEL")
    kind = _one_flag(r, stmt, vals, _JOINT_TYPES, "the joint type")
    msolve.JOINT(stmt.id, TYPE=kind, **_pick(vals, {"I": "I", "J": "J", "PD": "PD",
                                                    "PITCH": "PITCH"}), **_label(stmt))


def _jprim(r, stmt, vals, lines):
    r.need_id(stmt)
    kind = _one_flag(r, stmt, vals, _JPRIM_TYPES, "the primitive")
    msolve.JPRIM(r.id(stmt), TYPE=kind, **_pick(vals, {"I": "I", "J": "J"}), **_label(stmt))


def _routine(vals):
    return _pick(vals, {"ROUTINE": "ROUTINE"})


def _motion(r, stmt, vals, lines):
    r.need_id(stmt)
    kw = _pick(vals, {"FUNCTION": "FUNCTION", "ICDISP": "IC_DISP", "ICVEL": "IC_VEL"})
    given = [k for k in ("DISPLACEMENT", "VELOCITY", "ACCELERATION") if vals.get(k)]
    if len(given) > 1:
        raise r.error(stmt, "give one of DISPLACEMENT, VELOCITY, ACCELERATION")
    kw["VAL_TYPE"] = given[0][0] if given else "D"
    if "JOINT" in vals:
        kinds = [k for k in ("TRANSLATION", "ROTATION") if vals.get(k)]
        if len(kinds) > 1:
            raise r.error(stmt, "give TRANSLATION or ROTATION, not both")
        if kinds:
            kw["TYPE"] = kinds[0]
        msolve.MOTION(stmt.id, JOINT=vals["JOINT"], **kw, **_routine(vals), **_label(stmt))
        return
    direction = _one_flag(r, stmt, vals, ("X", "Y", "Z", "B1", "B2", "B3"),
                          "the direction of a marker motion, or JOINT=")
    msolve.MOTION(stmt.id, **_pick(vals, {"I": "I", "J": "J"}), DIRECTION=direction, **kw,
                  **_routine(vals), **_label(stmt))


def _gcon(r, stmt, vals, lines):
    r.need_id(stmt)
    msolve.GCON(stmt.id, **_pick(vals, {"FUNCTION": "FUNCTION", "I": "I"}), **_routine(vals),
                **_label(stmt))


def _coupler(r, stmt, vals, lines):
    r.need_id(stmt)
    _refuse(r, stmt, vals, lines, ("FUNCTION", "ROUTINE"), "COUSUB, a coupler's user "
            "subroutine, is not supported yet")
    kw = _pick(vals, {"JOINTS": "JOINTS", "SCALES": "SCALES"})
    for k in ("JOINTS", "SCALES"):
        if k in kw and not isinstance(kw[k], list):
            kw[k] = [kw[k]]
    if "TYPE" in vals:
        kw["TYPE"] = str(vals["TYPE"]) if not isinstance(vals["TYPE"], list) else \
            ":".join(map(str, vals["TYPE"]))
    msolve.COUPLER(stmt.id, **kw, **_label(stmt))


def _sforce(r, stmt, vals, lines):
    r.need_id(stmt)
    msolve.SFORCE(stmt.id, **_pick(vals, {"I": "I", "J": "J", "TRANSLATION": "TRANSLATION",
                                          "ROTATION": "ROTATION", "ACTIONONLY": "ACTIONONLY",
                                          "FUNCTION": "FUNCTION"}), **_routine(vals),
                  **_label(stmt))


def _springdamper(r, stmt, vals, lines):
    r.need_id(stmt)
    msolve.SPRINGDAMPER(stmt.id, **_pick(vals, {k: k for k in (
        "I", "J", "TRANSLATION", "ROTATION", "K", "C", "LENGTH", "FORCE", "KT", "CT",
        "ANGLE", "TORQUE")}), **_label(stmt))


def _bushing(r, stmt, vals, lines):
    r.need_id(stmt)
    kw = _pick(vals, {k: k for k in ("I", "J", "K", "C", "KT", "CT", "FORCE", "TORQUE")})
    for k in ("K", "C", "KT", "CT", "FORCE", "TORQUE"):
        if k in kw and not isinstance(kw[k], list):
            raise r.error(stmt, f"{k} takes three numbers", k, lines[k])
    msolve.BUSHING(stmt.id, **kw, **_label(stmt))


def _vector(function, comps):
    def emit(r, stmt, vals, lines):
        r.need_id(stmt)
        kw = _pick(vals, {k: k for k in ("I", "JFLOAT", "RM", *comps)})
        if "FUNCTION" in vals:
            raise r.error(stmt, "FUNCTION=USER(...) (a VFOSUB, VTOSUB or GFOSUB) is not "
                          "supported yet: give the components", "FUNCTION", lines["FUNCTION"])
        function(r.id(stmt), **kw, **_label(stmt))
    return emit


def _variable(r, stmt, vals, lines):
    r.need_id(stmt)
    if "IC" in vals:
        r.warn(stmt, "IC is set aside: pysolver's variables are explicit, IC only guesses "
               "an implicit one", lines["IC"])
    msolve.VARIABLE(stmt.id, **_pick(vals, {"FUNCTION": "FUNCTION"}), **_routine(vals),
                    **_label(stmt))


def _spline(r, stmt, vals, lines):
    r.need_id(stmt)
    _refuse(r, stmt, vals, lines, ("FILE", "CHANNEL", "BLOCK"), "spline data from files; "
            "give X= and Y=")
    x = vals.get("X", [])
    x = x if isinstance(x, list) else [x]
    ys = vals.get("Y", [])
    kw = {"LINEAR_EXTRAPOLATE": bool(vals.get("LINEAR_EXTRAPOLATE"))}
    if len(ys) == 1:                            # a curve
        msolve.SPLINE(stmt.id, X=x, Y=ys[0], **kw, **_label(stmt))
        return
    # a surface: one Y= per z value, its first number the z value
    msolve.SPLINE(stmt.id, X=x, Y=[y[1:] for y in ys], Z=[y[0] for y in ys], **kw,
                  **_label(stmt))


def _sensor(r, stmt, vals, lines):
    r.need_id(stmt)
    for k in ("CODGEN", "YYDUMP", "DUMP"):
        if vals.get(k):
            r.warn(stmt, f"{k} is an Adams diagnostic; set aside", lines[k])
    kw = _pick(vals, {"FUNCTION": "FUNCTION", "VALUE": "VALUE", "ERROR": "ERROR",
                      "HALT": "HALT", "RETURN": "RETURN", "PRINT": "PRINT",
                      "RESTART": "RESTART", "STEPSIZE": "STEPSIZE", "EVALUATE": "EVALUATE"})
    ops = [k for k in ("EQ", "GE", "LE") if vals.get(k)]
    if len(ops) > 1:
        raise r.error(stmt, "give one of EQ, GE, LE")
    kw["OPERATOR"] = ops[0] if ops else "EQ"
    msolve.SENSOR(stmt.id, **kw, **_routine(vals), **_label(stmt))


_REQUEST_TYPES = {"DISPLACEMENT": "MARKER_DISPLACEMENT", "VELOCITY": "MARKER_VELOCITY",
                  "ACCELERATION": "MARKER_ACCELERATION", "FORCE": "MARKER_FORCE"}


def _request(r, stmt, vals, lines):
    r.need_id(stmt)
    _refuse(r, stmt, vals, lines, ("VARIABLES",), "a request of variables; use F1..F8 with "
            "VARVAL()")
    kinds = [k for k in _REQUEST_TYPES if vals.get(k)]
    if len(kinds) > 1:
        raise r.error(stmt, f"give one of {', '.join(_REQUEST_TYPES)}")
    kw = _pick(vals, {f"F{k}": f"F{k}" for k in range(1, 9)})
    if "COMMENT" in vals or "TITLE" in vals:
        kw["COMMENT"] = str(vals.get("COMMENT", vals.get("TITLE")))
    if kinds:
        kw.update(TYPE=_REQUEST_TYPES[kinds[0]], **_pick(vals, {"I": "I", "J": "J",
                                                                "RM": "RM"}))
    if "FUNCTION" in vals:
        kw["FUNCTION"] = vals["FUNCTION"]
    msolve.REQUEST(stmt.id, **kw, **_routine(vals), **_label(stmt))


def _accgrav(r, stmt, vals, lines):
    msolve.ACCGRAV(**_pick(vals, {"IGRAV": "IGRAV", "JGRAV": "JGRAV", "KGRAV": "KGRAV"}))


_GRAPHIC_TYPES = ("CYLINDER", "BOX", "FRUSTUM", "SPHERE", "ELLIPSOID", "CIRCLE", "ARC",
                  "OUTLINE", "PLANE", "TORUS", "LINK", "EXTERNAL", "POINT", "FORCE",
                  "SPDP", "BLOCK", "REVOLUTION", "EXTRUSION")


def _graphics(r, stmt, vals, lines):
    r.need_id(stmt)
    kinds = [k for k in _GRAPHIC_TYPES if vals.get(k) is True]
    kw = {k.lower(): (", ".join(map(str, v)) if isinstance(v, list) else v)
          for k, v in vals.items() if vals.get(k) is not True}
    msolve.GRAPHICS(stmt.id, TYPE=kinds[0] if kinds else "OUTLINE", **kw)


_INTEGRATORS = ("GSTIFF", "WSTIFF", "CONSTANT_BDF", "HHT", "NEWMARK", "HASTIFF", "ABAM",
                "RKF45", "I3", "SI2", "SI1")


def _integrator(r, stmt, vals, lines):
    other = [k for k in ("HHT", "NEWMARK", "HASTIFF", "ABAM", "RKF45") if k in vals]
    if other:
        r.warn(stmt, f"{other[0]} is not pysolver's integrator: it integrates with IDA's "
               "variable-order BDF (as GSTIFF) and its own formulation (docs/numerics.md); "
               "ERROR, HMAX, HMIN and HINIT are used")
    msolve.INTEGRATOR(**_pick(vals, {"ERROR": "ERROR", "HMAX": "HMAX", "HMIN": "HMIN",
                                     "HINIT": "HINIT"}))


def _equilibrium(r, stmt, vals, lines):
    other = [k for k in ("TLIMIT", "ALIMIT", "PATTERN", "DYNAMIC", "STATIC") if k in vals]
    if other:
        r.warn(stmt, f"{', '.join(other)} set aside: pysolver's statics are FIM_S Newton "
               "with its own damping (docs/statics.md)")
    msolve.EQUILIBRIUM(**_pick(vals, {"ERROR": "ERROR", "IMBALANCE": "IMBALANCE",
                                      "MAXIT": "MAXIT", "STABILITY": "STABILITY"}))


_ANALYSES = {"DYNAMICS": "TRANSIENT", "TRANSIENT": "TRANSIENT", "KINEMATICS": "TRANSIENT",
             "STATICS": "STATIC", "INITIAL_CONDITIONS": "ASSEMBLY"}


def _simulate(r, stmt, vals, lines):
    kind = _one_flag(r, stmt, vals, tuple(_ANALYSES), "the analysis")
    kw = _pick(vals, {"END": "END", "DURATION": "DURATION", "STEPS": "STEPS",
                      "DTOUT": "DTOUT"})
    msolve.SIMULATE(TYPE=_ANALYSES[kind], **kw)


_FUNCS = ("ROUTINE",)
#: Statements that share one pysolver id space, and the one of each that keeps its ids.
_SHARED = {"PART": "body", "POINT_MASS": "body", "JOINT": "joint", "JPRIM": "joint",
           "VFORCE": "vforce", "VTORQUE": "vforce", "GFORCE": "vforce"}
_PRIMARY = ("PART", "JOINT", "VFORCE")
#: Statement -> (its keywords, its translation).
DATASET = {
    "UNITS": (("FORCE", "MASS", "LENGTH", "TIME", "SYSTEM", "UCF"), _units),
    "PART": (("GROUND", "MASS", "CM", "IM", "IP", "QG", "REULER", "XG", "ZG", "VX", "VY",
              "VZ", "WX", "WY", "WZ", "VM", "WM", "EXACT", "MATERIAL", "PLANAR"), _part),
    "POINT_MASS": (("MASS", "CM", "QG", "REULER", "XG", "ZG", "VX", "VY", "VZ", "EXACT"),
                   _point_mass),
    "MARKER": (("PART", "POINT_MASS", "FLEX_BODY", "FE_PART", "NODE_ID", "NODE_LABEL", "QP",
                "REULER", "ZP", "XP", "USEXP", "RM", "FLOATING"), _marker),
    "JOINT": (_JOINT_TYPES + ("I", "J", "PD", "PITCH", "IC", "ICTRAN", "ICROT"), _joint),
    "JPRIM": (_JPRIM_TYPES + ("I", "J"), _jprim),
    "MOTION": (("JOINT", "I", "J", "TRANSLATION", "ROTATION", "X", "Y", "Z", "B1", "B2", "B3",
                "DISPLACEMENT", "VELOCITY", "ACCELERATION", "FUNCTION", "ICDISP", "ICVEL")
               + _FUNCS, _motion),
    "GCON": (("FUNCTION", "I") + _FUNCS, _gcon),
    "COUPLER": (("JOINTS", "TYPE", "SCALES", "FUNCTION") + _FUNCS, _coupler),
    "SFORCE": (("I", "J", "TRANSLATION", "ROTATION", "ACTIONONLY", "FUNCTION") + _FUNCS,
               _sforce),
    "SPRINGDAMPER": (("I", "J", "TRANSLATION", "ROTATION", "K", "C", "LENGTH", "FORCE", "KT",
                      "CT", "ANGLE", "TORQUE"), _springdamper),
    "BUSHING": (("I", "J", "K", "C", "KT", "CT", "FORCE", "TORQUE"), _bushing),
    "VFORCE": (("I", "JFLOAT", "RM", "FX", "FY", "FZ", "FUNCTION") + _FUNCS,
               _vector(msolve.VFORCE, ("FX", "FY", "FZ"))),
    "VTORQUE": (("I", "JFLOAT", "RM", "TX", "TY", "TZ", "FUNCTION") + _FUNCS,
                _vector(msolve.VTORQUE, ("TX", "TY", "TZ"))),
    "GFORCE": (("I", "JFLOAT", "RM", "FX", "FY", "FZ", "TX", "TY", "TZ", "FUNCTION") + _FUNCS,
               _vector(msolve.GFORCE, ("FX", "FY", "FZ", "TX", "TY", "TZ"))),
    "VARIABLE": (("FUNCTION", "IC") + _FUNCS, _variable),
    "SPLINE": (("X", "Y", "LINEAR_EXTRAPOLATE", "FILE", "CHANNEL", "BLOCK"), _spline),
    "SENSOR": (("FUNCTION", "VALUE", "ERROR", "EQ", "GE", "LE", "HALT", "RETURN", "PRINT",
                "RESTART", "STEPSIZE", "EVALUATE", "CODGEN", "YYDUMP", "DUMP") + _FUNCS,
               _sensor),
    "REQUEST": (tuple(_REQUEST_TYPES) + ("I", "J", "RM", "FUNCTION", "TITLE", "COMMENT",
                                         "VARIABLES", *(f"F{k}" for k in range(1, 9)))
                + _FUNCS, _request),
    "ACCGRAV": (("IGRAV", "JGRAV", "KGRAV"), _accgrav),
    "GRAPHICS": (None, _graphics),          # kept as written, for the 3-D view
    "INTEGRATOR": (_INTEGRATORS + ("ERROR", "HMAX", "HMIN", "HINIT", "MAXIT", "KMAX",
                                   "PATTERN", "CORRECTOR", "INTERPOLATE", "ALPHA", "BETA",
                                   "GAMMA"), _integrator),
    "EQUILIBRIUM": (("ERROR", "IMBALANCE", "MAXIT", "STABILITY", "TLIMIT", "ALIMIT",
                     "PATTERN", "DYNAMIC", "STATIC"), _equilibrium),
}
#: Commands of a command file (after the dataset's and output's names).
COMMANDS = {
    "SIMULATE": (tuple(_ANALYSES) + ("END", "DURATION", "STEPS", "DTOUT"), _simulate),
    "INTEGRATOR": DATASET["INTEGRATOR"],
    "EQUILIBRIUM": DATASET["EQUILIBRIUM"],
}


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
    (the dataset) and second (the output name) are left out."""
    lines = acf_text.splitlines()
    return (dataset_text.rstrip("\n") + f"\n{COMMANDS_MARK} {acf_file}\n"
            + "\n".join(lines[2:]) + "\n")


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
