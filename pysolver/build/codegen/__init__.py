"""Generated C per deck: the scene's residual, iteration matrix, sensors and outputs as
straight-line C with exact symbolic derivatives, compiled once and cached on disk.

:func:`attach` gives a compiled :class:`~pysolver.build.kernel.Kernel` its generated library;
the kernel then calls it in place of the tape interpreter (csrc/residual.c). The tapes stay as
the fallback (no compiler, ``kernel="tapes"``, or a scene with user subroutines called from the
kernel) and as the reference the diagnosis of a non-finite value runs.
"""
import time

from ...headers import get_include
from .assemble import Assembly
from .cache import NoCompiler, build
from .emit import generate
from .scene import Scene
from .sym import Unsupported

__all__ = ["attach", "source", "NoCompiler", "Unsupported"]


def source(kernel):
    """The generated C source of a compiled kernel (raises Unsupported)."""
    return generate(Assembly(Scene(kernel)))


def attach(kernel, lib, ffi):
    """Generate, compile (or find in the cache) and load the C of `kernel`.

    Returns
    -------
    dict
        ``{"kernel": "generated", "generate": s, "compile": s, "cached": bool, "path": str,
        "ntrip": int}``, or ``{"kernel": "tapes", "why": message}`` when the tapes run (no
        compiler, or a scene the generator does not translate).
    """
    t0 = time.perf_counter()
    try:
        text = source(kernel)
    except Unsupported as exc:
        return {"kernel": "tapes", "why": f"not generated: {exc}"}
    t1 = time.perf_counter()
    try:
        path, seconds = build(text, get_include())
    except NoCompiler as exc:
        return {"kernel": "tapes", "why": str(exc)}
    msg = ffi.new("char[]", 512)
    gen = lib.ps_gen_open(str(path).encode(), kernel.m, msg, 512)
    if gen == ffi.NULL:
        return {"kernel": "tapes", "why": ffi.string(msg).decode(errors="replace")}
    return {"kernel": "generated", "generate": t1 - t0, "compile": seconds,
            "cached": seconds == 0.0, "path": str(path), "ntrip": gen.ntrip, "gen": gen}
