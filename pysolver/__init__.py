"""pysolver: multibody dynamics for MotionSolve/Adams-style decks.

>>> import pysolver
>>> model = pysolver.load("decks/catenary_bead.xml")   # doctest: +SKIP
>>> res = model.run()                                  # doctest: +SKIP
>>> res.request(1)[:, 0]                               # doctest: +SKIP
"""
from . import msolve as _msolve  # noqa: F401,E402  (the namespace Python decks run in)
from ._version import __version__
from .batch import Sweep, grid, sample, sweep
from .deck.loader import load, loads
from .errors import DeckError, DeckWarning
from .headers import get_include
from .model import Model
from .results import Result

__all__ = ["load", "loads", "DeckError", "DeckWarning", "Model", "Result", "get_include",
           "__version__", "sweep", "grid", "sample", "Sweep"]
