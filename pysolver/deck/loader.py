"""Entry points that turn a deck file or text into a validated Model."""
from __future__ import annotations

import io
import os
import re
import sys
import tokenize
import traceback

from ..errors import DeckError, MissingFileError
from ..model import Model, Source
from . import adams, msolve, provenance
from .validate import build_model
from .xml_reader import read_elements


def load(path: str | os.PathLike, user_code: bool = True,
         simulate: dict | None = None) -> Model:
    """Load and validate a deck.

    Parameters
    ----------
    path : str or os.PathLike
        ``.xml`` (MotionSolve XML; data only, never executes code), ``.py`` (a Python script
        of :mod:`pysolver.msolve` statements; it is executed), ``.adm`` (an Adams dataset,
        with the commands of the ``.acf`` of the same name beside it when there is one) or
        ``.acf`` (an Adams command file: the dataset its first line names, then its
        commands). docs/adams.md says what of the Adams language is read.
    simulate : dict, optional
        The attributes of one ``Simulate`` command that replaces the deck's commands
        (``{"analysis_type": "TRANSIENT", "end_time": 5, "num_step": 500}``; the command
        line's ``--end``, ``--steps``, ``--dtout``).
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
    MissingFileError
        There is no such file: a DeckError that is also a FileNotFoundError.
    """
    _not_class_model(path, "load", "a deck file")
    path = os.fspath(path)
    if os.path.isdir(path):
        raise DeckError("is a folder, not a deck file", file=path)
    ext = os.path.splitext(path)[1].lower()
    if ext == ".acf":
        return _load_acf(path, user_code, simulate)
    raw = _read(path)
    fmt = {".py": "py", ".adm": "adm", ".xml": "xml"}.get(ext) or _sniff(raw, path)
    if fmt == "xml" and raw.lstrip()[:1] != b"<" and _dataset_like(raw):
        raise DeckError("not XML: the file reads as an Adams dataset (PART/, MARKER/ ... "
                        "statements); name it .adm", file=path, line=1)
    text = _decode(raw, fmt, path)
    if fmt == "adm":
        acf = os.path.splitext(path)[0] + ".acf"
        if os.path.isfile(acf):         # the command file beside the dataset
            return _load_acf(acf, user_code, simulate, dataset=(path, text))
    return loads(text, fmt=fmt, file=path, user_code=user_code, simulate=simulate)


def _not_class_model(given, call, takes):
    """A TypeError when `given` is a model of msolve classes (pysolver.msolve.Model), which
    its own load() turns into a pysolver.Model."""
    kind = getattr(msolve.PUBLIC, "Model", None)
    if kind is not None and isinstance(given, kind):
        raise TypeError(f"pysolver.{call} reads {takes}; this is an msolve Model, whose "
                        "pysolver.Model is model.load()")


def _sniff(raw, path):
    """The format of a deck whose name does not say: XML when it starts with '<', an Adams
    dataset when a line starts like one of its statements; else a DeckError naming the
    formats pysolver reads."""
    head = raw.lstrip()[:1]
    if head == b"<":
        return "xml"
    if _dataset_like(raw):
        return "adm"
    raise DeckError("not a deck pysolver reads: expected MotionSolve XML (.xml), a Python "
                    "deck of pysolver.msolve statements (.py), an Adams dataset (.adm) or an "
                    "Adams command file (.acf)", file=path, line=1)


def _load_acf(path, user_code, simulate=None, dataset=None):
    """An Adams command file: its dataset (first line) with its commands."""
    acf = _decode(_read(path), "adm", path)
    if dataset is None:
        data_path = adams.acf_dataset(acf, path)
        if not os.path.isfile(data_path):
            raise MissingFileError(data_path, f"the dataset {data_path} named on the first "
                                   "line does not exist", file=path, line=1)
        dataset = (data_path, _decode(_read(data_path), "adm", data_path))
    text = adams.with_commands(dataset[1], acf, path)
    return loads(text, fmt="adm", file=dataset[0], user_code=user_code, simulate=simulate)


def _read(path):
    """The bytes of a deck file; MissingFileError when there is none."""
    try:
        with open(path, "rb") as fh:
            return fh.read()
    except FileNotFoundError:
        raise MissingFileError(path) from None


