"""Opening a user subroutine library, so that one rebuilt at the same path is the new one.

``dlopen`` returns the library already loaded under a path, so a library rebuilt in place
(the edit, build, rerun loop of a notebook) would go on running its old code in this process
with no sign of it. Each path's file identity (device, inode, size, modification time) is
remembered when it is opened; when it has changed since, a copy named by its content's digest
is opened instead (a copy's name is new for new content, and the same for the same content,
which dlopen then shares). Copies live in a private folder removed at exit.
"""
import atexit
import hashlib
import os
import shutil
import tempfile

from .bindings import ffi, lib

_OPENED = {}          # real path -> the file identity it had when first opened
_COPIES = []          # [the folder of copies], made on first need


def _identity(path):
    st = os.stat(path)
    return (st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns)


def _copy(path):
    """A copy of the library at `path` named by its content, made once per content."""
    if not _COPIES:
        _COPIES.append(tempfile.mkdtemp(prefix="pysolver-userlib-"))
        atexit.register(shutil.rmtree, _COPIES[0], True)
    with open(path, "rb") as fh:
        digest = hashlib.sha256(fh.read()).hexdigest()[:20]
    stem, ext = os.path.splitext(os.path.basename(path))
    copy = os.path.join(_COPIES[0], f"{stem}-{digest}{ext}")
    if not os.path.exists(copy):
        shutil.copyfile(path, copy)
    return copy


def open_routine(path, name):
    """(function pointer or NULL, message): routine `name` of the library at `path`, as the
    file is now."""
    msg = ffi.new("char[256]")
    real = os.path.realpath(path)
    try:
        now = _identity(real)
    except OSError:
        now = None                      # ps_user_open reports it
    target = path
    if now is not None:
        first = _OPENED.setdefault(real, now)
        if first != now:
            target = _copy(real)
    fn = lib.ps_user_open(target.encode(), str(name).encode(), msg, 256)
    return fn, ffi.string(msg).decode(errors="replace")
