"""IDA driven from C (csrc/ida.c): the same SUNDIALS that scikit-sundae wraps, with the kernel's
residual, Jacobian and root functions called from C instead of through Python.

The SUNDIALS shared libraries are those of the scikit-sundae wheel (``scikit_sundae.libs``),
opened at run time, once per process. :func:`available` says whether they could be loaded; the
driver falls back to scikit-sundae otherwise. :class:`CIDA` implements the integrator interface
of :mod:`.integrator`.
"""
import glob
import importlib.util
import os

import numpy as np

from ..build.bindings import ffi, lib
from ..build.ordering import column_order
from .step import ROOT_RETURN, Step

#: The SUNDIALS libraries, in the order ps_ida_load takes their paths; the last two (the
#: sparse matrix and SuperLU_MT) are optional.
_LIBS = ("sundials_core", "sundials_nvecserial", "sundials_sunmatrixdense",
         "sundials_sunlinsoldense", "sundials_ida", "sundials_sunmatrixband",
         "sundials_sunlinsolband", "sundials_sunmatrixsparse", "sundials_sunlinsolsuperlumt")
_OPTIONAL = 2
_LOADED = None


def _library_paths():
    """Paths of the SUNDIALS libraries in the scikit-sundae wheel, or None."""
    # found, not imported: importing scikit-sundae loads scipy.optimize (0.3-0.7 s)
    spec = importlib.util.find_spec("sksundae")
    if spec is None or not spec.origin:
        return None
    here = os.path.dirname(os.path.dirname(os.path.abspath(spec.origin)))
    paths = []
    for k, name in enumerate(_LIBS):
        found = sorted(glob.glob(os.path.join(here, "scikit_sundae.libs", f"lib{name}*.so*")))
        if not found and k < len(_LIBS) - _OPTIONAL:
            return None
        paths.append(found[0] if found else None)
    return paths


def _loaded():
    """The loaded function table (once per process; the libraries stay open), or None."""
    global _LOADED
    if _LOADED is None:
        _LOADED = False
        paths = _library_paths()
        if paths:
            cpaths = [ffi.new("char[]", p.encode()) if p else ffi.NULL for p in paths]
            msg = ffi.new("char[256]")
            table = lib.ps_ida_load(ffi.new("const char *[]", cpaths), msg, 256)
            if table != ffi.NULL:
                _LOADED = table
    return _LOADED or None


def available():
    """True when SUNDIALS can be loaded for the C driver."""
    return _loaded() is not None


def sparse_available(solver="lu"):
    """True when the C driver can also use SUNDIALS' sparse matrix with `solver`: "lu",
    pysolver's sparse LU (csrc/sparselu.c), or "superlu_mt", SUNDIALS' SuperLU_MT."""
    has = lib.ps_ida_has_sparse if solver == "lu" else lib.ps_ida_has_superlumt
    return available() and bool(has(_loaded()))


