"""Entry points that turn a deck file or text into a validated Model."""
from __future__ import annotations

import os
import sys
import traceback

from ..errors import DeckError
from ..model import Model, Source
from . import msolve
from .validate import build_model
from .xml_reader import read_elements


def load(path: str | os.PathLike) -> Model:
    """Load and validate a deck.

    Parameters
    ----------
    path : str or os.PathLike
        ``.xml`` (MotionSolve XML; data only, never executes code) or ``.py`` (a Python script
        of :mod:`pysolver.msolve` statements; it is executed).

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
    with open(path, encoding="utf-8") as fh:
        text = fh.read()
    fmt = "py" if path.lower().endswith(".py") else "xml"
    return loads(text, fmt=fmt, file=path)


def loads(text: str, fmt: str = "xml", file: str = "<string>") -> Model:
    """Load a deck from text; ``fmt`` is ``"xml"`` or ``"py"``. See :func:`load`."""
    if fmt == "xml":
        elements = read_elements(text, file)
    elif fmt == "py":
        elements = _run_python_deck(text, file)
    else:
        raise ValueError(f"unknown deck format {fmt!r}; expected 'xml' or 'py'")
    return build_model(elements, Source(file, text, fmt))


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
    except Exception as err:  # the deck's own error: report where it happened in the deck
        line = None
        for fr in traceback.extract_tb(sys.exc_info()[2]):
            if fr.filename == file:
                line = fr.lineno
        raise DeckError(f"{type(err).__name__}: {err}", file=file, line=line) from None
    finally:
        msolve._STATE.rec = prev
    return rec.elements
