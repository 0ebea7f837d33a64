"""pysolver: multibody dynamics for MotionSolve/Adams-style decks.

>>> import pysolver
>>> model = pysolver.load("decks/catenary_bead.xml")   # doctest: +SKIP
>>> res = model.run()                                  # doctest: +SKIP
>>> res.request(1)[:, 0]                               # doctest: +SKIP
"""
from .errors import DeckError
from .loader import load, loads
from .model import Model
from .results import Result
from .simulate import __version__

__all__ = ["load", "loads", "DeckError", "Model", "Result", "__version__"]