def _dataset_like(raw):
    """True when a line after the first starts like an Adams dataset statement."""
    lines = raw.decode("latin-1").splitlines()[1:50]
    return any(re.match(r"\s*(PART|MARKER|UNITS|JOINT|ACCGRAV|SFORCE|REQUEST)\s*/", ln, re.I)
               for ln in lines)


_XML_ENCODING = re.compile(rb"""^\s*<\?xml[^>]*?encoding\s*=\s*["']([A-Za-z0-9._-]+)["']""")


def _decode(raw, fmt, path):
    """A deck's text: XML in the encoding its declaration names (UTF-8 without one), Python
    by its coding line (PEP 263)."""
    if fmt == "adm":                    # Adams writes ASCII; older files may be Latin-1
        try:
            return raw.decode("utf-8")
        except UnicodeDecodeError:
            return raw.decode("latin-1")
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


def deck_elements(path, user_code=True, model=None):
    """(elements, title) of a deck file before they are checked: the list every format is
    read into (pysolver.deck.writer writes it as XML); title is an Adams dataset's first
    line (else None). `model`: the deck already loaded."""
    model = model if model is not None else load(path, user_code=user_code)
    text, fmt = model.source.text, model.source.fmt
    title = text.splitlines()[0].strip() if fmt == "adm" and text else None
    return _elements(text, fmt, model.source.file, user_code), title


def loads(text: str, fmt: str = "xml", file: str = "<string>",
          user_code: bool = True, simulate: dict | None = None) -> Model:
    """Load a deck from text; ``fmt`` is ``"xml"``, ``"py"`` or ``"adm"`` (an Adams
    dataset). See :func:`load`."""
    _not_class_model(text, "loads", "a deck's text")
    elements = _elements(text, fmt, file, user_code)
    source = Source(file, text, fmt, user_code, dict(simulate) if simulate else None)
    if fmt == "py":                     # a program: what it built, and the modules it imports
        source.built = provenance.elements_digest(elements)
        source.modules = provenance.local_modules(text, file)
    if simulate:
        elements = [e for e in elements if e[0].lower() not in ("simulate", "stop")]
        elements.append(("Simulate", dict(simulate), None,
                         {k: f"--{k}" for k in simulate}))
    return build_model(elements, source)


def _elements(text, fmt, file, user_code):
    if fmt == "xml":
        elements = read_elements(text, file)
    elif fmt == "adm":
        elements = adams.read_elements(text, file)
    elif fmt == "py":
        if not user_code:
            raise DeckError("a Python deck is a program, and user_code=False refuses code "
                            "(--no-user-code): write the deck as XML", file=file)
        elements = _run_python_deck(text, file)
    else:
        raise ValueError(f"unknown deck format {fmt!r}; expected 'xml', 'py' or 'adm'")
    return elements


def _deck_line(file):
    """The deck's own line in the traceback being handled (None when it is not in it)."""
    line = None
    for fr in traceback.extract_tb(sys.exc_info()[2]):
        if fr.filename == file:
            line = fr.lineno
    return line


def _run_python_deck(text, file):
    """Execute a Python deck: its statements (pysolver.deck.msolve) are recorded; or, a
    script of msolve classes (pysolver.modeling), its last Model (simulate() records its
    command and runs nothing). The script runs as __main__ (its main block too), except
    inside another deck's load."""
    rec = msolve._Recorder(file)
    prev = getattr(msolve._STATE, "rec", None)
    public = msolve.PUBLIC                  # pysolver.msolve, registered when it is imported
    namespace = {"__name__": "__pysolver_deck__" if prev else "__main__", "__file__": file}
    namespace.update({name: getattr(public, name) for name in public.__all__})
    shim = "msolve" not in sys.modules
    if shim:                                # a script's own `from msolve import *`
        sys.modules["msolve"] = public
    msolve._STATE.rec = rec
    try:
        code = compile(text, file, "exec")
        exec(code, namespace)
        if rec.models and rec.elements:
            raise DeckError("the script builds a msolve Model and also calls statement "
                            "functions (PART(...)); use one style", file=file)
        if rec.models:
            return rec.models[-1].elements()
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
        if shim:
            sys.modules.pop("msolve", None)
    return rec.elements
