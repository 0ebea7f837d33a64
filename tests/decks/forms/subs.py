"""User subroutines of every_attribute.xml (tests/test_formats.py): a VARSUB and a PFOSUB."""


def VARSUB(id, time, par, npar, dflag, iflag):
    return par[0] * time


def floor(id, time, par, npar, dflag, iflag):
    [z, errflg] = py_sysfnc("DY", [int(par[0])])  # noqa: F821 (pysolver provides it)
    return z - par[1]
