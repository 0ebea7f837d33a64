"""The Python model language (``from pysolver.msolve import *``).

Two styles, both Altair's: the statement functions (``PART(...)``, ``MARKER(...)``, defined in
:mod:`pysolver.deck.msolve`) and the msolve classes (``Model()``, ``Part(...)``,
``Marker(...)``, ``model.simulate(...)``, defined in :mod:`pysolver.modeling`).
"""
from .deck.msolve import *  # noqa: F401,F403
from .deck.msolve import __all__ as _statements
from .modeling import *  # noqa: F401,F403
from .modeling import __all__ as _classes

__all__ = list(_statements) + list(_classes)

from .deck import msolve as _deck  # noqa: E402

_deck.PUBLIC = __import__("sys").modules[__name__]
