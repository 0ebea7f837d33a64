"""What a Python deck's model depends on besides its own text, for a sweep's resume key
(pysolver.batch.case.fingerprint; docs/batch.md, "Resuming").

A Python deck is a program: the numbers it builds may come from modules it imports or files
it reads. :func:`elements_digest` hashes what it built (every statement it recorded, with its
numbers, a Python routine by its code), whatever they came from; :func:`local_modules` names
the source files of the modules it imports that are not part of the Python installation (the
user's own: a settings file, a geometry module beside the deck), found from its import
statements and theirs, so that editing one changes the key even where it changes only code.
"""
import ast
import functools
import hashlib
import importlib.util
import marshal
import os
import re
import site
import sys
import warnings

import numpy as np

from ..errors import DeckWarning

_ADDRESS = re.compile(r" at 0x[0-9a-fA-F]+")

#: Module files hashed so far in this process: real path -> (the module's import spec, digest)
#: (an import or importlib.reload makes a new spec).
_SEEN = {}


def code_token(fn):
    """A callable as text that changes when its code does: its module, name, code (with the
    code of the functions it defines), defaults and closure values."""
    fn = getattr(fn, "__func__", fn)
    parts = [getattr(fn, "__module__", "") or "", getattr(fn, "__qualname__", "") or ""]
    code = getattr(fn, "__code__", None)
    if code is None:
        return "callable:" + "|".join(parts + [_ADDRESS.sub("", repr(fn))])
    parts.append(hashlib.sha256(marshal.dumps(code)).hexdigest())
    parts.append(_ADDRESS.sub("", repr(getattr(fn, "__defaults__", None))))
    for cell in getattr(fn, "__closure__", None) or ():
        try:
            parts.append(_ADDRESS.sub("", repr(cell.cell_contents)))
        except ValueError:
            parts.append("<empty>")
    return "function:" + "|".join(parts)


def _token(value):
    """A deck attribute's value as text: numbers exactly, sequences item by item, a callable
    by its code."""
    if isinstance(value, (list, tuple)):
        return "[" + ",".join(_token(v) for v in value) + "]"
    if isinstance(value, np.ndarray):
        return _token(value.tolist())
    if callable(value):
        return code_token(value)
    return f"{type(value).__name__}:{_ADDRESS.sub('', repr(value))}"


def elements_digest(elements):
    """A hash of the elements a deck recorded (tag and attributes, in order; not where they
    were written)."""
    h = hashlib.sha256()
    for tag, attrs, _line, _names in elements:
        h.update(tag.encode("utf-8", "surrogatepass") + b"\0")
        for key in sorted(attrs, key=str):
            h.update(f"{key}={_token(attrs[key])}".encode("utf-8", "surrogatepass") + b"\0")
        h.update(b"\1")
    return h.hexdigest()


@functools.lru_cache(maxsize=1)
def _installation():
    """Folders of the Python installation and its packages (never the user's own modules),
    and pysolver's own package."""
    roots = {sys.prefix, sys.base_prefix, sys.exec_prefix, sys.base_exec_prefix,
             os.path.dirname(os.path.dirname(os.path.abspath(__file__)))}
    try:
        roots.update(site.getsitepackages())
    except AttributeError:              # a virtualenv's old site module
        pass
    roots.add(site.getusersitepackages())
    return tuple(os.path.realpath(r) + os.sep for r in roots if r)


def _is_local(path, installed):
    real = os.path.realpath(path)
    parts = real.split(os.sep)
    return os.path.isfile(real) and not real.startswith(installed) and \
        "site-packages" not in parts and "dist-packages" not in parts


def _imported_names(tree, package):
    """The modules an import statement anywhere in `tree` may have imported: every prefix of
    a dotted name, and the names a ``from`` import takes (submodules among them)."""
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            bases = [a.name for a in node.names]
            extra = []
        elif isinstance(node, ast.ImportFrom):
            try:
                base = importlib.util.resolve_name("." * node.level + (node.module or ""),
                                                   package) if node.level else node.module
            except (ImportError, ValueError):
                continue
            if not base:
                continue
            bases = [base]
            extra = [f"{base}.{a.name}" for a in node.names if a.name != "*"]
        else:
            continue
        for name in bases:
            pieces = name.split(".")
            names.update(".".join(pieces[:k]) for k in range(1, len(pieces) + 1))
        names.update(extra)
    return names


def local_modules(text, file):
    """The source files of the user's own modules a Python deck imported (directly or through
    another such module), as (path, sha256) pairs sorted by path: the modules its import
    statements name that have been imported (they are in sys.modules once the deck ran) and
    whose file is outside the Python installation, site-packages and pysolver."""
    installed = _installation()
    deck = os.path.realpath(file) if file else None
    found = {}
    todo = [(text, None)]
    while todo:
        source, package = todo.pop()
        try:
            tree = ast.parse(source)
        except (SyntaxError, ValueError):
            continue
        for name in sorted(_imported_names(tree, package)):
            module = sys.modules.get(name)
            path = getattr(module, "__file__", None)
            if not path or not _is_local(path, installed):
                continue
            real = os.path.realpath(path)
            if real in found or real == deck:
                continue
            try:
                with open(real, "rb") as fh:
                    data = fh.read()
            except OSError as err:
                found[real] = f"unreadable: {err.strerror}"
                continue
            found[real] = digest = hashlib.sha256(data).hexdigest()
            seen = _SEEN.get(real)
            spec = getattr(module, "__spec__", None)
            if seen is not None and spec is not None and seen[0] is spec and seen[1] != digest:
                warnings.warn(DeckWarning(
                    f"module {name} ({real}) changed since this session imported it, and "
                    "Python imports a module once: the deck still runs it as first imported "
                    "(a sweep's worker processes import it afresh); restart the session or "
                    "importlib.reload() it", file=file), stacklevel=4)
            else:
                _SEEN[real] = (spec, digest)
            if real.endswith(".py"):
                pkg = module.__package__ if getattr(module, "__package__", None) else None
                todo.append((data.decode("utf-8", "replace"), pkg))
    return tuple(sorted(found.items()))
