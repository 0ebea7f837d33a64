"""IDA driven from C (csrc/ida.c): the same SUNDIALS that scikit-sundae wraps, with the kernel's
residual, Jacobian and root functions called from C instead of through Python.

The SUNDIALS shared libraries are those of the scikit-sundae wheel (``scikit_sundae.libs``),
opened at run time. :func:`available` says whether they could be loaded; the driver falls back
to scikit-sundae otherwise. The interface mirrors the parts of ``sksundae.ida.IDA`` the driver
uses (``init_step``, ``step``), plus :meth:`CIDA.outputs` for a batch of output times.
"""
import glob
import os

import numpy as np

from ._bindings import ffi, lib

_LIBS = ("sundials_core", "sundials_nvecserial", "sundials_sunmatrixdense",
         "sundials_sunlinsoldense", "sundials_ida", "sundials_sunmatrixband",
         "sundials_sunlinsolband")
_PATHS = None
_LOADED = None
_MESSAGES = {0: "Successful function return.", 1: "Reached specified tstop.",
             2: "Found a root.", -1: "Could not reach endpoint after 'max_num_steps'.",
             -2: "The requested accuracy could not be achieved.",
             -3: "Error test failures occurred too many times.",
             -4: "Convergence test failures occurred too many times.",
             -8: "The residual function failed unrecoverably.",
             -12: "The residual function failed recoverably too many times."}


def _library_paths():
    """Paths of the five SUNDIALS libraries, or None when they cannot be found."""
    global _PATHS
    if _PATHS is None:
        _PATHS = False
        try:
            import sksundae
        except ImportError:
            return None
        here = os.path.dirname(os.path.dirname(os.path.abspath(sksundae.__file__)))
        paths = []
        for name in _LIBS:
            found = sorted(glob.glob(os.path.join(here, "scikit_sundae.libs", f"lib{name}*.so*")))
            if not found:
                return None
            paths.append(found[0])
        _PATHS = paths
    return _PATHS or None


def _loaded():
    """A psIDA whose libraries are open and function table filled (once per process; the
    libraries stay open), or None when SUNDIALS cannot be loaded."""
    global _LOADED
    if _LOADED is None:
        _LOADED = False
        paths = _library_paths()
        if paths:
            s = ffi.new("psIDA *")
            if lib.ps_ida_load(s, *[p.encode() for p in paths]) == 0:
                _LOADED = s
    return _LOADED or None


def available():
    """True when SUNDIALS can be loaded for the C driver."""
    return _loaded() is not None


class _Sol:
    """The fields of an IDA step result the driver reads."""
    __slots__ = ("t", "y", "yp", "status", "success", "message", "nfev", "njev", "roots")

    def __init__(self, t, y, yp, status, counts, roots):
        self.t, self.y, self.yp, self.status = t, y, yp, status
        self.success = status >= 0
        self.message = _MESSAGES.get(status, f"IDA flag {status}")
        self.nfev, self.njev = int(counts[1]), int(counts[2])
        self.roots = roots


