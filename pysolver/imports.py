"""Modules imported when first needed, and the time that takes (``Result.timing["imports"]``).

Heavy dependencies (scikit-sundae, which loads scipy.optimize; the later stages of the flow)
are imported by the code that uses them, so a run that does not need them does not pay for
them. :func:`timed` wraps such an import; :func:`spent` is the seconds the process has spent in
them so far, so a run reports the difference.
"""
import contextlib
import sys
import time

_SPENT = [0.0]
_DEPTH = [0]


@contextlib.contextmanager
def timed():
    """Count the time of the block (imports) in :func:`spent` when it imported a module not
    imported before (a repeated import statement costs nothing); nested blocks count once."""
    _DEPTH[0] += 1
    start, known = time.perf_counter(), len(sys.modules)
    try:
        yield
    finally:
        _DEPTH[0] -= 1
        if not _DEPTH[0] and len(sys.modules) != known:
            _SPENT[0] += time.perf_counter() - start


def spent():
    """Seconds this process has spent in :func:`timed` imports."""
    return _SPENT[0]
