"""One interface for IDA, whichever way it is driven.

:class:`~.cida.CIDA` drives SUNDIALS IDA from C (the kernel's residual, Jacobian and roots
called without Python); :class:`~.pyida.PyIDA` adapts scikit-sundae's ``IDA`` (Python
callbacks), for scenes the C driver does not take and for the static solvers' own DAEs. Both
return :class:`Step` records and count the same things, so the transient driver has one path.

The interface (duck-typed):

``init_step(t0, y0, yp0)``
    Start, or cold-restart, at a consistent point.
``step(tout, tstop, onestep=False) -> Step``
    One IDASolve call toward ``tout`` (one internal step if ``onestep``), never past ``tstop``.
``outputs(times, tstop) -> (Step, Y, YP, REQ, n)``
    Run through output times, returning the first ``n`` rows of states, derivatives and
    request channels; stops early at a root or a failure (the Step says which).
``counters() -> dict``
    IDA's counters over the object's life: steps, nfev, njev, netf, ncfn (None where IDA's
    wrapper does not report them) and growth_limited_at.
"""
import dataclasses

from .. import settings
from ..options import AUTO_STEP_GROWTH, NONLIN_CONV_COEF, SPARSE_THRESHOLD
from . import cida
from .pyida import PyIDA


@dataclasses.dataclass(frozen=True)
class Plan:
    """How a scene is integrated: backend and linear solver, chosen once per run."""
    use_c: bool
    sparse: object            # False; True (scikit-sundae); "lu" or "superlu_mt" (C driver)
    band: tuple = None        # (mu, ml) for IDA's band solver
    sundials_dense: bool = False   # dense: SUNDIALS' solver, not pysolver's own (C driver)

    @property
    def linsolver(self):
        if self.band:
            return "band"
        if self.sundials_dense:
            return "sundials_dense"
        return "superlu_mt" if self.sparse == "superlu_mt" else "sparse" if self.sparse \
            else "dense"


def cached_plan(compiled, options):
    """:func:`plan` of a compiled model's kernel, kept on it for the next run with the same
    options object and PYSOLVER_BACKEND (runs of one model reuse their options; solve.run)."""
    key = (id(options), settings.backend())
    cache = compiled.plans
    if key not in cache:
        cache.clear()                       # one entry: the options object is kept alive
        cache[key] = (options, plan(compiled.kernel, options))
    return cache[key][1]


def plan(kernel, options):
    """Choose backend and linear solver for `kernel` under `options` (see Options)."""
    backend = options.resolved_backend()
    want_c = backend in ("auto", "c") and options.jacobian == "exact"
    ls = options.linsolver
    if ls == "auto":
        ls = "sparse" if kernel.ny >= SPARSE_THRESHOLD else "dense"
        # a SUNDIALS build without the sparse LU's hooks: a narrow band still runs from C
        if ls == "sparse" and want_c and cida.available() and not cida.sparse_available():
            mu, ml = kernel.bandwidths()
            ls = "band" if 4 * (mu + ml + 1) <= kernel.ny else ls
    band = kernel.bandwidths() if ls == "band" else None
    sparse = ls in ("sparse", "superlu_mt")
    solver = "superlu_mt" if ls == "superlu_mt" else "lu"
    use_c = want_c and cida.available() and (not sparse or cida.sparse_available(solver))
    if backend == "c" and not use_c:
        raise ValueError("backend='c' needs the exact Jacobian and SUNDIALS libraries from "
                         "the scikit-sundae wheel")
    # scikit-sundae runs IDA's own step control: only its default values can be asked for
    for key, ida_default in (("max_step_growth", 2.0), ("nonlin_conv_coef", 0.33)):
        if getattr(options, key) not in (None, ida_default) and not use_c:
            raise ValueError(f"{key} other than IDA's {ida_default:g} needs IDA driven from "
                             "C (exact Jacobian, the scikit-sundae wheel's SUNDIALS "
                             "libraries)")
    if use_c:
        return Plan(True, solver if sparse else False, band, ls == "sundials_dense")
    # through scikit-sundae: its dense solver, or SciPy's sparse LU for the rest
    return Plan(False, ls not in ("dense", "sundials_dense"), None)


def make(kernel, options, the_plan, bounds):
    """A new integrator for `kernel` with step bounds (max, min, first; 0 = IDA's default)."""
    tol = options.integr_tol
    mxsteps = min(options.max_num_steps + 1, 2 ** 31 - 1)
    if the_plan.use_c:
        tune = (options.max_step_growth or 0.0, options.nonlin_conv_coef or NONLIN_CONV_COEF,
                AUTO_STEP_GROWTH)
        return cida.CIDA(kernel, tol, tol, *bounds, mxsteps, band=the_plan.band, tune=tune,
                         sparse=the_plan.sparse, sundials_dense=the_plan.sundials_dense)
    if the_plan.sparse:
        lin = dict(linsolver="sparse", sparsity=kernel.sparsity(), jacfn=kernel.jacobian_csc_fn())
    else:
        lin = dict(linsolver="dense", jacfn=kernel.jacobian_ida)
    if options.jacobian == "dq":      # IDA's own difference quotients, for comparison
        lin.pop("jacfn")
    if kernel.layout.algebraic:       # reactions (scikit-sundae keeps them in the error test)
        lin["algebraic_idx"] = list(kernel.layout.algebraic)
    rootfn = kernel.roots if kernel.nsensor else None
    return PyIDA(kernel.residual, rootfn=rootfn, nroots=kernel.nsensor, rtol=tol, atol=tol,
                 max_step=bounds[0], min_step=bounds[1], first_step=bounds[2],
                 max_num_steps=mxsteps, outputs=kernel.outputs, nout=len(kernel.channels),
                 hit_outputs=bool(kernel.layout.algebraic), **lin)
