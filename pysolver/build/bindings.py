"""The one import point for the compiled kernel: re-exports ``ffi`` and ``lib``.

Nothing else in the package touches the cffi module directly. In a source checkout whose kernel
is not built (say, the README's example run from the repository root after ``pip install .``,
where the checkout's ``pysolver`` folder shadows the installed package) the kernel is built in
place on first import, once, under a file lock; an installed package never builds anything.
"""
import fcntl
import pathlib
import subprocess
import sys

from .. import settings

_PACKAGE = pathlib.Path(__file__).resolve().parents[1]
_BUILDER = _PACKAGE / "_build_ffi.py"


def _build_in_place():
    """Compile the kernel next to the package sources (needs a C compiler and cffi)."""
    lock_dir = _PACKAGE.parent / "build"
    lock_dir.mkdir(exist_ok=True)
    with open(lock_dir / "inplace.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)          # another process may be building it
        try:
            from .._kernel import ffi, lib  # noqa: F401
            return
        except ImportError:
            pass
        print("pysolver: building the C kernel in this source checkout (once) ...",
              file=sys.stderr)
        out = subprocess.run([sys.executable, str(_BUILDER), "--inplace"],
                             capture_output=True, text=True)
        if out.returncode:
            raise ImportError("pysolver's C kernel is not built and building it in place "
                              f"failed:\n{out.stderr[-2000:]}")


try:
    from .._kernel import ffi, lib  # noqa: F401
except ImportError as err:
    if not (_BUILDER.exists() and (_PACKAGE.parent / "csrc").is_dir()) or \
            settings.no_inplace_build():
        raise ImportError("pysolver's C kernel is not built: install with 'pip install .' "
                          "(or run 'python pysolver/_build_ffi.py --inplace' in a checkout)"
                          ) from err
    _build_in_place()
    from .._kernel import ffi, lib  # noqa: F401
