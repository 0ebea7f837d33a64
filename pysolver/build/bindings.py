"""The one import point for the compiled kernel: re-exports ``ffi`` and ``lib``.

Nothing else in the package touches the cffi module directly.
"""
try:
    from .._kernel import ffi, lib  # noqa: F401
except ImportError as err:  # pragma: no cover - only on a broken install
    raise ImportError("pysolver's C kernel is not built: install with 'pip install .' "
                      "(or run 'python pysolver/_build_ffi.py --inplace' in a checkout)") from err
