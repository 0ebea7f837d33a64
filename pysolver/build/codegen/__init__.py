"""Generated C per deck: the scene's residual, iteration matrix, sensors and outputs as
straight-line C with exact symbolic derivatives, compiled once and cached on disk.

:func:`attach` gives a compiled :class:`~pysolver.build.kernel.Kernel` its generated library;
the kernel then calls it in place of the tape interpreter (csrc/residual.c). The tapes stay as
the fallback (no compiler, ``kernel="tapes"``, a scene larger than :data:`LIMIT` or whose C
would cost more than :data:`COMPILE_LIMIT` to compile, an unusable cache or compiler:
:mod:`.cache`) and as the reference the diagnosis of a non-finite value runs. User
subroutines the kernel calls (C libraries, untraceable Python) are called from the generated
code through the kernel's ``ps_user_point`` (the ``psg_user_point`` hook csrc/gen.c sets),
their differenced partials chained with the exact derivatives of what they read.
"""
import functools
import hashlib
import pathlib
import re
import time

import numpy as np

from ...headers import get_include
from . import looped
from .assemble import Assembly
from .cache import CacheUnusable, CompileError, CompileTimeout, Fallback, NoCompiler, build
from .emit import generate, scene_record
from .scene import Scene
from .sym import Unsupported

__all__ = ["attach", "key", "source", "compile_cost", "Fallback", "NoCompiler", "CompileError",
           "CompileTimeout", "CacheUnusable", "Unsupported", "LIMIT", "COMPILE_LIMIT"]

#: Most expression nodes of a generated kernel (what generating it costs; what compiling it
#: costs is capped by :data:`COMPILE_LIMIT`); a looped scene (below) over it has that many nodes
#: in its distinct templates, and runs the tapes.
LIMIT = 200_000

#: Most estimated seconds of gcc -O2 (:func:`compile_cost`) for a generated kernel's C: past
#: it the tapes run, so a cold compile stays near half a minute. :data:`LIMIT` alone does not
#: bound it: a chunk of C recomputes the shared nodes it needs (a 300-term SIN sum on a rigid
#: body: 28,000 graph nodes, 206,000 temporaries in 21 functions), and one expression that
#: alone needs more than ``emit.CHUNK`` temporaries is one function, in which many values live
#: at once (the 3,000-term sum on a particle: 27,000 nodes, one function of 21,000 statements
#: with up to 6,000 live values), which gcc's register allocation takes quadratic time over.
COMPILE_LIMIT = 30.0

#: gcc -O2's seconds per statement, per statement a value lives over (the live-range area of
#: each function) and per byte of C, fitted on a 2-core Linux machine (gcc 12) shared with other
#: jobs, to the slowest of its measured times (and estimated) in seconds: a Force_Penalty
#: summing 300 / 1,000 / 2,000 / 3,000 SIN terms of a particle's DX, 0.98 / 7.6 / 31 / 45
#: (0.9 / 9.1 / 33 / 71); the same on a rigid body, 100 / 300 terms, 4.4 / 51 (4.0 / 85);
#: straight chains of 100 / 300 bodies 7.2 / 20 (8.1 / 24); the particle bed straight 22 (23);
#: looped rigid chains of 50 / 1,000 bodies 2.7 / 3.8 (3.8 / 5.6); all_functions.xml 9.6 (8.3).
#: The same compiles ran up to twice as fast on a quieter machine.
COST_STATEMENT, COST_LIVE, COST_BYTE = 1e-4, 6e-7, 1.6e-7

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
_READ_AT_RUN_TIME = {"body_mass", "body_inertia", "body_plane", "gravity", "marker_pos",
                     "user_fn", "user_name", "user_python", "compliance"}


#: A temporary of generated C.
_TEMP = re.compile(r"\bt(\d+)\b")


@functools.lru_cache(maxsize=1)
def _generator_digest():
    here = pathlib.Path(__file__).parent
    h = hashlib.sha256()
    # the generator's modules and the catalogue they read (opcodes, C function names)
    for path in sorted(here.glob("*.py")) + [here.parent.parent / "catalogue.py"]:
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


def compile_cost(text):
    """Estimated seconds gcc -O2 takes over generated C (see :data:`COST_STATEMENT`): its
    statements, the live-range area of its temporaries (over each function, the statements
    from a temporary's definition to its last use) and its bytes."""
    statements = area = 0
    born = None
    for line in text.splitlines():
        if born is None:
            if line.startswith("static void ") and line.endswith("{"):
                born, last, k = {}, {}, 0
            continue
        if line == "}":
            area += sum(last.get(t, at) - at + 1 for t, at in born.items())
            statements += k
            born = None
            continue
        k += 1
        if line.startswith("  const double t"):
            lhs, _, line = line.partition(" = ")
            born[lhs[16:]] = k
        for t in _TEMP.findall(line):
            last[t] = k
    return COST_STATEMENT * statements + COST_LIVE * area + COST_BYTE * len(text)


def _check_cost(text):
    seconds = compile_cost(text)
    if seconds > COMPILE_LIMIT:
        raise Unsupported(f"the generated C is too large to compile in bounded time (about "
                          f"{seconds:.0f} s of gcc > codegen.COMPILE_LIMIT {COMPILE_LIMIT:g} s; "
                          f"{len(text) / 1e6:.1f} MB of C)")


def attach(kernel, lib, ffi):
    """Find in the cache, or generate and compile, the C of `kernel`, and load it.

    Returns
    -------
    dict
        ``{"kernel": "generated", "generate": s, "compile": s, "cached": bool, "path": str,
        "ntrip": int, "gen": psGen*}`` (and ``"rebuilt"``: why a cached entry was not used),
        or ``{"kernel": "tapes", "why": message}`` when the tapes run (no compiler, a scene
        the generator does not translate or too large to compile, an unusable cache).
    """
    spent = []

    def make(record):
        t0 = time.perf_counter()
        text = source(kernel, LIMIT)
        _check_cost(text)
        spent.append(time.perf_counter() - t0)
        return text + scene_record(record)

    try:
        built = build(key(kernel), make, get_include())
    except Unsupported as exc:
        return {"kernel": "tapes", "why": f"not generated: {exc}"}
    except Fallback as exc:
        return {"kernel": "tapes", "why": str(exc)}
    except OSError as exc:                 # anything else the file system refuses
        return {"kernel": "tapes", "why": f"the kernel cache failed: {exc}"}
    msg = ffi.new("char[]", 512)
    gen = lib.ps_gen_open(str(built.path).encode(), built.record.encode(), kernel.m, msg, 512)
    if gen == ffi.NULL:
        return {"kernel": "tapes", "why": ffi.string(msg).decode(errors="replace")}
    info = {"kernel": "generated", "generate": sum(spent), "compile": built.seconds,
            "cached": built.seconds == 0.0, "path": str(built.path), "ntrip": gen.ntrip,
            "gen": gen}
    if built.rebuilt:
        info["rebuilt"] = built.rebuilt
    return info
