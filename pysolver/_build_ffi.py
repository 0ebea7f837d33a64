"""Generate (or compile in place) the cffi extension ``pysolver._kernel``.

CMake calls ``python _build_ffi.py OUT.c`` to emit the C source of the extension, which it then
compiles together with ``csrc/``. ``python pysolver/_build_ffi.py --inplace`` builds the module
next to this file for development.

The cdef is derived from ``csrc/include/pysolver.h`` itself (comments, include guards and
``extern "C"`` stripped), so there is one source of truth for the interface; the generated C
file includes the real header, so the compiler still checks the two agree.
"""
import pathlib
import re
import sys

import cffi

ROOT = pathlib.Path(__file__).resolve().parent.parent
HEADER = ROOT / "csrc" / "include" / "pysolver.h"
USERSUB_HEADER = ROOT / "csrc" / "include" / "pysolver_usersub.h"
SOURCES = ["hd.c", "kinematics.c", "tape.c", "residual.c", "assembly.c", "elements/penalty.c",
           "elements/sforce.c", "elements/vforce.c", "elements/motion.c", "elements/joint.c",
           "elements/gcon.c", "elements/coupler.c", "elements/turn.c",
           "elements/table.c", "usersub.c", "control.c", "events.c", "ida.c", "sparselu.c",
           "csv.c", "gen.c"]


def cdef_from_header(text, start_at="#define PS_BODY_POINT"):
    """Return the declarations of a public header in a form cffi's cdef accepts."""
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    start = text.index(start_at)
    end = text.index("#ifdef __cplusplus", start)
    return "\n".join(line for line in text[start:end].splitlines() if line.strip())


def make_builder():
    """Return an FFI builder for the kernel."""
    ffibuilder = cffi.FFI()
    ffibuilder.cdef(cdef_from_header(USERSUB_HEADER.read_text(), "void c_sysfnc"))
    ffibuilder.cdef(cdef_from_header(HEADER.read_text()))
    ffibuilder.set_source(
        "pysolver._kernel",
        '#include "pysolver.h"',
        sources=[str(ROOT / "csrc" / s) for s in SOURCES],
        include_dirs=[str(ROOT / "csrc" / "include"), str(ROOT / "csrc"),
                      str(ROOT / "csrc" / "third_party")],
        extra_compile_args=["-std=c99", "-O3", "-fvisibility=hidden", "-flto", "-D_DEFAULT_SOURCE"],
        extra_link_args=["-O3", "-flto"],
        libraries=["m", "dl"],
    )
    return ffibuilder


if __name__ == "__main__":
    builder = make_builder()
    if sys.argv[1:] == ["--inplace"]:
        builder.compile(tmpdir=str(ROOT / "build" / "inplace"),
                        target=str(ROOT / "pysolver" / "_kernel.*"))
    else:
        builder.emit_c_code(sys.argv[1])