class CIDA:
    """One IDA integration of a compiled kernel, driven from C.

    Parameters
    ----------
    kernel : pysolver.kernel.Kernel
    rtol, atol : float
    max_step, min_step, first_step : float
        0 for IDA's defaults.
    max_num_steps : int
        IDA's limit per call.
    band : tuple (mu, ml) or None
        Use a band solver with these bandwidths instead of the dense one.
    tune : tuple (eta_max, nlconv, auto_eta) or None
        See ``ps_ida_tune``: a fixed step-growth limit, the Newton convergence coefficient and
        the limit switched on when the error test fails most steps (0: IDA's defaults).
    """

    def __init__(self, kernel, rtol, atol, max_step=0.0, min_step=0.0, first_step=0.0,
                 max_num_steps=500, band=None, tune=None):
        self.k = kernel
        template = _loaded()
        if template is None:
            raise RuntimeError("SUNDIALS libraries not available for the C driver")
        # a copy of the loaded template: library handles and function table, nothing running
        self.s = ffi.new("psIDA *")
        ffi.memmove(self.s, template, ffi.sizeof("psIDA"))
        self.opts = (float(rtol), float(atol), float(max_step), float(min_step),
                     float(first_step), int(max_num_steps))
        self.rootdir = np.ones(max(kernel.nsensor, 1), dtype=np.int32)
        self.roots = np.zeros(max(kernel.nsensor, 1), dtype=np.int32)
        n = kernel.ny
        self.y, self.yp = np.zeros(n), np.zeros(n)
        self.tret = ffi.new("double *")
        self.counts = ffi.new("long[7]")
        self.started = False
        self.tune = tune
        if band is None:
            self.band = (-1, -1)
            self.map = np.zeros(1, dtype=np.int32)
            self.ntrip = 0
        else:
            self.band = band
            self.map = kernel.band_map(*band)
            self.ntrip = len(self.map)

    def init_step(self, t0, y0, yp0):
        """Start (or cold-restart) at (t0, y0, yp0)."""
        fb = ffi.from_buffer
        y0 = np.ascontiguousarray(y0, float)
        yp0 = np.ascontiguousarray(yp0, float)
        if not self.started:
            rtol, atol, hmax, hmin, h0, mx = self.opts
            rc = lib.ps_ida_init(self.s, self.k.m, self.k.d, t0, fb("double[]", y0),
                                 fb("double[]", yp0), rtol, atol, hmax, hmin, h0, mx,
                                 ffi.cast("int *", fb(self.rootdir)), self.band[0], self.band[1],
                                 ffi.cast("int *", fb(self.map)), self.ntrip)
            if rc != 0:
                raise RuntimeError(ffi.string(self.s.msg).decode())
            if self.tune:
                lib.ps_ida_tune(self.s, *self.tune)
            self.started = True
        else:
            lib.ps_ida_reinit(self.s, t0, fb("double[]", y0), fb("double[]", yp0))

    def step(self, t, method="normal", tstop=None):
        """One IDASolve call toward t; see ``sksundae.ida.IDA.step``."""
        fb = ffi.from_buffer
        flag = lib.ps_ida_solve(self.s, t, t if tstop is None else tstop,
                                1 if method == "onestep" else 0, self.tret,
                                fb("double[]", self.y), fb("double[]", self.yp),
                                ffi.cast("int *", fb(self.roots)))
        lib.ps_ida_stats(self.s, self.counts)
        return _Sol(self.tret[0], self.y.copy(), self.yp.copy(), flag, self.counts,
                    self.roots.copy() if flag == 2 else None)

    def outputs(self, times, tstop):
        """Advance through output times in C; returns (sol of the last call, Y, YP, REQ, n)
        with the n output rows reached before a root or a failure."""
        fb = ffi.from_buffer
        times = np.ascontiguousarray(times, float)
        nt, n, nout = len(times), self.k.ny, max(self.k.arrays["nout"], 1)
        Y, YP, REQ = np.zeros((nt, n)), np.zeros((nt, n)), np.zeros((nt, nout))
        reached = ffi.new("int *")
        flag = lib.ps_ida_outputs(self.s, fb("double[]", times), nt, tstop, fb("double[]", Y),
                                  fb("double[]", YP), fb("double[]", REQ), reached, self.tret,
                                  ffi.cast("int *", fb(self.roots)))
        lib.ps_ida_stats(self.s, self.counts)
        k = reached[0]
        # row k holds the state IDA stopped at (a root, or its last point) when k < nt
        j = k if k < nt else nt - 1
        sol = _Sol(self.tret[0], Y[j].copy(), YP[j].copy(), flag, self.counts,
                   self.roots.copy() if flag == 2 else None)
        return sol, Y[:k], YP[:k], REQ[:k, :self.k.arrays["nout"]], k

    def stats(self):
        """IDA's counters: steps, nres, njac, netf, ncfn, ngevals, and the step at which the
        automatic step-growth limit switched on (0: it did not)."""
        lib.ps_ida_stats(self.s, self.counts)
        return [int(self.counts[i]) for i in range(7)]

    def __del__(self):
        try:
            lib.ps_ida_free(self.s)
        except Exception:  # noqa: BLE001 - interpreter shutdown
            pass
