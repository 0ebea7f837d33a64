"""Statement functions for Python-format decks (``from pysolver.msolve import *``).

The statements are defined in :mod:`pysolver.deck.msolve`; this module is their public name.
"""
from .deck.msolve import *  # noqa: F401,F403
from .deck.msolve import __all__  # noqa: F401