class CIDA:
    """One IDA integration of a compiled kernel, driven from C.

    Parameters
    ----------
    kernel : pysolver.build.Kernel
    rtol, atol : float
    max_step, min_step, first_step : float
        0 for IDA's defaults.
    max_num_steps : int
        IDA's limit per call.
    band : tuple (mu, ml) or None
        Use a band solver with these bandwidths instead of the dense one.
    sparse : {False, "lu", "superlu_mt"}
        Use SUNDIALS' compressed-sparse-column matrix with the kernel's Jacobian pattern
        (``kernel.sparsity()``) fixed for the integration, factored by pysolver's sparse LU
        in the column order of :func:`pysolver.build.ordering.column_order` or by SuperLU_MT.
    tune : tuple (eta_max, nlconv, auto_eta) or None
        See ``ps_ida_tune``: a fixed step-growth limit, the Newton convergence coefficient and
        the limit switched on when the error test fails most steps (0: IDA's defaults).
    sundials_dense : bool
        A dense matrix is factored by SUNDIALS' dense solver (pysolver's own dense LU
        otherwise).
    """

    def __init__(self, kernel, rtol, atol, max_step=0.0, min_step=0.0, first_step=0.0,
                 max_num_steps=500, band=None, tune=None, sparse=False, sundials_dense=False):
        self.k = kernel
        table = _loaded()
        if table is None:
            raise RuntimeError("SUNDIALS libraries not available for the C driver")
        self.s = ffi.gc(lib.ps_ida_new(table), lib.ps_ida_delete)
        if self.s == ffi.NULL:
            raise MemoryError("could not allocate an IDA object")
        self.opts = (float(rtol), float(atol), float(max_step), float(min_step),
                     float(first_step), int(max_num_steps))
        self.rootdir = np.ones(max(kernel.nsensor, 1), dtype=np.int32)
        self.roots = np.zeros(max(kernel.nsensor, 1), dtype=np.int32)
        n = kernel.ny
        self.y, self.yp = np.zeros(n), np.zeros(n)
        self.tret = ffi.new("double *")
        self.counts = ffi.new("long[7]")
        self.started = False
        self.retired = None              # counters of an integration on the held states
        self.bounds = None               # the step bounds set_bounds last set
        self.tune = tune
        self.colptr = self.rowind = self.colorder = np.zeros(1, dtype=np.int32)
        self.nnz = 0
        if sparse:
            pattern = kernel.sparsity()
            if sparse == "superlu_mt":
                self.band = (lib.PS_IDA_SUPERLU_MT, -1)
            else:
                self.band = (lib.PS_IDA_SPARSE, -1)
                self.colorder = column_order(kernel)
            self.map = kernel.csc_map()
            self.ntrip = len(self.map)
            self.colptr = np.ascontiguousarray(pattern.indptr, dtype=np.int32)
            self.rowind = np.ascontiguousarray(pattern.indices, dtype=np.int32)
            self.nnz = int(pattern.nnz)
        elif band is None:
            self.band = (lib.PS_IDA_SUNDIALS_DENSE if sundials_dense else -1, -1)
            self.map = np.zeros(1, dtype=np.int32)
            self.ntrip = 0
            # the states the scene holds at their start values (build/held.py): left out of
            # IDA when a start is at rest in them (ps_ida_hold)
            held = np.asarray(kernel.layout.held, dtype=np.int32)
            if len(held) and lib.ps_ida_hold(self.s, ffi.cast("int *", ffi.from_buffer(held)),
                                             len(held)) != 0:
                raise MemoryError("could not allocate an IDA object")
        else:
            self.band = band
            self.map = kernel.band_map(*band)
            self.ntrip = len(self.map)

    def _error(self):
        return RuntimeError(ffi.string(lib.ps_ida_message(self.s)).decode())

    def init_step(self, t0, y0, yp0):
        """Start (or cold-restart) at (t0, y0, yp0)."""
        fb = ffi.from_buffer
        y0 = np.ascontiguousarray(y0, float)
        yp0 = np.ascontiguousarray(yp0, float)
        if not self.started:
            self.retired = None
            rtol, atol, hmax, hmin, h0, mx = self.opts
            rc = lib.ps_ida_init(self.s, self.k.m, self.k.d, t0, fb("double[]", y0),
                                 fb("double[]", yp0), rtol, atol, hmax, hmin, h0, mx,
                                 ffi.cast("int *", fb(self.rootdir)), self.band[0], self.band[1],
                                 ffi.cast("int *", fb(self.map)), self.ntrip,
                                 ffi.cast("int *", fb(self.colptr)),
                                 ffi.cast("int *", fb(self.rowind)), self.nnz,
                                 ffi.cast("int *", fb(self.colorder)))
            if rc != 0 or (self.tune and lib.ps_ida_tune(self.s, *self.tune) != 0):
                raise self._error()
            self.started = True
        elif lib.ps_ida_reinit(self.s, t0, fb("double[]", y0),
                               fb("double[]", yp0)) == lib.PS_IDA_HELD:
            # the restart moves a held state (an actor set its velocity or changed the scene):
            # from here on IDA integrates every state, keeping the run's counters and bounds
            retired, bounds = self.counters(), self.bounds
            self.started = False
            lib.ps_ida_hold(self.s, ffi.NULL, 0)
            self.init_step(t0, y0, yp0)
            self.retired = retired
            if bounds is not None:
                self.set_bounds(*bounds)

    def step(self, tout, tstop, onestep=False):
        """One IDASolve call toward tout, never past tstop."""
        fb = ffi.from_buffer
        flag = lib.ps_ida_solve(self.s, tout, tstop, 1 if onestep else 0, self.tret,
                                fb("double[]", self.y), fb("double[]", self.yp),
                                ffi.cast("int *", fb(self.roots)))
        return Step(self.tret[0], self.y.copy(), self.yp.copy(), flag,
                    self.roots.copy() if flag == ROOT_RETURN else None)

    def set_bounds(self, hmax, hmin, h0):
        """New step bounds (0: IDA's default) from the next (re)start on, as a new object would
        have them (ps_ida_bounds)."""
        if lib.ps_ida_bounds(self.s, hmax, hmin, h0) != 0:
            raise self._error()
        self.bounds = (hmax, hmin, h0)

    def interpolate(self, t, tstop):
        """The state at t, which the last step passed: IDA's interpolant (no step, stop time or
        root search: ps_ida_interpolate)."""
        fb = ffi.from_buffer
        flag = lib.ps_ida_interpolate(self.s, t, fb("double[]", self.y), fb("double[]", self.yp))
        return Step(float(t), self.y.copy(), self.yp.copy(), flag, None)

    def outputs(self, times, tstop):
        """Advance through output times in C; returns (Step of the last call, Y, YP, REQ, n)
        with the n output rows reached before a root or a failure."""
        fb = ffi.from_buffer
        times = np.ascontiguousarray(times, float)
        nt, n, nout = len(times), self.k.ny, max(self.k.arrays["nout"], 1)
        Y, YP, REQ = np.zeros((nt, n)), np.zeros((nt, n)), np.zeros((nt, nout))
        reached = ffi.new("int *")
        flag = lib.ps_ida_outputs(self.s, fb("double[]", times), nt, tstop, 0,
                                  fb("double[]", Y), fb("double[]", YP), fb("double[]", REQ),
                                  reached, self.tret, ffi.cast("int *", fb(self.roots)))
        k = reached[0]
        # row k holds the state IDA stopped at (a root, or its last point) when k < nt
        j = k if k < nt else nt - 1
        step = Step(self.tret[0], Y[j].copy(), YP[j].copy(), flag,
                    self.roots.copy() if flag == ROOT_RETURN else None)
        return step, Y[:k], YP[:k], REQ[:k, :self.k.arrays["nout"]], k

    def held(self):
        """The number of states the current integration holds (0: IDA has every one)."""
        return int(lib.ps_ida_held(self.s))

    def counters(self):
        """IDA's counters over this object's life, restarts included."""
        lib.ps_ida_stats(self.s, self.counts)
        c = ffi.unpack(self.counts, 7)
        out = {"steps": c[0], "nfev": c[1], "njev": c[2], "netf": c[3], "ncfn": c[4],
               "growth_limited_at": c[6] or None}
        old = self.retired                  # those before IDA started again on every state
        if old is not None:
            limited = old["growth_limited_at"] or (c[6] and c[6] + old["steps"]) or None
            out = {key: out[key] + old[key] for key in ("steps", "nfev", "njev", "netf", "ncfn")}
            out["growth_limited_at"] = limited
        return out
