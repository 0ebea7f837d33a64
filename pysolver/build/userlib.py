"""Opening a user subroutine library, so that one rebuilt at the same path is the new one.

``dlopen`` returns the library already loaded under a name, so a library rebuilt in place
(the edit, build, rerun loop of a notebook) would go on running its old code in this process
with no sign of it. The library is opened by its real path (a symlink moved to a rebuilt
file is a new name), and each real path's file identity (device, inode, size, modification
time) is remembered when first opened; when it has changed since, a copy named by its
content's digest is opened instead: a new name for new content, the same name (which dlopen
then shares) for the same content. Copies are written whole, then renamed into place, in
the kernel cache's ``userlibs`` folder (``PYSOLVER_CACHE_DIR``), where kernels are loaded
from too. A copy does not find libraries its original finds through ``$ORIGIN``: such a
library must be loaded again in a new process.
"""
import hashlib
import os
import tempfile

from .. import settings
from .bindings import ffi, lib

_OPENED = {}          # real path -> the file identity it had when first opened


def _identity(path):
    st = os.stat(path)
    return (st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns)


def _copy(path):
    """A copy of the library at `path` named by its content (made once per content), or
    None when none can be written."""
    with open(path, "rb") as fh:
        data = fh.read()
    stem, ext = os.path.splitext(os.path.basename(path))
    folder = os.path.join(settings.cache_dir(), "userlibs")
    copy = os.path.join(folder, f"{stem}-{hashlib.sha256(data).hexdigest()[:20]}{ext}")
    if os.path.exists(copy):
        return copy
    try:
        os.makedirs(folder, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=folder, suffix=ext)
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        os.replace(tmp, copy)          # whole, or not there: no half-written copy is opened
    except OSError:
        return None
    return copy


def open_routine(path, name):
    """(function pointer or NULL, message): routine `name` of the library at `path`, as the
    file is now."""
    msg = ffi.new("char[256]")
    target = os.path.realpath(path)
    try:
        now = _identity(target)
    except OSError:
        now = None                      # ps_user_open reports it
    if now is not None and _OPENED.setdefault(target, now) != now:
        target = _copy(target) or target
    fn = lib.ps_user_open(target.encode(), str(name).encode(), msg, 256)
    return fn, ffi.string(msg).decode(errors="replace")
