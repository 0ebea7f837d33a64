"""Compile generated C into a shared library, cached on disk by a hash of what made it.

The key hashes what the source is a function of (the scene's compiled arrays and the generator's
own code, :func:`pysolver.build.codegen.key`), the compiler command and flags, the compiler's
version and the kernel header, so a changed generator, header or compiler never reuses a stale
library, and a warm load neither generates nor compiles. Each entry is the library and a
digest of its bytes written after a complete build; an entry whose library does not match its
digest (a crash mid-write, a truncated copy) is rebuilt, never loaded. Writes go through a
temporary file and an atomic rename, so concurrent processes building the same deck are safe.

Location: ``PYSOLVER_CACHE_DIR`` if set, else the platform's cache directory
(``$XDG_CACHE_HOME`` or ``~/.cache`` on Linux, ``~/Library/Caches`` on macOS,
``%LOCALAPPDATA%`` on Windows) under ``pysolver/kernels``.
"""
import functools
import hashlib
import os
import pathlib
import shlex
import shutil
import subprocess
import sys
import tempfile

#: Flags for the generated code: no fast-math (results must match the tapes to rounding and
#: keep IEEE NaN/inf semantics); -fno-math-errno lets sqrt inline.
FLAGS = ("-O2", "-fno-math-errno", "-fPIC", "-shared")


class NoCompiler(Exception):
    """No working C compiler: the tapes run instead."""


def cache_dir():
    """The directory holding compiled kernels (created on first use)."""
    env = os.environ.get("PYSOLVER_CACHE_DIR")
    if env:
        return pathlib.Path(env)
    home = pathlib.Path.home()
    if sys.platform == "darwin":
        base = home / "Library" / "Caches"
    elif os.name == "nt":
        base = pathlib.Path(os.environ.get("LOCALAPPDATA", home / "AppData" / "Local"))
    else:
        base = pathlib.Path(os.environ.get("XDG_CACHE_HOME") or home / ".cache")
    return base / "pysolver" / "kernels"


def compiler():
    """The C compiler command: ``CC`` if set, else cc, gcc or clang from PATH."""
    env = os.environ.get("CC")
    if env:
        return shlex.split(env)
    for name in ("cc", "gcc", "clang"):
        path = shutil.which(name)
        if path:
            return [path]
    raise NoCompiler("no C compiler on PATH (cc, gcc or clang) and CC is not set")


@functools.lru_cache(maxsize=8)
def _version(cmd):
    try:
        out = subprocess.run(list(cmd) + ["--version"], capture_output=True, text=True,
                             timeout=30)
    except (OSError, subprocess.SubprocessError) as exc:
        raise NoCompiler(f"C compiler {' '.join(cmd)!r} does not run: {exc}") from None
    if out.returncode != 0:
        raise NoCompiler(f"C compiler {' '.join(cmd)!r} does not run: {out.stderr.strip()}")
    return out.stdout.strip()


def _digest(path):
    return hashlib.sha256(path.read_bytes()).hexdigest()


def build(scene_key, make_source, include):
    """Return (path of the compiled library, seconds spent compiling: 0.0 on a cache hit).

    Parameters
    ----------
    scene_key : str
        Everything the generated source is a function of (see :func:`pysolver.build.codegen.key`).
    make_source : callable
        Returns the C source; called only on a cache miss.
    include : str
        The folder of pysolver.h.

    Raises
    ------
    NoCompiler
        No compiler, or it failed (the message says why).
    """
    import time
    cmd = tuple(compiler())
    key = hashlib.sha256("\0".join((scene_key, " ".join(cmd), " ".join(FLAGS), _version(cmd),
                                    _header(include))).encode()).hexdigest()[:32]
    folder = cache_dir()
    lib, stamp = folder / f"{key}.so", folder / f"{key}.sha256"
    try:
        if stamp.read_text().strip() == _digest(lib):
            return lib, 0.0
    except OSError:
        pass
    source = make_source()
    start = time.perf_counter()
    folder.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=folder, prefix=".build-") as tmp:
        src, out = pathlib.Path(tmp) / "kernel.c", pathlib.Path(tmp) / "kernel.so"
        src.write_text(source)
        try:
            done = subprocess.run(list(cmd) + list(FLAGS) + [f"-I{include}", str(src),
                                  "-o", str(out), "-lm"], capture_output=True, text=True,
                                  timeout=3600)
        except (OSError, subprocess.SubprocessError) as exc:
            raise NoCompiler(f"C compiler {' '.join(cmd)!r} failed: {exc}") from None
        if done.returncode != 0:
            raise NoCompiler(f"C compiler {' '.join(cmd)!r} failed: "
                             f"{done.stderr.strip()[-400:]}")
        digest = _digest(out)
        os.replace(out, lib)
        tmp_stamp = pathlib.Path(tmp) / "stamp"
        tmp_stamp.write_text(digest)
        os.replace(tmp_stamp, stamp)
    return lib, time.perf_counter() - start


@functools.lru_cache(maxsize=4)
def _header(include):
    return (pathlib.Path(include) / "pysolver.h").read_text()
