"""Generated C per deck: the scene's residual, iteration matrix, sensors and outputs as
straight-line C with exact symbolic derivatives, compiled once and cached on disk.

:func:`attach` gives a compiled :class:`~pysolver.build.kernel.Kernel` its generated library;
the kernel then calls it in place of the tape interpreter (csrc/residual.c). The tapes stay as
the fallback (no compiler, ``kernel="tapes"``, a scene with user subroutines called from the
kernel, or one larger than :data:`LIMIT`) and as the reference the diagnosis of a non-finite
value runs.
"""
import functools
import hashlib
import pathlib
import time

import numpy as np

from ...headers import get_include
from .assemble import Assembly
from .cache import NoCompiler, build
from .emit import generate
from .scene import Scene
from .sym import Unsupported

__all__ = ["attach", "key", "source", "NoCompiler", "Unsupported", "LIMIT"]

#: Most expression nodes of a generated kernel. Straight-line C compiles at about 7 s per 50 000
#: nodes (gcc -O2), so this caps a cold compile near half a minute; larger scenes run the tapes.
LIMIT = 200_000

#: Expression nodes per tape instruction and state of a typical scene (the chain: 32), for
#: refusing a scene clearly over :data:`LIMIT` before generating any of it.
_NODES_PER_ITEM = 30

#: Arrays the generated code reads at run time (``m->...``), so their values are not in the key:
#: one library serves every case of a sweep over masses, inertias, gravity and marker positions.
_READ_AT_RUN_TIME = {"body_mass", "body_inertia", "gravity", "marker_pos", "user_fn"}


@functools.lru_cache(maxsize=1)
def _generator_digest():
    here = pathlib.Path(__file__).parent
    h = hashlib.sha256()
    for path in sorted(here.glob("*.py")):
        h.update(path.read_bytes())
    return h.hexdigest()


def key(kernel):
    """Everything the generated source of `kernel` is a function of, as a hex digest: its
    compiled arrays (sweep parameters by slot, not value) and the generator's own code."""
    h = hashlib.sha256(_generator_digest().encode())
    slots = sorted(kernel.params.values())
    h.update(repr(slots).encode())
    for name in sorted(kernel.arrays):
        if name in _READ_AT_RUN_TIME:
            continue
        val = kernel.arrays[name]
        if name == "consts" and slots:
            val = val.copy()
            val[slots] = 0.0
        h.update(name.encode())
        if isinstance(val, np.ndarray):
            h.update(f"{val.dtype.str}{val.shape}".encode())
            h.update(np.ascontiguousarray(val).tobytes())
        else:
            h.update(repr(val).encode())
    return h.hexdigest()


def source(kernel, limit=None):
    """The generated C source of a compiled kernel (raises Unsupported)."""
    return generate(Assembly(Scene(kernel.arrays, kernel.params.values(), limit)))


def attach(kernel, lib, ffi):
    """Find in the cache, or generate and compile, the C of `kernel`, and load it.

    Returns
    -------
    dict
        ``{"kernel": "generated", "generate": s, "compile": s, "cached": bool, "path": str,
        "ntrip": int, "gen": psGen*}``, or ``{"kernel": "tapes", "why": message}`` when the
        tapes run (no compiler, or a scene the generator does not translate).
    """
    a = kernel.arrays
    if a["nuser"]:
        return {"kernel": "tapes", "why": "not generated: a user subroutine called from the kernel"}
    size = _NODES_PER_ITEM * (int(np.sum(a["tape_len"])) + int(a["ny"]))
    if size > LIMIT:
        return {"kernel": "tapes", "why": f"not generated: the deck is too large (about {size} "
                                          f"expression nodes, more than {LIMIT})"}
    spent = []

    def make():
        t0 = time.perf_counter()
        text = source(kernel, 2 * LIMIT)
        spent.append(time.perf_counter() - t0)
        return text

    try:
        path, seconds = build(key(kernel), make, get_include())
    except Unsupported as exc:
        return {"kernel": "tapes", "why": f"not generated: {exc}"}
    except NoCompiler as exc:
        return {"kernel": "tapes", "why": str(exc)}
    msg = ffi.new("char[]", 512)
    gen = lib.ps_gen_open(str(path).encode(), kernel.m, msg, 512)
    if gen == ffi.NULL:
        return {"kernel": "tapes", "why": ffi.string(msg).decode(errors="replace")}
    return {"kernel": "generated", "generate": sum(spent), "compile": seconds,
            "cached": seconds == 0.0, "path": str(path), "ntrip": gen.ntrip, "gen": gen}
