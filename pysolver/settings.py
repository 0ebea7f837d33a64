"""Every environment variable pysolver reads, read here and nowhere else, at the time of use
(so a change between runs, or a test's monkeypatch, takes effect).

==============================  ===========================================================
``PYSOLVER_BACKEND``            default of the ``backend`` run option (``c``, ``sksundae``)
``PYSOLVER_KERNEL``             default of the ``kernel`` run option (``generated``, ``tapes``)
``PYSOLVER_CACHE_DIR``          where generated kernels are cached (default: the platform's
                                cache folder, ``pysolver/kernels`` under it)
``PYSOLVER_COMPILE_TIMEOUT``    seconds a compile of generated C may take (default 120)
``CC``                          the C compiler for generated kernels (default cc, gcc, clang)
``PYSOLVER_OUTPUT_BUDGET``      bytes of output rows a run may hold (default 2 GiB)
``PYSOLVER_USERSUB_DIR``        folders searched for user subroutine scripts and libraries
``PYSOLVER_NO_INPLACE_BUILD``   set: a source checkout never builds its C kernel in place
``PYSOLVER_PLANAR``             ``off`` (``0``, ``no``, ``false``): integrate every scene in
                                3-D, planar ones too (read
                                when a model is compiled; default: planar scenes in planar
                                coordinates, docs/numerics.md "Planar scenes")
==============================  ===========================================================
"""
import os
import pathlib
import sys

# os.environ keeps the environment in a dict of encoded keys and values (its _data, what its
# get reads after encoding the key); a short run reads three variables, and reading the dict
# with keys encoded once is 20x faster (0.03 us against 0.6 us), with the same result.
_KEYS = {}


def _get(name, default=None):
    """os.environ.get(name, default), read at the time of the call."""
    env = os.environ
    data = getattr(env, "_data", None)
    if data is None or not hasattr(env, "encodekey"):   # not CPython's _Environ
        return env.get(name, default)
    key = _KEYS.get(name)
    if key is None:
        key = _KEYS[name] = env.encodekey(name)
    raw = data.get(key)
    return default if raw is None else env.decodevalue(raw)


#: Default of PYSOLVER_COMPILE_TIMEOUT, seconds.
COMPILE_TIMEOUT = 120.0

#: Default of PYSOLVER_OUTPUT_BUDGET, bytes.
OUTPUT_BUDGET = 2 ** 31


def backend():
    """``PYSOLVER_BACKEND``, or None when unset."""
    return _get("PYSOLVER_BACKEND") or None


def kernel():
    """``PYSOLVER_KERNEL``, or None when unset."""
    return _get("PYSOLVER_KERNEL") or None


def cache_dir():
    """The folder of compiled kernels: ``PYSOLVER_CACHE_DIR``, else the platform's cache folder
    (``$XDG_CACHE_HOME`` or ``~/.cache`` on Linux, ``~/Library/Caches`` on macOS,
    ``%LOCALAPPDATA%`` on Windows) under ``pysolver/kernels``."""
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


def compile_timeout():
    """Seconds a compile may take: ``PYSOLVER_COMPILE_TIMEOUT`` if it is a positive number,
    else :data:`COMPILE_TIMEOUT`."""
    try:
        value = float(os.environ.get("PYSOLVER_COMPILE_TIMEOUT", ""))
    except ValueError:
        value = 0.0
    return value if value > 0.0 else COMPILE_TIMEOUT


def compiler_command():
    """``CC`` as given (a shell-like command), or None when unset or empty."""
    return os.environ.get("CC") or None


def output_budget():
    """Bytes of output rows a run may hold: ``PYSOLVER_OUTPUT_BUDGET``, else
    :data:`OUTPUT_BUDGET`."""
    return float(_get("PYSOLVER_OUTPUT_BUDGET", OUTPUT_BUDGET))


def usersub_dirs():
    """The folders of ``PYSOLVER_USERSUB_DIR`` (os.pathsep-separated), in order."""
    return [d for d in os.environ.get("PYSOLVER_USERSUB_DIR", "").split(os.pathsep) if d]


def planar():
    """Whether planar scenes are integrated in planar coordinates (``PYSOLVER_PLANAR`` is not
    ``off``, ``0``, ``no`` or ``false``)."""
    return (_get("PYSOLVER_PLANAR") or "").strip().lower() not in ("off", "0", "no", "false")


def held():
    """Whether states a scene holds at their start values are left out of IDA's vectors
    (``PYSOLVER_HELD`` is not ``off``, ``0``, ``no`` or ``false``; pysolver/build/held.py)."""
    return (_get("PYSOLVER_HELD") or "").strip().lower() not in ("off", "0", "no", "false")


def affecting_results():
    """The settings a run's results depend on (the kernel and backend chosen, planar and held
    states, the compiler and its time limit that decide whether generated C runs, where user
    subroutine files are found), as (name, value) pairs: part of a sweep's resume key, and
    what a sweep's worker kept for later sweeps must have been started with."""
    return (("kernel", kernel() or ""), ("backend", backend() or ""), ("planar", planar()),
            ("held", held()), ("CC", compiler_command() or ""),
            ("compile_timeout", compile_timeout()),
            ("usersub_dir", os.environ.get("PYSOLVER_USERSUB_DIR", "")))


def no_inplace_build():
    """Whether ``PYSOLVER_NO_INPLACE_BUILD`` forbids building the C kernel in a checkout."""
    return bool(os.environ.get("PYSOLVER_NO_INPLACE_BUILD"))
