"""Building the kernel: the state layout and expression tapes (:mod:`.compiler`), and the
compiled scene bound to the C kernel through cffi (:mod:`.kernel`, :mod:`.bindings`, the one
module that imports the extension).
"""
from .kernel import Kernel

__all__ = ["Kernel"]
