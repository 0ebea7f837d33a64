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
from . import looped
from .assemble import Assembly
from .cache import NoCompiler, build
from .emit import generate
from .scene import Scene
from .sym import Unsupported

__all__ = ["attach", "key", "source", "NoCompiler", "Unsupported", "LIMIT"]

#: Most expression nodes of a generated kernel. Straight-line C compiles at about 7 s per 50 000
#: nodes (gcc -O2), so this caps a cold compile near half a minute; a looped scene (below) over
#: it has that many nodes in its distinct templates, and runs the tapes.
LIMIT = 200_000

#: Scenes of more (estimated) nodes are generated looped (:mod:`.looped`: one function per
#: distinct shape of body or element, run over its instances), in time independent of their
#: number; smaller ones straight-line, with kinematics shared between elements and every
#: constant folded in.
STRAIGHT = 20_000

#: Expression nodes per tape instruction and state of a typical scene (the chain: 32), for
#: choosing between straight-line and looped C before generating any of it.
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


def is_looped(kernel):
    """Whether `kernel`'s C is generated looped (see :data:`STRAIGHT`)."""
    a = kernel.arrays
    return _NODES_PER_ITEM * (int(np.sum(a["tape_len"])) + int(a["ny"])) > STRAIGHT


def key(kernel):
    """Everything the generated source of `kernel` is a function of, as a hex digest: its
    compiled arrays (sweep parameters by slot, not value; no constants at all in looped C),
    the generator's own code and whether the C is looped."""
    h = hashlib.sha256(_generator_digest().encode())
    looped_c = is_looped(kernel)
    h.update(b"looped" if looped_c else b"straight")
    slots = sorted(kernel.params.values())
    h.update(repr(slots).encode())
    for name in sorted(kernel.arrays):
        if name in _READ_AT_RUN_TIME:
            continue
        val = kernel.arrays[name]
        if name == "consts" and looped_c:      # looped C reads every constant at run time
            val = np.zeros_like(val)
        elif name == "consts" and slots:
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
    if is_looped(kernel):
        return looped.generate(kernel, limit)
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
    spent = []

    def make():
        t0 = time.perf_counter()
        text = source(kernel, LIMIT)
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
