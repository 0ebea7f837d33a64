"""Entry points that turn a deck file or text into a validated Model."""
from __future__ import annotations

import io
import os
import re
import sys
import tokenize
import traceback

from ..errors import DeckError
from ..model import Model, Source
from . import msolve
from .validate import build_model
from .xml_reader import read_elements


def load(path: str | os.PathLike, user_code: bool = True) -> Model:
    """Load and validate a deck.

    Parameters
    ----------
    path : str or os.PathLike
        ``.xml`` (MotionSolve XML; data only, never executes code) or ``.py`` (a Python script
        of :mod:`pysolver.msolve` statements; it is executed).
    user_code : bool, default True
        False refuses a deck that would run code of its own: a ``.py`` deck, and any element
        with a user subroutine (a Python script or a C library), each a DeckError naming it.
        What runs when: docs/user-subroutines.md.

    Returns
    -------
    Model

    Raises
    ------
    DeckError
        The deck is malformed or inconsistent; the message names file, line, element, id and
        attribute.
    FileNotFoundError
        There is no such file.
    """
    path = os.fspath(path)
    if os.path.isdir(path):
        raise DeckError("is a folder, not a deck file", file=path)
    with open(path, "rb") as fh:
        raw = fh.read()
    fmt = "py" if path.lower().endswith(".py") else "xml"
    return loads(_decode(raw, fmt, path), fmt=fmt, file=path, user_code=user_code)


_XML_ENCODING = re.compile(rb"""^\s*<\?xml[^>]*?encoding\s*=\s*["']([A-Za-z0-9._-]+)["']""")


def _decode(raw, fmt, path):
    """A deck's text: XML in the encoding its declaration names (UTF-8 without one), Python
    by its coding line (PEP 263)."""
    if fmt == "py":
        try:
            encoding = tokenize.detect_encoding(io.BytesIO(raw).readline)[0]
        except SyntaxError as err:
            raise DeckError(f"cannot read the file: {err}", file=path) from None
    else:
        found = _XML_ENCODING.match(raw)
        encoding = found.group(1).decode() if found else "utf-8"
    try:
        return raw.decode(encoding)
    except LookupError:
        raise DeckError(f"unknown text encoding {encoding!r} in the XML declaration",
                        file=path, line=1) from None
    except UnicodeDecodeError as err:
        line = raw[:err.start].count(b"\n") + 1
        raise DeckError(f"the file is not valid {encoding} text (byte {err.start}: "
                        f"{raw[err.start:err.start + 1]!r}); declare its encoding",
                        file=path, line=line) from None


def loads(text: str, fmt: str = "xml", file: str = "<string>",
          user_code: bool = True) -> Model:
    """Load a deck from text; ``fmt`` is ``"xml"`` or ``"py"``. See :func:`load`."""
    if fmt == "xml":
        elements = read_elements(text, file)
    elif fmt == "py":
        if not user_code:
            raise DeckError("a Python deck is a program, and user_code=False refuses code "
                            "(--no-user-code): write the deck as XML", file=file)
        elements = _run_python_deck(text, file)
    else:
        raise ValueError(f"unknown deck format {fmt!r}; expected 'xml' or 'py'")
    return build_model(elements, Source(file, text, fmt, user_code))


def _deck_line(file):
    """The deck's own line in the traceback being handled (None when it is not in it)."""
    line = None
    for fr in traceback.extract_tb(sys.exc_info()[2]):
        if fr.filename == file:
            line = fr.lineno
    return line


def _run_python_deck(text, file):
    rec = msolve._Recorder(file)
    namespace = {"__name__": "__pysolver_deck__", "__file__": file}
    namespace.update({name: getattr(msolve, name) for name in msolve.__all__})
    prev = getattr(msolve._STATE, "rec", None)
    msolve._STATE.rec = rec
    try:
        code = compile(text, file, "exec")
        exec(code, namespace)
    except DeckError:
        raise
    except SyntaxError as err:
        raise DeckError(f"Python syntax error: {err.msg}", file=file, line=err.lineno) from None
    except SystemExit as err:   # the deck may not end the program that reads it
        raise DeckError(f"the deck called sys.exit({err.code!r}); a deck script is read for "
                        "its statements and must not exit", file=file,
                        line=_deck_line(file)) from None
    except Exception as err:  # the deck's own error: report where it happened in the deck
        raise DeckError(f"{type(err).__name__}: {err}", file=file,
                        line=_deck_line(file)) from None
    finally:
        msolve._STATE.rec = prev
    return rec.elements
