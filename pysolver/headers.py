"""Where pysolver's C headers are, for building user subroutine libraries."""
import os


def get_include():
    """Return the folder of pysolver's C headers.

    ``pysolver_usersub.h`` there declares ``c_sysfnc``, ``c_sysary``, ``c_syspar``,
    ``c_adams_needs_partials`` and ``c_errmes``; a user subroutine library needs only
    ``cc -shared -fPIC -I<this folder> sub.c -o sub.so`` (it is not linked against pysolver:
    pysolver provides the functions when it loads the library).
    """
    here = os.path.dirname(os.path.abspath(__file__))
    installed = os.path.join(here, "include")
    if os.path.isdir(installed):
        return installed
    return os.path.join(os.path.dirname(here), "csrc", "include")   # a source checkout
