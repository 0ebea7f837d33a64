"""Exceptions raised for bad input, and the warning a deck that loads may give."""
import errno
import os
import sys
import warnings

#: The package's folder: a DeckWarning is attributed to the first frame outside it.
_PACKAGE = os.path.dirname(os.path.abspath(__file__)) + os.sep


class DeckError(ValueError):
    """A deck is malformed or inconsistent.

    The message names where the problem is: file, line, element and id, attribute, and what
    was expected. The same fields are available as attributes for programs.

    Parameters
    ----------
    message : str
        What is wrong and what is expected.
    file : str or None
        Path of the deck.
    line : int or None
        1-based line of the element (XML) or statement (Python deck).
    element : str or None
        Element or statement name, e.g. ``Force_Penalty`` or ``PFORCE``.
    id : int or None
        The element's id, if it has one.
    attribute : str or None
        The attribute or argument at fault.
    """

    def __init__(self, message, file=None, line=None, element=None, id=None, attribute=None):
        self.reason = message
        self.file = file
        self.line = line
        self.element = element
        self.id = id
        self.attribute = attribute
        super().__init__(self._format())

    def __reduce__(self):               # a worker's DeckError keeps its fields in the parent
        return type(self), (self.reason, self.file, self.line, self.element, self.id,
                            self.attribute)

    def _format(self):
        where = []
        if self.file:
            where.append(str(self.file) + (f":{self.line}" if self.line else ""))
        elif self.line:
            where.append(f"line {self.line}")
        if self.element:
            where.append(self.element + (f" id={self.id}" if self.id is not None else ""))
        if self.attribute:
            where.append(f"attribute '{self.attribute}'")
        return (", ".join(where) + ": " if where else "") + self.reason


class MissingFileError(DeckError, FileNotFoundError):
    """A deck file, or the dataset a command file names, does not exist: a :class:`DeckError`
    (bad input, located at `file` and `line`) that ``except FileNotFoundError`` also catches,
    with ``filename`` the file that is missing.

    Parameters
    ----------
    missing : str
        The path that does not exist.
    message : str, default "no such file"
        What is wrong.
    file, line : optional
        Where the problem is stated (default: the missing file itself).
    """

    def __init__(self, missing, message="no such file", file=None, line=None):
        super().__init__(message, file=missing if file is None else file, line=line)
        self.errno, self.strerror, self.filename = errno.ENOENT, message, missing
        self._given = (missing, message, file, line)

    def __reduce__(self):               # rebuilt from what it was given, not from its text
        return type(self), self._given

    def __str__(self):                  # the located message, not OSError's "[Errno 2] ..."
        return self._format()


class UsageError(Exception):
    """A mistake on the command line (an option, a file of cases): the ``pysolver`` command
    prints it as one line ``pysolver: error: <message>`` and exits with status 2."""


class DeckWarning(UserWarning):
    """A deck loads, but part of it is read in a way its author may not have meant (an
    ambiguity of the public documentation, decided in docs/). Located like :class:`DeckError`,
    with the same attributes."""

    def __init__(self, message, file=None, line=None, element=None, id=None, attribute=None):
        where = DeckError(message, file, line, element, id, attribute)
        self.reason, self.file, self.line = message, file, line
        self.element, self.id, self.attribute = element, id, attribute
        super().__init__(str(where))


def warn(warning):
    """Issue `warning` (a :class:`DeckWarning`) as the user's code's: attributed to the first
    frame outside pysolver (the line that loads the deck, or the Python deck's own
    statement), so that Python's warning line never shows a line of pysolver's code (the
    ``pysolver`` command prints ``pysolver: warning: ...`` instead)."""
    frame, level = sys._getframe(1), 2
    while frame.f_back is not None and \
            os.path.abspath(frame.f_code.co_filename).startswith(_PACKAGE):
        frame, level = frame.f_back, level + 1
    warnings.warn(warning, stacklevel=level)


class ExpressionError(ValueError):
    """A syntax or semantic error inside one expression string (column is 0-based)."""

    def __init__(self, message, column=None):
        self.reason = message
        self.column = column
        super().__init__(message if column is None else f"{message} (at column {column + 1})")
